//===- TimerReplay.h - abstract counterexamples replayed in exact time -*- C++
//-*-===//
//
// A path found with --timers=abstract may be one that no exact run takes
// (a timer expiring sooner than it can). The replay searches the exact
// model for a run that goes through the same control states as the
// abstract path, in order: the same marking and the same values of every
// variable but the clocks, while the exact model may take any number of
// steps (ticks, scans, input choices) that change nothing but the clocks
// between two of them — waiting for its timers. The search is breadth-
// first and bounded; it either confirms the path with an exact timed run,
// or says at which step of the abstract path no exact run can follow and
// which abstracted clocks were running there (those a refinement keeps
// exact).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_TIMERREPLAY_H
#define NETLIFT_ENGINE_TIMERREPLAY_H

#include "engine/Explorer.h"
#include "engine/Semantics.h"

#include "llvm/Support/raw_ostream.h"

#include <string>
#include <vector>

namespace netlift::engine {

struct ReplayOutcome {
  enum Verdict { Confirmed, Spurious, Undecided } verdict = Undecided;
  /// Confirmed: the exact run, as step labels (the first empty) and
  /// states.
  std::vector<std::string> labels;
  std::vector<std::vector<uint64_t>> states;
  /// Spurious: the first step of the abstract path no exact run follows,
  /// and the abstracted clocks running just before it.
  size_t divergesAt = 0;
  std::vector<std::string> involved;
  /// Exact states the search visited.
  uint64_t visited = 0;
};

/// Replays `path` (from `x`, explored on `abstract`) in `exact`.
/// `abstracted` names the abstracted clocks; `lastOk` says whether an exact
/// state may end the run (the property found, a deadlock); the search
/// stops undecided after `budget` exact states.
ReplayOutcome replayInExactTime(
    sem::Semantics &exact, sem::Semantics &abstract, const Explorer &x,
    llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
    llvm::ArrayRef<std::string> abstracted,
    llvm::function_ref<bool(const uint64_t *)> lastOk, uint64_t budget);

} // namespace netlift::engine

#endif
