//===- KeyAttributesTest.cpp - exact covers against brute force -----------===//
#include "backends/structural/StructuralReasoning.h"

#include <gtest/gtest.h>

#include <random>

using namespace netlift::structural;

// Algorithm X finds exactly the minimum exact covers that trying every
// subset finds, on random region distributions.
TEST(KeyAttributes, AlgorithmXAgreesWithBruteForce) {
  std::mt19937 rng(7);
  for (int round = 0; round < 300; ++round) {
    size_t k = 2 + rng() % 7;
    std::vector<std::string> names;
    for (size_t i = 0; i < k; ++i)
      names.push_back("a" + std::to_string(i));
    Analysis a(names);
    // Regions drawn from a few "one-hot" groups so that covers exist often.
    size_t n = 1 + rng() % 12;
    for (size_t s = 0; s < n; ++s) {
      Region r = 0;
      for (size_t i = 0; i < k; ++i)
        if (rng() % 3 == 0)
          r |= Region(1) << i;
      if (r == 0 && round % 2)
        r = 1;
      a.addState(r, false);
    }
    std::vector<std::vector<size_t>> expected;
    for (size_t size = 1; size <= k && expected.empty(); ++size)
      for (Region set = 1; set < (Region(1) << k); ++set) {
        if (size_t(__builtin_popcount(set)) != size)
          continue;
        bool exact = true;
        for (auto &[r, c] : a.regionCounts())
          exact = exact && __builtin_popcount(r & set) == 1;
        if (!exact)
          continue;
        std::vector<size_t> idx;
        for (size_t i = 0; i < k; ++i)
          if ((set >> i) & 1)
            idx.push_back(i);
        expected.push_back(idx);
      }
    Analysis::KeyAttributes got = a.keyAttributes();
    EXPECT_EQ(got.exact, !expected.empty()) << "round " << round;
    if (got.exact) {
      EXPECT_EQ(got.sets, expected) << "round " << round;
    }
  }
}
