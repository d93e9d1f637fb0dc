//===- FloatOps.cpp - what NetIR's operators compute on floats ------------===//
//
// Built with -ffp-contract=off (ir/CMakeLists.txt): a fused multiply-add
// would round once where the PLC rounds twice.
//
//===----------------------------------------------------------------------===//
#include "ir/net/FloatOps.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace netlift;
using namespace netlift::net;

namespace {
float asFloat(int64_t bits) {
  uint32_t u = uint32_t(uint64_t(bits));
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}
double asDouble(int64_t bits) {
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}
int64_t bitsOf(float f) {
  if (std::isnan(f))
    return 0x7FC00000;
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return int64_t(u);
}
int64_t bitsOf(double d) {
  if (std::isnan(d))
    return int64_t(0x7FF8000000000000ull);
  int64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

/// `f` applied in the width: float functions for real32, double for real64.
template <typename F32, typename F64>
int64_t inWidth(unsigned width, int64_t a, F32 f32, F64 f64) {
  if (width == 32)
    return bitsOf(float(f32(asFloat(a))));
  return bitsOf(double(f64(asDouble(a))));
}
} // namespace

double net::floatValue(unsigned width, int64_t bits) {
  return width == 32 ? double(asFloat(bits)) : asDouble(bits);
}

int64_t net::floatBits(unsigned width, double v) {
  return width == 32 ? bitsOf(float(v)) : bitsOf(v);
}

int64_t net::applyFloatBinary(BinaryOp op, unsigned width, int64_t x,
                              int64_t y) {
  // Comparisons are exact in double for both widths.
  double a = floatValue(width, x), b = floatValue(width, y);
  switch (op) {
  case BinaryOp::Eq:
    return a == b;
  case BinaryOp::Ne:
    return a != b;
  case BinaryOp::Lt:
    return a < b;
  case BinaryOp::Le:
    return a <= b;
  case BinaryOp::Gt:
    return a > b;
  case BinaryOp::Ge:
    return a >= b;
  default:
    break;
  }
  if (width == 32) {
    float fa = asFloat(x), fb = asFloat(y);
    switch (op) {
    case BinaryOp::Add:
      return bitsOf(float(fa + fb));
    case BinaryOp::Sub:
      return bitsOf(float(fa - fb));
    case BinaryOp::Mul:
      return bitsOf(float(fa * fb));
    case BinaryOp::Div:
      return bitsOf(float(fa / fb));
    default:
      return 0;
    }
  }
  switch (op) {
  case BinaryOp::Add:
    return bitsOf(a + b);
  case BinaryOp::Sub:
    return bitsOf(a - b);
  case BinaryOp::Mul:
    return bitsOf(a * b);
  case BinaryOp::Div:
    return bitsOf(a / b);
  default:
    return 0;
  }
}

int64_t net::applyFloatNeg(unsigned width, int64_t x) {
  return width == 32 ? bitsOf(-asFloat(x)) : bitsOf(-asDouble(x));
}

int64_t net::applyFloatBuiltin(Builtin fn, unsigned width, int64_t a,
                               int64_t b) {
  double x = floatValue(width, a), y = floatValue(width, b);
  switch (fn) {
  case Builtin::Min:
  case Builtin::Max:
    if (std::isnan(x) || std::isnan(y))
      return floatBits(width, NAN);
    // -0.0 is below +0.0 here, as in an ordered comparison of bit patterns.
    if (x == y)
      return (std::signbit(x) == (fn == Builtin::Min)) ? a : b;
    return (fn == Builtin::Min) == (x < y) ? a : b;
  case Builtin::Abs:
    return inWidth(
        width, a, [](float f) { return std::fabs(f); },
        [](double d) { return std::fabs(d); });
  case Builtin::Sqrt:
    return inWidth(
        width, a, [](float f) { return std::sqrt(f); },
        [](double d) { return std::sqrt(d); });
  case Builtin::Sin:
    return inWidth(width, a, ::sinf, ::sin);
  case Builtin::Cos:
    return inWidth(width, a, ::cosf, ::cos);
  case Builtin::Tan:
    return inWidth(width, a, ::tanf, ::tan);
  case Builtin::Asin:
    return inWidth(width, a, ::asinf, ::asin);
  case Builtin::Acos:
    return inWidth(width, a, ::acosf, ::acos);
  case Builtin::Atan:
    return inWidth(width, a, ::atanf, ::atan);
  case Builtin::Ln:
    return inWidth(width, a, ::logf, ::log);
  case Builtin::Log:
    return inWidth(width, a, ::log10f, ::log10);
  case Builtin::Exp:
    return inWidth(width, a, ::expf, ::exp);
  case Builtin::Expt:
    if (width == 32)
      return bitsOf(::powf(asFloat(a), asFloat(b)));
    return bitsOf(::pow(x, y));
  default: // trunc, conversions and the string functions are elsewhere
    break;
  }
  return 0;
}

ConvertError net::truncToInteger(unsigned width, int64_t bits, int64_t &out) {
  double v = std::trunc(floatValue(width, bits));
  if (std::isnan(v))
    return ConvertError::NotANumber;
  // 2^63 is exactly representable; every double below it fits int64.
  if (!(v >= -9223372036854775808.0 && v < 9223372036854775808.0))
    return ConvertError::OutOfRange;
  out = int64_t(v);
  return ConvertError::None;
}

ConvertError net::convertValue(const Type *from, const Type *to, int64_t v,
                               int64_t &out) {
  bool fromU64 = from->isUnsigned64();
  if (to->isFloat()) {
    if (from->isFloat())
      out = floatBits(to->width, floatValue(from->width, v));
    else if (fromU64) // the nearest value, ties to even
      out = to->width == 32 ? bitsOf(float(uint64_t(v)))
                            : bitsOf(double(uint64_t(v)));
    else // integer to float: the nearest value, ties to even
      out = to->width == 32 ? bitsOf(float(v)) : bitsOf(double(v));
    return ConvertError::None;
  }
  if (to->isUnsigned64()) {
    if (from->isFloat()) {
      double d = std::round(floatValue(from->width, v));
      if (std::isnan(d))
        return ConvertError::NotANumber;
      if (!(d >= 0 && d < 18446744073709551616.0))
        return ConvertError::OutOfRange;
      out = int64_t(uint64_t(d));
      return ConvertError::None;
    }
    if (!fromU64 && v < 0)
      return ConvertError::OutOfRange;
    out = v;
    return ConvertError::None;
  }
  if (fromU64) {
    if (v < 0 || v > to->hi) // 2^63 and above, or beyond the target
      return ConvertError::OutOfRange;
    out = v;
    return ConvertError::None;
  }
  if (from->isFloat()) {
    double d = floatValue(from->width, v);
    if (std::isnan(d))
      return ConvertError::NotANumber;
    d = std::round(d); // half away from zero
    if (!(d >= double(to->lo) && d <= double(to->hi)) ||
        !(d >= -9223372036854775808.0 && d < 9223372036854775808.0))
      return ConvertError::OutOfRange;
    v = int64_t(d);
  }
  if (v < to->lo || v > to->hi)
    return ConvertError::OutOfRange;
  out = v;
  return ConvertError::None;
}

std::string net::formatScalar(const Type *t, int64_t v) {
  if (t && t->isUnsigned64())
    return std::to_string(uint64_t(v));
  if (!t || !t->isFloat())
    return std::to_string(v);
  if (t->width == 32) {
    float f = asFloat(v);
    if (std::isnan(f))
      return "nan";
    if (std::isinf(f))
      return f < 0 ? "-inf" : "inf";
    std::string s = fmt::format("{}", f);
    if (s.find_first_of(".eE") == std::string::npos)
      s += ".0";
    return s;
  }
  double d = asDouble(v);
  if (std::isnan(d))
    return "nan";
  return formatReal(d);
}
