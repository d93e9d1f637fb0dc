//===- FloatOps.h - what NetIR's operators compute on floats ----*- C++ -*-===//
//
// The values of NetIR's operators, built-ins and conversions on `real32`
// and `real64` operands, which the engine holds as their IEEE-754 bit
// patterns in 64-bit words (real32 zero-extended). + - * / and sqrt are
// computed in the operand's width with round-to-nearest-even, so they are
// bit-exact on every IEEE machine; the transcendental functions are glibc's
// (sinf for real32, sin for real64). Every NaN a computation produces is
// stored as the one positive quiet NaN, so states do not depend on the
// machine's NaN sign. One definition for every evaluator, as ScalarOps.h is
// for integers.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_FLOATOPS_H
#define NETLIFT_IR_NET_FLOATOPS_H

#include "ir/net/Expr.h"

#include <string>

namespace netlift::net {

/// The value a bit pattern of a float type denotes.
double floatValue(unsigned width, int64_t bits);
/// The bit pattern of `v` rounded to the width (NaN made canonical).
int64_t floatBits(unsigned width, double v);

/// `x op y` on two floats of one width: a bit pattern for + - * /, 0/1 for
/// comparisons (NaN compares unequal and unordered, as IEEE says).
int64_t applyFloatBinary(BinaryOp op, unsigned width, int64_t x, int64_t y);
/// `-x`.
int64_t applyFloatNeg(unsigned width, int64_t x);
/// A built-in on floats of one width (min, max, abs, sqrt, sin, ... expt).
int64_t applyFloatBuiltin(Builtin fn, unsigned width, int64_t a, int64_t b);

/// Why a conversion has no value.
enum class ConvertError : uint8_t { None, NotANumber, OutOfRange };
/// `to(v)` where v is of type `from` (integers, Booleans and floats; to is
/// a PLC integer or a float). Float to integer rounds half away from zero;
/// `trunc` (toInteger with truncate) rounds toward zero. A value the target
/// cannot hold is an error, whatever its overflow rule.
ConvertError convertValue(const Type *from, const Type *to, int64_t v,
                          int64_t &out);
/// trunc(x): a float's integer part as a 64-bit integer.
ConvertError truncToInteger(unsigned width, int64_t bits, int64_t &out);
/// Text for a value of a scalar type (floats in shortest round-trip form).
std::string formatScalar(const Type *t, int64_t v);

} // namespace netlift::net

#endif
