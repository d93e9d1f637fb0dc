//===- AbstractTimers.cpp - timers whose elapsed time is not counted ------===//
//
// `abstract-timers` rewrites each clock variable c of cap N that the module
// only compares (`c >= PT`, in actions; never in a guard, an output or an
// initial value) into
//
//   var   c : 0..N                the value c was last set to
//   clock c.ticked : 0..1         a tick has passed since
//   data input c.reading : 0..N   the abstract reading, free
//
// `c := e` also clears c.ticked, and a comparison `c OP e` becomes
//
//   (c.ticked == 0 or c.reading < c) and c OP e
//     or not (c.ticked == 0 or c.reading < c) and c.reading OP e
//
// so that, once a tick has passed, c reads as any value in [c, N]: the
// exact clock, which counts ticks from the value it was set to and
// saturates at N, reads as one of them. Every read of the input is a
// comparison operand, so input splitting cuts it at the compared values
// only (two or three classes), whatever N is.
//
// A clock read any other way keeps its exact model and a note says where
// (a timer's ET the program uses). One exception: `x := c` where nothing
// reads x and every step ends by setting x to its initial value (a timer
// output nobody reads, reset after the scan) is a store nobody sees; it
// becomes `x := <initial value>`.
//
// Guards never read an abstracted clock, so a state's enabled transitions
// and ticks are those of the exact states it stands for: a deadlock of the
// exact model is one of the abstract model.
//
//===----------------------------------------------------------------------===//
#include "passes/AbstractTimers.h"
#include "passes/Pass.h"
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"
#include "ir/net/Clone.h"
#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::net;
using llvm::dyn_cast;
using llvm::dyn_cast_or_null;

std::string netlift::abstractReadingInput(llvm::StringRef clock) {
  return clock.str() + ".reading";
}

std::string netlift::abstractTickedFlag(llvm::StringRef clock) {
  return clock.str() + ".ticked";
}

namespace {

/// The analysis and rewrite of one module.
class TimerAbstractor {
public:
  TimerAbstractor(Design &d, Module &m) : d(d), m(m), b(d) { b.setModule(&m); }

  void analyse(const std::set<std::string> &keep);
  void rewrite(TimerAbstraction &result);

  /// Per variable: the reason its clock stays exact, and where.
  std::vector<std::string> why;
  std::vector<llvm::SMLoc> whyLoc;
  /// Per clock kept exact: a variable its value is stored in (a timer's
  /// ET), whose reads are where the program uses it; -1 if none.
  std::vector<int> storedInto;

private:
  /// The clock variable `e` denotes, or -1.
  int clockRef(const Expr *e) const {
    auto *r = dyn_cast<Ref>(e);
    return r && r->sym.kind == SymKind::Var &&
                   m.vars[r->sym.index].type->isClock()
               ? int(r->sym.index)
               : -1;
  }
  bool readsClock(const Expr *e) const {
    bool found = false;
    walkExpr(e, [&](const Expr *x) { found |= clockRef(x) >= 0; });
    return found;
  }
  void disqualify(int c, llvm::SMLoc at, llvm::StringRef reason) {
    if (why[c].empty()) {
      why[c] = reason.str();
      whyLoc[c] = at;
    }
  }
  void findScratch();
  void visitRead(const Expr *e, const Expr *parent,
                 const std::set<const Expr *> &deadStores);
  void rewriteComparisons(Expr *e);
  Stmt *settle(uint32_t c, llvm::SMLoc at);

  Design &d;
  Module &m;
  Builder b;
  /// Variables nothing reads that every step writing them ends by setting
  /// to this constant (their initial value).
  std::vector<std::optional<int64_t>> scratch;
  std::vector<bool> abstracted;
};

void TimerAbstractor::findScratch() {
  reduce::Uses uses(m);
  scratch.assign(m.vars.size(), std::nullopt);
  for (uint32_t v = 0; v < m.vars.size(); ++v) {
    const Type *t = m.vars[v].type;
    if (uses.varRead[v] || uses.writers[v].empty() || t->isClock() ||
        (!t->isInteger() && !t->isBool()))
      continue;
    std::optional<int64_t> init = initialValue(m.vars[v]);
    bool ok = init.has_value();
    for (uint32_t t : uses.writers[v]) {
      // The last top-level statement writing v must be `v := init`.
      const Stmt *last = nullptr;
      for (const Stmt *s : m.transitions[t].action()) {
        bool writes = false;
        forEachAssign(Block(const_cast<Stmt **>(&s), 1),
                      [&](const AssignStmt *a) {
                        Symbol root = targetRoot(a->target);
                        writes |= root.kind == SymKind::Var && root.index == v;
                      });
        if (writes)
          last = s;
      }
      auto *a = dyn_cast_or_null<AssignStmt>(last);
      int64_t k;
      ok &= a && llvm::isa<Ref>(a->target) && evalConstInt(a->value, k) &&
            k == *init;
    }
    if (ok)
      scratch[v] = init;
  }
}

void TimerAbstractor::visitRead(const Expr *e, const Expr *parent,
                                const std::set<const Expr *> &deadStores) {
  int c = clockRef(e);
  if (c >= 0) {
    auto *cmp = dyn_cast_or_null<BinaryExpr>(parent);
    bool compared = cmp && isComparison(cmp->op) &&
                    !readsClock(cmp->lhs == e ? cmp->rhs : cmp->lhs);
    if (!compared && !(parent == nullptr && deadStores.count(e)))
      disqualify(c, e->loc, "its value is read here");
    return;
  }
  forEachOperand(e, [&](const Expr *x) { visitRead(x, e, deadStores); });
}

void TimerAbstractor::analyse(const std::set<std::string> &keep) {
  size_t nv = m.vars.size();
  why.assign(nv, "");
  whyLoc.assign(nv, {});
  storedInto.assign(nv, -1);
  findScratch();
  for (uint32_t v = 0; v < nv; ++v)
    if (m.vars[v].type->isClock() && keep.count(m.vars[v].name.str()))
      disqualify(v, m.vars[v].loc, "kept exact");
  auto anyClock = [&](const Expr *root, llvm::StringRef reason) {
    walkExpr(root, [&](const Expr *x) {
      if (int c = clockRef(x); c >= 0)
        disqualify(c, x->loc, reason);
    });
  };
  for (const Transition &t : m.transitions) {
    if (t.guard())
      anyClock(t.guard(), "it is read in a guard here");
    for (const Expr *c : t.conds())
      anyClock(c, "it is read in a condition here");
    Block action = t.action();
    std::set<const Expr *> deadStores;
    forEachAssign(action, [&](const AssignStmt *a) {
      Symbol root = targetRoot(a->target);
      int c = clockRef(a->value);
      if (c < 0 || !llvm::isa<Ref>(a->target) || root.kind != SymKind::Var)
        return;
      if (scratch[root.index])
        deadStores.insert(a->value);
      else if (why[c].empty())
        storedInto[c] = int(root.index); // say where that one is read
    });
    forEachRead(action,
                [&](const Expr *e) { visitRead(e, nullptr, deadStores); });
  }
  forEachRead(m, [&](const Expr *root, int t) {
    if (t < 0)
      anyClock(root, "it is read outside the actions here");
  });
  // A clock stored into a variable (a timer's ET) is used where that
  // variable is read: the program's own text, not the timer's.
  for (uint32_t c = 0; c < nv; ++c) {
    if (storedInto[c] < 0 || why[c] != "its value is read here")
      continue;
    llvm::StringRef holder = m.vars[storedInto[c]].name;
    std::optional<llvm::SMLoc> readAt;
    forEachRead(m, [&](const Expr *root, int) {
      walkExpr(root, [&](const Expr *x) {
        auto *r = dyn_cast<Ref>(x);
        if (!readAt && r && r->sym.kind == SymKind::Var &&
            int(r->sym.index) == storedInto[c])
          readAt = x->loc;
      });
    });
    if (readAt) {
      why[c] = "'" + holder.str() + "' holds its value and is read here";
      whyLoc[c] = *readAt;
    }
  }
}

void TimerAbstractor::rewriteComparisons(Expr *e) {
  if (auto *cmp = dyn_cast<BinaryExpr>(e); cmp && isComparison(cmp->op)) {
    int c = clockRef(cmp->lhs);
    bool left = c >= 0;
    if (!left)
      c = clockRef(cmp->rhs);
    if (c >= 0 && abstracted[c]) {
      llvm::StringRef name = m.vars[c].name;
      llvm::SMLoc at = cmp->loc;
      auto identity = [](llvm::StringRef n) { return n.str(); };
      Expr *other = left ? cmp->rhs : cmp->lhs;
      Expr *reading = b.ref(abstractReadingInput(name), at);
      Expr *otherCopy = cloneExpr(b, m, other, identity);
      Expr *readCmp = left ? b.binary(cmp->op, reading, otherCopy, at)
                           : b.binary(cmp->op, otherCopy, reading, at);
      Expr *setCmp = b.binary(cmp->op, cmp->lhs, cmp->rhs, at);
      auto settled = [&] {
        return b.binary(
            BinaryOp::Or,
            b.binary(BinaryOp::Eq, b.ref(abstractTickedFlag(name), at),
                     b.intLit(0, at), at),
            b.binary(BinaryOp::Lt, b.ref(abstractReadingInput(name), at),
                     b.ref(name, at), at),
            at);
      };
      cmp->op = BinaryOp::Or;
      cmp->lhs = b.binary(BinaryOp::And, settled(), setCmp, at);
      cmp->rhs = b.binary(BinaryOp::And, b.unary(UnaryOp::Not, settled(), at),
                          readCmp, at);
      return;
    }
  }
  forEachOperand(
      e, [&](const Expr *x) { rewriteComparisons(const_cast<Expr *>(x)); });
}

/// `c.ticked := c >= N ? 1 : 0` after `c := e`: a clock set to its cap
/// reads as the cap whether or not a tick passes, so it is marked as
/// ticked at once and the next tick leaves the state as it is (as the
/// exact clock, saturated, does).
Stmt *TimerAbstractor::settle(uint32_t c, llvm::SMLoc at) {
  llvm::StringRef name = m.vars[c].name;
  return b.assign(b.ref(abstractTickedFlag(name), at),
                  b.cond(b.binary(BinaryOp::Ge, b.ref(name, at),
                                  b.intLit(m.vars[c].type->hi, at), at),
                         b.intLit(1, at), b.intLit(0, at), at),
                  at);
}

void TimerAbstractor::rewrite(TimerAbstraction &result) {
  size_t nv = m.vars.size();
  abstracted.assign(nv, false);
  for (uint32_t v = 0; v < nv; ++v) {
    if (!m.vars[v].type->isClock())
      continue;
    if (why[v].empty()) {
      abstracted[v] = true;
      result.abstracted.push_back(m.vars[v].name.str());
    } else {
      result.kept.push_back({m.vars[v].name.str(), why[v]});
    }
  }
  if (result.abstracted.empty())
    return;
  for (Transition &t : m.transitions) {
    if (!t.hasAction())
      continue;
    forEachRead(t.action(), [&](const Expr *e) {
      rewriteComparisons(const_cast<Expr *>(e));
    });
    t.extras->action = rewriteAssignments(
        b, t.action(), [&](AssignStmt *a, std::vector<Stmt *> &out) {
          Symbol root = targetRoot(a->target);
          int c = clockRef(a->value);
          if (c >= 0 && abstracted[c] && root.kind == SymKind::Var &&
              scratch[root.index])
            a->value = b.intLit(*scratch[root.index], a->value->loc);
          out.push_back(a);
          if (root.kind == SymKind::Var && abstracted[root.index])
            out.push_back(settle(root.index, a->loc));
        });
  }
  for (uint32_t v = 0; v < nv; ++v) {
    if (!abstracted[v])
      continue;
    // Copied: adding entities may move the variable table.
    std::string name = m.vars[v].name.str();
    llvm::SMLoc at = m.vars[v].loc;
    int64_t cap = m.vars[v].type->hi;
    std::optional<int64_t> init = initialValue(m.vars[v]);
    m.vars[v].type = d.types.getRange(0, cap);
    b.addVar(abstractTickedFlag(name), d.types.getClock(1),
             b.intLit(init && *init >= cap ? 1 : 0, at), at);
    b.addPort(abstractReadingInput(name), PortKind::Data, PortDir::In,
              d.types.getRange(0, cap), at);
  }
}

} // namespace

bool netlift::abstractTimers(Design &d, Module &m,
                             const std::set<std::string> &keep,
                             DiagEngine &diag, bool notes,
                             TimerAbstraction &result) {
  for (const Var &v : m.vars)
    if (v.type->isClock())
      for (const char *suffix : {".reading", ".ticked"})
        if (m.lookup(v.name.str() + suffix).kind != SymKind::None) {
          diag.error(v.loc, "abstract-timers: '" + v.name + suffix +
                                "' is taken; the clock's abstraction needs "
                                "that name");
          return false;
        }
  TimerAbstractor a(d, m);
  a.analyse(keep);
  if (notes)
    for (uint32_t v = 0; v < m.vars.size(); ++v)
      if (m.vars[v].type->isClock() && !a.why[v].empty() &&
          a.why[v] != "kept exact")
        diag.note(a.whyLoc[v], "clock '" + m.vars[v].name +
                                   "' keeps its exact time (a timer whose "
                                   "ET is used): " +
                                   a.why[v]);
  a.rewrite(result);
  return result.abstracted.empty() ||
         reduce::reverify(d, diag, "abstract-timers");
}

namespace {

class AbstractTimersPass : public Pass {
public:
  explicit AbstractTimersPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "abstract-timers");
    if (!m)
      return false;
    std::vector<std::string> kept = opts.list("keep");
    TimerAbstraction result;
    if (!abstractTimers(d, *m, {kept.begin(), kept.end()}, diag, true, result))
      return false;
    stats.add("abstract-timers", "abstracted", result.abstracted.size(),
              "clock variables abstracted");
    stats.add("abstract-timers", "exact", result.kept.size(),
              "clock variables kept exact");
    return true;
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createAbstractTimersPass(const PassOptions &opts) {
  return std::make_unique<AbstractTimersPass>(opts);
}
} // namespace netlift
