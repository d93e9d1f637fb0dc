//===- Flatten.cpp - inline the instance hierarchy ------------------------===//
//
// `flatten` turns a module with instances into one flat module. Every entity
// of an instance `c` of module `Ctrl` becomes an entity of the flat module
// named `c.<name>` (recursively: `line.c.scan`), and connections disappear:
//
//  - a cond/data input bound by a connection is replaced, wherever it is
//    read, by the name of what drives it;
//  - an event input bound by a connection becomes event arcs from every
//    transition that emits the driving event output (several drivers merge);
//  - an input that nothing drives becomes an input of the flat module,
//    `c.start`: unconnected inputs stay the free environment;
//  - every output of every instance stays observable as an output of the
//    flat module (`p.at_end`), so properties and reports can name it;
//  - the top module's own ports keep their names.
//
// Preserved: the state space and every step exactly (markings, data, clocks,
// event synchronisation), up to the renaming above. A forced transition whose
// event input is driven by an event nobody emits can never fire; it keeps a
// `false` guard and a warning says so. Modules other than the result are
// removed from the design. Attributes follow their entities (a module's own
// become its instance's, `attr c device = ...`); those of bound inputs go
// with the inputs.
//
//===----------------------------------------------------------------------===//
#include "passes/Flatten.h"
#include "passes/Pass.h"

#include "ir/net/Builder.h"
#include "ir/net/Clone.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"

#include <algorithm>

using namespace netlift;
using namespace netlift::net;
using llvm::StringRef;

namespace {

class Flattener {
public:
  Flattener(Design &d, DiagEngine &diag) : d(d), diag(diag), b(d) {}
  Module *run(Module *top);
  unsigned numInstances = 0, numFreeInputs = 0;

private:
  using CondMap = llvm::StringMap<std::string>;
  using EventMap = llvm::StringMap<std::vector<std::string>>;
  bool inlineModule(const Module &y, const std::string &prefix, bool isTop,
                    const CondMap &condMap, const EventMap &eventMap);
  bool resolveEvents();

  Design &d;
  DiagEngine &diag;
  Builder b;
  Module *flat = nullptr;
  // Per flat transition: the names its event arcs come from (flat
  // transitions, flat event inputs, or flat event outputs to expand), and
  // the flat event outputs it emits.
  std::vector<std::vector<std::string>> pendingEvents;
  std::vector<std::vector<std::string>> pendingEmits;
  // Flat event output `first` is emitted whenever `second` is.
  std::vector<std::pair<std::string, std::string>> eventAliases;
};

Module *Flattener::run(Module *top) {
  flat = b.createModule((top->name + ".flat").str(), top->isSystem, top->loc);
  if (!flat) {
    diag.error(top->loc, "flatten: cannot create the flat module");
    return nullptr;
  }
  if (!inlineModule(*top, "", true, {}, {}) || !resolveEvents())
    return nullptr;
  if (!flat->ports.empty())
    flat->isSystem = false;
  // An instance's bound inputs are gone, and their attributes with them.
  flat->pruneAttributes();
  return flat;
}

bool Flattener::inlineModule(const Module &y, const std::string &prefix,
                             bool isTop, const CondMap &condMap,
                             const EventMap &eventMap) {
  auto rename = [&](StringRef n) -> std::string {
    int p = y.findPort(n);
    if (p >= 0 && y.ports[p].isInput() && !isTop) {
      auto it = condMap.find(n);
      return it == condMap.end() ? prefix + n.str() : it->second;
    }
    return prefix + n.str();
  };
  auto eventSources = [&](StringRef port) -> std::vector<std::string> {
    if (isTop)
      return {port.str()};
    auto it = eventMap.find(port);
    return it == eventMap.end() ? std::vector<std::string>{prefix + port.str()}
                                : it->second;
  };

  // Interface: the top keeps its ports; an instance's outputs stay
  // observable under qualified names (its inputs were bound by the parent).
  for (const Port &p : y.ports) {
    if (!isTop && p.isInput())
      continue;
    uint32_t fp =
        b.addPort(prefix + p.name.str(), p.kind, p.dir, p.type, p.loc);
    Port &np = flat->ports[fp];
    np.definition = cloneExpr(b, y, p.definition, rename);
    np.definitionLoc = p.definitionLoc;
    np.init = cloneExpr(b, y, p.init, rename);
  }
  for (const Var &v : y.vars) {
    uint32_t nv = b.addVar(prefix + v.name.str(), v.type,
                           cloneExpr(b, y, v.init, rename), v.loc);
    flat->vars[nv].initHi = cloneExpr(b, y, v.initHi, rename);
  }
  uint32_t placeBase = flat->places.size();
  for (const Place &p : y.places)
    b.addPlace(prefix + p.name.str(), p.tokens, p.capacity, p.loc);
  for (const Transition &t : y.transitions) {
    std::vector<PreArc> pre(t.pre().begin(), t.pre().end());
    std::vector<PostArc> post(t.post().begin(), t.post().end());
    for (PreArc &a : pre)
      a.place += placeBase;
    for (PostArc &a : post)
      a.place += placeBase;
    uint32_t ft = b.addTransition(prefix + t.name.str(), pre, post, t.loc);
    if (!t.conds().empty()) {
      std::vector<Expr *> conds;
      for (const Expr *c : t.conds())
        conds.push_back(cloneExpr(b, y, c, rename));
      b.setConds(ft, conds);
    }
    if (t.guard())
      b.setGuard(ft, cloneExpr(b, y, t.guard(), rename));
    if (t.hasAction())
      b.setAction(ft, cloneBlock(b, y, t.action(), rename));
    b.setUrgent(ft, t.urgent);
    flat->transitions[ft].mode = t.mode;
    std::vector<std::string> evs, emits;
    for (const EventSource &s : t.events()) {
      if (!s.fromPort) {
        evs.push_back(prefix + y.transitions[s.index].name.str());
        continue;
      }
      std::vector<std::string> srcs = eventSources(y.ports[s.index].name);
      if (t.mode == EventMode::And && srcs.size() > 1) {
        diag.error(t.loc, "flatten: transition '" + prefix + t.name +
                              "' waits for all of its events ('&'), but "
                              "event input '" +
                              y.ports[s.index].name +
                              "' merges several events; this cannot be "
                              "expressed with one event mode");
        return false;
      }
      // An empty expansion is kept as a marker: the arc can never fire.
      evs.push_back(srcs.empty() ? std::string() : srcs[0]);
      for (size_t i = 1; i < srcs.size(); ++i)
        evs.push_back(srcs[i]);
    }
    for (uint32_t e : t.emits())
      emits.push_back(prefix + y.ports[e].name.str());
    pendingEvents.push_back(std::move(evs));
    pendingEmits.push_back(std::move(emits));
  }
  for (const Flow &f : y.flows) {
    std::vector<Flow::Equation> eqs;
    for (const Flow::Equation &eq : f.equations) {
      Flow::Equation n = eq;
      n.var = d.save(prefix + eq.var.str());
      n.rate = cloneExpr(b, y, eq.rate, rename);
      if (eq.rateHi)
        n.rateHi = cloneExpr(b, y, eq.rateHi, rename);
      eqs.push_back(n);
    }
    b.addFlow(placeBase + f.place, eqs, f.loc);
  }
  for (const Invariant &inv : y.invariants) {
    std::vector<Expr *> conds;
    for (const Expr *c : inv.conditions)
      conds.push_back(cloneExpr(b, y, c, rename));
    b.addInvariant(placeBase + inv.place, conds, inv.loc);
  }

  // Attributes follow their entity; the module's own become the
  // instance's (a scope of the flat names).
  for (const Attribute &a : y.attributes) {
    std::string target = a.target.empty() && !prefix.empty()
                             ? prefix.substr(0, prefix.size() - 1)
                             : prefix + a.target.str();
    b.addAttribute(target, a.key, a.value, a.loc);
  }

  // Instances, depth first in declaration order.
  for (const Instance &inst : y.instances) {
    ++numInstances;
    const Module &z = *inst.module;
    std::string childPrefix = prefix + inst.name.str() + ".";
    CondMap childCond;
    EventMap childEvents;
    for (const Port &q : z.ports) {
      if (!q.isInput())
        continue;
      std::vector<std::string> drivers;
      for (const Connection &c : y.connections) {
        if (c.to.instance != inst.name || c.to.port != q.name)
          continue;
        if (c.from.instance.empty()) {
          if (q.kind == PortKind::Event) {
            for (std::string &s : eventSources(c.from.port))
              drivers.push_back(std::move(s));
          } else {
            drivers.push_back(rename(c.from.port));
          }
        } else {
          drivers.push_back(prefix + c.from.instance.str() + "." +
                            c.from.port.str());
        }
      }
      if (drivers.empty()) {
        // Nothing drives it: it stays free, an input of the flat module.
        b.addPort(childPrefix + q.name.str(), q.kind, PortDir::In, q.type,
                  q.loc);
        ++numFreeInputs;
        drivers.push_back(childPrefix + q.name.str());
      }
      if (q.kind == PortKind::Event)
        childEvents[q.name] = std::move(drivers);
      else
        childCond[q.name] = drivers[0];
    }
    if (!inlineModule(z, childPrefix, false, childCond, childEvents))
      return false;
  }

  // Outputs of this module driven by connections.
  for (const Connection &c : y.connections) {
    if (!c.to.instance.empty())
      continue;
    std::string target = prefix + c.to.port.str();
    int fp = flat->findPort(target);
    const Port &yp = y.ports[y.findPort(c.to.port)];
    if (yp.kind == PortKind::Event) {
      if (c.from.instance.empty()) {
        diag.error(c.loc, "flatten: event output '" + c.to.port +
                              "' is connected straight to event input '" +
                              c.from.port +
                              "'; an event needs a transition to pass it on");
        return false;
      }
      eventAliases.push_back(
          {target, prefix + c.from.instance.str() + "." + c.from.port.str()});
      continue;
    }
    std::string src = c.from.instance.empty() ? rename(c.from.port)
                                              : prefix + c.from.instance.str() +
                                                    "." + c.from.port.str();
    flat->ports[fp].definition = b.ref(src, c.loc);
    flat->ports[fp].definitionLoc = c.loc;
  }
  return true;
}

bool Flattener::resolveEvents() {
  // Who emits each flat event output, closed under the aliases.
  llvm::StringMap<std::vector<uint32_t>> emitters;
  for (uint32_t t = 0; t < pendingEmits.size(); ++t)
    for (const std::string &e : pendingEmits[t])
      emitters[e].push_back(t);
  for (bool changed = true; changed;) {
    changed = false;
    for (auto &[tgt, src] : eventAliases) {
      std::vector<uint32_t> add = emitters.lookup(src);
      std::vector<uint32_t> &have = emitters[tgt];
      for (uint32_t t : add)
        if (std::find(have.begin(), have.end(), t) == have.end()) {
          have.push_back(t);
          pendingEmits[t].push_back(tgt);
          changed = true;
        }
    }
  }
  for (uint32_t t = 0; t < pendingEmits.size(); ++t) {
    std::vector<uint32_t> ports;
    for (const std::string &e : pendingEmits[t])
      ports.push_back(uint32_t(flat->findPort(e)));
    std::sort(ports.begin(), ports.end());
    if (!ports.empty())
      b.setEmits(t, ports);
  }
  for (uint32_t t = 0; t < pendingEvents.size(); ++t) {
    if (pendingEvents[t].empty())
      continue;
    Transition &tr = flat->transitions[t];
    std::vector<EventSource> srcs;
    bool dead = false;
    std::string deadBecause;
    for (const std::string &name : pendingEvents[t]) {
      Symbol s = name.empty() ? Symbol() : flat->lookup(name);
      std::vector<EventSource> expanded;
      if (s.kind == SymKind::Transition) {
        expanded.push_back({s.index, false});
      } else if (s.kind == SymKind::Port && flat->ports[s.index].isInput()) {
        expanded.push_back({s.index, true});
      } else if (s.kind == SymKind::Port) {
        for (uint32_t e : emitters.lookup(name))
          expanded.push_back({e, false});
        if (expanded.empty())
          deadBecause = name;
      }
      if (expanded.empty() && tr.mode == EventMode::And)
        dead = true;
      for (const EventSource &e : expanded)
        if (std::find(srcs.begin(), srcs.end(), e) == srcs.end())
          srcs.push_back(e);
    }
    if (srcs.empty())
      dead = true;
    if (dead) {
      diag.warning(tr.loc, "transition '" + tr.name +
                               "' can never fire: its event comes from '" +
                               deadBecause + "', which no transition emits");
      // The `false` guard keeps it disabled; arcs that resolve to nothing
      // are dropped.
      b.setGuard(t, b.boolLit(false, tr.loc));
      if (srcs.empty())
        continue;
    }
    b.setEvents(t, srcs, tr.mode);
  }
  return true;
}

class FlattenPass : public Pass {
public:
  explicit FlattenPass(const PassOptions &opts) : top(opts.text("top")) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    std::string why;
    Module *t = d.findTop(top, why);
    if (!t) {
      diag.error(llvm::SMLoc(), "flatten: " + why);
      return false;
    }
    Flattener f(d, diag);
    Module *flat = f.run(t);
    if (!flat)
      return false;
    std::string name = t->name.str();
    unsigned removed = 0;
    std::vector<Module *> others;
    for (auto &m : d.modules)
      if (m.get() != flat)
        others.push_back(m.get());
    for (Module *m : others) {
      d.eraseModule(m);
      ++removed;
    }
    d.renameModule(flat, name);
    stats.add("flatten", "instances", f.numInstances, "instances inlined");
    stats.add("flatten", "free-inputs", f.numFreeInputs,
              "unconnected instance inputs kept as free inputs");
    stats.add("flatten", "places", flat->places.size(),
              "places in the flat module");
    stats.add("flatten", "transitions", flat->transitions.size(),
              "transitions in the flat module");
    return true;
  }

private:
  std::string top;
};

} // namespace

namespace netlift {
net::Module *flattenModule(net::Design &design, net::Module *top,
                           DiagEngine &diag) {
  Flattener f(design, diag);
  return f.run(top);
}

std::unique_ptr<Pass> createFlattenPass(const PassOptions &opts) {
  return std::make_unique<FlattenPass>(opts);
}
} // namespace netlift
