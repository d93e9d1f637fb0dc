//===- LowerStrings.cpp - STRING and WSTRING in NetIR ---------------------===//
//
// STRING[n] and WSTRING[n] become NetIR's string[n] and wstring[n], which
// the engine executes (docs/netir.md, "Strings"): literals are decoded from
// IEC's `$` escapes, the standard string functions map one to one onto
// NetIR's built-ins (CONCAT's extra operands chained), and the conversions
// *_TO_STRING / STRING_TO_* onto NetIR conversions. CHAR and WCHAR hold a
// character's code (an unsigned integer of 8 or 16 bits): a one-character
// literal is its code, CHAR_TO_STRING the one-character string (empty for
// code 0, the terminator), STRING_TO_CHAR the first character's code (0 for
// an empty string), conversions to and from integers the code itself.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

const net::Type *Lowering::stringType(const PType *t, SMLoc at,
                                      StringRef what) {
  if (!t->isString())
    refuse(at, t->str() + " " + what +
                   ": single characters (CHAR, WCHAR) are not supported; "
                   "use STRING[1]");
  return design.types.getString(t->strLen, t->width == 16);
}

NExpr *Lowering::charLiteral(Expr *e) {
  std::u16string chars;
  if (auto err = decodeStringLiteral(e->name, chars))
    refuse(e->loc, *err); // Sema has reported it
  return b.intLit(chars.empty() ? 0 : int64_t(chars[0]), e->loc);
}

bool Lowering::isStringIndex(const Expr *e) {
  return e->kind == ExprKind::Index && e->operands.size() == 2 &&
         e->base()->type && baseOf(e->base()->type)->isString();
}

NExpr *Lowering::stringByteRead(Expr *e, Frame &f, Sink &pre) {
  SMLoc at = e->loc;
  NExpr *s = expr(e->base(), f, pre);
  NExpr *p = b.binary(net::BinaryOp::Add, expr(e->operands[1], f, pre),
                      b.intLit(1, at), at);
  return b.call(net::Builtin::Code, {s, p}, at);
}

void Lowering::stringByteWrite(Expr *target, NExpr *value, Frame &f, Sink &out,
                               SMLoc at) {
  Expr *base = target->base();
  NExpr *p = b.binary(net::BinaryOp::Add, expr(target->operands[1], f, out),
                      b.intLit(1, at), at);
  NExpr *updated =
      b.call(net::Builtin::WithCode, {expr(base, f, out), p, value}, at);
  if (throughReference(base)) {
    writeThroughReference(base, updated, base, f, out, at);
    return;
  }
  out.push_back(b.assign(lvalue(base, f, out), updated, at));
}

NExpr *Lowering::stringLiteral(Expr *e) {
  std::u16string chars;
  if (auto err = decodeStringLiteral(e->name, chars))
    refuse(e->loc, *err); // Sema has reported it
  return b.stringLit(llvm::ArrayRef<char16_t>(chars.data(), chars.size()),
                     e->loc);
}

NExpr *Lowering::stringFunction(Expr *e, llvm::ArrayRef<NExpr *> args,
                                SMLoc at) {
  // NetIR's string built-ins are IEC's functions, spelled in lower case.
  std::optional<net::Builtin> fn =
      net::builtinNamed(StringRef(e->name).lower());
  if (!fn)
    refuse(at, "'" + e->name + "' is not a standard function netlift models");
  if (*fn != net::Builtin::Concat)
    return b.call(*fn, args, at);
  // CONCAT(a, b, c) is concat(concat(a, b), c): nothing is cut on the way.
  NExpr *r = args[0];
  for (size_t i = 1; i < args.size(); ++i)
    r = b.call(net::Builtin::Concat, {r, args[i]}, at);
  return r;
}

NExpr *Lowering::convertString(NExpr *v, const PType *from, const PType *to,
                               SMLoc at) {
  auto refused = [&]() -> NExpr * {
    refuse(at, "conversion from " + from->str() + " to " + to->str() +
                   " is not supported");
  };
  // A character as the unsigned integer of its width.
  auto code = [&](const PType *c) {
    return elementaryType(c->width == 16 ? "WORD" : "BYTE");
  };
  if (from->isChar() && to->isString()) {
    const net::Type *one = design.types.getString(1, to->width == 16);
    NExpr *text =
        b.call(net::Builtin::WithCode,
               {b.convert(one, b.stringLit({}, at), at), b.intLit(1, at),
                convert(v, code(from), code(to), at)},
               at);
    return b.convert(stringType(to, at, "conversion result"), text, at);
  }
  if (from->isString() && to->isChar())
    return convert(b.call(net::Builtin::Code, {v, b.intLit(1, at)}, at),
                   elementaryType("DWORD"), code(to), at);
  if (from->isChar() || to->isChar()) {
    if (!(from->isChar() || from->kind == PTypeKind::Int) ||
        !(to->isChar() || to->kind == PTypeKind::Int))
      return refused();
    return convert(v, from->isChar() ? code(from) : from,
                   to->isChar() ? code(to) : to, at);
  }
  if (to->kind == PTypeKind::String) {
    if (!(from->isString() || from->kind == PTypeKind::Bool ||
          from->kind == PTypeKind::Int || from->kind == PTypeKind::Real))
      refused();
    // A REAL literal takes its float type from its context, which a
    // conversion to text does not give: the REAL or LREAL it is, first.
    if (from->kind == PTypeKind::Real && llvm::isa<net::RealLit>(v))
      v = b.convert(floatType(from), v, at);
    return b.convert(stringType(to, at, "conversion result"), v, at);
  }
  if (!from->isString())
    refused();
  switch (to->kind) {
  case PTypeKind::Bool:
    return b.convert(design.types.getBool(), v, at);
  case PTypeKind::Int:
    // The text must spell a value of the target type; anything else is a
    // runtime error (docs/netir.md, "Strings").
    return b.convert(
        design.types.getInt(to->width, to->isSigned, net::Overflow::Error), v,
        at);
  case PTypeKind::Real:
    return b.convert(floatType(to), v, at);
  default:
    return refused();
  }
}
