//===- SemaExprs.cpp - checking PLC expressions
//-----------------------------===//
#include "frontends/plc/SemaChecker.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

const PType *Checker::lvalue(Expr *e) {
  const PType *t = expr(e);
  if (!t)
    return nullptr;
  Expr *root = e;
  while (root->kind != ExprKind::Name && root->base()) {
    // Through a reference the storage written is its target's.
    if (root->kind == ExprKind::Deref)
      return t;
    root = root->base();
  }
  if (root->kind != ExprKind::Name || !root->var) {
    error(e->loc, "cannot assign to this expression");
    return nullptr;
  }
  VarDecl *v = root->var;
  if (v->constant) {
    error(e->loc, "assignment to constant '" + v->name + "'");
    return nullptr;
  }
  if (!v->runtimeRecord.empty()) {
    error(e->loc, "'" + v->name + "' " + v->runtimeRecord +
                      ", which the runtime writes before every scan; "
                      "netlift lets the program read it only");
    return nullptr;
  }
  // A program's input image may be written (matiec and CODESYS accept
  // it); the lowering gives such an input a scan-local copy, and so for a
  // function block's input when the block is translated as the top (an
  // instance's own input is an ordinary variable: the flag is unused).
  if (v->area() == 'I' || (v->section == VarSection::Input && v->owner &&
                           v->owner->kind != PouKind::Function))
    v->writtenInput = true;
  // `fb.Q := x` writes an instance's output from outside.
  if (e->kind == ExprKind::Field && e->base()->type &&
      e->base()->type->kind == PTypeKind::FunctionBlock && e->var &&
      e->var->section == VarSection::Output) {
    error(e->loc,
          "assignment to output '" + e->name + "' of function block instance");
    return nullptr;
  }
  return t;
}

const PType *Checker::expr(Expr *e) {
  if (!e)
    return nullptr;
  const PType *t = nullptr;
  switch (e->kind) {
  case ExprKind::IntLit:
    if (!e->typeName.empty()) {
      t = elementaryType(e->typeName);
      if (!t) {
        // `Color#3`? Not IEC.
        error(e->loc, "unknown type '" + e->typeName + "' in typed literal");
        return nullptr;
      }
      if (!literalFits(e, t, e->loc))
        return nullptr;
      if (t->kind == PTypeKind::Int && !e->beyondInt64 &&
          (e->intValue < t->lo || e->intValue > t->hi) && !t->isBits) {
        error(e->loc, "value " + Twine(e->intValue) + " is out of range for " +
                          t->str());
        return nullptr;
      }
      if (t->kind == PTypeKind::Bool && e->intValue != 0 && e->intValue != 1) {
        error(e->loc, "BOOL literal must be 0 or 1");
        return nullptr;
      }
    } else {
      t = anyIntType();
    }
    break;
  case ExprKind::RealLit:
    t = e->typeName.empty() ? anyRealType() : elementaryType(e->typeName);
    if (!t || t->kind != PTypeKind::Real) {
      error(e->loc, "a real number cannot be a " + e->typeName);
      return nullptr;
    }
    break;
  case ExprKind::BoolLit:
    t = boolType();
    break;
  case ExprKind::TimeLit:
    t = elementaryType("TIME");
    break;
  case ExprKind::DateLit:
    t = elementaryType(e->typeName); // set by the parser from the prefix
    break;
  case ExprKind::StringLit: {
    std::u16string chars;
    if (auto err = decodeStringLiteral(e->name, chars)) {
      error(e->loc, *err);
      return nullptr;
    }
    t = stringType(std::max<size_t>(chars.size(), 1),
                   StringRef(e->name).startswith("\""));
    break;
  }
  case ExprKind::EnumLit: {
    const PType *et = resolveNamed(e->typeName, e->loc);
    if (!et)
      return nullptr;
    if (et->kind != PTypeKind::Enum) {
      error(e->loc, "'" + e->typeName + "' is not an enumerated type");
      return nullptr;
    }
    for (size_t i = 0; i < et->enumerators.size(); ++i)
      if (sameName(et->enumerators[i], e->name))
        e->enumValue = int64_t(i);
    if (e->enumValue < 0) {
      error(e->loc, "'" + e->typeName + "' has no value '" + e->name + "'");
      return nullptr;
    }
    t = et;
    break;
  }
  case ExprKind::Name: {
    if (e->name[0] == '%') {
      // A direct address used without a declaration: an input, output or
      // memory bit/word of the program.
      for (VarDecl *v : current ? current->vars : std::vector<VarDecl *>{})
        if (sameName(v->location, e->name))
          e->var = v;
      for (VarDecl *g : allGlobals)
        if (!e->var && sameName(g->location, e->name))
          e->var = g;
      if (!e->var && current && current->kind == PouKind::Program) {
        // IEC lets a program use %IX0.1 without declaring it: an implicit
        // variable of the size the address names, located there.
        StringRef addr(e->name);
        char size = addr.size() > 2 ? char(std::toupper(addr[2])) : 'X';
        const char *typeName = size == 'B'   ? "BYTE"
                               : size == 'W' ? "WORD"
                               : size == 'D' ? "DWORD"
                               : size == 'L' ? "LWORD"
                                             : "BOOL";
        VarDecl *v = unit.make<VarDecl>();
        v->name = e->name;
        v->loc = e->loc;
        v->location = e->name;
        v->owner = current;
        v->type = elementaryType(typeName);
        current->vars.push_back(v);
        e->var = v;
      }
      if (!e->var) {
        error(e->loc, "direct address " + e->name +
                          " is not declared (declare it with AT)");
        return nullptr;
      }
      t = e->var->type;
      break;
    }
    if (e->ofSuper) {
      error(e->loc, "SUPER^." + e->name +
                        " is not called (SUPER^ gives the "
                        "base's methods to call)");
      return nullptr;
    }
    if (e->selfInstance) {
      Pou *running = runningBlock();
      if (!running || running->kind != PouKind::FunctionBlock) {
        error(e->loc, "THIS^ is the running function block instance: there "
                      "is none here");
        return nullptr;
      }
      e->callee = running;
      t = resolveNamed(running->name, e->loc);
      break;
    }
    if (VarDecl *v = lookupVar(e->name, e->ofThis)) {
      e->var = v;
      t = v->type;
      break;
    }
    if (VarDecl *v = enEno(current, e->name)) {
      e->var = v;
      t = v->type;
      break;
    }
    if (current && current->resultVar && sameName(current->name, e->name)) {
      e->var = current->resultVar;
      t = current->resultType;
      break;
    }
    if (sameName(e->name, "NULL")) {
      t = nullType();
      break;
    }
    if (hasProperty(runningBlock(), e->name)) {
      if (!(t = propertyRead(e, nullptr)))
        return nullptr;
      break;
    }
    const PType *et = nullptr;
    int64_t ev = lookupEnumerator(e->name, et);
    if (ev == -2 && expectedEnum)
      for (size_t i = 0; i < expectedEnum->enumerators.size(); ++i)
        if (sameName(expectedEnum->enumerators[i], e->name)) {
          ev = int64_t(i);
          et = expectedEnum;
        }
    if (ev == -2) {
      error(e->loc, "'" + e->name +
                        "' names a value of several enumerated "
                        "types; write TYPE#" +
                        e->name);
      return nullptr;
    }
    if (ev >= 0) {
      e->enumValue = ev;
      t = et;
      break;
    }
    if (sameName(e->name, "THIS")) {
      // TwinCAT's and CODESYS's THIS: a POINTER TO the running instance,
      // ADR(THIS^).
      Expr *self = unit.make<Expr>(*e);
      self->name = "THIS^";
      self->selfInstance = true;
      e->kind = ExprKind::Call;
      e->name = "ADR";
      CallArg arg;
      arg.value = self;
      arg.loc = e->loc;
      e->args = {arg};
      return expr(e);
    }
    error(e->loc, "unknown variable '" + e->name + "'" + suggestVar(e->name));
    return nullptr;
  }
  case ExprKind::Field: {
    if (qualifiedName(e))
      return expr(e);
    const PType *bt = expr(e->base());
    if (!bt)
      return nullptr;
    e->operands[0] = throughInterface(e->base());
    bt = e->base()->type;
    if (bt->kind == PTypeKind::Struct) {
      for (VarDecl *f : bt->fields)
        if (sameName(f->name, e->name)) {
          e->var = f;
          t = f->type;
        }
      if (!t) {
        error(e->loc, "'" + bt->str() + "' has no field '" + e->name + "'");
        return nullptr;
      }
      break;
    }
    if (bt->kind == PTypeKind::FunctionBlock) {
      VarDecl *m = bt->fb->find(e->name);
      if (!m && hasProperty(bt->fb, e->name)) {
        if (!(t = propertyRead(e, e->base())))
          return nullptr;
        break;
      }
      if (!m)
        m = enEno(bt->fb, e->name);
      if (!m || (m->section != VarSection::Input &&
                 m->section != VarSection::Output &&
                 m->section != VarSection::InOut)) {
        error(e->loc, "'" + e->name + "' is not an input or output of " +
                          "function block " + bt->fb->name);
        return nullptr;
      }
      e->var = m;
      t = m->type;
      break;
    }
    error(e->loc, "'.'" + Twine(" applied to a value of type ") + bt->str());
    return nullptr;
  }
  case ExprKind::BitAccess: {
    const PType *bt = expr(e->base());
    if (!bt)
      return nullptr;
    const PType *b = baseOf(bt);
    if (b->kind != PTypeKind::Int) {
      error(e->loc, "bit access on a value of type " + bt->str());
      return nullptr;
    }
    if (e->intValue < 0 || e->intValue >= int64_t(b->width / e->partWidth)) {
      static const char *const partNames[] = {"bit", "byte", "word",
                                              "double word", "long word"};
      unsigned k = e->partWidth == 1    ? 0
                   : e->partWidth == 8  ? 1
                   : e->partWidth == 16 ? 2
                   : e->partWidth == 32 ? 3
                                        : 4;
      error(e->loc, Twine(partNames[k]) + " " + Twine(e->intValue) +
                        " does not exist in " + b->str());
      return nullptr;
    }
    t = e->partWidth == 1    ? boolType()
        : e->partWidth == 8  ? elementaryType("BYTE")
        : e->partWidth == 16 ? elementaryType("WORD")
        : e->partWidth == 32 ? elementaryType("DWORD")
                             : elementaryType("LWORD");
    break;
  }
  case ExprKind::Index: {
    const PType *bt = expr(e->base());
    if (!bt)
      return nullptr;
    // CODESYS and TwinCAT index a STRING's bytes (a WSTRING's words) from
    // 0: s[i] is the code of its (i+1)-th character (LowerStrings.cpp).
    if (baseOf(bt)->isString() && e->operands.size() == 2) {
      const PType *it = expr(e->operands[1]);
      if (it && !baseOf(it)->isInteger()) {
        error(e->operands[1]->loc, "string index must be an integer");
        return nullptr;
      }
      t = elementaryType(baseOf(bt)->width == 16 ? "WORD" : "BYTE");
      break;
    }
    // CODESYS indexes a POINTER TO T: p[i] is (p + i * SIZEOF(T))^.
    if (bt->isReference() && bt->refKind == RefKind::Pointer) {
      t = pointerIndex(e, bt);
      if (!t)
        return nullptr;
      break;
    }
    if (bt->kind != PTypeKind::Array) {
      error(e->loc, "indexing a value of type " + bt->str());
      return nullptr;
    }
    if (e->operands.size() - 1 != bt->dims.size()) {
      error(e->loc, "array has " + Twine(bt->dims.size()) +
                        " dimension(s), indexed with " +
                        Twine(e->operands.size() - 1));
      return nullptr;
    }
    for (size_t i = 1; i < e->operands.size(); ++i) {
      const PType *it = expr(e->operands[i]);
      if (it && !baseOf(it)->isInteger()) {
        error(e->operands[i]->loc, "array index must be an integer");
        return nullptr;
      }
    }
    t = bt->elem;
    break;
  }
  case ExprKind::Deref:
    t = derefType(e);
    if (!t)
      return nullptr;
    break;
  case ExprKind::Unary: {
    Expr *x = e->operands[0];
    if (e->op == Op::Neg && x->kind == ExprKind::IntLit && x->beyondInt64 &&
        x->intValue == INT64_MIN && x->typeName.empty()) {
      // -9223372036854775808, LINT's least value: one literal.
      e->kind = ExprKind::IntLit;
      e->intValue = INT64_MIN;
      e->operands.clear();
      return e->type = anyIntType();
    }
    const PType *a = expr(e->operands[0]);
    if (!a)
      return nullptr;
    const PType *b = baseOf(a);
    if (e->op == Op::Not) {
      if (!b->isAnyBit() && !(b->kind == PTypeKind::Int) &&
          b->kind != PTypeKind::AnyInt) {
        error(e->loc, "NOT applied to " + a->str());
        return nullptr;
      }
      t = b;
    } else {
      if (!b->isInteger() && b->kind != PTypeKind::Time &&
          b->kind != PTypeKind::Real) {
        error(e->loc, "'" + spelling(e->op) + "' applied to " + a->str());
        return nullptr;
      }
      if (e->op == Op::Neg && e->operands[0]->beyondInt64) {
        error(e->loc, "value -" + Twine(uint64_t(e->operands[0]->intValue)) +
                          " is out of range");
        return nullptr;
      }
      if (e->op == Op::Neg && b->kind == PTypeKind::Int && !b->isSigned) {
        error(e->loc, "negation of unsigned " + a->str());
        return nullptr;
      }
      t = b;
    }
    break;
  }
  case ExprKind::Binary: {
    const PType *a = expr(e->operands[0]);
    const PType *b = expr(e->operands[1]);
    if (!a || !b)
      return nullptr;
    const PType *ab = baseOf(a), *bb = baseOf(b);
    // CODESYS and TwinCAT: next to a number, or in arithmetic, an
    // enumerator is its integer value (of its base type); the lowering
    // converts it (Lowering::enumToInteger).
    auto numeric = [](const PType *t) {
      return t->isInteger() || t->kind == PTypeKind::Real;
    };
    bool arithmetic = e->op == Op::Add || e->op == Op::Sub ||
                      e->op == Op::Mul || e->op == Op::Div ||
                      e->op == Op::Mod || e->op == Op::And || e->op == Op::Or ||
                      e->op == Op::Xor;
    if (ab->kind == PTypeKind::Enum && ab->enumBase &&
        (numeric(bb) || arithmetic))
      a = ab = ab->enumBase;
    if (bb->kind == PTypeKind::Enum && bb->enumBase &&
        (numeric(ab) || arithmetic))
      b = bb = bb->enumBase;
    switch (e->op) {
    case Op::And:
    case Op::Or:
    case Op::Xor:
    case Op::AndThen:
    case Op::OrElse:
      if (ab->kind == PTypeKind::Bool && bb->kind == PTypeKind::Bool) {
        t = boolType();
        break;
      }
      if (e->op == Op::AndThen || e->op == Op::OrElse) {
        error(e->loc, spelling(e->op) + " needs BOOL operands");
        return nullptr;
      }
      if (ab->isInteger() && bb->isInteger()) {
        t = commonNumeric(a, b, e);
        break;
      }
      error(e->loc, "operands of " + spelling(e->op) +
                        " must both be BOOL "
                        "or both bit strings, "
                        "not " +
                        a->str() + " and " + b->str());
      return nullptr;
    case Op::Eq:
    case Op::Ne:
    case Op::Lt:
    case Op::Le:
    case Op::Gt:
    case Op::Ge: {
      bool ok = false;
      if ((ab->isInteger() || ab->kind == PTypeKind::Real) &&
          (bb->isInteger() || bb->kind == PTypeKind::Real))
        ok = commonNumeric(a, b, e) != nullptr;
      else if (ab->isString() && bb->isString())
        ok = ab->width == bb->width ||
             (ab->width < bb->width ? e->operands[0] : e->operands[1])->kind ==
                 ExprKind::StringLit;
      else if (ab->kind == bb->kind &&
               (ab->kind == PTypeKind::Bool || ab->kind == PTypeKind::Time ||
                (ab->kind == PTypeKind::Date && ab->dateKind == bb->dateKind)))
        ok = true;
      else if (ab->kind == PTypeKind::Enum && ab == bb)
        ok = true;
      else if ((ab->isReference() || bb->isReference()) &&
               (e->op == Op::Eq || e->op == Op::Ne))
        ok = comparableReferences(ab, bb, e);
      else if (ab->isReference() && bb->isReference()) {
        if (!pointerPair(e, "compare"))
          return nullptr;
        ok = true;
      } else if (ab->isChar() || bb->isChar())
        ok = ab->isChar() ? charValue(ab, e->operands[1])
                          : charValue(bb, e->operands[0]);
      if (!ok) {
        if (!addressAsNumber(a, b, e->loc))
          error(e->loc, "cannot compare " + a->str() + " with " + b->str());
        return nullptr;
      }
      t = boolType();
      break;
    }
    case Op::Add:
    case Op::Sub:
    case Op::Mul:
    case Op::Div:
    case Op::Mod:
      if (ab->isReference() || bb->isReference()) {
        t = pointerArithmetic(e, ab, bb);
        if (!t)
          return nullptr;
        break;
      }
      if (ab->kind == PTypeKind::Date || bb->kind == PTypeKind::Date) {
        t = dateArithmetic(e->op, ab, bb);
        if (!t) {
          error(e->loc, "'" + spelling(e->op) + "' on " + a->str() + " and " +
                            b->str());
          return nullptr;
        }
        break;
      }
      if (ab->kind == PTypeKind::Time || bb->kind == PTypeKind::Time) {
        bool ok = false;
        if (e->op == Op::Add || e->op == Op::Sub)
          ok = ab->kind == PTypeKind::Time && bb->kind == PTypeKind::Time;
        else if (e->op == Op::Mul)
          ok = (ab->kind == PTypeKind::Time && bb->isInteger()) ||
               (bb->kind == PTypeKind::Time && ab->isInteger());
        else if (e->op == Op::Div)
          ok = ab->kind == PTypeKind::Time && bb->isInteger();
        if (!ok) {
          error(e->loc, "'" + spelling(e->op) + "' on " + a->str() + " and " +
                            b->str());
          return nullptr;
        }
        t = elementaryType("TIME");
        break;
      }
      if ((ab->isInteger() || ab->kind == PTypeKind::Real) &&
          (bb->isInteger() || bb->kind == PTypeKind::Real)) {
        if (e->op == Op::Mod &&
            (ab->kind == PTypeKind::Real || bb->kind == PTypeKind::Real)) {
          error(e->loc, "MOD needs integer operands");
          return nullptr;
        }
        t = commonNumeric(a, b, e);
        if (!t)
          return nullptr;
        break;
      }
      error(e->loc,
            "'" + spelling(e->op) + "' on " + a->str() + " and " + b->str());
      return nullptr;
    case Op::Pow:
      if ((ab->isInteger() || ab->kind == PTypeKind::Real) &&
          (bb->isInteger() || bb->kind == PTypeKind::Real)) {
        t = elementaryType("LREAL");
        break;
      }
      error(e->loc, "'**' on " + a->str() + " and " + b->str());
      return nullptr;
    default:
      return nullptr;
    }
    break;
  }
  case ExprKind::Call:
    t = call(e, false);
    if (!t)
      return nullptr;
    break;
  }
  if (e->kind == ExprKind::Name || e->kind == ExprKind::Field ||
      e->kind == ExprKind::Index)
    t = implicitDeref(e, t);
  e->type = t;
  return t;
}

const PType *Checker::dateArithmetic(Op op, const PType *a, const PType *b) {
  // IEC 61131-3 Table 35 (ADD_TOD_TIME, SUB_DT_DT, ...) as operators, as
  // CODESYS and TwinCAT take them; a duration may come first in a sum.
  auto isTime = [](const PType *t) { return t->kind == PTypeKind::Time; };
  bool wide = a->width == 64 || b->width == 64;
  if (op == Op::Add && isTime(a))
    std::swap(a, b);
  if (a->kind != PTypeKind::Date)
    return nullptr;
  bool moves = a->dateKind == DateKind::TimeOfDay ||
               a->dateKind == DateKind::DateAndTime;
  if ((op == Op::Add || op == Op::Sub) && isTime(b) && moves)
    return a;
  if (op == Op::Sub && b->kind == PTypeKind::Date && a->dateKind == b->dateKind)
    return elementaryType(wide ? "LTIME" : "TIME");
  return nullptr;
}

/// CODESYS and TwinCAT qualify an enumerator by its type (`E_Mode.Running`,
/// required under {attribute 'qualified_only'}) and a global by its list
/// (`GVL_IO.bStart`): `e` becomes the enumerator or the global.
bool Checker::qualifiedName(Expr *e) {
  Expr *q = e->base();
  // A library's enumeration named with its library
  // (`__SYSTEM.TYPE_CLASS.TYPE_INT`).
  if (q->kind == ExprKind::Field && q->base()->kind == ExprKind::Name &&
      !lookupVar(q->base()->name) && libraryNamespace(q->base()->name))
    if (TypeDecl *td = unit.findType(q->name); td && td->isLibrary) {
      q->kind = ExprKind::Name;
      q->operands.clear();
    }
  if (q->kind != ExprKind::Name || q->ofThis || q->ofSuper ||
      lookupVar(q->name))
    return false;
  if (TypeDecl *td = unit.findType(q->name)) {
    const PType *t = resolveNamed(td->name, q->loc);
    if (!t || t->kind != PTypeKind::Enum)
      return false;
    e->kind = ExprKind::EnumLit;
    e->typeName = td->name;
    e->operands.clear();
    return true;
  }
  for (VarDecl *g : allGlobals)
    if (sameName(g->globalList, q->name) && sameName(g->name, e->name)) {
      e->kind = ExprKind::Name;
      e->operands.clear();
      e->name = g->name;
      return true;
    }
  return false;
}
