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
    diag.error(llvm::SMLoc(), pass + ": " + why);
    return nullptr;
  }
  if (!m->instances.empty()) {
    diag.error(llvm::SMLoc(), pass + ": '" + m->name +
                                  "' has instances; reductions work on a flat "
                                  "module (run flatten first: -p 'flatten," +
                                  pass + "')");
    return nullptr;
  }
  if (hasHybridParts(*m)) {
    diag.error(llvm::SMLoc(), pass + ": '" + m->name +
                                  "' has real variables; run discretise first");
    return nullptr;
  }
  return m;
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
  diag.error(llvm::SMLoc(), pass + " produced invalid IR (a bug in netlift)");
  return false;
}

std::optional<reduce::Observed>
reduce::observedElements(const Module &m, const PassOptions &opts,
                         StringRef pass, DiagEngine &diag) {
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
      diag.error(llvm::SMLoc(), pass + ": '" + n +
                                    "' in observe= is not a place, variable, "
                                    "port or transition of '" +
                                    m.name + "'");
      return std::nullopt;
    }
  }
  return o;
}
