//===- DiscretiseTransitions.cpp - timed transitions of positions
//-----------===//
#include "passes/Discretiser.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

//===----------------------------------------------------------------------===//
// Transitions
//===----------------------------------------------------------------------===//

void Discretiser::emitTransitions(Real &r) {
  size_t ri = &r - reals.data();
  unsigned numOriginal = m.transitions.size();
  // What each original transition does to x and to x's location (the
  // place of its state machine component it moves the token between).
  struct Effect {
    int leaves = -1, enters = -1;
    std::optional<std::pair<double, double>> assign; // [lo, hi]
    std::optional<std::pair<double, double>> affine; // x := a*x + b
    std::optional<TransferReset> transfer;           // x := a*x + b*y + c
    bool interval() const {
      return (assign && assign->first < assign->second) || affine || transfer;
    }
    int locFrom = -1, locTo = -1; // component places; -1: not touched
    bool touchesOtherReal = false;
    bool relevant() const {
      return leaves >= 0 || enters >= 0 || assign || affine || transfer;
    }
  };
  std::vector<Effect> effects(numOriginal);
  std::vector<bool> isEventSource(numOriginal);
  for (uint32_t ti = 0; ti < numOriginal; ++ti)
    for (const EventSource &es : m.transitions[ti].events())
      if (!es.fromPort)
        isEventSource[es.index] = true;
  for (uint32_t ti = 0; ti < numOriginal; ++ti) {
    Transition &t = m.transitions[ti];
    Effect &e = effects[ti];
    std::set<uint32_t> pre, post;
    for (const PreArc &a : t.pre()) {
      pre.insert(a.place);
      if (r.component.count(a.place))
        e.locFrom = a.place;
    }
    for (const PostArc &a : t.post()) {
      post.insert(a.place);
      if (r.component.count(a.place))
        e.locTo = a.place;
    }
    for (uint32_t pl : pre)
      if (!post.count(pl) && r.flowOfPlace.count(pl))
        e.leaves = r.flowOfPlace[pl];
    for (uint32_t pl : post)
      if (!pre.count(pl) && r.flowOfPlace.count(pl))
        e.enters = r.flowOfPlace[pl];
    auto it = assigns.find({ti, ri});
    if (it != assigns.end())
      e.assign = it->second;
    if (auto af = affineResets.find({ti, ri}); af != affineResets.end())
      e.affine = af->second;
    if (auto tx = transferResets.find({ti, ri}); tx != transferResets.end())
      e.transfer = tx->second;
    for (size_t rj = 0; rj < reals.size(); ++rj) {
      if (rj == ri)
        continue;
      if (assigns.count({ti, rj}) || affineResets.count({ti, rj}) ||
          transferResets.count({ti, rj}))
        e.touchesOtherReal = true;
      for (uint32_t pl : pre)
        if (reals[rj].flowOfPlace.count(pl) && !post.count(pl))
          e.touchesOtherReal = true;
      for (uint32_t pl : post)
        if (reals[rj].flowOfPlace.count(pl) && !pre.count(pl))
          e.touchesOtherReal = true;
    }
  }
  auto valueIndex = [&](double c) {
    return unsigned(std::lower_bound(r.grid.begin(), r.grid.end(),
                                     c - 1e-12 * std::max(1.0, std::fabs(c))) -
                    r.grid.begin());
  };
  // `x := a*x + b` from value v: the grid points and open segments the
  // image of v (a point, or an open segment) meets, widened by [dl, dh]
  // (what the other reals of a transfer add). Past the end of a range
  // left open by closeOpenRanges, values rest at its end; past a closed
  // range the reset is refused.
  std::set<uint32_t> refusedResets;
  auto affineImage = [&](uint32_t ti, std::pair<double, double> ab, Value v,
                         std::vector<Value> &values, double dl = 0,
                         double dh = 0, bool closedLo = false,
                         bool closedHi = false) {
    auto [lo, hi] = hullOf(r, v);
    double l = ab.first * lo + ab.second, h = ab.first * hi + ab.second;
    if (ab.first == 0)
      l = h = ab.second; // x is not read (an open end would give 0*inf)
    if (l > h)
      std::swap(l, h);
    l += dl;
    h += dh;
    double eps = 1e-9 * std::max({1.0, std::fabs(r.grid.front()),
                                  std::fabs(r.grid.back())});
    double bottom = r.grid.front(), top = r.grid.back();
    bool restTop = false, restBottom = false;
    bool overTop = h > top + eps, underBottom = l < bottom - eps;
    if (overTop || underBottom) {
      // The side that a closed end cannot take, if any.
      bool beyondTop = overTop && !r.openTop;
      if (beyondTop || (underBottom && !r.openBottom)) {
        if (!refusedResets.insert(ti).second)
          return false; // said once per transition
        std::string image =
            (ab.first == 0   ? ""
             : ab.first == 1 ? r.shortName
                             : num(ab.first) + "*" + r.shortName) +
            (ab.second > 0   ? " + " + num(ab.second)
             : ab.second < 0 ? " - " + num(-ab.second)
                             : "");
        if (effects[ti].transfer)
          image = "a value reading other reals";
        error(m.transitions[ti].loc,
              "transition '" + m.transitions[ti].name + "' resets '" + r.name +
                  "' to " + image + ", which can take it to " +
                  num(beyondTop ? h : l) + ", outside its range [" +
                  num(bottom) + ", " + num(top) +
                  "] (widen the range, or bound it by the target's "
                  "invariant)");
        return false;
      }
      restTop = overTop;
      restBottom = underBottom;
      l = std::clamp(l, bottom, top);
      h = std::clamp(h, bottom, top);
    }
    auto add = [&](Value w) {
      if (llvm::none_of(values, [&](Value o) {
            return o.atPoint == w.atPoint && o.k == w.k;
          }))
        values.push_back(w);
    };
    if (restBottom)
      add({true, 0});
    if (h - l <= eps) {
      // A point: exactly a grid point or inside one segment.
      unsigned k = valueIndex(l);
      if (k < r.grid.size() && std::fabs(r.grid[k] - l) <= eps)
        add({true, k});
      else
        add({false, k});
    } else {
      // The open interval (l, h): the segment just above l, then every
      // point strictly inside with the segment above it.
      unsigned k = 0;
      while (k < r.grid.size() && r.grid[k] <= l + eps)
        ++k;
      add({false, k});
      for (unsigned j = k; j < r.grid.size() && r.grid[j] < h - eps; ++j) {
        add({true, j});
        add({false, j + 1});
      }
      // What other reals add may include its ends (a token that just
      // entered its segment stands at its entry point); x's own part
      // keeps them only where x is at a point.
      bool xAtPoint = v.atPoint || ab.first == 0;
      for (auto [end, closed] : {std::pair{l, closedLo}, {h, closedHi}}) {
        if (!closed || !xAtPoint)
          continue;
        unsigned j = valueIndex(end);
        bool onPoint = j < r.grid.size() && std::fabs(r.grid[j] - end) <= eps;
        add({onPoint, j});
      }
    }
    if (restTop)
      add({true, unsigned(r.grid.size() - 1)});
    return true;
  };
  // Where the token goes when t fires from form f (clockZero: the form's
  // place clock is 0, i.e. a moving token is exactly at its entry point):
  // one form, or one per value of a reset to an interval (its grid points
  // and the open segments between them); empty after an error.
  auto targetsOf = [&](uint32_t ti, Form f, bool clockZero,
                       std::optional<Added> added = std::nullopt) {
    const Effect &e = effects[ti];
    int flowAfter = e.enters >= 0                         ? e.enters
                    : (f.flow >= 0 && e.leaves != f.flow) ? f.flow
                                                          : -1;
    std::vector<Form> out;
    if (flowAfter == f.flow && !e.assign && !e.affine && !e.transfer) {
      out.push_back(f);
      return out;
    }
    std::vector<Value> values;
    if (e.transfer) {
      // Over every position of the reals read, unless one is given.
      Added all = transferHull(*e.transfer);
      const Added &with = added ? *added : all;
      if (!affineImage(ti, {e.transfer->a, e.transfer->c},
                       valueOf(r, f, clockZero), values, with.lo, with.hi,
                       with.closedLo, with.closedHi))
        return std::vector<Form>();
    } else if (e.affine) {
      if (!affineImage(ti, *e.affine, valueOf(r, f, clockZero), values))
        return std::vector<Form>();
    } else if (e.assign) {
      // An end left open (`y' >= 0`) reaches the range's end where that end
      // stands for every value past it; a closed end is refused.
      auto [lo, hi] = *e.assign;
      bool openLo = !std::isfinite(lo), openHi = !std::isfinite(hi);
      if ((openLo && !r.openBottom) || (openHi && !r.openTop)) {
        if (refusedResets.insert(ti).second)
          error(m.transitions[ti].loc,
                "transition '" + m.transitions[ti].name + "' resets '" +
                    r.name + "' to any value " +
                    (openHi ? "from " + num(lo) + " up" : "up to " + num(hi)) +
                    ", past the end of its range [" + num(r.grid.front()) +
                    ", " + num(r.grid.back()) +
                    "], which is closed there (a real that only " +
                    (openHi ? "rises" : "falls") +
                    " has that end open; else bound the reset)");
        return std::vector<Form>();
      }
      unsigned k0 = openLo ? 0 : valueIndex(lo);
      unsigned k1 = openHi ? unsigned(r.grid.size() - 1) : valueIndex(hi);
      for (unsigned k = k0; k <= k1; ++k) {
        if (k > k0)
          values.push_back({false, k});
        values.push_back({true, k});
      }
    } else {
      values.push_back(valueOf(r, f, clockZero));
    }
    for (Value v : values) {
      std::optional<Form> to =
          flowAfter < 0 ? global(v) : entry(r, flowAfter, v);
      if (!to)
        return std::vector<Form>();
      if (!llvm::is_contained(out, *to))
        out.push_back(*to);
    }
    return out;
  };
  auto targetOf = [&](uint32_t ti, Form f,
                      bool clockZero) -> std::optional<Form> {
    std::vector<Form> to = targetsOf(ti, f, clockZero);
    if (to.empty())
      return std::nullopt;
    return to.front();
  };
  auto guardMayHold = [&](uint32_t ti, Form f) {
    const Expr *g = m.transitions[ti].guard();
    std::optional<bool> a = truthAt(g, r, valueOf(r, f, false));
    std::optional<bool> z = truthAt(g, r, valueOf(r, f, true));
    return !(a && !*a && z && !*z);
  };
  // Fusable transitions: urgent, spontaneous, no condition arcs, not an
  // event source, consuming exactly one flow place of x, enabled by nothing
  // but a guard over x, producing only into x's component (so it always
  // fits), and not touching another real.
  std::vector<bool> fusable(numOriginal);
  for (uint32_t ti = 0; ti < numOriginal; ++ti) {
    Transition &t = m.transitions[ti];
    const Effect &e = effects[ti];
    bool ok = t.urgent && !t.isForced() && t.conds().empty() && t.guard() &&
              e.leaves >= 0 && !e.touchesOtherReal && !isEventSource[ti] &&
              !e.interval() && t.pre().size() == 1 && t.pre()[0].weight == 1 &&
              t.pre()[0].time.isTrivial();
    for (const PostArc &a : t.post())
      ok &= r.component.count(a.place) && a.weight == 1;
    for (unsigned k = 0; ok && k < r.grid.size(); ++k) {
      ok &= truthAt(t.guard(), r, {true, k}).has_value();
      if (k > 0)
        ok &= truthAt(t.guard(), r, {false, k}).has_value();
    }
    fusable[ti] = ok;
  }
  auto fusionFor = [&](Form f, const Motion &mo) -> std::optional<uint32_t> {
    for (uint32_t ti = 0; ti < numOriginal; ++ti) {
      if (!fusable[ti] || effects[ti].leaves != f.flow)
        continue;
      const Expr *g = m.transitions[ti].guard();
      if (!*truthAt(g, r, valueOf(r, f, false)) &&
          *truthAt(g, r, valueOf(r, mo.to, false)))
        return ti;
    }
    return std::nullopt;
  };

  // Joint reachability of (location in x's component, form), over-
  // approximating everything else (data, conditions, other components):
  // only the forms and location changes it finds are coded.
  using AState = std::pair<int, Form>;
  std::set<AState> seen;
  std::deque<AState> work;
  std::set<std::pair<uint32_t, Form>> fires; // (t, form) pairs to code
  std::vector<Form> forms; // in the order found, for a readable output
  std::set<Form> formSet;
  int loc0 = -1;
  for (uint32_t p : r.component)
    if (m.places[p].tokens)
      loc0 = p;
  for (auto &[f, p] : r.places) {
    seen.insert({loc0, f});
    work.push_back({loc0, f});
  }
  bool failed = false;
  auto add = [&](int loc, std::optional<Form> f) {
    if (!f) {
      failed = true;
      return;
    }
    if (seen.insert({loc, *f}).second)
      work.push_back({loc, *f});
  };
  while (!work.empty() && !failed) {
    auto [loc, f] = work.front();
    work.pop_front();
    if (formSet.insert(f).second)
      forms.push_back(f);
    for (Motion &mo : motionsOf(r, f)) {
      if (auto ti = fusionFor(f, mo))
        add(effects[*ti].locTo, targetOf(*ti, mo.to, true));
      else
        add(loc, mo.to);
    }
    for (uint32_t ti = 0; ti < numOriginal; ++ti) {
      const Effect &e = effects[ti];
      if (e.locFrom >= 0 ? e.locFrom != loc : e.locTo >= 0)
        continue;
      if (!guardMayHold(ti, f))
        continue;
      int locAfter = e.locFrom >= 0 ? e.locTo : loc;
      if (!e.relevant()) {
        add(locAfter, f);
        continue;
      }
      fires.insert({ti, f});
      for (bool clockZero : {false, true}) {
        if (clockZero && f.kind != FormKind::Up && f.kind != FormKind::Down)
          break;
        std::vector<Form> to = targetsOf(ti, f, clockZero);
        if (to.empty())
          add(locAfter, std::nullopt);
        for (Form g : to)
          add(locAfter, g);
      }
    }
  }
  if (failed)
    return;

  for (Form f : forms)
    placeOf(r, f);

  // Motions, fused with the transition their arrival enables where there is
  // one.
  std::vector<uint32_t> arrivals;
  for (Form f : forms) {
    for (Motion &mo : motionsOf(r, f)) {
      ++numSegments;
      Interval when{mo.lo, mo.hi};
      when.deadline = mo.deadline;
      PreArc pre{placeOf(r, f), 1, when};
      std::optional<uint32_t> fuseWith = fusionFor(f, mo);
      if (!fuseWith) {
        uint32_t t = b.addTransition(d.save(fresh(mo.name)), {pre},
                                     {PostArc{placeOf(r, mo.to), 1}});
        arrivals.push_back(t);
        b.setUrgent(t, mo.urgent);
        ++numTransitions;
        continue;
      }
      // The arrival and the transition it enables, as one.
      uint32_t ti = *fuseWith;
      std::optional<Form> to = targetOf(ti, mo.to, true);
      Transition src = m.transitions[ti];
      std::vector<PreArc> pres(src.pre().begin(), src.pre().end());
      pres.push_back(pre);
      std::vector<PostArc> posts(src.post().begin(), src.post().end());
      posts.push_back({placeOf(r, *to), 1});
      uint32_t t =
          b.addTransition(d.save(fresh(src.name.str() + "_" + formName(r, f))),
                          pres, posts, src.loc);
      b.setUrgent(t, mo.urgent);
      arrivals.push_back(t);
      if (!src.emits().empty())
        b.setEmits(t, src.emits());
      if (src.hasAction())
        b.setAction(t, src.action());
      ++numTransitions;
      ++numFused;
    }
  }

  // The position follows location changes and resets in the same step.
  for (auto &[ti, f] : fires) {
    bool split = f.kind == FormKind::Up || f.kind == FormKind::Down;
    const Effect &e = effects[ti];
    auto emit = [&, ti = ti, f = f](Form to, Interval iv, StringRef suffix) {
      // A reset to where a moving token entered restarts its place clock
      // (a self-loop re-marks the place); a choice among several values
      // must be made even where one of them is the current form (the
      // forced transitions of a step are maximal).
      if (to == f && !((e.assign || e.affine) && (f.moving() || e.interval())))
        return;
      std::string name =
          m.transitions[ti].name.str() + "_" + formName(r, f) + suffix.str();
      uint32_t t =
          b.addTransition(d.save(fresh(name)), {PreArc{placeOf(r, f), 1, iv}},
                          {PostArc{placeOf(r, to), 1}});
      b.setEvents(t, {EventSource{ti, false}});
      ++numTransitions;
    };
    if (e.transfer) {
      // Per combination of positions of the reals read (condition arcs:
      // their values before the step), one forced transition per value.
      double combinations = 1;
      for (auto [rj, bj] : e.transfer->terms)
        combinations *= double(reals[rj].places.size());
      if (combinations > double(kMaxTransferCombinations)) {
        if (refusedResets.insert(ti).second)
          error(m.transitions[ti].loc,
                "transition '" + m.transitions[ti].name + "' resets '" +
                    r.name + "' from reals whose positions make " +
                    num(combinations) + " combinations (more than " +
                    std::to_string(kMaxTransferCombinations) +
                    "); use a coarser grid");
        continue;
      }
      for (auto &[conds, added] :
           transferCombinations(*e.transfer, m.transitions[ti].guard())) {
        std::vector<Form> tos = targetsOf(ti, f, false, added);
        if (split)
          for (Form to : targetsOf(ti, f, true, added))
            if (!llvm::is_contained(tos, to))
              tos.push_back(to);
        std::string when;
        std::vector<Expr *> condRefs;
        for (uint32_t p : conds) {
          when += "_if_" + m.places[p].name.str();
          condRefs.push_back(b.ref(m.places[p].name));
        }
        for (Form to : tos) {
          uint32_t t = b.addTransition(
              d.save(fresh(m.transitions[ti].name.str() + "_" + formName(r, f) +
                           "_to_" + formName(r, to) + when)),
              {PreArc{placeOf(r, f), 1, Interval{}}},
              {PostArc{placeOf(r, to), 1}});
          b.setConds(t, condRefs);
          b.setEvents(t, {EventSource{ti, false}});
          ++numTransitions;
        }
      }
      continue;
    }
    if (e.interval()) {
      // One forced transition per value: they take the same token, so each
      // firing of t takes one of them.
      std::vector<Form> tos = targetsOf(ti, f, false);
      // An affine image depends on where in its form x is: a token that
      // just entered stands at the entry point, one later inside.
      if (e.affine && split)
        for (Form to : targetsOf(ti, f, true))
          if (!llvm::is_contained(tos, to))
            tos.push_back(to);
      for (Form to : tos)
        emit(to, Interval{}, "_to_" + formName(r, to));
      continue;
    }
    Form later = *targetOf(ti, f, false);
    Form now = split ? *targetOf(ti, f, true) : later;
    if (now == later) {
      emit(later, Interval{}, "");
    } else {
      emit(now, Interval{0, 0}, "_now");
      emit(later, Interval{1, kInf}, "");
    }
  }
  // A transition forced by an event (an input event above all) could join
  // the step of an arrival, whose motion takes the position token its
  // followers need: the location would change and the position stay
  // behind. One shared place, taken and given back by both, keeps them
  // in separate steps (both orders remain).
  std::vector<uint32_t> forcedMovers;
  for (auto &[ti, f] : fires) {
    // Only while x moves can an arrival be due: leaving a place whose flow
    // moves it, or resetting it.
    const Effect &e = effects[ti];
    bool whileMoving = f.moving() || (e.assign && e.locFrom < 0);
    if (m.transitions[ti].isForced() && whileMoving &&
        !llvm::is_contained(forcedMovers, ti))
      forcedMovers.push_back(ti);
  }
  if (!forcedMovers.empty() && !arrivals.empty()) {
    uint32_t lock = b.addPlace(d.save(fresh(r.shortName + "_step")), 1, 1);
    ++numPlaces;
    auto take = [&](uint32_t ti) {
      Transition &tr = m.transitions[ti];
      std::vector<PreArc> pres(tr.pre().begin(), tr.pre().end());
      std::vector<PostArc> posts(tr.post().begin(), tr.post().end());
      pres.push_back({lock, 1, {}});
      posts.push_back({lock, 1});
      tr.setArcs(d.copy(llvm::ArrayRef<PreArc>(pres)),
                 d.copy(llvm::ArrayRef<PostArc>(posts)));
    };
    for (uint32_t ti : forcedMovers)
      take(ti);
    for (uint32_t ti : arrivals)
      take(ti);
  }
  emitInvariantStops(r, forms);
}

/// Where x stands at an invariant's bound in the place that moves it (an
/// Up form entered at an upper bound, a Down form at a lower one), time
/// may not pass: a forced transition that never fires, with a `[0,0
/// deadline]` arc from the form, blocks every tick until the place is
/// left (and if it cannot be, the state is a timelock: `reach` reports it
/// as a deadlock). Entered anywhere else the token is still short of the
/// bound, and its motion brings it there in time.
void Discretiser::emitInvariantStops(Real &r, const std::vector<Form> &forms) {
  size_t ri = size_t(&r - reals.data());
  for (const InvariantBound &ib : invariantBounds) {
    if (ib.real != ri || !r.flowOfPlace.count(ib.place))
      continue;
    int fl = r.flowOfPlace[ib.place];
    for (Form f : forms) {
      if (f.flow != fl)
        continue;
      bool atBound = ib.upper
                         ? f.kind == FormKind::Up && f.k >= 1 &&
                               r.grid[f.k - 1] == ib.bound
                         : f.kind == FormKind::Down && f.k < r.grid.size() &&
                               r.grid[f.k] == ib.bound;
      // At the end of its range x rests, but the flow still pushes it past
      // the bound: the place must be left there too.
      if (f.kind == FormKind::Rest && f.k < r.grid.size() &&
          r.grid[f.k] == ib.bound) {
        double rate = r.flows[fl].fn(ib.bound);
        atBound = ib.upper ? rate > 0 : rate < 0;
      }
      if (!atBound)
        continue;
      addStop(placeOf(r, f),
              m.places[ib.place].name.str() + "_" + r.shortName + "_invariant",
              ib.loc);
    }
  }
}

void Discretiser::addStop(uint32_t place, const std::string &name,
                          llvm::SMLoc loc) {
  if (!neverFires) {
    uint32_t p = b.addPlace(d.save(fresh("_never_marked")), 0, 1);
    neverFires = b.addTransition(d.save(fresh("_never")), {PreArc{p, 1, {}}},
                                 {PostArc{p, 1}});
    ++numPlaces;
    ++numTransitions;
  }
  Interval now{0, 0};
  now.deadline = true;
  uint32_t t = b.addTransition(d.save(fresh(name)), {PreArc{place, 1, now}},
                               {PostArc{place, 1}}, loc);
  b.setEvents(t, {EventSource{*neverFires, false}});
  ++numTransitions;
}

//===----------------------------------------------------------------------===//
// Rewriting guards and sensors
//===----------------------------------------------------------------------===//

/// Replaces every comparison of a real with a constant by the disjunction
/// of the position places where it holds.
Expr *Discretiser::rewrite(Expr *e, Real *only) {
  if (!e)
    return e;
  switch (e->getKind()) {
  case ExprKind::Binary: {
    auto *bin = llvm::cast<BinaryExpr>(e);
    if (bin->op >= BinaryOp::Eq && bin->op <= BinaryOp::Ge) {
      if (auto it = relations.find(bin); it != relations.end())
        return encodeRelation(it->second, e->loc);
      for (Real &r : reals) {
        auto isX = [&](Expr *x) {
          auto *ref = llvm::dyn_cast<Ref>(x);
          return ref && ref->sym.kind == SymKind::Var &&
                 ref->sym.index == r.var;
        };
        if (!isX(bin->lhs) && !isX(bin->rhs))
          continue;
        Expr *out = nullptr;
        for (auto &[f, p] : r.places) {
          if (!*truthAt(e, r, valueOf(r, f, false)))
            continue;
          Expr *ref = b.ref(m.places[p].name, e->loc);
          out = out ? b.binary(BinaryOp::Or, out, ref, e->loc) : ref;
        }
        return out ? out : b.boolLit(false, e->loc);
      }
      return e;
    }
    bin->lhs = rewrite(bin->lhs, only);
    bin->rhs = rewrite(bin->rhs, only);
    return e;
  }
  case ExprKind::Unary: {
    auto *u = llvm::cast<UnaryExpr>(e);
    u->operand = rewrite(u->operand, only);
    return e;
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    c->cond = rewrite(c->cond, only);
    c->thenExpr = rewrite(c->thenExpr, only);
    c->elseExpr = rewrite(c->elseExpr, only);
    return e;
  }
  default:
    return e;
  }
}

static bool readsOnlySignals(const Expr *e, const Module &m) {
  switch (e->getKind()) {
  case ExprKind::BoolLit:
    return true;
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    return r->sym.kind == SymKind::Place ||
           (r->sym.kind == SymKind::Port &&
            m.ports[r->sym.index].kind == PortKind::Cond);
  }
  case ExprKind::Unary:
    return llvm::cast<UnaryExpr>(e)->op == UnaryOp::Not &&
           readsOnlySignals(llvm::cast<UnaryExpr>(e)->operand, m);
  case ExprKind::Binary: {
    auto *b = llvm::cast<BinaryExpr>(e);
    return (b->op == BinaryOp::And || b->op == BinaryOp::Or ||
            b->op == BinaryOp::Xor) &&
           readsOnlySignals(b->lhs, m) && readsOnlySignals(b->rhs, m);
  }
  default:
    return false;
  }
}

void Discretiser::finish() {
  // Guards and definitions: comparisons become position places. New place
  // references are unresolved (sym None) until the verifier runs; a guard
  // that compared only reals becomes a condition arc.
  for (Port &p : m.ports)
    if (p.definition)
      p.definition = rewrite(p.definition);
  unsigned n = m.transitions.size();
  for (uint32_t ti = 0; ti < n; ++ti) {
    Transition &t = m.transitions[ti];
    if (!t.guard())
      continue;
    const Expr *where = nullptr;
    if (!mentionsReal(t.guard(), realOfVar, where))
      continue;
    Expr *g = rewrite(t.guard());
    // Resolve the fresh references enough to classify them.
    std::function<void(Expr *)> resolve = [&](Expr *e) {
      if (auto *r = llvm::dyn_cast<Ref>(e)) {
        if (r->sym.kind == SymKind::None)
          r->sym = m.lookup(r->name);
      } else if (auto *u = llvm::dyn_cast<UnaryExpr>(e)) {
        resolve(u->operand);
      } else if (auto *bb = llvm::dyn_cast<BinaryExpr>(e)) {
        resolve(bb->lhs);
        resolve(bb->rhs);
      }
    };
    resolve(g);
    if (readsOnlySignals(g, m)) {
      std::vector<Expr *> conds(t.conds().begin(), t.conds().end());
      conds.push_back(g);
      b.setConds(ti, conds);
      b.setGuard(ti, nullptr);
    } else {
      b.setGuard(ti, g);
    }
  }
  // Actions lose their `x := c` (the forced transitions moved the token).
  for (uint32_t ti = 0; ti < n; ++ti) {
    Transition &t = m.transitions[ti];
    if (!t.hasAction())
      continue;
    std::vector<Stmt *> kept;
    bool changed = false;
    for (Stmt *s : t.action()) {
      if (auto *a = llvm::dyn_cast<AssignStmt>(s))
        if (auto *r = llvm::dyn_cast<Ref>(a->target))
          if (r->sym.kind == SymKind::Var && realOfVar.count(r->sym.index)) {
            changed = true;
            continue;
          }
      kept.push_back(s);
    }
    if (changed)
      b.setAction(ti, kept);
  }
  m.flows.clear();
  m.invariants.clear(); // now stops at their bounds (emitInvariantStops)
  Module::Table<Var> vars;
  for (Var &v : m.vars)
    if (!v.type->isReal())
      vars.push_back(v);
  m.vars = std::move(vars);
  m.rebuildSymbols();
}
