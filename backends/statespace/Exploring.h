//===- Exploring.h - what the engine found, said to the user ----*- C++ -*-===//
//
// The engine (engine/) explores and replays; this unit says what came of
// it the way every exploring command says it alike: a runtime error with
// the trace that leads to it, the verdict of an abstract counterexample's
// replay in exact time with the exact run, and how a set-up's traces are
// shown (TraceView). It is the one place where engine results meet the
// trace writers.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STATESPACE_EXPLORING_H
#define NETLIFT_BACKENDS_STATESPACE_EXPLORING_H

#include "backends/statespace/Writers.h"
#include "engine/ExplorationSetup.h"
#include "engine/TimerReplay.h"

#include <memory>

namespace netlift::statespace {

/// How the traces of a command exploring `setup` are shown.
TraceView traceViewOf(const engine::ExplorationSetup &setup);

/// Runs `explorer` (made on the set-up's semantics) into `result`; false
/// after reporting a runtime error of the model with its trace.
bool exploreAndReport(engine::ExplorationSetup &setup,
                      engine::Explorer &explorer, engine::ExploreResult &result,
                      DiagEngine &diag);
/// Explores the whole graph (edges recorded, the set-up's limits) for the
/// analyses over it (check, sr); null after a runtime error.
std::unique_ptr<engine::Explorer> exploreGraph(engine::ExplorationSetup &setup,
                                               engine::ExploreResult &result,
                                               DiagEngine &diag);

/// Reports the runtime error an exploration stopped at, at its place in
/// the model and with the path that leads there (when the initial state
/// could be built). Every command that explores says it the same way.
void reportRuntimeError(const engine::ExploreResult &result, bool started,
                        engine::Explorer &explorer, sem::Semantics &semantics,
                        DiagEngine &diag, const TraceView &view = {});

/// The exact run of a confirmed replay, as `reach` prints paths.
void writeReplayedRun(sem::Semantics &exact, const engine::ReplayOutcome &o,
                      llvm::raw_ostream &os, const TraceView &view = {});

/// Replays the path to `target` of a set-up with abstract timers and says
/// what came of it: `confirmed in exact time` with the exact run,
/// `spurious` with the step and the clocks involved (returned in
/// `involved`), or `undecided`. `deadlock`: the run must end in a state
/// without successors.
engine::ReplayOutcome::Verdict
replayAndReport(engine::ExplorationSetup &setup, const engine::Explorer &x,
                llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
                bool deadlock, llvm::raw_ostream &out,
                std::vector<std::string> &involved);

/// When an abstract path could not be followed: the exact model of
/// `setup` searched directly, within --replay-states, for a state
/// satisfying `find` (`findText` as the user wrote it; null: a deadlock).
/// Confirms with its path (0 found, 3 a deadlock), or settles that there
/// is none when the whole exact model fits (3 not found, 0 no deadlock);
/// engine::kRefine when it does not.
int searchExactModel(engine::ExplorationSetup &setup, const net::Expr *find,
                     llvm::StringRef findText, llvm::raw_ostream &out);

} // namespace netlift::statespace

#endif
