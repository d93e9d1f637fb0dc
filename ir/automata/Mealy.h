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
// Machines learnt by AALpy or LearnLib read and write *symbols* (`coin`,
// `ClientHelloRSA`) rather than signal vectors. Such a machine keeps its
// alphabets in `inputSymbols`/`outputSymbols` and is encoded on Boolean
// signals: input symbol k is the input vector of k in binary (signals
// i1..iN, N = max(1, ceil(log2 |alphabet|))), output symbol k likewise;
// vectors beyond the alphabet are never specified. Minimisation and
// equivalence thus work unchanged; writers print symbols again.
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
/// Every vector a cube of 0/1/- covers, appended to `out`.
void cubeVectors(const std::string &cube, std::vector<uint32_t> &out);

class MealyMachine {
public:
  std::string name;
  std::vector<std::string> inputs, outputs, states;
  uint32_t initial = 0;
  std::vector<MealyTransition> transitions;
  /// Empty for a machine over Boolean signals; else the symbol of each
  /// code (see the file comment).
  std::vector<std::string> inputSymbols, outputSymbols;

  bool isSymbolic() const { return !inputSymbols.empty(); }
  /// Bits needed to encode `n` symbols (at least one).
  static unsigned symbolWidth(size_t n);
  /// The symbol of an encoded input/output vector; the vector itself for a
  /// machine over Boolean signals or a vector beyond the alphabet.
  std::string inputLabel(const std::string &vector) const;
  std::string outputLabel(const std::string &vector) const;
  /// Re-encodes the machine over the given alphabets (which must contain
  /// its own symbols), so that two machines learnt separately share codes.
  void recodeSymbols(const std::vector<std::string> &newInputs,
                     const std::vector<std::string> &newOutputs);

  /// Index of a state, adding it if new.
  uint32_t stateIndex(const std::string &s);
  /// Do two input cubes share an input vector?
  static bool cubesIntersect(const std::string &a, const std::string &b);

  /// Reports, as errors, every pair of transitions of one state whose input
  /// cubes overlap but lead to different states or to contradicting
  /// outputs. Returns false if there is one.
  bool checkDeterminism(DiagEngine &diag) const;
  /// For each state, how many of the 2^inputs input vectors (or input
  /// symbols) no transition covers (machines with more than 24 inputs are
  /// not counted: -1).
  std::vector<int64_t> unspecifiedVectors() const;
  /// Rewrites the rows of each state so that the input vectors leading to
  /// one (target, output) pair are covered by few disjoint cubes: vectors
  /// differing in one position merge into a cube with '-' there, position
  /// by position. The machine's behaviour is unchanged; rows come out per
  /// state, pairs in order of their first vector, cubes in vector order.
  /// Machines of more than 24 inputs, and machines over symbols (a cube
  /// of codes means nothing there), are left as they are.
  void mergeInputCubes();
};

/// Makes two machines comparable: both over Boolean signals (nothing to
/// do), or both over symbols, re-encoded on the union of their alphabets
/// (first `a`'s symbols, then `b`'s new ones). False with `why` if one
/// reads symbols and the other signals.
bool alignAlphabets(MealyMachine &a, MealyMachine &b, std::string &why);

} // namespace netlift::automata

#endif
