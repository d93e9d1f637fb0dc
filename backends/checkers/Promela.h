//===- Promela.h - flat modules as Promela models for spin ------*- C++ -*-===//
//
// Writes a flat module as a Promela model whose reachable global states are
// exactly netlift's reachable states (interleaving, weak timing), so that
// spin's state count and verdicts are an independent check of the
// semantics engine, and spin's speed a yardstick for it. Place/transition
// nets loop over one `d_step` per transition (spin's transitions are then
// netlift's edges too); every other model loops over one atomic sequence
// per step: free inputs, the starting transition or tick, the rounds of
// forced closure with every maximal choice, actions on shadow copies, and
// one d_step that lands the step. Runtime errors of netlift (write
// conflicts, range errors, token overflow) are assertions. docs/check.md
// states the encoding and what it refuses.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_PROMELA_H
#define NETLIFT_BACKENDS_CHECKERS_PROMELA_H

#include "backends/checkers/Ctl.h"
#include "engine/Semantics.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::checkers {

/// Writes `m` (flat) as Promela, with one `ltl` claim `p1`, `p2`... per
/// property. False, with an error at the first construct the encoding does
/// not cover, or at a property outside the fragment of CTL that netlift
/// writes as LTL (invariants `AG p`, `AF p`, `A[p U q]`, `AG AF p`,
/// `AG (p -> AF q)`, conjunctions of these, over state propositions).
/// The module and its layout are the semantics' (an ExplorationSetup's);
/// a step policy or timing the encoding does not cover is refused.
bool writePromela(const sem::Semantics &semantics, DiagEngine &diag,
                  llvm::raw_ostream &os,
                  llvm::ArrayRef<const CtlFormula *> properties = {});

} // namespace netlift::checkers

#endif
