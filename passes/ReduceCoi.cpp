//===- ReduceCoi.cpp - cut a model to the cone of influence ---------------===//
//
// `reduce-coi{observe=a,b,...}` keeps what can influence the observed
// places, variables and ports (default: every output of the module) and
// removes the rest. Relevance grows to a fixpoint:
//  - a transition is relevant if it has an arc to or from a relevant place,
//    assigns a relevant variable or stored output, emits a relevant event
//    output, is the event source of a relevant transition, or is urgent (an
//    urgent transition stops time, which every timed element observes);
//  - everything a relevant transition reads is relevant: the places of its
//    arcs (their tokens and capacities enable it), its condition arcs and
//    guard, and in its action the conditions and selectors of `if`/`case`
//    and the values assigned to relevant targets; so is everything a
//    relevant output's definition reads.
// Irrelevant transitions, places, variables and outputs go, and relevant
// transitions lose their assignments to irrelevant variables and outputs.
// Inputs all stay (the environment is unchanged).
//
// Preserved: the set of reachable valuations of the observed elements, and
// every property over them that does not count steps (CTL/LTL without next):
// the removed part never changes a kept element, so every run of the
// original projects onto a run of the reduced model and back, up to steps
// that changed only removed elements. Not preserved: deadlocks caused or
// avoided by the removed part alone (a state where only a removed
// transition could fire becomes a deadlock), and runtime errors (write
// conflicts, range errors) in removed variables.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;
using llvm::dyn_cast;
using llvm::StringRef;

namespace {

class Cone {
public:
  Cone(Module &m)
      : m(m), place(m.places.size()), var(m.vars.size()), port(m.ports.size()),
        trans(m.transitions.size()) {}
  Module &m;
  std::vector<bool> place, var, port, trans;
  bool changed = false;

  void mark(std::vector<bool> &v, uint32_t i) {
    if (!v[i]) {
      v[i] = true;
      changed = true;
    }
  }
  void readExpr(const Expr *e) {
    net::walkExpr(e, [&](const Expr *x) {
      auto *r = dyn_cast<Ref>(x);
      if (!r)
        return;
      if (r->sym.kind == SymKind::Place)
        mark(place, r->sym.index);
      else if (r->sym.kind == SymKind::Var)
        mark(var, r->sym.index);
      else if (r->sym.kind == SymKind::Port)
        mark(port, r->sym.index);
    });
  }
  bool targetRelevant(const AssignStmt *a) const {
    Symbol s = net::targetRoot(a->target);
    return (s.kind == SymKind::Var && var[s.index]) ||
           (s.kind == SymKind::Port && port[s.index]);
  }
  void readBlock(Block b) {
    for (const Stmt *s : b) {
      switch (s->getKind()) {
      case StmtKind::Assign: {
        auto *a = cast<AssignStmt>(s);
        if (targetRelevant(a)) {
          readExpr(a->value);
          readExpr(a->target); // indices (and the root, already relevant)
        }
        break;
      }
      case StmtKind::If:
        for (const IfArm &arm : cast<IfStmt>(s)->arms) {
          readExpr(arm.cond);
          readBlock(arm.body);
        }
        readBlock(cast<IfStmt>(s)->elseBody);
        break;
      case StmtKind::Case: {
        auto *c = cast<CaseStmt>(s);
        readExpr(c->selector);
        for (const CaseArm &arm : c->arms)
          readBlock(arm.body);
        readBlock(c->elseBody);
        break;
      }
      case StmtKind::For: {
        // Run-time bounds decide how often the body writes.
        auto *f = cast<ForStmt>(s);
        readExpr(f->lo);
        readExpr(f->hi);
        readBlock(f->body);
        break;
      }
      case StmtKind::While:
        readExpr(cast<WhileStmt>(s)->cond);
        readBlock(cast<WhileStmt>(s)->body);
        break;
      }
    }
  }
  bool writesRelevant(const Transition &t) const {
    bool any = false;
    net::forEachAssign(t.action(),
                       [&](const AssignStmt *a) { any |= targetRelevant(a); });
    return any;
  }

  void run() {
    do {
      changed = false;
      for (uint32_t p = 0; p < m.ports.size(); ++p)
        if (port[p] && m.ports[p].definition)
          readExpr(m.ports[p].definition);
      for (uint32_t t = 0; t < m.transitions.size(); ++t) {
        const Transition &tr = m.transitions[t];
        bool rel = trans[t] || tr.urgent || writesRelevant(tr);
        for (const PreArc &a : tr.pre())
          rel |= place[a.place];
        for (const PostArc &a : tr.post())
          rel |= place[a.place];
        for (uint32_t e : tr.emits())
          rel |= port[e];
        if (!rel)
          continue;
        mark(trans, t);
        for (const PreArc &a : tr.pre())
          mark(place, a.place);
        for (const PostArc &a : tr.post())
          mark(place, a.place);
        for (const Expr *c : tr.conds())
          readExpr(c);
        readExpr(tr.guard());
        readBlock(tr.action());
        for (const EventSource &s : tr.events()) {
          if (s.fromPort)
            mark(port, s.index);
          else
            mark(trans, s.index);
        }
      }
    } while (changed);
  }
};

class ReduceCoiPass : public Pass {
public:
  explicit ReduceCoiPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce-coi");
    if (!m)
      return false;
    Cone cone(*m);
    auto observed = reduce::observedElements(*m, opts, "reduce-coi", diag);
    if (!observed)
      return false;
    cone.place = observed->place;
    cone.var = observed->var;
    cone.port = observed->port;
    cone.trans = observed->trans;
    // Inputs are the environment: they stay whatever happens.
    for (uint32_t p = 0; p < m->ports.size(); ++p)
      if (m->ports[p].isInput())
        cone.port[p] = true;
    cone.run();

    unsigned removedT = 0, removedP = 0, removedV = 0, removedO = 0;
    for (bool k : cone.trans)
      removedT += !k;
    for (bool k : cone.place)
      removedP += !k;
    for (bool k : cone.var)
      removedV += !k;
    for (bool k : cone.port)
      removedO += !k;
    stats.add("reduce-coi", "transitions", removedT,
              "transitions outside the cone of influence removed");
    stats.add("reduce-coi", "places", removedP,
              "places outside the cone of influence removed");
    stats.add("reduce-coi", "variables", removedV,
              "variables outside the cone of influence removed");
    stats.add("reduce-coi", "outputs", removedO,
              "outputs outside the cone of influence removed");
    if (!removedT && !removedP && !removedV && !removedO)
      return true;
    Builder b(d);
    b.setModule(m);
    for (Transition &t : m->transitions)
      if (t.extras && t.extras->hasAction)
        t.extras->action =
            net::dropAssignments(b, t.extras->action, [&](const AssignStmt *a) {
              return cone.targetRelevant(a);
            });
    reduce::removePorts(d, *m, cone.port);
    reduce::compactModule(*m, cone.place, cone.trans, cone.var);
    return reduce::reverify(d, diag, "reduce-coi");
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReduceCoiPass(const PassOptions &opts) {
  return std::make_unique<ReduceCoiPass>(opts);
}
} // namespace netlift
