//===- ScanStep.h - one scan of a controller with given inputs --*- C++ -*-===//
//
// What a PLC does with one input vector: time passes while no step is
// possible, then the one step (its scan) is taken. Semantics::fixInputs
// fixes the vector; nextScan finds the ticks and the step from a state.
// Mealy extraction (a machine per input vector) and `netlift replay` (a
// field log, scan by scan) both run a controller this way.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_SCANSTEP_H
#define NETLIFT_ENGINE_SCANSTEP_H

#include "engine/Semantics.h"

#include <cstdint>
#include <string>
#include <vector>

namespace netlift::engine {

struct ScanOutcome {
  enum Kind {
    Stepped,          // `step` taken into `after`
    Nondeterministic, // two steps possible: `step` and `other`
    Deadlock,         // neither a step nor time passing
    Waited            // maxWaitTicks ticks and still no step
  } kind = Deadlock;
  /// The states after each tick before the step, in order.
  std::vector<std::vector<uint64_t>> ticks;
  std::string step, other; // `{scan}`
  std::vector<uint64_t> after;
};

/// Runs one scan from `from` with the inputs `sem` has fixed. False (and
/// `err`) on a runtime error of the model.
bool nextScan(sem::Semantics &sem, const uint64_t *from, uint64_t maxWaitTicks,
              ScanOutcome &out, sem::RuntimeError &err);

} // namespace netlift::engine

#endif
