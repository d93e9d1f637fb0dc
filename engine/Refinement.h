//===- Refinement.h - abstract timers, refined on demand --------*- C++ -*-===//
//
// The abstraction-refinement loop of --timers=abstract, one component that
// `reach` and `check` both run: search the model with its timers
// abstracted; replay what was found in exact time (TimerReplay.h); when
// the replay shows it spurious, keep the clocks running at the step it
// failed exact and search again, up to --refine rounds. A round is the
// caller's (it builds the set-up from the options and searches); this
// unit decides what follows a replay and runs the rounds.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_REFINEMENT_H
#define NETLIFT_ENGINE_REFINEMENT_H

#include "engine/ExplorationSetup.h"
#include "engine/TimerReplay.h"

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/Support/raw_ostream.h"

namespace netlift::engine {

/// A round's answer when a spurious counterexample made more clocks exact:
/// search again.
constexpr int kRefine = -1;

/// Runs `round` (0, 1, ...) with `options` until it answers something other
/// than kRefine; the exit code.
int refineUntilSettled(
    ExplorationOptions &options,
    llvm::function_ref<int(ExplorationOptions &, unsigned)> round);

/// What follows a replay of round `round`'s counterexample: `failCode`
/// (the exit code of a confirmed violation) when confirmed, 2 (undecided)
/// when the replay stopped; when spurious, kRefine with the clocks
/// `involved` kept exact in `options` while --refine allows and some are
/// new, else 2. Says so on `out`.
int afterReplay(ReplayOutcome::Verdict verdict,
                llvm::ArrayRef<std::string> involved, int failCode,
                ExplorationOptions &options, unsigned round,
                llvm::raw_ostream &out);

} // namespace netlift::engine

#endif
