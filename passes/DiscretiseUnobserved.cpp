//===- DiscretiseUnobserved.cpp - reals nothing observes are dropped ------===//
//
// A real that no guard, condition, output, invariant or observed real's
// rate or reset reads tells nothing apart: its position need not be
// followed, and its grid would only multiply the states. Such reals are
// common in benchmark models (a global time `tglobal` kept for plots, a
// variable local to a component template, a copy made by a reset). They
// are found as the complement of a fixpoint — observed: what the model
// reads, then whatever an observed real's rate or reset reads — and
// dropped with their flows and their assignments, each with a note. Nothing
// the model can see changes, so nothing is lost.
//
//===----------------------------------------------------------------------===//
#include "passes/Discretiser.h"

#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

bool Discretiser::dropUnobservedReals() {
  std::vector<bool> isReal(m.vars.size()), observed(m.vars.size());
  for (uint32_t i = 0; i < m.vars.size(); ++i)
    isReal[i] = m.vars[i].type->isReal() && !unfollowed.count(i);
  bool changed = false;
  auto observe = [&](const Expr *e) {
    walkExpr(e, [&](const Expr *x) {
      if (auto *r = llvm::dyn_cast<Ref>(x))
        if (r->sym.kind == SymKind::Var && isReal[r->sym.index] &&
            !observed[r->sym.index]) {
          observed[r->sym.index] = true;
          changed = true;
        }
    });
  };
  auto realTarget = [&](const AssignStmt *a) -> std::optional<uint32_t> {
    auto *t = llvm::dyn_cast<Ref>(a->target);
    if (t && t->sym.kind == SymKind::Var && isReal[t->sym.index])
      return t->sym.index;
    return std::nullopt;
  };
  // What the user says they observe (the SpaceEx configuration's
  // output-variables) is observed.
  for (const Attribute &a : m.attributes)
    if (a.key == kObservedAttribute) {
      Symbol s = m.lookup(a.target);
      if (s.kind == SymKind::Var && isReal[s.index])
        observed[s.index] = true;
    }
  do {
    changed = false;
    for (const Port &p : m.ports)
      observe(p.definition);
    for (const Var &v : m.vars)
      if (!v.type->isReal())
        observe(v.init);
    for (const Invariant &inv : m.invariants)
      for (const Expr *c : inv.conditions)
        observe(c);
    for (const Flow &f : m.flows)
      for (const Flow::Equation &eq : f.equations)
        if (eq.varIndex < observed.size() && observed[eq.varIndex]) {
          observe(eq.rate);
          observe(eq.rateHi);
        }
    for (const Transition &t : m.transitions) {
      for (const Expr *c : t.conds())
        observe(c);
      observe(t.guard());
      if (!t.hasAction())
        continue;
      for (const Stmt *s : t.action()) {
        auto *a = llvm::dyn_cast<AssignStmt>(s);
        std::optional<uint32_t> target = a ? realTarget(a) : std::nullopt;
        if (a && target && !observed[*target])
          continue; // read only if its real is observed
        forEachRead(Block(const_cast<Stmt **>(&s), 1), observe);
      }
    }
  } while (changed);
  std::set<uint32_t> dropped;
  for (uint32_t i = 0; i < m.vars.size(); ++i)
    if (isReal[i] && !observed[i])
      dropped.insert(i);
  if (dropped.empty())
    return true;
  for (uint32_t v : dropped)
    diag.note(m.vars[v].loc,
              "real '" + m.vars[v].name +
                  "' is read by no guard, condition, output, invariant or "
                  "observed real, nor plotted (output-variables): nothing "
                  "tells its values apart, and discretise drops it with its "
                  "flows and resets");
  removeReals(dropped);
  return true;
}

void Discretiser::removeReals(const std::set<uint32_t> &vars) {
  for (Flow &f : m.flows) {
    std::vector<Flow::Equation> kept;
    for (const Flow::Equation &eq : f.equations)
      if (!vars.count(eq.varIndex))
        kept.push_back(eq);
    f.equations = d.copy(llvm::ArrayRef<Flow::Equation>(kept));
  }
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    Transition &t = m.transitions[ti];
    if (!t.hasAction())
      continue;
    Block kept = dropAssignments(b, t.action(), [&](const AssignStmt *a) {
      auto *target = llvm::dyn_cast<Ref>(a->target);
      return !target || target->sym.kind != SymKind::Var ||
             !vars.count(target->sym.index);
    });
    b.setAction(ti, kept);
  }
  // They need no position: collectReals skips them, and finish() removes
  // every real variable.
  unfollowed.insert(vars.begin(), vars.end());
}
