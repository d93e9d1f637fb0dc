//===- LowerUnions.cpp - UNION types in NetIR -----------------------------===//
//
// A UNION's members share their bytes (CODESYS and TwinCAT; IEC 61131-3 has
// no UNION). netlift holds a UNION of up to 8 bytes as one NetIR int64: its
// bytes, little-endian, as on the x86 and ARM targets those runtimes run on.
// Members are laid out as those compilers lay them out (natural alignment:
// a DINT at a multiple of 4 within a structure), every member at offset 0.
// Reading a member takes its bits and decodes them (sign-extension for a
// signed integer, `real32_from_bits` for a REAL, `<> 0` for a BOOL);
// writing one replaces its bits and keeps the others, so writing a DWORD and
// reading an ARRAY[0..3] OF BYTE or a REAL gives what the PLC gives.
// Members are scalars, or arrays and structures of them read and written
// element by element; TIME, dates, strings and enumerations are refused by
// name, as is a UNION larger than 8 bytes.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

namespace {
bool isUnion(const PType *t) {
  t = baseOf(t);
  return t && t->kind == PTypeKind::Struct && t->isUnion;
}
int64_t alignUp(int64_t n, int64_t a) { return (n + a - 1) / a * a; }
} // namespace

Lowering::UnionLayout Lowering::unionLayout(const PType *t, SMLoc at) {
  // Members are integers, bit strings, BOOL, REAL/LREAL, and arrays and
  // structures of them; their layout is the compilers' (memoryLayout).
  const PType *bad = nullptr;
  std::function<bool(const PType *)> held = [&](const PType *m) {
    m = baseOf(m);
    switch (m->kind) {
    case PTypeKind::Bool:
    case PTypeKind::Int:
    case PTypeKind::Real:
      return true;
    case PTypeKind::Array:
      return held(m->elem);
    case PTypeKind::Struct:
      return llvm::all_of(m->fields, [&](VarDecl *f) { return held(f->type); });
    default:
      bad = m;
      return false;
    }
  };
  std::string why;
  std::optional<MemoryLayout> l = held(t) ? memoryLayout(t, why) : std::nullopt;
  if (!l)
    refuse(at, "a UNION member of type " + (bad ? bad : baseOf(t))->str() +
                   " is not supported (netlift models UNIONs of integers, "
                   "bit strings, BOOL, REAL and LREAL, and arrays and "
                   "structures of them)");
  return {l->size, l->align};
}

const net::Type *Lowering::unionType(const PType *t, SMLoc at) {
  UnionLayout l = unionLayout(t, at);
  if (l.size > 8)
    refuse(at, "UNION " + t->str() + " holds " + Twine(l.size) +
                   " bytes; netlift holds UNIONs of up to 8 bytes");
  return design.types.getInt(64, true, net::Overflow::Wrap);
}

std::optional<Lowering::UnionPart> Lowering::unionPart(Expr *e, Frame &f,
                                                       Sink &pre) {
  if (e->kind != ExprKind::Field && e->kind != ExprKind::Index)
    return std::nullopt;
  Expr *base = e->base();
  std::optional<UnionPart> part = unionPart(base, f, pre);
  if (!part) {
    if (e->kind != ExprKind::Field || !isUnion(base->type))
      return std::nullopt;
    part = UnionPart{base, b.intLit(0, e->loc), baseOf(base->type)};
  }
  SMLoc at = e->loc;
  const PType *t = baseOf(part->type);
  if (e->kind == ExprKind::Field) {
    int64_t offset = 0;
    const PType *ft = nullptr;
    for (VarDecl *field : t->fields) {
      UnionLayout l = unionLayout(field->type, at);
      if (!t->isUnion)
        offset = alignUp(offset, l.align);
      if (sameName(field->name, e->name)) {
        ft = field->type;
        break;
      }
      if (!t->isUnion)
        offset += l.size;
    }
    if (!ft)
      refuse(at, "internal: no member '" + e->name + "' in " + t->str());
    if (!t->isUnion && offset)
      part->bitOffset = b.binary(net::BinaryOp::Add, part->bitOffset,
                                 b.intLit(offset * 8, at), at);
    part->type = ft;
    return part;
  }
  // An element: its row-major position times its size.
  int64_t elemBits = unionLayout(t->elem, at).size * 8;
  NExpr *pos = nullptr;
  for (size_t d = 0; d < t->dims.size(); ++d) {
    auto [lo, hi] = t->dims[d];
    // The index passes through a variable of type lo..hi, so one outside
    // the bounds is a runtime error naming them, as for any array.
    PType *bounds = unit.make<PType>(PTypeKind::Int);
    bounds->isSubrange = true;
    bounds->lo = lo;
    bounds->hi = hi;
    bounds->base = elementaryType("DINT");
    bounds->width = 32;
    std::string checked = unique("_union_index");
    declareTemp(checked, bounds, at);
    pre.push_back(
        b.assign(b.ref(checked, at), expr(e->operands[d + 1], f, pre), at));
    NExpr *i =
        b.binary(net::BinaryOp::Sub, b.ref(checked, at), b.intLit(lo, at), at);
    pos = pos ? b.binary(net::BinaryOp::Add,
                         b.binary(net::BinaryOp::Mul, pos,
                                  b.intLit(hi - lo + 1, at), at),
                         i, at)
              : i;
  }
  part->bitOffset = b.binary(
      net::BinaryOp::Add, part->bitOffset,
      b.binary(net::BinaryOp::Mul, pos, b.intLit(elemBits, at), at), at);
  part->type = t->elem;
  return part;
}

namespace {
/// The mask of a w-bit field, as an int64 (all ones for 64).
int64_t maskOf(int64_t bits) {
  return bits >= 64 ? -1 : (int64_t(1) << bits) - 1;
}
} // namespace

const PType *Lowering::scalarUnionMember(const UnionPart &p, SMLoc at) {
  const PType *t = baseOf(p.type);
  if (t->kind == PTypeKind::Array || t->kind == PTypeKind::Struct)
    refuse(at, "a UNION member of type " + t->str() +
                   " is read and written element by element");
  return t;
}

NExpr *Lowering::unionRead(const UnionPart &p, Frame &f, Sink &pre, SMLoc at) {
  const PType *t = scalarUnionMember(p, at);
  int64_t bits = unionLayout(t, at).size * 8;
  NExpr *whole = lvalue(p.unionExpr, f, pre);
  NExpr *raw = b.binary(net::BinaryOp::Shr, whole, p.bitOffset, at);
  return fromBits(t, raw, bits, at);
}

NExpr *Lowering::fromBits(const PType *t, NExpr *raw, int64_t bits, SMLoc at) {
  if (bits < 64)
    raw = b.binary(net::BinaryOp::BitAnd, raw, b.intLit(maskOf(bits), at), at);
  switch (t->kind) {
  case PTypeKind::Bool:
    return b.binary(net::BinaryOp::Ne, raw, b.intLit(0, at), at);
  case PTypeKind::Real:
    return b.call(t->width == 32 ? net::Builtin::Real32FromBits
                                 : net::Builtin::Real64FromBits,
                  {raw}, at);
  default: // an integer
    if (bits == 64)
      return t->isSigned ? raw : asUnsigned64(raw, elementaryType("LINT"), at);
    if (!t->isSigned)
      return raw;
    // Two's complement: the top bit set is a negative value.
    return b.cond(
        b.binary(net::BinaryOp::Ge, raw, b.intLit(int64_t(1) << (bits - 1), at),
                 at),
        b.binary(net::BinaryOp::Sub, raw, b.intLit(int64_t(1) << bits, at), at),
        raw, at);
  }
}

NExpr *Lowering::unionBits(const PType *t, NExpr *value, SMLoc at) {
  switch (t->kind) {
  case PTypeKind::Bool:
    return b.cond(value, b.intLit(1, at), b.intLit(0, at), at);
  case PTypeKind::Real: // a literal gets its width first
    return b.call(net::Builtin::Bits, {b.convert(floatType(t), value, at)}, at);
  default:
    if (t->width == 64 && !t->isSigned)
      return fromUnsigned64(value, elementaryType("LINT"), at);
    return value;
  }
}

NStmt *Lowering::unionWrite(const UnionPart &p, NExpr *value,
                            const PType *valueType, Frame &f, Sink &pre,
                            SMLoc at) {
  const PType *t = scalarUnionMember(p, at);
  int64_t bits = unionLayout(t, at).size * 8;
  NExpr *v = unionBits(t, coerce(value, valueType, t, at), at);
  if (bits < 64)
    v = insertBits(lvalue(p.unionExpr, f, pre), v, bits, p.bitOffset, at);
  return b.assign(lvalue(p.unionExpr, f, pre), v, at);
}

NExpr *Lowering::insertBits(NExpr *whole, NExpr *field, int64_t bits,
                            NExpr *offset, SMLoc at) {
  NExpr *mask = b.intLit(maskOf(bits), at);
  NExpr *kept =
      b.binary(net::BinaryOp::BitAnd, whole,
               b.unary(net::UnaryOp::BitNot,
                       b.binary(net::BinaryOp::Shl, mask, offset, at), at),
               at);
  NExpr *placed = b.binary(
      net::BinaryOp::Shl,
      b.binary(net::BinaryOp::BitAnd, field, b.intLit(maskOf(bits), at), at),
      offset, at);
  return b.binary(net::BinaryOp::BitOr, kept, placed, at);
}

NExpr *Lowering::unionInitialValue(VarDecl *v, Initializer *init,
                                   const PType *t, SMLoc at) {
  if (!init)
    return b.intLit(0, at);
  if (init->kind != Initializer::Struct || init->fields.size() != 1 ||
      !init->fields[0].second ||
      init->fields[0].second->kind != Initializer::Value)
    refuse(init->loc, "a UNION is initialised through one scalar member, "
                      "as in (dw := 16#12345678)");
  const PType *ft = nullptr;
  for (VarDecl *field : baseOf(t)->fields)
    if (sameName(field->name, init->fields[0].first))
      ft = baseOf(field->type);
  if (!ft || ft->kind == PTypeKind::Array || ft->kind == PTypeKind::Struct)
    refuse(init->loc, "a UNION is initialised through one scalar member, "
                      "as in (dw := 16#12345678)");
  Frame none;
  Sink pre;
  Expr *e = init->fields[0].second->value;
  NExpr *value = unionBits(ft, coerce(expr(e, none, pre), e->type, ft, at), at);
  if (!pre.empty())
    refuse(e->loc, "initial value of '" + v->name + "' must be a constant");
  int64_t bits = unionLayout(ft, at).size * 8;
  return bits < 64 ? b.binary(net::BinaryOp::BitAnd, value,
                              b.intLit(maskOf(bits), at), at)
                   : value;
}
