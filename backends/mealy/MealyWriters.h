//===- MealyWriters.h - Mealy machines as KISS2 and DOT ---------*- C++ -*-===//
//
// Canonical KISS2 (header, `.ilb`/`.ob` only when the signals have other
// than the default names, rows in stored order, `.e`), which reads back to
// the same machine, and DOT in the AALpy/AutomataLib style
// (`s0 -> s1 [label="01/10"]` with a start pseudo-node).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_MEALY_MEALYWRITERS_H
#define NETLIFT_BACKENDS_MEALY_MEALYWRITERS_H

#include "ir/automata/Mealy.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::mealy {

void writeKiss2(const automata::MealyMachine &m, llvm::raw_ostream &os);
void writeMealyDot(const automata::MealyMachine &m, llvm::raw_ostream &os);
/// `mealy --info`: the signals, states and transitions, and which states
/// leave input vectors (or symbols) unspecified.
void writeMealyInfo(const automata::MealyMachine &m, llvm::raw_ostream &os);

} // namespace netlift::mealy

#endif
