//===- PtKernel.cpp - compiled successors of plain P/T nets ---------------===//
#include "engine/PtKernel.h"

#include "engine/Semantics.h"

#include "llvm/ADT/SmallVector.h"

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::net;

/// Is every transition of `m` a plain P/T transition, so that the general
/// interpreter would do nothing but move tokens?
static bool isPlainPT(const Module &m, const StateLayout &L,
                      const Options &opts) {
  if (!opts.compilePT || opts.policy != StepPolicy::Interleaving)
    return false;
  for (const Port &p : m.ports)
    if (p.isInput())
      return false; // free inputs multiply the steps
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (L.clockSlot(p) >= 0)
      return false;
  for (const Var &v : m.vars)
    if (v.type->isClock())
      return false; // ticks
  for (const Transition &t : m.transitions) {
    if (t.isForced() || !t.conds().empty() || t.guard() || t.hasAction())
      return false;
    for (const PreArc &a : t.pre())
      if (!a.time.isTrivial())
        return false;
  }
  return true;
}

std::unique_ptr<PtKernel>
PtKernel::compile(const Module &m, const StateLayout &L, const Options &opts) {
  if (!isPlainPT(m, L, opts))
    return nullptr;
  std::unique_ptr<PtKernel> k(new PtKernel(L));
  k->words = L.numWords();
  for (const Transition &t : m.transitions) {
    std::vector<PlaceEffect> arcs = placeEffects(t);
    Compiled c{};
    c.urgent = t.urgent;
    bool never = false;
    uint32_t lo = UINT32_MAX, hi = 0;
    for (const PlaceEffect &a : arcs) {
      const Slot &s = L.slots()[L.markingSlot(a.place)];
      if (a.pre > uint64_t(s.hi))
        never = true; // demands more than the place can ever hold
      lo = std::min(lo, s.bitOffset / 64);
      hi =
          std::max(hi, (s.bitOffset + std::max<uint32_t>(s.width, 1) - 1) / 64);
    }
    c.maskBegin = k->masks.size();
    c.fieldBegin = k->fields.size();
    c.limitBegin = k->limits.size();
    c.effectBegin = k->effect.size();
    if (never || arcs.empty()) {
      // Never enabled (an impossible demand), or a transition without arcs
      // whose firing changes nothing: keep it out of every test by an
      // impossible field test or an empty effect.
      c.wordLo = 0;
      c.numWords = 0;
      if (never)
        k->fields.push_back({L.markingSlot(arcs[0].place), UINT32_MAX});
    } else {
      c.wordLo = lo;
      c.numWords = hi - lo + 1;
      k->effect.resize(k->effect.size() + 2 * c.numWords, 0);
      uint64_t *sub = &k->effect[c.effectBegin];
      uint64_t *add = sub + c.numWords;
      // Adds `w << bitOffset` into a multi-word integer of the touched
      // words (modulo its width: the result always fits, see the header).
      auto place = [&](uint64_t *acc, const Slot &s, uint64_t w) {
        uint32_t word = s.bitOffset / 64 - lo, bit = s.bitOffset % 64;
        unsigned __int128 v = (unsigned __int128)w << bit;
        uint64_t carry = 0;
        for (uint32_t i = word; i < c.numWords; ++i) {
          uint64_t part = i == word       ? uint64_t(v)
                          : i == word + 1 ? uint64_t(v >> 64)
                                          : 0;
          unsigned __int128 sum = (unsigned __int128)acc[i] + part + carry;
          acc[i] = uint64_t(sum);
          carry = uint64_t(sum >> 64);
        }
      };
      uint32_t firstMask = k->masks.size();
      auto addMask = [&](uint32_t word, uint64_t bit) {
        for (uint32_t i = firstMask; i < k->masks.size(); ++i)
          if (k->masks[i].word == word) {
            k->masks[i].mask |= bit;
            return;
          }
        k->masks.push_back({word, bit});
      };
      for (const PlaceEffect &a : arcs) {
        uint32_t slot = L.markingSlot(a.place);
        const Slot &s = L.slots()[slot];
        if (a.pre == 1 && s.width == 1)
          addMask(s.bitOffset / 64, uint64_t(1) << (s.bitOffset % 64));
        else if (a.pre > 0)
          k->fields.push_back({slot, uint32_t(a.pre)});
        place(sub, s, a.pre);
        place(add, s, a.post);
        if (a.post > a.pre && !L.isStructurallyBounded(a.place))
          k->limits.push_back({slot, uint32_t(a.post - a.pre), uint64_t(s.hi),
                               m.places[a.place].capacity == kInf});
      }
    }
    c.maskEnd = k->masks.size();
    c.fieldEnd = k->fields.size();
    c.limitEnd = k->limits.size();
    if (c.maskBegin < c.maskEnd) {
      k->firstWord.push_back(k->masks[c.maskBegin].word);
      k->firstMask.push_back(k->masks[c.maskBegin].mask);
      ++c.maskBegin; // tested by the hot loop
    } else {
      k->firstWord.push_back(0);
      k->firstMask.push_back(0);
    }
    k->hasMore.push_back(c.maskBegin < c.maskEnd || c.fieldBegin < c.fieldEnd ||
                         c.limitBegin < c.limitEnd);
    k->trans.push_back(c);
  }
  return k;
}

bool PtKernel::restEnabled(const Compiled &c, const uint64_t *s,
                           bool &overflow) const {
  for (uint32_t i = c.maskBegin; i < c.maskEnd; ++i)
    if ((s[masks[i].word] & masks[i].mask) != masks[i].mask)
      return false;
  for (uint32_t i = c.fieldBegin; i < c.fieldEnd; ++i)
    if (uint64_t(L.get(s, fields[i].slot)) < fields[i].weight)
      return false;
  for (uint32_t i = c.limitBegin; i < c.limitEnd; ++i) {
    const LimitTest &t = limits[i];
    if (uint64_t(L.get(s, t.slot)) + t.gain > t.limit) {
      if (!t.overflowIsError)
        return false;
      overflow = true;
    }
  }
  return true;
}

void PtKernel::fire(const Compiled &c, const uint64_t *s, uint64_t *out) const {
  // (s - sub + add) over the touched words, carries and borrows included.
  const uint64_t *sub = &effect[c.effectBegin];
  const uint64_t *add = sub + c.numWords;
  unsigned borrow = 0, carry = 0;
  for (uint32_t i = 0; i < c.numWords; ++i) {
    uint64_t x = s[c.wordLo + i];
    unsigned __int128 d = (unsigned __int128)x - sub[i] - borrow;
    borrow = unsigned(d >> 64) & 1;
    unsigned __int128 e = (unsigned __int128)uint64_t(d) + add[i] + carry;
    carry = unsigned(e >> 64);
    out[c.wordLo + i] = uint64_t(e);
  }
}

bool PtKernel::successors(const uint64_t *state, uint64_t *succ, Emit emit) {
  std::vector<uint32_t> &en = enabledScratch;
  en.resize(trans.size());
  uint32_t numEnabled = 0;
  bool overflow = false, urgentEnabled = false;
  const uint32_t *word = firstWord.data();
  const uint64_t *mask = firstMask.data();
  const uint8_t *more = hasMore.data();
  for (uint32_t t = 0, n = trans.size(); t < n; ++t) {
    if ((state[word[t]] & mask[t]) != mask[t])
      continue;
    if (more[t] && !restEnabled(trans[t], state, overflow))
      continue;
    en[numEnabled++] = t;
    urgentEnabled |= trans[t].urgent;
  }
  if (overflow)
    return false;
  std::copy(state, state + words, succ);
  for (uint32_t i = 0; i < numEnabled; ++i) {
    uint32_t t = en[i];
    const Compiled &c = trans[t];
    if (urgentEnabled && !c.urgent)
      continue;
    if (c.numWords == 1) {
      // The common case: one word changes.
      uint64_t w = state[c.wordLo];
      succ[c.wordLo] = w - effect[c.effectBegin] + effect[c.effectBegin + 1];
      emit(t, succ);
      succ[c.wordLo] = w;
      continue;
    }
    fire(c, state, succ);
    emit(t, succ);
    std::copy(state + c.wordLo, state + c.wordLo + c.numWords, succ + c.wordLo);
  }
  return true;
}
