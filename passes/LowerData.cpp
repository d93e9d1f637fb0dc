//===- LowerData.cpp - Boolean data into NCES places and arcs -------------===//
//
// `lower-data` rewrites a flat module's Boolean data into pure places and
// arcs, for tools that know NCES but not netlift's data extension:
//  - each Boolean variable `x` becomes two complementary places, `x`
//    (marked while x is true) and `x_false`; a stored Boolean output `o`
//    becomes `o_true`/`o_false` and the output is then defined as `o_true`;
//    Boolean data inputs and outputs become cond inputs and outputs. Since
//    a place read in an expression means "is marked", every property and
//    output definition that named `x` keeps its meaning;
//  - each transition with a guard, an action or a non-literal condition is
//    replaced by one copy per combination of the signals its conditions
//    and guard read (Shannon expansion, splitting only on what the
//    evaluation actually reads): the copy tests that combination with
//    condition arcs — a variable's place or its complement, a place or cond
//    input or their negation. The copies' conditions are disjoint, so in
//    every state at most one copy is enabled, exactly when the original
//    was; copies keep the original's arcs, timing, events, emitted outputs
//    and urgency; a transition forced by a replaced one is forced by each
//    copy (`|`). A single copy keeps the original name; several are `t_1`,
//    `t_2`, ...;
//  - the action is executed symbolically into one expression per written
//    variable, over the state before the step, and each becomes forced
//    setters `t_sets_x` (x_false -> x) and `t_clears_x` (x -> x_false),
//    triggered by the copies, one per combination of the signals the new
//    value depends on. A setter whose variable already has the new value
//    is not enabled; the setters of one variable exclude each other and
//    touch only its two places, so they join the copy's step without
//    conflict.
//
// Preserved: the labelled state graph up to reading x's value as the
// marking of place `x` (same states, edges, deadlocks; step labels gain
// the setters), under the interleaving step policy. Refused with the
// reason: non-Boolean variables and data ports, clock variables (NCES
// keeps time on arcs), a variable written by two transitions of which one
// is forced (a step holding both is a write conflict in the original,
// which places cannot express), an expression depending on more than
// kMaxCopies combinations, and `&` events from a transition that needs
// several copies. Under `--steps maximal` two spontaneous writers of one
// variable in one step are a runtime error of the original but two steps
// of the lowered model: check such models before lowering. Negated places
// and cond inputs stay as `not p` conditions.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"
#include "ir/net/Clone.h"
#include "ir/net/ExecutedOnly.h"
#include "ir/net/ScalarOps.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/StringSet.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;
using llvm::dyn_cast;
using llvm::StringRef;

namespace {

/// More combinations than this for one expression (a transition's
/// enabling, or a variable's new value) is refused: the lowering would not
/// be a model anyone could read.
constexpr size_t kMaxCopies = 4096;

/// A Boolean signal a transition's copies test or set: a lowered variable
/// or stored output (a "bit", with its two places), a place, or a cond
/// input.
struct Atom {
  Symbol sym;
  int bit = -1; // index into bits for lowered data
};

struct Bit {
  Symbol sym; // Var or Port
  StringRef name;
  llvm::SMLoc loc;
  bool init = false;
  uint32_t truePlace = 0, falsePlace = 0;
};

/// The value each lowered bit has after a transition's action, as an
/// expression over the state before the step: statements run in order, so
/// a later read sees an earlier write; `if`/`case` merge their arms'
/// values with conditional expressions; `for` loops are unrolled.
class SymbolicAction {
public:
  SymbolicAction(Builder &b, const std::vector<Atom> &atoms,
                 const llvm::DenseMap<uint64_t, uint32_t> &atomIndex,
                 size_t numBits)
      : b(b), atoms(atoms), atomIndex(atomIndex) {
    env.assign(numBits, nullptr);
  }

  /// Null after reporting a statement that is not supported.
  bool exec(Block block, DiagEngine &diag) {
    for (const Stmt *s : block) {
      if (auto *a = dyn_cast<AssignStmt>(s)) {
        int bit = bitOf(a->target);
        if (bit < 0) {
          diag.error(a->target->loc, "lower-data: only Boolean variables and "
                                     "outputs can be assigned");
          return false;
        }
        env[bit] = subst(a->value);
      } else if (auto *i = dyn_cast<IfStmt>(s)) {
        std::vector<Expr *> conds;
        std::vector<std::vector<Expr *>> arms;
        std::vector<Expr *> before = env;
        for (const IfArm &arm : i->arms) {
          conds.push_back(subst(arm.cond));
          env = before;
          if (!exec(arm.body, diag))
            return false;
          arms.push_back(env);
        }
        env = before;
        if (i->hasElse && !exec(i->elseBody, diag))
          return false;
        merge(conds, arms, before);
      } else if (auto *c = dyn_cast<CaseStmt>(s)) {
        Expr *sel = subst(c->selector);
        std::vector<Expr *> conds;
        std::vector<std::vector<Expr *>> arms;
        std::vector<Expr *> before = env;
        for (const CaseArm &arm : c->arms) {
          Expr *hit = nullptr;
          for (const CaseLabel &l : arm.labels) {
            Expr *lo = subst(l.lo);
            Expr *one =
                l.hi ? b.binary(BinaryOp::And, b.binary(BinaryOp::Le, lo, sel),
                                b.binary(BinaryOp::Le, sel, subst(l.hi)))
                     : b.binary(BinaryOp::Eq, sel, lo);
            hit = hit ? b.binary(BinaryOp::Or, hit, one) : one;
          }
          conds.push_back(hit);
          env = before;
          if (!exec(arm.body, diag))
            return false;
          arms.push_back(env);
        }
        env = before;
        if (c->hasElse && !exec(c->elseBody, diag))
          return false;
        merge(conds, arms, before);
      } else {
        auto *f = cast<ForStmt>(s);
        int64_t lo, hi;
        if (!evalConstInt(subst(f->lo), lo) ||
            !evalConstInt(subst(f->hi), hi)) {
          diag.error(f->loc, "lower-data: loop bounds must be constants");
          return false;
        }
        loopVals.push_back(0);
        for (int64_t i = lo; i <= hi; ++i) {
          loopVals.back() = i;
          if (!exec(f->body, diag))
            return false;
        }
        loopVals.pop_back();
      }
    }
    return true;
  }

  /// Per bit: its value after the action, or null if the action leaves it.
  std::vector<Expr *> env;

private:
  int bitOf(const Expr *e) const {
    auto *r = dyn_cast<Ref>(e);
    if (!r || !r->fields.empty())
      return -1;
    auto it = atomIndex.find(uint64_t(r->sym.kind) << 32 | r->sym.index);
    return it == atomIndex.end() ? -1 : atoms[it->second].bit;
  }

  /// After the arms of a conditional: each bit some arm wrote is the
  /// choice among the arms' values (the value before the conditional where
  /// an arm did not write it). `env` holds the else arm's values.
  void merge(const std::vector<Expr *> &conds,
             const std::vector<std::vector<Expr *>> &arms,
             const std::vector<Expr *> &before) {
    for (size_t bit = 0; bit < env.size(); ++bit) {
      bool any = env[bit] != before[bit];
      for (auto &arm : arms)
        any |= arm[bit] != before[bit];
      if (!any)
        continue;
      Expr *v = valueOf(env[bit], bit);
      for (size_t i = arms.size(); i-- > 0;)
        v = b.cond(conds[i], valueOf(arms[i][bit], bit), v);
      env[bit] = v;
    }
  }
  Expr *valueOf(Expr *v, size_t bit) { return v ? v : current(uint32_t(bit)); }
  /// A read of a bit the action has not written: the bit itself.
  Expr *current(uint32_t bit) {
    if (!bitRefs.count(bit)) {
      auto *r = cast<Ref>(b.ref("", {}));
      r->sym = atoms[bit].sym;
      bitRefs[bit] = r;
    }
    return bitRefs[bit];
  }

  /// `e` with every bit read replaced by its current value and every loop
  /// variable by its value; shares what does not change.
  Expr *subst(Expr *e) {
    switch (e->getKind()) {
    case ExprKind::Ref: {
      auto *r = cast<Ref>(e);
      if (r->sym.kind == SymKind::LoopVar)
        return b.intLit(loopVals[r->sym.index], e->loc);
      int bit = bitOf(e);
      return bit >= 0 && env[bit] ? env[bit] : e;
    }
    case ExprKind::Unary: {
      auto *u = cast<UnaryExpr>(e);
      Expr *a = subst(u->operand);
      return a == u->operand ? e : b.unary(u->op, a, e->loc);
    }
    case ExprKind::Binary: {
      auto *x = cast<BinaryExpr>(e);
      Expr *l = subst(x->lhs), *r = subst(x->rhs);
      return l == x->lhs && r == x->rhs ? e : b.binary(x->op, l, r, e->loc);
    }
    case ExprKind::Cond: {
      auto *c = cast<CondExpr>(e);
      Expr *k = subst(c->cond), *t = subst(c->thenExpr),
           *f = subst(c->elseExpr);
      return k == c->cond && t == c->thenExpr && f == c->elseExpr
                 ? e
                 : b.cond(k, t, f, e->loc);
    }
    case ExprKind::Call: {
      auto *c = cast<CallExpr>(e);
      std::vector<Expr *> args;
      bool same = true;
      for (Expr *a : c->args) {
        args.push_back(subst(a));
        same &= args.back() == a;
      }
      return same ? e : b.call(c->fn, args, e->loc, c->to);
    }
    default:
      return e;
    }
  }

  Builder &b;
  const std::vector<Atom> &atoms;
  const llvm::DenseMap<uint64_t, uint32_t> &atomIndex;
  std::vector<int64_t> loopVals;
  llvm::DenseMap<uint32_t, Ref *> bitRefs;
};

/// Evaluates a Boolean expression over the state before a step against a
/// partial valuation of the atoms. A read of an atom without a value stops
/// the evaluation and names the atom to split on.
class Evaluator {
public:
  Evaluator(const Module &m, llvm::DenseMap<uint64_t, uint32_t> &atomIndex,
            std::vector<Atom> &atoms)
      : m(m), atomIndex(atomIndex), atoms(atoms) {}

  enum class Status { Done, Split, Error };

  /// The value of `e` for transition `t` (whose pre-places are marked)
  /// under `cube` (per atom: -1 unknown, 0, 1).
  Status run(const Expr *e, const Transition &t,
             const std::vector<int8_t> &cube, int64_t &out) {
    this->cube = &cube;
    this->t = &t;
    status = Status::Done;
    return eval(e, out) ? Status::Done : status;
  }

  uint32_t splitAtom = 0;
  std::string error;
  llvm::SMLoc errorLoc;

private:
  bool fail(const Expr *e, const std::string &msg) {
    status = Status::Error;
    error = msg;
    errorLoc = e->loc;
    return false;
  }

  uint32_t atomFor(Symbol s) {
    uint64_t key = uint64_t(s.kind) << 32 | s.index;
    auto [it, fresh] = atomIndex.try_emplace(key, uint32_t(atoms.size()));
    if (fresh)
      atoms.push_back({s, -1});
    return it->second;
  }

  bool readAtom(uint32_t a, int64_t &out) {
    if (a < cube->size() && (*cube)[a] >= 0) {
      out = (*cube)[a];
      return true;
    }
    splitAtom = a;
    status = Status::Split;
    return false;
  }

  bool readRef(const Ref *r, int64_t &out) {
    switch (r->sym.kind) {
    case SymKind::EnumLit:
      out = r->sym.index;
      return true;
    case SymKind::Place:
      // A place the transition consumes from is marked whenever it fires;
      // one it fills to capacity without consuming is empty.
      for (const PreArc &a : t->pre())
        if (a.place == r->sym.index) {
          out = 1;
          return true;
        }
      for (const PostArc &a : t->post())
        if (a.place == r->sym.index && m.places[a.place].capacity != kInf &&
            a.weight >= m.places[a.place].capacity) {
          out = 0;
          return true;
        }
      return readAtom(atomFor(r->sym), out);
    case SymKind::Var:
    case SymKind::Port:
      if (r->sym.kind == SymKind::Port && m.ports[r->sym.index].definition)
        return eval(m.ports[r->sym.index].definition, out);
      return readAtom(atomFor(r->sym), out);
    default:
      return fail(r, "'" + r->name.str() + "' cannot be read here");
    }
  }

  bool eval(const Expr *e, int64_t &out) {
    switch (e->getKind()) {
    case ExprKind::IntLit:
      out = cast<IntLit>(e)->value;
      return true;
    case ExprKind::BoolLit:
      out = cast<BoolLit>(e)->value;
      return true;
    case ExprKind::Ref:
      return readRef(cast<Ref>(e), out);
    case ExprKind::Unary: {
      auto *u = cast<UnaryExpr>(e);
      int64_t a;
      if (!eval(u->operand, a))
        return false;
      if (u->op == UnaryOp::Not) {
        out = !a;
        return true;
      }
      OpError err = applyUnary(u, a, out);
      return err == OpError::None || fail(e, opErrorMessage(err, e, 0));
    }
    case ExprKind::Binary: {
      auto *b = cast<BinaryExpr>(e);
      int64_t x, y;
      if (!eval(b->lhs, x))
        return false;
      if (b->op == BinaryOp::And || b->op == BinaryOp::Or) {
        // Short-circuit: the right side is not read (nor split on) when
        // the left side decides.
        if ((b->op == BinaryOp::And) != bool(x)) {
          out = x != 0;
          return true;
        }
        if (!eval(b->rhs, y))
          return false;
        out = y != 0;
        return true;
      }
      if (!eval(b->rhs, y))
        return false;
      OpError err = applyBinary(b, x, y, out);
      return err == OpError::None || fail(e, opErrorMessage(err, e, y));
    }
    case ExprKind::Cond: {
      auto *c = cast<CondExpr>(e);
      int64_t k;
      if (!eval(c->cond, k))
        return false;
      return eval(k ? c->thenExpr : c->elseExpr, out);
    }
    case ExprKind::Call: {
      auto *c = cast<CallExpr>(e);
      int64_t a, b = 0;
      if (!eval(c->args[0], a) || (c->args.size() > 1 && !eval(c->args[1], b)))
        return false;
      OpError err = applyBuiltin(c, a, b, out);
      return err == OpError::None || fail(e, opErrorMessage(err, e, b));
    }
    default:
      return fail(e, "this expression has no Boolean meaning");
    }
  }

  const Module &m;
  llvm::DenseMap<uint64_t, uint32_t> &atomIndex;
  std::vector<Atom> &atoms;
  const std::vector<int8_t> *cube = nullptr;
  const Transition *t = nullptr;
  Status status = Status::Done;
};

/// One combination of atom values under which an expression is true.
using Cube = std::vector<int8_t>;

class LowerDataPass : public Pass {
public:
  explicit LowerDataPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "lower-data");
    if (!m)
      return false;
    if (std::optional<ExecutedOnly> x = findExecutedOnly(*m)) {
      diag.error(x->loc, "lower-data: cannot encode " + x->what +
                             " in places and arcs");
      return false;
    }
    if (!collectBits(*m, diag) || !checkWriters(*m, diag))
      return false;
    Builder b(d);
    b.setModule(m);
    for (const Port &p : m->ports)
      taken.insert(p.name);
    for (const Place &p : m->places)
      taken.insert(p.name);
    for (const Transition &t : m->transitions)
      taken.insert(t.name);
    // Variables' names are free once they are places; ports keep theirs.
    for (Bit &bit : bits) {
      bool isVar = bit.sym.kind == SymKind::Var;
      std::string t = fresh(isVar ? bit.name.str() : bit.name.str() + "_true");
      std::string f = fresh(bit.name.str() + "_false");
      bit.truePlace = b.addPlace(t, bit.init ? 1 : 0, 1, bit.loc);
      bit.falsePlace = b.addPlace(f, bit.init ? 0 : 1, 1, bit.loc);
    }

    size_t nt = m->transitions.size();
    std::vector<bool> keep(nt, true);
    // Per replaced transition: its copies, then the setters they force.
    std::vector<std::vector<uint32_t>> copiesOf(nt), settersOf(nt);
    for (uint32_t t = 0; t < nt; ++t) {
      if (!needsLowering(*m, m->transitions[t]))
        continue;
      keep[t] = false;
      if (!lowerTransition(b, *m, t, copiesOf[t], settersOf[t], diag))
        return false;
    }
    // Event arcs from a replaced transition now come from each copy.
    for (uint32_t u = 0; u < m->transitions.size(); ++u) {
      Transition &tr = m->transitions[u];
      if (!tr.isForced())
        continue;
      std::vector<EventSource> evs;
      bool changed = false;
      for (EventSource s : tr.events()) {
        if (s.fromPort || s.index >= nt || keep[s.index]) {
          evs.push_back(s);
          continue;
        }
        changed = true;
        if (tr.mode == EventMode::And && copiesOf[s.index].size() > 1) {
          diag.error(tr.loc, "lower-data: '" + tr.name +
                                 "' waits for all its events (&) and '" +
                                 m->transitions[s.index].name +
                                 "' becomes several transitions");
          return false;
        }
        for (uint32_t c : copiesOf[s.index])
          evs.push_back({c, false});
      }
      if (changed) {
        b.setEvents(u, evs, tr.mode);
        tr.extras->eventLocs = {};
      }
    }
    lowerPorts(b, *m);
    // The replacements take their original's place in the order.
    std::vector<uint32_t> order;
    for (uint32_t t = 0; t < nt; ++t)
      if (keep[t]) {
        order.push_back(t);
      } else {
        order.insert(order.end(), copiesOf[t].begin(), copiesOf[t].end());
        order.insert(order.end(), settersOf[t].begin(), settersOf[t].end());
      }
    std::vector<uint32_t> newIndex(m->transitions.size(), UINT32_MAX);
    for (uint32_t i = 0; i < order.size(); ++i)
      newIndex[order[i]] = i;
    Module::Table<Transition> reordered;
    for (uint32_t t : order) {
      reordered.push_back(m->transitions[t]);
      Transition &tr = reordered.back();
      if (!tr.isForced())
        continue;
      std::vector<EventSource> evs(tr.events().begin(), tr.events().end());
      for (EventSource &s : evs)
        if (!s.fromPort)
          s.index = newIndex[s.index];
      tr.extras->events = d.copy(llvm::ArrayRef(evs));
    }
    m->transitions = std::move(reordered);
    reduce::compactModule(*m, std::vector<bool>(m->places.size(), true),
                          std::vector<bool>(m->transitions.size(), true),
                          std::vector<bool>(m->vars.size(), false));
    size_t copies = 0, setters = 0;
    for (uint32_t t = 0; t < nt; ++t) {
      copies += copiesOf[t].size();
      setters += settersOf[t].size();
    }
    stats.add("lower-data", "bits", bits.size(),
              "Boolean variables and outputs turned into place pairs");
    stats.add("lower-data", "copies", copies,
              "copies of transitions with data, one per condition combination");
    stats.add("lower-data", "setters", setters,
              "forced transitions setting or clearing a variable's place");
    return reduce::reverify(d, diag, "lower-data");
  }

private:
  std::string fresh(const std::string &base) {
    std::string n = base;
    for (unsigned i = 1; taken.count(n); ++i)
      n = base + "_" + std::to_string(i);
    taken.insert(n);
    return n;
  }

  bool collectBits(Module &m, DiagEngine &diag) {
    bool ok = true;
    for (uint32_t v = 0; v < m.vars.size(); ++v) {
      const Var &var = m.vars[v];
      if (var.type->isBool()) {
        auto init = net::initialValue(var);
        bits.push_back({{SymKind::Var, v}, var.name, var.loc, init && *init});
        continue;
      }
      ok = false;
      if (var.type->isClock())
        diag.error(var.loc, "lower-data: clock variable '" + var.name +
                                "' cannot become places (NCES keeps time on "
                                "arcs: a timed arc from a place)");
      else
        diag.error(var.loc, "lower-data: variable '" + var.name +
                                "' has type " + var.type->str() +
                                "; only Boolean data can become places");
    }
    for (uint32_t i = 0; i < m.ports.size(); ++i) {
      const Port &p = m.ports[i];
      if (p.kind == PortKind::Event)
        continue;
      if (p.kind == PortKind::Data && !p.type->isBool()) {
        ok = false;
        diag.error(p.loc, "lower-data: data port '" + p.name + "' has type " +
                              p.type->str() +
                              "; only Boolean data can become places");
        continue;
      }
      if (p.isStored()) {
        int64_t init = 0;
        if (p.init && !evalConstInt(p.init, init))
          if (auto *bl = dyn_cast<BoolLit>(p.init))
            init = bl->value;
        bits.push_back({{SymKind::Port, i}, p.name, p.loc, init != 0});
      }
    }
    for (uint32_t i = 0; i < bits.size(); ++i) {
      atomIndex[uint64_t(bits[i].sym.kind) << 32 | bits[i].sym.index] = i;
      atoms.push_back({bits[i].sym, int(i)});
    }
    return ok;
  }

  /// Two writers of one variable may share a step only when one is forced
  /// (under interleaving); the original reports that as a write conflict.
  bool checkWriters(const Module &m, DiagEngine &diag) {
    std::vector<std::vector<uint32_t>> writers(bits.size());
    net::forEachAssign(m, [&](const AssignStmt *a, int t) {
      Symbol s = net::targetRoot(a->target);
      auto it = atomIndex.find(uint64_t(s.kind) << 32 | s.index);
      if (it == atomIndex.end())
        return;
      auto &w = writers[atoms[it->second].bit];
      if (w.empty() || w.back() != uint32_t(t))
        w.push_back(uint32_t(t));
    });
    for (size_t bit = 0; bit < bits.size(); ++bit) {
      auto &w = writers[bit];
      if (w.size() < 2)
        continue;
      for (uint32_t t : w)
        if (m.transitions[t].isForced()) {
          uint32_t other = t == w[0] ? w[1] : w[0];
          diag.error(m.transitions[t].loc,
                     "lower-data: '" + bits[bit].name +
                         "' is written by forced transition '" +
                         m.transitions[t].name + "' and by '" +
                         m.transitions[other].name +
                         "'; a step holding both is a write conflict, "
                         "which places cannot express");
          return false;
        }
    }
    return true;
  }

  /// Conditions that are a place or a cond input (negated or not) stay;
  /// anything else, a guard or an action makes the transition lowered.
  bool needsLowering(const Module &m, const Transition &t) {
    if (t.guard() || t.hasAction())
      return true;
    for (const Expr *c : t.conds()) {
      if (auto *u = dyn_cast<UnaryExpr>(c))
        if (u->op == UnaryOp::Not)
          c = u->operand;
      auto *r = dyn_cast<Ref>(c);
      if (!r)
        return true;
      if (r->sym.kind == SymKind::Place)
        continue;
      if (r->sym.kind != SymKind::Port)
        return true;
      const Port &p = m.ports[r->sym.index];
      if (!p.isInput() || p.kind != PortKind::Cond)
        return true;
    }
    return false;
  }

  /// Splits on the atoms the conjunction `goal` reads until its value is
  /// known, depth first with false before true (stable order and names);
  /// calls `leaf` with each cube and the value there.
  bool expand(const Module &m, const Transition &t,
              llvm::ArrayRef<const Expr *> goal,
              llvm::function_ref<void(const Cube &, bool)> leaf,
              DiagEngine &diag) {
    Evaluator ev(m, atomIndex, atoms);
    std::vector<Cube> work{{}};
    size_t leaves = 0;
    while (!work.empty()) {
      Cube cube = std::move(work.back());
      work.pop_back();
      cube.resize(atoms.size(), -1);
      int64_t v = 1;
      Evaluator::Status st = Evaluator::Status::Done;
      for (const Expr *e : goal)
        if ((st = ev.run(e, t, cube, v)) != Evaluator::Status::Done || !v)
          break;
      if (st == Evaluator::Status::Error) {
        diag.error(ev.errorLoc, "lower-data: " + ev.error);
        return false;
      }
      if (st == Evaluator::Status::Split) {
        cube.resize(atoms.size(), -1);
        Cube one = cube;
        one[ev.splitAtom] = 1;
        cube[ev.splitAtom] = 0;
        work.push_back(std::move(one));
        work.push_back(std::move(cube));
        continue;
      }
      if (++leaves > kMaxCopies) {
        diag.error(t.loc, "lower-data: '" + t.name + "' depends on more than " +
                              std::to_string(kMaxCopies) +
                              " combinations of the signals it reads (one "
                              "transition each); reduce the model first");
        return false;
      }
      leaf(cube, v != 0);
    }
    return true;
  }

  /// Replaces transition `t` by copies for the combinations under which
  /// its conditions and guard hold, and by forced setters, one per
  /// combination under which its action gives a bit a new value.
  bool lowerTransition(Builder &b, Module &m, uint32_t t,
                       std::vector<uint32_t> &copies,
                       std::vector<uint32_t> &setters, DiagEngine &diag) {
    const Transition orig = m.transitions[t];
    std::vector<const Expr *> goal(orig.conds().begin(), orig.conds().end());
    if (orig.guard())
      goal.push_back(orig.guard());
    std::vector<Cube> enabling;
    if (!expand(
            m, orig, goal,
            [&](const Cube &c, bool v) {
              if (v)
                enabling.push_back(c);
            },
            diag))
      return false;
    for (size_t i = 0; i < std::max<size_t>(enabling.size(), 1); ++i) {
      std::string name =
          enabling.size() <= 1
              ? orig.name.str()
              : fresh(orig.name.str() + "_" + std::to_string(i + 1));
      std::vector<PreArc> pre(orig.pre().begin(), orig.pre().end());
      std::vector<PostArc> post(orig.post().begin(), orig.post().end());
      std::vector<Expr *> conds;
      if (enabling.empty())
        conds.push_back(b.boolLit(false, orig.loc)); // never enabled
      else
        literals(b, m, enabling[i], -1, conds);
      uint32_t n = b.addTransition(name, pre, post, orig.loc);
      if (!conds.empty())
        b.setConds(n, conds);
      if (orig.isForced())
        b.setEvents(n, orig.events(), orig.mode);
      if (!orig.emits().empty())
        b.setEmits(n, orig.emits());
      b.setUrgent(n, orig.urgent);
      copies.push_back(n);
    }
    if (enabling.empty() || !orig.hasAction())
      return true;

    SymbolicAction action(b, atoms, atomIndex, bits.size());
    if (!action.exec(orig.action(), diag))
      return false;
    std::vector<EventSource> byCopies;
    for (uint32_t c : copies)
      byCopies.push_back({c, false});
    StringRef prefix = orig.name.substr(0, orig.name.rfind('.') + 1);
    for (uint32_t bit = 0; bit < bits.size(); ++bit) {
      if (!action.env[bit])
        continue;
      const Bit &bt = bits[bit];
      // Combinations where the new value differs from the old one.
      std::vector<std::pair<Cube, bool>> changes;
      const Expr *value = action.env[bit];
      if (!expand(
              m, orig, {&value, 1},
              [&](const Cube &c, bool v) {
                if (c[bit] != int8_t(v))
                  changes.emplace_back(c, v);
              },
              diag))
        return false;
      std::string rel = bt.name.startswith(prefix)
                            ? bt.name.substr(prefix.size()).str()
                            : bt.name.str();
      std::replace(rel.begin(), rel.end(), '.', '_');
      for (bool v : {true, false}) {
        size_t count = llvm::count_if(
            changes, [&](const auto &ch) { return ch.second == v; });
        size_t k = 0;
        for (auto &[cube, value] : changes) {
          if (value != v)
            continue;
          std::string base =
              orig.name.str() + (v ? "_sets_" : "_clears_") + rel;
          std::string name =
              fresh(count == 1 ? base : base + "_" + std::to_string(++k));
          std::vector<Expr *> conds;
          literals(b, m, cube, int(bit), conds);
          uint32_t from = v ? bt.falsePlace : bt.truePlace;
          uint32_t to = v ? bt.truePlace : bt.falsePlace;
          uint32_t n = b.addTransition(name, {PreArc{from, 1, {}}},
                                       {PostArc{to, 1}}, orig.loc);
          if (!conds.empty())
            b.setConds(n, conds);
          b.setEvents(n, byCopies, EventMode::Or);
          setters.push_back(n);
        }
      }
    }
    return true;
  }

  /// The condition arcs testing `cube` (but not atom `skip`): a bit's
  /// place or its complement, a place or cond input or their negation.
  void literals(Builder &b, const Module &m, const Cube &cube, int skip,
                std::vector<Expr *> &conds) {
    for (size_t a = 0; a < cube.size(); ++a) {
      if (cube[a] < 0 || int(a) == skip)
        continue;
      bool value = cube[a];
      if (int bit = atoms[a].bit; bit >= 0) {
        const Bit &bt = bits[bit];
        conds.push_back(
            b.ref(m.places[value ? bt.truePlace : bt.falsePlace].name));
        continue;
      }
      Expr *r = b.ref(m.symbolName(atoms[a].sym));
      conds.push_back(value ? r : b.unary(UnaryOp::Not, r));
    }
  }

  /// Stored outputs become defined by their true place; Boolean data
  /// ports become cond ports; definitions read the places.
  void lowerPorts(Builder &b, Module &m) {
    llvm::DenseMap<uint64_t, StringRef> placeOf;
    for (const Bit &bit : bits)
      placeOf[uint64_t(bit.sym.kind) << 32 | bit.sym.index] =
          m.places[bit.truePlace].name;
    auto rename = [&](StringRef n) -> std::string {
      Symbol s = m.lookup(n);
      auto it = placeOf.find(uint64_t(s.kind) << 32 | s.index);
      return it == placeOf.end() ? n.str() : it->second.str();
    };
    for (uint32_t i = 0; i < m.ports.size(); ++i) {
      Port &p = m.ports[i];
      if (p.kind == PortKind::Event)
        continue;
      if (p.definition)
        p.definition = cloneExpr(b, m, p.definition, rename);
      else if (p.isOutput()) {
        p.definition = b.ref(rename(p.name), p.loc);
        p.definitionLoc = p.loc;
        p.init = nullptr;
      }
      p.kind = PortKind::Cond;
    }
  }

  PassOptions opts;
  llvm::StringSet<> taken;
  std::vector<Bit> bits;
  llvm::DenseMap<uint64_t, uint32_t> atomIndex;
  std::vector<Atom> atoms;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createLowerDataPass(const PassOptions &opts) {
  return std::make_unique<LowerDataPass>(opts);
}
} // namespace netlift
