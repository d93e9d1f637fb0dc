//===- ReduceRanges.cpp - narrow integer variables to the values they take ===//
//
// `reduce-ranges` computes, for every integer variable (a range `lo..hi` or
// a PLC integer such as `int16 wrap`), an interval holding every value it
// can take: its initial value joined with the interval of every value
// assigned to it, evaluated by interval arithmetic over the intervals of
// the variables read, to a fixpoint (widened to the declared bounds after a
// few rounds, so a counter does not take 32767 rounds). The variable's type
// becomes that interval when it is smaller:
//  - a range (out-of-range writes are errors) is intersected with its
//    declared range, so an erroneous write is still erroneous;
//  - a wrapping PLC integer is narrowed only when no assignment can leave
//    its range, i.e. when it never wraps; it then becomes a range.
// The analysis is path-insensitive (it does not use guards or `if`
// conditions), so it is sound and sometimes coarse.
//
// Preserved: the state space exactly (values, steps, runtime errors); the
// state vector gets narrower.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;
using llvm::dyn_cast;

namespace {

struct Interval {
  int64_t lo, hi;
  Interval join(Interval o) const {
    return {std::min(lo, o.lo), std::max(hi, o.hi)};
  }
};

constexpr int64_t kBig = int64_t(1) << 62;

int64_t clampMul(int64_t a, int64_t b) {
  __int128 p = (__int128)a * b;
  return p > kBig ? kBig : p < -kBig ? -kBig : int64_t(p);
}

class RangeAnalysis {
public:
  explicit RangeAnalysis(const Module &m) : m(m), iv(m.vars.size()) {}
  const Module &m;
  std::vector<std::optional<Interval>> iv; // null: not yet assigned

  static Interval ofType(const Type *t) {
    if (!t)
      return {-kBig, kBig};
    if (t->isBool())
      return {0, 1};
    if (t->kind == TypeKind::Enum)
      return {0, int64_t(t->enumerators.size()) - 1};
    if (t->isInteger())
      return {t->lo, t->hi};
    return {-kBig, kBig};
  }

  Interval eval(const Expr *e) const {
    // A uint64 holds bit patterns its operators read unsigned: signed
    // intervals say nothing about them.
    if (e->type && e->type->isUnsigned64())
      return {-kBig, kBig};
    switch (e->getKind()) {
    case ExprKind::IntLit: {
      int64_t v = cast<IntLit>(e)->value;
      return {v, v};
    }
    case ExprKind::BoolLit:
      return {0, 1};
    case ExprKind::Ref: {
      auto *r = cast<Ref>(e);
      if (r->sym.kind == SymKind::Var && r->fields.empty() && iv[r->sym.index])
        return *iv[r->sym.index];
      return ofType(e->type);
    }
    case ExprKind::Unary: {
      auto *u = cast<UnaryExpr>(e);
      if (u->op == UnaryOp::Neg) {
        Interval a = eval(u->operand);
        return {-a.hi, -a.lo};
      }
      return ofType(e->type);
    }
    case ExprKind::Binary: {
      auto *x = cast<BinaryExpr>(e);
      if (x->op < BinaryOp::Add)
        return ofType(e->type); // Booleans and bit operations
      Interval a = eval(x->lhs), b = eval(x->rhs);
      switch (x->op) {
      case BinaryOp::Add:
        return {std::max(a.lo + b.lo, -kBig), std::min(a.hi + b.hi, kBig)};
      case BinaryOp::Sub:
        return {std::max(a.lo - b.hi, -kBig), std::min(a.hi - b.lo, kBig)};
      case BinaryOp::Mul: {
        int64_t c[4] = {clampMul(a.lo, b.lo), clampMul(a.lo, b.hi),
                        clampMul(a.hi, b.lo), clampMul(a.hi, b.hi)};
        return {*std::min_element(c, c + 4), *std::max_element(c, c + 4)};
      }
      case BinaryOp::Div: {
        // Truncating division never grows the magnitude.
        int64_t mag = std::max(std::abs(a.lo), std::abs(a.hi));
        return {-mag, mag};
      }
      case BinaryOp::Mod: {
        int64_t mb = std::max(std::abs(b.lo), std::abs(b.hi));
        return {a.lo < 0 ? -mb : 0, a.hi > 0 ? mb : 0};
      }
      default:
        return ofType(e->type);
      }
    }
    case ExprKind::Cond: {
      auto *c = cast<CondExpr>(e);
      return eval(c->thenExpr).join(eval(c->elseExpr));
    }
    case ExprKind::Call: {
      auto *c = cast<CallExpr>(e);
      if (c->fn == Builtin::Len || c->fn == Builtin::Find)
        return {0, int64_t(c->args[0]->type->maxLen)};
      if (c->fn != Builtin::Min && c->fn != Builtin::Max &&
          c->fn != Builtin::Abs)
        return ofType(e->type); // conversions, trunc: their type's range
      Interval a = eval(c->args[0]);
      if (c->fn == Builtin::Abs) {
        if (a.lo >= 0)
          return a;
        int64_t mag = std::max(std::abs(a.lo), std::abs(a.hi));
        return {a.hi < 0 ? -a.hi : 0, mag};
      }
      Interval b = eval(c->args[1]);
      if (c->fn == Builtin::Min)
        return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
      return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
    }
    default:
      return ofType(e->type);
    }
  }
};

bool candidate(const Var &v) {
  const Type *t = v.type;
  return t->kind == TypeKind::Range ||
         (t->kind == TypeKind::Int && !t->isUnsigned64());
}

class ReduceRangesPass : public Pass {
public:
  explicit ReduceRangesPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce-ranges");
    if (!m)
      return false;
    size_t nv = m->vars.size();
    RangeAnalysis ra(*m);
    std::vector<bool> usable(nv);
    for (uint32_t v = 0; v < nv; ++v) {
      const Var &var = m->vars[v];
      if (!candidate(var))
        continue;
      std::optional<int64_t> init = net::initialValue(var);
      if (!init)
        continue;
      usable[v] = true;
      ra.iv[v] = Interval{*init, *init};
    }
    // Writes through an index or field (arrays, records) are not analysed;
    // scalars only are candidates, so a whole-variable Ref is the target.
    std::vector<bool> wraps(nv);
    for (unsigned round = 0;; ++round) {
      bool changed = false;
      net::forEachAssign(*m, [&](const AssignStmt *a, int) {
        Symbol s = net::targetRoot(a->target);
        if (s.kind != SymKind::Var || !usable[s.index])
          return;
        const Type *t = m->vars[s.index].type;
        Interval decl = RangeAnalysis::ofType(t);
        Interval w = ra.eval(a->value);
        if (t->kind == TypeKind::Int && t->overflow == Overflow::Wrap &&
            (w.lo < decl.lo || w.hi > decl.hi)) {
          wraps[s.index] = true; // it may wrap: every value is possible
          w = decl;
        }
        // Erroneous writes store nothing: keep the part in range.
        w = {std::max(w.lo, decl.lo), std::min(w.hi, decl.hi)};
        if (w.lo > w.hi)
          return;
        Interval &cur = *ra.iv[s.index];
        Interval j = cur.join(w);
        if (j.lo != cur.lo || j.hi != cur.hi) {
          // Widening: after a few rounds a growing bound jumps to the
          // declared one.
          if (round >= 4)
            j = {j.lo < cur.lo ? decl.lo : j.lo,
                 j.hi > cur.hi ? decl.hi : j.hi};
          cur = j;
          changed = true;
        }
      });
      if (!changed)
        break;
    }
    Builder b(d);
    b.setModule(m);
    unsigned narrowed = 0;
    uint64_t bitsSaved = 0;
    auto bits = [](int64_t lo, int64_t hi) {
      uint64_t span = uint64_t(hi - lo);
      unsigned n = 0;
      while (span) {
        ++n;
        span >>= 1;
      }
      return n;
    };
    for (uint32_t v = 0; v < nv; ++v) {
      Var &var = m->vars[v];
      if (!usable[v] || wraps[v])
        continue;
      Interval decl = RangeAnalysis::ofType(var.type);
      Interval got = *ra.iv[v];
      if (got.lo == decl.lo && got.hi == decl.hi)
        continue;
      bitsSaved += bits(decl.lo, decl.hi) - bits(got.lo, got.hi);
      int64_t init = *net::initialValue(var);
      var.type = d.types.getRange(got.lo, got.hi);
      var.init = b.intLit(init, var.loc); // the new type's default may differ
      ++narrowed;
    }
    stats.add("reduce-ranges", "variables", narrowed,
              "integer variables narrowed");
    stats.add("reduce-ranges", "bits", bitsSaved,
              "bits saved in the state vector");
    return !narrowed || reduce::reverify(d, diag, "reduce-ranges");
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReduceRangesPass(const PassOptions &opts) {
  return std::make_unique<ReduceRangesPass>(opts);
}
} // namespace netlift
