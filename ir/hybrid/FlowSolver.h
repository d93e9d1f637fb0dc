//===- FlowSolver.h - when a one-dimensional flow reaches a level -*- C++
//-*-===//
//
// The numerical core of `discretise`: for an autonomous scalar flow
// x' = f(x) started at `from`, the time at which x first equals `to`. The
// pass classifies each rate: a constant or an affine rate is solved in
// closed form; any other rate is integrated by an adaptive Dormand-Prince
// 5(4) Runge-Kutta method with event location (the step that crosses the
// level is shortened by Newton iteration until it lands on it). A level
// that the flow cannot reach — f is zero or points away somewhere between
// the two values, e.g. the end point of a first-order lag — is reported as
// unreachable instead of being integrated forever; but a rate vanishing at
// the level like a power below 1 (an orifice, k*sqrt(h)) reaches it in
// finite time, and that time is computed.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_HYBRID_FLOWSOLVER_H
#define NETLIFT_IR_HYBRID_FLOWSOLVER_H

#include "llvm/ADT/STLFunctionalExtras.h"

#include <optional>
#include <string>

namespace netlift::hybrid {

/// A rate x' = f(x) and what is known about its shape.
struct Rate {
  enum class Shape { Constant, Affine, General };
  Shape shape = Shape::General;
  /// Constant: f = b. Affine: f = a*x + b.
  double a = 0, b = 0;
  /// The rate as a function; always set.
  llvm::function_ref<double(double)> f;
  /// Forces the integrator even for constant and affine rates (used to
  /// cross-check the integrator against the closed forms).
  bool forceNumeric = false;
};

/// Relative tolerance the integrator guarantees on a reported time (the
/// documented bound; the local error control runs tighter).
constexpr double kRelativeTolerance = 1e-9;

struct Crossing {
  bool reached = false;
  double time = 0;
  /// Why not reached (for the report): e.g. "x' = 0 at 100".
  std::string why;
};

/// Time for x to go from `from` to `to` (either direction) under `rate`.
Crossing timeToReach(const Rate &rate, double from, double to);

/// "constant", "affine" or "numeric" (what timeToReach uses for `rate`).
const char *methodName(const Rate &rate);

} // namespace netlift::hybrid

#endif
