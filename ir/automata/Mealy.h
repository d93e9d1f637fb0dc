//===- Mealy.h - Mealy machines over Boolean vectors ------------*- C++ -*-===//
//
// A Mealy machine whose inputs and outputs are vectors of named Boolean
// signals, as KISS2 describes them: each transition has an input cube (one
// character per input: '0', '1' or '-' for "either"), a source and target
// state and an output vector ('0', '1' or '-' for "unspecified"). Machines
// are read faithfully (cubes are kept, not expanded); `checkDeterminism`
// and `checkCompleteness` state precisely where a machine is
// nondeterministic or leaves input vectors unspecified.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_AUTOMATA_MEALY_H
#define NETLIFT_IR_AUTOMATA_MEALY_H

#include "ir/support/Diagnostics.h"

#include "llvm/Support/SMLoc.h"

#include <cstdint>
#include <string>
#include <vector>

namespace netlift::automata {

struct MealyTransition {
  std::string input; // one of 0 1 - per input signal
  uint32_t from = 0, to = 0;
  std::string output; // one of 0 1 - per output signal
  llvm::SMLoc loc;
};

/// The input vector `v` (most significant bit first) as n 0/1 characters.
std::string vectorBits(uint32_t v, size_t n);

class MealyMachine {
public:
  std::string name;
  std::vector<std::string> inputs, outputs, states;
  uint32_t initial = 0;
  std::vector<MealyTransition> transitions;

  /// Index of a state, adding it if new.
  uint32_t stateIndex(const std::string &s);
  /// Do two input cubes share an input vector?
  static bool cubesIntersect(const std::string &a, const std::string &b);

  /// Reports, as errors, every pair of transitions of one state whose input
  /// cubes overlap but lead to different states or to contradicting
  /// outputs. Returns false if there is one.
  bool checkDeterminism(DiagEngine &diag) const;
  /// For each state, how many of the 2^inputs input vectors no transition
  /// covers (machines with more than 24 inputs are not counted: -1).
  std::vector<int64_t> unspecifiedVectors() const;
  /// Rewrites the rows of each state so that the input vectors leading to
  /// one (target, output) pair are covered by few disjoint cubes: vectors
  /// differing in one position merge into a cube with '-' there, position
  /// by position. The machine's behaviour is unchanged; rows come out per
  /// state, pairs in order of their first vector, cubes in vector order.
  /// Machines of more than 24 inputs are left as they are.
  void mergeInputCubes();
};

} // namespace netlift::automata

#endif
