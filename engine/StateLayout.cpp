//===- StateLayout.cpp - where each part of a state lives -----------------===//
#include "engine/StateLayout.h"

#include "ir/semantics/StructuralBounds.h"

#include <algorithm>

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::net;

unsigned netlift::sem::bitsFor(uint64_t n) {
  unsigned b = 0;
  while (b < 64 && (n >> b) != 0)
    ++b;
  return b;
}

uint32_t StateLayout::addSlot(std::string name, int64_t lo, int64_t hi,
                              bool wrap, bool zeroInitial) {
  Slot s;
  s.lo = lo;
  s.hi = hi;
  s.wrap = wrap;
  s.initial = zeroInitial && lo <= 0 && 0 <= hi ? 0 : lo;
  s.width = uint8_t(bitsFor(uint64_t(hi) - uint64_t(lo)));
  s.name = std::move(name);
  slotVec.push_back(std::move(s));
  return slotVec.size() - 1;
}

void StateLayout::addLeaves(const std::string &name, const Type *t) {
  switch (t->kind) {
  case TypeKind::Array:
    for (int64_t i = t->indexLo; i <= t->indexHi; ++i)
      addLeaves(name + "[" + std::to_string(i) + "]", t->elem);
    return;
  case TypeKind::Record:
    for (const Field &f : t->fields)
      addLeaves(name + "." + f.name.str(), f.type);
    return;
  case TypeKind::String: {
    // The length, typed as the string (how the whole is written out),
    // then one slot per character; empty is all zeros.
    uint32_t len = addSlot(name, 0, t->maxLen);
    slotVec[len].type = t;
    for (uint32_t i = 1; i <= t->maxLen; ++i)
      addSlot(name + "[" + std::to_string(i) + "]", 0,
              t->width == 16 ? 0xffff : 0xff);
    return;
  }
  default: {
    // PLC integers and floats start at 0 (+0.0 for a float).
    uint32_t s =
        addSlot(name, t->lo, t->hi,
                t->kind == TypeKind::Int && t->overflow == Overflow::Wrap,
                t->kind == TypeKind::Int || t->kind == TypeKind::Float);
    slotVec[s].type = t;
  }
  }
}

StateLayout::StateLayout(const Module &mod, unsigned unboundedBits) : m(mod) {
  placeSlot.resize(m.places.size());
  placeClock.assign(m.places.size(), -1);
  placeClockCap.assign(m.places.size(), 0);
  varFirst.assign(m.vars.size(), -1);
  portFirst.assign(m.ports.size(), -1);
  // A place needs bits for its capacity or its structural bound,
  // whichever is smaller; only places with neither get `unboundedBits`.
  std::vector<uint64_t> bound = structuralBounds(m);
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    const Place &pl = m.places[p];
    uint64_t hi = pl.capacity == kInf ? (uint64_t(1) << unboundedBits) - 1
                                      : uint64_t(pl.capacity);
    if (bound[p] != kNoBound && bound[p] <= hi) {
      hi = bound[p];
      structurallyBounded.push_back(p);
    }
    placeSlot[p] = addSlot(pl.name.str(), 0, int64_t(hi));
  }
  // A place clock is needed only where a timed arc leaves the place; it
  // saturates one past the largest finite bound (beyond, values agree).
  for (const Transition &t : m.transitions)
    for (const PreArc &a : t.pre())
      if (!a.time.isTrivial()) {
        uint32_t bound = a.time.hi == kInf ? a.time.lo : a.time.hi;
        placeClockCap[a.place] = std::max(placeClockCap[a.place], bound + 1);
      }
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (placeClockCap[p])
      placeClock[p] =
          addSlot("clock(" + m.places[p].name.str() + ")", 0, placeClockCap[p]);
  for (uint32_t v = 0; v < m.vars.size(); ++v) {
    if (m.vars[v].type->isReal())
      continue; // hybrid models are refused before exploration
    varFirst[v] = slotVec.size();
    addLeaves(m.vars[v].name.str(), m.vars[v].type);
  }
  for (uint32_t p = 0; p < m.ports.size(); ++p)
    if (m.ports[p].isStored()) {
      portFirst[p] = slotVec.size();
      addLeaves(m.ports[p].name.str(), m.ports[p].type);
    }
  packedSlots = slotVec.size();
  uint32_t off = 0;
  for (Slot &s : slotVec) {
    s.bitOffset = off;
    off += s.width;
  }
  bits = off;
  words = std::max<uint32_t>(1, (off + 63) / 64);
  // Free inputs: unpacked only.
  for (uint32_t p = 0; p < m.ports.size(); ++p) {
    const Port &port = m.ports[p];
    if (!port.isInput() || port.kind == PortKind::Event)
      continue;
    portFirst[p] = slotVec.size();
    addLeaves(port.name.str(), port.type);
  }
}

bool StateLayout::isUnbounded(uint32_t place) const {
  return m.places[place].capacity == kInf;
}

uint32_t StateLayout::fieldOffset(const Type *t, uint32_t field) {
  uint32_t off = 0;
  for (uint32_t i = 0; i < field; ++i)
    off += slotsOf(t->fields[i].type);
  return off;
}

int64_t StateLayout::refSlot(const Ref *r) const {
  int64_t base = -1;
  const Type *t = nullptr;
  if (r->sym.kind == SymKind::Var) {
    base = varSlot(r->sym.index);
    t = m.vars[r->sym.index].type;
  } else if (r->sym.kind == SymKind::Port &&
             !m.ports[r->sym.index].definition &&
             m.ports[r->sym.index].kind != PortKind::Event) {
    base = portSlot(r->sym.index);
    t = m.ports[r->sym.index].type;
  }
  if (base < 0)
    return -1;
  for (uint32_t f : r->fields) {
    base += fieldOffset(t, f);
    t = t->fields[f].type;
  }
  return base;
}
