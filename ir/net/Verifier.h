//===- Verifier.h - NetIR well-formedness -----------------------*- C++ -*-===//
//
// Checks that a Design means something under docs/semantics.md and reports
// every problem with file:line:col: names that are undefined or declared
// twice, type errors in guards, definitions and actions, arcs of the wrong
// kind, initial markings over capacity, connections between ports of
// different kinds or types, recursive instantiation and event cycles among
// forced transitions. On success every name in every expression is resolved
// and every expression carries its type, which is what later stages rely on.
// Unconnected inputs are not errors: they are the free environment.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_VERIFIER_H
#define NETLIFT_IR_NET_VERIFIER_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

namespace netlift::net {

/// Verifies every module of the design. Returns false if an error was
/// reported.
bool verifyDesign(Design &d, DiagEngine &diag);

/// Resolves and type-checks a Boolean expression in the context of module
/// `m` (a predicate such as `reach --find`). False after reporting.
bool verifyPredicate(Design &d, Module &m, Expr *e, DiagEngine &diag);

/// Does the module still have hybrid (real) variables or flows? Stages
/// after `discretise` refuse such modules.
bool hasHybridParts(const Module &m);

} // namespace netlift::net

#endif
