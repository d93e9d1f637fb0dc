//===- ReduceSupport.cpp - what the reduction passes share ----------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Verifier.h"

using namespace netlift;
using namespace netlift::net;
using llvm::cast;
using llvm::dyn_cast;
using llvm::StringRef;

Module *reduce::flatTop(Design &d, DiagEngine &diag, const PassOptions &opts,
                        StringRef pass) {
  // Passes before this one may have left names unresolved (clones are
  // resolved by the verifier); the analyses below read resolved names.
  if (!reverify(d, diag, pass))
    return nullptr;
  std::string why;
  Module *m = d.findTop(opts.text("top"), why);
  if (!m) {
    llvm::errs() << "netlift: error: " << pass << ": " << why << "\n";
    return nullptr;
  }
  if (!m->instances.empty()) {
    llvm::errs() << "netlift: error: " << pass << ": '" << m->name
                 << "' has instances; reductions work on a flat module "
                    "(run flatten first: -p 'flatten,"
                 << pass << "')\n";
    return nullptr;
  }
  if (hasHybridParts(*m)) {
    llvm::errs() << "netlift: error: " << pass << ": '" << m->name
                 << "' has real variables; run discretise first\n";
    return nullptr;
  }
  return m;
}

void reduce::walkExpr(const Expr *e, llvm::function_ref<void(const Expr *)> f) {
  if (!e)
    return;
  f(e);
  switch (e->getKind()) {
  case ExprKind::Index:
    walkExpr(cast<IndexExpr>(e)->base, f);
    walkExpr(cast<IndexExpr>(e)->index, f);
    break;
  case ExprKind::Field:
    walkExpr(cast<FieldExpr>(e)->base, f);
    break;
  case ExprKind::Unary:
    walkExpr(cast<UnaryExpr>(e)->operand, f);
    break;
  case ExprKind::Binary:
    walkExpr(cast<BinaryExpr>(e)->lhs, f);
    walkExpr(cast<BinaryExpr>(e)->rhs, f);
    break;
  case ExprKind::Cond:
    walkExpr(cast<CondExpr>(e)->cond, f);
    walkExpr(cast<CondExpr>(e)->thenExpr, f);
    walkExpr(cast<CondExpr>(e)->elseExpr, f);
    break;
  case ExprKind::Call:
    for (const Expr *a : cast<CallExpr>(e)->args)
      walkExpr(a, f);
    break;
  default:
    break;
  }
}

namespace {
/// Visits a block: `read` for every expression evaluated, `assign` for
/// every assignment.
void walkBlock(Block b, int t, llvm::function_ref<void(const Expr *, int)> read,
               llvm::function_ref<void(const AssignStmt *, int)> assign) {
  for (const Stmt *s : b) {
    switch (s->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(s);
      if (assign)
        assign(a, t);
      if (read) {
        read(a->value, t);
        // Indices inside the target are read; the root is written.
        for (const Expr *x = a->target; x;) {
          if (auto *ix = dyn_cast<IndexExpr>(x)) {
            read(ix->index, t);
            x = ix->base;
          } else if (auto *fe = dyn_cast<FieldExpr>(x)) {
            x = fe->base;
          } else {
            x = nullptr;
          }
        }
      }
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      for (const IfArm &arm : i->arms) {
        if (read)
          read(arm.cond, t);
        walkBlock(arm.body, t, read, assign);
      }
      walkBlock(i->elseBody, t, read, assign);
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      if (read)
        read(c->selector, t);
      for (const CaseArm &arm : c->arms) {
        if (read)
          for (const CaseLabel &l : arm.labels) {
            read(l.lo, t);
            if (l.hi)
              read(l.hi, t);
          }
        walkBlock(arm.body, t, read, assign);
      }
      walkBlock(c->elseBody, t, read, assign);
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      if (read) {
        read(f->lo, t);
        read(f->hi, t);
      }
      walkBlock(f->body, t, read, assign);
      break;
    }
    }
  }
}
} // namespace

void reduce::forEachRead(const Module &m,
                         llvm::function_ref<void(const Expr *, int)> f) {
  for (const Port &p : m.ports) {
    if (p.definition)
      f(p.definition, -1);
    if (p.init)
      f(p.init, -1);
  }
  for (const Var &v : m.vars)
    if (v.init)
      f(v.init, -1);
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    const Transition &tr = m.transitions[t];
    for (const Expr *c : tr.conds())
      f(c, int(t));
    if (tr.guard())
      f(tr.guard(), int(t));
    walkBlock(tr.action(), int(t), f, nullptr);
  }
}

void reduce::forEachAssign(
    const Module &m, llvm::function_ref<void(const AssignStmt *, int)> f) {
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    walkBlock(m.transitions[t].action(), int(t), nullptr, f);
}

Block reduce::dropAssignments(
    Builder &b, Block blk, llvm::function_ref<bool(const AssignStmt *)> keep) {
  std::vector<Stmt *> out;
  Design &d = b.getDesign();
  for (Stmt *s : blk) {
    if (auto *a = dyn_cast<AssignStmt>(s)) {
      if (keep(a))
        out.push_back(s);
    } else if (auto *i = dyn_cast<IfStmt>(s)) {
      std::vector<IfArm> arms;
      for (const IfArm &arm : i->arms)
        arms.push_back({arm.cond, dropAssignments(b, arm.body, keep)});
      out.push_back(b.ifStmt(arms, i->hasElse,
                             dropAssignments(b, i->elseBody, keep), s->loc));
    } else if (auto *c = dyn_cast<CaseStmt>(s)) {
      std::vector<CaseArm> arms;
      for (const CaseArm &arm : c->arms)
        arms.push_back({arm.labels, dropAssignments(b, arm.body, keep)});
      out.push_back(b.caseStmt(c->selector, arms, c->hasElse,
                               dropAssignments(b, c->elseBody, keep), s->loc));
    } else if (auto *f = dyn_cast<ForStmt>(s)) {
      out.push_back(b.forStmt(f->var, f->lo, f->hi,
                              dropAssignments(b, f->body, keep), s->loc));
    }
  }
  return d.copy(llvm::ArrayRef<Stmt *>(out));
}

void reduce::forEachAssign(Block block,
                           llvm::function_ref<void(const AssignStmt *)> f) {
  walkBlock(block, -1, nullptr, [&](const AssignStmt *a, int) { f(a); });
}

std::optional<int64_t> reduce::initialValue(const Var &v) {
  const Type *t = v.type;
  if (!v.init)
    return t->kind == TypeKind::Range ? t->lo : 0;
  if (auto *bl = dyn_cast<BoolLit>(v.init))
    return bl->value;
  if (auto *r = dyn_cast<Ref>(v.init))
    if (r->sym.kind == SymKind::EnumLit)
      return r->sym.index;
  int64_t x;
  if (evalConstInt(v.init, x))
    return x;
  return std::nullopt;
}

Symbol reduce::targetRoot(const Expr *target) {
  for (const Expr *x = target; x;) {
    if (auto *r = dyn_cast<Ref>(x))
      return r->sym;
    if (auto *ix = dyn_cast<IndexExpr>(x))
      x = ix->base;
    else if (auto *fe = dyn_cast<FieldExpr>(x))
      x = fe->base;
    else
      break;
  }
  return {};
}

reduce::Uses::Uses(const Module &m)
    : writers(m.vars.size()), varRead(m.vars.size()),
      placeRead(m.places.size()) {
  forEachRead(m, [&](const Expr *e, int) {
    walkExpr(e, [&](const Expr *x) {
      if (auto *r = dyn_cast<Ref>(x)) {
        if (r->sym.kind == SymKind::Var)
          varRead[r->sym.index] = true;
        else if (r->sym.kind == SymKind::Place)
          placeRead[r->sym.index] = true;
      }
    });
  });
  forEachAssign(m, [&](const AssignStmt *a, int t) {
    Symbol s = targetRoot(a->target);
    if (s.kind == SymKind::Var) {
      auto &w = writers[s.index];
      if (w.empty() || w.back() != uint32_t(t))
        w.push_back(uint32_t(t));
    }
  });
}

void reduce::compactModule(Module &m, const std::vector<bool> &keepPlace,
                           const std::vector<bool> &keepTrans,
                           const std::vector<bool> &keepVar) {
  std::vector<uint32_t> placeMap(m.places.size(), UINT32_MAX);
  std::vector<uint32_t> transMap(m.transitions.size(), UINT32_MAX);
  uint32_t n = 0;
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (keepPlace[p]) {
      placeMap[p] = n;
      m.places[n++] = m.places[p];
    }
  m.places.resize(n);
  n = 0;
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    if (keepTrans[t]) {
      transMap[t] = n;
      m.transitions[n++] = m.transitions[t];
    }
  m.transitions.resize(n);
  for (Transition &t : m.transitions) {
    for (PreArc &a : t.mutablePre())
      a.place = placeMap[a.place];
    for (PostArc &a : t.mutablePost())
      a.place = placeMap[a.place];
    if (t.extras && !t.extras->events.empty()) {
      // Event arcs from removed transitions go; the caller removed every
      // transition that could only be forced by them.
      std::vector<EventSource> evs;
      std::vector<llvm::SMLoc> locs;
      for (size_t i = 0; i < t.extras->events.size(); ++i) {
        EventSource s = t.extras->events[i];
        if (!s.fromPort) {
          if (transMap[s.index] == UINT32_MAX)
            continue;
          s.index = transMap[s.index];
        }
        evs.push_back(s);
        if (i < t.extras->eventLocs.size())
          locs.push_back(t.extras->eventLocs[i]);
      }
      // Only sources are dropped, so the arena arrays are rewritten in place.
      auto *dst = const_cast<EventSource *>(t.extras->events.data());
      std::copy(evs.begin(), evs.end(), dst);
      t.extras->events = llvm::ArrayRef<EventSource>(dst, evs.size());
      if (!t.extras->eventLocs.empty()) {
        auto *ldst = const_cast<llvm::SMLoc *>(t.extras->eventLocs.data());
        std::copy(locs.begin(), locs.end(), ldst);
        t.extras->eventLocs = llvm::ArrayRef<llvm::SMLoc>(ldst, locs.size());
      }
    }
  }
  for (Flow &f : m.flows)
    f.place = placeMap[f.place];
  n = 0;
  for (uint32_t v = 0; v < m.vars.size(); ++v)
    if (keepVar[v])
      m.vars[n++] = m.vars[v];
  m.vars.resize(n);
  m.rebuildSymbols();
}

void reduce::removePorts(Design &d, Module &m,
                         const std::vector<bool> &keepPort) {
  std::vector<Port> ports;
  std::vector<uint32_t> portMap(m.ports.size(), UINT32_MAX);
  for (uint32_t p = 0; p < m.ports.size(); ++p)
    if (keepPort[p]) {
      portMap[p] = ports.size();
      ports.push_back(m.ports[p]);
    }
  for (Transition &t : m.transitions) {
    if (!t.extras)
      continue;
    std::vector<uint32_t> emits;
    for (uint32_t e : t.extras->emits)
      if (portMap[e] != UINT32_MAX)
        emits.push_back(portMap[e]);
    t.extras->emits = d.copy(llvm::ArrayRef<uint32_t>(emits));
    std::vector<EventSource> evs;
    for (EventSource s : t.extras->events) {
      if (s.fromPort)
        s.index = portMap[s.index];
      evs.push_back(s);
    }
    t.extras->events = d.copy(llvm::ArrayRef<EventSource>(evs));
  }
  m.ports.assign(ports.begin(), ports.end());
}

bool reduce::reverify(Design &d, DiagEngine &diag, StringRef pass) {
  if (verifyDesign(d, diag))
    return true;
  llvm::errs() << "netlift: error: " << pass
               << " produced invalid IR (a bug in netlift)\n";
  return false;
}

std::optional<reduce::Observed>
reduce::observedElements(const Module &m, const PassOptions &opts,
                         StringRef pass) {
  Observed o;
  o.place.assign(m.places.size(), false);
  o.var.assign(m.vars.size(), false);
  o.port.assign(m.ports.size(), false);
  o.trans.assign(m.transitions.size(), false);
  if (!opts.has("observe")) {
    for (uint32_t p = 0; p < m.ports.size(); ++p)
      o.port[p] = m.ports[p].isOutput();
    return o;
  }
  for (const std::string &name : opts.list("observe")) {
    StringRef n = name;
    Symbol s = m.lookup(n);
    if (s.kind == SymKind::Place)
      o.place[s.index] = true;
    else if (s.kind == SymKind::Var)
      o.var[s.index] = true;
    else if (s.kind == SymKind::Port)
      o.port[s.index] = true;
    else if (s.kind == SymKind::Transition)
      o.trans[s.index] = true;
    else {
      llvm::errs() << "netlift: error: " << pass << ": '" << n
                   << "' in observe= is not a place, variable, port or "
                      "transition of '"
                   << m.name << "'\n";
      return std::nullopt;
    }
  }
  return o;
}
