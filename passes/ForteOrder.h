//===- ForteOrder.h - a resource's events in FORTE's order ------*- C++ -*-===//
//
// The default execution model of the IEC 61499 frontend: on the flat
// module of one resource, pending events leave in the order of one FIFO
// for the whole resource, as in 4diac FORTE (docs/iec61499.md).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_FORTEORDER_H
#define NETLIFT_PASSES_FORTEORDER_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/STLFunctionalExtras.h"

#include <set>

namespace netlift::net {
class Builder;
}

namespace netlift::iec61499 {

/// Rewrites the flat module `m` built from translated blocks so that their
/// events go in one FIFO order. Returns false after reporting.
bool orderLikeForte(net::Design &design, net::Module &m, DiagEngine &diag);

/// A name of the flat module split into the prefix of the block it belongs
/// to (`a.b.`, empty at the top) and its name in the block (`send_EO`).
std::pair<std::string, llvm::StringRef> splitBlockName(llvm::StringRef name);

/// What starts an event chain from outside the blocks — the environment's
/// queue, E_DELAY and E_CYCLE expiring, E_RESTART — waits for `idle`
/// (added to its guard): every transition that is not forced, not in
/// `ordered` and emits an event or is heard. Shared by the execution models
/// that run a chain to its end before taking the next outside event.
void waitForIdle(net::Builder &b, net::Module &m,
                 const std::set<uint32_t> &ordered,
                 llvm::function_ref<net::Expr *()> idle);

} // namespace netlift::iec61499

#endif
