//===- Clone.cpp - copying expressions and actions ------------------------===//
#include "ir/net/Clone.h"

#include "llvm/ADT/SmallVector.h"

using namespace netlift::net;
using llvm::cast;

Expr *netlift::net::cloneExpr(Builder &b, const Module &src, const Expr *e,
                              RenameFn rename) {
  if (!e)
    return nullptr;
  auto rec = [&](const Expr *x) { return cloneExpr(b, src, x, rename); };
  switch (e->getKind()) {
  case ExprKind::IntLit:
    return b.intLit(cast<IntLit>(e)->value, e->loc);
  case ExprKind::BoolLit:
    return b.boolLit(cast<BoolLit>(e)->value, e->loc);
  case ExprKind::RealLit:
    return b.realLit(cast<RealLit>(e)->value, e->loc);
  case ExprKind::StringLit:
    return b.stringLit(cast<StringLit>(e)->chars, e->loc);
  case ExprKind::Ref: {
    auto *r = cast<Ref>(e);
    switch (r->sym.kind) {
    case SymKind::Place:
    case SymKind::Port:
    case SymKind::Var: {
      llvm::StringRef base = src.symbolName(r->sym);
      std::string n = rename(base) + r->name.drop_front(base.size()).str();
      return b.ref(n, e->loc);
    }
    case SymKind::EnumLit:
      if (r->type && !r->type->name.empty())
        return b.ref(
            (r->type->name + "#" + r->type->enumerators[r->sym.index]).str(),
            e->loc);
      return b.ref(r->name, e->loc);
    default:
      return b.ref(r->name, e->loc);
    }
  }
  case ExprKind::Index: {
    auto *x = cast<IndexExpr>(e);
    return b.index(rec(x->base), rec(x->index), e->loc);
  }
  case ExprKind::Field: {
    auto *f = cast<FieldExpr>(e);
    return b.field(rec(f->base), f->field, e->loc);
  }
  case ExprKind::Unary: {
    auto *u = cast<UnaryExpr>(e);
    return b.unary(u->op, rec(u->operand), e->loc);
  }
  case ExprKind::Binary: {
    auto *x = cast<BinaryExpr>(e);
    return b.binary(x->op, rec(x->lhs), rec(x->rhs), e->loc);
  }
  case ExprKind::Cond: {
    auto *c = cast<CondExpr>(e);
    return b.cond(rec(c->cond), rec(c->thenExpr), rec(c->elseExpr), e->loc);
  }
  case ExprKind::Call: {
    auto *c = cast<CallExpr>(e);
    llvm::SmallVector<Expr *, 2> args;
    for (const Expr *a : c->args)
      args.push_back(rec(a));
    return b.call(c->fn, args, e->loc, c->to);
  }
  case ExprKind::Aggregate: {
    auto *a = cast<AggregateLit>(e);
    llvm::SmallVector<Expr *, 8> elems;
    for (const Expr *x : a->elems)
      elems.push_back(rec(x));
    return b.aggregate(elems, a->fieldNames, e->loc);
  }
  }
  return nullptr;
}

Block netlift::net::cloneBlock(Builder &b, const Module &src, Block block,
                               RenameFn rename) {
  llvm::SmallVector<Stmt *, 8> out;
  auto ce = [&](const Expr *x) { return cloneExpr(b, src, x, rename); };
  auto cb = [&](Block x) { return cloneBlock(b, src, x, rename); };
  for (const Stmt *s : block) {
    switch (s->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(s);
      out.push_back(b.assign(ce(a->target), ce(a->value), s->loc));
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      llvm::SmallVector<IfArm, 2> arms;
      for (const IfArm &arm : i->arms)
        arms.push_back({ce(arm.cond), cb(arm.body)});
      out.push_back(b.ifStmt(arms, i->hasElse, cb(i->elseBody), s->loc));
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      std::vector<CaseArm> arms;
      for (const CaseArm &arm : c->arms) {
        llvm::SmallVector<CaseLabel, 4> labels;
        for (const CaseLabel &l : arm.labels)
          labels.push_back({ce(l.lo), ce(l.hi)});
        arms.push_back({b.getDesign().copy(llvm::ArrayRef<CaseLabel>(labels)),
                        cb(arm.body)});
      }
      out.push_back(b.caseStmt(ce(c->selector), arms, c->hasElse,
                               cb(c->elseBody), s->loc));
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      out.push_back(
          b.forStmt(f->var, ce(f->lo), ce(f->hi), cb(f->body), s->loc));
      break;
    }
    case StmtKind::While: {
      auto *w = cast<WhileStmt>(s);
      out.push_back(
          b.whileStmt(ce(w->cond), cb(w->body), w->testAfter, s->loc));
      break;
    }
    }
  }
  return b.getDesign().copy(llvm::ArrayRef<Stmt *>(out));
}
