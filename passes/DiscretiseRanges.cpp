//===- DiscretiseRanges.cpp - the ranges of reals from the model ----------===//
//
// `discretise` places its grid over each real's range. SpaceEx declares
// none: a real's range comes from the model (inferRange) — its start, the
// constants it is reset to, the invariant bounds where it moves, stable
// equilibria, how far a reset shifts it back (farthestShift) — and is left
// open past its last constant where nothing can bring it back (staysPast,
// closeOpenRanges), as timed automata abstract a clock past its largest
// constant. docs/hybrid.md, "Ranges from the model", says what each rule
// preserves.
//
//===----------------------------------------------------------------------===//
#include "passes/Discretiser.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

std::optional<VarBound> discretise::varBound(const Expr *c) {
  auto *bin = llvm::dyn_cast<BinaryExpr>(c);
  if (!bin || !(bin->op == BinaryOp::Lt || bin->op == BinaryOp::Le ||
                bin->op == BinaryOp::Gt || bin->op == BinaryOp::Ge))
    return std::nullopt;
  auto varOf = [](const Expr *e) -> std::optional<uint32_t> {
    auto *r = llvm::dyn_cast<Ref>(e);
    if (r && r->sym.kind == SymKind::Var)
      return r->sym.index;
    return std::nullopt;
  };
  std::optional<uint32_t> l = varOf(bin->lhs);
  std::optional<uint32_t> v = l ? l : varOf(bin->rhs);
  if (!v)
    return std::nullopt;
  auto k = evalConstReal(l ? bin->rhs : bin->lhs);
  if (!k)
    return std::nullopt;
  bool less = bin->op == BinaryOp::Lt || bin->op == BinaryOp::Le;
  return VarBound{*v, l ? less : !less, *k};
}

bool Discretiser::markedWhenever(uint32_t p, uint32_t q) {
  if (p == q)
    return true;
  auto [it, fresh] = markedWheneverCache.try_emplace({p, q}, false);
  if (!fresh)
    return it->second;
  const Place &pp = m.places[p], &qp = m.places[q];
  if (pp.capacity != 1 || qp.capacity != 1 || (pp.tokens && !qp.tokens))
    return false;
  for (const Transition &t : m.transitions) {
    auto takes = [&](uint32_t x) {
      for (const PreArc &a : t.pre())
        if (a.place == x)
          return a.weight == 1;
      return false;
    };
    auto gives = [&](uint32_t x) {
      for (const PostArc &a : t.post())
        if (a.place == x)
          return a.weight == 1;
      return false;
    };
    bool touchesP = takes(p) || gives(p), touchesQ = takes(q) || gives(q);
    if (!touchesP && !touchesQ)
      continue;
    if (gives(q))
      continue; // q marked after t
    if (takes(q)) {
      // q emptied: p must be emptied too.
      if (!(takes(p) && !gives(p)))
        return false;
      continue;
    }
    // q untouched: p marked after t only if it was before (then q was).
    if (gives(p) && !takes(p))
      return false;
  }
  it->second = true;
  return true;
}

void discretise::forEachReset(
    const Transition &tr, uint32_t var,
    llvm::function_ref<void(const AssignStmt *, bool)> fn) {
  if (!tr.hasAction())
    return;
  std::function<void(Block, bool)> walk = [&](Block blk, bool conditional) {
    for (Stmt *s : blk) {
      if (auto *a = llvm::dyn_cast<AssignStmt>(s)) {
        auto *target = llvm::dyn_cast<Ref>(a->target);
        if (target && target->sym.kind == SymKind::Var &&
            target->sym.index == var)
          fn(a, conditional);
      } else if (auto *i = llvm::dyn_cast<IfStmt>(s)) {
        for (const IfArm &arm : i->arms)
          walk(arm.body, true);
        walk(i->elseBody, true);
      }
    }
  };
  walk(tr.action(), false);
}

/// The values `a` resets to when it resets to a constant or to an interval
/// between constants (`between(lo, hi)`): [lo, hi]; none otherwise.
static std::optional<std::pair<double, double>>
constantReset(const AssignStmt *a) {
  auto *reset = llvm::dyn_cast<CallExpr>(a->value);
  if (reset && reset->fn == Builtin::Between) {
    auto lo = evalConstReal(reset->args[0]), hi = evalConstReal(reset->args[1]);
    if (!lo || !hi)
      return std::nullopt;
    return std::make_pair(std::min(*lo, *hi), std::max(*lo, *hi));
  }
  if (auto c = evalConstReal(a->value))
    return std::make_pair(*c, *c);
  return std::nullopt;
}

bool Discretiser::staysPast(uint32_t var, uint32_t from, int sign) {
  for (const Transition &tr : m.transitions) {
    bool other = false;
    forEachReset(tr, var, [&](const AssignStmt *a, bool) {
      other |= !constantReset(a);
    });
    if (other)
      return false; // an image of a far value may come back (x := x - 10)
  }
  std::vector<uint32_t> work{from};
  std::set<uint32_t> seen{from};
  while (!work.empty()) {
    uint32_t p = work.back();
    work.pop_back();
    for (const Flow &f : m.flows)
      if (f.place == p)
        for (const Flow::Equation &eq : f.equations)
          if (eq.varIndex == var) {
            std::optional<int> dir = constantDirection(eq);
            if (!dir || *dir * sign < 0)
              return false;
          }
    for (const Transition &tr : m.transitions) {
      if (llvm::none_of(tr.pre(),
                        [&](const PreArc &a) { return a.place == p; }))
        continue;
      bool reset = false;
      forEachReset(tr, var, [&](const AssignStmt *, bool conditional) {
        reset |= !conditional;
      });
      if (reset)
        continue; // x starts afresh at a constant
      for (const PostArc &a : tr.post())
        if (seen.insert(a.place).second)
          work.push_back(a.place);
    }
  }
  return true;
}

std::optional<double> Discretiser::farthestShift(uint32_t var, int sign) {
  const Var &v = m.vars[var];
  // Work with u = sign * x, which only rises: the lowest u each flow place
  // of x is entered with, from the initial marking and along transitions
  // (a reset's image, or the value carried from the place left).
  std::set<uint32_t> flowPlaces;
  for (const Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations)
      if (eq.varIndex == var)
        flowPlaces.insert(f.place);
  bool shifts = false;
  for (const Transition &tr : m.transitions)
    forEachReset(tr, var, [&](const AssignStmt *a, bool) {
      shifts |= !constantReset(a);
    });
  auto init = evalConstReal(v.init);
  auto initHi = v.initHi ? evalConstReal(v.initHi) : init;
  if (!shifts || !init || !initHi)
    return std::nullopt;
  std::map<uint32_t, double> lowest;
  for (uint32_t p : flowPlaces)
    if (m.places[p].tokens > 0)
      lowest[p] = std::min(sign * *init, sign * *initHi);
  auto lowestOf = [&](uint32_t p) {
    auto it = lowest.find(p);
    return it == lowest.end() ? INFINITY : it->second;
  };
  // Every round lowers some entry or ends; more rounds than places mean a
  // reset applied again and again (x := x - 10 in a loop): no bound.
  for (size_t round = 0; round <= flowPlaces.size() + 1; ++round) {
    bool changed = false;
    for (const Transition &tr : m.transitions) {
      double from = INFINITY;
      bool leaves = false, enters = false;
      for (const PreArc &a : tr.pre())
        if (flowPlaces.count(a.place)) {
          leaves = true;
          from = std::min(from, lowestOf(a.place));
        }
      for (const PostArc &a : tr.post())
        enters |= flowPlaces.count(a.place) > 0;
      // The guard's bound on x where it fires (`x >= 4` before `x := x - 4`).
      std::function<void(const Expr *)> guardBound = [&](const Expr *g) {
        auto *bin = llvm::dyn_cast_or_null<BinaryExpr>(g);
        if (bin && bin->op == BinaryOp::And) {
          guardBound(bin->lhs);
          guardBound(bin->rhs);
        } else if (std::optional<VarBound> vb = g ? varBound(g) : std::nullopt;
                   vb && vb->var == var && vb->upper == (sign < 0)) {
          from = std::max(from, sign * vb->value);
        }
      };
      if (leaves)
        guardBound(tr.guard());
      double entry = INFINITY;
      bool resets = false, always = false, unknown = false;
      forEachReset(tr, var, [&](const AssignStmt *a, bool conditional) {
        resets = true;
        always |= !conditional;
        if (auto c = constantReset(a)) {
          entry = std::min({entry, sign * c->first, sign * c->second});
          unknown |= !std::isfinite(entry); // `x' >= 0`: from anywhere
        } else if (auto ab = affineCoefficients(a->value, var);
                   ab && ab->first > 0 && leaves) {
          entry = std::min(entry, ab->first * from + sign * ab->second);
        } else {
          unknown = true; // turns x around, or reads where x is not known
        }
      });
      if (unknown || leaves != enters)
        return std::nullopt;
      std::vector<uint32_t> targets;
      if (enters) {
        if (!always)
          entry = std::min(entry, from);
        for (const PostArc &a : tr.post())
          if (flowPlaces.count(a.place))
            targets.push_back(a.place);
      } else if (resets) {
        // x stays where it is, which may be any of its places.
        targets.assign(flowPlaces.begin(), flowPlaces.end());
      }
      for (uint32_t p : targets)
        if (entry < lowestOf(p)) {
          lowest[p] = entry;
          changed = true;
        }
    }
    if (!changed) {
      double low = INFINITY;
      for (auto &[p, u] : lowest)
        low = std::min(low, u);
      if (!std::isfinite(low))
        return std::nullopt;
      return sign * low;
    }
  }
  return std::nullopt;
}

/// The range a real's model gives it where its type does not (SpaceEx
/// declares none): every value it can take lies between its initial value,
/// the constants it is reset to, and, in each place whose flow moves it,
/// the invariant's bound in the direction it moves (a constant rate) or in
/// both (any other rate). `why` says what leaves it unbounded.
bool Discretiser::inferRange(Real &r, std::string &why) {
  uint32_t var = r.var;
  double &lo = r.lo, &hi = r.hi;
  const Var &v = m.vars[var];
  // The values x starts at or is reset to span [startLo, startHi] (set
  // below, before the flows are looked at).
  double startLo = 0, startHi = 0;
  // Which way `eq` moves x, if one way: a constant rate's sign, or, for an
  // unstable affine rate (x' = a*x + b, a > 0), away from its equilibrium
  // where x starts and is reset beyond it on one side (then, if every
  // place moves x that way, x never comes back to it: exponential growth).
  auto directionOf = [&](const Flow::Equation &eq) -> std::optional<int> {
    if (std::optional<int> dir = constantDirection(eq))
      return dir;
    if (eq.rateHi)
      return std::nullopt;
    auto ab = affineCoefficients(eq.rate, var);
    if (!ab || !(ab->first > 0))
      return std::nullopt;
    double equilibrium = -ab->second / ab->first;
    if (equilibrium <= startLo)
      return +1;
    if (equilibrium >= startHi)
      return -1;
    return std::nullopt;
  };
  // Does every place that moves it move it one way?
  auto monotone = [&](int sign) {
    for (const Flow &f : m.flows)
      for (const Flow::Equation &eq : f.equations)
        if (eq.varIndex == var) {
          std::optional<int> dir = directionOf(eq);
          if (!dir || *dir * sign < 0)
            return false;
        }
    return true;
  };
  double init = 0, initHi = 0;
  if (v.init) {
    auto c = evalConstReal(v.init);
    auto h = v.initHi ? evalConstReal(v.initHi) : c;
    if (!c || !h) {
      why = "its initial value is not a constant";
      return false;
    }
    if (!std::isfinite(*c) || !std::isfinite(*h)) {
      why = "its initial set is unbounded";
      return false;
    }
    init = *c;
    initHi = *h;
  }
  double newLo = std::isfinite(lo) ? lo : init;
  double newHi = std::isfinite(hi) ? hi : initHi;
  bool needLo = !std::isfinite(lo), needHi = !std::isfinite(hi);
  auto widen = [&](double c) {
    if (needLo)
      newLo = std::min(newLo, c);
    if (needHi)
      newHi = std::max(newHi, c);
  };
  for (const Transition &tr : m.transitions)
    forEachReset(tr, var, [&](const AssignStmt *a, bool) {
      // An end left open (`y' >= 0`, between(0, inf)) does not widen:
      // the range must come from elsewhere, and the reset's values past
      // it rest at an open end or are refused at a closed one.
      if (auto c = constantReset(a))
        for (double v : {c->first, c->second})
          if (std::isfinite(v))
            widen(v);
    });
  startLo = newLo;
  startHi = newHi;
  for (const Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations) {
      if (eq.varIndex != var)
        continue;
      std::optional<int> dir = constantDirection(eq);
      if (dir && *dir == 0)
        continue;
      if (!dir)
        if (std::optional<int> away = directionOf(eq); away && monotone(*away))
          dir = away;
      bool up = !dir || *dir > 0, down = !dir || *dir < 0;
      std::optional<double> upper, lower;
      // A stable affine rate (x' = a*x + b, a < 0) moves x towards its
      // equilibrium -b/a and never past it: it bounds x both ways, as an
      // invariant would (a first-order lag: a heater towards its ambient).
      if (!dir && !eq.rateHi)
        if (auto ab = affineCoefficients(eq.rate, var); ab && ab->first < 0) {
          double equilibrium = -ab->second / ab->first;
          upper = equilibrium;
          lower = equilibrium;
        }
      for (const Invariant &inv : m.invariants) {
        if (!markedWhenever(f.place, inv.place))
          continue;
        for (const Expr *c : inv.conditions) {
          std::optional<VarBound> vb = varBound(c);
          if (!vb || vb->var != var)
            continue;
          if (vb->upper)
            upper = upper ? std::min(*upper, vb->value) : vb->value;
          else
            lower = lower ? std::max(*lower, vb->value) : vb->value;
        }
      }
      // Past its last constant nothing tells x's values apart, as long as
      // nothing brings it back: everywhere it moves it moves one way, or
      // the place moving it leads only to places that do (a final
      // location: how far x went there matters to nobody).
      if (up && needHi && !upper &&
          (monotone(+1) || (dir && staysPast(var, f.place, +1)))) {
        r.openTop = true;
        continue;
      }
      if (down && needLo && !lower &&
          (monotone(-1) || (dir && staysPast(var, f.place, -1)))) {
        r.openBottom = true;
        continue;
      }
      if ((up && needHi && !upper) || (down && needLo && !lower)) {
        bool rising = up && needHi && !upper;
        why = "place '" + f.placeName.str() + "' moves it " +
              (rising ? "up" : "down") + " and its invariant gives no " +
              (rising ? "upper" : "lower") + " bound, and it does not only " +
              (rising ? "rise" : "fall") +
              " there and in every place it can go on to, at constant "
              "rates or away from an unstable equilibrium it starts beyond "
              "(then its guards would bound it), nor follow x' = a*x + b "
              "with a < 0 there (then its equilibrium would)";
        return false;
      }
      if (up && needHi)
        newHi = std::max(newHi, *upper);
      if (down && needLo)
        newLo = std::min(newLo, *lower);
    }
  // A real that only rises may still be shifted down by a reset (y := y -
  // 10): its range reaches as low as the images of the values it can have
  // where the reset takes it from.
  if ((r.openTop && needLo) || (r.openBottom && needHi)) {
    int sign = r.openTop ? +1 : -1;
    if (std::optional<double> far = farthestShift(var, sign))
      (sign > 0 ? newLo : newHi) =
          sign > 0 ? std::min(newLo, *far) : std::max(newHi, *far);
  }
  // A real nothing moves or resets keeps its initial value: any range
  // around it serves (the grid's other point is never reached).
  if (!(newLo < newHi) && !r.openTop && !r.openBottom) {
    if (needHi)
      newHi = newLo + 1;
    else
      newLo = newHi - 1;
  }
  lo = newLo;
  hi = newHi;
  return true;
}

void Discretiser::closeOpenRanges() {
  // One direction at most: a real open both ways would move both ways,
  // which inferRange refuses.
  for (Real &r : reals) {
    if (!r.openTop && !r.openBottom)
      continue;
    // The closed end's bound too: places that move x back bound it there.
    std::vector<double> known{r.init, r.initHi, r.lo, r.hi};
    known.insert(known.end(), r.thresholds.begin(), r.thresholds.end());
    known.insert(known.end(), r.assigned.begin(), r.assigned.end());
    double last = *std::max_element(known.begin(), known.end());
    double first = *std::min_element(known.begin(), known.end());
    double step =
        (last - first) / (spec.mode == GridSpec::Mode::Count ? spec.count : 1);
    if (!(step > 0))
      step = 1;
    if (r.openTop)
      r.hi = last + step;
    else
      r.lo = first - step;
    diag.note(m.vars[r.var].loc,
              "real '" + r.name + "' " + (r.openTop ? "rises" : "falls") +
                  " without bound; past " + num(r.openTop ? last : first) +
                  ", the last value it is compared with, set to or starts "
                  "at, nothing tells its values apart: its range ends at " +
                  num(r.openTop ? r.hi : r.lo) + ", where it rests");
  }
}
