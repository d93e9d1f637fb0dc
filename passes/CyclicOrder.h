//===- CyclicOrder.h - a resource's blocks in one cycle ---------*- C++ -*-===//
//
// The cyclic execution model of fb2smv (the closed-loop modelling paper's
// SMV generator): the blocks of a resource take turns in a fixed order —
// the order of the networks, composites in place — and each, at its turn,
// reacts to all the events that arrived since its last turn at once
// (docs/iec61499.md).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_CYCLICORDER_H
#define NETLIFT_PASSES_CYCLICORDER_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

namespace netlift::iec61499 {

/// Rewrites the flat module `m` built from blocks translated for the cyclic
/// model (events set flags; a hidden event input `_run` reacts to them) so
/// that the blocks take their turns in the order of their `_run`
/// reactions in `m`. Returns false after reporting.
bool orderCyclically(net::Design &design, net::Module &m, DiagEngine &diag);

} // namespace netlift::iec61499

#endif
