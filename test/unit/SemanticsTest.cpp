//===- SemanticsTest.cpp - state encoding and step semantics --------------===//
#include "engine/Semantics.h"
#include "ir/net/Parser.h"
#include "ir/net/Verifier.h"
#include "ir/semantics/StructuralBounds.h"

#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

#include <memory>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::sem;

namespace {

Module *parse(const char *text, Design &d, llvm::SourceMgr &sm) {
  DiagEngine diag(sm);
  unsigned id = sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, "t.net"), llvm::SMLoc());
  if (!parseNetIR(id, diag, d) || !verifyDesign(d, diag))
    return nullptr;
  return d.modules.back().get();
}

TEST(StateLayout, SlotsStraddleWordsAndKeepTheirValues) {
  // 9 variables of 13 bits: several cross a 64-bit word boundary.
  llvm::SourceMgr sm;
  Design d;
  Module *m = parse("system S { var a, b, c, d, e, f, g, h, i : -4000..4000; "
                    "place p(3) cap 5; }",
                    d, sm);
  ASSERT_NE(m, nullptr);
  StateLayout L(*m, 8);
  // p has no transitions: its marking is invariant, so 3 tokens need 2 bits
  // (not the 3 its capacity 5 would).
  EXPECT_EQ(L.slots()[L.markingSlot(0)].width, 2);
  EXPECT_EQ(L.packedBits(), 2u + 9 * 13);
  EXPECT_EQ(L.numWords(), 2u);
  std::vector<uint64_t> st(L.numWords(), 0);
  for (uint32_t v = 0; v < 9; ++v)
    L.set(st.data(), L.varSlot(v), int64_t(v) * 977 - 4000);
  L.set(st.data(), L.markingSlot(0), 3);
  for (uint32_t v = 0; v < 9; ++v)
    EXPECT_EQ(L.get(st.data(), L.varSlot(v)), int64_t(v) * 977 - 4000) << v;
  EXPECT_EQ(L.get(st.data(), L.markingSlot(0)), 3);
}

TEST(StructuralBounds, SemiflowsBoundPlaces) {
  // A mutex: idle_i + crit_i = 1 and lock + crit_a + crit_b = 1 bound every
  // place by 1; the pump place p is covered by no semiflow.
  llvm::SourceMgr sm;
  Design d;
  Module *m =
      parse("system S { place ia(1) cap inf, ca cap inf, ib(1) cap inf, "
            "cb cap inf, lock(1) cap inf, src(1) cap inf, p cap inf; "
            "trans ea : ia, lock -> ca; trans la : ca -> ia, lock; "
            "trans eb : ib, lock -> cb; trans lb : cb -> ib, lock; "
            "trans pump : src -> src, p; "
            "trans twice : 2*p -> p; }",
            d, sm);
  ASSERT_NE(m, nullptr);
  std::vector<uint64_t> b = structuralBounds(*m);
  EXPECT_EQ(b, (std::vector<uint64_t>{1, 1, 1, 1, 1, 1, kNoBound}));
}

TEST(StateLayout, OnlyPlacesWithTimedArcsHaveClocks) {
  llvm::SourceMgr sm;
  Design d;
  Module *m = parse("system S { place p(1), q, r; "
                    "trans t : p[2,7] -> q; trans u : q[3,inf] -> r; "
                    "trans w : r -> p; }",
                    d, sm);
  ASSERT_NE(m, nullptr);
  StateLayout L(*m, 8);
  EXPECT_GE(L.clockSlot(0), 0);
  EXPECT_EQ(L.clockCap(0), 8u); // one past the upper bound 7
  EXPECT_GE(L.clockSlot(1), 0);
  EXPECT_EQ(L.clockCap(1), 4u); // one past the lower bound 3 (upper inf)
  EXPECT_EQ(L.clockSlot(2), -1);
}

/// A model ready to step: parsed, laid out, in its initial state.
struct Stepper {
  llvm::SourceMgr sm;
  Design d;
  Module *m = nullptr;
  std::unique_ptr<StateLayout> L;
  std::unique_ptr<Semantics> sem;
  std::vector<uint64_t> init;
  RuntimeError err;
  explicit Stepper(const char *text) {
    m = parse(text, d, sm);
    if (!m)
      return;
    L = std::make_unique<StateLayout>(*m, 8);
    sem = std::make_unique<Semantics>(*m, *L, Options());
    init.resize(L->numWords());
    if (!sem->initialState(init.data(), err))
      m = nullptr;
  }
};

TEST(Semantics, ConflictingForcedTransitionsGiveOneSuccessorEach) {
  Stepper st("system S { place a(1), p(1), q, r; trans t : a -> (); "
             "trans u1 : p -> q on t; trans u2 : p -> r on t; }");
  ASSERT_NE(st.m, nullptr);
  RuntimeError &err = st.err;
  std::vector<std::vector<uint32_t>> steps;
  ASSERT_TRUE(st.sem->successors(
      st.init.data(),
      [&](llvm::ArrayRef<uint32_t> step, const uint64_t *) {
        steps.emplace_back(step.begin(), step.end());
      },
      err));
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0], (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(steps[1], (std::vector<uint32_t>{0, 2}));
}

TEST(Semantics, WriteConflictIsARuntimeError) {
  Stepper st("system S { var v : 0..3; place a(1), b(1); "
             "trans t : a -> () { v := 1; } "
             "trans u : b -> () on t { v := 2; } }");
  ASSERT_NE(st.m, nullptr);
  RuntimeError &err = st.err;
  EXPECT_FALSE(st.sem->successors(
      st.init.data(), [](llvm::ArrayRef<uint32_t>, const uint64_t *) {}, err));
  EXPECT_EQ(err.message, "transitions 't' and 'u' both write 'v' in one step");
}

} // namespace
