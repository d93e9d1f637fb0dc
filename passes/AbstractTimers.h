//===- AbstractTimers.h - timers whose elapsed time is not counted -*- C++
//-*-===//
//
// `abstract-timers` (docs/reach.md, "Timers abstracted"): each clock
// variable that is only compared (a TON, TOF or TP whose ET nobody reads)
// stops counting ticks. It keeps the value it was last set to and whether
// a tick has passed since; once one has, each step reads it as any value
// between that value and its cap, chosen by a free input. Every behaviour
// of the exact model is one of the abstract model's, so an invariant that
// holds there holds exactly; the converse needs the exact model
// (replayed counterexamples, TimerReplay.h).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_ABSTRACTTIMERS_H
#define NETLIFT_PASSES_ABSTRACTTIMERS_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <set>
#include <string>
#include <vector>

namespace netlift {

/// What the abstraction did to one module.
struct TimerAbstraction {
  /// The clock variables abstracted, by name, in module order.
  std::vector<std::string> abstracted;
  /// Those kept exact and why (`its value is read`, `kept by --refine`).
  std::vector<std::pair<std::string, std::string>> kept;
};

/// Abstracts the clock variables of the flat, verified module `m` except
/// those named in `keep`; notes each clock kept exact because of how it is
/// read (with `notes`). The design is verified again. False after
/// reporting.
bool abstractTimers(net::Design &d, net::Module &m,
                    const std::set<std::string> &keep, DiagEngine &diag,
                    bool notes, TimerAbstraction &result);

/// The free input that chooses an abstracted clock's reading, and the
/// clock variable that says a tick has passed since it was set.
std::string abstractReadingInput(llvm::StringRef clock);
std::string abstractTickedFlag(llvm::StringRef clock);

} // namespace netlift

#endif
