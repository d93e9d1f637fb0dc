//===- Clone.h - copying expressions and actions ----------------*- C++ -*-===//
//
// Deep copies of verified expressions and statement blocks with every name
// that denotes a module entity rewritten, so that passes (flatten, compose,
// reductions) can move guards and actions between modules. Enumerators and
// loop variables keep their names; copies are unresolved until verified.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_CLONE_H
#define NETLIFT_IR_NET_CLONE_H

#include "ir/net/Builder.h"

#include "llvm/ADT/STLFunctionalExtras.h"

#include <string>

namespace netlift::net {

/// Maps the entity name a Ref denotes (without record field suffixes) to
/// the name it has in the destination.
using RenameFn = llvm::function_ref<std::string(llvm::StringRef)>;

Expr *cloneExpr(Builder &b, const Module &src, const Expr *e, RenameFn rename);
Block cloneBlock(Builder &b, const Module &src, Block block, RenameFn rename);

} // namespace netlift::net

#endif
