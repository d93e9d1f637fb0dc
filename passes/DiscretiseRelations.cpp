//===- DiscretiseRelations.cpp - comparisons of sums of reals -------------===//
//
// Hybrid models compare more than one real with a constant: a switching
// line `y + 0.714*x == 0`, a scaled bound `2*x <= 7`, the difference of
// two clocks `x1 - x2 > 2*d` in a forbidden set. A comparison reading one
// real through a linear sum is the bound `x op c` it is equivalent to, and
// is rewritten so before anything reads it: its constant becomes a grid
// point like any threshold, and the discretisation stays exact. One
// relating several reals (a relation) cannot be made exact on grids that
// each real places by itself: it becomes the disjunction of the
// combinations of position places in which it may hold (or, under a
// negation, must hold), computed by interval arithmetic over the values
// each position stands for. A guard or a forbidden set so coded
// over-approximates the hybrid model (a `never forbidden` verified on the
// net holds on the hybrid model; a guard may fire where the hybrid model
// could not); a relation in a location invariant is not enforced (the
// place may be stayed in longer), again an over-approximation, and a note
// says so at each.
//
//===----------------------------------------------------------------------===//
#include "passes/Discretiser.h"

#include "ir/net/Printer.h"

#include "llvm/Support/FormatVariadic.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

namespace {

/// `lhs - rhs` of a comparison, as a sum over reals.
std::optional<LinearSum> difference(BinaryExpr *cmp, const Module &m) {
  auto l = linearSum(cmp->lhs, m), r = linearSum(cmp->rhs, m);
  if (!l || !r)
    return std::nullopt;
  l->add(*r, -1);
  l->dropZeros();
  return l;
}

BinaryOp mirrored(BinaryOp op) {
  switch (op) {
  case BinaryOp::Lt:
    return BinaryOp::Gt;
  case BinaryOp::Le:
    return BinaryOp::Ge;
  case BinaryOp::Gt:
    return BinaryOp::Lt;
  case BinaryOp::Ge:
    return BinaryOp::Le;
  default:
    return op;
  }
}

} // namespace

std::optional<LinearSum> discretise::linearSum(Expr *e, const Module &m) {
  if (auto c = evalConstReal(e)) {
    LinearSum s;
    s.constant = *c;
    return s;
  }
  if (auto *r = llvm::dyn_cast<Ref>(e)) {
    if (r->sym.kind != SymKind::Var || !r->fields.empty() ||
        !m.vars[r->sym.index].type->isReal())
      return std::nullopt;
    LinearSum s;
    s.coef[r->sym.index] = 1;
    s.refOf[r->sym.index] = r;
    return s;
  }
  if (auto *u = llvm::dyn_cast<UnaryExpr>(e)) {
    if (u->op != UnaryOp::Neg)
      return std::nullopt;
    auto s = linearSum(u->operand, m);
    if (s)
      s->scale(-1);
    return s;
  }
  auto *bin = llvm::dyn_cast<BinaryExpr>(e);
  if (!bin)
    return std::nullopt;
  auto l = linearSum(bin->lhs, m), r = linearSum(bin->rhs, m);
  if (!l || !r)
    return std::nullopt;
  switch (bin->op) {
  case BinaryOp::Add:
    l->add(*r, 1);
    return l;
  case BinaryOp::Sub:
    l->add(*r, -1);
    return l;
  case BinaryOp::Mul:
    if (r->coef.empty()) {
      l->scale(r->constant);
      return l;
    }
    if (l->coef.empty()) {
      r->scale(l->constant);
      return r;
    }
    return std::nullopt;
  case BinaryOp::Div:
    if (!r->coef.empty() || r->constant == 0)
      return std::nullopt;
    l->scale(1 / r->constant);
    return l;
  default:
    return std::nullopt;
  }
}

void Discretiser::normaliseComparisons() {
  std::function<void(Expr *)> walk = [&](Expr *e) {
    if (!e)
      return;
    if (auto *u = llvm::dyn_cast<UnaryExpr>(e))
      return walk(u->operand);
    if (auto *c = llvm::dyn_cast<CondExpr>(e)) {
      walk(c->cond);
      walk(c->thenExpr);
      return walk(c->elseExpr);
    }
    auto *bin = llvm::dyn_cast<BinaryExpr>(e);
    if (!bin)
      return;
    if (!isComparison(bin->op)) {
      walk(bin->lhs);
      return walk(bin->rhs);
    }
    auto isPlainRef = [](Expr *x) {
      auto *r = llvm::dyn_cast<Ref>(x);
      return r && r->sym.kind == SymKind::Var && r->fields.empty();
    };
    if ((isPlainRef(bin->lhs) && evalConstReal(bin->rhs)) ||
        (isPlainRef(bin->rhs) && evalConstReal(bin->lhs)))
      return; // already `x op c`
    auto diff = difference(bin, m);
    if (!diff || diff->coef.size() != 1)
      return;
    // a*x + b op 0  <=>  x op' -b/a, op' mirrored when a < 0.
    auto [var, a] = *diff->coef.begin();
    bin->lhs = diff->refOf[var];
    // Snapped to 12 significant digits: `0.1*x <= 0.3` means x <= 3, not
    // 2.9999999999999996, a grid point a rounding error away from 3.
    double bound = std::strtod(
        llvm::formatv("{0:e11}", -diff->constant / a).str().c_str(), nullptr);
    bin->rhs = b.realLit(bound, bin->loc);
    if (a < 0)
      bin->op = mirrored(bin->op);
  };
  for (Transition &t : m.transitions)
    walk(t.guard());
  for (Port &p : m.ports)
    walk(p.definition);
  for (Invariant &inv : m.invariants)
    for (Expr *c : inv.conditions)
      walk(c);
}

std::optional<Discretiser::Relation>
Discretiser::relationOf(BinaryExpr *cmp) const {
  if (!isComparison(cmp->op))
    return std::nullopt;
  auto diff = difference(cmp, m);
  if (!diff || diff->coef.size() < 2)
    return std::nullopt;
  Relation rel;
  rel.op = cmp->op;
  rel.constant = diff->constant;
  for (auto &[var, a] : diff->coef) {
    auto it = realOfVar.find(var);
    if (it == realOfVar.end())
      return std::nullopt; // a real discretise does not follow
    rel.terms.push_back({it->second, a});
  }
  return rel;
}

bool Discretiser::scanRelation(BinaryExpr *cmp, int polarity, bool &isOne) {
  isOne = false;
  std::optional<Relation> rel = relationOf(cmp);
  if (!rel)
    return true;
  isOne = true;
  if (polarity == 0)
    return error(cmp->loc,
                 "'" + exprToString(cmp) +
                     "' relates several reals where it is neither asserted "
                     "nor denied (an action's condition, a choice or an "
                     "equivalence); discretise codes such a comparison only "
                     "in a guard or a Boolean output, as the positions where "
                     "it may hold");
  rel->polarity = polarity;
  auto [it, fresh] = relations.try_emplace(cmp, *rel);
  if (!fresh && it->second.polarity != polarity)
    return error(cmp->loc, "'" + exprToString(cmp) +
                               "' is read both asserted and denied");
  return true;
}

namespace {

/// Does `sum op 0` hold for every value of [lo, hi] (all), or for none?
/// Both answer "no" near the boundary, so that a position that may
/// satisfy the comparison is never excluded and one that may fail it is
/// never taken as satisfying it.
struct Verdicts {
  bool all, none;
};
Verdicts judge(BinaryOp op, double lo, double hi, double eps) {
  switch (op) {
  case BinaryOp::Lt:
  case BinaryOp::Le:
    return {hi<-eps, lo> eps};
  case BinaryOp::Gt:
  case BinaryOp::Ge:
    return {lo > eps, hi < -eps};
  case BinaryOp::Eq:
    return {false, lo > eps || hi < -eps};
  case BinaryOp::Ne:
    return {lo > eps || hi < -eps, false};
  default:
    return {false, false};
  }
}

} // namespace

Expr *Discretiser::encodeRelation(const Relation &rel, llvm::SMLoc loc) {
  // The values each position of each term's real stands for, scaled.
  struct Option {
    uint32_t place;
    double lo, hi;
  };
  size_t n = rel.terms.size();
  std::vector<std::vector<Option>> options(n);
  double scale = 1;
  for (size_t i = 0; i < n; ++i) {
    const Real &r = reals[rel.terms[i].first];
    double a = rel.terms[i].second;
    for (auto &[f, place] : r.places) {
      auto [lo, hi] = hullOf(r, valueOf(r, f, false));
      scale = std::max(
          {scale, std::fabs(r.grid.front() * a), std::fabs(r.grid.back() * a)});
      options[i].push_back(a > 0 ? Option{place, a * lo, a * hi}
                                 : Option{place, a * hi, a * lo});
    }
  }
  double eps = 1e-9 * scale;
  // What the terms from i on can add up to.
  std::vector<double> restLo(n + 1, 0), restHi(n + 1, 0);
  for (size_t i = n; i-- > 0;) {
    double lo = INFINITY, hi = -INFINITY;
    for (const Option &o : options[i]) {
      lo = std::min(lo, o.lo);
      hi = std::max(hi, o.hi);
    }
    restLo[i] = restLo[i + 1] + lo;
    restHi[i] = restHi[i + 1] + hi;
  }
  bool possible = rel.polarity > 0;
  size_t terms = 0;
  // The positions of terms i.. under which the comparison may (must) hold,
  // given that the terms before add up to [lo, hi]; null = none.
  std::function<Expr *(size_t, double, double)> build =
      [&](size_t i, double lo, double hi) -> Expr * {
    Verdicts v = judge(rel.op, lo + restLo[i], hi + restHi[i], eps);
    if (v.all)
      return b.boolLit(true, loc);
    if (v.none || (i == n && !possible))
      return nullptr;
    if (i == n)
      return b.boolLit(true, loc);
    Expr *out = nullptr;
    for (const Option &o : options[i]) {
      if (terms > kMaxRelationTerms) {
        relationTooLarge = loc; // reported by run(); stop building
        return b.boolLit(true, loc);
      }
      Expr *rest = build(i + 1, lo + o.lo, hi + o.hi);
      if (!rest)
        continue;
      ++terms;
      Expr *here = b.ref(m.places[o.place].name, loc);
      if (!llvm::isa<BoolLit>(rest))
        here = b.binary(BinaryOp::And, here, rest, loc);
      out = out ? b.binary(BinaryOp::Or, out, here, loc) : here;
    }
    return out;
  };
  Expr *out = build(0, rel.constant, rel.constant);
  return out ? out : b.boolLit(false, loc);
}
