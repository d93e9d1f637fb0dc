//===- ReduceDead.cpp - remove what can never happen ----------------------===//
//
// `reduce-dead` removes transitions that can never be enabled and places
// that can never be marked, found by a structural fixpoint that
// over-approximates what is possible: a place is markable if it starts
// marked or a possibly firing transition puts a token into it; a transition
// may fire if all its pre-places are markable, no condition arc is the
// constant `false` or a place that is never markable (a conjunct of the
// arc), its guard is not the constant `false`, and, when forced, one (`|`)
// or every (`&`) event source may fire (an event input always may: it is
// the environment). Places nothing can mark, that no expression names,
// go too; a named one stays (it is always empty, and properties may name
// it).
//
// A transition with a deadline arc that may be enabled is kept even if it
// never fires, with its event sources: enabled, it blocks time.
//
// Preserved: the state space exactly — every reachable state and step,
// up to the removed places, which are empty in every reachable state, and
// the removed transitions, which never fire. Tokens, time, data and
// deadlocks are unchanged.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

using namespace netlift;
using namespace netlift::net;
using llvm::dyn_cast;

namespace {

/// The conjuncts of a condition that require a place to be marked, and
/// whether the condition is the constant false.
void placeConjuncts(const Expr *e, std::vector<uint32_t> &places,
                    bool &isFalse) {
  if (auto *b = dyn_cast<BoolLit>(e)) {
    if (!b->value)
      isFalse = true;
    return;
  }
  if (auto *r = dyn_cast<Ref>(e)) {
    if (r->sym.kind == SymKind::Place)
      places.push_back(r->sym.index);
    return;
  }
  if (auto *x = dyn_cast<BinaryExpr>(e))
    if (x->op == BinaryOp::And) {
      placeConjuncts(x->lhs, places, isFalse);
      placeConjuncts(x->rhs, places, isFalse);
    }
}

class ReduceDeadPass : public Pass {
public:
  explicit ReduceDeadPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce-dead");
    if (!m)
      return false;
    size_t np = m->places.size(), nt = m->transitions.size();
    std::vector<bool> markable(np), fireable(nt);
    for (size_t p = 0; p < np; ++p)
      markable[p] = m->places[p].tokens > 0;
    // Static part of each transition's enabling.
    std::vector<std::vector<uint32_t>> needs(nt);
    std::vector<bool> never(nt);
    for (size_t t = 0; t < nt; ++t) {
      const Transition &tr = m->transitions[t];
      bool isFalse = false;
      for (const PreArc &a : tr.pre())
        needs[t].push_back(a.place);
      for (const Expr *c : tr.conds())
        placeConjuncts(c, needs[t], isFalse);
      if (tr.guard())
        placeConjuncts(tr.guard(), needs[t], isFalse);
      never[t] = isFalse;
    }
    for (bool changed = true; changed;) {
      changed = false;
      for (size_t t = 0; t < nt; ++t) {
        if (fireable[t] || never[t])
          continue;
        const Transition &tr = m->transitions[t];
        bool ok =
            llvm::all_of(needs[t], [&](uint32_t p) { return markable[p]; });
        if (ok && tr.isForced()) {
          auto fires = [&](const EventSource &s) {
            return s.fromPort || fireable[s.index];
          };
          ok = tr.mode == EventMode::And ? llvm::all_of(tr.events(), fires)
                                         : llvm::any_of(tr.events(), fires);
        }
        if (!ok)
          continue;
        fireable[t] = true;
        changed = true;
        for (const PostArc &a : tr.post())
          markable[a.place] = true;
      }
    }
    // A transition with a deadline blocks time while it is enabled, fired
    // or not (a discretised invariant's stop waits for an event that never
    // comes): kept when it can be enabled, with what it listens to.
    std::vector<bool> keep = fireable;
    std::vector<uint32_t> work;
    for (size_t t = 0; t < nt; ++t) {
      const Transition &tr = m->transitions[t];
      bool deadline = llvm::any_of(
          tr.pre(), [](const PreArc &a) { return a.time.deadline; });
      if (!keep[t] && deadline && !never[t] &&
          llvm::all_of(needs[t], [&](uint32_t p) { return markable[p]; })) {
        keep[t] = true;
        work.push_back(uint32_t(t));
      }
    }
    while (!work.empty()) {
      uint32_t t = work.back();
      work.pop_back();
      for (const EventSource &s : m->transitions[t].events())
        if (!s.fromPort && !keep[s.index]) {
          keep[s.index] = true;
          work.push_back(s.index);
        }
    }
    reduce::Uses uses(*m);
    std::vector<bool> keepPlace(np), keepVar(m->vars.size(), true);
    for (size_t t = 0; t < nt; ++t)
      if (keep[t] && !fireable[t]) {
        for (const PreArc &a : m->transitions[t].pre())
          keepPlace[a.place] = true;
        for (const PostArc &a : m->transitions[t].post())
          keepPlace[a.place] = true;
      }
    unsigned places = 0, transitions = 0;
    for (size_t p = 0; p < np; ++p) {
      keepPlace[p] = keepPlace[p] || markable[p] || uses.placeRead[p];
      places += !keepPlace[p];
    }
    for (size_t t = 0; t < nt; ++t)
      transitions += !keep[t];
    stats.add("reduce-dead", "transitions", transitions,
              "transitions that can never fire removed");
    stats.add("reduce-dead", "places", places,
              "places that can never be marked removed");
    if (!places && !transitions)
      return true;
    reduce::compactModule(*m, keepPlace, keep, keepVar);
    return reduce::reverify(d, diag, "reduce-dead");
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReduceDeadPass(const PassOptions &opts) {
  return std::make_unique<ReduceDeadPass>(opts);
}
} // namespace netlift
