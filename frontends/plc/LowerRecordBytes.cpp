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

NExpr *Lowering::recordByte(const PType *t, const FreshPlace &place,
                            const FreshPlace &pos, SMLoc at) {
  t = baseOf(t);
  auto *lit = llvm::dyn_cast<net::IntLit>(pos());
  switch (t->kind) {
  case PTypeKind::Array: {
    int64_t es = sizeOf(t->elem);
    FreshPlace element = [&, t] {
      NExpr *k =
          lit ? b.intLit(lit->value / es, at)
              : b.binary(net::BinaryOp::Div, pos(), b.intLit(es, at), at);
      return elementNumber(b, t, place(), k, at);
    };
    FreshPlace within = [&] {
      return lit ? b.intLit(lit->value % es, at)
                 : b.binary(net::BinaryOp::Mod, pos(), b.intLit(es, at), at);
    };
    return recordByte(t->elem, element, within, at);
  }
  case PTypeKind::Struct: {
    std::vector<int64_t> offsets = fieldOffsets(t);
    NExpr *r = b.intLit(0, at); // padding
    for (size_t i = t->fields.size(); i-- > 0;) {
      VarDecl *fld = t->fields[i];
      int64_t off = offsets[i], size = sizeOf(fld->type);
      if (lit && (lit->value < off || lit->value >= off + size))
        continue;
      FreshPlace member = [&, fld] {
        return b.field(place(), sanitize(fld->name), at);
      };
      FreshPlace inside = [&, off] {
        return lit ? b.intLit(lit->value - off, at)
                   : b.binary(net::BinaryOp::Sub, pos(), b.intLit(off, at), at);
      };
      NExpr *byte = recordByte(fld->type, member, inside, at);
      if (lit)
        return byte;
      NExpr *in = b.binary(
          net::BinaryOp::And,
          b.binary(net::BinaryOp::Ge, pos(), b.intLit(off, at), at),
          b.binary(net::BinaryOp::Lt, pos(), b.intLit(off + size, at), at), at);
      r = b.cond(in, byte, r, at);
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
    int64_t es = sizeOf(t->elem);
    FreshPlace element = [&, t] {
      NExpr *k =
          lit ? b.intLit(lit->value / es, at)
              : b.binary(net::BinaryOp::Div, pos(), b.intLit(es, at), at);
      return elementNumber(b, t, place(), k, at);
    };
    FreshPlace within = [&] {
      return lit ? b.intLit(lit->value % es, at)
                 : b.binary(net::BinaryOp::Mod, pos(), b.intLit(es, at), at);
    };
    storeRecordByte(t->elem, element, within, byte, out, at);
    return;
  }
  case PTypeKind::Struct: {
    std::vector<int64_t> offsets = fieldOffsets(t);
    std::vector<net::IfArm> arms;
    for (size_t i = 0; i < t->fields.size(); ++i) {
      VarDecl *fld = t->fields[i];
      int64_t off = offsets[i], size = sizeOf(fld->type);
      if (lit && (lit->value < off || lit->value >= off + size))
        continue;
      FreshPlace member = [&, fld] {
        return b.field(place(), sanitize(fld->name), at);
      };
      FreshPlace inside = [&, off] {
        return lit ? b.intLit(lit->value - off, at)
                   : b.binary(net::BinaryOp::Sub, pos(), b.intLit(off, at), at);
      };
      if (lit) {
        storeRecordByte(fld->type, member, inside, byte, out, at);
        return;
      }
      Sink body;
      storeRecordByte(fld->type, member, inside, byte, body, at);
      NExpr *in = b.binary(
          net::BinaryOp::And,
          b.binary(net::BinaryOp::Ge, pos(), b.intLit(off, at), at),
          b.binary(net::BinaryOp::Lt, pos(), b.intLit(off + size, at), at), at);
      arms.push_back({in, design.copy(llvm::ArrayRef<NStmt *>(body))});
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
  std::string name = unique("_byte_at");
  b.addVar(name, design.types.getRange(lo, hi), b.intLit(lo, at), at);
  if (resetNames.insert(name).second)
    resets.push_back({name, b.intLit(lo, at)});
  pre.push_back(b.assign(b.ref(name, at), v, at));
  return [this, name, at] { return b.ref(name, at); };
}
