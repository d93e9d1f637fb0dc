//===- ExtractMealy.h - the Mealy machine of a controller -------*- C++ -*-===//
//
// Extracts the Mealy machine of a controller module (a PLC program
// translated to NetIR, or any flat discrete module with Boolean inputs and
// outputs) in the open loop: from every reachable state at a cycle boundary
// and for every input vector, the controller runs its next step (the PLC
// scan), after letting time pass while no step is possible; the step's
// post-state is the next state, the output ports' values there are the
// output. A state is thus the whole controller memory (variables, stored
// outputs, timers' clocks) between two scans. The module must be
// deterministic under this reading (one step per state and input vector);
// event ports, non-Boolean ports and nondeterminism are refused by name.
// docs/enforce.md gives the exact definition.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_MEALY_EXTRACTMEALY_H
#define NETLIFT_BACKENDS_MEALY_EXTRACTMEALY_H

#include "engine/Semantics.h"
#include "ir/automata/Mealy.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

namespace netlift::mealy {

struct MealyExtractOptions {
  /// Refuse machines with more states (the extraction is exhaustive).
  uint32_t maxStates = 1u << 20;
  /// Every state tries 2^inputs vectors.
  unsigned maxInputs = 16;
  /// Ticks waited for a step before the controller is declared stuck.
  uint64_t maxWaitTicks = 1u << 20;
};

/// Extracts the Mealy machine of the semantics' flat module (an
/// ExplorationSetup's: its step policy and timing decide what a step is)
/// into `out` (states named s0, s1, ... in breadth-first order from the
/// initial state s0; rows merged into input cubes). False after reporting
/// the reason through `diag`.
bool extractMealy(sem::Semantics &semantics, const MealyExtractOptions &opts,
                  DiagEngine &diag, automata::MealyMachine &out);

} // namespace netlift::mealy

#endif
