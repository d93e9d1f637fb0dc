//===- TraceValues.h - a path shown with the values the PLC has --*- C++
//-*-===//
//
// A model explored with end-of-scan resets (ir/net/ScanResets.h) holds the
// initial value of a reset function-block member between scans, where the
// PLC holds what the scan left in it. Traces are observers: before one is
// shown, its path is run again without the resets, from the initial state,
// taking at each step the successor with the same label that agrees with
// the explored state on every variable that is not reset. The resets only
// touch values the model never reads, so that run exists and differs from
// the explored one only in those values: it is the run the PLC makes.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_TRACEVALUES_H
#define NETLIFT_ENGINE_TRACEVALUES_H

#include "engine/Semantics.h"

#include <memory>
#include <string>
#include <vector>

namespace netlift::engine {

/// A path's states as the PLC has them.
struct PlcPath {
  /// The semantics without the resets (traces are shown and their input
  /// classes and source lines found in it); null when `sem` resets
  /// nothing, and the states are then the explored ones.
  std::unique_ptr<sem::Semantics> semantics;
  std::vector<std::vector<uint64_t>> storage;
  std::vector<const uint64_t *> states;
  /// The semantics to show the path in.
  sem::Semantics &in(sem::Semantics &explored) {
    return semantics ? *semantics : explored;
  }
};

/// `states` (with `labels[i]` the step into `states[i]`, labels without
/// input classes or with them) explored in `sem`, run again without its
/// end-of-scan resets.
PlcPath plcValues(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
                  llvm::ArrayRef<const uint64_t *> states);

} // namespace netlift::engine

#endif
