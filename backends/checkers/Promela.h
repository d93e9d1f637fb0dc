//===- Promela.h - flat modules as Promela models for spin ------*- C++ -*-===//
//
// Writes a flat module as a Promela model whose reachable global states are
// exactly netlift's reachable states, so that spin's state count is an
// independent check of the semantics engine (and spin's speed a yardstick
// for it). One process loops over one `d_step` per transition: the step is
// atomic, so spin stores no intermediate states; its guard is the
// transition's enabling (pre-places hold the weights, capacities are kept,
// urgency) and its body the firing. A firing that would overflow the
// encoding of an unbounded place fails an assertion, as it is a runtime
// error in netlift. Covered so far: place/transition nets (weights,
// capacities, urgency) under the interleaving policy; data, clocks,
// conditions, events and free inputs are refused by name.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_PROMELA_H
#define NETLIFT_BACKENDS_CHECKERS_PROMELA_H

#include "ir/semantics/StateLayout.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::checkers {

/// Writes `m` (flat) as Promela. False, with an error at the first
/// construct the encoding does not cover, when it cannot.
bool writePromela(const net::Module &m, const sem::StateLayout &layout,
                  DiagEngine &diag, llvm::raw_ostream &os);

} // namespace netlift::checkers

#endif
