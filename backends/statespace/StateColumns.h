//===- StateColumns.h - a state's values as named columns -------*- C++ -*-===//
//
// What every state listing (traces, DOT, CSV, JSON, VCD) shows of a state:
// its columns (marked places, place clocks, variables' leaves, outputs) and
// a column's value in one state as a number and as text. Private to the
// state-space writers.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STATESPACE_STATECOLUMNS_H
#define NETLIFT_BACKENDS_STATESPACE_STATECOLUMNS_H

#include "ir/net/Module.h"
#include "ir/net/StringOps.h"
#include "ir/semantics/Semantics.h"

#include <string>
#include <vector>

namespace netlift::statespace::listing {

/// The columns of a state listing: places, variables (leaves; a string is
/// one leaf), outputs.
struct StateColumn {
  std::string name;
  enum Kind { Place, Clock, Data, Output } kind;
  uint32_t slot = 0;               // Place, Clock, Data, stored Output
  const net::Expr *def = nullptr;  // defined Output
  const net::Type *type = nullptr; // Data and Output: how to write the value
  bool isString() const { return type && type->isString(); }
};

std::vector<StateColumn> stateColumns(const sem::Semantics &sem);

/// A column's value in one state: the number it holds (a string: its
/// length) and how it is written (a string: as a NetIR literal).
struct Cell {
  int64_t v = 0;
  net::StringValue str; // a string's characters
  std::string text;
  bool operator!=(const Cell &o) const { return text != o.text; }
};

Cell cellOf(sem::Semantics &sem, const StateColumn &a, const uint64_t *state);

} // namespace netlift::statespace::listing

#endif
