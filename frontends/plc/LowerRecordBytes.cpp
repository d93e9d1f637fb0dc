//===- LowerRecordBytes.cpp - structures and arrays seen as bytes --------===//
//
// `ADR(x)` of a structure or of an array of BOOLs, integers and REALs where
// a POINTER TO BYTE or a POINTER TO ARRAY[lo..hi] OF BYTE is wanted (a
// checksum over a record, a telegram assembled in place, OSCAT's buffer
// routines given a structure): the pointer sees the bytes x is held in,
// in the layout SIZEOF assumes (x64 alignment, `pack_mode`, little-endian
// scalars). A byte is read from the scalar that holds it (padding reads 0)
// and written into it with its other bytes kept (a byte written into
// padding is not kept: no program reads padding back). The family and
// its numbering are the scalar views' (RefView::Scalar with an aggregate
// `seen`, LowerReferences.cpp); this file is the byte arithmetic.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

static int64_t sizeOf(const PType *t) {
  std::string why;
  return memoryLayout(t, why)->size;
}

static bool isAggregate(const PType *t) {
  t = baseOf(t);
  return t->kind == PTypeKind::Struct || t->kind == PTypeKind::Array;
}

bool Lowering::seesRecordBytes(const RefView &view) {
  return view.kind == RefView::Scalar && view.seen && isAggregate(view.seen);
}

/// Element `k` (row-major, counted from 0) of the array `t` at `place`.
static NExpr *elementNumber(net::Builder &b, const PType *t, NExpr *place,
                            NExpr *k, SMLoc at) {
  auto *lit = llvm::dyn_cast<net::IntLit>(k);
  int64_t stride = 1;
  for (auto &[lo, hi] : t->dims)
    stride *= hi - lo + 1;
  NExpr *x = place;
  for (size_t d = 0; d < t->dims.size(); ++d) {
    auto [lo, hi] = t->dims[d];
    int64_t n = hi - lo + 1;
    stride /= n;
    // (k / stride) % n, the first dimension without the modulo (k lies
    // within the array).
    NExpr *i;
    if (lit) {
      int64_t v = lit->value / stride;
      i = b.intLit((d ? v % n : v) + lo, at);
    } else {
      i = stride > 1 ? b.binary(net::BinaryOp::Div, k, b.intLit(stride, at), at)
                     : k;
      if (d)
        i = b.binary(net::BinaryOp::Mod, i, b.intLit(n, at), at);
      if (lo)
        i = b.binary(net::BinaryOp::Add, i, b.intLit(lo, at), at);
    }
    x = b.index(x, i, at);
  }
  return x;
}

/// The element of the array `t` at `place` holding byte `pos`, and the
/// byte within it.
static std::pair<FreshPlace, FreshPlace>
arrayByte(net::Builder &b, const PType *t, const FreshPlace &place,
          const FreshPlace &pos, SMLoc at) {
  int64_t es = sizeOf(t->elem);
  auto *lit = llvm::dyn_cast<net::IntLit>(pos());
  std::optional<int64_t> known;
  if (lit)
    known = lit->value;
  FreshPlace element = [&b, t, &place, &pos, at, es, known] {
    NExpr *k = known ? b.intLit(*known / es, at)
               : es == 1
                   ? pos()
                   : b.binary(net::BinaryOp::Div, pos(), b.intLit(es, at), at);
    return elementNumber(b, t, place(), k, at);
  };
  FreshPlace within = [&b, &pos, at, es, known] {
    return known || es == 1
               ? b.intLit(known ? *known % es : 0, at)
               : b.binary(net::BinaryOp::Mod, pos(), b.intLit(es, at), at);
  };
  return {element, within};
}

std::vector<Lowering::FieldBytes>
Lowering::fieldsHolding(const PType *t, const FreshPlace &place,
                        const FreshPlace &pos, SMLoc at) {
  auto *lit = llvm::dyn_cast<net::IntLit>(pos());
  std::optional<int64_t> known;
  if (lit)
    known = lit->value;
  std::vector<int64_t> offsets = fieldOffsets(t);
  std::vector<FieldBytes> fields;
  for (size_t i = 0; i < t->fields.size(); ++i) {
    VarDecl *fld = t->fields[i];
    int64_t off = offsets[i], size = sizeOf(fld->type);
    if (known && (*known < off || *known >= off + size))
      continue;
    FieldBytes fb;
    fb.field = fld;
    fb.member = [this, &place, fld, at] {
      return b.field(place(), sanitize(fld->name), at);
    };
    fb.inside = [this, &pos, known, off, at] {
      return known ? b.intLit(*known - off, at)
                   : b.binary(net::BinaryOp::Sub, pos(), b.intLit(off, at), at);
    };
    fb.holds = [this, &pos, off, size, at] {
      return b.binary(
          net::BinaryOp::And,
          b.binary(net::BinaryOp::Ge, pos(), b.intLit(off, at), at),
          b.binary(net::BinaryOp::Lt, pos(), b.intLit(off + size, at), at), at);
    };
    fields.push_back(std::move(fb));
  }
  return fields;
}

NExpr *Lowering::recordByte(const PType *t, const FreshPlace &place,
                            const FreshPlace &pos, SMLoc at) {
  t = baseOf(t);
  auto *lit = llvm::dyn_cast<net::IntLit>(pos());
  switch (t->kind) {
  case PTypeKind::Array: {
    auto [element, within] = arrayByte(b, t, place, pos, at);
    return recordByte(t->elem, element, within, at);
  }
  case PTypeKind::String: // its characters, 0 at and past the end
    return b.call(
        net::Builtin::Code,
        {place(), b.binary(net::BinaryOp::Add, pos(), b.intLit(1, at), at)},
        at);
  case PTypeKind::Struct: {
    std::vector<FieldBytes> fields = fieldsHolding(t, place, pos, at);
    NExpr *r = b.intLit(0, at); // padding
    for (auto fb = fields.rbegin(); fb != fields.rend(); ++fb) {
      NExpr *byte = recordByte(fb->field->type, fb->member, fb->inside, at);
      if (lit)
        return byte;
      r = b.cond(fb->holds(), byte, r, at);
    }
    return r;
  }
  default: {
    // Little-endian: byte k is bits 8k..8k+7.
    if (t->kind == PTypeKind::Int && t->width == 8 && !t->isSigned)
      return place(); // a BYTE is its byte
    NExpr *bits = unionBits(t, place(), at);
    if (!lit || lit->value)
      bits = b.binary(net::BinaryOp::Shr, bits,
                      b.binary(net::BinaryOp::Mul, pos(), b.intLit(8, at), at),
                      at);
    return b.binary(net::BinaryOp::BitAnd, bits, b.intLit(255, at), at);
  }
  }
}

void Lowering::storeRecordByte(const PType *t, const FreshPlace &place,
                               const FreshPlace &pos, const FreshPlace &byte,
                               Sink &out, SMLoc at) {
  t = baseOf(t);
  auto *lit = llvm::dyn_cast<net::IntLit>(pos());
  switch (t->kind) {
  case PTypeKind::Array: {
    auto [element, within] = arrayByte(b, t, place, pos, at);
    storeRecordByte(t->elem, element, within, byte, out, at);
    return;
  }
  case PTypeKind::Struct: {
    std::vector<net::IfArm> arms;
    for (FieldBytes &fb : fieldsHolding(t, place, pos, at)) {
      if (lit) {
        storeRecordByte(fb.field->type, fb.member, fb.inside, byte, out, at);
        return;
      }
      Sink body;
      storeRecordByte(fb.field->type, fb.member, fb.inside, byte, body, at);
      arms.push_back({fb.holds(), design.copy(llvm::ArrayRef<NStmt *>(body))});
    }
    if (!arms.empty()) // a byte in padding is not kept
      out.push_back(b.ifStmt(arms, false, {}, at));
    return;
  }
  default: {
    int64_t bits = sizeOf(t) * 8;
    NExpr *shift =
        lit ? b.intLit(lit->value * 8, at)
            : b.binary(net::BinaryOp::Mul, pos(), b.intLit(8, at), at);
    NExpr *raw = insertBits(unionBits(t, place(), at), byte(), 8, shift, at);
    out.push_back(b.assign(place(), fromBits(t, raw, bits, at), at));
    return;
  }
  }
}

FreshPlace Lowering::positionValue(NExpr *v, int64_t lo, int64_t hi, Sink &pre,
                                   SMLoc at) {
  if (auto *lit = llvm::dyn_cast<net::IntLit>(v)) {
    int64_t k = lit->value;
    return [this, k, at] { return b.intLit(k, at); };
  }
  std::string name =
      scanVariable("_byte_at", design.types.getRange(lo, hi), lo, at);
  pre.push_back(b.assign(b.ref(name, at), v, at));
  return [this, name, at] { return b.ref(name, at); };
}

/// The place `l` reaches from `root` (its fields and constant indices).
NExpr *Lowering::leafPlace(NExpr *root, const MemoryLeaf &l, SMLoc at) {
  for (const MemoryLeaf::Step &s : l.path) {
    if (!s.field.empty()) {
      root = b.field(root, sanitize(s.field), at);
      continue;
    }
    for (int64_t i : s.index)
      root = b.index(root, b.intLit(i, at), at);
  }
  return root;
}

NExpr *Lowering::imageCopySpans(Expr *call, Frame &f, Sink &pre) {
  SMLoc at = call->loc;
  // One side of the copy: the bytes of a variable (or field), or of a
  // one-dimensional array from element i on (base: i's first byte).
  struct Span {
    Expr *place;
    const PType *type;
    FreshPlace base;
    int64_t size;
  };
  auto placeOf = [&](Expr *place) {
    return directPlace(place, call->name, f, pre);
  };
  auto spanOf = [&](Expr *adr) {
    Expr *x = adr->args[0].value;
    Span s{x, baseOf(x->type), nullptr, sizeOf(x->type)};
    if (!arrayElementPlace(x)) {
      s.base = [this, at] { return b.intLit(0, at); };
      return s;
    }
    s.place = x->base();
    s.type = baseOf(x->base()->type);
    auto [lo, hi] = s.type->dims[0];
    int64_t es = sizeOf(s.type->elem);
    s.size = (hi - lo + 1) * es;
    NExpr *i = checkedRange(expr(x->operands[1], f, pre), lo, hi,
                            sanitize(call->name) + "_index", pre, at);
    NExpr *first = b.binary(net::BinaryOp::Sub, i, b.intLit(lo, at), at);
    if (auto *lit = llvm::dyn_cast<net::IntLit>(i))
      first = b.intLit(lit->value - lo, at);
    if (es != 1)
      first = llvm::isa<net::IntLit>(first)
                  ? b.intLit(llvm::cast<net::IntLit>(first)->value * es, at)
                  : b.binary(net::BinaryOp::Mul, first, b.intLit(es, at), at);
    s.base = positionValue(first, 0, s.size - es, pre, at);
    return s;
  };
  Span dst = spanOf(call->args[0].value), src = spanOf(call->args[1].value);
  auto rootVar = [](Expr *e) -> VarDecl * {
    while (e && e->kind != ExprKind::Name)
      e = e->base();
    return e ? e->var : nullptr;
  };
  if (rootVar(dst.place) && rootVar(dst.place) == rootVar(src.place))
    refuse(at, call->name + " between places of different types within one "
                            "variable is not modelled");
  int64_t most = std::min(dst.size, src.size);
  FreshPlace count;
  if (call->intValue >= 0) {
    int64_t n = call->intValue;
    count = [this, n, at] { return b.intLit(n, at); };
  } else {
    // More than the smaller side holds is the range error of this
    // variable.
    std::string name = scanVariable(sanitize(call->name) + "_bytes",
                                    design.types.getRange(0, most), 0, at);
    pre.push_back(
        b.assign(b.ref(name, at), expr(call->args[2].value, f, pre), at));
    count = [this, name, at] { return b.ref(name, at); };
  }
  // Both sides must hold the bytes from their base on.
  std::vector<NExpr *> over;
  for (const Span *s : {&dst, &src}) {
    NExpr *end = b.binary(net::BinaryOp::Add, s->base(), count(), at);
    auto *base = llvm::dyn_cast<net::IntLit>(s->base());
    auto *n = llvm::dyn_cast<net::IntLit>(count());
    if (base && n) {
      if (base->value + n->value > s->size)
        refuse(at, call->name + " of " + Twine(n->value) + " bytes from byte " +
                       Twine(base->value) + " of " + s->type->str() + " (" +
                       Twine(s->size) + " bytes) overflows it");
      continue;
    }
    over.push_back(b.binary(net::BinaryOp::Gt, end, b.intLit(s->size, at), at));
  }
  failWhenAny(over, sanitize(call->name) + "_overflow", pre, at);
  FreshPlace srcPlace = [&] { return placeOf(src.place); };
  // The source's byte `rel` bytes after its base.
  auto sourceByte = [&](NExpr *rel) {
    FreshPlace pos = [&, rel] {
      return b.binary(net::BinaryOp::Add, src.base(), rel, at);
    };
    if (auto *base = llvm::dyn_cast<net::IntLit>(src.base()))
      if (auto *r = llvm::dyn_cast<net::IntLit>(rel)) {
        int64_t k = base->value + r->value;
        pos = [this, k, at] { return b.intLit(k, at); };
      }
    return recordByte(src.type, srcPlace, pos, at);
  };
  const PType *elem =
      dst.type->kind == PTypeKind::Array ? baseOf(dst.type->elem) : nullptr;
  if (elem && sizeOf(elem) == 1 && elem->kind != PTypeKind::Struct) {
    // A buffer of bytes: one element per byte copied, in a loop over as
    // many as the smaller side holds.
    std::string k = "_k" + std::to_string(++loopVars);
    int64_t lo = dst.type->dims[0].first;
    NExpr *target = b.index(
        placeOf(dst.place),
        b.binary(net::BinaryOp::Add,
                 b.binary(net::BinaryOp::Add, dst.base(), b.ref(k, at), at),
                 b.intLit(lo, at), at),
        at);
    Sink body{
        b.assign(target, fromBits(elem, sourceByte(b.ref(k, at)), 8, at), at)};
    Sink guarded{
        b.ifStmt({{b.binary(net::BinaryOp::Lt, b.ref(k, at), count(), at),
                   design.copy(llvm::ArrayRef<NStmt *>(body))}},
                 false, {}, at)};
    pre.push_back(
        b.forStmt(k, b.intLit(0, at), b.intLit(most - 1, at), guarded, at));
    return b.intLit(0, at);
  }
  // Otherwise every scalar of the target, each of its bytes the source's
  // where it lies among the bytes copied, all computed before any is
  // written.
  std::vector<MemoryLeaf> leaves;
  std::string why;
  memoryLeaves(dst.type, leaves, why);
  std::vector<std::pair<const MemoryLeaf *, NExpr *>> written;
  for (const MemoryLeaf &l : leaves) {
    NExpr *old = unionBits(l.type, leafPlace(placeOf(dst.place), l, at), at);
    NExpr *raw = nullptr;
    for (int64_t j = 0; j < l.size; ++j) {
      NExpr *rel = b.binary(net::BinaryOp::Sub, b.intLit(l.offset + j, at),
                            dst.base(), at);
      if (auto *base = llvm::dyn_cast<net::IntLit>(dst.base()))
        rel = b.intLit(l.offset + j - base->value, at);
      NExpr *copied =
          b.binary(net::BinaryOp::And,
                   b.binary(net::BinaryOp::Ge, rel, b.intLit(0, at), at),
                   b.binary(net::BinaryOp::Lt, rel, count(), at), at);
      NExpr *kept = old;
      if (j)
        kept = b.binary(net::BinaryOp::Shr, kept, b.intLit(8 * j, at), at);
      kept = b.binary(net::BinaryOp::BitAnd, kept, b.intLit(255, at), at);
      NExpr *byte = b.cond(copied, sourceByte(rel), kept, at);
      if (j)
        byte = b.binary(net::BinaryOp::Shl, byte, b.intLit(8 * j, at), at);
      raw = raw ? b.binary(net::BinaryOp::BitOr, raw, byte, at) : byte;
    }
    written.push_back({&l, raw});
  }
  storeLeavesTogether(
      written,
      [&](const MemoryLeaf &l) { return leafPlace(placeOf(dst.place), l, at); },
      pre, at);
  return b.intLit(0, at);
}

void Lowering::storeLeavesTogether(
    llvm::ArrayRef<std::pair<const MemoryLeaf *, NExpr *>> leaves,
    llvm::function_ref<NExpr *(const MemoryLeaf &)> placeOf, Sink &pre,
    SMLoc at) {
  // Every value computed before any is written: the source may share
  // bytes with the target, as MEMMOVE allows.
  std::vector<std::string> temps;
  for (auto &[l, raw] : leaves) {
    std::string tmp = unique("_memcpy");
    declareTemp(tmp, l->type, at);
    pre.push_back(
        b.assign(b.ref(tmp, at), fromBits(l->type, raw, 8 * l->size, at), at));
    temps.push_back(tmp);
  }
  for (size_t i = 0; i < leaves.size(); ++i)
    pre.push_back(b.assign(placeOf(*leaves[i].first), b.ref(temps[i], at), at));
}

NExpr *Lowering::directPlace(Expr *place, StringRef what, Frame &f, Sink &pre) {
  // Made afresh at each use: its selectors are constants or computed
  // before, nothing to evaluate again.
  size_t before = pre.size();
  NExpr *x = lvalue(place, f, pre);
  if (pre.size() != before)
    refuse(place->loc, what + " between places of different types: the "
                              "places must be variables and their fields "
                              "and elements, not reached through a "
                              "reference");
  return x;
}
