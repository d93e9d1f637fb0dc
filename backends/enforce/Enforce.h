//===- Enforce.h - judging observed I/O traces ------------------*- C++ -*-===//
//
// Runs an edit automaton over an observed trace (CSV with a header naming
// the signals, in any order; one row of 0/1 per observed I/O vector),
// streaming: the memory used does not depend on the trace's length. The
// enforced sequence is what the automaton emits; the verdict says whether
// the trace conforms (no stop, ending in a specified state). Also writes an
// automaton as DOT and as a text table.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_ENFORCE_ENFORCE_H
#define NETLIFT_BACKENDS_ENFORCE_ENFORCE_H

#include "ir/automata/EditAutomaton.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

#include <functional>

namespace netlift::enforce {

struct EnforceResult {
  bool conform = false;
  bool stopped = false;
  uint64_t vectors = 0;   // rows read
  uint64_t stopIndex = 0; // 1-based row of the stop
  std::string stopVector;
  std::vector<std::string> expected; // events the automaton accepted there
  bool endedIntermediate = false;
};

/// Enforces the trace in buffer `bufferID`; each emitted vector is passed to
/// `emit` (0/1 digits in the automaton's signal order). False after
/// reporting a malformed trace.
bool enforceTrace(const automata::EditAutomaton &ea, unsigned bufferID,
                  DiagEngine &diag,
                  const std::function<void(const std::string &)> &emit,
                  EnforceResult &result);

/// `netlift enforce`: enforces the trace, printing each emitted vector on
/// `vectors` and, with `csv`, writing it there as CSV under a header of
/// the automaton's signals; then prints the verdict on `vectors`. Returns
/// the exit code: 0 conform, 3 not conform, 1 a malformed trace
/// (reported).
int enforceAndJudge(const automata::EditAutomaton &ea, unsigned bufferID,
                    DiagEngine &diag, llvm::raw_ostream &vectors,
                    llvm::raw_ostream *csv, EnforceResult *result = nullptr);

void writeEditAutomatonDot(const automata::EditAutomaton &ea,
                           llvm::raw_ostream &os);
void writeEditAutomatonTable(const automata::EditAutomaton &ea,
                             llvm::raw_ostream &os);

} // namespace netlift::enforce

#endif
