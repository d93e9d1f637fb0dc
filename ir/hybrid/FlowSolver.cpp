//===- FlowSolver.cpp - when a one-dimensional flow reaches a level -------===//
#include "ir/hybrid/FlowSolver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace netlift::hybrid;

const char *netlift::hybrid::methodName(const Rate &rate) {
  if (rate.forceNumeric)
    return "numeric";
  switch (rate.shape) {
  case Rate::Shape::Constant:
    return "constant";
  case Rate::Shape::Affine:
    return "affine";
  case Rate::Shape::General:
    break;
  }
  return "numeric";
}

static std::string fmtNum(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v == 0 ? 0.0 : v);
  return buf;
}

namespace {
/// One Dormand-Prince 5(4) step of x' = f(x): the fifth-order result and an
/// estimate of its local error.
struct DormandPrince {
  llvm::function_ref<double(double)> f;

  double step(double x, double h, double &err) const {
    double k1 = f(x);
    double k2 = f(x + h * (k1 / 5));
    double k3 = f(x + h * (3 * k1 / 40 + 9 * k2 / 40));
    double k4 = f(x + h * (44 * k1 / 45 - 56 * k2 / 15 + 32 * k3 / 9));
    double k5 = f(x + h * (19372 * k1 / 6561 - 25360 * k2 / 2187 +
                           64448 * k3 / 6561 - 212 * k4 / 729));
    double k6 =
        f(x + h * (9017 * k1 / 3168 - 355 * k2 / 33 + 46732 * k3 / 5247 +
                   49 * k4 / 176 - 5103 * k5 / 18656));
    double x5 = x + h * (35 * k1 / 384 + 500 * k3 / 1113 + 125 * k4 / 192 -
                         2187 * k5 / 6784 + 11 * k6 / 84);
    double k7 = f(x5);
    // Fifth- minus fourth-order weights.
    err = h * (71 * k1 / 57600 - 71 * k3 / 16695 + 71 * k4 / 1920 -
               17253 * k5 / 339200 + 22 * k6 / 525 - k7 / 40);
    return x5;
  }
};
} // namespace

/// Integrates from `from` until x reaches `to`; `bound` is an upper bound
/// of the true time (distance over the smallest sampled speed), past which
/// the integration gives up.
static Crossing integrate(llvm::function_ref<double(double)> f, double from,
                          double to, double bound) {
  DormandPrince dp{f};
  double dir = to > from ? 1 : -1;
  double scale = std::max({std::fabs(from), std::fabs(to), 1.0});
  // Local error per step, well under kRelativeTolerance on the total.
  double tol = 1e-13 * scale;
  double t = 0, x = from;
  double h = std::fabs(to - from) / std::fabs(f(from)) / 64;
  for (unsigned steps = 0; steps < 10000000; ++steps) {
    double err;
    double xn = dp.step(x, h, err);
    err = std::fabs(err);
    if (err > tol && h > 1e-300) {
      h *= std::max(0.1, 0.9 * std::pow(tol / err, 0.2));
      continue;
    }
    if (dir * (xn - to) >= 0) {
      // Event location: the step length that lands exactly on `to`, by
      // Newton's method on h (dx/dh = f(x(h))), starting from the linear
      // guess.
      double hs = (to - x) / f(x);
      for (int it = 0; it < 60; ++it) {
        double e2;
        double xs = dp.step(x, hs, e2);
        double r = xs - to;
        if (std::fabs(r) <= 1e-14 * scale)
          break;
        hs -= r / f(xs);
      }
      return {true, t + hs, ""};
    }
    t += h;
    x = xn;
    if (t > 2 * bound + 1e-9)
      break;
    double grow = err > 0 ? 0.9 * std::pow(tol / err, 0.2) : 5.0;
    h *= std::min(5.0, std::max(0.2, grow));
  }
  return {false, 0, "the integration did not reach " + fmtNum(to)};
}

/// The rate vanishes at `to` and nowhere before it. A Lipschitz rate only
/// approaches such a point (x - to decays exponentially); one that vanishes
/// like a power |x - to|^p with p < 1 reaches it in finite time, as a
/// tank draining through an orifice (h' = -k*sqrt(h)) empties. The order p
/// is read off the rate near `to`; the time is integrated up to 1e-9 of
/// the distance from `to`, and the rest taken from the power law.
static Crossing reachingStop(llvm::function_ref<double(double)> f, double from,
                             double to, double minSpeed) {
  double dir = to > from ? 1 : -1, span = std::fabs(to - from);
  double d1 = span * 1e-6, d2 = span * 1e-9;
  double v1 = f(to - dir * d1) * dir, v2 = f(to - dir * d2) * dir;
  std::string why = "x' = 0 at " + fmtNum(to);
  if (!(v1 > 0) || !(v2 > 0))
    return {false, 0, why};
  double order = std::log(v1 / v2) / std::log(d1 / d2);
  if (!(order < 0.99))
    return {false, 0, why}; // approached, never reached
  double end = to - dir * d2;
  Crossing c =
      integrate(f, from, end, std::fabs(end - from) / std::min(minSpeed, v2));
  if (c.reached)
    c.time += d2 / ((1 - order) * v2);
  return c;
}

Crossing netlift::hybrid::timeToReach(const Rate &rate, double from,
                                      double to) {
  if (from == to)
    return {true, 0, ""};
  double dir = to > from ? 1 : -1;
  // A scalar autonomous flow is monotone and cannot pass a point where its
  // rate is zero: the level is reached iff the rate points towards it on
  // the whole closed interval. Checked on a fine sample (an equilibrium
  // strictly between two samples with the same sign elsewhere would be
  // missed; the integrator's time bound still stops it).
  constexpr int kSamples = 4096;
  double minSpeed = INFINITY;
  for (int i = 0; i <= kSamples; ++i) {
    double x = from + (to - from) * double(i) / kSamples;
    double v = rate.f(x) * dir;
    if (i == kSamples && v == 0 && rate.shape == Rate::Shape::General)
      return reachingStop(rate.f, from, to, minSpeed);
    if (!(v > 0))
      return {false, 0, "x' = " + fmtNum(dir * v) + " at " + fmtNum(x)};
    minSpeed = std::min(minSpeed, v);
  }
  if (!rate.forceNumeric) {
    if (rate.shape == Rate::Shape::Constant ||
        (rate.shape == Rate::Shape::Affine && rate.a == 0))
      return {true, (to - from) / rate.b, ""};
    if (rate.shape == Rate::Shape::Affine) {
      // x(t) = (x0 - e) exp(a t) + e with e = -b/a the equilibrium.
      double e = -rate.b / rate.a;
      return {true, std::log((to - e) / (from - e)) / rate.a, ""};
    }
  }
  return integrate(rate.f, from, to, std::fabs(to - from) / minSpeed);
}
