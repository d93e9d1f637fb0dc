//===- SemaReferences.cpp - checking references and pointers -------------===//
//
// REF_TO, POINTER TO and REFERENCE TO (IEC 61131-3 3rd edition 6.4.4.10,
// CODESYS and TwinCAT): their types, REF/ADR, `^`, NULL, `REF=` and `?=`,
// and the implicit dereference of a REFERENCE TO. The three spellings are
// one type here; a reference to T takes the value of another only when
// both designate the same type (referenceKey).
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/SemaChecker.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

const PType *Checker::resolveReference(TypeSyntax *ts, StringRef ownerName) {
  PType *t = make(PTypeKind::Reference);
  t->refKind = ts->refKind;
  // A structure may hold a reference to its own type (a linked list): the
  // target is filled in once the type being resolved is (resolveNamed).
  if (ts->elem->kind == TypeSyntaxKind::Named &&
      !elementaryType(ts->elem->name)) {
    std::string key = StringRef(ts->elem->name).upper();
    if (resolving.count(key) && resolving[key] > 0) {
      pendingTargets.push_back({t, key});
      return t;
    }
  }
  t->elem = resolve(ts->elem, ownerName);
  return t->elem ? t : nullptr;
}

void Checker::completeReferences(StringRef key, const PType *resolved) {
  for (auto &[ref, waiting] : pendingTargets)
    if (waiting == key)
      ref->elem = resolved;
}

/// `e` is an lvalue a reference can designate: a variable, or a field,
/// element or dereference of one.
static bool designatesStorage(Expr *e) {
  for (; e; e = e->base()) {
    switch (e->kind) {
    case ExprKind::Name:
      return e->var != nullptr || e->selfInstance;
    case ExprKind::Field:
    case ExprKind::Index:
      continue;
    case ExprKind::Deref:
      return true;
    default:
      return false;
    }
  }
  return false;
}

std::optional<const PType *> Checker::referenceCall(Expr *e, bool asStatement) {
  for (const char *mem : {"MEMCPY", "MEMSET", "MEMCMP", "MEMMOVE"})
    if (sameName(e->name, mem)) {
      e->name = mem;
      return memoryCall(e, asStatement);
    }
  if (sameName(e->name, "__QUERYINTERFACE")) {
    e->name = "__QUERYINTERFACE";
    return queryInterface(e);
  }
  if (e->name == "__UPCAST" && e->type)
    return e->type; // checked where it was made (referenceAsBase)
  bool isRef = sameName(e->name, "REF"), isAdr = sameName(e->name, "ADR");
  bool isValid = sameName(e->name, "__ISVALIDREF");
  if (sameName(e->name, "__NEW") || sameName(e->name, "__DELETE")) {
    error(e->loc, "dynamic memory (" + e->name + ") is not supported");
    return nullptr;
  }
  if (!isRef && !isAdr && !isValid)
    return std::nullopt;
  if (e->args.size() != 1 || e->args[0].isOutput || !e->args[0].name.empty()) {
    error(e->loc, e->name + " takes one variable");
    return nullptr;
  }
  Expr *arg = e->args[0].value;
  e->name = isRef ? "REF" : isAdr ? "ADR" : "__ISVALIDREF";
  if (isValid) {
    // The reference itself, not what it designates.
    const PType *t = referenceItself(arg, /*asTarget=*/false);
    if (t && !t->isReference()) {
      error(arg->loc, "__ISVALIDREF takes a reference, not " + t->str());
      return nullptr;
    }
    return t ? boolType() : nullptr;
  }
  const PType *t = expr(arg);
  if (!t)
    return nullptr;
  // ADR(s[i]), a character of a STRING (CODESYS, TwinCAT): ADR(s) + i, a
  // step through the string's bytes.
  if (arg->kind == ExprKind::Index && arg->operands.size() == 2 &&
      arg->base()->type && baseOf(arg->base()->type)->isString()) {
    if (!isAdr || baseOf(arg->base()->type)->width == 16) {
      error(arg->loc, e->name + " of a character of a " +
                          baseOf(arg->base()->type)->str() +
                          ": netlift takes ADR(s[i]) of a STRING (ADR(s) + "
                          "i, a POINTER TO BYTE)");
      return nullptr;
    }
    Expr *whole = unit.make<Expr>(*e);
    whole->args[0].value = arg->base();
    whole->type = nullptr;
    Expr *offset = arg->operands[1];
    e->kind = ExprKind::Binary;
    e->op = Op::Add;
    e->name.clear();
    e->args.clear();
    e->operands = {whole, offset};
    return expr(e);
  }
  if (!designatesStorage(arg)) {
    error(arg->loc, e->name + " needs a variable, a field, an element or a "
                              "dereference");
    return nullptr;
  }
  for (Expr *x = arg; x; x = x->base())
    if (x->kind == ExprKind::Name && x->var) {
      if (x->var->constant) {
        error(arg->loc, e->name + " of constant '" + x->var->name + "'");
        return nullptr;
      }
      // Written through the reference, perhaps: the scan keeps a copy of
      // the input image (as for any written input).
      if (x->var->area() == 'I' ||
          (x->var->section == VarSection::Input && x->var->owner &&
           x->var->owner->kind != PouKind::Function))
        x->var->writtenInput = true;
    } else if (x->kind == ExprKind::Deref) {
      break;
    }
  PType *r = make(PTypeKind::Reference);
  r->refKind = isAdr ? RefKind::Pointer : RefKind::RefTo;
  r->elem = t;
  return r;
}

Expr *Checker::addressCall(Expr *place) {
  Expr *call = unit.make<Expr>(ExprKind::Call, place->loc);
  call->name = "REF";
  CallArg a;
  a.value = place;
  a.loc = place->loc;
  call->args.push_back(a);
  return call;
}

const PType *Checker::derefType(Expr *e) {
  // `r^` on a REFERENCE TO is explicit: r itself is dereferenced.
  const PType *bt = referenceItself(e->base(), /*asTarget=*/false);
  if (!bt)
    return nullptr;
  if (!bt->isReference()) {
    error(e->loc, "'^' applied to a value of type " + bt->str());
    return nullptr;
  }
  if (!bt->elem) {
    error(e->loc, "dereference of NULL");
    return nullptr;
  }
  return bt->elem;
}

const PType *Checker::referenceItself(Expr *e, bool asTarget) {
  Expr *outer = keepReference;
  keepReference = e;
  const PType *t = asTarget ? lvalue(e) : expr(e);
  keepReference = outer;
  return t;
}

const PType *Checker::implicitDeref(Expr *e, const PType *t) {
  if (!t || !t->isReference() || t->refKind != RefKind::Reference ||
      e == keepReference || !t->elem || implicitlyDereferenced.count(e))
    return t;
  // `r` for a REFERENCE TO is what it designates: `r^`.
  Expr *inner = unit.make<Expr>(*e);
  inner->type = t;
  implicitlyDereferenced.insert(inner);
  e->kind = ExprKind::Deref;
  e->operands = {inner};
  e->name.clear();
  e->var = nullptr;
  e->args.clear();
  return t->elem;
}

bool Checker::decayToElement(Expr *e, const PType *elem) {
  if (e->kind != ExprKind::Call || e->name != "ADR" || !e->type ||
      !e->type->elem || e->type->elem->kind != PTypeKind::Array ||
      referenceKey(e->type->elem->elem) != referenceKey(elem))
    return false;
  const PType *array = e->type->elem;
  Expr *place = e->args[0].value;
  Expr *first = unit.make<Expr>(ExprKind::Index, place->loc);
  first->operands.push_back(place);
  for (auto &[lo, hi] : array->dims) {
    Expr *i = unit.make<Expr>(ExprKind::IntLit, place->loc);
    i->intValue = lo;
    i->type = anyIntType();
    first->operands.push_back(i);
  }
  first->type = array->elem;
  e->args[0].value = first;
  PType *r = make(PTypeKind::Reference);
  r->refKind = RefKind::Pointer;
  r->elem = array->elem;
  e->type = r;
  return true;
}

/// ADR(x) not yet seen as anything else.
static bool plainAddress(Expr *e) {
  return e->kind == ExprKind::Call && e->name == "ADR" && e->type &&
         e->type->elem && e->typeName.empty();
}

/// Marks ADR(x) as a view of x (`kind`, read by the lowering in
/// LowerReferences.cpp viewOf) through a POINTER TO `elem`.
bool Checker::markView(Expr *e, const char *kind, const PType *elem) {
  e->typeName = kind;
  PType *r = make(PTypeKind::Reference);
  r->refKind = RefKind::Pointer;
  r->elem = elem;
  e->type = r;
  return true;
}

bool Checker::viewAsBytes(Expr *e, const PType *elem) {
  if (!plainAddress(e))
    return false;
  const PType *text = baseOf(e->type->elem);
  // A STRING's characters are BYTEs; a WSTRING's are WORDs (UTF-16 code
  // units), as CODESYS and TwinCAT hold them.
  auto oneChar = [&](const PType *t) {
    t = baseOf(t);
    return t->kind == PTypeKind::Int && t->width == text->width;
  };
  if (!text->isString() ||
      !(oneChar(elem) || (elem->kind == PTypeKind::Array &&
                          elem->dims.size() == 1 && oneChar(elem->elem))))
    return false;
  return markView(e, "BYTES", elem);
}

bool Checker::viewAsElements(Expr *e, const PType *array) {
  if (!plainAddress(e))
    return false;
  const PType *place = e->type->elem;
  if (place->kind != PTypeKind::Array || array->kind != PTypeKind::Array ||
      place->dims.size() != 1 || array->dims.size() != 1 ||
      referenceKey(place->elem) != referenceKey(array->elem))
    return false;
  return markView(e, "ELEMENTS", array);
}

bool Checker::viewAsScalar(Expr *e, const PType *elem) {
  if (!plainAddress(e))
    return false;
  const PType *seen = baseOf(e->type->elem), *as = baseOf(elem);
  auto numeric = [](const PType *t) {
    return (t->kind == PTypeKind::Int && !t->isSubrange) ||
           t->kind == PTypeKind::Real;
  };
  auto oneByteArray = [](const PType *t) {
    return t->kind == PTypeKind::Array && t->dims.size() == 1 &&
           baseOf(t->elem)->kind == PTypeKind::Int &&
           baseOf(t->elem)->width == 8;
  };
  // A POINTER TO BYTE over a wider scalar steps through its bytes.
  bool oneByte = as->kind == PTypeKind::Int && as->width == 8;
  // A structure or an array of BOOLs, integers and REALs seen as its bytes
  // (a checksum over a record, a telegram built in place).
  if (seen->kind == PTypeKind::Struct || seen->kind == PTypeKind::Array) {
    std::vector<MemoryLeaf> leaves;
    std::string why;
    if (!(oneByte || oneByteArray(as)))
      return false;
    // Why its bytes are not seen, for the mismatch reported then.
    if (!memoryLeaves(seen, leaves, why)) {
      bytesUnseen = " (as bytes: " + why + ")";
      return false;
    }
    if (llvm::any_of(leaves, [](const MemoryLeaf &l) {
          return l.type->kind == PTypeKind::String;
        })) {
      bytesUnseen = " (as bytes: a STRING among them is not seen through a "
                    "pointer; MEMCPY copies it)";
      return false;
    }
    return markView(e, "SCALAR", elem);
  }
  if (!numeric(seen) ||
      !(oneByteArray(as) || (numeric(as) && seen->width == as->width) ||
        (oneByte && seen->width > 8)))
    return false;
  return markView(e, "SCALAR", elem);
}

const PType *Checker::pointerArithmetic(Expr *e, const PType *a,
                                        const PType *b) {
  Expr *ptr = e->operands[0], *offset = e->operands[1];
  if (!a->isReference())
    std::swap(ptr, offset);
  const PType *pt = ptr->type, *ot = baseOf(offset->type);
  if (e->op == Op::Sub && ptr != e->operands[0])
    pt = nullptr; // n - p
  auto refuse = [&](const Twine &why) -> const PType * {
    error(e->loc, "pointer arithmetic ('" + spelling(e->op) + "' on " +
                      a->str() + " and " + b->str() + "): " + why);
    return nullptr;
  };
  if (e->op == Op::Sub && a->isReference() && b->isReference()) {
    // The distance in bytes, as CODESYS's addresses differ.
    if (!pointerPair(e, "subtract"))
      return nullptr;
    return elementaryType("DINT");
  }
  if (!pt || (e->op != Op::Add && e->op != Op::Sub) || !ot->isInteger())
    return refuse("only a POINTER TO plus or minus an integer is supported");
  if (pt->refKind != RefKind::Pointer || !pt->elem)
    return refuse("only a POINTER TO moves");
  // Stepping from an array's address steps through its elements, from a
  // STRING's through its bytes.
  if (pt->elem->kind == PTypeKind::Array && decayToElement(ptr, pt->elem->elem))
    pt = ptr->type;
  else if (viewAsBytes(ptr, elementaryType("BYTE")) ||
           viewAsScalar(ptr, elementaryType("BYTE")))
    pt = ptr->type;
  std::string why;
  auto layout = memoryLayout(pt->elem, why);
  if (!layout)
    return refuse(why);
  if (!wholeElements(offset, layout->size))
    return refuse("the offset is not written as a whole number of " +
                  pt->elem->str() + " (n * SIZEOF(" + pt->elem->str() +
                  ") = n * " + Twine(layout->size) + ")");
  return pt;
}

bool Checker::wholeElements(Expr *bytes, int64_t size) {
  // A constant multiple of the size, or a product with one.
  auto multiple = [&](Expr *x) {
    int64_t v;
    return constInt(x, v) && v % size == 0;
  };
  return size == 1 || multiple(bytes) ||
         (bytes->kind == ExprKind::Binary && bytes->op == Op::Mul &&
          (multiple(bytes->operands[0]) || multiple(bytes->operands[1])));
}

bool Checker::pointerPair(Expr *e, StringRef what) {
  Expr *l = e->operands[0], *r = e->operands[1];
  auto refuse = [&](const Twine &why) {
    error(e->loc, "cannot " + what + " " + l->type->str() + " and " +
                      r->type->str() + ": " + why);
    return false;
  };
  if (l->type->refKind != RefKind::Pointer ||
      r->type->refKind != RefKind::Pointer)
    return refuse("only POINTER TOs are ordered (into one array)");
  // ADR(arr) next to a pointer to its elements is its first element's
  // address; a STRING's next to a pointer to bytes, its first byte's.
  auto alignTo = [&](Expr *x, Expr *other) {
    const PType *want = other->type->elem;
    if (want && x->type->elem &&
        referenceKey(x->type->elem) != referenceKey(want))
      decayToElement(x, want) || viewAsBytes(x, want) || viewAsScalar(x, want);
  };
  alignTo(l, r);
  alignTo(r, l);
  if (!l->type->elem || !r->type->elem ||
      referenceKey(l->type->elem) != referenceKey(r->type->elem))
    return refuse("they designate different types");
  if (l->type->elem->kind == PTypeKind::Array)
    return refuse("a pointer to a whole array is not stepped through; take "
                  "ADR of its first element");
  std::string why;
  if (!memoryLayout(l->type->elem, why))
    return refuse(why);
  return true;
}

const PType *Checker::pointerIndex(Expr *e, const PType *pointer) {
  if (e->operands.size() != 2) {
    error(e->loc, "a pointer is indexed with one index, not " +
                      Twine(e->operands.size() - 1));
    return nullptr;
  }
  if (!pointer->elem || pointer->elem->kind == PTypeKind::Array) {
    error(e->loc,
          "indexing a " + pointer->str() +
              " steps whole arrays (CODESYS: p[i] is (p + i * SIZEOF(...))^); "
              "write p^[i] for an element");
    return nullptr;
  }
  Expr *index = e->operands[1];
  const PType *it = expr(index);
  if (!it)
    return nullptr;
  if (!baseOf(it)->isInteger()) {
    error(index->loc, "array index must be an integer");
    return nullptr;
  }
  std::string why;
  auto layout = memoryLayout(pointer->elem, why);
  if (!layout) {
    error(e->loc, "indexing a " + pointer->str() + ": " + why);
    return nullptr;
  }
  // (p + i * SIZEOF(T))^, the offset computed in LINT.
  Expr *size = unit.make<Expr>(ExprKind::IntLit, e->loc);
  size->intValue = layout->size;
  size->type = elementaryType("LINT");
  Expr *offset = unit.make<Expr>(ExprKind::Binary, index->loc);
  offset->op = Op::Mul;
  offset->operands = {index, size};
  offset->type = elementaryType("LINT");
  Expr *moved = unit.make<Expr>(ExprKind::Binary, e->loc);
  moved->op = Op::Add;
  moved->operands = {e->operands[0], offset};
  moved->type = pointerArithmetic(moved, pointer, offset->type);
  if (!moved->type)
    return nullptr;
  e->kind = ExprKind::Deref;
  e->operands = {moved};
  return moved->type->elem;
}

bool Checker::referenceAssignable(const PType *to, Expr *from, SMLoc at,
                                  const Twine &what) {
  bytesUnseen.clear();
  if (to->elem &&
      (decayToElement(from, to->elem) || viewAsBytes(from, to->elem)))
    return true;
  if (to->elem && to->refKind == RefKind::Pointer && from->type->elem &&
      referenceKey(from->type->elem) != referenceKey(to->elem) &&
      (viewAsElements(from, to->elem) || viewAsScalar(from, to->elem)))
    return true;
  const PType *ft = from->type;
  if (ft->isReference() &&
      (!ft->elem || referenceKey(ft->elem) == referenceKey(to->elem)))
    return true;
  // CODESYS writes a null pointer as 0.
  if (to->refKind == RefKind::Pointer && ft->kind == PTypeKind::AnyInt &&
      from->kind == ExprKind::IntLit && from->intValue == 0)
    return true;
  if (addressAsNumber(to, ft, at))
    return false;
  error(at, "type mismatch in " + what + ": cannot assign " + ft->str() +
                " to " + to->str() + bytesUnseen);
  bytesUnseen.clear();
  return false;
}

bool Checker::addressAsNumber(const PType *a, const PType *b, SMLoc at) {
  const PType *ptr = a->isReference() ? a : b->isReference() ? b : nullptr;
  const PType *num = ptr == a ? baseOf(b) : baseOf(a);
  if (!ptr || ptr->refKind != RefKind::Pointer || !num->isInteger())
    return false;
  error(at, "a " + ptr->str() + " used as a number (its address, with " +
                num->str() +
                "): netlift models a pointer as the location it designates, "
                "not as an address; pointer arithmetic other than element "
                "steps (ADR(x) + n * SIZEOF(element)) is not modelled");
  return true;
}

bool Checker::comparableReferences(const PType *a, const PType *b, Expr *e) {
  auto nullPointer = [](const PType *t, Expr *x) {
    return t->kind == PTypeKind::AnyInt && x->kind == ExprKind::IntLit &&
           x->intValue == 0;
  };
  if (a->isReference() && b->isReference())
    return !a->elem || !b->elem ||
           referenceKey(a->elem) == referenceKey(b->elem);
  return (a->isReference() && nullPointer(b, e->operands[1])) ||
         (b->isReference() && nullPointer(a, e->operands[0]));
}

void Checker::referenceAssign(Stmt *s) {
  const char *op = s->assignKind == AssignKind::BindReference ? "REF=" : "?=";
  const PType *t = referenceItself(s->target, /*asTarget=*/true);
  if (!t)
    return;
  if (!t->isReference()) {
    error(s->loc, Twine("the target of '") + op +
                      "' must be a reference, not " + t->str());
    return;
  }
  if (s->assignKind == AssignKind::BindReference) {
    // `r REF= x` is `r := REF(x)`; `r REF= NULL` clears it.
    Expr *x = s->value;
    if (x->kind == ExprKind::Name && sameName(x->name, "NULL") &&
        !lookupVar(x->name)) {
      expr(x);
      return;
    }
    Expr *call = addressCall(x);
    s->value = call;
    s->assignKind = AssignKind::Value;
    if (expr(call))
      assignable(t, call, s->loc, "reference binding");
    return;
  }
  const PType *vt = referenceItself(s->value, /*asTarget=*/false);
  if (!vt)
    return;
  if (!vt->isReference()) {
    error(s->value->loc,
          "the value of '?=' must be a reference, not " + vt->str());
    return;
  }
  // Between interfaces the attempt asks the instance designated whether
  // its block implements the target's interface (the lowering's
  // interfaceQuery); an interface it extends always does.
  if (t->refKind == RefKind::Interface && vt->refKind == RefKind::Interface) {
    if (implementsInterface(unit, vt->elem->fb, t->elem->fb))
      s->assignKind = AssignKind::Value;
    return;
  }
  if (t->refKind == RefKind::Interface || vt->refKind == RefKind::Interface) {
    error(s->loc, "'?=' between an interface and a " +
                      (t->refKind == RefKind::Interface ? vt : t)->str() +
                      ": netlift takes it between interfaces or between "
                      "references");
    return;
  }
  // Without EXTENDS and interfaces every type is only itself: the attempt
  // succeeds exactly when both designate the same type, and stores NULL
  // otherwise (the lowering reads assignKind).
  if (!vt->elem || referenceKey(vt->elem) == referenceKey(t->elem))
    s->assignKind = AssignKind::Value;
}

const PType *Checker::queryInterface(Expr *e) {
  if (e->args.size() != 2 || e->args[0].isOutput || e->args[1].isOutput) {
    error(e->loc, "__QUERYINTERFACE takes two interfaces: the one asked "
                  "and the one it sets");
    return nullptr;
  }
  const PType *from = referenceItself(e->args[0].value, /*asTarget=*/false);
  const PType *to = referenceItself(e->args[1].value, /*asTarget=*/true);
  if (!from || !to)
    return nullptr;
  for (const PType *t : {from, to})
    if (!t->isReference() || t->refKind != RefKind::Interface) {
      error(e->loc, "__QUERYINTERFACE takes interfaces, not " + t->str());
      return nullptr;
    }
  if (!designatesStorage(e->args[1].value)) {
    error(e->args[1].value->loc,
          "__QUERYINTERFACE sets its second argument: it must be a variable");
    return nullptr;
  }
  return boolType();
}

bool plc::arrayElementPlace(Expr *place) {
  if (place->kind != ExprKind::Index || place->operands.size() != 2 ||
      !place->base()->type)
    return false;
  const PType *array = baseOf(place->base()->type);
  return array->kind == PTypeKind::Array && array->dims.size() == 1;
}

std::optional<const PType *> Checker::imageCopy(Expr *e, Expr *dst, Expr *src,
                                                Expr *count, bool asStatement) {
  auto adrPlace = [](Expr *p) -> Expr * {
    return p->kind == ExprKind::Call && sameName(p->name, "ADR") &&
                   p->args.size() == 1 && p->type && p->type->elem
               ? p->args[0].value
               : nullptr;
  };
  // What the element-wise copy copies: an array of scalars' elements.
  auto elementKey = [](Expr *p) {
    const PType *t = p->type->elem;
    if (t && t->kind == PTypeKind::Array && t->elem->kind != PTypeKind::Array &&
        t->elem->kind != PTypeKind::Struct)
      t = t->elem;
    return referenceKey(t);
  };
  // Places of one type are copied element by element, unless the count
  // cuts an element (two bytes of a DWORD): then byte by byte, as two
  // types are.
  auto wholeElementsOf = [&](Expr *p) {
    const PType *t = p->type->elem;
    if (t->kind == PTypeKind::Array && t->elem->kind != PTypeKind::Array &&
        t->elem->kind != PTypeKind::Struct)
      t = t->elem;
    std::string why;
    auto layout = memoryLayout(t, why);
    return !layout || wholeElements(count, layout->size);
  };
  Expr *dp = adrPlace(dst), *sp = adrPlace(src);
  if (!dp || !sp ||
      (elementKey(dst) == elementKey(src) && wholeElementsOf(dst)))
    return std::nullopt;
  const PType *dt = dst->type->elem, *st = src->type->elem;
  std::string what = e->name + " from " + st->str() + " to " + dt->str();
  std::vector<MemoryLeaf> dl, sl;
  std::string why;
  if (!memoryLeaves(dt, dl, why) || !memoryLeaves(st, sl, why)) {
    error(e->loc, what + ": " + why);
    return nullptr;
  }
  std::string dummy;
  // ADR(a[i]) of a one-dimensional array: the bytes from element i to the
  // array's end (TwinCAT's `MEMCPY(ADR(buf[nOffset]), ADR(st), SIZEOF(st))`),
  // as many as a constant index leaves, at most the whole array's.
  auto spanBytes = [&](Expr *place, const PType *t) {
    int64_t size = memoryLayout(t, dummy)->size;
    if (!arrayElementPlace(place))
      return size;
    const PType *array = baseOf(place->base()->type);
    auto [lo, hi] = array->dims[0];
    int64_t i;
    return constInt(place->operands[1], i) && i >= lo && i <= hi
               ? (hi - i + 1) * size
               : (hi - lo + 1) * size;
  };
  int64_t dsize = spanBytes(dp, dt), ssize = spanBytes(sp, st), n;
  // A count known only at run time is checked then (Lowering::imageCopy).
  if (!baseOf(count->type)->isInteger() ||
      (constInt(count, n) && (n <= 0 || n > std::min(dsize, ssize)))) {
    error(count->loc, what + ": the size must be a number of bytes from 1 to " +
                          Twine(std::min(dsize, ssize)) +
                          " (both are that long at least)");
    return nullptr;
  }
  if (!constInt(count, n))
    n = -1;
  for (const MemoryLeaf &l : dl)
    if (l.type->kind == PTypeKind::String &&
        l.offset < (n < 0 ? std::min(dsize, ssize) : n)) {
      error(e->loc, what + ": bytes copied into a STRING are not modelled");
      return nullptr;
    }
  e->typeName = "IMAGE";
  e->intValue = n;
  if (!asStatement) {
    error(e->loc, "the result of " + e->name +
                      " (an address) is not modelled; call it as a statement");
    return nullptr;
  }
  return voidType();
}

const PType *Checker::memoryCall(Expr *e, bool asStatement) {
  bool set = e->name == "MEMSET", compare = e->name == "MEMCMP";
  if (e->args.size() != 3 ||
      llvm::any_of(e->args, [](CallArg &a) { return a.isOutput; })) {
    error(e->loc, e->name + " takes three arguments");
    return nullptr;
  }
  for (CallArg &a : e->args)
    if (!expr(a.value))
      return nullptr;
  Expr *dst = e->args[0].value, *src = e->args[1].value,
       *count = e->args[2].value;
  if (!set && !compare)
    if (std::optional<const PType *> r =
            imageCopy(e, dst, src, count, asStatement))
      return *r;
  auto designated = [&](Expr *p) -> const PType * {
    if (!p->type->isReference() || !p->type->elem) {
      error(p->loc, e->name + " takes addresses (ADR), not " + p->type->str());
      return nullptr;
    }
    // The address of an array of scalars is its first element's: the
    // elements are what is copied, set or compared.
    const PType *t = p->type->elem;
    if (t->kind == PTypeKind::Array && t->elem->kind != PTypeKind::Array &&
        t->elem->kind != PTypeKind::Struct && decayToElement(p, t->elem))
      t = p->type->elem;
    return t;
  };
  const PType *t = designated(dst);
  if (!t)
    return nullptr;
  if (!set) {
    const PType *ts = designated(src);
    if (!ts)
      return nullptr;
    if (referenceKey(ts) != referenceKey(t)) {
      error(e->loc, e->name + " between " + t->str() + " and " + ts->str() +
                        " reinterprets memory, which netlift models between "
                        "ADR(x) and ADR(y) only (the bytes of two places)");
      return nullptr;
    }
  } else if (!baseOf(src->type)->isInteger()) {
    error(src->loc, "MEMSET fills with a byte, not " + src->type->str());
    return nullptr;
  }
  std::string why;
  auto layout = memoryLayout(t, why);
  if (!layout) {
    error(e->loc, e->name + ": " + why);
    return nullptr;
  }
  int64_t n;
  if (!baseOf(count->type)->isInteger() ||
      (constInt(count, n) ? n < 0 || n % layout->size != 0
                          : !wholeElements(count, layout->size))) {
    error(count->loc, e->name + " of " + t->str() +
                          ": the size must be a whole number of " + t->str() +
                          " (n * " + Twine(layout->size) + ")");
    return nullptr;
  }
  // Known only at run time: as many elements as the block holds at most
  // (Lowering::memoryCall).
  e->intValue = constInt(count, n) ? n / layout->size : -1;
  if (e->intValue > 4096) {
    error(count->loc, e->name + " of " + Twine(e->intValue) + " " + t->str() +
                          ": netlift copies at most 4096 elements");
    return nullptr;
  }
  bool scalar = t->kind != PTypeKind::Array && t->kind != PTypeKind::Struct &&
                !t->isString();
  // Zero bytes are every value's zero (MEMSET(ADR(s), 0, SIZEOF(s)) of a
  // structure or array); other fills are taken by BOOLs, integers and
  // REALs of at most 32 bits (each byte the fill: 16#FF makes an INT -1),
  // not by the scalars whose byte patterns netlift does not hold.
  int64_t fill;
  if (set && !(constInt(src, fill) && (fill & 0xff) == 0)) {
    std::function<const PType *(const PType *)> unfillable =
        [&](const PType *x) -> const PType * {
      x = baseOf(x);
      switch (x->kind) {
      case PTypeKind::Array:
        return unfillable(x->elem);
      case PTypeKind::Struct:
        if (x->isUnion)
          return x;
        for (VarDecl *fld : x->fields)
          if (const PType *bad = unfillable(fld->type))
            return bad;
        return nullptr;
      case PTypeKind::Bool:
        return nullptr;
      case PTypeKind::Int:
      case PTypeKind::Real:
        return x->width <= 32 ? nullptr : x;
      default:
        return x;
      }
    };
    if (const PType *bad = unfillable(t)) {
      error(e->loc,
            "MEMSET of " + t->str() + " with a byte other than 0: " +
                (bad == baseOf(t) ? std::string("a ") : std::string("its ")) +
                bad->str() +
                " takes only 0 (BOOLs, integers and REALs of at "
                "most 32 bits take any byte)");
      return nullptr;
    }
  }
  // MEMCMP compares bytes in memory order (x64: little-endian), so every
  // byte of the elements must be one netlift holds.
  if (compare && !(scalar && layout->size == 1)) {
    std::vector<MemoryLeaf> leaves;
    if (!memoryLeaves(t, leaves, why) ||
        llvm::any_of(leaves, [](const MemoryLeaf &l) {
          return l.type->kind == PTypeKind::String;
        })) {
      error(e->loc, "MEMCMP of " + t->str() + ": " +
                        (why.empty() ? "the bytes of a STRING among them "
                                       "are not compared"
                                     : why));
      return nullptr;
    }
  }
  if (compare)
    return elementaryType("DINT");
  if (!asStatement) {
    error(e->loc, "the result of " + e->name +
                      " (an address) is not modelled; call it as a statement");
    return nullptr;
  }
  return voidType();
}

/// The __SYSTEM.TYPE_CLASS enumerator CODESYS gives a value of type `t`.
static const char *typeClassOf(const PType *t) {
  switch (t->kind) {
  case PTypeKind::Bool:
    return "TYPE_BOOL";
  case PTypeKind::Int: {
    static const char *bits[] = {"TYPE_BYTE", "TYPE_WORD", "TYPE_DWORD",
                                 "TYPE_LWORD"};
    static const char *sig[] = {"TYPE_SINT", "TYPE_INT", "TYPE_DINT",
                                "TYPE_LINT"};
    static const char *uns[] = {"TYPE_USINT", "TYPE_UINT", "TYPE_UDINT",
                                "TYPE_ULINT"};
    if (t->isSubrange)
      return "TYPE_SUBRANGE";
    unsigned i = t->width <= 8    ? 0
                 : t->width <= 16 ? 1
                 : t->width <= 32 ? 2
                                  : 3;
    return t->isBits ? bits[i] : t->isSigned ? sig[i] : uns[i];
  }
  case PTypeKind::Real:
    return t->width == 32 ? "TYPE_REAL" : "TYPE_LREAL";
  case PTypeKind::String:
    return t->width == 16 ? "TYPE_WSTRING" : "TYPE_STRING";
  case PTypeKind::Time:
    return t->width == 64 ? "TYPE_LTIME" : "TYPE_TIME";
  case PTypeKind::Date:
    switch (t->dateKind) {
    case DateKind::Date:
      return t->width == 64 ? "TYPE_LDATE" : "TYPE_DATE";
    case DateKind::TimeOfDay:
      return t->width == 64 ? "TYPE_LTIMEOFDAY" : "TYPE_TIMEOFDAY";
    default:
      return t->width == 64 ? "TYPE_LDATEANDTIME" : "TYPE_DATEANDTIME";
    }
  case PTypeKind::Enum:
    return "TYPE_ENUM";
  case PTypeKind::Array:
    return "TYPE_ARRAY";
  case PTypeKind::Reference:
    return t->refKind == RefKind::Pointer ? "TYPE_POINTER" : "TYPE_REFERENCE";
  default:
    return "TYPE_USERDEF";
  }
}

/// Does a value of type `t` belong to the generic type `generic`?
static bool inGeneric(const PType *t, llvm::StringRef generic) {
  bool integer = t->kind == PTypeKind::Int && !t->isBits;
  bool real = t->kind == PTypeKind::Real;
  bool elementary = t->kind != PTypeKind::Struct &&
                    t->kind != PTypeKind::Array &&
                    t->kind != PTypeKind::Reference;
  return llvm::StringSwitch<bool>(generic)
      .Case("ANY_ELEMENTARY", elementary)
      .Case("ANY_MAGNITUDE", integer || real || t->kind == PTypeKind::Time)
      .Case("ANY_NUM", integer || real)
      .Case("ANY_REAL", real)
      .Case("ANY_INT", integer)
      .Case("ANY_SIGNED", integer && t->isSigned)
      .Case("ANY_UNSIGNED", integer && !t->isSigned)
      .Case("ANY_DURATION", t->kind == PTypeKind::Time)
      .Case("ANY_BIT", t->isAnyBit())
      .Cases("ANY_CHARS", "ANY_STRING", t->kind == PTypeKind::String)
      .Case("ANY_CHAR", t->isChar())
      .Case("ANY_DATE", t->kind == PTypeKind::Date)
      .Default(true); // ANY, ANY_DERIVED
}

void Checker::anyArgument(CallArg &a, VarDecl *p) {
  const PType *t = expr(a.value);
  if (!t || t == p->type)
    return; // reported, or an ANY input passed on whole
  // An untyped literal takes the smallest type holding it, as CODESYS
  // gives constants (the signed one; LREAL for a real).
  if (t->kind == PTypeKind::AnyInt) {
    int64_t v = 0;
    constInt(a.value, v);
    t = elementaryType(v >= -128 && v <= 127              ? "SINT"
                       : v >= -32768 && v <= 32767        ? "INT"
                       : v >= INT32_MIN && v <= INT32_MAX ? "DINT"
                                                          : "LINT");
  } else if (t == anyRealType()) {
    t = elementaryType("LREAL");
  }
  const PType *bt = baseOf(t);
  if (bt->kind == PTypeKind::FunctionBlock || bt->kind == PTypeKind::Void ||
      !inGeneric(bt, p->anyGeneric)) {
    error(a.value->loc, "'" + p->name + "' is " + p->anyGeneric +
                            ": it cannot take a " + t->str());
    return;
  }
  std::string why;
  auto layout = memoryLayout(t, why);
  if (!layout) {
    error(a.value->loc, "'" + p->name + "' is " + p->anyGeneric +
                            ": netlift does not know the bytes of a " +
                            t->str() + " (" + why + ")");
    return;
  }
  // Its address: of the variable passed, or of a temporary of the caller's
  // holding the value (a constant, an expression).
  Expr *place = a.value;
  bool constant = false;
  for (Expr *x = place; x && x->kind != ExprKind::Deref; x = x->base())
    constant |= x->kind == ExprKind::Name && x->var && x->var->constant;
  if (!designatesStorage(place) || constant) {
    if (!current) {
      error(a.value->loc, "'" + p->name + "' is " + p->anyGeneric +
                              ": outside a POU it takes a variable, not a "
                              "value");
      return;
    }
    VarDecl *tmp = unit.make<VarDecl>();
    tmp->name = "__any" + std::to_string(++anyTemps);
    tmp->loc = a.loc;
    tmp->section = VarSection::Temp;
    tmp->owner = current;
    tmp->type = t;
    current->vars.push_back(tmp); // (checkPou walks them by index)
    Expr *n = unit.make<Expr>(ExprKind::Name, a.loc);
    n->name = tmp->name;
    n->var = tmp;
    n->type = t;
    a.anyValue = a.value;
    a.anyTemp = n;
    place = n;
  }
  Expr *adr = addressCall(place);
  adr->name = "ADR";
  PType *bytePointer = make(PTypeKind::Reference);
  bytePointer->refKind = RefKind::Pointer;
  bytePointer->elem = elementaryType("BYTE");
  if (!expr(adr) ||
      !assignable(bytePointer, adr, a.loc, "ANY input '" + p->name + "'"))
    return;
  a.value = adr;
  a.anyClass = unit.make<Expr>(ExprKind::EnumLit, a.loc);
  a.anyClass->typeName = "TYPE_CLASS";
  a.anyClass->name = typeClassOf(bt);
  a.anySize = unit.make<Expr>(ExprKind::IntLit, a.loc);
  a.anySize->typeName = "DINT";
  a.anySize->intValue = layout->size;
  expr(a.anyClass);
  expr(a.anySize);
}
