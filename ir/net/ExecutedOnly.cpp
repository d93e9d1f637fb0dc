//===- ExecutedOnly.cpp - what only execution gives a meaning to ----------===//
#include "ir/net/ExecutedOnly.h"

#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::net;

const char *net::executedOnlyData(const Type *t) {
  switch (t->kind) {
  case TypeKind::Float:
    return "floating point";
  case TypeKind::String:
    return "a string";
  case TypeKind::Int:
    return t->isUnsigned64() ? "64-bit unsigned arithmetic" : nullptr;
  case TypeKind::Array:
    return executedOnlyData(t->elem);
  case TypeKind::Record:
    for (const Field &f : t->fields)
      if (const char *what = executedOnlyData(f.type))
        return what;
    return nullptr;
  default:
    return nullptr;
  }
}

namespace {
/// A loop only execution can run: `while`, `repeat`, or `for` with bounds
/// that are not constants.
std::optional<ExecutedOnly> asExecutedOnlyLoop(const Stmt *s) {
  if (auto *w = llvm::dyn_cast<WhileStmt>(s))
    return ExecutedOnly{s->loc, w->testAfter ? "a loop without constant "
                                               "bounds ('repeat')"
                                             : "a loop without constant "
                                               "bounds ('while')"};
  int64_t v;
  if (auto *f = llvm::dyn_cast<ForStmt>(s))
    if (!evalConstInt(f->lo, v) || !evalConstInt(f->hi, v))
      return ExecutedOnly{s->loc, "a loop without constant bounds ('for')"};
  return std::nullopt;
}
} // namespace

std::optional<ExecutedOnly> net::findExecutedOnly(const Module &m) {
  for (const Var &v : m.vars)
    if (const char *what = executedOnlyData(v.type))
      return ExecutedOnly{v.loc, "the " + v.type->str() + " variable '" +
                                     v.name.str() + "' (" + what + ")"};
  for (const Port &p : m.ports)
    if (const char *what = p.type ? executedOnlyData(p.type) : nullptr)
      return ExecutedOnly{p.loc, "the " + p.type->str() + " port '" +
                                     p.name.str() + "' (" + what + ")"};
  std::optional<ExecutedOnly> found;
  forEachRead(m, [&](const Expr *e, int) {
    walkExpr(e, [&](const Expr *x) {
      if (!found && x->type && x->type->isFloat())
        found = ExecutedOnly{x->loc, "floating-point arithmetic"};
      if (!found && x->type && x->type->isString())
        found = ExecutedOnly{x->loc, "a string operation"};
    });
  });
  if (found)
    return found;
  for (const Transition &t : m.transitions)
    forEachStmt(t.action(), [&](const Stmt *s) {
      if (!found)
        found = asExecutedOnlyLoop(s);
    });
  return found;
}
