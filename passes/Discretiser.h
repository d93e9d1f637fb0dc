//===- Discretiser.h - the discretise pass's engine -------------*- C++ -*-===//
//
// Internal to passes/: the Discretiser that turns one hybrid module's real
// variables and flows into timed chains of position places (see
// Discretise.cpp for the method), shared by the files that implement it
// by concept — Discretise.cpp (the pass, what is hybrid, the driver and
// report), DiscretiseGrid.cpp (the grid, its times, position forms) and
// DiscretiseTransitions.cpp (transitions, rewritten guards and sensors).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_DISCRETISER_H
#define NETLIFT_PASSES_DISCRETISER_H

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
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace netlift::discretise {

using namespace netlift::net;
using llvm::StringRef;

inline std::string num(double v) {
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

/// `sum(coef[v] * v) + constant` over real variables (by index).
struct LinearSum {
  std::map<uint32_t, double> coef;
  std::map<uint32_t, Ref *> refOf; // one reference per variable read
  double constant = 0;

  void scale(double k) {
    for (auto &[v, c] : coef)
      c *= k;
    constant *= k;
  }
  void add(const LinearSum &o, double k) {
    for (auto &[v, c] : o.coef) {
      coef[v] += k * c;
      refOf.try_emplace(v, o.refOf.at(v));
    }
    constant += k * o.constant;
  }
  void dropZeros() {
    for (auto it = coef.begin(); it != coef.end();)
      if (it->second == 0) {
        refOf.erase(it->first);
        it = coef.erase(it);
      } else {
        ++it;
      }
  }
};

/// `e` as a sum of reals with constant coefficients, if it is one.
std::optional<LinearSum> linearSum(Expr *e, const Module &m);

/// An invariant condition `x op c` / `c op x` (op one of < <= > >=, x a
/// variable, c a constant): the variable, whether c bounds it from above,
/// and c.
struct VarBound {
  uint32_t var;
  bool upper;
  double value;
};
std::optional<VarBound> varBound(const Expr *c);

/// Calls `fn` for each assignment to variable `var` in `tr`'s action, with
/// whether it runs only under a condition (inside an IF).
void forEachReset(const Transition &tr, uint32_t var,
                  llvm::function_ref<void(const AssignStmt *, bool)> fn);

/// Intervals of reals a rate reads (disturbances, uncertain constants).
using Box = std::map<uint32_t, std::pair<double, double>>;
/// What spanOverBox finds: the rate's extremes, or why there are none.
struct RateSpan {
  bool ok = false;
  double lo = 0, hi = 0;
  /// It reads its own variable or a real outside the box: a coupled flow.
  bool coupled = false;
  /// The box's real it reads other than through a constant coefficient
  /// (none: a product of several).
  std::optional<uint32_t> notLinearIn;
};
/// The extremes of `eq`'s rate while the reals of `vary` range over their
/// intervals in `box` (the box's others at their low ends): a rectangular
/// flow covering every rate the hybrid model can have there.
RateSpan spanOverBox(const Flow::Equation &eq, const Box &box,
                     llvm::ArrayRef<uint32_t> vary);

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
      if (others && r->sym.kind == SymKind::Var && r->fields.empty())
        if (auto it = others->find(r->sym.index); it != others->end())
          return it->second;
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
      case Builtin::Sqrt:
        return std::sqrt(args[0]);
      case Builtin::Sin:
        return std::sin(args[0]);
      case Builtin::Cos:
        return std::cos(args[0]);
      case Builtin::Tan:
        return std::tan(args[0]);
      case Builtin::Asin:
        return std::asin(args[0]);
      case Builtin::Acos:
        return std::acos(args[0]);
      case Builtin::Atan:
        return std::atan(args[0]);
      case Builtin::Ln:
        return std::log(args[0]);
      case Builtin::Log:
        return std::log10(args[0]);
      case Builtin::Exp:
        return std::exp(args[0]);
      case Builtin::Expt:
        return std::pow(args[0], args[1]);
      default: // conversions, strings, bit patterns: not real arithmetic
        bad = e;
        return std::nullopt;
      }
    }
    default:
      bad = e;
      return std::nullopt;
    }
  }
  uint32_t var;
  /// Values of other variables the expression may read (disturbances).
  const std::map<uint32_t, double> *others = nullptr;
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
  /// A rectangular flow `x' in [a, b]` (a and b of one sign): `fn` is the
  /// slow rate (closest to 0), `fast` the other, per tick; a segment takes
  /// any time between distance/|fast| and distance/|slow|.
  bool rectangular = false;
  double fast = 0;
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
  double initHi; // the initial value is anywhere in [init, initHi]
  /// Where x may start (one: its place is marked; more: chosen at time 0).
  std::vector<Form> starts;
  std::vector<double> grid;
  std::vector<FlowOf> flows;
  llvm::DenseMap<uint32_t, int> flowOfPlace;
  std::set<double> thresholds, assigned;
  std::set<uint32_t> component; // the exclusive places holding its flows
  /// It only rises (falls) and nothing bounds it above (below): past its
  /// last threshold no guard tells its values apart, so its range is
  /// closed there (closeOpenRanges), the way timed automata abstract a
  /// clock beyond its largest constant.
  bool openTop = false, openBottom = false;
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
    diag.error(loc.isValid() ? loc : context, msg);
    return false;
  }
  /// Where an error points when its expression has no position (frontends
  /// such as SpaceEx's build expressions from XML text): the port or
  /// transition being read.
  llvm::SMLoc context;
  /// Reals that change freely (SpaceEx's variables without a flow: inputs,
  /// unfollowed), bounded where they are read by invariants and read
  /// only in the rates of other reals: each such rate becomes the interval
  /// it spans (a rectangular flow) and the disturbance is removed
  /// (DiscretiseDisturbances.cpp).
  bool eliminateDisturbances();
  /// Rates reading a constant the initial set gives a range (a real no
  /// flow moves and nothing assigns: `x' == 1 + drift`) become the
  /// rectangular flows spanning it.
  void spanUncertainConstants();
  /// Reals nothing observes (no guard, condition, output, invariant, or
  /// observed real's rate or reset reads them) are dropped with their
  /// flows and resets (DiscretiseUnobserved.cpp).
  bool dropUnobservedReals();
  /// The reals discretise removes without giving them a position:
  /// disturbances and unobserved reals.
  std::set<uint32_t> unfollowed;
  /// Removes the flow equations of `vars` and every assignment to them
  /// (they join `unfollowed`).
  void removeReals(const std::set<uint32_t> &vars);
  /// Every rate reads only its own real and constants: a coupled flow is
  /// the first thing to say about a model (no range or grid would make it
  /// one-dimensional).
  bool checkOneDimensional();
  bool collectReals();
  /// The bounds of every rectangular flow: constants of one sign.
  bool checkRectangularFlows();
  bool inferRange(Real &r, std::string &why);
  /// Once place `from` has moved real `var` past its last constant in
  /// direction `sign` (+1 up), does it stay past it until it is reset to a
  /// constant: every place reachable from `from` (along transitions that do
  /// not reset it) moves it only that way at constant rates, and no
  /// transition resets it to anything but constants?
  bool staysPast(uint32_t var, uint32_t from, int sign);
  /// For real `var` that only moves in direction `sign`, the farthest
  /// value back that resets shifting it (`x := a*x + b`, a > 0) take it
  /// to, from the values it can have in the places they leave; none if no
  /// reset shifts it, or if one applies again and again.
  std::optional<double> farthestShift(uint32_t var, int sign);
  /// Is `q` marked whenever `p` is (p == q, or shown inductively on the
  /// one-token places of both: the initial marking and every transition
  /// keep "p marked implies q marked")? Then q's invariant bounds what
  /// moves in p, as the invariant of a synchronised component's location
  /// (a controller's mode) bounds the plant's flow in its own location.
  bool markedWhenever(uint32_t p, uint32_t q);
  std::map<std::pair<uint32_t, uint32_t>, bool> markedWheneverCache;
  /// A range left open by inferRange ends one grid step past the last
  /// constant the real is compared with, set to or starts at.
  void closeOpenRanges();
  bool collectUses();
  /// Checks a Boolean expression read where `polarity` says (+1 asserted,
  /// -1 denied, 0 both or neither): reals are compared with constants (a
  /// threshold) or related by a linear comparison (a relation).
  bool scanExpr(Expr *e, int polarity = 0);
  /// Comparisons reading one real through a linear sum (`2*x - 1 <= 6`)
  /// become the bound they mean (`x <= 3.5`) (DiscretiseRelations.cpp).
  void normaliseComparisons();
  /// A linear comparison of several reals, `sum(a_i * x_i) + constant op 0`.
  struct Relation {
    std::vector<std::pair<size_t, double>> terms; // (real, coefficient)
    double constant = 0;
    BinaryOp op;
    int polarity = 1; // +1: coded where it may hold; -1: where it must
  };
  std::optional<Relation> relationOf(BinaryExpr *cmp) const;
  /// Records `cmp` as a relation if it is one (`isOne`); an error where
  /// its polarity is unknown.
  bool scanRelation(BinaryExpr *cmp, int polarity, bool &isOne);
  /// The disjunction of the combinations of position places where the
  /// relation may (polarity +1) or must (-1) hold.
  Expr *encodeRelation(const Relation &rel, llvm::SMLoc loc);
  std::map<const Expr *, Relation> relations;
  static constexpr size_t kMaxRelationTerms = 200000;
  std::optional<llvm::SMLoc> relationTooLarge;
  bool collectAssignments();
  /// Location invariants as bounds of a moving real in a place.
  bool collectInvariants();
  /// Blocks time where x stands at an invariant's bound in its place.
  void emitInvariantStops(Real &r, const std::vector<Form> &forms);
  /// No time passes while `place` is marked: a `[0,0 deadline]` arc from
  /// it into a transition that never fires.
  void addStop(uint32_t place, const std::string &name, llvm::SMLoc loc);
  bool buildGrid(Real &r);
  bool checkExclusive(Real &r);
  bool computeTimes(Real &r);
  bool buildForms(Real &r);
  /// A real starting in an interval: a choice of its start at time 0,
  /// before anything else.
  void emitStartChoices();
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
    /// No tick past `hi` while it is enabled (a rectangular flow arrives
    /// at any time in [lo, hi], at hi at the latest).
    bool deadline = false;
  };
  std::vector<Motion> motionsOf(Real &r, Form f);
  /// Grid-time table: duration in ticks from g_a to g_b under flow `fl`.
  struct Segment {
    bool reached;
    double time;    // model time units (ticks); the longest
    uint32_t ticks; // rounded
    std::string why;
    /// A rectangular flow's shortest time and its ticks, rounded down
    /// (`ticks` is then the longest rounded up); otherwise the same.
    double timeLo = 0;
    uint32_t ticksLo = 0;
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
  // Per transition and real: `x := c` assigned at the top of its action,
  // as [c, c], or `x := between(a, b)` as [a, b].
  std::map<std::pair<uint32_t, size_t>, std::pair<double, double>> assigns;
  /// Per transition and real: `x := a*x + b` (a != 0) at the top of its
  /// action, as (a, b): the image of x's grid value or segment.
  std::map<std::pair<uint32_t, size_t>, std::pair<double, double>> affineResets;
  /// Per transition and real: `x := a*x + sum(b_j * y_j) + c` reading
  /// other reals y_j (a copy `x2 := x1`, a mean `x := (c1 + c2)/2`): x's
  /// new position is the image of its own and of the y_j's positions, each
  /// read by a condition arc (DiscretiseTransfers.cpp).
  struct TransferReset {
    double a = 0, c = 0;
    std::vector<std::pair<size_t, double>> terms; // (other real, b_j)
  };
  std::map<std::pair<uint32_t, size_t>, TransferReset> transferResets;
  static constexpr size_t kMaxTransferCombinations = 100000;
  /// The order reals are coded in: one whose reset reads another after it
  /// (its forms are then known); false after an error (resets reading
  /// each other in a cycle).
  bool codingOrder(std::vector<size_t> &order);
  /// Inferred ranges widened to hold every value a transfer gives.
  bool widenForTransfers();
  /// The values a value state of `r` stands for: a grid point, a
  /// segment's closed hull, the end of an open range everything past it.
  std::pair<double, double> hullOf(const Real &r, Value v) const;
  /// Whether those values include the hull's lower and upper ends: a
  /// point does, an open segment does not, a token moving up (down)
  /// through a segment may stand at the end it entered at.
  static std::pair<bool, bool> endsIncluded(Form f);
  /// What the reals a transfer reads add to x: from lo to hi, each end
  /// included or not.
  struct Added {
    double lo = 0, hi = 0;
    bool closedLo = true, closedHi = true;
  };
  /// Over every position of the reals read.
  Added transferHull(const TransferReset &tx) const;
  /// Every combination of positions of the reals a transfer reads where
  /// `guard` may hold, with what they add.
  std::vector<std::pair<std::vector<uint32_t>, Added>>
  transferCombinations(const TransferReset &tx, const Expr *guard) const;
  llvm::StringSet<> taken;
  double ticksPerUnit = 1; // model time units per second or tick
  std::string timeUnit = "tick";
  double worstRounding = 0;
  /// `x <= c` (upper) or `x >= c` in place `place` while x moves there.
  struct InvariantBound {
    uint32_t place;
    size_t real;
    bool upper;
    double bound;
    llvm::SMLoc loc;
  };
  std::vector<InvariantBound> invariantBounds;
  /// Places with the invariant `false` (SpaceEx's urgent locations): left
  /// in the instant they are entered.
  std::vector<std::pair<uint32_t, llvm::SMLoc>> urgentPlaces;
  /// The transition that never fires, whose event the stops wait for.
  std::optional<uint32_t> neverFires;
};

/// The direction a flow moves its variable, where its rate (or both ends
/// of a rectangular one) is constant: +1, -1 or 0; nullopt when it
/// depends on the value.
std::optional<int> constantDirection(const Flow::Equation &eq);

/// The coefficients (a, b) of a rate x' = a*x + b that reads only x
/// (`var`) and constants, where it is affine: checked at fixed points and
/// at `alsoAt`; nullopt when it reads anything else or is not affine.
std::optional<std::pair<double, double>>
affineCoefficients(const Expr *rate, uint32_t var,
                   llvm::ArrayRef<double> alsoAt = {});

/// Does `e` read a real variable (`where`: the first such read)?
bool mentionsReal(const Expr *e,
                  const llvm::DenseMap<uint32_t, size_t> &realOfVar,
                  const Expr *&where);

} // namespace netlift::discretise

#endif
