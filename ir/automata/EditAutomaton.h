//===- EditAutomaton.h - edit automata over I/O vectors ---------*- C++ -*-===//
//
// Edit automata (Ligatti, Bauer, Walker) whose events are observed I/O
// vectors (inputs then outputs, one 0/1 character each), as built by the
// method of Guignard and Faure (ETFA 2013) from a Mealy specification:
// specified states are the machine's states, intermediate states stand for
// what a PLC's desynchronised reading of simultaneous input changes can
// show. Transitions validate (emit the event) or suppress it; an event with
// no transition is an implicit stop.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_AUTOMATA_EDITAUTOMATON_H
#define NETLIFT_IR_AUTOMATA_EDITAUTOMATON_H

#include "ir/automata/Mealy.h"

#include <map>
#include <string>
#include <vector>

namespace netlift::automata {

enum class EditKind : uint8_t { Validate, Suppress };

struct EditTransition {
  uint32_t from;
  std::string event; // inputs then outputs, 0/1
  EditKind kind;
  uint32_t to;
};

struct EditState {
  std::string name;
  bool specified;
};

class EditAutomaton {
public:
  std::vector<std::string> signals; // inputs then outputs
  size_t numInputs = 0;
  std::vector<EditState> states;
  uint32_t initial = 0;
  std::vector<EditTransition> transitions;

  /// The transition on `event` from `state`, or null (an implicit stop).
  const EditTransition *step(uint32_t state, const std::string &event) const;
  /// Events with a transition from `state`, sorted.
  std::vector<std::string> expected(uint32_t state) const;
  /// Adds a transition; false if another one on the same event leaves the
  /// same state with a different effect (the automaton would not be
  /// deterministic).
  bool add(const EditTransition &t);

private:
  std::map<std::pair<uint32_t, std::string>, uint32_t> index;
};

/// The scan-cycle phenomena an edit automaton tolerates (docs/enforce.md).
/// Desynchronisation is the paper's construction and always on; the other
/// two are netlift's extensions of it.
struct EditAutomatonOptions {
  /// Outputs appear at the end of the scan: a vector may show the new
  /// inputs with the outputs of before.
  bool delayedOutputs = false;
  /// Two changes of different inputs, one after the other, read in one
  /// scan: the first shows no reaction, the second the reaction to both.
  bool synchronisedInputs = false;
};

/// Builds the edit automaton of a deterministic Mealy machine for the
/// desynchronisation of simultaneous input changes (at most 16 inputs),
/// and the phenomena `opts` adds. False with `why` set when it cannot (too
/// many inputs, or the result would not be deterministic).
bool buildEditAutomaton(const MealyMachine &m, EditAutomaton &ea,
                        std::string &why,
                        const EditAutomatonOptions &opts = {});

} // namespace netlift::automata

#endif
