//===- Walk.h - visiting what a module reads and writes ---------*- C++ -*-===//
//
// Walks over NetIR that analyses and rewrites share: every sub-expression
// of an expression, every expression a module evaluates, every assignment
// of its actions; and the small facts read off them (a variable's initial
// value, the variable an assignment target writes).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_WALK_H
#define NETLIFT_IR_NET_WALK_H

#include "ir/net/Builder.h"
#include "ir/net/Module.h"

#include "llvm/ADT/STLFunctionalExtras.h"

#include <optional>
#include <vector>

namespace netlift::net {

/// Calls `f` on each direct operand of `e` (indexed base and index, field
/// base, operands, condition and arms, call arguments; not the elements of
/// an aggregate literal).
void forEachOperand(const Expr *e, llvm::function_ref<void(const Expr *)> f);

/// Calls `f` on `e` and every sub-expression.
void walkExpr(const Expr *e, llvm::function_ref<void(const Expr *)> f);

/// Every expression the module evaluates, with the transition it belongs to
/// (-1: an output definition or initial value): guards, condition arcs,
/// and in actions the conditions, selectors, labels, loop bounds, values
/// assigned and indices of assignment targets.
void forEachRead(const Module &m,
                 llvm::function_ref<void(const Expr *, int)> f);

/// Every assignment in every action, with its transition.
void forEachAssign(const Module &m,
                   llvm::function_ref<void(const AssignStmt *, int)> f);

/// Every expression `block` evaluates (as forEachRead lists them).
void forEachRead(Block block, llvm::function_ref<void(const Expr *)> f);

/// Every statement in `block`, nested ones included, each before its body.
void forEachStmt(Block block, llvm::function_ref<void(const Stmt *)> f);

/// Every assignment in `block`, nested ones included.
void forEachAssign(Block block, llvm::function_ref<void(const AssignStmt *)> f);

/// `block` with each assignment (nested ones included) replaced by the
/// statements `rewrite` appends for it (none drops it).
Block rewriteAssignments(
    Builder &b, Block block,
    llvm::function_ref<void(AssignStmt *, std::vector<Stmt *> &)> rewrite);
/// `block` without the assignments `keep` rejects (nested ones included).
Block dropAssignments(Builder &b, Block block,
                      llvm::function_ref<bool(const AssignStmt *)> keep);

/// The initial value of a scalar variable (its `init` or the type's
/// default: false, the low bound of a range, 0), or nullopt if the
/// initialiser is not a constant.
std::optional<int64_t> initialValue(const Var &v);

/// The variable or port an assignment target writes (through indices and
/// fields).
Symbol targetRoot(const Expr *target);

} // namespace netlift::net

#endif
