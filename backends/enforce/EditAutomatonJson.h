//===- EditAutomatonJson.h - edit automata as JSON --------------*- C++ -*-===//
//
// An edit automaton written as JSON so that another run (`enforce`) or
// another tool can read it without rebuilding it from the specification:
// the signals (inputs then outputs), the states with whether each is a
// specified or an intermediate state, the initial state, and one object
// per transition (from, event, validate|suppress, to). The reader checks
// everything the builder guarantees (known states, events of the right
// width, determinism) and reports what is wrong at its place in the file.
// docs/enforce.md shows the layout.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_ENFORCE_EDITAUTOMATONJSON_H
#define NETLIFT_BACKENDS_ENFORCE_EDITAUTOMATONJSON_H

#include "ir/automata/EditAutomaton.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::enforce {

void writeEditAutomatonJson(const automata::EditAutomaton &ea,
                            llvm::raw_ostream &os);

/// Reads the automaton `writeEditAutomatonJson` writes from buffer
/// `bufferID`. False after reporting the first problem.
bool readEditAutomatonJson(unsigned bufferID, DiagEngine &diag,
                           automata::EditAutomaton &ea);

} // namespace netlift::enforce

#endif
