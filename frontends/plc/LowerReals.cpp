//===- LowerReals.cpp - REAL and LREAL in NetIR ---------------------------===//
//
// REAL and LREAL become NetIR's real32 and real64, which the engine computes
// bit for bit as the PLC does (docs/netir.md, "Floating point"). NetIR never
// converts implicitly, so every place IEC converts implicitly — an operand
// next to a wider REAL or an integer, an assignment, a parameter, a
// function's result — gets its conversion here, and an untyped real literal
// takes the float type of its context as IEC's ANY_REAL literal does.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

static bool isReal(const PType *t) { return t && t->kind == PTypeKind::Real; }

const net::Type *Lowering::floatType(const PType *t) {
  return design.types.getFloat(t->width == 32 ? 32 : 64);
}

NExpr *Lowering::unsigned64Literal(uint64_t v, SMLoc at) {
  const net::Type *u64 = design.types.getInt(64, false, net::Overflow::Wrap);
  NExpr *low =
      b.convert(u64, b.intLit(int64_t(v & uint64_t(INT64_MAX)), at), at);
  NExpr *r =
      b.binary(net::BinaryOp::Add,
               b.binary(net::BinaryOp::Add, low, b.intLit(INT64_MAX, at), at),
               b.intLit(1, at), at);
  unsigned64Literals.insert(r);
  return r;
}

NExpr *Lowering::asUnsigned64(NExpr *v, const PType *from, SMLoc at) {
  const net::Type *u64 = design.types.getInt(64, false, net::Overflow::Wrap);
  if (unsigned64Literals.count(v))
    return v;
  if (llvm::isa<net::IntLit>(v) && llvm::cast<net::IntLit>(v)->value >= 0)
    return v; // NetIR reads a constant as the uint64 it denotes
  if (!from->isSigned && from->kind == PTypeKind::Int)
    return b.convert(u64, v, at);
  // Two's complement, as IEC implementations convert: a negative value
  // wraps modulo 2^64. 2^63 is added as INT64_MAX, then 1, so that no
  // step leaves its domain.
  auto addHalf = [&](NExpr *x) {
    return b.binary(
        net::BinaryOp::Add,
        b.binary(net::BinaryOp::Add, x, b.intLit(INT64_MAX, at), at),
        b.intLit(1, at), at);
  };
  NExpr *shifted = addHalf(b.convert(u64, addHalf(v), at));
  return b.cond(b.binary(net::BinaryOp::Lt, v, b.intLit(0, at), at), shifted,
                b.convert(u64, v, at), at);
}

void Lowering::unifyUnsigned64(std::vector<NExpr *> &values,
                               llvm::ArrayRef<Expr *> sources, SMLoc at) {
  if (llvm::none_of(sources, [](Expr *s) {
        return s->type && isUnsigned64(baseOf(s->type));
      }))
    return;
  for (size_t i = 0; i < values.size(); ++i) {
    const PType *t = sources[i]->type ? baseOf(sources[i]->type) : nullptr;
    if (t && (t->kind == PTypeKind::Int || t->kind == PTypeKind::AnyInt) &&
        !isUnsigned64(t))
      values[i] = asUnsigned64(values[i], t, at);
  }
}

NExpr *Lowering::fromUnsigned64(NExpr *v, const PType *to, SMLoc at) {
  const net::Type *i64 = design.types.getInt(64, true, net::Overflow::Wrap);
  if (to->width < 64) {
    // The low bits, then the target's own wrap (two's complement).
    NExpr *low = b.binary(net::BinaryOp::BitAnd, v,
                          b.intLit((int64_t(1) << to->width) - 1, at), at);
    return wrapTo(b.convert(i64, low, at), to, {0, 0, false}, at);
  }
  // LINT: the same 64 bits, read signed.
  NExpr *high = b.binary(net::BinaryOp::Eq,
                         b.binary(net::BinaryOp::Shr, v, b.intLit(63, at), at),
                         b.intLit(0, at), at);
  NExpr *low = b.convert(
      i64, b.binary(net::BinaryOp::BitAnd, v, b.intLit(INT64_MAX, at), at), at);
  NExpr *negative =
      b.binary(net::BinaryOp::Sub,
               b.binary(net::BinaryOp::Sub, low, b.intLit(INT64_MAX, at), at),
               b.intLit(1, at), at);
  return b.cond(high, b.convert(i64, v, at), negative, at);
}

NExpr *Lowering::coerce(NExpr *v, const PType *from, const PType *to,
                        SMLoc at) {
  from = from ? baseOf(from) : nullptr;
  to = to ? baseOf(to) : nullptr;
  if (from && to && from->kind == PTypeKind::Enum && from->enumBase &&
      to->kind != PTypeKind::Enum)
    return coerce(enumToInteger(v, from, at), from->enumBase, to, at);
  if (isUnsigned64(to) && from &&
      (from->kind == PTypeKind::Int || from->kind == PTypeKind::AnyInt) &&
      !isUnsigned64(from))
    return asUnsigned64(v, from, at);
  if (!isReal(to) || !from || from == anyRealType())
    return v; // an untyped literal adopts the type in NetIR
  if (isReal(from))
    return from->width == to->width ? v : b.convert(floatType(to), v, at);
  if (auto *lit = llvm::dyn_cast<net::IntLit>(v))
    return b.realLit(double(lit->value), at);
  if (from->isInteger())
    return b.convert(floatType(to), v, at);
  return v; // not numeric: Sema has reported it
}

const PType *Lowering::commonReal(llvm::ArrayRef<Expr *> operands) {
  const PType *common = nullptr;
  for (Expr *e : operands) {
    const PType *t = e->type ? baseOf(e->type) : nullptr;
    if (!isReal(t) || t == anyRealType())
      continue;
    if (!common || t->width > common->width)
      common = t;
  }
  if (common)
    return common;
  for (Expr *e : operands)
    if (isReal(e->type))
      return anyRealType(); // literals only: NetIR gives them a width
  return nullptr;
}

NExpr *Lowering::realMath(Expr *e, llvm::ArrayRef<NExpr *> args, SMLoc at) {
  // NetIR's float built-ins are IEC's functions, spelled in lower case
  // (ATAN2 has none).
  std::optional<net::Builtin> fn =
      net::builtinNamed(StringRef(e->name).lower());
  if (!fn)
    refuse(at, "'" + e->name + "' is not a standard function netlift models");
  // The operands in the float type the function computes in.
  const PType *in =
      *fn == net::Builtin::Trunc ? baseOf(e->args[0].value->type) : e->type;
  if (!isReal(in))
    in = elementaryType("LREAL");
  std::vector<NExpr *> xs;
  for (size_t i = 0; i < args.size(); ++i)
    xs.push_back(coerce(args[i], e->args[i].value->type, in, at));
  if (*fn == net::Builtin::Trunc) // DINT, as CODESYS's TRUNC
    return b.convert(design.types.getInt(32, true, net::Overflow::Error),
                     b.call(net::Builtin::Trunc, xs, at), at);
  return b.call(*fn, xs, at);
}

NExpr *Lowering::convertReal(NExpr *v, const PType *from, const PType *to,
                             SMLoc at) {
  if (isReal(to)) {
    if (from->kind == PTypeKind::Bool)
      return b.cond(v, b.realLit(1.0, at), b.realLit(0.0, at), at);
    if (isReal(from) || from->isInteger())
      return coerce(v, from, to, at);
  } else if (isReal(from)) {
    if (to->kind == PTypeKind::Bool)
      return b.binary(net::BinaryOp::Ne, v, b.realLit(0.0, at), at);
    if (to->kind == PTypeKind::Int)
      // Rounded half away from zero; a value the target cannot hold is a
      // runtime error (CODESYS and TwinCAT call the result undefined).
      return b.convert(
          design.types.getInt(to->width, to->isSigned, net::Overflow::Error), v,
          at);
  }
  refuse(at, "conversion from " + from->str() + " to " + to->str() +
                 " is not supported");
}
