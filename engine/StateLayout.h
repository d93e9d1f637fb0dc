//===- StateLayout.h - where each part of a state lives ---------*- C++ -*-===//
//
// The compact encoding of a state of a flat module (docs/semantics.md): one
// bit-packed vector of 64-bit words holding, slot by slot, the marking of
// every place, the clock of every place that has timed arcs leaving it,
// every scalar leaf of every variable (arrays and records flattened, a
// string as its length followed by its characters), every
// stored output and every clock variable. A slot holds `value - lo` in just
// enough bits for its domain; places of unbounded capacity get a fixed
// width (an overflow is reported, never wrapped). Free inputs are not part
// of the state: they get slots after the packed ones in the unpacked
// valuation the interpreter works on.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_STATELAYOUT_H
#define NETLIFT_ENGINE_STATELAYOUT_H

#include "ir/net/Expr.h"
#include "ir/net/Module.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace netlift::sem {

struct Slot {
  uint32_t bitOffset = 0;
  uint8_t width = 0;
  int64_t lo = 0, hi = 0;
  /// Writes outside [lo, hi] wrap around (PLC integers declared `wrap`);
  /// otherwise they are runtime errors.
  bool wrap = false;
  /// The value a variable starts with when it has no `init`: 0 for PLC
  /// integers (as in IEC 61131-3), the low bound otherwise.
  int64_t initial = 0;
  std::string name; // for states written out: `p`, `v[2].x`, `clock(p)`
  /// The scalar type of a variable's or port's leaf (null for markings and
  /// clocks): how its value is read (a float's bits) and written out. A
  /// string's length slot has the string's type; its characters have none.
  const net::Type *type = nullptr;
};

enum class SlotKind : uint8_t { Marking, PlaceClock, Data, Input };

class StateLayout {
public:
  /// `unboundedBits`: width of the marking of places with capacity inf.
  StateLayout(const net::Module &m, unsigned unboundedBits);

  const net::Module &module() const { return m; }
  const std::vector<Slot> &slots() const { return slotVec; }
  /// Slots [0, numPacked()) are the state; the rest are free inputs.
  uint32_t numPacked() const { return packedSlots; }
  uint32_t numSlots() const { return slotVec.size(); }
  /// 64-bit words of one packed state.
  uint32_t numWords() const { return words; }
  uint32_t packedBits() const { return bits; }

  uint32_t markingSlot(uint32_t place) const { return placeSlot[place]; }
  /// -1 when no timed arc leaves the place.
  int32_t clockSlot(uint32_t place) const { return placeClock[place]; }
  /// Saturation value of a place clock: one past the largest finite bound.
  uint32_t clockCap(uint32_t place) const { return placeClockCap[place]; }
  /// First slot of a variable's leaves (in layout order), or of a stored
  /// output; input ports map to their input slot. -1: no slot.
  int32_t varSlot(uint32_t var) const { return varFirst[var]; }
  int32_t portSlot(uint32_t port) const { return portFirst[port]; }
  /// Unbounded places (their width is a choice, not a bound).
  bool isUnbounded(uint32_t place) const;
  /// Does a P-invariant keep this place within its slot (the bound is at
  /// most its capacity, so that neither the capacity nor the encoding can
  /// be exceeded by any firing)?
  bool isStructurallyBounded(uint32_t place) const {
    return std::binary_search(structurallyBounded.begin(),
                              structurallyBounded.end(), place);
  }

  int64_t get(const uint64_t *state, uint32_t slot) const {
    const Slot &s = slotVec[slot];
    uint32_t w = s.bitOffset >> 6, b = s.bitOffset & 63;
    uint64_t v = state[w] >> b;
    if (b + s.width > 64)
      v |= state[w + 1] << (64 - b);
    if (s.width < 64)
      v &= (uint64_t(1) << s.width) - 1;
    return int64_t(v + uint64_t(s.lo));
  }
  void set(uint64_t *state, uint32_t slot, int64_t value) const {
    const Slot &s = slotVec[slot];
    uint64_t v = uint64_t(value) - uint64_t(s.lo);
    uint32_t w = s.bitOffset >> 6, b = s.bitOffset & 63;
    uint64_t mask = s.width < 64 ? (uint64_t(1) << s.width) - 1 : ~uint64_t(0);
    v &= mask;
    state[w] = (state[w] & ~(mask << b)) | (v << b);
    if (b + s.width > 64) {
      uint32_t rest = b + s.width - 64;
      uint64_t m2 = (uint64_t(1) << rest) - 1;
      state[w + 1] = (state[w + 1] & ~m2) | (v >> (64 - b));
    }
  }
  /// Largest value a slot can hold.
  int64_t slotMax(uint32_t slot) const { return slotVec[slot].hi; }
  /// First slot of what a name designates (a variable, a stored output or
  /// an input, down its record field path); -1 when it has no storage (a
  /// place, a defined output, an enumerator...).
  int64_t refSlot(const net::Ref *r) const;
  /// Slots before field `field` in a value of record type `t`.
  static uint32_t fieldOffset(const net::Type *t, uint32_t field);
  /// Number of slots of a value of type `t` (arrays, records flattened).
  static uint32_t slotsOf(const net::Type *t) {
    return uint32_t(t->numSlots());
  }

private:
  uint32_t addSlot(std::string name, int64_t lo, int64_t hi, bool wrap = false,
                   bool zeroInitial = false);
  void addLeaves(const std::string &name, const net::Type *t);

  const net::Module &m;
  std::vector<Slot> slotVec;
  std::vector<uint32_t> placeSlot, placeClockCap, structurallyBounded;
  std::vector<int32_t> placeClock, varFirst, portFirst;
  uint32_t packedSlots = 0, words = 0, bits = 0;
};

/// The number of bits needed for values 0..n.
unsigned bitsFor(uint64_t n);

} // namespace netlift::sem

#endif
