//===- Flatten.h - inlining one module's hierarchy --------------*- C++ -*-===//
//
// The `flatten` pass's engine for callers that flatten one module of a
// design and keep the rest (the IEC 61499 frontend flattens each resource
// it translates before ordering its events).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_FLATTEN_H
#define NETLIFT_PASSES_FLATTEN_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

namespace netlift {

/// Builds the flat form of `top` as a new module `<top>.flat` of `design`
/// (see Flatten.cpp for what it preserves); null after reporting.
net::Module *flattenModule(net::Design &design, net::Module *top,
                           DiagEngine &diag);

} // namespace netlift

#endif
