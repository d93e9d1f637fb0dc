//===- LowerPointers.cpp - pointer arithmetic and memory functions --------===//
//
// What a program does with a pointer besides dereferencing it: steps it
// through the block it points into (`p + n * SIZEOF(T)`, `p[i]`), orders
// and subtracts two pointers into one block, calls an FB instance through
// a reference, and copies, fills or compares memory (MEMCPY, MEMMOVE,
// MEMSET, MEMCMP) element by element through the places a reference may
// designate. A pointer is its number (LowerReferences.cpp); numbers follow
// the addresses inside one contiguous block and just around it, which is
// what makes stepping and ordering meaningful; far outside only the side
// is kept (RefFamily::hasOutside, docs/st.md "References and pointers").
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Pointer arithmetic
//===----------------------------------------------------------------------===//

NExpr *Lowering::stepElements(Expr *e, Frame &f, Sink &pre, Expr *&start) {
  Expr *ptr = e->operands[0], *offset = e->operands[1];
  if (!ptr->type->isReference())
    std::swap(ptr, offset);
  SMLoc at = e->loc;
  std::string why;
  int64_t size = memoryLayout(e->type->elem, why)->size;
  // `p + a - b` is `(p + a) - b`: one move by a - b, so that a pointer
  // passing far outside its block on the way (ADR(s) + pos - 1 with a large
  // pos) comes back exactly.
  NExpr *inner = nullptr;
  if (ptr->kind == ExprKind::Binary &&
      (ptr->op == Op::Add || ptr->op == Op::Sub) && ptr->type &&
      ptr->type->isReference() &&
      referenceKey(ptr->type->elem) == referenceKey(e->type->elem))
    inner = stepElements(ptr, f, pre, start);
  else
    start = ptr;
  NExpr *d = elementsIn(offset, size, f, pre);
  if (e->op == Op::Sub)
    d = llvm::isa<net::IntLit>(d)
            ? b.intLit(-llvm::cast<net::IntLit>(d)->value, at)
            : b.unary(net::UnaryOp::Neg, d, at);
  if (!inner)
    return d;
  auto *innerLit = llvm::dyn_cast<net::IntLit>(inner);
  auto *dLit = llvm::dyn_cast<net::IntLit>(d);
  if (innerLit && dLit)
    return b.intLit(innerLit->value + dLit->value, at);
  return b.binary(net::BinaryOp::Add, inner, d, at);
}

NExpr *Lowering::elementsIn(Expr *bytes, int64_t size, Frame &f, Sink &pre) {
  SMLoc at = bytes->loc;
  // Whole elements (Sema checked the bytes are written as a multiple):
  // `i * SIZEOF(T)` is i elements, without computing the bytes.
  if (bytes->kind == ExprKind::Binary && bytes->op == Op::Mul) {
    NExpr *l = expr(bytes->operands[0], f, pre);
    NExpr *r = expr(bytes->operands[1], f, pre);
    auto isSize = [&](NExpr *x) {
      auto *lit = llvm::dyn_cast<net::IntLit>(x);
      return lit && lit->value == size;
    };
    if (isSize(r))
      return l;
    if (isSize(l))
      return r;
    auto *lLit = llvm::dyn_cast<net::IntLit>(l);
    auto *rLit = llvm::dyn_cast<net::IntLit>(r);
    if (lLit && rLit)
      return b.intLit(lLit->value * rLit->value / size, at);
    NExpr *n = b.binary(net::BinaryOp::Mul, l, r, at);
    return size == 1 ? n
                     : b.binary(net::BinaryOp::Div, n, b.intLit(size, at), at);
  }
  NExpr *n = expr(bytes, f, pre);
  if (auto *lit = llvm::dyn_cast<net::IntLit>(n))
    return b.intLit(lit->value / size, at);
  return size == 1 ? n
                   : b.binary(net::BinaryOp::Div, n, b.intLit(size, at), at);
}

NExpr *Lowering::pointerStep(Expr *e, Frame &f, Sink &pre) {
  SMLoc at = e->loc;
  const PType *elem = e->type->elem;
  Expr *ptr = nullptr;
  NExpr *d = stepElements(e, f, pre, ptr);
  NExpr *k = expr(ptr, f, pre);
  auto table = refPlan.tables.find(referenceKey(elem));
  int64_t count = table == refPlan.tables.end() ? 0 : table->second.count;
  std::string stem = stemOf(ptr);
  auto *kLit = llvm::dyn_cast<net::IntLit>(k);
  auto *dLit = llvm::dyn_cast<net::IntLit>(d);
  if (kLit && dLit && kLit->value >= 1 && kLit->value <= count) {
    // Known now: moved now, and checked now.
    for (const RefFamily &fam : table->second.families) {
      if (!fam.holds(kLit->value, /*withOutside=*/true))
        continue;
      int64_t from = kLit->value - fam.offset, by = dLit->value;
      if (fam.hasOutside) {
        if ((kLit->value == fam.farBelow() && by > 0) ||
            (kLit->value == fam.farAbove() && by < 0))
          refuse(at, "the pointer comes back from far outside '" + fam.key +
                         "', where netlift does not keep its distance");
        int64_t to = std::clamp(from + by, fam.farBelow() - fam.offset,
                                fam.farAbove() - fam.offset);
        return b.intLit(fam.offset + to, at);
      }
      int64_t block = contiguousBlock(fam);
      int64_t pos = from % block + by;
      if (pos < 0 || pos >= block)
        refuse(at, "the pointer moves " + Twine(by) +
                       " element(s) out of the " + Twine(block) +
                       " of its array");
      return b.intLit(kLit->value + by, at);
    }
  }
  // NULL moves nowhere: a run-time error, as a dereference.
  std::string number = scanVariable(
      stem + "_deref", design.types.getRange(1, std::max<int64_t>(count, 1)), 1,
      at);
  pre.push_back(b.assign(b.ref(number, at), k, at));
  if (count == 0)
    return b.intLit(0, at);
  // A step longer than every place of the type leaves any block: its
  // length beyond that is not needed.
  std::string step = scanVariable(
      stem + "_step", design.types.getRange(-count - 1, count + 1), 0, at);
  if (!llvm::isa<net::IntLit>(d)) {
    std::string raw = scanVariable(
        stem + "_offset", design.types.getInt(64, true, net::Overflow::Error),
        0, at);
    pre.push_back(b.assign(b.ref(raw, at), d, at));
    NExpr *r = b.ref(raw, at);
    d = b.cond(
        b.binary(net::BinaryOp::Lt, r, b.intLit(-count - 1, at), at),
        b.intLit(-count - 1, at),
        b.cond(b.binary(net::BinaryOp::Gt, r, b.intLit(count + 1, at), at),
               b.intLit(count + 1, at), r, at),
        at);
  }
  pre.push_back(b.assign(b.ref(step, at), d, at));
  NExpr *num = b.ref(number, at), *by = b.ref(step, at);
  auto lit = [&](int64_t v) { return b.intLit(v, at); };
  // Far outside a block only the side is kept: moving back towards it
  // would need the distance.
  std::vector<NExpr *> back;
  for (const RefFamily &fam : table->second.families)
    if (fam.hasOutside) {
      back.push_back(
          b.binary(net::BinaryOp::And,
                   b.binary(net::BinaryOp::Eq, num, lit(fam.farBelow()), at),
                   b.binary(net::BinaryOp::Gt, by, lit(0), at), at));
      back.push_back(
          b.binary(net::BinaryOp::And,
                   b.binary(net::BinaryOp::Eq, num, lit(fam.farAbove()), at),
                   b.binary(net::BinaryOp::Lt, by, lit(0), at), at));
    }
  failWhenAny(back, stem + "_from_far", pre, at);
  std::string moved =
      scanVariable(stem + "_moved", design.types.getRange(1, count), 1, at);
  std::vector<net::IfArm> arms;
  for (const RefFamily &fam : table->second.families) {
    NExpr *inFamily =
        b.binary(net::BinaryOp::And,
                 b.binary(net::BinaryOp::Ge, num, lit(fam.first()), at),
                 b.binary(net::BinaryOp::Le, num, lit(fam.last()), at), at);
    NExpr *pos = b.binary(net::BinaryOp::Sub, num, lit(fam.offset), at);
    Sink body;
    if (fam.hasOutside) {
      // Exact from one before the first element to the end; beyond, on
      // either side, the number for every address there.
      int64_t lo = fam.farBelow() - fam.offset,
              hi = fam.farAbove() - fam.offset;
      std::string to = scanVariable(
          stem + "_to", design.types.getRange(lo - count, hi + count), 0, at);
      body.push_back(b.assign(b.ref(to, at),
                              b.binary(net::BinaryOp::Add, pos, by, at), at));
      NExpr *clamped =
          b.cond(b.binary(net::BinaryOp::Lt, b.ref(to, at), lit(lo), at),
                 lit(fam.farBelow()),
                 b.cond(b.binary(net::BinaryOp::Gt, b.ref(to, at), lit(hi), at),
                        lit(fam.farAbove()),
                        b.binary(net::BinaryOp::Add, b.ref(to, at),
                                 lit(fam.offset), at),
                        at),
                 at);
      body.push_back(b.assign(b.ref(moved, at), clamped, at));
    } else {
      // The element moved to stays in the block of its family it started
      // in (a family's blocks are not contiguous, and a single place
      // moves nowhere): leaving it is the range check's run-time error.
      int64_t block = contiguousBlock(fam);
      std::string inBlock = scanVariable(
          stem + "_element", design.types.getRange(0, block - 1), 0, at);
      if (block > 1 && block < fam.size)
        pos = b.binary(net::BinaryOp::Mod, pos, lit(block), at);
      body.push_back(b.assign(b.ref(inBlock, at),
                              b.binary(net::BinaryOp::Add, pos, by, at), at));
      body.push_back(b.assign(b.ref(moved, at),
                              b.binary(net::BinaryOp::Add, num, by, at), at));
    }
    arms.push_back({inFamily, design.copy(llvm::ArrayRef<NStmt *>(body))});
  }
  pre.push_back(b.ifStmt(arms, false, {}, at));
  return b.ref(moved, at);
}

NExpr *Lowering::farFromBlock(const RefTable &table, NExpr *k, SMLoc at) {
  NExpr *any = nullptr;
  for (const RefFamily &fam : table.families)
    if (fam.hasOutside)
      for (int64_t far : {fam.farBelow(), fam.farAbove()}) {
        NExpr *is = b.binary(net::BinaryOp::Eq, k, b.intLit(far, at), at);
        any = any ? b.binary(net::BinaryOp::Or, any, is, at) : is;
      }
  return any;
}

NExpr *Lowering::pointerPairValue(Expr *e, Frame &f, Sink &pre) {
  SMLoc at = e->loc;
  const PType *elem = e->operands[0]->type->elem;
  std::string why;
  int64_t size = memoryLayout(elem, why)->size;
  auto table = refPlan.tables.find(referenceKey(elem));
  int64_t count = table == refPlan.tables.end() ? 0 : table->second.count;
  std::string stem = stemOf(e->operands[0]);
  // Each number once, in a variable of the scan.
  auto numberOf = [&](Expr *x) -> NExpr * {
    NExpr *k = expr(x, f, pre);
    if (llvm::isa<net::IntLit>(k) || llvm::isa<net::Ref>(k))
      return k;
    std::string name = scanVariable(
        stem + "_pointer",
        design.types.getRange(0, std::max<int64_t>(count, 1)), 0, at);
    pre.push_back(b.assign(b.ref(name, at), k, at));
    return b.ref(name, at);
  };
  NExpr *l = numberOf(e->operands[0]);
  NExpr *r = numberOf(e->operands[1]);
  // The first number of the contiguous block a number lies in (0 for
  // NULL, which lies in none): equal for two pointers into one block.
  auto blockStart = [&](NExpr *k) -> NExpr * {
    NExpr *start = b.intLit(0, at);
    if (count == 0)
      return start;
    const auto &families = table->second.families;
    auto *lit = llvm::dyn_cast<net::IntLit>(k);
    for (auto fam = families.rbegin(); fam != families.rend(); ++fam) {
      int64_t block = fam->hasOutside ? fam->last() - fam->first() + 1
                                      : contiguousBlock(*fam);
      int64_t last = fam->last();
      if (lit && fam->holds(lit->value, /*withOutside=*/true))
        return b.intLit(
            fam->first() + (lit->value - fam->first()) / block * block, at);
      if (lit)
        continue;
      NExpr *in = b.binary(
          net::BinaryOp::And,
          b.binary(net::BinaryOp::Ge, k, b.intLit(fam->first(), at), at),
          b.binary(net::BinaryOp::Le, k, b.intLit(last, at), at), at);
      NExpr *first = b.intLit(fam->first(), at);
      if (block < last - fam->first() + 1) {
        // (k - offset) / block * block + offset
        NExpr *pos = b.binary(net::BinaryOp::Sub, k, first, at);
        first = b.binary(
            net::BinaryOp::Add,
            b.binary(net::BinaryOp::Mul,
                     b.binary(net::BinaryOp::Div, pos, b.intLit(block, at), at),
                     b.intLit(block, at), at),
            b.intLit(fam->offset, at), at);
      }
      start = b.cond(in, first, start, at);
    }
    return start;
  };
  NExpr *ls = blockStart(l), *rs = blockStart(r);
  auto *lLit = llvm::dyn_cast<net::IntLit>(ls);
  auto *rLit = llvm::dyn_cast<net::IntLit>(rs);
  if (lLit && rLit && (lLit->value != rLit->value || lLit->value == 0))
    refuse(at, "the pointers are not into one array, string or variable: "
               "their order is not defined");
  if (!(lLit && rLit))
    failWhenAny(
        {b.binary(net::BinaryOp::Or, b.binary(net::BinaryOp::Ne, ls, rs, at),
                  b.binary(net::BinaryOp::Eq, ls, b.intLit(0, at), at), at)},
        stem + "_apart", pre, at);
  // Far outside a block only the side is known: no distance to it, and
  // two such pointers on one side have no order.
  if (NExpr *lFar = count ? farFromBlock(table->second, l, at) : nullptr) {
    NExpr *rFar = farFromBlock(table->second, r, at);
    NExpr *unknown = e->op == Op::Sub
                         ? b.binary(net::BinaryOp::Or, lFar, rFar, at)
                         : b.binary(net::BinaryOp::And, lFar,
                                    b.binary(net::BinaryOp::Eq, l, r, at), at);
    failWhenAny({unknown}, stem + "_far", pre, at);
  }
  if (e->op == Op::Sub) {
    NExpr *d = b.binary(net::BinaryOp::Sub, l, r, at);
    return size == 1 ? d
                     : b.binary(net::BinaryOp::Mul, d, b.intLit(size, at), at);
  }
  net::BinaryOp op = e->op == Op::Lt   ? net::BinaryOp::Lt
                     : e->op == Op::Le ? net::BinaryOp::Le
                     : e->op == Op::Gt ? net::BinaryOp::Gt
                                       : net::BinaryOp::Ge;
  return b.binary(op, l, r, at);
}

//===----------------------------------------------------------------------===//
// Calls through references
//===----------------------------------------------------------------------===//

void Lowering::callThroughReference(Expr *call, Frame &f, Sink &out) {
  Expr *instance = call->operands[0];
  Pou *fb = instance->type->fb;
  DerefTargets t = derefTargets(instance, f, out);
  if (t.live.empty())
    return; // the reference is NULL whenever this runs: reported above
  auto pathOf = [&](const RefFamily &fam) {
    auto *ref = llvm::dyn_cast<net::Ref>(familyPlace(fam, t, instance, f, out));
    if (!ref)
      refuse(call->loc, "internal: a function block instance in an element");
    return ref->name.str();
  };
  std::vector<InstanceChoice> choices;
  for (const RefFamily *fam : t.live)
    choices.push_back({familyTest(*fam, t), pathOf(*fam)});
  callChosenInstance(call, fb, choices, f, out);
}

//===----------------------------------------------------------------------===//
// MEMCPY, MEMMOVE, MEMSET, MEMCMP
//===----------------------------------------------------------------------===//

NExpr *Lowering::filledScalar(const PType *t, NExpr *byte, SMLoc at) {
  t = baseOf(t);
  if (t->kind == PTypeKind::Bool)
    return b.binary(net::BinaryOp::Ne, byte, b.intLit(0, at), at);
  // Sema let through only BOOL, integers and REAL of at most 32 bits.
  int64_t bits = t->kind == PTypeKind::Real ? 32 : t->width;
  int64_t repeat = 0;
  for (int64_t k = 0; k < bits / 8; ++k)
    repeat = (repeat << 8) | 1;
  NExpr *raw = repeat == 1 ? byte
                           : b.binary(net::BinaryOp::Mul, byte,
                                      b.intLit(repeat, at), at);
  return fromBits(t, raw, bits, at);
}

void Lowering::fillThroughReference(Expr *place, NExpr *byte, Frame &f,
                                    Sink &pre, SMLoc at) {
  const PType *t = baseOf(place->type);
  switch (t->kind) {
  case PTypeKind::Array:
    forEachIndex(t, [&](llvm::ArrayRef<int64_t> index) {
      Expr *element = unit.make<Expr>(ExprKind::Index, at);
      element->operands.push_back(place);
      for (int64_t i : index) {
        Expr *lit = unit.make<Expr>(ExprKind::IntLit, at);
        lit->intValue = i;
        lit->type = elementaryType("DINT");
        element->operands.push_back(lit);
      }
      element->type = t->elem;
      fillThroughReference(element, byte, f, pre, at);
    });
    return;
  case PTypeKind::Struct:
    if (t->isUnion)
      break;
    for (VarDecl *fld : t->fields) {
      Expr *field = unit.make<Expr>(ExprKind::Field, at);
      field->operands.push_back(place);
      field->name = fld->name;
      field->var = fld;
      field->type = fld->type;
      fillThroughReference(field, byte, f, pre, at);
    }
    return;
  case PTypeKind::FunctionBlock:
    refuse(at, "MEMSET over a function block instance (" + t->str() +
                   ") is not modelled");
  default:
    break;
  }
  if (byte) {
    writeThroughReference(place, filledScalar(t, byte, at), nullptr, f, pre,
                          at);
    return;
  }
  // All bits zero: 0, 0.0, FALSE, '', NULL, 1970-01-01; an enumeration
  // its first value.
  NExpr *zero =
      t->kind == PTypeKind::Int ? b.intLit(0, at) : defaultValue(t, at);
  writeThroughReference(place, zero, nullptr, f, pre, at);
}

NExpr *Lowering::imageCopy(Expr *call, Frame &f, Sink &pre) {
  SMLoc at = call->loc;
  Expr *dstAdr = call->args[0].value, *srcAdr = call->args[1].value;
  // From or into an array element, more bytes than the element's (or a
  // count known at run time): the bytes up to the array's end.
  if (call->intValue < 0)
    return imageCopySpans(call, f, pre);
  for (Expr *adr : {dstAdr, srcAdr}) {
    std::string why;
    if (arrayElementPlace(adr->args[0].value) &&
        call->intValue > memoryLayout(adr->type->elem, why)->size)
      return imageCopySpans(call, f, pre);
  }
  std::vector<MemoryLeaf> dl, sl;
  std::string why;
  memoryLeaves(dstAdr->type->elem, dl, why);
  memoryLeaves(srcAdr->type->elem, sl, why);
  int64_t n = call->intValue;
  auto placeOf = [&](Expr *adr) {
    return directPlace(adr->args[0].value, call->name, f, pre);
  };
  auto leafOf = [&](Expr *adr, const MemoryLeaf &l) {
    return leafPlace(placeOf(adr), l, at);
  };
  // Byte k of the source: of the leaf that holds it, little-endian (a
  // STRING's characters, 0 past its end); padding reads 0.
  auto sourceByte = [&](int64_t k) -> NExpr * {
    for (const MemoryLeaf &l : sl) {
      if (k < l.offset || k >= l.offset + l.size)
        continue;
      if (l.type->kind == PTypeKind::String)
        return b.call(net::Builtin::Code,
                      {leafOf(srcAdr, l), b.intLit(k - l.offset + 1, at)}, at);
      NExpr *bits = unionBits(l.type, leafOf(srcAdr, l), at);
      if (k > l.offset)
        bits = b.binary(net::BinaryOp::Shr, bits,
                        b.intLit(8 * (k - l.offset), at), at);
      return b.binary(net::BinaryOp::BitAnd, bits, b.intLit(255, at), at);
    }
    return b.intLit(0, at);
  };
  // Every target leaf the bytes reach, computed before any is written (the
  // source may share bytes with the target, as MEMMOVE allows).
  std::vector<std::pair<const MemoryLeaf *, NExpr *>> written;
  for (const MemoryLeaf &l : dl) {
    if (l.offset >= n)
      break;
    NExpr *raw = nullptr;
    if (l.offset + l.size <= n) {
      for (int64_t j = 0; j < l.size; ++j) {
        NExpr *byte = sourceByte(l.offset + j);
        if (j)
          byte = b.binary(net::BinaryOp::Shl, byte, b.intLit(8 * j, at), at);
        raw = raw ? b.binary(net::BinaryOp::BitOr, raw, byte, at) : byte;
      }
    } else {
      // The leading bytes only; the others kept.
      raw = unionBits(l.type, leafOf(dstAdr, l), at);
      for (int64_t j = 0; l.offset + j < n; ++j)
        raw = insertBits(raw, sourceByte(l.offset + j), 8, b.intLit(8 * j, at),
                         at);
    }
    written.push_back({&l, raw});
  }
  storeLeavesTogether(
      written, [&](const MemoryLeaf &l) { return leafOf(dstAdr, l); }, pre, at);
  return b.intLit(0, at);
}

NExpr *Lowering::memoryCall(Expr *call, Frame &f, Sink &pre) {
  SMLoc at = call->loc;
  if (call->typeName == "IMAGE")
    return imageCopy(call, f, pre);
  Expr *dst = call->args[0].value, *src = call->args[1].value;
  const PType *t = dst->type->elem;
  std::string why;
  int64_t size = memoryLayout(t, why)->size;
  // Element j of what `p` points to: (p + j * size)^.
  auto element = [&](Expr *p, int64_t j) {
    Expr *offset = nullptr;
    if (j) {
      offset = unit.make<Expr>(ExprKind::IntLit, at);
      offset->intValue = j * size;
      offset->type = elementaryType("DINT");
    }
    return elementAt(p, offset, t, at);
  };
  int64_t k = call->intValue;
  if (k < 0)
    return memoryLoop(call, f, pre);
  if (call->name == "MEMCMP") {
    // The first byte that differs decides, as unsigned bytes, in memory
    // order (each element's bytes little-endian).
    std::vector<std::pair<NExpr *, NExpr *>> pairs;
    for (int64_t j = 0; j < k; ++j) {
      FreshPlace x = comparedValue(element(dst, j), f, pre);
      FreshPlace y = comparedValue(element(src, j), f, pre);
      for (int64_t byte = 0; byte < size; ++byte)
        pairs.push_back({valueByte(t, x, byte, at), valueByte(t, y, byte, at)});
    }
    NExpr *r = b.intLit(0, at);
    for (size_t j = pairs.size(); j-- > 0;) {
      auto [x, y] = pairs[j];
      NExpr *sign = b.cond(b.binary(net::BinaryOp::Lt, x, y, at),
                           b.intLit(-1, at), b.intLit(1, at), at);
      r = b.cond(b.binary(net::BinaryOp::Ne, x, y, at), sign, r, at);
    }
    return r;
  }
  if (call->name == "MEMSET") {
    NExpr *fill = fillByte(src, f, pre);
    for (int64_t j = 0; j < k; ++j)
      fillElement(element(dst, j), fill, f, pre);
    return b.intLit(0, at);
  }
  // MEMCPY, MEMMOVE: every element read before any is written, so that
  // overlapping places copy as MEMMOVE does.
  std::vector<NExpr *> values;
  for (int64_t j = 0; j < k; ++j) {
    NExpr *v = readThroughReference(element(src, j), f, pre);
    if (k > 1) {
      std::string tmp = unique("_copy");
      declareTemp(tmp, t, at);
      pre.push_back(b.assign(b.ref(tmp, at), v, at));
      v = b.ref(tmp, at);
    }
    values.push_back(v);
  }
  for (int64_t j = 0; j < k; ++j)
    writeThroughReference(element(dst, j), values[j], nullptr, f, pre, at);
  return b.intLit(0, at);
}

Expr *Lowering::elementAt(Expr *p, Expr *offset, const PType *t, SMLoc at) {
  Expr *moved = p;
  if (offset) {
    moved = unit.make<Expr>(ExprKind::Binary, at);
    moved->op = Op::Add;
    moved->operands = {p, offset};
    moved->type = p->type;
  }
  Expr *d = unit.make<Expr>(ExprKind::Deref, at);
  d->operands.push_back(moved);
  d->type = t;
  return d;
}

NExpr *Lowering::memoryLoop(Expr *call, Frame &f, Sink &pre) {
  SMLoc at = call->loc;
  Expr *dst = call->args[0].value, *src = call->args[1].value;
  const PType *t = dst->type->elem;
  std::string why;
  int64_t size = memoryLayout(t, why)->size;
  // At most the longest block a pointer of the type may stand in: more
  // elements would leave any (the range of the count reports it).
  int64_t most = 0;
  if (auto table = refPlan.tables.find(referenceKey(t));
      table != refPlan.tables.end())
    for (const RefFamily &fam : table->second.families)
      most = std::max(most, contiguousBlock(fam));
  most = std::min<int64_t>(most, 4096);
  std::string count = scanVariable(sanitize(call->name) + "_elements",
                                   design.types.getRange(0, most), 0, at);
  pre.push_back(b.assign(b.ref(count, at),
                         elementsIn(call->args[2].value, size, f, pre), at));
  if (most == 0)
    return b.intLit(0, at);
  // Element `index` of what p points to, `index` a NetIR value: a
  // variable standing for it (as a VAR_IN_OUT stands for its argument).
  auto *indexVar = unit.make<VarDecl>();
  indexVar->name = "_memory_index";
  indexVar->section = VarSection::InOut;
  indexVar->type = elementaryType("DINT");
  auto at_ = [&](Expr *p) {
    Expr *index = unit.make<Expr>(ExprKind::Name, at);
    index->name = indexVar->name;
    index->var = indexVar;
    index->type = indexVar->type;
    Expr *bytes = index;
    if (size != 1) {
      Expr *sz = unit.make<Expr>(ExprKind::IntLit, at);
      sz->intValue = size;
      sz->type = elementaryType("DINT");
      bytes = unit.make<Expr>(ExprKind::Binary, at);
      bytes->op = Op::Mul;
      bytes->operands = {index, sz};
      bytes->type = index->type;
    }
    return elementAt(p, bytes, t, at);
  };
  // for k in 0..most-1 { if index(k) in 0..count-1 { each } }
  auto loop = [&](auto indexOf, auto each, Sink &out) {
    std::string k = "_k" + std::to_string(++loopVars);
    NExpr *index = indexOf(b.ref(k, at));
    f.aliases[indexVar] = index;
    Sink body;
    each(body);
    f.aliases.erase(indexVar);
    NExpr *inside =
        b.binary(net::BinaryOp::And,
                 b.binary(net::BinaryOp::Ge, index, b.intLit(0, at), at),
                 b.binary(net::BinaryOp::Lt, index, b.ref(count, at), at), at);
    Sink guarded{b.ifStmt(
        {{inside, design.copy(llvm::ArrayRef<NStmt *>(body))}}, false, {}, at)};
    out.push_back(
        b.forStmt(k, b.intLit(0, at), b.intLit(most - 1, at), guarded, at));
  };
  auto forward = [](NExpr *k) { return k; };
  if (call->name == "MEMCMP") {
    // The first element that differs decides, as unsigned bytes.
    std::string result =
        scanVariable("MEMCMP_result", design.types.getRange(-1, 1), 0, at);
    pre.push_back(b.assign(b.ref(result, at), b.intLit(0, at), at));
    loop(
        forward,
        [&](Sink &body) {
          FreshPlace x = comparedValue(at_(dst), f, body);
          FreshPlace y = comparedValue(at_(src), f, body);
          for (int64_t byte = 0; byte < size; ++byte) {
            NExpr *xb = valueByte(t, x, byte, at);
            NExpr *yb = valueByte(t, y, byte, at);
            NExpr *sign = b.cond(b.binary(net::BinaryOp::Lt, xb, yb, at),
                                 b.intLit(-1, at),
                                 b.cond(b.binary(net::BinaryOp::Gt, xb, yb, at),
                                        b.intLit(1, at), b.intLit(0, at), at),
                                 at);
            Sink set{b.assign(b.ref(result, at), sign, at)};
            body.push_back(
                b.ifStmt({{b.binary(net::BinaryOp::Eq, b.ref(result, at),
                                    b.intLit(0, at), at),
                           design.copy(llvm::ArrayRef<NStmt *>(set))}},
                         false, {}, at));
          }
        },
        pre);
    return b.ref(result, at);
  }
  if (call->name == "MEMSET") {
    NExpr *fill = fillByte(src, f, pre);
    loop(
        forward, [&](Sink &body) { fillElement(at_(dst), fill, f, body); },
        pre);
    return b.intLit(0, at);
  }
  // MEMCPY, MEMMOVE: forwards when the target stands before the source
  // (or in another block), backwards otherwise, so that overlapping
  // elements copy as MEMMOVE does.
  auto copy = [&](Sink &body) {
    writeThroughReference(at_(dst), readThroughReference(at_(src), f, body),
                          nullptr, f, body, at);
  };
  Sink forwards, backwards;
  loop(forward, copy, forwards);
  loop(
      [&](NExpr *k) {
        return b.binary(
            net::BinaryOp::Sub,
            b.binary(net::BinaryOp::Sub, b.ref(count, at), b.intLit(1, at), at),
            k, at);
      },
      copy, backwards);
  NExpr *before =
      b.binary(net::BinaryOp::Le, expr(dst, f, pre), expr(src, f, pre), at);
  pre.push_back(
      b.ifStmt({{before, design.copy(llvm::ArrayRef<NStmt *>(forwards))}}, true,
               design.copy(llvm::ArrayRef<NStmt *>(backwards)), at));
  return b.intLit(0, at);
}

FreshPlace Lowering::comparedValue(Expr *element, Frame &f, Sink &pre) {
  SMLoc at = element->loc;
  NExpr *v = readThroughReference(element, f, pre);
  if (auto *lit = llvm::dyn_cast<net::IntLit>(v)) {
    int64_t k = lit->value;
    return [this, k, at] { return b.intLit(k, at); };
  }
  // A one-byte scalar is read once, where it is compared.
  std::string why;
  const PType *t = baseOf(element->type);
  if (t->kind != PTypeKind::Array && t->kind != PTypeKind::Struct &&
      memoryLayout(t, why)->size == 1)
    return [v] { return v; };
  // An array or structure is read into a temporary (a Ref); a wider
  // scalar's selection over places is read once into one.
  std::string name;
  if (auto *r = llvm::dyn_cast<net::Ref>(v)) {
    name = r->name.str();
  } else {
    name = unique("_compared");
    declareTemp(name, element->type, at);
    pre.push_back(b.assign(b.ref(name, at), v, at));
  }
  return [this, name, at] { return b.ref(name, at); };
}

NExpr *Lowering::valueByte(const PType *t, const FreshPlace &value,
                           int64_t byte, SMLoc at) {
  int64_t k = byte;
  return recordByte(
      t, value, [this, k, at] { return b.intLit(k, at); }, at);
}

NExpr *Lowering::fillByte(Expr *fill, Frame &f, Sink &pre) {
  NExpr *v = expr(fill, f, pre);
  if (auto *lit = llvm::dyn_cast<net::IntLit>(v))
    return b.intLit(lit->value & 0xff, fill->loc);
  return maskTo(v, elementaryType("BYTE"), fill->loc);
}

void Lowering::fillElement(Expr *element, NExpr *fill, Frame &f, Sink &out) {
  // The fill's low byte in every byte: every scalar of the element built
  // from it (Sema let through only 0, or scalars that take any byte
  // pattern).
  SMLoc at = element->loc;
  const PType *t = element->type;
  auto *lit = llvm::dyn_cast<net::IntLit>(fill);
  NExpr *byte = lit && lit->value == 0 ? nullptr : fill;
  bool whole = (t->kind == PTypeKind::Array || t->kind == PTypeKind::Struct ||
                t->isString()) &&
               !(t->kind == PTypeKind::Struct && t->isUnion);
  std::string why;
  if (whole || !byte)
    fillThroughReference(element, byte, f, out, at);
  else if (memoryLayout(t, why)->size == 1 && t->kind != PTypeKind::Bool)
    writeThroughReference(element, fill, nullptr, f, out, at);
  else
    writeThroughReference(element, filledScalar(t, byte, at), nullptr, f, out,
                          at);
}
