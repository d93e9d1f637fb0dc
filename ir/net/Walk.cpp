//===- Walk.cpp - visiting what a module reads and writes
//------------------===//
#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;
using llvm::dyn_cast;

void net::forEachOperand(const Expr *e,
                         llvm::function_ref<void(const Expr *)> f) {
  switch (e->getKind()) {
  case ExprKind::Index:
    f(cast<IndexExpr>(e)->base);
    f(cast<IndexExpr>(e)->index);
    break;
  case ExprKind::Field:
    f(cast<FieldExpr>(e)->base);
    break;
  case ExprKind::Unary:
    f(cast<UnaryExpr>(e)->operand);
    break;
  case ExprKind::Binary:
    f(cast<BinaryExpr>(e)->lhs);
    f(cast<BinaryExpr>(e)->rhs);
    break;
  case ExprKind::Cond:
    f(cast<CondExpr>(e)->cond);
    f(cast<CondExpr>(e)->thenExpr);
    f(cast<CondExpr>(e)->elseExpr);
    break;
  case ExprKind::Call:
    for (const Expr *a : cast<CallExpr>(e)->args)
      f(a);
    break;
  default:
    break;
  }
}

void net::walkExpr(const Expr *e, llvm::function_ref<void(const Expr *)> f) {
  if (!e)
    return;
  f(e);
  forEachOperand(e, [&](const Expr *x) { walkExpr(x, f); });
}

namespace {
/// Visits a block: `read` for every expression evaluated, `assign` for
/// every assignment, `visit` for every statement (before its body).
void walkBlock(Block b, int t, llvm::function_ref<void(const Expr *, int)> read,
               llvm::function_ref<void(const AssignStmt *, int)> assign,
               llvm::function_ref<void(const Stmt *)> visit = nullptr) {
  for (const Stmt *s : b) {
    if (visit)
      visit(s);
    switch (s->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(s);
      if (assign)
        assign(a, t);
      if (read) {
        read(a->value, t);
        // Indices inside the target are read; the root is written.
        for (const Expr *x = a->target; x;) {
          if (auto *ix = dyn_cast<IndexExpr>(x)) {
            read(ix->index, t);
            x = ix->base;
          } else if (auto *fe = dyn_cast<FieldExpr>(x)) {
            x = fe->base;
          } else {
            x = nullptr;
          }
        }
      }
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      for (const IfArm &arm : i->arms) {
        if (read)
          read(arm.cond, t);
        walkBlock(arm.body, t, read, assign, visit);
      }
      walkBlock(i->elseBody, t, read, assign, visit);
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      if (read)
        read(c->selector, t);
      for (const CaseArm &arm : c->arms) {
        if (read)
          for (const CaseLabel &l : arm.labels) {
            read(l.lo, t);
            if (l.hi)
              read(l.hi, t);
          }
        walkBlock(arm.body, t, read, assign, visit);
      }
      walkBlock(c->elseBody, t, read, assign, visit);
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      if (read) {
        read(f->lo, t);
        read(f->hi, t);
      }
      walkBlock(f->body, t, read, assign, visit);
      break;
    }
    case StmtKind::While: {
      auto *w = cast<WhileStmt>(s);
      if (read)
        read(w->cond, t);
      walkBlock(w->body, t, read, assign, visit);
      break;
    }
    }
  }
}
} // namespace

void net::forEachRead(const Module &m,
                      llvm::function_ref<void(const Expr *, int)> f) {
  for (const Port &p : m.ports) {
    if (p.definition)
      f(p.definition, -1);
    if (p.init)
      f(p.init, -1);
  }
  for (const Var &v : m.vars)
    if (v.init)
      f(v.init, -1);
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    const Transition &tr = m.transitions[t];
    for (const Expr *c : tr.conds())
      f(c, int(t));
    if (tr.guard())
      f(tr.guard(), int(t));
    walkBlock(tr.action(), int(t), f, nullptr);
  }
}

void net::forEachRead(Block block, llvm::function_ref<void(const Expr *)> f) {
  walkBlock(
      block, -1, [&](const Expr *e, int) { f(e); }, nullptr);
}

void net::forEachAssign(const Module &m,
                        llvm::function_ref<void(const AssignStmt *, int)> f) {
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    walkBlock(m.transitions[t].action(), int(t), nullptr, f);
}

Block net::rewriteAssignments(
    Builder &b, Block blk,
    llvm::function_ref<void(AssignStmt *, std::vector<Stmt *> &)> rewrite) {
  std::vector<Stmt *> out;
  Design &d = b.getDesign();
  auto inner = [&](Block body) { return rewriteAssignments(b, body, rewrite); };
  for (Stmt *s : blk) {
    if (auto *a = dyn_cast<AssignStmt>(s)) {
      rewrite(a, out);
    } else if (auto *i = dyn_cast<IfStmt>(s)) {
      std::vector<IfArm> arms;
      for (const IfArm &arm : i->arms)
        arms.push_back({arm.cond, inner(arm.body)});
      out.push_back(b.ifStmt(arms, i->hasElse, inner(i->elseBody), s->loc));
    } else if (auto *c = dyn_cast<CaseStmt>(s)) {
      std::vector<CaseArm> arms;
      for (const CaseArm &arm : c->arms)
        arms.push_back({arm.labels, inner(arm.body)});
      out.push_back(b.caseStmt(c->selector, arms, c->hasElse,
                               inner(c->elseBody), s->loc));
    } else if (auto *f = dyn_cast<ForStmt>(s)) {
      out.push_back(b.forStmt(f->var, f->lo, f->hi, inner(f->body), s->loc));
    } else if (auto *w = dyn_cast<WhileStmt>(s)) {
      out.push_back(b.whileStmt(w->cond, inner(w->body), w->testAfter, s->loc));
    }
  }
  return d.copy(llvm::ArrayRef<Stmt *>(out));
}

Block net::dropAssignments(Builder &b, Block blk,
                           llvm::function_ref<bool(const AssignStmt *)> keep) {
  return rewriteAssignments(b, blk,
                            [&](AssignStmt *a, std::vector<Stmt *> &out) {
                              if (keep(a))
                                out.push_back(a);
                            });
}

void net::forEachStmt(Block block, llvm::function_ref<void(const Stmt *)> f) {
  walkBlock(block, -1, nullptr, nullptr, f);
}

void net::forEachAssign(Block block,
                        llvm::function_ref<void(const AssignStmt *)> f) {
  walkBlock(block, -1, nullptr, [&](const AssignStmt *a, int) { f(a); });
}

std::optional<int64_t> net::initialValue(const Var &v) {
  const Type *t = v.type;
  if (!v.init)
    return t->kind == TypeKind::Range ? t->lo : 0;
  if (auto *bl = dyn_cast<BoolLit>(v.init))
    return bl->value;
  if (auto *r = dyn_cast<Ref>(v.init))
    if (r->sym.kind == SymKind::EnumLit)
      return r->sym.index;
  int64_t x;
  if (evalConstInt(v.init, x))
    return x;
  return std::nullopt;
}

Symbol net::targetRoot(const Expr *target) {
  for (const Expr *x = target; x;) {
    if (auto *r = dyn_cast<Ref>(x))
      return r->sym;
    if (auto *ix = dyn_cast<IndexExpr>(x))
      x = ix->base;
    else if (auto *fe = dyn_cast<FieldExpr>(x))
      x = fe->base;
    else
      break;
  }
  return {};
}
