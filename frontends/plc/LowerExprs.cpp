//===- LowerExprs.cpp - PLC expressions in NetIR
//----------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

std::optional<int64_t> Lowering::constValue(Expr *e, Frame &f) {
  // Dates count nanoseconds, durations ticks: their arithmetic is
  // LowerDates.cpp's.
  if (!e || (e->type && e->type->kind == PTypeKind::Date) ||
      (e->kind == ExprKind::Binary && llvm::any_of(e->operands, [](Expr *o) {
         return o->type && o->type->kind == PTypeKind::Date;
       })))
    return std::nullopt;
  switch (e->kind) {
  case ExprKind::IntLit:
    if (e->beyondInt64)
      return std::nullopt; // a uint64, not an int64
    return e->intValue;
  case ExprKind::BoolLit:
    return e->intValue;
  case ExprKind::TimeLit:
    return ticks(e->intValue, e->loc);
  case ExprKind::Unary: {
    auto a = constValue(e->operands[0], f);
    if (!a)
      return a;
    if (e->op == Op::Neg)
      return -*a;
    if (e->op == Op::Not && e->type && e->type->kind == PTypeKind::Bool)
      return int64_t(!*a);
    if (e->op == Op::Plus)
      return a;
    return std::nullopt;
  }
  case ExprKind::Binary: {
    auto a = constValue(e->operands[0], f), c = constValue(e->operands[1], f);
    if (!a || !c)
      return std::nullopt;
    switch (e->op) {
    case Op::Add:
      return *a + *c;
    case Op::Sub:
      return *a - *c;
    case Op::Mul:
      return *a * *c;
    case Op::Div:
      return *c ? std::optional<int64_t>(*a / *c) : std::nullopt;
    case Op::Mod:
      return *c ? std::optional<int64_t>(*a % *c) : std::nullopt;
    default:
      return std::nullopt;
    }
  }
  case ExprKind::Name: {
    // A constant, or a variable nobody ever writes, has its initial value.
    VarDecl *v = e->var;
    if (!v || v->section == VarSection::Input || v->area() == 'I' ||
        v->section == VarSection::InOut || written.count(v) ||
        (v->owner && v->owner->kind != PouKind::Program && !v->constant))
      return std::nullopt;
    if (!v->type ||
        (v->type->kind != PTypeKind::Int && v->type->kind != PTypeKind::Time &&
         v->type->kind != PTypeKind::Bool))
      return std::nullopt;
    Initializer *init = v->typeSyntax ? v->typeSyntax->init : nullptr;
    if (!init)
      return v->type->isSubrange ? v->type->lo : 0;
    if (init->kind != Initializer::Value)
      return std::nullopt;
    return constValue(init->value, f);
  }
  default:
    return std::nullopt;
  }
}

Range Lowering::rangeOf(Expr *e) {
  const PType *t = e->type;
  Range full{0, 0, false};
  if (t && t->kind == PTypeKind::Bool)
    full = {0, 1, true};
  else if (t && t->kind == PTypeKind::Int)
    full = {t->lo, t->hi, true};
  switch (e->kind) {
  case ExprKind::IntLit:
    if (e->beyondInt64)
      return {0, 0, false};
    return {e->intValue, e->intValue, true};
  case ExprKind::Name:
  case ExprKind::Field:
  case ExprKind::Index:
    if (auto it = inputRanges.find(e->var); it != inputRanges.end())
      return {it->second.first, it->second.second, true};
    if (e->var && e->var->type && e->var->type->kind == PTypeKind::Int)
      return {e->var->type->lo, e->var->type->hi, true};
    return full;
  case ExprKind::Unary:
    if (e->op == Op::Neg) {
      Range a = rangeOf(e->operands[0]);
      if (a.exact && a.lo != INT64_MIN)
        return {-a.hi, -a.lo, true};
      return {0, 0, false};
    }
    return e->op == Op::Plus ? rangeOf(e->operands[0]) : full;
  case ExprKind::Binary: {
    Range a = rangeOf(e->operands[0]), c = rangeOf(e->operands[1]);
    if (!a.exact || !c.exact)
      return {0, 0, false};
    auto fits = [](__int128 v) {
      return v >= INT64_MIN / 4 && v <= INT64_MAX / 4;
    };
    __int128 lo, hi;
    switch (e->op) {
    case Op::Add:
      lo = __int128(a.lo) + c.lo;
      hi = __int128(a.hi) + c.hi;
      break;
    case Op::Sub:
      lo = __int128(a.lo) - c.hi;
      hi = __int128(a.hi) - c.lo;
      break;
    case Op::Mul: {
      __int128 p[] = {__int128(a.lo) * c.lo, __int128(a.lo) * c.hi,
                      __int128(a.hi) * c.lo, __int128(a.hi) * c.hi};
      lo = *std::min_element(p, p + 4);
      hi = *std::max_element(p, p + 4);
      break;
    }
    default:
      return full;
    }
    if (!fits(lo) || !fits(hi))
      return {0, 0, false};
    return {int64_t(lo), int64_t(hi), true};
  }
  default:
    return full;
  }
}

NExpr *Lowering::maskTo(NExpr *v, const PType *t, SMLoc at) {
  if (t->width >= 64)
    return v;
  int64_t mask = (int64_t(1) << t->width) - 1;
  return b.binary(net::BinaryOp::BitAnd, v, b.intLit(mask, at), at);
}

NExpr *Lowering::wrapTo(NExpr *v, const PType *t, Range r, SMLoc at) {
  t = t && t->isSubrange ? t->base : t;
  if (!t || t->kind != PTypeKind::Int || t->width >= 64)
    return v;
  if (r.exact && r.lo >= t->lo && r.hi <= t->hi)
    return v;
  if (!t->isSigned)
    return maskTo(v, t, at);
  int64_t half = int64_t(1) << (t->width - 1);
  NExpr *shifted = b.binary(net::BinaryOp::Add, v, b.intLit(half, at), at);
  return b.binary(net::BinaryOp::Sub, maskTo(shifted, t, at),
                  b.intLit(half, at), at);
}

NExpr *Lowering::varRef(VarDecl *v, Frame &f, SMLoc at) {
  auto alias = f.aliases.find(v);
  if (alias != f.aliases.end())
    return alias->second;
  if (!v->owner) // a global
    return b.ref(sanitize(v->name), at);
  if (v->section == VarSection::Stat && v->owner->kind != PouKind::Program)
    return b.ref(staticVar(v, at), at);
  if (f.self && v->owner != f.pou && v->section == VarSection::InOut)
    refuse(at, "VAR_IN_OUT '" + v->name + "' of '" + f.self->name +
                   "' used by a method called from outside the block's body "
                   "(it is bound only while the body runs)");
  return b.ref(f.prefixOf(v) + sanitize(v->name), at);
}

NExpr *Lowering::lvalue(Expr *e, Frame &f, Sink &pre) {
  if (throughReference(e))
    return placeThroughReference(e, f, pre, "bound to an output or passed");
  switch (e->kind) {
  case ExprKind::Name:
    if (!e->var)
      refuse(e->loc, "cannot assign to '" + e->name + "'");
    return varRef(e->var, f, e->loc);
  case ExprKind::Field: {
    Expr *base = e->base();
    for (Expr *x = base; x;
         x = x->kind == ExprKind::Field || x->kind == ExprKind::Index
                 ? x->base()
                 : nullptr)
      if (x->type && baseOf(x->type)->kind == PTypeKind::Struct &&
          baseOf(x->type)->isUnion)
        refuse(e->loc, "a UNION member is read and assigned here, not "
                       "written as an output, an in-out argument or a bit");
    if (base->type && base->type->kind == PTypeKind::FunctionBlock) {
      std::string path = instancePath(base, f) + "." + sanitize(e->var->name);
      if (f.external)
        externallyRead.insert(path);
      return b.ref(path, e->loc);
    }
    return b.field(lvalue(base, f, pre), sanitize(e->name), e->loc);
  }
  case ExprKind::Index: {
    if (isStringIndex(e))
      refuse(e->loc, "a character of a string (s[i]) is passed by reference "
                     "or bound to an output; netlift reads and assigns it");
    if (e->type && e->type->kind == PTypeKind::FunctionBlock)
      refuse(e->loc, "an element of an array of function block instances is "
                     "called, or its inputs and outputs are read or "
                     "assigned, but it is not passed or bound");
    NExpr *r = lvalue(e->base(), f, pre);
    for (size_t i = 1; i < e->operands.size(); ++i)
      r = b.index(r, expr(e->operands[i], f, pre), e->loc);
    return r;
  }
  default:
    refuse(e->loc, "cannot assign to this expression");
  }
}

NExpr *Lowering::expr(Expr *e, Frame &f, Sink &pre) {
  switch (e->kind) {
  case ExprKind::IntLit:
    if (e->beyondInt64)
      return unsigned64Literal(uint64_t(e->intValue), e->loc);
    if (e->type && e->type->kind == PTypeKind::Bool)
      return b.boolLit(e->intValue != 0, e->loc);
    // LWORD#1 is a uint64 where it stands, also under NOT or in SHL(...):
    // a bare NetIR constant would make `~1` a negative integer there.
    if (e->type && isUnsigned64(baseOf(e->type)))
      return b.convert(design.types.getInt(64, false, net::Overflow::Wrap),
                       b.intLit(e->intValue, e->loc), e->loc);
    return b.intLit(e->intValue, e->loc);
  case ExprKind::BoolLit:
    return b.boolLit(e->intValue != 0, e->loc);
  case ExprKind::TimeLit:
    return b.intLit(ticks(e->intValue, e->loc), e->loc);
  case ExprKind::RealLit:
    return b.realLit(e->realValue, e->loc);
  case ExprKind::StringLit:
    // Sema types a one-character literal met by a CHAR as that CHAR.
    return e->type && e->type->isChar() ? charLiteral(e) : stringLiteral(e);
  case ExprKind::DateLit:
    return b.intLit(e->intValue, e->loc); // nanoseconds
  case ExprKind::EnumLit:
    return b.ref(sanitize(e->type->name) + "#" +
                     sanitize(e->type->enumerators[e->enumValue]),
                 e->loc);
  case ExprKind::Name:
    if (e->type == nullType())
      return b.intLit(0, e->loc);
    if (!e->var && e->enumValue >= 0)
      return b.ref(sanitize(e->type->name) + "#" +
                       sanitize(e->type->enumerators[e->enumValue]),
                   e->loc);
    if (e->var && e->var->type &&
        e->var->type->kind == PTypeKind::FunctionBlock)
      refuse(e->loc, "a function block instance is not a value");
    return environmentValueOr(lvalue(e, f, pre), pre);
  case ExprKind::Field:
  case ExprKind::Index:
    if (isStringIndex(e))
      return stringByteRead(e, f, pre);
    if (throughReference(e))
      return readThroughReference(e, f, pre);
    if (memberOfChosenInstance(e, f))
      return chosenMemberRead(e, f, pre);
    if (auto part = unionPart(e, f, pre))
      return unionRead(*part, f, pre, e->loc);
    return environmentValueOr(lvalue(e, f, pre), pre);
  case ExprKind::BitAccess:
    return partRead(e, f, pre);
  case ExprKind::Deref:
    return readThroughReference(e, f, pre);
  case ExprKind::Unary: {
    NExpr *a = expr(e->operands[0], f, pre);
    switch (e->op) {
    case Op::Plus:
      return a;
    case Op::Neg:
      return wrapTo(b.unary(net::UnaryOp::Neg, a, e->loc), e->type, rangeOf(e),
                    e->loc);
    default: {
      const PType *t = e->type->isSubrange ? e->type->base : e->type;
      if (t->kind == PTypeKind::Bool)
        return b.unary(net::UnaryOp::Not, a, e->loc);
      NExpr *n = b.unary(net::UnaryOp::BitNot, a, e->loc);
      return t->kind == PTypeKind::Int && !t->isSigned ? maskTo(n, t, e->loc)
                                                       : n;
    }
    }
  }
  case ExprKind::Binary: {
    if (e->type && e->type->isReference())
      return pointerStep(e, f, pre);
    if (e->operands[0]->type->isReference() &&
        e->operands[1]->type->isReference() && e->op != Op::Eq &&
        e->op != Op::Ne)
      return pointerPairValue(e, f, pre);
    NExpr *l = expr(e->operands[0], f, pre);
    NExpr *r = expr(e->operands[1], f, pre);
    if (e->operands[0]->type->isReference() && e->operands[0]->type->elem) {
      // Two pointers far outside one block on one side have one number
      // but maybe two addresses: their equality is not known.
      auto table =
          refPlan.tables.find(referenceKey(e->operands[0]->type->elem));
      if (table != refPlan.tables.end())
        if (NExpr *far = farFromBlock(table->second, l, e->loc))
          failWhenAny(
              {b.binary(net::BinaryOp::And, far,
                        b.binary(net::BinaryOp::Eq, l, r, e->loc), e->loc)},
              stemOf(e->operands[0]) + "_far", pre, e->loc);
    }
    if (const PType *real = commonReal({e->operands[0], e->operands[1]})) {
      // Both operands in the REAL the operation is computed in.
      l = coerce(l, e->operands[0]->type, real, e->loc);
      r = coerce(r, e->operands[1]->type, real, e->loc);
    }
    if (e->op != Op::Pow) {
      // Next to a ULINT or LWORD, the other operand becomes one.
      std::vector<NExpr *> both{l, r};
      unifyUnsigned64(both, {e->operands[0], e->operands[1]}, e->loc);
      l = both[0];
      r = both[1];
    }
    if (e->op == Op::Pow) {
      const PType *in = baseOf(e->type);
      return b.call(net::Builtin::Expt,
                    {coerce(l, e->operands[0]->type, in, e->loc),
                     coerce(r, e->operands[1]->type, in, e->loc)},
                    e->loc);
    }
    const PType *lt = e->operands[0]->type;
    const PType *rt = e->operands[1]->type;
    {
      // An enumerator next to a number, or in arithmetic, is its value
      // (Sema took it as its base type); two of one enumeration are
      // ordered by their values (NetIR's enumerations are only equal or
      // not).
      const PType *le = baseOf(lt), *re = baseOf(rt);
      bool lEnum = le->kind == PTypeKind::Enum && le->enumBase;
      bool rEnum = re->kind == PTypeKind::Enum && re->enumBase;
      if (lEnum != rEnum || (lEnum && le != re) ||
          (lEnum && e->op != Op::Eq && e->op != Op::Ne)) {
        if (lEnum) {
          l = enumToInteger(l, le, e->loc);
          lt = le->enumBase;
        }
        if (rEnum) {
          r = enumToInteger(r, re, e->loc);
          rt = re->enumBase;
        }
      }
    }
    if ((e->op == Op::Add || e->op == Op::Sub) &&
        (baseOf(lt)->kind == PTypeKind::Date ||
         baseOf(rt)->kind == PTypeKind::Date))
      return dateArithmetic(e->op, l, lt, r, rt, e->loc);
    bool logical = lt && (lt->kind == PTypeKind::Bool);
    net::BinaryOp op;
    switch (e->op) {
    case Op::Or:
    case Op::OrElse:
      op = logical ? net::BinaryOp::Or : net::BinaryOp::BitOr;
      break;
    case Op::Xor:
      op = logical ? net::BinaryOp::Xor : net::BinaryOp::BitXor;
      break;
    case Op::And:
    case Op::AndThen:
      op = logical ? net::BinaryOp::And : net::BinaryOp::BitAnd;
      break;
    case Op::Eq:
      op = net::BinaryOp::Eq;
      break;
    case Op::Ne:
      op = net::BinaryOp::Ne;
      break;
    case Op::Lt:
      op = net::BinaryOp::Lt;
      break;
    case Op::Le:
      op = net::BinaryOp::Le;
      break;
    case Op::Gt:
      op = net::BinaryOp::Gt;
      break;
    case Op::Ge:
      op = net::BinaryOp::Ge;
      break;
    case Op::Add:
      op = net::BinaryOp::Add;
      break;
    case Op::Sub:
      op = net::BinaryOp::Sub;
      break;
    case Op::Mul:
      op = net::BinaryOp::Mul;
      break;
    case Op::Div:
      op = net::BinaryOp::Div;
      break;
    case Op::Mod:
      op = net::BinaryOp::Mod;
      break;
    default:
      refuse(e->loc, "unsupported operator");
    }
    // Booleans compared for order (FALSE < TRUE) become integers in NetIR.
    if (logical && (op == net::BinaryOp::Lt || op == net::BinaryOp::Le ||
                    op == net::BinaryOp::Gt || op == net::BinaryOp::Ge)) {
      l = b.cond(l, b.intLit(1, e->loc), b.intLit(0, e->loc), e->loc);
      r = b.cond(r, b.intLit(1, e->loc), b.intLit(0, e->loc), e->loc);
    }
    NExpr *v = b.binary(op, l, r, e->loc);
    if (op == net::BinaryOp::Add || op == net::BinaryOp::Sub ||
        op == net::BinaryOp::Mul || op == net::BinaryOp::Div)
      v = wrapTo(v, e->type, rangeOf(e), e->loc);
    return v;
  }
  case ExprKind::Call:
    if (e->callee)
      return functionCall(e, f, pre);
    if (e->name == "REF" || e->name == "ADR")
      return addressOf(e, f, pre);
    if (e->name == "MEMCPY" || e->name == "MEMMOVE" || e->name == "MEMSET" ||
        e->name == "MEMCMP")
      return memoryCall(e, f, pre);
    if (e->name == "__QUERYINTERFACE")
      return queryInterfaceCall(e, f, pre);
    if (e->name == "__UPCAST")
      return referenceUpcast(e, f, pre);
    if (e->name == "__ISVALIDREF")
      return b.binary(net::BinaryOp::Ne, expr(e->args[0].value, f, pre),
                      b.intLit(0, e->loc), e->loc);
    return stdCall(e, f, pre);
  }
  refuse(e->loc, "unsupported expression");
}

NExpr *Lowering::enumToInteger(NExpr *v, const PType *t, SMLoc at) {
  t = baseOf(t);
  auto literal = [&](size_t i) {
    return sanitize(t->name) + "#" + sanitize(t->enumerators[i]);
  };
  if (auto *r = llvm::dyn_cast<net::Ref>(v))
    for (size_t i = 0; i < t->enumerators.size(); ++i)
      if (r->name == literal(i))
        return b.intLit(t->enumValues[i], at);
  NExpr *x = b.intLit(t->enumValues.back(), at);
  for (size_t i = t->enumerators.size() - 1; i-- > 0;)
    x = b.cond(b.binary(net::BinaryOp::Eq, v, b.ref(literal(i), at), at),
               b.intLit(t->enumValues[i], at), x, at);
  return x;
}

NExpr *Lowering::integerToEnum(NExpr *v, const PType *t, Sink &pre, SMLoc at) {
  t = baseOf(t);
  auto literal = [&](size_t i) {
    return b.ref(sanitize(t->name) + "#" + sanitize(t->enumerators[i]), at);
  };
  size_t n = t->enumerators.size();
  if (auto *lit = llvm::dyn_cast<net::IntLit>(v)) {
    for (size_t i = 0; i < n; ++i)
      if (t->enumValues[i] == lit->value)
        return literal(i);
    refuse(at, "value " + Twine(lit->value) + " is none of the values of " +
                   t->str() + "'s enumerators");
  }
  // The enumerator's position, -1 for no enumerator's value: a run-time
  // error (the variable of its range cannot take it).
  NExpr *position = b.intLit(-1, at);
  for (size_t i = n; i-- > 0;)
    position = b.cond(
        b.binary(net::BinaryOp::Eq, v, b.intLit(t->enumValues[i], at), at),
        b.intLit(int64_t(i), at), position, at);
  NExpr *k = checkedRange(position, 0, int64_t(n) - 1,
                          sanitize(t->name) + "_value", pre, at);
  NExpr *x = literal(n - 1);
  for (size_t i = n - 1; i-- > 0;)
    x = b.cond(b.binary(net::BinaryOp::Eq, k, b.intLit(int64_t(i), at), at),
               literal(i), x, at);
  return x;
}

NExpr *Lowering::convert(NExpr *v, const PType *from, const PType *to,
                         SMLoc at) {
  if (from && to && baseOf(from)->kind == PTypeKind::Enum &&
      baseOf(from)->enumNamesAsText && baseOf(to)->isString()) {
    // {attribute 'to_string'}: the enumerator's name.
    const PType *t = baseOf(from);
    auto name = [&](size_t i) {
      std::u16string chars(t->enumerators[i].begin(), t->enumerators[i].end());
      return b.stringLit(llvm::ArrayRef<char16_t>(chars.data(), chars.size()),
                         at);
    };
    NExpr *x = name(t->enumerators.size() - 1);
    for (size_t i = t->enumerators.size() - 1; i-- > 0;)
      x = b.cond(
          b.binary(
              net::BinaryOp::Eq, v,
              b.ref(sanitize(t->name) + "#" + sanitize(t->enumerators[i]), at),
              at),
          name(i), x, at);
    return x;
  }
  if (from && baseOf(from)->kind == PTypeKind::Enum && baseOf(from)->enumBase &&
      to && baseOf(to)->kind != PTypeKind::Enum)
    return convert(enumToInteger(v, from, at), baseOf(from)->enumBase, to, at);
  from = from && from->isSubrange ? from->base : from;
  to = to && to->isSubrange ? to->base : to;
  if (!from || from->kind == PTypeKind::AnyInt)
    from = to;
  bool timeText = (from->kind == PTypeKind::Time && to->isString()) ||
                  (from->isString() && to->kind == PTypeKind::Time);
  if (from->kind == PTypeKind::Date || to->kind == PTypeKind::Date || timeText)
    return convertDate(v, from, to, at);
  if (from->kind == PTypeKind::String || to->kind == PTypeKind::String)
    return convertString(v, from, to, at);
  if (from->kind == PTypeKind::Time && to->kind == PTypeKind::Real)
    return timeInUnit(v, timeNumberNs(at), to, at);
  if (from->kind == PTypeKind::Real && to->kind == PTypeKind::Time) {
    // That many seconds or milliseconds, rounded up to whole ticks.
    NExpr *ns = b.binary(net::BinaryOp::Mul, coerce(v, from, anyRealType(), at),
                         b.realLit(double(timeNumberNs(at)), at), at);
    return nsToTicks(
        b.convert(design.types.getInt(64, true, net::Overflow::Error), ns, at),
        at);
  }
  if (from->kind == PTypeKind::Real || to->kind == PTypeKind::Real)
    return convertReal(v, from, to, at);
  if (to->kind == PTypeKind::Bool) {
    if (from->kind == PTypeKind::Bool)
      return v;
    return b.binary(net::BinaryOp::Ne, v, b.intLit(0, at), at);
  }
  auto isU64 = [](const PType *t) {
    return t->kind == PTypeKind::Int && t->width == 64 && !t->isSigned;
  };
  if (from->kind == PTypeKind::Bool && to->kind == PTypeKind::Int) {
    NExpr *bit = b.cond(v, b.intLit(1, at), b.intLit(0, at), at);
    return isU64(to) ? asUnsigned64(bit, elementaryType("USINT"), at) : bit;
  }
  if (from->kind == PTypeKind::Int && to->kind == PTypeKind::Int) {
    if (isU64(from) && isU64(to))
      return v;
    if (isU64(to))
      return asUnsigned64(v, from, at);
    if (isU64(from))
      return fromUnsigned64(v, to, at);
    return wrapTo(v, to, {from->lo, from->hi, true}, at);
  }
  if (from->kind == PTypeKind::Time && to->kind == PTypeKind::Int && isU64(to))
    return asUnsigned64(convert(v, from, elementaryType("LINT"), at),
                        elementaryType("LINT"), at);
  if (from->kind == PTypeKind::Int && to->kind == PTypeKind::Time &&
      isU64(from))
    return convert(fromUnsigned64(v, elementaryType("LINT"), at),
                   elementaryType("LINT"), to, at);
  if (from->kind == PTypeKind::Int && to->kind == PTypeKind::Time) {
    // That many seconds or milliseconds: whole ticks, else rounded up.
    int64_t unitNs = timeNumberNs(at);
    if (unitNs % tickNs == 0)
      return b.binary(net::BinaryOp::Mul, v, b.intLit(unitNs / tickNs, at), at);
    return nsToTicks(b.binary(net::BinaryOp::Mul, v, b.intLit(unitNs, at), at),
                     at);
  }
  if (from->kind == PTypeKind::Time && to->kind == PTypeKind::Int) {
    // Whole seconds, truncated toward zero; or milliseconds, which the
    // tick must hold whole.
    if (timeNumberNs(at) != 1000000)
      return timeInUnit(v, timeNumberNs(at), to, at);
    if (tickNs % 1000000 != 0)
      refuse(at, "TIME to integer conversion gives milliseconds, but a tick "
                 "is not a whole number of milliseconds (choose "
                 "--timescale)");
    NExpr *ms =
        b.binary(net::BinaryOp::Mul, v, b.intLit(tickNs / 1000000, at), at);
    return wrapTo(ms, to, {0, 0, false}, at);
  }
  if (from->kind == to->kind && from->kind == PTypeKind::Time)
    return v;
  return convertReal(v, from, to, at);
}

int64_t Lowering::timeNumberNs(SMLoc at) {
  if (!notedTimeNumbers) {
    notedTimeNumbers = true;
    diag.note(at, "TIME converts to and from numbers in " +
                      (unit.timeNumbersWhy.empty()
                           ? std::string("milliseconds, as CODESYS and "
                                         "TwinCAT convert")
                           : unit.timeNumbersWhy) +
                      " (--time-unit s or ms chooses)");
  }
  return unit.timeNumbers == TimeNumbers::Seconds ? 1000000000 : 1000000;
}

NExpr *Lowering::timeInUnit(NExpr *v, int64_t unitNs, const PType *to,
                            SMLoc at) {
  NExpr *ns = b.binary(net::BinaryOp::Mul, v, b.intLit(tickNs, at), at);
  // A REAL is the nanoseconds divided once in LREAL (so 1500 ms is exactly
  // 1.5 s), then narrowed once, as matiec does (and as CODESYS's whole
  // milliseconds convert); an integer counts whole units, truncated toward
  // zero as 4diac's integer division does.
  if (to->kind == PTypeKind::Real) {
    const net::Type *wide = floatType(elementaryType("LREAL"));
    NExpr *r = b.binary(net::BinaryOp::Div, b.convert(wide, ns, at),
                        b.realLit(double(unitNs), at), at);
    return floatType(to) == wide ? r : b.convert(floatType(to), r, at);
  }
  NExpr *n = unitNs == 1
                 ? ns
                 : b.binary(net::BinaryOp::Div, ns, b.intLit(unitNs, at), at);
  return convert(n, elementaryType("LINT"), to, at);
}

NExpr *Lowering::stdCall(Expr *e, Frame &f, Sink &pre) {
  if (!e->enable && !e->enableOut)
    return stdValue(e, f, pre);
  // With EN and ENO (matiec's rule): FALSE gives the type's initial value
  // and clears ENO.
  SMLoc at = e->loc;
  NExpr *en = e->enable ? expr(e->enable, f, pre) : b.boolLit(true, at);
  if (!llvm::isa<net::Ref>(en) && !llvm::isa<net::BoolLit>(en)) {
    std::string flag = unique(sanitize(e->name) + "_EN");
    declareTemp(flag, elementaryType("BOOL"), at);
    pre.push_back(b.assign(b.ref(flag, at), en, at));
    en = b.ref(flag, at);
  }
  if (e->enableOut)
    assign(lvalue(e->enableOut, f, pre), en, e->enableOut->type, nullptr, pre,
           at);
  NExpr *value = stdValue(e, f, pre);
  if (auto *lit = llvm::dyn_cast<net::BoolLit>(en); lit && lit->value)
    return value;
  NExpr *initial = defaultValue(e->type, at);
  if (!initial)
    refuse(at, "'" + e->name + "' with EN: its result has no initial value");
  return b.cond(en, value, initial, at);
}

NExpr *Lowering::stdValue(Expr *e, Frame &f, Sink &pre) {
  StdFnInfo info = lookupStdFunction(e->name);
  std::vector<NExpr *> a;
  std::vector<Expr *> src;
  for (CallArg &arg : e->args) {
    a.push_back(expr(arg.value, f, pre));
    src.push_back(arg.value);
  }
  SMLoc at = e->loc;
  if (info.fn != StdFn::RealMath && info.fn != StdFn::Convert) {
    // The value operands in the REAL they are computed in (SEL's and MUX's
    // selector aside).
    size_t first = info.fn == StdFn::Sel || info.fn == StdFn::Mux ? 1 : 0;
    std::vector<Expr *> values(src.begin() + std::min(first, src.size()),
                               src.end());
    if (const PType *real = commonReal(values))
      for (size_t i = first; i < a.size(); ++i)
        a[i] = coerce(a[i], src[i]->type, real, at);
    bool shifts = info.fn == StdFn::Shl || info.fn == StdFn::Shr ||
                  info.fn == StdFn::Rol || info.fn == StdFn::Ror;
    if (!shifts) {
      std::vector<NExpr *> tail(a.begin() + std::min(first, a.size()), a.end());
      unifyUnsigned64(tail, values, at);
      std::copy(tail.begin(), tail.end(),
                a.begin() + std::min(first, a.size()));
    }
  }
  auto chain = [&](net::BinaryOp op, size_t from, bool wrap) {
    NExpr *r = a[from];
    for (size_t i = from + 1; i < a.size(); ++i)
      r = b.binary(op, r, a[i], at);
    return wrap ? wrapTo(r, e->type, {0, 0, false}, at) : r;
  };
  bool logical =
      !src.empty() && src[0]->type && src[0]->type->kind == PTypeKind::Bool;
  switch (info.fn) {
  case StdFn::Abs:
    return wrapTo(b.call(net::Builtin::Abs, {a[0]}, at), e->type, {0, 0, false},
                  at);
  case StdFn::Min:
  case StdFn::Max: {
    net::Builtin fn =
        info.fn == StdFn::Min ? net::Builtin::Min : net::Builtin::Max;
    NExpr *r = a[0];
    for (size_t i = 1; i < a.size(); ++i)
      r = b.call(fn, {r, a[i]}, at);
    return r;
  }
  case StdFn::Limit:
    return b.call(net::Builtin::Max,
                  {a[0], b.call(net::Builtin::Min, {a[1], a[2]}, at)}, at);
  case StdFn::Sel:
    return b.cond(a[0], a[2], a[1], at);
  case StdFn::Mux: {
    // An out-of-range K is an error (IEC): storing it into a variable of
    // range 0..n-1 makes the model report it.
    std::string k = unique("MUX_" + std::to_string(++callSites) + ".K");
    PType *range = unit.make<PType>(*elementaryType("DINT"));
    range->name.clear();
    range->isSubrange = true;
    range->base = elementaryType("DINT");
    range->lo = 0;
    range->hi = int64_t(a.size()) - 2;
    declareTemp(k, range, at);
    pre.push_back(b.assign(b.ref(k, at), a[0], at));
    NExpr *r = a.back();
    for (size_t i = a.size() - 1; i-- > 1;)
      r = b.cond(b.binary(net::BinaryOp::Eq, b.ref(k, at),
                          b.intLit(int64_t(i) - 1, at), at),
                 a[i], r, at);
    return r;
  }
  case StdFn::Move:
    return a[0];
  case StdFn::Add:
  case StdFn::Sub:
    if (a.size() == 2 && (baseOf(src[0]->type)->kind == PTypeKind::Date ||
                          baseOf(src[1]->type)->kind == PTypeKind::Date))
      return dateArithmetic(info.fn == StdFn::Add ? Op::Add : Op::Sub, a[0],
                            src[0]->type, a[1], src[1]->type, at);
    return chain(info.fn == StdFn::Add ? net::BinaryOp::Add
                                       : net::BinaryOp::Sub,
                 0, true);
  case StdFn::Mul:
    return chain(net::BinaryOp::Mul, 0, true);
  case StdFn::Div:
    return chain(net::BinaryOp::Div, 0, true);
  case StdFn::Mod:
    return chain(net::BinaryOp::Mod, 0, false);
  case StdFn::And:
    return chain(logical ? net::BinaryOp::And : net::BinaryOp::BitAnd, 0,
                 false);
  case StdFn::Or:
    return chain(logical ? net::BinaryOp::Or : net::BinaryOp::BitOr, 0, false);
  case StdFn::Xor:
    return chain(logical ? net::BinaryOp::Xor : net::BinaryOp::BitXor, 0,
                 false);
  case StdFn::Not: {
    if (logical)
      return b.unary(net::UnaryOp::Not, a[0], at);
    const PType *t = e->type;
    NExpr *n = b.unary(net::UnaryOp::BitNot, a[0], at);
    return t->kind == PTypeKind::Int && !t->isSigned ? maskTo(n, t, at) : n;
  }
  case StdFn::Shl:
  case StdFn::Shr:
  case StdFn::Rol:
  case StdFn::Ror: {
    const PType *t = e->type->isSubrange ? e->type->base : e->type;
    NExpr *x =
        t->isSigned && info.fn != StdFn::Shl ? maskTo(a[0], t, at) : a[0];
    if (info.fn == StdFn::Shl)
      return wrapTo(b.binary(net::BinaryOp::Shl, x, a[1], at), t, {0, 0, false},
                    at);
    if (info.fn == StdFn::Shr)
      return wrapTo(b.binary(net::BinaryOp::Shr, x, a[1], at), t, {0, 0, false},
                    at);
    // Rotations by n mod width.
    NExpr *n = b.binary(net::BinaryOp::Mod, a[1], b.intLit(t->width, at), at);
    NExpr *back = b.binary(net::BinaryOp::Sub, b.intLit(t->width, at), n, at);
    NExpr *left = info.fn == StdFn::Rol ? n : back;
    NExpr *right = info.fn == StdFn::Rol ? back : n;
    NExpr *r =
        b.binary(net::BinaryOp::BitOr,
                 maskTo(b.binary(net::BinaryOp::Shl, x, left, at), t, at),
                 b.binary(net::BinaryOp::Shr, maskTo(x, t, at), right, at), at);
    return wrapTo(r, t, {0, 0, false}, at);
  }
  case StdFn::Gt:
  case StdFn::Ge:
  case StdFn::Eq:
  case StdFn::Le:
  case StdFn::Lt:
  case StdFn::Ne: {
    net::BinaryOp op = info.fn == StdFn::Gt   ? net::BinaryOp::Gt
                       : info.fn == StdFn::Ge ? net::BinaryOp::Ge
                       : info.fn == StdFn::Eq ? net::BinaryOp::Eq
                       : info.fn == StdFn::Le ? net::BinaryOp::Le
                       : info.fn == StdFn::Lt ? net::BinaryOp::Lt
                                              : net::BinaryOp::Ne;
    NExpr *r = b.binary(op, a[0], a[1], at);
    for (size_t i = 2; i < a.size(); ++i)
      r = b.binary(net::BinaryOp::And, r, b.binary(op, a[i - 1], a[i], at), at);
    return r;
  }
  case StdFn::Convert: {
    // LTIME_TO_STRING(a TIME) writes an LTIME: TIME and LTIME (and DT and
    // LDT...) share their representation, so the name says which it is.
    // An untyped literal is of the type the name converts from
    // (DINT_TO_TIME(3) is 3 DINT units, not 3 ticks).
    const PType *from = src[0]->type;
    NExpr *value = a[0];
    if (info.from && baseOf(from)->kind == PTypeKind::Enum) {
      // The enumerator's value, as the type the name converts from.
      value = convert(value, from, info.from, at);
      from = info.from;
    }
    if (info.from && (info.from->kind == PTypeKind::Time ||
                      info.from->kind == PTypeKind::Date ||
                      baseOf(from)->kind == PTypeKind::AnyInt))
      from = info.from;
    if (info.unitNs)
      return timeInUnit(value, info.unitNs, info.to, at);
    return convert(value, from, info.to, at);
  }
  case StdFn::RealMath:
    return realMath(e, a, at);
  case StdFn::StringOp:
    return stringFunction(e, a, at);
  case StdFn::Bcd:
    return bcdConversion(e, info, a[0], pre, at);
  case StdFn::Clock:
    return clockReading(e);
  case StdFn::Bound:
    return arrayBound(e, f);
  case StdFn::None:
    break;
  }
  refuse(at, "standard function '" + e->name + "' is not supported");
}

NExpr *Lowering::bcdConversion(Expr *call, const StdFnInfo &info, NExpr *v,
                               Sink &pre, SMLoc at) {
  const PType *src = baseOf(call->args[0].value->type);
  std::string stem =
      unique(sanitize(call->name) + "_" + std::to_string(++callSites));
  if (!info.toBcd) {
    // Each nibble a decimal digit (a larger one is a run-time error, the
    // check variable holding the largest), weighted by its power of ten.
    const PType *bits = info.from ? info.from : src;
    unsigned digits = (bits->kind == PTypeKind::AnyInt ? 32 : bits->width) / 4;
    std::vector<NExpr *> nibbles;
    for (unsigned k = 0; k < digits; ++k)
      nibbles.push_back(
          b.binary(net::BinaryOp::BitAnd,
                   b.binary(net::BinaryOp::Shr, v, b.intLit(4 * k, at), at),
                   b.intLit(15, at), at));
    std::string digit =
        scanVariable(stem + ".digit", design.types.getRange(0, 9), 0, at);
    NExpr *largest = nibbles[0];
    for (unsigned k = 1; k < digits; ++k)
      largest = b.call(net::Builtin::Max, {largest, nibbles[k]}, at);
    pre.push_back(b.assign(b.ref(digit, at), largest, at));
    NExpr *sum = nullptr;
    int64_t weight = 1;
    for (unsigned k = 0; k < digits; ++k, weight *= 10) {
      NExpr *term = weight == 1 ? nibbles[k]
                                : b.binary(net::BinaryOp::Mul, nibbles[k],
                                           b.intLit(weight, at), at);
      sum = sum ? b.binary(net::BinaryOp::Add, sum, term, at) : term;
    }
    return convert(sum, elementaryType("LINT"), info.to, at);
  }
  // The integer, checked to fit the digits, one decimal digit per nibble
  // (as many as the bit string the context gave INT_TO_BCD holds).
  unsigned digits = baseOf(call->type)->width / 4;
  int64_t limit = 1;
  for (unsigned k = 0; k < digits; ++k)
    limit *= 10;
  std::string value =
      scanVariable(stem + ".value", design.types.getRange(0, limit - 1), 0, at);
  pre.push_back(b.assign(b.ref(value, at), v, at));
  NExpr *r = nullptr;
  int64_t weight = 1;
  for (unsigned k = 0; k < digits; ++k, weight *= 10) {
    NExpr *digit =
        b.binary(net::BinaryOp::Mod,
                 weight == 1 ? b.ref(value, at)
                             : b.binary(net::BinaryOp::Div, b.ref(value, at),
                                        b.intLit(weight, at), at),
                 b.intLit(10, at), at);
    NExpr *placed =
        k == 0 ? digit
               : b.binary(net::BinaryOp::Shl, digit, b.intLit(4 * k, at), at);
    r = r ? b.binary(net::BinaryOp::BitOr, r, placed, at) : placed;
  }
  return r;
}
