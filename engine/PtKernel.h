//===- PtKernel.h - compiled successors of plain P/T nets -------*- C++ -*-===//
//
// The successor function of a module that is a plain place/transition net
// under the interleaving policy (no data, clocks, timed arcs, conditions,
// guards, actions, forced transitions or free inputs), compiled once into
// flat tables over the packed state so that a state is expanded without
// unpacking it: a transition is enabled when its pre-places hold their
// weights (one AND-compare per word for 1-bit places) and its post-places
// stay within their capacities; its successor is the packed state minus the
// packed pre-weights plus the packed post-weights, as multi-word integer
// arithmetic over the words it touches (exact, since no field borrows or
// overflows). Semantics uses it for every module it applies to; its result
// is the same as the general interpreter's, which it defers to whenever a
// firing would overflow an unbounded place (to report that error).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_PTKERNEL_H
#define NETLIFT_ENGINE_PTKERNEL_H

#include "engine/StateLayout.h"

#include "llvm/ADT/STLFunctionalExtras.h"

#include <memory>
#include <vector>

namespace netlift::sem {

struct Options;

class PtKernel {
public:
  /// Null when the module is not a plain P/T net under `opts`.
  static std::unique_ptr<PtKernel>
  compile(const net::Module &m, const StateLayout &layout, const Options &opts);

  using Emit =
      llvm::function_ref<void(uint32_t transition, const uint64_t *succ)>;
  /// Calls `emit` for every enabled transition of `state` in transition
  /// order (only the urgent ones when some urgent one is enabled), with its
  /// successor in `succ` (numWords() words, reused between calls). False,
  /// before emitting anything, when some enabled firing would overflow the
  /// encoding of an unbounded place: the caller reports that error.
  bool successors(const uint64_t *state, uint64_t *succ, Emit emit);

private:
  /// 1-bit places of weight 1 in one word: enabled iff (s[w] & mask) ==
  /// mask.
  struct MaskTest {
    uint32_t word;
    uint64_t mask;
  };
  /// Any other pre-place: its slot holds at least `weight`.
  struct FieldTest {
    uint32_t slot;
    uint32_t weight;
  };
  /// A post-place the firing can push over its limit: disabled (capacity)
  /// or an overflow error (unbounded place) when get(slot) + gain > limit.
  struct LimitTest {
    uint32_t slot;
    uint32_t gain;
    uint64_t limit;
    bool overflowIsError;
  };
  struct Compiled {
    uint32_t maskBegin, maskEnd, fieldBegin, fieldEnd, limitBegin, limitEnd;
    /// Words [wordLo, wordLo + numWords) change; their packed pre- and
    /// post-weights start at effect[effectBegin] (sub, then add).
    uint32_t wordLo, numWords, effectBegin;
    bool urgent;
  };
  PtKernel(const StateLayout &layout) : L(layout) {}
  /// The tests beyond the first mask test (see `firstWord`).
  bool restEnabled(const Compiled &c, const uint64_t *s, bool &overflow) const;
  void fire(const Compiled &c, const uint64_t *s, uint64_t *out) const;

  const StateLayout &L;
  uint32_t words = 0;
  std::vector<Compiled> trans;
  // The hot loop's view of each transition, in flat arrays: most
  // transitions of a 1-safe net are decided by one mask test on one word
  // (firstMask 0 when a transition has none); `hasMore` flags those that
  // need restEnabled.
  std::vector<uint32_t> firstWord;
  std::vector<uint64_t> firstMask;
  std::vector<uint8_t> hasMore;
  std::vector<MaskTest> masks;
  std::vector<FieldTest> fields;
  std::vector<LimitTest> limits;
  std::vector<uint64_t> effect;
  std::vector<uint32_t> enabledScratch;
};

} // namespace netlift::sem

#endif
