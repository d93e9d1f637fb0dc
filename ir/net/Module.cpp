//===- Module.cpp - NetIR modules, nets and designs -----------------------===//
#include "ir/net/Module.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/STLExtras.h"

#include "llvm/Support/xxhash.h"
#include <cstring>

using namespace netlift::net;
using llvm::StringRef;

StringRef netlift::net::spelling(PortKind k) {
  switch (k) {
  case PortKind::Event:
    return "event";
  case PortKind::Cond:
    return "cond";
  case PortKind::Data:
    return "data";
  }
  return "?";
}

static uint32_t hashName(StringRef n) { return uint32_t(llvm::xxHash64(n)); }

Symbol SymbolTable::lookup(StringRef name, const Module &m) const {
  if (buckets.empty())
    return {};
  uint32_t h = hashName(name);
  size_t mask = buckets.size() - 1;
  for (size_t i = h & mask;; i = (i + 1) & mask) {
    const Bucket &b = buckets[i];
    if (b.packed == kEmpty)
      return {};
    if (b.hash != h)
      continue;
    Symbol s{SymKind(b.packed >> 28), b.packed & 0x0FFFFFFF};
    if (m.symbolName(s) == name)
      return s;
  }
}

void SymbolTable::grow(const Module &m) {
  auto old = std::move(buckets);
  buckets.assign(old.empty() ? 64 : old.size() * 2, Bucket{0, kEmpty});
  size_t mask = buckets.size() - 1;
  for (const Bucket &b : old) {
    if (b.packed == kEmpty)
      continue;
    size_t i = b.hash & mask;
    while (buckets[i].packed != kEmpty)
      i = (i + 1) & mask;
    buckets[i] = b;
  }
}

void SymbolTable::reserve(size_t n, const Module &m) {
  while (n * 10 > buckets.size() * 7)
    grow(m);
}

bool SymbolTable::insert(StringRef name, Symbol s, const Module &m) {
  if ((count + 1) * 10 > buckets.size() * 7)
    grow(m);
  uint32_t h = hashName(name);
  size_t mask = buckets.size() - 1;
  size_t i = h & mask;
  for (;; i = (i + 1) & mask) {
    Bucket &b = buckets[i];
    if (b.packed == kEmpty)
      break;
    if (b.hash == h &&
        m.symbolName({SymKind(b.packed >> 28), b.packed & 0x0FFFFFFF}) == name)
      return false;
  }
  assert(s.index < (1u << 28) && "too many entities in one module");
  buckets[i] = {h, uint32_t(s.kind) << 28 | s.index};
  ++count;
  return true;
}

void Module::rebuildSymbols() {
  symbols.clear();
  for (uint32_t i = 0; i < ports.size(); ++i)
    declare(ports[i].name, {SymKind::Port, i});
  for (uint32_t i = 0; i < places.size(); ++i)
    declare(places[i].name, {SymKind::Place, i});
  for (uint32_t i = 0; i < transitions.size(); ++i)
    declare(transitions[i].name, {SymKind::Transition, i});
  for (uint32_t i = 0; i < vars.size(); ++i)
    declare(vars[i].name, {SymKind::Var, i});
  for (uint32_t i = 0; i < instances.size(); ++i)
    declare(instances[i].name, {SymKind::Instance, i});
  pruneAttributes();
}

bool Module::isAttributeTarget(StringRef target) const {
  if (target.empty() || lookup(target).kind != SymKind::None)
    return true;
  // A scope: the prefix of some qualified name. Few attributes name one,
  // so a scan per attribute is cheap enough.
  auto inScope = [&](StringRef n) {
    return n.size() > target.size() && n.startswith(target) &&
           n[target.size()] == '.';
  };
  auto anyInScope = [&](const auto &table) {
    for (const auto &entity : table)
      if (inScope(entity.name))
        return true;
    return false;
  };
  return anyInScope(ports) || anyInScope(places) || anyInScope(transitions) ||
         anyInScope(vars) || anyInScope(instances);
}

void Module::pruneAttributes() {
  llvm::erase_if(attributes, [&](const Attribute &a) {
    return !isAttributeTarget(a.target);
  });
}

StringRef Module::symbolName(Symbol s) const {
  switch (s.kind) {
  case SymKind::Place:
    return places[s.index].name;
  case SymKind::Transition:
    return transitions[s.index].name;
  case SymKind::Port:
    return ports[s.index].name;
  case SymKind::Var:
    return vars[s.index].name;
  case SymKind::Instance:
    return instances[s.index].name;
  default:
    return "";
  }
}

int Module::findPort(StringRef n) const {
  Symbol s = lookup(n);
  return s.kind == SymKind::Port ? int(s.index) : -1;
}

char *Design::saveString(StringRef s) {
  char *p = arena.Allocate<char>(s.size() + 1);
  if (!s.empty())
    memcpy(p, s.data(), s.size());
  p[s.size()] = 0;
  return p;
}

Design::Design() = default;
Design::~Design() = default;

Module *Design::createModule(StringRef name, llvm::SMLoc loc, bool isSystem) {
  StringRef saved = save(name);
  if (moduleIndex.count(saved))
    return nullptr;
  modules.push_back(std::make_unique<Module>(saved, loc, isSystem));
  Module *m = modules.back().get();
  moduleIndex[saved] = m;
  return m;
}

void Design::eraseModule(Module *m) {
  moduleIndex.erase(m->name);
  for (auto it = modules.begin(); it != modules.end(); ++it)
    if (it->get() == m) {
      modules.erase(it);
      return;
    }
}

bool Design::renameModule(Module *m, StringRef newName) {
  StringRef saved = save(newName);
  if (moduleIndex.count(saved))
    return false;
  moduleIndex.erase(m->name);
  m->name = saved;
  moduleIndex[saved] = m;
  return true;
}

std::vector<std::string> Module::declaredNames() const {
  std::vector<std::string> names;
  for (const Port &p : ports)
    names.push_back(p.name.str());
  for (const Place &p : places)
    names.push_back(p.name.str());
  for (const Transition &t : transitions)
    names.push_back(t.name.str());
  for (const Var &v : vars)
    names.push_back(v.name.str());
  for (const Instance &i : instances)
    names.push_back(i.name.str());
  return names;
}

Module *Design::findTop(StringRef name, std::string &why) const {
  if (!name.empty()) {
    if (Module *m = lookupModule(name))
      return m;
    std::vector<std::string> names;
    for (auto &m : modules)
      names.push_back(m->name.str());
    why = ("no module named '" + name + "'" + didYouMean(name, names)).str();
    return nullptr;
  }
  std::vector<Module *> systems;
  for (auto &m : modules)
    if (m->isSystem)
      systems.push_back(m.get());
  if (systems.size() == 1)
    return systems[0];
  if (systems.size() > 1) {
    why = "several systems; choose one with top=NAME";
    return nullptr;
  }
  llvm::DenseSet<StringRef> instantiated;
  for (auto &m : modules)
    for (const Instance &i : m->instances)
      instantiated.insert(i.moduleName);
  Module *top = nullptr;
  for (auto &m : modules) {
    if (instantiated.count(m->name))
      continue;
    if (top) {
      why = ("several top-level modules ('" + top->name + "', '" + m->name +
             "'); choose one with top=NAME")
                .str();
      return nullptr;
    }
    top = m.get();
  }
  if (!top)
    why = modules.empty() ? "the design has no module"
                          : "every module is instantiated by another";
  return top;
}

std::vector<netlift::net::PlaceEffect>
netlift::net::placeEffects(const Transition &t) {
  std::vector<PlaceEffect> out;
  // A handful of arcs: a linear search is the fastest map.
  auto of = [&](uint32_t p) -> PlaceEffect & {
    for (PlaceEffect &e : out)
      if (e.place == p)
        return e;
    return out.emplace_back(PlaceEffect{p});
  };
  for (const PreArc &a : t.pre())
    of(a.place).pre += a.weight;
  for (const PostArc &a : t.post())
    of(a.place).post += a.weight;
  return out;
}

uint64_t netlift::net::Timescale::nanoseconds() const {
  static const std::pair<llvm::StringRef, uint64_t> units[] = {
      {"ns", 1},
      {"us", 1000},
      {"ms", 1000000},
      {"s", 1000000000ULL},
      {"min", 60000000000ULL},
      {"h", 3600000000000ULL}};
  for (auto &[u, f] : units)
    if (unit == u)
      return amount * f;
  return 0;
}
