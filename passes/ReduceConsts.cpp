//===- ReduceConsts.cpp - constant propagation and unused variables -------===//
//
// `reduce-consts`:
//  - a scalar variable that no action writes keeps its initial value: every
//    read becomes that constant and the variable goes (clocks advance with
//    time and are never constant);
//  - constant sub-expressions are folded (`1 + 2`, `c and false`,
//    `true ? a : b`, comparisons of constants) in guards, condition arcs,
//    output definitions and actions; an `if` or `case` whose choice is
//    constant keeps only the branch taken; a guard or condition arc that
//    folds to `true` disappears (one that folds to `false` is left for
//    reduce-dead, which removes the transition);
//  - a variable nothing reads goes with the assignments to it, when this
//    cannot hide a runtime error: its type is bool, an enumeration or a
//    wrapping integer (no out-of-range error), or every value assigned is
//    a constant within its range, and at most one transition writes it (so
//    no write conflict is lost).
//
// Preserved: the state space up to the removed variables (a constant one
// has one value; an unread one influences nothing), every step, every
// runtime error.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"
#include "ir/net/Clone.h"

#include "llvm/ADT/DenseMap.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;
using llvm::dyn_cast;
using llvm::isa;

namespace {

class ConstFolder {
public:
  ConstFolder(Design &d, Module &m) : d(d), m(m), b(d) { b.setModule(&m); }

  /// Values of the variables found constant (scalars only).
  llvm::DenseMap<uint32_t, int64_t> constVars;
  unsigned folded = 0;

  Expr *fold(Expr *e);
  Block foldBlock(Block blk);

private:
  std::optional<int64_t> value(const Expr *e) const {
    if (auto *i = dyn_cast<IntLit>(e))
      return i->value;
    if (auto *bl = dyn_cast<BoolLit>(e))
      return bl->value;
    if (auto *r = dyn_cast<Ref>(e))
      if (r->sym.kind == SymKind::EnumLit)
        return r->sym.index;
    return std::nullopt;
  }
  /// A literal for `v` of type `t` (the type of the expression replaced).
  Expr *literal(const Type *t, int64_t v, llvm::SMLoc loc) {
    ++folded;
    if (t && t->isBool())
      return b.boolLit(v != 0, loc);
    if (t && t->kind == TypeKind::Enum) {
      // Resolved at once, so that folding can compare it right away.
      auto *r =
          cast<Ref>(b.ref((t->name + "#" + t->enumerators[v]).str(), loc));
      r->sym = {SymKind::EnumLit, uint32_t(v)};
      r->type = t;
      return r;
    }
    return b.intLit(v, loc);
  }
  Design &d;
  Module &m;
  Builder b;
};

Expr *ConstFolder::fold(Expr *e) {
  if (!e)
    return e;
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = cast<Ref>(e);
    if (r->sym.kind == SymKind::Var && r->fields.empty()) {
      auto it = constVars.find(r->sym.index);
      if (it != constVars.end())
        return literal(r->type, it->second, r->loc);
    }
    return e;
  }
  case ExprKind::Index: {
    auto *x = cast<IndexExpr>(e);
    x->index = fold(x->index);
    return e;
  }
  case ExprKind::Unary: {
    auto *u = cast<UnaryExpr>(e);
    u->operand = fold(u->operand);
    auto v = value(u->operand);
    if (!v)
      return e;
    switch (u->op) {
    case UnaryOp::Not:
      return literal(e->type, !*v, e->loc);
    case UnaryOp::Neg:
      return literal(e->type, -*v, e->loc);
    case UnaryOp::BitNot:
      return e; // width-dependent: left to the interpreter
    }
    return e;
  }
  case ExprKind::Binary: {
    auto *x = cast<BinaryExpr>(e);
    x->lhs = fold(x->lhs);
    x->rhs = fold(x->rhs);
    auto a = value(x->lhs), c = value(x->rhs);
    if ((x->lhs->type && x->lhs->type->isUnsigned64()) ||
        (x->rhs->type && x->rhs->type->isUnsigned64()))
      return e; // unsigned arithmetic is left to the engine
    // Boolean identities need only one constant side.
    if (x->op == BinaryOp::And || x->op == BinaryOp::Or) {
      bool isAnd = x->op == BinaryOp::And;
      for (auto [k, other] : {std::pair{a, x->rhs}, std::pair{c, x->lhs}}) {
        if (!k)
          continue;
        if (bool(*k) == isAnd) {
          ++folded;
          return other; // true and y = y; false or y = y
        }
        return literal(e->type, !isAnd, e->loc);
      }
      return e;
    }
    if (!a || !c)
      return e;
    int64_t l = *a, r = *c;
    switch (x->op) {
    case BinaryOp::Xor:
      return literal(e->type, (l != 0) != (r != 0), e->loc);
    case BinaryOp::Eq:
      return literal(e->type, l == r, e->loc);
    case BinaryOp::Ne:
      return literal(e->type, l != r, e->loc);
    case BinaryOp::Lt:
      return literal(e->type, l < r, e->loc);
    case BinaryOp::Le:
      return literal(e->type, l <= r, e->loc);
    case BinaryOp::Gt:
      return literal(e->type, l > r, e->loc);
    case BinaryOp::Ge:
      return literal(e->type, l >= r, e->loc);
    case BinaryOp::Add:
      return literal(e->type, l + r, e->loc);
    case BinaryOp::Sub:
      return literal(e->type, l - r, e->loc);
    case BinaryOp::Mul:
      return literal(e->type, l * r, e->loc);
    default:
      return e; // division by zero, shifts, bit operations: at run time
    }
  }
  case ExprKind::Cond: {
    auto *c = cast<CondExpr>(e);
    c->cond = fold(c->cond);
    c->thenExpr = fold(c->thenExpr);
    c->elseExpr = fold(c->elseExpr);
    if (auto v = value(c->cond)) {
      ++folded;
      return *v ? c->thenExpr : c->elseExpr;
    }
    return e;
  }
  case ExprKind::Call: {
    auto *c = cast<CallExpr>(e);
    std::vector<Expr *> args;
    bool allConst = true;
    for (Expr *a : c->args) {
      args.push_back(fold(a));
      allConst &= bool(value(args.back()));
    }
    c->args = d.copy(llvm::ArrayRef<Expr *>(args));
    if (!allConst)
      return e;
    int64_t v0 = *value(args[0]);
    switch (c->fn) {
    case Builtin::Min:
      return literal(e->type, std::min(v0, *value(args[1])), e->loc);
    case Builtin::Max:
      return literal(e->type, std::max(v0, *value(args[1])), e->loc);
    case Builtin::Abs:
      return literal(e->type, v0 < 0 ? -v0 : v0, e->loc);
    default: // conversions and float functions are left to the engine
      return e;
    }
  }
  default:
    return e;
  }
}

Block ConstFolder::foldBlock(Block blk) {
  std::vector<Stmt *> out;
  auto append = [&](Block inner) {
    for (Stmt *s : foldBlock(inner))
      out.push_back(s);
  };
  for (Stmt *s : blk) {
    switch (s->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(s);
      a->value = fold(a->value);
      if (auto *ix = dyn_cast<IndexExpr>(a->target))
        ix->index = fold(ix->index);
      out.push_back(s);
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      std::vector<IfArm> arms;
      bool decided = false;
      for (const IfArm &arm : i->arms) {
        Expr *c = fold(arm.cond);
        auto v = value(c);
        if (v && !*v) {
          ++folded;
          continue; // never taken
        }
        if (v && *v && arms.empty()) {
          ++folded;
          append(arm.body); // always taken
          decided = true;
          break;
        }
        arms.push_back({c, foldBlock(arm.body)});
        if (v && *v) {
          // Taken whenever reached: it is the else of what precedes.
          arms.back().cond = nullptr;
          break;
        }
      }
      if (decided)
        break;
      bool hasElse = i->hasElse;
      Block elseBody = i->elseBody;
      if (!arms.empty() && !arms.back().cond) {
        hasElse = true;
        elseBody = arms.back().body;
        arms.pop_back();
      } else {
        elseBody = foldBlock(elseBody);
      }
      if (arms.empty()) {
        append(elseBody);
        break;
      }
      out.push_back(
          b.ifStmt(arms, hasElse && !elseBody.empty(), elseBody, s->loc));
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      c->selector = fold(c->selector);
      if (auto v = value(c->selector)) {
        ++folded;
        Block taken = c->elseBody;
        for (const CaseArm &arm : c->arms) {
          bool hit = false;
          for (const CaseLabel &l : arm.labels) {
            auto lo = value(l.lo), hi = l.hi ? value(l.hi) : value(l.lo);
            if (lo && hi && *lo <= *v && *v <= *hi)
              hit = true;
          }
          if (hit) {
            taken = arm.body;
            break;
          }
        }
        append(taken);
        break;
      }
      std::vector<CaseArm> arms;
      for (const CaseArm &arm : c->arms)
        arms.push_back({arm.labels, foldBlock(arm.body)});
      out.push_back(b.caseStmt(c->selector, arms, c->hasElse,
                               foldBlock(c->elseBody), s->loc));
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      out.push_back(
          b.forStmt(f->var, f->lo, f->hi, foldBlock(f->body), s->loc));
      break;
    }
    case StmtKind::While: {
      auto *w = cast<WhileStmt>(s);
      out.push_back(
          b.whileStmt(fold(w->cond), foldBlock(w->body), w->testAfter, s->loc));
      break;
    }
    }
  }
  return d.copy(llvm::ArrayRef<Stmt *>(out));
}

class ReduceConstsPass : public Pass {
public:
  explicit ReduceConstsPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce-consts");
    if (!m)
      return false;
    reduce::Uses uses(*m);
    ConstFolder cf(d, *m);
    size_t nv = m->vars.size();
    std::vector<bool> dropWrites(nv);
    std::vector<bool> keepVar(nv, true);
    unsigned consts = 0, unused = 0;
    // Assignments whose value is a constant within the range.
    std::vector<bool> safeWrites(nv, true);
    net::forEachAssign(*m, [&](const AssignStmt *a, int) {
      Symbol s = net::targetRoot(a->target);
      if (s.kind != SymKind::Var)
        return;
      const Type *t = m->vars[s.index].type;
      int64_t x;
      if (!isa<Ref>(a->target) || !evalConstInt(a->value, x) || x < t->lo ||
          x > t->hi)
        safeWrites[s.index] = false;
    });
    for (uint32_t v = 0; v < nv; ++v) {
      const Var &var = m->vars[v];
      const Type *t = var.type;
      // A uint64's literal would lose the unsigned reading of its bits.
      if (!t->isScalar() || t->isClock() || t->isReal() || t->isFloat() ||
          t->isUnsigned64())
        continue;
      if (uses.writers[v].empty()) {
        if (auto x = net::initialValue(var)) {
          cf.constVars[v] = *x;
          keepVar[v] = false;
          ++consts;
        }
        continue;
      }
      bool noErrors =
          t->isBool() || t->kind == TypeKind::Enum ||
          (t->kind == TypeKind::Int && t->overflow == Overflow::Wrap) ||
          safeWrites[v];
      if (!uses.varRead[v] && uses.writers[v].size() == 1 && noErrors) {
        dropWrites[v] = true;
        keepVar[v] = false;
        ++unused;
      }
    }
    for (Port &p : m->ports) {
      p.definition = cf.fold(p.definition);
    }
    unsigned guardsDropped = 0;
    Builder b(d);
    b.setModule(m);
    for (uint32_t t = 0; t < m->transitions.size(); ++t) {
      Transition &tr = m->transitions[t];
      if (!tr.extras)
        continue;
      std::vector<Expr *> conds;
      for (Expr *c : tr.extras->conds) {
        Expr *f = cf.fold(c);
        auto *bl = dyn_cast<BoolLit>(f);
        if (bl && bl->value) {
          ++guardsDropped;
          continue;
        }
        conds.push_back(f);
      }
      tr.extras->conds = d.copy(llvm::ArrayRef<Expr *>(conds));
      if (tr.extras->guard) {
        Expr *g = cf.fold(tr.extras->guard);
        auto *bl = dyn_cast<BoolLit>(g);
        if (bl && bl->value) {
          g = nullptr;
          ++guardsDropped;
        }
        tr.extras->guard = g;
      }
      if (tr.extras->hasAction)
        tr.extras->action = cf.foldBlock(net::dropAssignments(
            b, tr.extras->action, [&](const AssignStmt *a) {
              Symbol s = net::targetRoot(a->target);
              return !(s.kind == SymKind::Var && dropWrites[s.index]);
            }));
    }
    stats.add("reduce-consts", "constants", consts,
              "variables never written replaced by their value");
    stats.add("reduce-consts", "unused", unused,
              "variables never read removed");
    stats.add("reduce-consts", "folded", cf.folded,
              "expressions and statements folded");
    stats.add("reduce-consts", "conditions", guardsDropped,
              "guards and condition arcs always true removed");
    if (!consts && !unused && !cf.folded && !guardsDropped)
      return true;
    std::vector<bool> keepPlace(m->places.size(), true),
        keepTrans(m->transitions.size(), true);
    reduce::compactModule(*m, keepPlace, keepTrans, keepVar);
    return reduce::reverify(d, diag, "reduce-consts");
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReduceConstsPass(const PassOptions &opts) {
  return std::make_unique<ReduceConstsPass>(opts);
}
} // namespace netlift
