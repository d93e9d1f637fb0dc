//===- InputSplitterTest.cpp - decision prefixes and input order keys -----===//
#include "engine/SemanticsImpl.h"
#include "ir/net/FloatOps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <set>

using namespace netlift;
using namespace netlift::sem;

namespace {

using K = Semantics::Impl::KeyKind;

int64_t bits32(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return int64_t(b);
}

TEST(InputSplitter, RunsEveryCombinationOfChoicesOnce) {
  // An "execution" with two points: the second asks only when the first
  // chose segment 1 — as a branch taken in one class and not another.
  InputSplitter s;
  s.reset();
  std::set<std::pair<int, int>> seen;
  do {
    s.start();
    auto a = s.decide(0, [](std::vector<InputSplitter::Segment> &out) {
      out.push_back({0, 4, 0, false});
      out.push_back({5, 9, 1, false});
      out.push_back({10, 10, 2, false});
    });
    int b = -1;
    if (a.value == 1)
      b = int(s.decide(1, [](std::vector<InputSplitter::Segment> &out) {
                 out.push_back({0, 0, 0, false});
                 out.push_back({1, 1, 1, false});
               }).value);
    EXPECT_TRUE(seen.insert({int(a.value), b}).second);
  } while (s.advance());
  EXPECT_EQ(seen.size(), 4u);
  EXPECT_EQ(s.classesRun(), 4u);
}

TEST(InputSplitter, SingleSegmentsKeepReplayAligned) {
  // A point with one segment before a real decision: replay must still
  // find the decision at its position.
  InputSplitter s;
  s.reset();
  int runs = 0;
  do {
    s.start();
    s.decide(3, [](std::vector<InputSplitter::Segment> &out) {
      out.push_back({0, 1, 7, false});
    });
    auto b = s.decide(4, [](std::vector<InputSplitter::Segment> &out) {
      out.push_back({0, 0, 0, false});
      out.push_back({1, 1, 1, false});
    });
    EXPECT_EQ(b.value, runs);
    ++runs;
  } while (s.advance());
  EXPECT_EQ(runs, 2);
}

TEST(InputKeys, FloatKeysFollowTheNumbersOrder) {
  std::vector<float> xs = {-INFINITY, -3.4e38f, -1.0f, -1e-45f, -0.0f,
                           0.0f,      1e-45f,   1.0f,  3.4e38f, INFINITY};
  int64_t prev = INT64_MIN;
  for (float x : xs) {
    int64_t key = Semantics::Impl::keyOf(K::Float32, bits32(x));
    EXPECT_GT(key, prev) << x;
    prev = key;
    EXPECT_EQ(Semantics::Impl::valueOf(K::Float32, key), bits32(x)) << x;
  }
  // NaN (canonical, whatever its sign) just above +inf.
  int64_t nan = Semantics::Impl::keyOf(K::Float32, floatBits(32, NAN));
  EXPECT_EQ(nan, prev + 1);
  EXPECT_TRUE(
      std::isnan(floatValue(32, Semantics::Impl::valueOf(K::Float32, nan))));
  // Random patterns: keys are a bijection on non-NaN values and ordered.
  std::mt19937 rng(7);
  for (int i = 0; i < 100000; ++i) {
    uint32_t a = rng(), b = rng();
    float fa, fb;
    std::memcpy(&fa, &a, 4);
    std::memcpy(&fb, &b, 4);
    if (std::isnan(fa) || std::isnan(fb))
      continue;
    int64_t ka = Semantics::Impl::keyOf(K::Float32, a);
    int64_t kb = Semantics::Impl::keyOf(K::Float32, b);
    EXPECT_EQ(Semantics::Impl::valueOf(K::Float32, ka), int64_t(a));
    if (fa < fb) {
      EXPECT_LT(ka, kb);
    }
    if (fa == fb && a != b) { // -0 and +0: neighbours
      EXPECT_EQ(std::abs(ka - kb), 1);
    }
  }
}

TEST(InputKeys, DoubleAndUnsignedKeysFollowTheOrder) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 100000; ++i) {
    uint64_t a = rng(), b = rng();
    double da, db;
    std::memcpy(&da, &a, 8);
    std::memcpy(&db, &b, 8);
    int64_t ua = Semantics::Impl::keyOf(K::Unsigned64, int64_t(a));
    int64_t ub = Semantics::Impl::keyOf(K::Unsigned64, int64_t(b));
    EXPECT_EQ(a < b, ua < ub);
    EXPECT_EQ(Semantics::Impl::valueOf(K::Unsigned64, ua), int64_t(a));
    if (std::isnan(da) || std::isnan(db))
      continue;
    int64_t ka = Semantics::Impl::keyOf(K::Float64, int64_t(a));
    int64_t kb = Semantics::Impl::keyOf(K::Float64, int64_t(b));
    EXPECT_EQ(Semantics::Impl::valueOf(K::Float64, ka), int64_t(a));
    if (da < db) {
      EXPECT_LT(ka, kb);
    }
  }
}

} // namespace
