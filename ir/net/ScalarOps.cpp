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

OpError net::applyBinary(const BinaryExpr *b, int64_t x, int64_t y,
                         int64_t &out) {
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
    out = x < y;
    return OpError::None;
  case BinaryOp::Le:
    out = x <= y;
    return OpError::None;
  case BinaryOp::Gt:
    out = x > y;
    return OpError::None;
  case BinaryOp::Ge:
    out = x >= y;
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
