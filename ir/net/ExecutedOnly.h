//===- ExecutedOnly.h - what only execution gives a meaning to --*- C++ -*-===//
//
// NetIR expresses what a PLC executes (ARCHITECTURE §3.1): floats, strings,
// `while`
// and `repeat` loops, `for` loops with run-time bounds. The explicit-state
// engine runs them on concrete states; a backend that encodes a module
// symbolically (SMV, Promela, lower-data and what reads its result) cannot,
// and refuses the first such construct by name and place, found here.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_EXECUTEDONLY_H
#define NETLIFT_IR_NET_EXECUTEDONLY_H

#include "ir/net/Module.h"

#include "llvm/Support/SMLoc.h"

#include <optional>
#include <string>

namespace netlift::net {

struct ExecutedOnly {
  llvm::SMLoc loc;
  /// What it is, for "... cannot encode <what>": "the real32 variable 'x'",
  /// "a loop without constant bounds ('while')".
  std::string what;
};

/// The first construct of `m` (declarations first, then transitions in
/// order) that only execution can give a meaning to; nullopt if none.
std::optional<ExecutedOnly> findExecutedOnly(const Module &m);

/// What in a value of type `t` (or any element or field of it) only
/// execution gives a meaning to ("floating point", "a string", "64-bit
/// unsigned arithmetic"); null if nothing.
const char *executedOnlyData(const Type *t);

} // namespace netlift::net

#endif
