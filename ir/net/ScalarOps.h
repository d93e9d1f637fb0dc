//===- ScalarOps.h - what NetIR's operators compute on integers -*- C++ -*-===//
//
// The value of a NetIR unary or binary operator or built-in function on
// integer operands (Booleans are 0/1): exact 64-bit arithmetic, with
// overflow, division by zero and shifts outside 0..63 as errors. One
// definition for every evaluator (the semantics engine, predicates over
// state files), so they cannot disagree. `and`/`or` short-circuit and
// aggregate comparisons need their operands unevaluated: callers handle
// those.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_SCALAROPS_H
#define NETLIFT_IR_NET_SCALAROPS_H

#include "ir/net/Expr.h"

#include <string>

namespace netlift::net {

/// Why an operation has no value; the message is built only when needed,
/// as evaluation sits in the successor generator's hot path.
enum class OpError : uint8_t { None, Overflow, DivisionByZero, BadShift };
std::string opErrorMessage(OpError err, const Expr *e, int64_t rhs);

OpError applyBinary(const BinaryExpr *b, int64_t x, int64_t y, int64_t &out);
OpError applyUnary(const UnaryExpr *u, int64_t a, int64_t &out);
/// `abs(a)`, `min(a, b)`, `max(a, b)` (b unused for abs).
OpError applyBuiltin(const CallExpr *c, int64_t a, int64_t b, int64_t &out);

} // namespace netlift::net

#endif
