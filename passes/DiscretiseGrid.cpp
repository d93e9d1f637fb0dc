//===- DiscretiseGrid.cpp - grids, times and position forms
//-----------------===//
#include "passes/Discretiser.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

//===----------------------------------------------------------------------===//
// The grid and its times
//===----------------------------------------------------------------------===//

bool Discretiser::buildGrid(Real &r) {
  std::vector<double> g{r.lo, r.hi, r.init, r.initHi};
  switch (spec.mode) {
  case GridSpec::Mode::Count:
    for (unsigned i = 1; i < spec.count; ++i)
      g.push_back(r.lo + (r.hi - r.lo) * double(i) / spec.count);
    break;
  case GridSpec::Mode::Points:
    for (double p : spec.points)
      if (p > r.lo && p < r.hi)
        g.push_back(p);
    break;
  case GridSpec::Mode::Step:
    break; // added below, once the rates are known
  }
  for (double t : r.thresholds)
    if (t >= r.lo && t <= r.hi)
      g.push_back(t);
  for (double a : r.assigned) {
    if (a < r.lo || a > r.hi)
      return error(m.vars[r.var].loc, "real '" + r.name + "' is assigned " +
                                          num(a) + ", outside its range");
    g.push_back(a);
  }
  if (r.init < r.lo || r.initHi > r.hi)
    return error(m.vars[r.var].loc,
                 "the initial value of real '" + r.name + "' is out of range");
  if (spec.mode == GridSpec::Mode::Step) {
    // The points each flow reaches at multiples of the time step, starting
    // from where x can start a flow: its initial and assigned values and
    // the range's ends.
    std::vector<double> starts{r.lo, r.hi, r.init, r.initHi};
    starts.insert(starts.end(), r.assigned.begin(), r.assigned.end());
    for (FlowOf &fl : r.flows)
      for (double s : starts) {
        double v = fl.fn(s);
        if (!(v != 0))
          continue;
        double end = v > 0 ? r.hi : r.lo;
        for (unsigned k = 1; k < 10000; ++k) {
          double target = spec.step * k;
          // Bisection on the position reached at time `target`.
          double a = s, bnd = end;
          hybrid::Crossing full = hybrid::timeToReach(fl.rate, s, end);
          if (full.reached && full.time <= target)
            break;
          for (int it = 0; it < 100; ++it) {
            double mid = (a + bnd) / 2;
            hybrid::Crossing c = hybrid::timeToReach(fl.rate, s, mid);
            if (c.reached && c.time <= target)
              a = mid;
            else
              bnd = mid;
          }
          if (!g.empty() && std::fabs(a - g.back()) <= 1e-9 * (r.hi - r.lo))
            break; // converging to an equilibrium
          g.push_back(a);
          if (g.size() > 100000)
            return error(m.vars[r.var].loc,
                         "step= gives more than 100000 grid points for '" +
                             r.name + "'");
        }
      }
  }
  std::sort(g.begin(), g.end());
  double eps = 1e-12 * std::max({std::fabs(r.lo), std::fabs(r.hi), 1.0});
  for (double v : g)
    if (r.grid.empty() || v - r.grid.back() > eps)
      r.grid.push_back(v);
  return true;
}

Discretiser::Segment Discretiser::segment(Real &r, int fl, unsigned a,
                                          unsigned bIdx) {
  auto key = std::make_tuple(r.var, fl, a, bIdx);
  auto it = segCache.find(key);
  if (it != segCache.end())
    return it->second;
  Segment s;
  if (r.flows[fl].rectangular) {
    // Any time from distance/|fast| to distance/|slow|, rounded outward so
    // that no arrival time is lost.
    double dist = std::fabs(r.grid[bIdx] - r.grid[a]);
    double slow = std::fabs(r.flows[fl].fn(r.grid[a]));
    double fast = std::fabs(r.flows[fl].fast);
    s.reached = true;
    s.timeLo = dist / fast;
    s.time = dist / slow;
    auto clamp = [](double t) { return std::min(t, double(kInf - 1)); };
    double lo = clamp(std::floor(s.timeLo + 1e-9 * std::max(1.0, s.timeLo)));
    double hi = clamp(std::ceil(s.time - 1e-9 * std::max(1.0, s.time)));
    s.ticksLo = uint32_t(lo);
    s.ticks = uint32_t(hi);
    worstRounding = std::max(
        {worstRounding, std::fabs(s.timeLo - lo), std::fabs(s.time - hi)});
    segCache[key] = s;
    return s;
  }
  hybrid::Crossing c =
      hybrid::timeToReach(r.flows[fl].rate, r.grid[a], r.grid[bIdx]);
  s.reached = c.reached;
  s.why = c.why;
  s.ticks = 0;
  if (c.reached) {
    s.time = c.time;
    double ticks = c.time;
    double rounded = std::nearbyint(ticks);
    if (rounded > double(kInf - 1))
      rounded = double(kInf - 1);
    s.ticks = uint32_t(rounded);
    worstRounding = std::max(worstRounding, std::fabs(ticks - rounded));
    s.timeLo = s.time;
    s.ticksLo = s.ticks;
  }
  segCache[key] = s;
  return s;
}

bool Discretiser::computeTimes(Real &r) {
  for (FlowOf &fl : r.flows) {
    if (fl.eq->rateHi) {
      // Constants of one sign (checkRectangularFlows): the slow rate gives
      // the direction and the longest times.
      double lo = *evalConstReal(fl.eq->rate) / ticksPerUnit;
      double hi = *evalConstReal(fl.eq->rateHi) / ticksPerUnit;
      double slow = std::fabs(lo) <= std::fabs(hi) ? lo : hi;
      fl.fast = slow == lo ? hi : lo;
      fl.rectangular = lo != hi;
      fl.fn = [slow](double) { return slow; };
      fl.rate.f = fl.fn;
      fl.rate.shape = hybrid::Rate::Shape::Constant;
      fl.rate.a = 0;
      fl.rate.b = slow;
      continue;
    }
    RealEval ev(r.var);
    if (!ev.eval(fl.eq->rate, r.lo)) {
      const Expr *bad = ev.bad ? ev.bad : fl.eq->rate;
      return error(bad->loc, "the rate of '" + r.name + "' in place '" +
                                 m.places[fl.place].name +
                                 "' reads something other than '" + r.name +
                                 "' and constants; discretise needs x' = f(x)");
    }
    const Expr *rate = fl.eq->rate;
    uint32_t var = r.var;
    double scale = ticksPerUnit;
    // Rates are per second with a timescale, else per tick; the solver
    // works in ticks.
    fl.fn = [rate, var, scale](double x) {
      RealEval e(var);
      return *e.eval(rate, x) / scale;
    };
    fl.rate.f = fl.fn;
    fl.rate.forceNumeric = numeric;
    auto ab = affineCoefficients(
        rate, var, {r.lo, r.hi, (r.lo + r.hi) / 2, r.lo + (r.hi - r.lo) / 3});
    bool affine = ab.has_value();
    fl.rate.a = affine ? ab->first / scale : 0;
    fl.rate.b = affine ? ab->second / scale : fl.fn(0);
    fl.rate.shape = !affine          ? hybrid::Rate::Shape::General
                    : fl.rate.a == 0 ? hybrid::Rate::Shape::Constant
                                     : hybrid::Rate::Shape::Affine;
  }
  return true;
}

/// The flow places of x must never be marked together. Shown by a state
/// machine component: the places linked to them by one-in-one-out
/// transitions, holding one token at most, which every transition that
/// touches them preserves.
/// The places a one-token state machine component holding `seed` needs:
/// closed under the transitions that move one token from one place to
/// another.
static std::set<uint32_t> closeUnderMoves(const Module &m,
                                          std::set<uint32_t> comp) {
  for (bool grew = true; grew;) {
    grew = false;
    for (const Transition &t : m.transitions) {
      if (t.pre().size() != 1 || t.post().size() != 1 ||
          t.pre()[0].weight != 1 || t.post()[0].weight != 1)
        continue;
      uint32_t a = t.pre()[0].place, c = t.post()[0].place;
      if (comp.count(a) != comp.count(c)) {
        comp.insert(a);
        comp.insert(c);
        grew = true;
      }
    }
  }
  return comp;
}

/// The first transition that changes the number of tokens in `comp`.
static const Transition *tokenChange(const Module &m,
                                     const std::set<uint32_t> &comp) {
  for (const Transition &t : m.transitions) {
    int64_t delta = 0;
    for (const PreArc &a : t.pre())
      if (comp.count(a.place))
        delta -= a.weight;
    for (const PostArc &a : t.post())
      if (comp.count(a.place))
        delta += a.weight;
    if (delta != 0)
      return &t;
  }
  return nullptr;
}

bool Discretiser::checkExclusive(Real &r) {
  std::set<uint32_t> seed;
  for (FlowOf &fl : r.flows)
    seed.insert(fl.place);
  std::set<uint32_t> comp = closeUnderMoves(m, seed);
  const Transition *change = tokenChange(m, comp);
  if (change) {
    // A composed network moves the tokens of several automata in one
    // synchronised transition: the component is then the locations of the
    // automata holding the flows (the places of their scopes, `inst.loc`),
    // if those keep one token.
    std::set<StringRef> scopes;
    for (uint32_t p : seed)
      scopes.insert(m.places[p].name.rsplit('.').second.empty()
                        ? StringRef()
                        : m.places[p].name.rsplit('.').first);
    std::set<uint32_t> automata = seed;
    for (uint32_t p = 0; p < m.places.size(); ++p) {
      StringRef name = m.places[p].name;
      StringRef scope = name.rsplit('.').second.empty()
                            ? StringRef()
                            : name.rsplit('.').first;
      if (scopes.count(scope))
        automata.insert(p);
    }
    automata = closeUnderMoves(m, automata);
    uint64_t tokens = 0;
    for (uint32_t p : automata)
      tokens += m.places[p].tokens;
    if (tokens <= 1 && !tokenChange(m, automata)) {
      comp = std::move(automata);
      change = nullptr;
    }
  }
  uint64_t initial = 0;
  for (uint32_t p : comp)
    initial += m.places[p].tokens;
  if (initial > 1)
    return error(m.vars[r.var].loc,
                 "the flow places of '" + r.name +
                     "' may be marked together (their component starts "
                     "with " +
                     std::to_string(initial) + " tokens)");
  if (change)
    return error(change->loc, "transition '" + change->name +
                                  "' changes the number of tokens among the "
                                  "places that hold the flows of '" +
                                  r.name +
                                  "', so discretise cannot show that two of "
                                  "them are never marked together");
  r.component = std::move(comp);
  return true;
}

//===----------------------------------------------------------------------===//
// Position forms
//===----------------------------------------------------------------------===//

Value Discretiser::valueOf(const Real &r, Form f, bool clockZero) const {
  switch (f.kind) {
  case FormKind::At:
  case FormKind::Rest:
    return {true, f.k};
  case FormKind::Up:
    return clockZero ? Value{true, f.k - 1} : Value{false, f.k};
  case FormKind::Down:
    return clockZero ? Value{true, f.k} : Value{false, f.k};
  default:
    return {false, f.k};
  }
}

/// The form x takes when flow `flow` starts acting on value v; nullopt
/// after an error.
std::optional<Form> Discretiser::entry(Real &r, int flow, Value v) {
  unsigned K = r.grid.size() - 1;
  FlowOf &fl = r.flows[flow];
  if (v.atPoint) {
    double rate = fl.fn(r.grid[v.k]);
    if (rate > 0 && v.k < K)
      return Form{FormKind::Up, flow, v.k + 1};
    if (rate < 0 && v.k > 0)
      return Form{FormKind::Down, flow, v.k};
    return Form{FormKind::Rest, flow, v.k};
  }
  double fl0 = fl.fn(r.grid[v.k - 1]), fh = fl.fn(r.grid[v.k]);
  if (fl0 >= 0 && fh > 0)
    return Form{FormKind::UpMid, flow, v.k};
  if (fl0 < 0 && fh <= 0)
    return Form{FormKind::DownMid, flow, v.k};
  if (fl0 < 0 && fh > 0) {
    error(fl.eq->loc,
          "the flow of '" + r.name + "' in place '" + m.places[fl.place].name +
              "' has an unstable equilibrium between " + num(r.grid[v.k - 1]) +
              " and " + num(r.grid[v.k]) + "; add it to the grid with points=");
    return std::nullopt;
  }
  return Form{FormKind::RestIn, flow, v.k};
}

std::string Discretiser::formName(const Real &r, Form f) const {
  std::string k = std::to_string(f.k);
  if (f.flow < 0)
    return r.name + (f.kind == FormKind::At ? "_at" : "_in") + k;
  std::string p =
      m.places[r.flows[f.flow].place].name.str() + "_" + r.shortName;
  switch (f.kind) {
  case FormKind::Up:
    return p + "_up" + k;
  case FormKind::Down:
    return p + "_down" + k;
  case FormKind::UpMid:
    return p + "_up" + k + "_mid";
  case FormKind::DownMid:
    return p + "_down" + k + "_mid";
  case FormKind::Rest:
    return p + "_rest" + k;
  case FormKind::RestIn:
    return p + "_rest_in" + k;
  default:
    return p;
  }
}

std::string Discretiser::fresh(const std::string &base) {
  std::string n = base;
  for (unsigned i = 1; m.lookup(n).kind != SymKind::None || taken.count(n); ++i)
    n = base + "_" + std::to_string(i);
  taken.insert(n);
  return n;
}

uint32_t Discretiser::placeOf(Real &r, Form f) {
  auto it = r.places.find(f);
  if (it != r.places.end())
    return it->second;
  uint32_t p = b.addPlace(d.save(fresh(formName(r, f))), 0, 1);
  r.places[f] = p;
  ++numPlaces;
  return p;
}

std::vector<Discretiser::Motion> Discretiser::motionsOf(Real &r, Form f) {
  std::vector<Motion> out;
  if (!f.moving())
    return out;
  bool up = f.kind == FormKind::Up || f.kind == FormKind::UpMid;
  unsigned from = up ? f.k - 1 : f.k, to = up ? f.k : f.k - 1;
  Segment s = segment(r, f.flow, from, to);
  std::optional<Form> next = entry(r, f.flow, Value{true, to});
  if (!next)
    return out;
  std::string base = formName(r, f);
  if (!s.reached) {
    // Reported with the table; from the grid point the token rests in the
    // segment forever. From inside, the end may still be reached when the
    // rate vanishes only at the start: at some time, with no bound.
    bool mid = f.kind == FormKind::UpMid || f.kind == FormKind::DownMid;
    double start = r.grid[from] + (r.grid[to] - r.grid[from]) * 1e-6;
    if (mid &&
        hybrid::timeToReach(r.flows[f.flow].rate, start, r.grid[to]).reached)
      out.push_back({f, *next, 0, kInf, false, base + "_reach_early"});
    return out;
  }
  if (r.flows[f.flow].rectangular) {
    // Any time in [lo, hi] from the grid point, any in [0, hi] from
    // inside; at hi at the latest (a deadline).
    bool mid = f.kind == FormKind::UpMid || f.kind == FormKind::DownMid;
    uint32_t lo = mid ? 0 : s.ticksLo;
    Motion mo{f, *next, lo, s.ticks, lo == s.ticks, base + "_reach"};
    mo.deadline = lo != s.ticks;
    out.push_back(mo);
    return out;
  }
  if (f.kind == FormKind::Up || f.kind == FormKind::Down) {
    out.push_back({f, *next, s.ticks, s.ticks, true, base + "_reach"});
  } else {
    // Entered at an unknown point inside: arrives within the duration.
    if (s.ticks > 0)
      out.push_back({f, *next, 0, s.ticks, false, base + "_reach_early"});
    out.push_back({f, *next, s.ticks, s.ticks, true, base + "_reach"});
  }
  return out;
}

bool Discretiser::compareHolds(BinaryOp op, double a, double c) const {
  switch (op) {
  case BinaryOp::Eq:
    return a == c;
  case BinaryOp::Ne:
    return a != c;
  case BinaryOp::Lt:
    return a < c;
  case BinaryOp::Le:
    return a <= c;
  case BinaryOp::Gt:
    return a > c;
  case BinaryOp::Ge:
    return a >= c;
  default:
    return false;
  }
}

std::optional<bool> Discretiser::truthAt(const Expr *e, const Real &r,
                                         Value v) const {
  if (!e)
    return true;
  if (auto *bl = llvm::dyn_cast<BoolLit>(e))
    return bl->value;
  if (auto *u = llvm::dyn_cast<UnaryExpr>(e)) {
    if (u->op != UnaryOp::Not)
      return std::nullopt;
    auto a = truthAt(u->operand, r, v);
    if (!a)
      return std::nullopt;
    return !*a;
  }
  auto *bin = llvm::dyn_cast<BinaryExpr>(e);
  if (!bin)
    return std::nullopt;
  if (bin->op == BinaryOp::And || bin->op == BinaryOp::Or) {
    auto a = truthAt(bin->lhs, r, v), c = truthAt(bin->rhs, r, v);
    bool isAnd = bin->op == BinaryOp::And;
    if ((a && *a != isAnd) || (c && *c != isAnd))
      return !isAnd;
    if (a && c)
      return isAnd;
    return std::nullopt;
  }
  if (bin->op < BinaryOp::Eq || bin->op > BinaryOp::Ge)
    return std::nullopt;
  auto *lr = llvm::dyn_cast<Ref>(bin->lhs);
  auto *rr = llvm::dyn_cast<Ref>(bin->rhs);
  bool left = lr && lr->sym.kind == SymKind::Var && lr->sym.index == r.var;
  bool right = rr && rr->sym.kind == SymKind::Var && rr->sym.index == r.var;
  std::optional<double> k = evalConstReal(left ? bin->rhs : bin->lhs);
  if ((!left && !right) || !k)
    return std::nullopt; // another real's comparison, or a relation
  double c = *k;
  // A value inside an open segment compares like its midpoint: every
  // threshold is a grid point, so no comparison changes inside a segment.
  double x = v.atPoint ? r.grid[v.k] : (r.grid[v.k - 1] + r.grid[v.k]) / 2;
  return left ? compareHolds(bin->op, x, c) : compareHolds(bin->op, c, x);
}

bool Discretiser::buildForms(Real &r) {
  auto indexOf = [&](double v) {
    return unsigned(std::lower_bound(r.grid.begin(), r.grid.end(),
                                     v - 1e-12 * std::max(1.0, std::fabs(v))) -
                    r.grid.begin());
  };
  // Every value of the initial interval: its grid points and the open
  // segments between them.
  unsigned k0 = indexOf(r.init), k1 = indexOf(r.initHi);
  for (unsigned k = k0; k <= k1; ++k)
    for (Value v : {Value{false, k}, Value{true, k}}) {
      if (!v.atPoint && k == k0)
        continue;
      Form start = global(v);
      for (FlowOf &fl : r.flows)
        if (m.places[fl.place].tokens) {
          auto f = entry(r, r.flowOfPlace[fl.place], v);
          if (!f)
            return false;
          start = *f;
        }
      if (!llvm::is_contained(r.starts, start))
        r.starts.push_back(start);
    }
  for (Form f : r.starts)
    placeOf(r, f);
  if (r.starts.size() == 1)
    m.places[placeOf(r, r.starts[0])].tokens = 1;
  return true;
}

void Discretiser::emitStartChoices() {
  std::vector<StringRef> initPlaces;
  std::set<uint32_t> choices;
  for (Real &r : reals) {
    if (r.starts.size() < 2)
      continue;
    llvm::SMLoc at = m.vars[r.var].loc;
    std::string init = fresh(r.name + "_init");
    uint32_t p = b.addPlace(d.save(init), 1, 1, at);
    for (Form f : r.starts) {
      uint32_t t =
          b.addTransition(d.save(fresh(formName(r, f) + "_start")),
                          {PreArc{p, 1, {}}}, {PostArc{placeOf(r, f), 1}}, at);
      b.setUrgent(t);
      choices.insert(t);
      ++numTransitions;
    }
    initPlaces.push_back(d.save(init));
  }
  // Nothing else happens before every start is chosen (all at time 0: the
  // choices are urgent).
  for (uint32_t ti = 0; !initPlaces.empty() && ti < m.transitions.size();
       ++ti) {
    Transition &t = m.transitions[ti];
    if (choices.count(ti) || t.isForced())
      continue;
    std::vector<Expr *> conds(t.conds().begin(), t.conds().end());
    for (StringRef p : initPlaces)
      conds.push_back(b.unary(UnaryOp::Not, b.ref(p)));
    b.setConds(ti, conds);
  }
}
