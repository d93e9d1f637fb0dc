//===- Discretise.cpp - hybrid flows to timed place chains ----------------===//
//
// `discretise` removes every real variable and flow (design §3.1, "hybrid
// variables") by the method of the closed-loop modelling paper (section
// VI): for a grid of values of each real variable x, the times at which the
// flow of each place brings x from one grid point to the next are computed
// (ir/hybrid/FlowSolver), and the hybrid automaton becomes a timed
// automaton whose chain of states is coded as places joined by urgent
// transitions with the segment's duration as the `[d,d]` interval on the
// arc, so that the token moves exactly at the grid time.
//
// The position of x is one token in a set of *position places*:
//   x_at{k}           x equals grid point g_k, no flow acting on it;
//   x_in{k}           x strictly between g_{k-1} and g_k, no flow;
//   P_x_up{k}         place P's flow moves x up through segment k, entered
//                     exactly at g_{k-1} (the place clock is the time since);
//   P_x_down{k}       the same downwards, entered at g_k;
//   P_x_up{k}_mid     ... entered from an unknown point inside the segment:
//   P_x_down{k}_mid   it reaches the next grid point within the duration;
//   P_x_rest{k}       P is marked but x rests at g_k (the range's end, or
//                     the rate is zero there);
//   P_x_rest_in{k}    ... rests inside segment k (an attractor inside it).
// A place with a flow stays a place; transitions that enter or leave a flow
// place of x, or assign `x := c`, move the position token in the same step
// by forced transitions (`on t`); guards and sensors comparing x with a
// constant become conditions on the position places where they hold (a
// moving token counts as strictly inside its segment). An urgent transition
// whose only enabling condition is such a guard is fused with the arrival
// that makes it true, which is the paper's chain S_i = s_0 -> ... -> s_N =
// S_{i+1} exactly.
//
// Preserved: the behaviour of the hybrid model at the grid (every grid
// crossing happens at its rounded grid time; location changes and sensor
// values as in the hybrid model with each sensor switching in the step at
// the crossing); positions between grid points are abstracted to segments,
// and a segment entered from inside is left nondeterministically within its
// full duration. Requires that the flow places of one variable are never
// marked together (checked) and that rates depend only on the variable
// itself (one-dimensional autonomous flows). docs/hybrid.md has the details.
//
//===----------------------------------------------------------------------===//
#include "passes/Discretiser.h"

#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

//===----------------------------------------------------------------------===//
// Collecting what is hybrid
//===----------------------------------------------------------------------===//

std::optional<std::pair<double, double>>
discretise::affineCoefficients(const Expr *rate, uint32_t var,
                               llvm::ArrayRef<double> alsoAt) {
  RealEval ev(var);
  auto f0 = ev.eval(rate, 0), f1 = ev.eval(rate, 1);
  if (!f0 || !f1)
    return std::nullopt;
  double a = *f1 - *f0, b = *f0;
  std::vector<double> points{-7.25, 13.5, 1e3, -1e3};
  points.insert(points.end(), alsoAt.begin(), alsoAt.end());
  for (double x : points) {
    auto got = ev.eval(rate, x);
    if (!got || !std::isfinite(x))
      continue;
    double want = a * x + b;
    if (std::fabs(want - *got) >
        1e-12 * std::max({std::fabs(want), std::fabs(*got), 1.0}))
      return std::nullopt;
  }
  return std::make_pair(a, b);
}

std::optional<int> discretise::constantDirection(const Flow::Equation &eq) {
  auto lo = evalConstReal(eq.rate);
  auto hi = eq.rateHi ? evalConstReal(eq.rateHi) : lo;
  if (!lo || !hi)
    return std::nullopt;
  if (*lo > 0 && *hi > 0)
    return +1;
  if (*lo < 0 && *hi < 0)
    return -1;
  if (*lo == 0 && *hi == 0)
    return 0;
  return std::nullopt; // a rectangular flow whose rates include 0
}

bool Discretiser::checkRectangularFlows() {
  for (const Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations) {
      if (!eq.rateHi)
        continue;
      StringRef place = m.places[f.place].name;
      auto lo = evalConstReal(eq.rate), hi = evalConstReal(eq.rateHi);
      if (!lo || !hi)
        return error((lo ? eq.rateHi : eq.rate)->loc,
                     "the rates of '" + eq.var + "' in place '" + place +
                         "' are bounded by something that is not a "
                         "constant; discretise takes rectangular flows x' "
                         "in [a, b] with constant a and b");
      if (spec.mode == GridSpec::Mode::Step)
        return error(eq.loc, "step= places grid points where a flow is "
                             "after each step, which a rectangular flow ('" +
                                 eq.var + "' in place '" + place +
                                 "') does not fix; use grid= or points=");
      // A rate bounded on one side only (SpaceEx's `x' >= 1`): any rate
      // from 1 up, a segment crossed in any time up to its distance / 1.
      bool oneSided = std::isfinite(*lo) != std::isfinite(*hi);
      if (oneSided && (std::isfinite(*lo) ? *lo > 0 : *hi < 0))
        continue;
      if (!std::isfinite(*lo) && !std::isfinite(*hi))
        return error(eq.loc,
                     "'" + eq.var + "' changes freely in place '" + place +
                         "' (its rates are [" + num(*lo) + ", " + num(*hi) +
                         "]: SpaceEx gives it no flow there, an input or a "
                         "disturbance); discretise needs rates that are "
                         "bounded");
      if (*lo <= 0 && *hi >= 0 && !(*lo == 0 && *hi == 0))
        return error(eq.loc,
                     "the rates of '" + eq.var + "' in place '" + place +
                         "' range over [" + num(*lo) + ", " + num(*hi) +
                         "], which contains 0: it may stop or turn back "
                         "anywhere, which a grid of timed segments cannot "
                         "follow (discretise takes 0 < a <= b or a <= b < 0)");
    }
  return true;
}

bool Discretiser::checkOneDimensional() {
  for (const Flow &f : m.flows)
    for (const Flow::Equation &eq : f.equations) {
      if (eq.rateHi)
        continue; // rectangular: constant bounds, checked with them
      RealEval ev(eq.varIndex);
      auto *other =
          ev.eval(eq.rate, 0) ? nullptr : llvm::dyn_cast_or_null<Ref>(ev.bad);
      if (other && other->sym.kind == SymKind::Var)
        return error(other->loc.isValid() ? other->loc : eq.loc,
                     "the rate of '" + eq.var + "' in place '" + f.placeName +
                         "' reads '" + other->name +
                         "': a coupled flow (x' = f(x, y)), which discretise "
                         "does not take; it needs x' = f(x) "
                         "(one-dimensional autonomous flows)");
    }
  return true;
}

bool Discretiser::collectReals() {
  for (uint32_t i = 0; i < m.vars.size(); ++i) {
    const Var &v = m.vars[i];
    if (!v.type->isReal() || unfollowed.count(i))
      continue;
    Real r;
    r.var = i;
    r.name = v.name.str();
    r.shortName = v.name.rsplit('.').second.empty()
                      ? v.name.str()
                      : v.name.rsplit('.').second.str();
    r.lo = v.type->realLo;
    r.hi = v.type->realHi;
    if (v.initHi)
      for (const Expr *e : {v.init, v.initHi})
        if (auto c = evalConstReal(e); c && !std::isfinite(*c))
          return error(v.loc, "real '" + v.name +
                                  "' may start at any value (its initial set "
                                  "does not bound it); discretise needs a "
                                  "bounded start (bound it in the initial "
                                  "set)");
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi)) {
      std::string why;
      if (!inferRange(r, why))
        return error(v.loc, "real '" + v.name +
                                "' has an unbounded range, and the model "
                                "does not bound it: " +
                                why +
                                "; discretise needs finite bounds to place "
                                "its grid (give a range: --range "
                                "NAME=LO..HI for a SpaceEx model, `real "
                                "NAME : [LO, HI]` in NetIR)");
    }
    if (!(r.lo < r.hi) && !r.openTop && !r.openBottom)
      return error(v.loc, "real '" + v.name + "' has an empty range");
    r.init = r.lo;
    if (v.init) {
      auto c = evalConstReal(v.init);
      if (!c)
        return error(v.init->loc, "the initial value of real '" + v.name +
                                      "' is not a constant");
      r.init = *c;
    }
    r.initHi = r.init;
    if (v.initHi)
      r.initHi = *evalConstReal(v.initHi); // the verifier checked it
    realOfVar[i] = reals.size();
    reals.push_back(std::move(r));
  }
  for (const Flow &f : m.flows) {
    for (const Flow::Equation &eq : f.equations) {
      auto it = realOfVar.find(eq.varIndex);
      Real &r = reals[it->second];
      if (r.flowOfPlace.count(f.place))
        continue; // the verifier reports duplicates
      FlowOf fl;
      fl.place = f.place;
      fl.eq = &eq;
      r.flowOfPlace[f.place] = r.flows.size();
      r.flows.push_back(std::move(fl));
    }
  }
  // A place may move several reals: each has its own position places, whose
  // clocks measure its own progress (its rate reads only itself, checked
  // with the rates).
  return true;
}

/// Checks a Boolean expression (guard, condition, definition): real
/// variables may only be compared with constants (records the thresholds)
/// or related by a linear comparison where it is asserted or denied.
bool Discretiser::scanExpr(Expr *e, int polarity) {
  if (!e)
    return true;
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    if (r->sym.kind == SymKind::Var && realOfVar.count(r->sym.index))
      return error(r->loc, "real '" + r->name +
                               "' is used here other than compared with a "
                               "constant or in a linear comparison; "
                               "discretise can only replace comparisons");
    return true;
  }
  case ExprKind::Binary: {
    auto *bin = llvm::cast<BinaryExpr>(e);
    bool cmp = bin->op >= BinaryOp::Eq && bin->op <= BinaryOp::Ge;
    auto realSide = [&](Expr *x) -> Real * {
      auto *r = llvm::dyn_cast<Ref>(x);
      if (r && r->sym.kind == SymKind::Var && realOfVar.count(r->sym.index))
        return &reals[realOfVar[r->sym.index]];
      return nullptr;
    };
    if (cmp) {
      Real *l = realSide(bin->lhs), *rr = realSide(bin->rhs);
      Real *x = l ? l : rr;
      Expr *other = l ? bin->rhs : bin->lhs;
      if (x && evalConstReal(other)) {
        x->thresholds.insert(*evalConstReal(other));
        return true;
      }
      bool isRelation = false;
      if (!scanRelation(bin, polarity, isRelation))
        return false;
      if (isRelation)
        return true;
      if (x)
        return error(other->loc, "real '" + x->name +
                                     "' is compared with something that "
                                     "is neither a constant nor a linear "
                                     "sum of reals; discretise needs `x op "
                                     "constant` or `a*x + b*y op constant`");
    }
    bool keeps = bin->op == BinaryOp::And || bin->op == BinaryOp::Or;
    return scanExpr(bin->lhs, keeps ? polarity : 0) &&
           scanExpr(bin->rhs, keeps ? polarity : 0);
  }
  case ExprKind::Unary: {
    auto *u = llvm::cast<UnaryExpr>(e);
    return scanExpr(u->operand, u->op == UnaryOp::Not ? -polarity : 0);
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    return scanExpr(c->cond) && scanExpr(c->thenExpr, polarity) &&
           scanExpr(c->elseExpr, polarity);
  }
  case ExprKind::Call: {
    for (Expr *a : llvm::cast<CallExpr>(e)->args)
      if (!scanExpr(a))
        return false;
    return true;
  }
  case ExprKind::Index: {
    auto *x = llvm::cast<IndexExpr>(e);
    return scanExpr(x->base) && scanExpr(x->index);
  }
  case ExprKind::Field:
    return scanExpr(llvm::cast<FieldExpr>(e)->base);
  default:
    return true;
  }
}

/// Statements of an action: `x := constant` at the top level is a reset
/// of the position; any other write or read of a real is refused.
bool Discretiser::collectAssignments() {
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    Transition &t = m.transitions[ti];
    if (!t.hasAction())
      continue;
    context = t.loc;
    // What the reals this action has set so far hold, as sums of the
    // values before the step (statements run in order, and a later reset
    // reading one reads the new value, where the position tokens stand for
    // the old ones): nullopt where it is not such a sum (an interval).
    std::map<uint32_t, std::optional<LinearSum>> settled;
    auto record = [&](uint32_t ti, uint32_t var, const LinearSum &sum) {
      size_t ri = realOfVar[var];
      TransferReset tx;
      for (auto &[v, k] : sum.coef) {
        if (v == var)
          tx.a = k;
        else
          tx.terms.push_back({realOfVar[v], k});
      }
      tx.c = sum.constant;
      if (!tx.terms.empty())
        transferResets[{ti, ri}] = tx;
      else if (tx.a != 0)
        affineResets[{ti, ri}] = {tx.a, tx.c};
      else {
        reals[ri].assigned.insert(tx.c);
        assigns[{ti, ri}] = {tx.c, tx.c};
      }
    };
    std::function<bool(Block, bool)> walk = [&](Block blk, bool top) -> bool {
      for (Stmt *s : blk) {
        if (auto *a = llvm::dyn_cast<AssignStmt>(s)) {
          auto *tr = llvm::dyn_cast<Ref>(a->target);
          bool toReal = tr && tr->sym.kind == SymKind::Var &&
                        realOfVar.count(tr->sym.index);
          // A reset reading reals set earlier in the action reads what
          // they were set to.
          const Ref *late = nullptr;
          walkExpr(a->value, [&](const Expr *e) {
            if (auto *r = llvm::dyn_cast<Ref>(e); r && !late &&
                                                  r->sym.kind == SymKind::Var &&
                                                  settled.count(r->sym.index))
              late = r;
          });
          if (late) {
            std::optional<LinearSum> sum = linearSum(a->value, m);
            auto lateError = [&] {
              return error(late->loc.isValid() ? late->loc : a->loc,
                           "this reset reads real '" + late->name +
                               "' after the same action has set it to " +
                               "something discretise cannot follow (an "
                               "interval, or in a condition); reset it "
                               "after reading it");
            };
            if (!toReal || !top || !tr->fields.empty() || !sum)
              return lateError();
            LinearSum before = *sum;
            before.coef.clear();
            before.refOf.clear();
            for (auto &[v, k] : sum->coef) {
              auto it = settled.find(v);
              if (it == settled.end()) {
                LinearSum one;
                one.coef[v] = 1;
                one.refOf[v] = sum->refOf[v];
                before.add(one, k);
              } else if (!it->second) {
                return lateError();
              } else {
                before.add(*it->second, k);
              }
            }
            before.dropZeros();
            for (auto &[v, k] : before.coef)
              if (!realOfVar.count(v))
                return lateError();
            record(ti, tr->sym.index, before);
            settled[tr->sym.index] = before;
            continue;
          }
          // `x := x` (SpaceEx tools write one per unchanged variable)
          // leaves the position where it is; it is dropped with the
          // other resets of reals.
          auto *same = llvm::dyn_cast<Ref>(a->value);
          if (toReal && top && same && same->sym == tr->sym &&
              same->fields.empty() && tr->fields.empty())
            continue;
          // `x := c`, `x := a*x + b` (SpaceEx's `x' == 3*x`, `y' == y -
          // 10`: the new position is the image of the old one's value or
          // segment) and `x := a*x + b*y + c` reading other reals (a
          // transfer).
          if (toReal && top && tr->fields.empty())
            if (std::optional<LinearSum> sum = linearSum(a->value, m);
                sum && llvm::all_of(sum->coef, [&](auto &vk) {
                  return realOfVar.count(vk.first) != 0;
                })) {
              sum->dropZeros();
              record(ti, tr->sym.index, *sum);
              settled[tr->sym.index] = *sum;
              continue;
            }
          if (toReal)
            settled[tr->sym.index] = std::nullopt;
          const Expr *where = nullptr;
          if (mentionsReal(a->value, realOfVar, where))
            return error(where->loc.isValid() ? where->loc : t.loc,
                         "an action reads a real variable; after discretise "
                         "reals exist only as position places, which actions "
                         "can only reset (`x := constant`, `x := a*x + b`, "
                         "`x := a*x + b*y + c`); test thresholds in the guard "
                         "instead");
          if (!toReal)
            continue;
          size_t ri = realOfVar[tr->sym.index];
          if (!top)
            return error(a->loc, "a conditional assignment to real '" +
                                     tr->name +
                                     "' is not supported by discretise "
                                     "(write it at the top of the action)");
          // `x := c`, or `x := between(a, b)`: any value from a to b.
          auto *reset = llvm::dyn_cast<CallExpr>(a->value);
          bool interval = reset && reset->fn == Builtin::Between;
          auto c = evalConstReal(interval ? reset->args[0] : a->value);
          auto h = interval ? evalConstReal(reset->args[1]) : c;
          if (!c || !h)
            return error(a->value->loc, "real '" + tr->name +
                                            "' is assigned something that is "
                                            "not a constant" +
                                            (interval ? " interval" : ""));
          for (double v : {*c, *h})
            if (std::isfinite(v)) // `y' >= 0`: between(0, inf)
              reals[ri].assigned.insert(v);
          assigns[{ti, ri}] = {*c, *h};
          continue;
        }
        if (auto *i = llvm::dyn_cast<IfStmt>(s)) {
          for (const IfArm &arm : i->arms)
            if (!scanExpr(arm.cond) || !walk(arm.body, false))
              return false;
          if (!walk(i->elseBody, false))
            return false;
        } else if (auto *c = llvm::dyn_cast<CaseStmt>(s)) {
          const Expr *where = nullptr;
          if (mentionsReal(c->selector, realOfVar, where))
            return error(where->loc, "a case selector reads a real variable");
          for (const CaseArm &arm : c->arms)
            if (!walk(arm.body, false))
              return false;
          if (!walk(c->elseBody, false))
            return false;
        } else if (auto *f = llvm::dyn_cast<ForStmt>(s)) {
          if (!walk(f->body, false))
            return false;
        } else if (auto *w = llvm::dyn_cast<WhileStmt>(s)) {
          const Expr *where = nullptr;
          if (mentionsReal(w->cond, realOfVar, where))
            return error(where->loc, "a loop condition reads a real variable");
          if (!walk(w->body, false))
            return false;
        }
      }
      return true;
    };
    if (!walk(t.action(), true))
      return false;
  }
  return true;
}

bool discretise::mentionsReal(const Expr *e,
                              const llvm::DenseMap<uint32_t, size_t> &realOfVar,
                              const Expr *&where) {
  if (!e)
    return false;
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    if (r->sym.kind == SymKind::Var && realOfVar.count(r->sym.index)) {
      where = e;
      return true;
    }
    return false;
  }
  case ExprKind::Unary:
    return mentionsReal(llvm::cast<UnaryExpr>(e)->operand, realOfVar, where);
  case ExprKind::Binary: {
    auto *b = llvm::cast<BinaryExpr>(e);
    return mentionsReal(b->lhs, realOfVar, where) ||
           mentionsReal(b->rhs, realOfVar, where);
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    return mentionsReal(c->cond, realOfVar, where) ||
           mentionsReal(c->thenExpr, realOfVar, where) ||
           mentionsReal(c->elseExpr, realOfVar, where);
  }
  case ExprKind::Call:
    for (const Expr *a : llvm::cast<CallExpr>(e)->args)
      if (mentionsReal(a, realOfVar, where))
        return true;
    return false;
  case ExprKind::Index: {
    auto *x = llvm::cast<IndexExpr>(e);
    return mentionsReal(x->base, realOfVar, where) ||
           mentionsReal(x->index, realOfVar, where);
  }
  case ExprKind::Field:
    return mentionsReal(llvm::cast<FieldExpr>(e)->base, realOfVar, where);
  default:
    return false;
  }
}

bool Discretiser::collectUses() {
  for (Port &p : m.ports) {
    if (!p.definition)
      continue;
    context = p.definitionLoc.isValid() ? p.definitionLoc : p.loc;
    if (p.kind == PortKind::Data) {
      const Expr *where = nullptr;
      if (mentionsReal(p.definition, realOfVar, where))
        return error(where->loc, "data output '" + p.name +
                                     "' is defined from a real variable; "
                                     "only Boolean sensors (cond outputs "
                                     "comparing it with a constant) survive "
                                     "discretise");
      continue;
    }
    size_t before = relations.size();
    if (!scanExpr(p.definition, +1))
      return false;
    if (relations.size() > before)
      diag.note(context,
                "output '" + p.name +
                    "' relates several reals: discretise makes it true in "
                    "the combinations of their positions where it may hold "
                    "(an over-approximation of the set it defines: a "
                    "`never " +
                    p.name + "` verified on the net holds on the model)");
  }
  for (Transition &t : m.transitions) {
    context = t.loc;
    for (Expr *c : t.conds())
      if (!scanExpr(c))
        return false;
    size_t before = relations.size();
    if (!scanExpr(t.guard(), +1))
      return false;
    if (relations.size() > before) {
      // Coded where it may hold, the guard lets the transition fire where
      // the hybrid model could not: harmless for a transition that may
      // fire or not, but one that must fire once enabled (urgent, or
      // forced by an event) would then leave where the model stays.
      if (t.urgent || t.isForced())
        return error(t.loc, "the guard of " +
                                std::string(t.urgent ? "urgent" : "forced") +
                                " transition '" + t.name +
                                "' relates several reals, which discretise "
                                "codes where it may hold: the transition "
                                "would have to fire where the model does "
                                "not (compare each real with a constant, "
                                "or let the transition fire at will)");
      diag.note(t.loc, "the guard of transition '" + t.name +
                           "' relates several reals: discretise lets it "
                           "fire in the combinations of their positions "
                           "where it may hold (an over-approximation)");
    }
  }
  for (Var &v : m.vars)
    if (v.init) {
      const Expr *where = nullptr;
      if (!v.type->isReal() && mentionsReal(v.init, realOfVar, where))
        return error(where->loc, "an initial value reads a real variable");
    }
  return collectAssignments();
}

//===----------------------------------------------------------------------===//
// Driver and report
//===----------------------------------------------------------------------===//

/// Each condition of a location invariant must compare a real with a
/// constant. A bound on a real the place moves becomes a grid point and,
/// when the coded net is built, a stop at it (emitInvariantStops); one on a
/// real the place does not move holds or fails on entry and is not
/// checked (an over-approximation, docs/hybrid.md).
bool Discretiser::collectInvariants() {
  auto leaves = [&](uint32_t place) {
    for (const Transition &t : m.transitions)
      for (const PreArc &a : t.pre())
        if (a.place == place)
          return true;
    return false;
  };
  for (const Invariant &inv : m.invariants) {
    for (Expr *c : inv.conditions) {
      // A place no time may pass in (SpaceEx's `flow false`).
      if (auto *lit = llvm::dyn_cast<BoolLit>(c); lit && !lit->value) {
        if (!leaves(inv.place))
          diag.warning(inv.loc,
                       "place '" + inv.placeName +
                           "' is a timelock: no time may pass in it, and no "
                           "transition leaves it; runs end there, and reach "
                           "reports the states as deadlocks");
        urgentPlaces.push_back({inv.place, c->loc});
        continue;
      }
      std::optional<VarBound> vb = varBound(c);
      auto *cmp = llvm::dyn_cast<BinaryExpr>(c);
      if (!vb && cmp && relationOf(cmp)) {
        diag.note(c->loc.isValid() ? c->loc : inv.loc,
                  "location invariant '" + exprToString(c) + "' of place '" +
                      inv.placeName +
                      "' relates several reals; discretise does not "
                      "enforce it (the place may be stayed in longer "
                      "than it allows: an over-approximation)");
        continue;
      }
      if (!vb || !realOfVar.count(vb->var))
        return error(c->loc, "location invariant '" + exprToString(c) +
                                 "' of place '" + inv.placeName +
                                 "': discretise takes invariants that bound "
                                 "one real by a constant (x <= c, x >= c)");
      Real &x = reals[realOfVar[vb->var]];
      x.thresholds.insert(vb->value);
      // It bounds x in each place that moves x while inv.place is marked.
      for (const FlowOf &fl : x.flows) {
        if (!markedWhenever(fl.place, inv.place))
          continue;
        std::optional<int> dir = constantDirection(*fl.eq);
        if (dir && *dir == 0)
          continue;
        // A place the invariant bounds and nothing leaves: the model's
        // runs end there (SpaceEx models bound their horizon this way); the
        // stop keeps it, and reach reports each such state as a deadlock.
        if (!leaves(fl.place))
          diag.warning(
              inv.loc,
              "place '" + m.places[fl.place].name +
                  "' is a timelock: its invariant '" + exprToString(c) + "'" +
                  (fl.place == inv.place
                       ? std::string()
                       : " (of '" + inv.placeName + "', marked with it)") +
                  " ends its dwell, and no transition "
                  "leaves it; runs end there, and reach "
                  "reports the states as deadlocks");
        invariantBounds.push_back({fl.place, size_t(&x - reals.data()),
                                   vb->upper, vb->value, c->loc});
      }
    }
  }
  return true;
}

bool Discretiser::run() {
  if (d.timescale) {
    ticksPerUnit = 1e9 / double(d.timescale->nanoseconds()); // rates per s
    timeUnit = "tick of " + std::to_string(d.timescale->amount) +
               d.timescale->unit.str();
  }
  normaliseComparisons();
  if (!eliminateDisturbances())
    return false;
  spanUncertainConstants();
  if (!dropUnobservedReals() || !checkOneDimensional() ||
      !checkRectangularFlows() || !collectReals() || !collectUses() ||
      !collectInvariants() || !widenForTransfers())
    return false;
  closeOpenRanges();
  for (Real &r : reals)
    if (!computeTimes(r))
      return false;
  for (Real &r : reals)
    if (!buildGrid(r) || !checkExclusive(r))
      return false;

  if (report) {
    auto &os = *report;
    os << "discretise: module " << m.name << " (times in ticks";
    if (d.timescale)
      os << "; 1 tick = " << d.timescale->amount << d.timescale->unit
         << ", rates per second";
    else
      os << ", rates per tick";
    os << ")\n";
  }
  for (Real &r : reals) {
    // Grid times of every flow, both directions, before the forms exist so
    // that unreachable points are reported once, in order.
    if (report) {
      auto &os = *report;
      os << "real " << r.name << " [" << num(r.lo) << ", " << num(r.hi)
         << "], grid";
      for (double g : r.grid)
        os << " " << num(g);
      os << "\n";
    }
    for (size_t fi = 0; fi < r.flows.size(); ++fi) {
      FlowOf &fl = r.flows[fi];
      StringRef pname = m.places[fl.place].name;
      if (report && fl.rectangular)
        *report << "  flow " << pname << ": " << r.name << "' in ["
                << exprToString(fl.eq->rate) << ", "
                << exprToString(fl.eq->rateHi) << "] (rectangular)\n";
      else if (report)
        *report << "  flow " << pname << ": " << r.name
                << "' = " << exprToString(fl.eq->rate) << " ("
                << hybrid::methodName(fl.rate) << ")\n";
      unsigned K = r.grid.size() - 1;
      for (int dir : {+1, -1}) {
        bool any = false;
        double total = 0;
        for (unsigned k = 0; k < K; ++k) {
          unsigned a = dir > 0 ? k : K - k, c = dir > 0 ? k + 1 : K - k - 1;
          double mid = (r.grid[a] + r.grid[c]) / 2;
          if (fl.fn(mid) * dir <= 0)
            continue;
          Segment s = segment(r, fi, a, c);
          if (report && !any)
            *report << "    " << (dir > 0 ? "up" : "down")
                    << ":  from      to        time          T         "
                       "ticks\n";
          any = true;
          if (!s.reached) {
            diag.warning(fl.eq->loc, "in place '" + pname + "', '" + r.name +
                                         "' never reaches " + num(r.grid[c]) +
                                         " from " + num(r.grid[a]) + " (" +
                                         s.why + "); the segment has no exit");
            if (report)
              *report << llvm::formatv("          {0,-9} {1,-9} never ({2})\n",
                                       num(r.grid[a]), num(r.grid[c]), s.why);
            break;
          }
          total += s.time;
          auto whole = [](double t, uint32_t ticks) {
            return std::fabs(t - ticks) <= 1e-9 * std::max(1.0, t);
          };
          if (exact && (!whole(s.time, s.ticks) || !whole(s.timeLo, s.ticksLo)))
            return error(
                fl.eq->loc,
                "in place '" + pname + "', '" + r.name + "' goes from " +
                    num(r.grid[a]) + " to " + num(r.grid[c]) + " in " +
                    (fl.rectangular ? num(s.timeLo) + " to " : "") +
                    num(s.time) + " ticks, not a whole number (exact=true)");
          // A rectangular flow: the shortest and the longest time, and
          // the total of the longest.
          std::string time = num(s.time), ticks = std::to_string(s.ticks);
          if (fl.rectangular) {
            time = num(s.timeLo) + ".." + time;
            ticks = std::to_string(s.ticksLo) + ".." + ticks;
          }
          if (report)
            *report << llvm::formatv("          {0,-9} {1,-9} {2,-13} {3,-9} "
                                     "{4}\n",
                                     num(r.grid[a]), num(r.grid[c]), time,
                                     num(total), ticks);
        }
      }
    }
  }
  std::vector<size_t> order;
  if (!codingOrder(order))
    return false;
  for (size_t ri : order) {
    Real &r = reals[ri];
    if (!buildForms(r))
      return false;
    emitTransitions(r);
    if (diag.hadError())
      return false;
  }
  for (auto [place, loc] : urgentPlaces)
    addStop(place, m.places[place].name.str() + "_urgent", loc);
  emitStartChoices();
  if (report) {
    *report << "rounding: grid times rounded to whole ticks, worst error "
            << num(worstRounding) << " tick per segment\n";
  }
  finish();
  if (relationTooLarge)
    return error(*relationTooLarge,
                 "a comparison relating several reals holds in more than " +
                     std::to_string(kMaxRelationTerms) +
                     " combinations of their positions; use a coarser grid");
  return true;
}

namespace {

class DiscretisePass : public Pass {
public:
  explicit DiscretisePass(const PassOptions &opts) : opts(opts) {}

  bool parseOptions(DiagEngine &diag, GridSpec &spec) {
    unsigned given = opts.has("grid") + opts.has("points") + opts.has("step");
    if (given != 1) {
      diag.error(llvm::SMLoc(), "discretise needs exactly one of grid=N, "
                                "points=a,b,... or step=D");
      return false;
    }
    if (opts.has("grid")) {
      if (opts.wholeNumber("grid") > 100000) {
        diag.error(llvm::SMLoc(),
                   "discretise: grid= needs a whole number from 1 to 100000");
        return false;
      }
      spec.mode = GridSpec::Mode::Count;
      spec.count = unsigned(opts.wholeNumber("grid"));
    } else if (opts.has("points")) {
      spec.mode = GridSpec::Mode::Points;
      spec.points = opts.numbers("points");
    } else {
      spec.mode = GridSpec::Mode::Step;
      spec.step = opts.number("step");
    }
    return true;
  }

  bool run(Design &design, DiagEngine &diag, Statistics &stats) override {
    GridSpec spec;
    if (!parseOptions(diag, spec))
      return false;
    bool exact = opts.flag("exact");
    bool numeric = opts.text("solver", "auto") == "numeric";
    ReportStream reportStream;
    if (!reportStream.open(opts, "discretise", diag))
      return false;
    llvm::raw_ostream *report = reportStream.get();
    for (auto &mod : design.modules) {
      if (!hasHybridParts(*mod))
        continue;
      Discretiser ds(design, *mod, diag, spec, exact, numeric, report);
      if (!ds.run())
        return false;
      stats.add("discretise", "segments", ds.numSegments,
                "grid segments coded as timed transitions");
      stats.add("discretise", "places", ds.numPlaces, "position places");
      stats.add("discretise", "transitions", ds.numTransitions,
                "transitions added");
      stats.add("discretise", "fused", ds.numFused,
                "guarded transitions fused with the arrival enabling them");
    }
    return true;
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createDiscretisePass(const PassOptions &opts) {
  return std::make_unique<DiscretisePass>(opts);
}
} // namespace netlift
