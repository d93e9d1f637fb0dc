//===- Minimize.h - minimal and equivalent Mealy machines -------*- C++ -*-===//
//
// Works on the *completed* machine: every state reacts to every input
// vector; where the machine specifies nothing the completion goes to an
// explicit error sink that outputs "error" forever. An unspecified output
// bit ('-') is a value of its own. Under this reading, minimisation merges
// exactly the states no input sequence can tell apart, and two machines
// are equivalent when every input sequence gives the same outputs
// (including where each stops being specified). So a machine and its
// minimised form are always equivalent, LGSynth91's incompletely specified
// machines included. Both need the input vectors enumerated: at most 16
// inputs.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_AUTOMATA_MINIMIZE_H
#define NETLIFT_IR_AUTOMATA_MINIMIZE_H

#include "ir/automata/Mealy.h"

#include <optional>
#include <string>
#include <vector>

#include "llvm/Support/raw_ostream.h"

namespace netlift::automata {

constexpr unsigned kMaxEnumeratedInputs = 16;

/// The minimal machine equivalent to `m` (rows written per input vector,
/// states named after the first original state of their class). False
/// with `why` set if `m` has too many inputs.
bool minimize(const MealyMachine &m, MealyMachine &out, std::string &why);

/// Checks equivalence; when the machines differ, `witness` gets a shortest
/// input sequence (input vectors as 0/1 strings in `a`'s signal order) whose
/// last step gives different outputs, and `outputs` the two outputs there.
/// False with `why` set if they cannot be compared (signals differ, too
/// many inputs).
struct EquivalenceResult {
  bool equivalent = true;
  std::vector<std::string> witness;
  std::string outputA, outputB;
};
bool checkEquivalence(const MealyMachine &a, const MealyMachine &b,
                      EquivalenceResult &result, std::string &why);

/// `mealy --equiv`: "equivalent", or the shortest distinguishing input
/// sequence and the two outputs it ends with.
void writeEquivalence(const MealyMachine &a, const EquivalenceResult &r,
                      llvm::raw_ostream &os);

} // namespace netlift::automata

#endif
