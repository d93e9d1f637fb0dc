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
#include "passes/Pass.h"

#include "ir/hybrid/FlowSolver.h"
#include "ir/net/Builder.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/SmallString.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/FormatVariadic.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <set>

using namespace netlift;
using namespace netlift::net;
using llvm::StringRef;

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v == 0 ? 0.0 : v);
  return buf;
}

/// How the grid is chosen (the pass options).
struct GridSpec {
  enum class Mode { Count, Points, Step } mode = Mode::Count;
  unsigned count = 0;
  std::vector<double> points;
  double step = 0;
};

/// Evaluates a real-valued expression of one variable; fails on anything
/// else and names what it met.
class RealEval {
public:
  explicit RealEval(uint32_t var) : var(var) {}
  std::optional<double> eval(const Expr *e, double x) {
    switch (e->getKind()) {
    case ExprKind::IntLit:
      return double(llvm::cast<IntLit>(e)->value);
    case ExprKind::RealLit:
      return llvm::cast<RealLit>(e)->value;
    case ExprKind::Ref: {
      auto *r = llvm::cast<Ref>(e);
      if (r->sym.kind == SymKind::Var && r->sym.index == var &&
          r->fields.empty()) {
        readsVar = true;
        return x;
      }
      bad = e;
      return std::nullopt;
    }
    case ExprKind::Unary: {
      auto *u = llvm::cast<UnaryExpr>(e);
      auto a = eval(u->operand, x);
      if (!a || u->op != UnaryOp::Neg) {
        bad = bad ? bad : e;
        return std::nullopt;
      }
      return -*a;
    }
    case ExprKind::Binary: {
      auto *bin = llvm::cast<BinaryExpr>(e);
      auto a = eval(bin->lhs, x), b = eval(bin->rhs, x);
      if (!a || !b)
        return std::nullopt;
      switch (bin->op) {
      case BinaryOp::Add:
        return *a + *b;
      case BinaryOp::Sub:
        return *a - *b;
      case BinaryOp::Mul:
        return *a * *b;
      case BinaryOp::Div:
        return *a / *b;
      default:
        bad = e;
        return std::nullopt;
      }
    }
    case ExprKind::Call: {
      auto *c = llvm::cast<CallExpr>(e);
      std::vector<double> args;
      for (const Expr *a : c->args) {
        auto v = eval(a, x);
        if (!v)
          return std::nullopt;
        args.push_back(*v);
      }
      switch (c->fn) {
      case Builtin::Abs:
        return std::fabs(args[0]);
      case Builtin::Min:
        return *std::min_element(args.begin(), args.end());
      case Builtin::Max:
        return *std::max_element(args.begin(), args.end());
      }
      return std::nullopt;
    }
    default:
      bad = e;
      return std::nullopt;
    }
  }
  uint32_t var;
  bool readsVar = false;
  const Expr *bad = nullptr;
};

/// Where a real variable is: a grid point or an open segment, and which
/// flow place (if any) is acting on it. See the file comment for the names.
enum class FormKind : uint8_t {
  At,
  In,
  Up,
  Down,
  UpMid,
  DownMid,
  Rest,
  RestIn
};

struct Form {
  FormKind kind;
  int flow; // index into Real::flows; -1 for At/In
  unsigned k;
  bool operator<(const Form &o) const {
    return std::tie(kind, flow, k) < std::tie(o.kind, o.flow, o.k);
  }
  bool operator==(const Form &o) const {
    return kind == o.kind && flow == o.flow && k == o.k;
  }
  bool atPoint() const {
    return kind == FormKind::At || kind == FormKind::Rest;
  }
  bool moving() const {
    return kind == FormKind::Up || kind == FormKind::Down ||
           kind == FormKind::UpMid || kind == FormKind::DownMid;
  }
};

/// One place's flow for one variable.
struct FlowOf {
  uint32_t place;
  const Flow::Equation *eq;
  hybrid::Rate rate;
  std::function<double(double)> fn; // in units per tick
};

/// A value state of x: a grid point or an open segment.
struct Value {
  bool atPoint;
  unsigned k;
};

struct Real {
  uint32_t var;
  std::string name;      // the variable's name
  std::string shortName; // its last name component (for place names)
  double lo, hi, init;
  std::vector<double> grid;
  std::vector<FlowOf> flows;
  llvm::DenseMap<uint32_t, int> flowOfPlace;
  std::set<double> thresholds, assigned;
  std::set<uint32_t> component; // the exclusive places holding its flows
  std::map<Form, uint32_t> places;
};

class Discretiser {
public:
  Discretiser(Design &d, Module &m, DiagEngine &diag, const GridSpec &spec,
              bool exact, bool numeric, llvm::raw_ostream *report)
      : d(d), m(m), diag(diag), b(d), spec(spec), exact(exact),
        numeric(numeric), report(report) {
    b.setModule(&m);
  }
  bool run();
  unsigned numSegments = 0, numPlaces = 0, numTransitions = 0, numFused = 0;

private:
  bool error(llvm::SMLoc loc, const llvm::Twine &msg) {
    diag.error(loc, msg);
    return false;
  }
  bool collectReals();
  bool collectUses();
  bool scanExpr(Expr *e);
  bool collectAssignments();
  bool buildGrid(Real &r);
  bool checkExclusive(Real &r);
  bool computeTimes(Real &r);
  bool buildForms(Real &r);
  void emitTransitions(Real &r);
  Expr *rewrite(Expr *e, Real *only = nullptr);
  void finish();

  // Form semantics.
  Value valueOf(const Real &r, Form f, bool clockZero) const;
  std::optional<Form> entry(Real &r, int flow, Value v);
  Form global(Value v) const {
    return {v.atPoint ? FormKind::At : FormKind::In, -1, v.k};
  }
  uint32_t placeOf(Real &r, Form f);
  std::string formName(const Real &r, Form f) const;
  std::string fresh(const std::string &base);
  /// Three-valued truth of `e` when x has value v: nullopt = depends on
  /// something else.
  std::optional<bool> truthAt(const Expr *e, const Real &r, Value v) const;
  bool compareHolds(BinaryOp op, double a, double b) const;

  // Motion of x under flow f from a moving form: (duration, target).
  struct Motion {
    Form from, to;
    uint32_t lo, hi; // interval in ticks
    bool urgent;
    std::string name;
  };
  std::vector<Motion> motionsOf(Real &r, Form f);
  /// Grid-time table: duration in ticks from g_a to g_b under flow `fl`.
  struct Segment {
    bool reached;
    double time;    // model time units (ticks)
    uint32_t ticks; // rounded
    std::string why;
  };
  Segment segment(Real &r, int fl, unsigned a, unsigned b);
  std::map<std::tuple<uint32_t, int, unsigned, unsigned>, Segment> segCache;

  Design &d;
  Module &m;
  DiagEngine &diag;
  Builder b;
  const GridSpec &spec;
  bool exact, numeric;
  llvm::raw_ostream *report;
  std::vector<Real> reals;
  llvm::DenseMap<uint32_t, size_t> realOfVar;
  // Per transition and real: `x := c` assigned at the top of its action.
  std::map<std::pair<uint32_t, size_t>, double> assigns;
  llvm::StringSet<> taken;
  double ticksPerUnit = 1; // model time units per second or tick
  std::string timeUnit = "tick";
  double worstRounding = 0;
};

} // namespace

//===----------------------------------------------------------------------===//
// Collecting what is hybrid
//===----------------------------------------------------------------------===//

bool Discretiser::collectReals() {
  for (uint32_t i = 0; i < m.vars.size(); ++i) {
    const Var &v = m.vars[i];
    if (!v.type->isReal())
      continue;
    Real r;
    r.var = i;
    r.name = v.name.str();
    r.shortName = v.name.rsplit('.').second.empty()
                      ? v.name.str()
                      : v.name.rsplit('.').second.str();
    r.lo = v.type->realLo;
    r.hi = v.type->realHi;
    if (!std::isfinite(r.lo) || !std::isfinite(r.hi))
      return error(v.loc, "real '" + v.name +
                              "' has an unbounded range; discretise needs "
                              "finite bounds to place its grid");
    if (!(r.lo < r.hi))
      return error(v.loc, "real '" + v.name + "' has an empty range");
    r.init = r.lo;
    if (v.init) {
      auto c = evalConstReal(v.init);
      if (!c)
        return error(v.init->loc, "the initial value of real '" + v.name +
                                      "' is not a constant");
      r.init = *c;
    }
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
  // One moving variable per place: the chain of a place measures one
  // variable's progress.
  for (const Flow &f : m.flows) {
    unsigned moving = 0;
    for (const Flow::Equation &eq : f.equations) {
      auto c = evalConstReal(eq.rate);
      if (!c || *c != 0)
        ++moving;
    }
    if (moving > 1)
      return error(f.loc, "place '" + f.placeName +
                              "' moves more than one real variable; "
                              "discretise handles one moving variable per "
                              "place (split the motion into parallel places)");
  }
  return true;
}

/// Checks a Boolean expression (guard, condition, definition): real
/// variables may only be compared with constants; records the thresholds.
bool Discretiser::scanExpr(Expr *e) {
  if (!e)
    return true;
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    if (r->sym.kind == SymKind::Var && realOfVar.count(r->sym.index))
      return error(r->loc, "real '" + r->name +
                               "' is used here other than compared with a "
                               "constant; discretise can only replace "
                               "comparisons `x op constant`");
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
      if (l || rr) {
        Real *x = l ? l : rr;
        Expr *other = l ? bin->rhs : bin->lhs;
        auto c = evalConstReal(other);
        if (!c)
          return error(other->loc, "real '" + x->name +
                                       "' is compared with something that "
                                       "is not a constant; discretise needs "
                                       "`x op constant`");
        x->thresholds.insert(*c);
        return true;
      }
    }
    return scanExpr(bin->lhs) && scanExpr(bin->rhs);
  }
  case ExprKind::Unary:
    return scanExpr(llvm::cast<UnaryExpr>(e)->operand);
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    return scanExpr(c->cond) && scanExpr(c->thenExpr) && scanExpr(c->elseExpr);
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
static bool mentionsReal(const Expr *e,
                         const llvm::DenseMap<uint32_t, size_t> &realOfVar,
                         const Expr *&where);

bool Discretiser::collectAssignments() {
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    Transition &t = m.transitions[ti];
    if (!t.hasAction())
      continue;
    std::function<bool(Block, bool)> walk = [&](Block blk, bool top) -> bool {
      for (Stmt *s : blk) {
        if (auto *a = llvm::dyn_cast<AssignStmt>(s)) {
          auto *tr = llvm::dyn_cast<Ref>(a->target);
          bool toReal = tr && tr->sym.kind == SymKind::Var &&
                        realOfVar.count(tr->sym.index);
          const Expr *where = nullptr;
          if (mentionsReal(a->value, realOfVar, where))
            return error(where->loc,
                         "an action reads a real variable; after discretise "
                         "reals exist only as position places, which actions "
                         "can only reset (`x := constant`); test thresholds "
                         "in the guard instead");
          if (!toReal)
            continue;
          size_t ri = realOfVar[tr->sym.index];
          if (!top)
            return error(a->loc, "a conditional assignment to real '" +
                                     tr->name +
                                     "' is not supported by discretise "
                                     "(write it at the top of the action)");
          auto c = evalConstReal(a->value);
          if (!c)
            return error(a->value->loc, "real '" + tr->name +
                                            "' is assigned something that is "
                                            "not a constant");
          reals[ri].assigned.insert(*c);
          assigns[{ti, ri}] = *c;
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
        }
      }
      return true;
    };
    if (!walk(t.action(), true))
      return false;
  }
  return true;
}

static bool mentionsReal(const Expr *e,
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
    if (!scanExpr(p.definition))
      return false;
  }
  for (Transition &t : m.transitions) {
    for (Expr *c : t.conds())
      if (!scanExpr(c))
        return false;
    if (!scanExpr(t.guard()))
      return false;
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
// The grid and its times
//===----------------------------------------------------------------------===//

bool Discretiser::buildGrid(Real &r) {
  std::vector<double> g{r.lo, r.hi, r.init};
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
  if (r.init < r.lo || r.init > r.hi)
    return error(m.vars[r.var].loc,
                 "the initial value of real '" + r.name + "' is out of range");
  if (spec.mode == GridSpec::Mode::Step) {
    // The points each flow reaches at multiples of the time step, starting
    // from where x can start a flow: its initial and assigned values and
    // the range's ends.
    std::vector<double> starts{r.lo, r.hi, r.init};
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
  hybrid::Crossing c =
      hybrid::timeToReach(r.flows[fl].rate, r.grid[a], r.grid[bIdx]);
  Segment s;
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
  }
  segCache[key] = s;
  return s;
}

bool Discretiser::computeTimes(Real &r) {
  for (FlowOf &fl : r.flows) {
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
    double f0 = fl.fn(0), f1 = fl.fn(1);
    fl.rate.a = f1 - f0;
    fl.rate.b = f0;
    bool affine = true;
    for (double x : {r.lo, r.hi, (r.lo + r.hi) / 2, r.lo + (r.hi - r.lo) / 3,
                     -7.25, 13.5}) {
      double want = fl.rate.a * x + fl.rate.b, got = fl.fn(x);
      if (std::fabs(want - got) >
          1e-12 * std::max({std::fabs(want), std::fabs(got), 1.0}))
        affine = false;
    }
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
bool Discretiser::checkExclusive(Real &r) {
  std::set<uint32_t> comp;
  for (FlowOf &fl : r.flows)
    comp.insert(fl.place);
  for (bool grew = true; grew;) {
    grew = false;
    for (Transition &t : m.transitions) {
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
  uint64_t initial = 0;
  for (uint32_t p : comp)
    initial += m.places[p].tokens;
  if (initial > 1)
    return error(m.vars[r.var].loc,
                 "the flow places of '" + r.name +
                     "' may be marked together (their component starts "
                     "with " +
                     std::to_string(initial) + " tokens)");
  for (Transition &t : m.transitions) {
    int64_t delta = 0;
    bool touches = false;
    for (const PreArc &a : t.pre())
      if (comp.count(a.place)) {
        delta -= a.weight;
        touches = true;
      }
    for (const PostArc &a : t.post())
      if (comp.count(a.place)) {
        delta += a.weight;
        touches = true;
      }
    if (touches && delta != 0)
      return error(t.loc, "transition '" + t.name +
                              "' changes the number of tokens among the "
                              "places that hold the flows of '" +
                              r.name +
                              "', so discretise cannot show that two of "
                              "them are never marked together");
  }
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
  if (!left && !right)
    return std::nullopt;
  double c = *evalConstReal(left ? bin->rhs : bin->lhs);
  // A value inside an open segment compares like its midpoint: every
  // threshold is a grid point, so no comparison changes inside a segment.
  double x = v.atPoint ? r.grid[v.k] : (r.grid[v.k - 1] + r.grid[v.k]) / 2;
  return left ? compareHolds(bin->op, x, c) : compareHolds(bin->op, c, x);
}

bool Discretiser::buildForms(Real &r) {
  unsigned k0 =
      std::lower_bound(r.grid.begin(), r.grid.end(),
                       r.init - 1e-12 * std::max(1.0, std::fabs(r.init))) -
      r.grid.begin();
  Form start = global({true, k0});
  for (FlowOf &fl : r.flows)
    if (m.places[fl.place].tokens) {
      auto f = entry(r, r.flowOfPlace[fl.place], {true, k0});
      if (!f)
        return false;
      start = *f;
    }
  uint32_t p = placeOf(r, start);
  m.places[p].tokens = 1;
  return true;
}

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
    std::optional<double> assign;
    int locFrom = -1, locTo = -1; // component places; -1: not touched
    bool touchesOtherReal = false;
    bool relevant() const { return leaves >= 0 || enters >= 0 || assign; }
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
    for (size_t rj = 0; rj < reals.size(); ++rj) {
      if (rj == ri)
        continue;
      if (assigns.count({ti, rj}))
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
  // Where the token goes when t fires from form f (clockZero: the form's
  // place clock is 0, i.e. a moving token is exactly at its entry point).
  auto targetOf = [&](uint32_t ti, Form f,
                      bool clockZero) -> std::optional<Form> {
    const Effect &e = effects[ti];
    int flowAfter = e.enters >= 0                         ? e.enters
                    : (f.flow >= 0 && e.leaves != f.flow) ? f.flow
                                                          : -1;
    if (flowAfter == f.flow && !e.assign)
      return f;
    Value v = e.assign ? Value{true, valueIndex(*e.assign)}
                       : valueOf(r, f, clockZero);
    if (flowAfter < 0)
      return global(v);
    return entry(r, flowAfter, v);
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
              t.pre().size() == 1 && t.pre()[0].weight == 1 &&
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
      add(locAfter, targetOf(ti, f, false));
      if (f.kind == FormKind::Up || f.kind == FormKind::Down)
        add(locAfter, targetOf(ti, f, true));
    }
  }
  if (failed)
    return;

  for (Form f : forms)
    placeOf(r, f);

  // Motions, fused with the transition their arrival enables where there is
  // one.
  for (Form f : forms) {
    for (Motion &mo : motionsOf(r, f)) {
      ++numSegments;
      PreArc pre{placeOf(r, f), 1, Interval{mo.lo, mo.hi}};
      std::optional<uint32_t> fuseWith = fusionFor(f, mo);
      if (!fuseWith) {
        uint32_t t = b.addTransition(d.save(fresh(mo.name)), {pre},
                                     {PostArc{placeOf(r, mo.to), 1}});
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
    Form later = *targetOf(ti, f, false);
    Form now = split ? *targetOf(ti, f, true) : later;
    auto emit = [&, ti = ti, f = f](Form to, Interval iv, StringRef suffix) {
      if (to == f)
        return;
      std::string name =
          m.transitions[ti].name.str() + "_" + formName(r, f) + suffix.str();
      uint32_t t =
          b.addTransition(d.save(fresh(name)), {PreArc{placeOf(r, f), 1, iv}},
                          {PostArc{placeOf(r, to), 1}});
      b.setEvents(t, {EventSource{ti, false}});
      ++numTransitions;
    };
    if (now == later) {
      emit(later, Interval{}, "");
    } else {
      emit(now, Interval{0, 0}, "_now");
      emit(later, Interval{1, kInf}, "");
    }
  }
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
  Module::Table<Var> vars;
  for (Var &v : m.vars)
    if (!v.type->isReal())
      vars.push_back(v);
  m.vars = std::move(vars);
  m.rebuildSymbols();
}

//===----------------------------------------------------------------------===//
// Driver and report
//===----------------------------------------------------------------------===//

bool Discretiser::run() {
  if (d.timescale) {
    ticksPerUnit = 1e9 / double(d.timescale->nanoseconds()); // rates per s
    timeUnit = "tick of " + std::to_string(d.timescale->amount) +
               d.timescale->unit.str();
  }
  if (!collectReals() || !collectUses())
    return false;
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
      if (report)
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
          if (exact &&
              std::fabs(s.time - s.ticks) > 1e-9 * std::max(1.0, s.time))
            return error(fl.eq->loc,
                         "in place '" + pname + "', '" + r.name +
                             "' goes from " + num(r.grid[a]) + " to " +
                             num(r.grid[c]) + " in " + num(s.time) +
                             " ticks, not a whole number (exact=true)");
          if (report)
            *report << llvm::formatv("          {0,-9} {1,-9} {2,-13} {3,-9} "
                                     "{4}\n",
                                     num(r.grid[a]), num(r.grid[c]),
                                     num(s.time), num(total), s.ticks);
        }
      }
    }
  }
  for (Real &r : reals) {
    if (!buildForms(r))
      return false;
    emitTransitions(r);
    if (diag.hadError())
      return false;
  }
  if (report) {
    *report << "rounding: grid times rounded to whole ticks, worst error "
            << num(worstRounding) << " tick per segment\n";
  }
  finish();
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
      if (opts.count("grid") > 100000) {
        diag.error(llvm::SMLoc(),
                   "discretise: grid= needs a whole number from 1 to 100000");
        return false;
      }
      spec.mode = GridSpec::Mode::Count;
      spec.count = unsigned(opts.count("grid"));
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
