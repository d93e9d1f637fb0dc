//===- StateUnits.cpp - a flat module's state as a checker names it -------===//
#include "backends/checkers/StateUnits.h"

#include "ir/net/ExecutedOnly.h"

#include "ir/net/Printer.h"

#include <cstdint>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;

std::string checkers::checkerIdentifier(const char *prefix, uint32_t i,
                                        llvm::StringRef name) {
  std::string out = prefix + std::to_string(i) + "_";
  for (char c : name)
    out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

bool StateUnits::refuse(llvm::SMLoc loc, const std::string &what) {
  if (!failed)
    diag.error(loc, what + ": " + format + " does not cover it");
  failed = true;
  return false;
}

bool StateUnits::addUnits(const std::string &name, const Type *t,
                          uint32_t &slot, bool isInput, llvm::SMLoc loc) {
  switch (t->kind) {
  case TypeKind::Record:
    for (const Field &f : t->fields)
      if (!addUnits(name + "_" + f.name.str(), f.type, slot, isInput, loc))
        return false;
    return true;
  case TypeKind::Array:
    if (!t->elem->isScalar())
      return refuse(loc, "an array of arrays or records ('" +
                             L.slots()[slot].name + "')");
    [[fallthrough]];
  default: {
    Unit u;
    u.name = name;
    u.firstSlot = slot;
    u.isArray = t->kind == TypeKind::Array;
    u.count = u.isArray ? uint32_t(t->indexHi - t->indexLo + 1) : 1;
    u.indexLo = u.isArray ? t->indexLo : 0;
    const sem::Slot &s = L.slots()[slot];
    u.lo = s.lo;
    u.hi = s.hi;
    u.wrap = s.wrap;
    u.isInput = isInput;
    if (s.lo < INT32_MIN || s.hi > INT32_MAX)
      return refuse(loc, "'" + s.name + "' ranges over " +
                             std::to_string(s.lo) + ".." +
                             std::to_string(s.hi) + ", beyond 32 bits");
    unitOfSlot[slot] = int32_t(units.size());
    units.push_back(u);
    slot += u.count;
    return true;
  }
  }
}

bool checkers::encodesSemantics(const Module &m, const sem::Options &o,
                                const char *format, DiagEngine &diag) {
  if (std::optional<ExecutedOnly> x = findExecutedOnly(m)) {
    diag.error(x->loc, std::string(format) + " cannot encode " + x->what +
                           "; `netlift reach` and `check` execute it");
    return false;
  }
  if (o.policy == sem::StepPolicy::Maximal) {
    unsigned spontaneous = 0;
    for (const Transition &t : m.transitions)
      spontaneous += !t.isForced();
    if (spontaneous > 1) {
      diag.error(llvm::SMLoc(),
                 std::string(format) +
                     " encodes one spontaneous transition a step; "
                     "--semantics maximal differs on module '" +
                     m.name.str() + "' (" + std::to_string(spontaneous) +
                     " spontaneous transitions): check it with `netlift "
                     "check --semantics maximal`");
      return false;
    }
  }
  if (o.timing == sem::Timing::Strong)
    for (const Transition &t : m.transitions)
      for (const PreArc &a : t.pre())
        if (!t.urgent && !a.time.isTrivial() && a.time.hi != kInf) {
          diag.error(t.loc, std::string(format) +
                                " encodes weak timing; --timing strong "
                                "differs at transition '" +
                                t.name.str() +
                                "' (a deadline on a transition that is not "
                                "urgent): check it with `netlift check "
                                "--timing strong`");
          return false;
        }
  return true;
}

bool StateUnits::buildUnits() {
  unitOfSlot.assign(L.numSlots(), -1);
  for (uint32_t v = 0; v < m.vars.size(); ++v) {
    uint32_t slot = uint32_t(L.varSlot(v));
    if (!addUnits(checkerIdentifier("V", v, m.vars[v].name), m.vars[v].type,
                  slot, false, m.vars[v].loc))
      return false;
  }
  for (uint32_t p = 0; p < m.ports.size(); ++p) {
    const Port &port = m.ports[p];
    if (port.kind == PortKind::Event) {
      if (port.isInput())
        eventNames.push_back(checkerIdentifier("E", p, port.name));
      continue;
    }
    if (!port.isInput() && !port.isStored())
      continue;
    uint32_t slot = uint32_t(L.portSlot(p));
    if (!addUnits(checkerIdentifier(port.isInput() ? "I" : "O", p, port.name),
                  port.type, slot, port.isInput(), port.loc))
      return false;
  }
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    placeNames.push_back(checkerIdentifier("P", p, m.places[p].name));
    clockNames.push_back(checkerIdentifier("K", p, m.places[p].name));
  }
  return true;
}

uint32_t StateUnits::inputEventIndex(uint32_t port) const {
  uint32_t k = 0;
  for (uint32_t p = 0; p < port; ++p)
    k += m.ports[p].kind == PortKind::Event && m.ports[p].isInput();
  return k;
}

/// The slot an expression statically designates (-1: none or not static).
static int64_t staticSlot(const sem::StateLayout &L, const Expr *e) {
  if (auto *r = llvm::dyn_cast<Ref>(e))
    return L.refSlot(r);
  if (auto *f = llvm::dyn_cast<FieldExpr>(e)) {
    int64_t base = staticSlot(L, f->base);
    return base < 0 ? -1
                    : base + sem::StateLayout::fieldOffset(f->base->type,
                                                           f->fieldIndex);
  }
  return -1;
}

std::optional<Access> StateUnits::access(const Expr *e) {
  if (auto *x = llvm::dyn_cast<IndexExpr>(e)) {
    int64_t base = staticSlot(L, x->base);
    if (base < 0 || unitOfSlot[base] < 0 || !units[unitOfSlot[base]].isArray) {
      refuse(e->loc, "indexing '" + exprToString(x->base) + "'");
      return std::nullopt;
    }
    return Access{uint32_t(unitOfSlot[base]), x->index};
  }
  int64_t slot = staticSlot(L, e);
  if (slot < 0)
    return std::nullopt;
  if (unitOfSlot[slot] < 0 || units[unitOfSlot[slot]].isArray) {
    refuse(e->loc, "the aggregate value '" + exprToString(e) + "'");
    return std::nullopt;
  }
  return Access{uint32_t(unitOfSlot[slot]), nullptr};
}

bool StateUnits::initialState(std::vector<uint64_t> &state) {
  sem::Semantics semantics(m, L, sem::Options());
  state.assign(L.numWords(), 0);
  sem::RuntimeError err;
  if (semantics.initialState(state.data(), err))
    return true;
  diag.error(err.loc, err.message);
  return false;
}

std::vector<std::string> StateUnits::tokenAndTimeConditions(uint32_t ti) const {
  const Transition &t = m.transitions[ti];
  std::vector<std::string> c;
  for (const PlaceEffect &e : placeEffects(t)) {
    if (e.pre > 0)
      c.push_back(placeNames[e.place] + " >= " + std::to_string(e.pre));
    uint32_t cap = m.places[e.place].capacity;
    if (e.post > e.pre && cap != kInf)
      c.push_back(placeNames[e.place] + " + " + std::to_string(e.post - e.pre) +
                  " <= " + std::to_string(cap));
  }
  for (const PreArc &a : t.pre())
    if (!a.time.isTrivial()) {
      const std::string &k = clockNames[a.place];
      if (a.time.lo > 0)
        c.push_back(k + " >= " + std::to_string(a.time.lo));
      if (a.time.hi != kInf)
        c.push_back(k + " <= " + std::to_string(a.time.hi));
    }
  return c;
}

std::vector<std::pair<uint32_t, EffectsOnPlace>>
StateUnits::forcedPlaces() const {
  std::vector<std::vector<std::pair<uint32_t, PlaceEffect>>> byPlace(
      m.places.size());
  std::vector<char> forcedTouches(m.places.size(), 0);
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti)
    for (const PlaceEffect &e : placeEffects(m.transitions[ti])) {
      byPlace[e.place].push_back({ti, e});
      if (m.transitions[ti].isForced())
        forcedTouches[e.place] = 1;
    }
  std::vector<std::pair<uint32_t, EffectsOnPlace>> out;
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (forcedTouches[p])
      out.push_back({p, std::move(byPlace[p])});
  return out;
}
