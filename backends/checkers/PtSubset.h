//===- PtSubset.h - the place/transition part of a module -------*- C++ -*-===//
//
// The exports to P/T-net formats and checkers (Promela, PNML) cover the
// place/transition part of NetIR: places with weights, capacities and
// urgency. This unit finds the first construct outside it (a free input, a
// stored output, a variable, an event or condition arc, a guard, an
// action, a timed arc) and reports it by name and place.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_PTSUBSET_H
#define NETLIFT_BACKENDS_CHECKERS_PTSUBSET_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <optional>
#include <string>

namespace netlift::checkers {

/// A construct outside the place/transition part, and where it is.
struct BeyondPt {
  llvm::SMLoc loc;
  std::string what; // "variable 'x'", "transition 't' has a guard"
};

/// The first construct of flat module `m` outside the place/transition
/// part, if any.
std::optional<BeyondPt> firstBeyondPt(const net::Module &m);

/// False after an error at the first construct of flat module `m` that a
/// P/T export to `format` cannot carry.
bool refuseBeyondPt(const net::Module &m, llvm::StringRef format,
                    DiagEngine &diag);

} // namespace netlift::checkers

#endif
