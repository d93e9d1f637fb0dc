//===- ForteOrder.h - a resource's events in FORTE's order ------*- C++ -*-===//
//
// The default execution model of the IEC 61499 frontend: on the flat
// module of one resource, pending events leave in the order of one FIFO
// for the whole resource, as in 4diac FORTE (docs/iec61499.md).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_IEC61499_FORTEORDER_H
#define NETLIFT_FRONTENDS_IEC61499_FORTEORDER_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

namespace netlift::iec61499 {

/// Rewrites the flat module `m` built from translated blocks so that their
/// events go in one FIFO order. Returns false after reporting.
bool orderLikeForte(net::Design &design, net::Module &m, DiagEngine &diag);

} // namespace netlift::iec61499

#endif
