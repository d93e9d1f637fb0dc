//===- Smv.h - flat modules as SMV models for NuSMV/nuXmv -------*- C++ -*-===//
//
// Writes a flat module as one SMV `MODULE main` whose transitions are
// exactly netlift's steps and ticks (interleaving, weak timing): input
// variables (IVAR) choose what starts a step, the free inputs and, round by
// round, the choices among conflicting forced transitions; DEFINEs compute
// the closure rounds as the engine makes them and the actions' effects by
// symbolic execution; TRANS keeps the choices that make a step. Its
// reachable states are netlift's states, deadlocks loop on themselves as in
// `netlift check`, and runtime errors lead to an absorbing `netlift_error`
// state that `INVARSPEC !netlift_error` reports. CTL properties become
// CTLSPECs. docs/check.md states the encoding and what it refuses.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_SMV_H
#define NETLIFT_BACKENDS_CHECKERS_SMV_H

#include "backends/checkers/Ctl.h"
#include "engine/Semantics.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::checkers {

/// Writes `m` (flat) as SMV with one CTLSPEC per property. False, with an
/// error at the first construct the encoding does not cover.
/// The module and its layout are the semantics' (an ExplorationSetup's);
/// a step policy or timing the encoding does not cover is refused.
bool writeSmv(const sem::Semantics &semantics, DiagEngine &diag,
              llvm::raw_ostream &os,
              llvm::ArrayRef<const CtlFormula *> properties = {});

} // namespace netlift::checkers

#endif
