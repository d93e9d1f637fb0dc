//===- DiscretiseDisturbances.cpp - free reals become rate intervals ------===//
//
// SpaceEx lets a variable that no location gives a flow change freely: an
// input or a disturbance, bounded by invariants (`1 <= u <= 2`) and read in
// the flows of other variables (`y' == 1 + u`). The SpaceEx reader writes
// it as a real whose rate is `[-inf, inf]` (docs/hybrid.md). Such a real
// has no position to discretise, but where a rate reads it only through a
// constant-coefficient sum, the rate spans an interval over the bounds the
// invariants give it, which is a rectangular flow (`y' in [2, 3]`): every
// trajectory of the hybrid model is one of the rectangular flow's, so the
// rewrite over-approximates, and exactly covers what the disturbance can do
// in one place. The disturbance and the invariant conditions that bound it
// are then removed. A free real read anywhere else (a guard, an action, a
// rate that also reads its own variable) stays, and is refused as before.
//
//===----------------------------------------------------------------------===//
#include "passes/Discretiser.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

namespace {

/// A free real: every flow of it is `[-inf, inf]`.
bool changesFreely(const Module &m, uint32_t var) {
  bool any = false;
  for (const Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations) {
      if (eq.varIndex != var)
        continue;
      auto lo = evalConstReal(eq.rate);
      auto hi = eq.rateHi ? evalConstReal(eq.rateHi) : lo;
      if (!lo || !hi || std::isfinite(*lo) || std::isfinite(*hi))
        return false;
      any = true;
    }
  return any;
}

/// `e` is a disturbance or a constant: its index or its value.
struct Operand {
  std::optional<uint32_t> var;
  double value = 0;
};
std::optional<Operand> operandOf(const Expr *e,
                                 const std::set<uint32_t> &candidates) {
  if (auto *r = llvm::dyn_cast<Ref>(e))
    if (r->sym.kind == SymKind::Var && r->fields.empty() &&
        candidates.count(r->sym.index))
      return Operand{r->sym.index, 0};
  if (auto c = evalConstReal(e))
    return Operand{std::nullopt, *c};
  return std::nullopt;
}

/// Narrows `box` by one invariant condition `a op b` over disturbances and
/// constants; false if the condition has another form.
bool narrow(const Expr *c, const std::set<uint32_t> &candidates, Box &box) {
  auto *bin = llvm::dyn_cast<BinaryExpr>(c);
  if (!bin || bin->op < BinaryOp::Eq || bin->op > BinaryOp::Ge ||
      bin->op == BinaryOp::Ne)
    return false;
  auto l = operandOf(bin->lhs, candidates), r = operandOf(bin->rhs, candidates);
  if (!l || !r || (!l->var && !r->var))
    return false;
  auto range = [&](const Operand &o) {
    return o.var ? box[*o.var] : std::make_pair(o.value, o.value);
  };
  // l <= r (or l >= r, swapped): l's top is at most r's top, r's bottom at
  // least l's bottom; == both ways.
  auto lessEq = [&](const Operand &a, const Operand &b) {
    auto ra = range(a), rb = range(b);
    if (a.var)
      box[*a.var].second = std::min(ra.second, rb.second);
    if (b.var)
      box[*b.var].first = std::max(rb.first, ra.first);
  };
  switch (bin->op) {
  case BinaryOp::Lt:
  case BinaryOp::Le:
    lessEq(*l, *r);
    break;
  case BinaryOp::Gt:
  case BinaryOp::Ge:
    lessEq(*r, *l);
    break;
  default: // Eq
    lessEq(*l, *r);
    lessEq(*r, *l);
    break;
  }
  return true;
}

} // namespace

RateSpan discretise::spanOverBox(const Flow::Equation &eq, const Box &box,
                                 llvm::ArrayRef<uint32_t> vary) {
  // The rate must read the box's reals and constants only, through a sum
  // with constant coefficients: its extremes are at the box's corners,
  // found coordinate by coordinate.
  RateSpan span;
  std::map<uint32_t, double> at;
  for (auto &[v, range] : box)
    at[v] = std::isfinite(range.first) ? range.first : 0;
  RealEval ev(eq.varIndex);
  ev.others = &at;
  auto base = ev.eval(eq.rate, 0);
  if (!base || ev.readsVar) {
    span.coupled = true;
    return span;
  }
  double lo = *base, hi = *base, sum = 0;
  for (uint32_t v : vary) {
    auto range = box.at(v);
    // Along v alone, the others at their low ends (v itself too).
    std::map<uint32_t, double> alone;
    for (auto &[w, wr] : box)
      alone[w] = std::isfinite(wr.first) ? wr.first : 0;
    ev.others = &alone;
    alone[v] = range.second;
    auto top = ev.eval(eq.rate, 0);
    alone[v] = (range.first + range.second) / 2;
    auto mid = ev.eval(eq.rate, 0);
    ev.others = &at;
    if (!top || !mid ||
        std::fabs((*base + *top) / 2 - *mid) >
            1e-9 * std::max({std::fabs(*mid), 1.0})) {
      span.notLinearIn = v;
      return span;
    }
    double delta = *top - *base;
    (delta > 0 ? hi : lo) += delta;
    sum += delta;
    at[v] = range.second;
  }
  // A product of two of them is not a sum: the far corner shows it.
  auto corner = ev.eval(eq.rate, 0);
  if (!corner || std::fabs(*corner - (*base + sum)) >
                     1e-9 * std::max({std::fabs(*corner), 1.0}))
    return span;
  span.ok = true;
  span.lo = lo;
  span.hi = hi;
  return span;
}

bool Discretiser::eliminateDisturbances() {
  std::set<uint32_t> candidates;
  for (uint32_t i = 0; i < m.vars.size(); ++i)
    if (m.vars[i].type->isReal() && changesFreely(m, i))
      candidates.insert(i);
  if (candidates.empty())
    return true;
  llvm::DenseMap<uint32_t, size_t> candidateMap;
  for (uint32_t v : candidates)
    candidateMap[v] = 0;
  // Read only in rates and in invariants that bound them, and written
  // only at the top of actions: anything else keeps the variable (and its
  // refusal as a free real).
  auto readElsewhere = [&](const Expr *e) {
    const Expr *where = nullptr;
    return mentionsReal(e, candidateMap, where);
  };
  for (const Port &p : m.ports)
    if (readElsewhere(p.definition))
      return true;
  for (const Var &v : m.vars)
    if (readElsewhere(v.init) || readElsewhere(v.initHi))
      return true;
  for (const Transition &t : m.transitions) {
    for (const Expr *c : t.conds())
      if (readElsewhere(c))
        return true;
    if (readElsewhere(t.guard()))
      return true;
    if (!t.hasAction())
      continue;
    for (const Stmt *s : t.action()) {
      // SpaceEx resets are flat assignments; a compound statement may read
      // one anywhere inside: left to the checks.
      auto *a = llvm::dyn_cast<AssignStmt>(s);
      if (!a || readElsewhere(a->value) ||
          (!llvm::isa<Ref>(a->target) && readElsewhere(a->target)))
        return true;
    }
  }
  // Bounds where each place's rates read them: the invariants of the places
  // marked whenever that place is.
  auto boxAt = [&](uint32_t place, Box &box) {
    for (uint32_t v : candidates)
      box[v] = {-INFINITY, INFINITY};
    for (int round = 0; round < 4; ++round)
      for (const Invariant &inv : m.invariants)
        if (markedWhenever(place, inv.place))
          for (const Expr *c : inv.conditions)
            if (readElsewhere(c))
              narrow(c, candidates, box);
  };
  Box scratch;
  for (const Invariant &inv : m.invariants)
    for (const Expr *c : inv.conditions)
      if (readElsewhere(c) && !narrow(c, candidates, scratch))
        return true; // an invariant of another form: left to the checks
  std::map<uint32_t, std::string> unenterable;
  // A place whose invariants leave a disturbance no value is never entered
  // (checked for every place such an invariant bounds, read or not).
  for (const Invariant &inv : m.invariants)
    for (const Expr *c : inv.conditions)
      if (readElsewhere(c)) {
        Box box;
        boxAt(inv.place, box);
        for (auto &[v, range] : box)
          if (range.first > range.second)
            unenterable.insert({inv.place, m.vars[v].name.str()});
        break;
      }
  std::vector<Flow::Equation *> rewritten;
  std::vector<std::pair<double, double>> spans;
  for (Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations) {
      if (candidates.count(eq.varIndex) || eq.rateHi || !readElsewhere(eq.rate))
        continue;
      Box box;
      boxAt(f.place, box);
      if (spanOverBox(eq, box, {}).coupled)
        return true; // coupled with its own or another real: refused later
      std::vector<uint32_t> vary;
      for (auto &[v, range] : box) {
        const Expr *where = nullptr;
        llvm::DenseMap<uint32_t, size_t> one{{v, 0}};
        if (!mentionsReal(eq.rate, one, where))
          continue;
        if (!std::isfinite(range.first) || !std::isfinite(range.second))
          return error(eq.loc,
                       "'" + m.vars[v].name.str() +
                           "' changes freely and the rate of '" + eq.var +
                           "' in place '" + f.placeName +
                           "' reads it, but no invariant marked with that "
                           "place bounds it both ways; discretise needs the "
                           "rate's bounds");
        if (range.first > range.second) {
          // The hybrid model can never enter the place: its invariant
          // cannot hold.
          unenterable.insert({f.place, m.vars[v].name.str()});
          continue;
        }
        vary.push_back(v);
      }
      RateSpan span = spanOverBox(eq, box, vary);
      if (span.coupled)
        return true; // coupled with its own or another real: refused later
      if (!span.ok)
        return error(eq.loc,
                     "the rate of '" + eq.var + "' in place '" + f.placeName +
                         (span.notLinearIn
                              ? "' reads '" +
                                    m.vars[*span.notLinearIn].name.str() +
                                    "', which changes freely, other than "
                                    "through a sum with a constant "
                                    "coefficient; discretise needs the "
                                    "rate's bounds"
                              : "' combines variables that change freely "
                                "other than in a sum; discretise needs the "
                                "rate's bounds"));
      rewritten.push_back(const_cast<Flow::Equation *>(&eq));
      spans.push_back({span.lo, span.hi});
    }
  for (auto &[place, var] : unenterable) {
    if (m.places[place].tokens)
      return error(m.places[place].loc,
                   "the invariants of the initial place '" +
                       m.places[place].name + "' bound '" + var +
                       "' to an empty range: the model has no initial state");
    diag.warning(m.places[place].loc,
                 "the invariants of place '" + m.places[place].name +
                     "' bound '" + var +
                     "' to an empty range: the model never enters it, and "
                     "the transitions into it never fire");
    for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
      const Transition &t = m.transitions[ti];
      bool into = false, from = false;
      for (const PostArc &a : t.post())
        into |= a.place == place;
      for (const PreArc &a : t.pre())
        from |= a.place == place;
      if (into && !from)
        b.setGuard(ti, b.boolLit(false, t.loc));
    }
  }
  // Rewrite: each rate its span, then the disturbances go.
  for (size_t i = 0; i < rewritten.size(); ++i) {
    Flow::Equation &eq = *rewritten[i];
    auto [lo, hi] = spans[i];
    diag.note(eq.loc, "the rate of '" + eq.var.str() +
                          "' reads variables that change freely within "
                          "their invariants' bounds: it is taken as the "
                          "interval [" +
                          num(lo) + ", " + num(hi) + "] (a rectangular flow)");
    eq.rate = b.realLit(lo, eq.loc);
    eq.rateHi = lo == hi ? nullptr : b.realLit(hi, eq.loc);
  }
  for (uint32_t v : candidates)
    diag.note(m.vars[v].loc, "real '" + m.vars[v].name.str() +
                                 "' changes freely and is read only by "
                                 "rates, which now span its bounds: it is "
                                 "removed");
  for (Invariant &inv : m.invariants) {
    std::vector<Expr *> kept;
    for (Expr *c : inv.conditions)
      if (!readElsewhere(c))
        kept.push_back(c);
    inv.conditions = d.copy(llvm::ArrayRef<Expr *>(kept));
  }
  removeReals(candidates);
  return true;
}

void Discretiser::spanUncertainConstants() {
  Box box;
  for (uint32_t i = 0; i < m.vars.size(); ++i) {
    const Var &v = m.vars[i];
    if (!v.type->isReal() || !v.initHi)
      continue;
    auto lo = evalConstReal(v.init), hi = evalConstReal(v.initHi);
    if (!lo || !hi || !std::isfinite(*lo) || !std::isfinite(*hi) ||
        !(*lo < *hi))
      continue;
    bool moves = false;
    for (const Flow &f : m.flows)
      for (const Flow::Equation &eq : f.equations)
        if (eq.varIndex == i) {
          auto rate = evalConstReal(eq.rate);
          moves |= !rate || *rate != 0 || eq.rateHi;
        }
    for (const Transition &t : m.transitions)
      forEachReset(t, i, [&](const AssignStmt *, bool) { moves = true; });
    if (!moves)
      box[i] = {*lo, *hi};
  }
  if (box.empty())
    return;
  llvm::DenseMap<uint32_t, size_t> constants;
  for (auto &[v, range] : box)
    constants[v] = 0;
  for (Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations) {
      const Expr *where = nullptr;
      if (box.count(eq.varIndex) || eq.rateHi ||
          !mentionsReal(eq.rate, constants, where))
        continue;
      std::vector<uint32_t> vary;
      std::string names;
      for (auto &[v, range] : box) {
        llvm::DenseMap<uint32_t, size_t> one{{v, 0}};
        if (mentionsReal(eq.rate, one, where)) {
          vary.push_back(v);
          names += (names.empty() ? "'" : ", '") + m.vars[v].name.str() +
                   "' in [" + num(range.first) + ", " + num(range.second) + "]";
        }
      }
      // A rate also reading a moving real, or not through a sum, is left
      // to the coupled-flow check, which names what it reads.
      RateSpan span = spanOverBox(eq, box, vary);
      if (!span.ok)
        continue;
      diag.note(eq.loc,
                "the rate of '" + eq.var.str() + "' in place '" + f.placeName +
                    "' reads " + names +
                    ", fixed for a run somewhere in the range the initial "
                    "set gives: it is taken as the rectangular flow [" +
                    num(span.lo) + ", " + num(span.hi) +
                    "], which lets the rate vary within it at any instant "
                    "(an over-approximation)");
      // The equations live in the design's arena, as the rewrite of
      // disturbances above changes them.
      auto &rewrite = const_cast<Flow::Equation &>(eq);
      rewrite.rate = b.realLit(span.lo, eq.loc);
      rewrite.rateHi =
          span.lo == span.hi ? nullptr : b.realLit(span.hi, eq.loc);
    }
}
