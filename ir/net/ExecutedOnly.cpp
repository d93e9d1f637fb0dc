//===- ExecutedOnly.cpp - what only execution gives a meaning to ----------===//
#include "ir/net/ExecutedOnly.h"

#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;

bool net::holdsFloat(const Type *t) {
  switch (t->kind) {
  case TypeKind::Float:
    return true;
  case TypeKind::Array:
    return holdsFloat(t->elem);
  case TypeKind::Record:
    for (const Field &f : t->fields)
      if (holdsFloat(f.type))
        return true;
    return false;
  default:
    return false;
  }
}

namespace {
std::optional<ExecutedOnly> inBlock(Block b) {
  for (const Stmt *s : b) {
    switch (s->getKind()) {
    case StmtKind::Assign:
      break;
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      for (const IfArm &arm : i->arms)
        if (auto r = inBlock(arm.body))
          return r;
      if (auto r = inBlock(i->elseBody))
        return r;
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      for (const CaseArm &arm : c->arms)
        if (auto r = inBlock(arm.body))
          return r;
      if (auto r = inBlock(c->elseBody))
        return r;
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      int64_t v;
      if (!evalConstInt(f->lo, v) || !evalConstInt(f->hi, v))
        return ExecutedOnly{s->loc, "a loop without constant bounds ('for')"};
      if (auto r = inBlock(f->body))
        return r;
      break;
    }
    case StmtKind::While:
      return ExecutedOnly{s->loc, cast<WhileStmt>(s)->testAfter
                                      ? "a loop without constant bounds "
                                        "('repeat')"
                                      : "a loop without constant bounds "
                                        "('while')"};
    }
  }
  return std::nullopt;
}
} // namespace

std::optional<ExecutedOnly> net::findExecutedOnly(const Module &m) {
  for (const Var &v : m.vars)
    if (holdsFloat(v.type))
      return ExecutedOnly{v.loc, "the " + v.type->str() + " variable '" +
                                     v.name.str() + "' (floating point)"};
  for (const Port &p : m.ports)
    if (p.type && holdsFloat(p.type))
      return ExecutedOnly{p.loc, "the " + p.type->str() + " port '" +
                                     p.name.str() + "' (floating point)"};
  std::optional<ExecutedOnly> found;
  forEachRead(m, [&](const Expr *e, int) {
    walkExpr(e, [&](const Expr *x) {
      if (!found && x->type && x->type->isFloat())
        found = ExecutedOnly{x->loc, "floating-point arithmetic"};
    });
  });
  if (found)
    return found;
  for (const Transition &t : m.transitions)
    if (auto r = inBlock(t.action()))
      return r;
  return std::nullopt;
}
