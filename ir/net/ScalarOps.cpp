//===- ScalarOps.cpp - what NetIR's operators compute on integers ---------===//
#include "ir/net/ScalarOps.h"

#include "ir/net/Printer.h"

using namespace netlift;
using namespace netlift::net;

std::string net::opErrorMessage(OpError err, const Expr *e, int64_t rhs) {
  switch (err) {
  case OpError::None:
    return "";
  case OpError::Overflow:
    return "arithmetic overflow";
  case OpError::DivisionByZero:
    return "division by zero in '" + exprToString(e) + "'";
  case OpError::BadShift:
    return "shift by " + std::to_string(rhs) + " is outside 0..63";
  }
  return "";
}

/// `x op y` for `<`, `<=`, `>`, `>=`, the operands read as T (int64_t or
/// uint64_t).
template <typename T> static int64_t ordered(BinaryOp op, T x, T y) {
  switch (op) {
  case BinaryOp::Lt:
    return x < y;
  case BinaryOp::Le:
    return x <= y;
  case BinaryOp::Gt:
    return x > y;
  default:
    return x >= y;
  }
}

/// The uint64 type an operation on `a` and `b` computes in, if any.
static const Type *unsigned64(const Type *a, const Type *b) {
  if (a && a->isUnsigned64())
    return a;
  if (b && b->isUnsigned64())
    return b;
  return nullptr;
}

/// `x op y` in unsigned 64-bit arithmetic: comparisons, division and
/// shifts unsigned; + - * modulo 2^64, an overflow an error when the type
/// says `error`.
static OpError applyUnsigned64(BinaryOp op, const Type *t, uint64_t x,
                               uint64_t y, int64_t &out) {
  uint64_t r = 0;
  bool overflow = false;
  switch (op) {
  case BinaryOp::Lt:
  case BinaryOp::Le:
  case BinaryOp::Gt:
  case BinaryOp::Ge:
    out = ordered(op, x, y);
    return OpError::None;
  case BinaryOp::Shr:
    if (y > 63)
      return OpError::BadShift;
    out = int64_t(x >> y);
    return OpError::None;
  case BinaryOp::Add:
    overflow = __builtin_add_overflow(x, y, &r);
    break;
  case BinaryOp::Sub:
    overflow = __builtin_sub_overflow(x, y, &r);
    break;
  case BinaryOp::Mul:
    overflow = __builtin_mul_overflow(x, y, &r);
    break;
  case BinaryOp::Div:
  case BinaryOp::Mod:
    if (y == 0)
      return OpError::DivisionByZero;
    r = op == BinaryOp::Div ? x / y : x % y;
    break;
  default:
    return OpError::None; // not reached: the caller computes the rest
  }
  if (overflow && t->overflow == Overflow::Error)
    return OpError::Overflow;
  out = int64_t(r);
  return OpError::None;
}

OpError net::applyBinary(const BinaryExpr *b, int64_t x, int64_t y,
                         int64_t &out) {
  if (const Type *u = unsigned64(b->lhs->type, b->rhs->type))
    switch (b->op) {
    case BinaryOp::Lt:
    case BinaryOp::Le:
    case BinaryOp::Gt:
    case BinaryOp::Ge:
    case BinaryOp::Shr:
    case BinaryOp::Add:
    case BinaryOp::Sub:
    case BinaryOp::Mul:
    case BinaryOp::Div:
    case BinaryOp::Mod:
      return applyUnsigned64(b->op, u, uint64_t(x), uint64_t(y), out);
    default:
      break; // bitwise and equality: the same on bit patterns
    }
  switch (b->op) {
  case BinaryOp::And:
    out = x && y;
    return OpError::None;
  case BinaryOp::Or:
    out = x || y;
    return OpError::None;
  case BinaryOp::Xor:
    out = (x != 0) != (y != 0);
    return OpError::None;
  case BinaryOp::Eq:
    out = x == y;
    return OpError::None;
  case BinaryOp::Ne:
    out = x != y;
    return OpError::None;
  case BinaryOp::Lt:
  case BinaryOp::Le:
  case BinaryOp::Gt:
  case BinaryOp::Ge:
    out = ordered(b->op, x, y);
    return OpError::None;
  case BinaryOp::BitOr:
    out = x | y;
    return OpError::None;
  case BinaryOp::BitXor:
    out = x ^ y;
    return OpError::None;
  case BinaryOp::BitAnd:
    out = x & y;
    return OpError::None;
  case BinaryOp::Shl:
  case BinaryOp::Shr:
    if (y < 0 || y > 63)
      return OpError::BadShift;
    out = b->op == BinaryOp::Shl ? int64_t(uint64_t(x) << y) : x >> y;
    return OpError::None;
  case BinaryOp::Add:
  case BinaryOp::Sub:
  case BinaryOp::Mul: {
    bool overflow = b->op == BinaryOp::Add ? __builtin_add_overflow(x, y, &out)
                    : b->op == BinaryOp::Sub
                        ? __builtin_sub_overflow(x, y, &out)
                        : __builtin_mul_overflow(x, y, &out);
    return overflow ? OpError::Overflow : OpError::None;
  }
  case BinaryOp::Div:
  case BinaryOp::Mod:
    if (y == 0)
      return OpError::DivisionByZero;
    if (x == INT64_MIN && y == -1)
      return OpError::Overflow;
    out = b->op == BinaryOp::Div ? x / y : x % y;
    return OpError::None;
  }
  out = 0;
  return OpError::None;
}

OpError net::applyUnary(const UnaryExpr *u, int64_t a, int64_t &out) {
  switch (u->op) {
  case UnaryOp::Not:
    out = !a;
    return OpError::None;
  case UnaryOp::BitNot:
    out = ~a;
    return OpError::None;
  case UnaryOp::Neg:
    if (a == INT64_MIN)
      return OpError::Overflow;
    out = -a;
    return OpError::None;
  }
  out = 0;
  return OpError::None;
}

OpError net::applyBuiltin(const CallExpr *c, int64_t a, int64_t b,
                          int64_t &out) {
  if (c->type && c->type->isUnsigned64()) {
    uint64_t x = uint64_t(a), y = uint64_t(b);
    out = int64_t(c->fn == Builtin::Min   ? std::min(x, y)
                  : c->fn == Builtin::Max ? std::max(x, y)
                                          : x); // abs
    return OpError::None;
  }
  switch (c->fn) {
  case Builtin::Abs:
    if (a == INT64_MIN)
      return OpError::Overflow;
    out = a < 0 ? -a : a;
    return OpError::None;
  case Builtin::Min:
    out = std::min(a, b);
    return OpError::None;
  case Builtin::Max:
    out = std::max(a, b);
    return OpError::None;
  default: // float functions and conversions: FloatOps.h
    break;
  }
  out = 0;
  return OpError::None;
}
