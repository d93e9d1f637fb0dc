//===- FlowSolverTest.cpp - crossing times of scalar flows ----------------===//
#include "ir/hybrid/FlowSolver.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace netlift::hybrid;

namespace {

Crossing cross(double (*f)(double), double from, double to) {
  Rate r;
  r.f = f;
  return timeToReach(r, from, to);
}

TEST(FlowSolver, OrificeEmptiesInFiniteTime) {
  // h' = -k*sqrt(h): sqrt(h) falls at k/2, so h0 = 9 empties at 2*3/k.
  auto drain = [](double h) { return -0.25 * std::sqrt(h); };
  Crossing c = cross(drain, 9, 0);
  ASSERT_TRUE(c.reached) << c.why;
  EXPECT_NEAR(c.time, 24, 24 * 1e-8);
  c = cross(drain, 1, 0);
  ASSERT_TRUE(c.reached) << c.why;
  EXPECT_NEAR(c.time, 8, 8 * 1e-8);
}

TEST(FlowSolver, HigherRootsToo) {
  // x' = -(x^(1/3)): x^(2/3) falls at 2/3, so from 8 (x^(2/3) = 4) it
  // takes 6.
  auto f = [](double x) { return -std::cbrt(x); };
  Crossing c = cross(f, 8, 0);
  ASSERT_TRUE(c.reached) << c.why;
  EXPECT_NEAR(c.time, 6, 6 * 1e-8);
}

TEST(FlowSolver, LipschitzEquilibriumIsOnlyApproached) {
  // A first-order lag and a quadratic approach never get there.
  Crossing c = cross([](double x) { return 100 - x; }, 0, 100);
  EXPECT_FALSE(c.reached);
  c = cross([](double x) { return -x * x; }, 1, 0);
  EXPECT_FALSE(c.reached);
  c = cross([](double x) { return -x; }, 1, 0);
  EXPECT_FALSE(c.reached);
}

} // namespace
