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

#include "backends/statespace/Writers.h"
#include "engine/Semantics.h"
#include "ir/net/Module.h"
#include "ir/net/StringOps.h"

#include "llvm/Support/JSON.h"

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

/// `stateFile`: the columns of a state file, which leaves out the PLC memory
/// the semantics resets at the end of each scan (its stored value is not
/// the PLC's; --keep keeps it, docs/semantics.md "Observers").
std::vector<StateColumn> stateColumns(const sem::Semantics &sem,
                                      bool stateFile = false);

/// A column's value in one state: the number it holds (a string: its
/// length) and how it is written (a string: as a NetIR literal).
struct Cell {
  int64_t v = 0;
  net::StringValue str; // a string's characters
  std::string text;
  bool operator!=(const Cell &o) const { return text != o.text; }
};

Cell cellOf(sem::Semantics &sem, const StateColumn &a, const uint64_t *state);
/// A cell as a JSON trace writes it (docs/formats.md, "JSON traces"): a
/// Boolean or integer as an integer, a real as a number, a string as its
/// characters, anything else as its text.
llvm::json::Value jsonOf(const StateColumn &a, const Cell &c);

/// A path in the program's view (docs/reach.md, "Traces"): the columns
/// shown (clocks and internal names left out) and a row per step that is
/// not a tick (a tick ending the path, or changing something shown, too).
struct TraceRow {
  size_t step = 0;
  std::string time;         // in the design's unit, or ticks
  std::string taken;        // `{scan}`, transitions of internal scopes left out
  std::string inputs;       // the input classes that took it, `go=1`
  std::string ran;          // with `withRan`: the source lines it executed
  std::vector<Cell> values; // per shown column, after the step
  std::vector<char> changed;   // per shown column
  std::vector<std::string> at; // per changed column: its assignment's line
};
struct ProgramTrace {
  std::vector<StateColumn> columns;
  std::vector<TraceRow> rows;
  size_t hiddenNames = 0;
  bool timed = false; // the time column is in the design's unit
};
/// `withRan`: each row lists the source lines it ran (--trace-source).
ProgramTrace programTrace(sem::Semantics &sem,
                          llvm::ArrayRef<std::string> labels,
                          llvm::ArrayRef<const uint64_t *> states,
                          const TraceView &view, bool withRan);

} // namespace netlift::statespace::listing

#endif
