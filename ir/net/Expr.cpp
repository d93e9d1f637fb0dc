//===- Expr.cpp - NetIR guard and action language -------------------------===//
#include "ir/net/Expr.h"

using namespace netlift::net;
using llvm::StringRef;

StringRef netlift::net::spelling(UnaryOp op) {
  switch (op) {
  case UnaryOp::Not:
    return "not ";
  case UnaryOp::Neg:
    return "-";
  case UnaryOp::BitNot:
    return "~";
  }
  return "?";
}

StringRef netlift::net::spelling(BinaryOp op) {
  switch (op) {
  case BinaryOp::Or:
    return "or";
  case BinaryOp::Xor:
    return "xor";
  case BinaryOp::And:
    return "and";
  case BinaryOp::Eq:
    return "==";
  case BinaryOp::Ne:
    return "!=";
  case BinaryOp::Lt:
    return "<";
  case BinaryOp::Le:
    return "<=";
  case BinaryOp::Gt:
    return ">";
  case BinaryOp::Ge:
    return ">=";
  case BinaryOp::BitOr:
    return "|";
  case BinaryOp::BitXor:
    return "^";
  case BinaryOp::BitAnd:
    return "&";
  case BinaryOp::Shl:
    return "<<";
  case BinaryOp::Shr:
    return ">>";
  case BinaryOp::Add:
    return "+";
  case BinaryOp::Sub:
    return "-";
  case BinaryOp::Mul:
    return "*";
  case BinaryOp::Div:
    return "/";
  case BinaryOp::Mod:
    return "%";
  }
  return "?";
}

StringRef netlift::net::spelling(Builtin b) {
  switch (b) {
#define NETLIFT_BUILTIN(name, spelling, arity, summary)                        \
  case Builtin::name:                                                          \
    return spelling;
#include "ir/net/Builtins.def"
  }
  return "?";
}

std::string netlift::net::calleeSpelling(const CallExpr *c) {
  if (c->fn != Builtin::Convert)
    return spelling(c->fn).str();
  const Type *t = c->to;
  if (t->isString() || t->isBool())
    return t->str();
  return (t->isFloat()  ? "real"
          : t->isSigned ? "int"
                        : "uint") +
         std::to_string(t->width);
}

bool netlift::net::isStringBuiltin(Builtin b) {
  switch (b) {
  case Builtin::Len:
  case Builtin::Left:
  case Builtin::Right:
  case Builtin::Mid:
  case Builtin::Concat:
  case Builtin::Insert:
  case Builtin::Delete:
  case Builtin::Replace:
  case Builtin::Find:
  case Builtin::Code:
  case Builtin::WithCode:
  case Builtin::FormatDuration:
  case Builtin::FormatDate:
  case Builtin::FormatTod:
  case Builtin::FormatDt:
  case Builtin::ParseDuration:
  case Builtin::ParseDate:
  case Builtin::ParseTod:
  case Builtin::ParseDt:
    return true;
  default:
    return false;
  }
}

unsigned netlift::net::arity(Builtin b) {
  switch (b) {
#define NETLIFT_BUILTIN(name, spelling, arity, summary)                        \
  case Builtin::name:                                                          \
    return arity;
#include "ir/net/Builtins.def"
  }
  return 0;
}

std::optional<Builtin> netlift::net::builtinNamed(StringRef name) {
#define NETLIFT_BUILTIN(name_, spelling, arity, summary)                       \
  if (name == spelling && Builtin::name_ != Builtin::Convert)                  \
    return Builtin::name_;
#include "ir/net/Builtins.def"
  return std::nullopt;
}

int netlift::net::precedence(BinaryOp op) {
  switch (op) {
  case BinaryOp::Or:
    return 1;
  case BinaryOp::Xor:
    return 2;
  case BinaryOp::And:
    return 3;
  // 4 is prefix `not`.
  case BinaryOp::Eq:
  case BinaryOp::Ne:
  case BinaryOp::Lt:
  case BinaryOp::Le:
  case BinaryOp::Gt:
  case BinaryOp::Ge:
    return 5;
  case BinaryOp::BitOr:
    return 6;
  case BinaryOp::BitXor:
    return 7;
  case BinaryOp::BitAnd:
    return 8;
  case BinaryOp::Shl:
  case BinaryOp::Shr:
    return 9;
  case BinaryOp::Add:
  case BinaryOp::Sub:
    return 10;
  case BinaryOp::Mul:
  case BinaryOp::Div:
  case BinaryOp::Mod:
    return 11;
  }
  return 0;
}

bool netlift::net::evalConstInt(const Expr *e, int64_t &out) {
  if (auto *l = llvm::dyn_cast<IntLit>(e)) {
    out = l->value;
    return true;
  }
  if (auto *r = llvm::dyn_cast<Ref>(e)) {
    if (r->sym.kind == SymKind::EnumLit) {
      out = r->sym.index;
      return true;
    }
    return false;
  }
  if (auto *u = llvm::dyn_cast<UnaryExpr>(e)) {
    int64_t v;
    if (u->op != UnaryOp::Neg || !evalConstInt(u->operand, v))
      return false;
    out = -v;
    return true;
  }
  if (auto *b = llvm::dyn_cast<BinaryExpr>(e)) {
    int64_t x, y;
    if (!evalConstInt(b->lhs, x) || !evalConstInt(b->rhs, y))
      return false;
    switch (b->op) {
    case BinaryOp::Add:
      return !__builtin_add_overflow(x, y, &out);
    case BinaryOp::Sub:
      return !__builtin_sub_overflow(x, y, &out);
    case BinaryOp::Mul:
      return !__builtin_mul_overflow(x, y, &out);
    case BinaryOp::Div:
      if (y == 0 || (x == INT64_MIN && y == -1))
        return false;
      out = x / y;
      return true;
    default:
      return false;
    }
  }
  return false;
}

std::optional<double> netlift::net::evalConstReal(const Expr *e) {
  if (auto *i = llvm::dyn_cast<IntLit>(e))
    return double(i->value);
  if (auto *r = llvm::dyn_cast<RealLit>(e))
    return r->value;
  if (auto *u = llvm::dyn_cast<UnaryExpr>(e)) {
    auto a = evalConstReal(u->operand);
    if (!a || u->op != UnaryOp::Neg)
      return std::nullopt;
    return -*a;
  }
  auto *b = llvm::dyn_cast<BinaryExpr>(e);
  if (!b)
    return std::nullopt;
  auto x = evalConstReal(b->lhs), y = evalConstReal(b->rhs);
  if (!x || !y)
    return std::nullopt;
  switch (b->op) {
  case BinaryOp::Add:
    return *x + *y;
  case BinaryOp::Sub:
    return *x - *y;
  case BinaryOp::Mul:
    return *x * *y;
  case BinaryOp::Div:
    if (*y == 0)
      return std::nullopt;
    return *x / *y;
  default:
    return std::nullopt;
  }
}
