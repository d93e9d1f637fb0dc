//===- SemaStmts.cpp - checking PLC statements
//------------------------------===//
#include "frontends/plc/SemaChecker.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

void Checker::stmts(StmtList &list) {
  for (Stmt *s : list)
    stmt(s);
}

void Checker::stmt(Stmt *s) {
  switch (s->kind) {
  case StmtKind::Assign: {
    if (s->assignKind != AssignKind::Value) {
      referenceAssign(s);
      return;
    }
    if (propertyWrite(s))
      return;
    if (s->target->kind == ExprKind::Name) {
      VarDecl *v = lookupVar(s->target->name);
      if (v && v->inferType && !v->type) {
        const PType *vt = expr(s->value);
        if (!vt)
          return;
        vt = baseOf(vt);
        v->type = vt->kind == PTypeKind::AnyInt ? elementaryType("DINT") : vt;
      }
    }
    const PType *t = lvalue(s->target);
    // An enumerator several types share takes the target's type.
    expectedEnum = t && t->kind == PTypeKind::Enum ? t : nullptr;
    const PType *vt = expr(s->value);
    expectedEnum = nullptr;
    if (vt && t)
      assignable(t, s->value, s->loc, "assignment");
    return;
  }
  case StmtKind::Call:
    call(s->value, true);
    return;
  case StmtKind::If:
    for (auto &[cond, body] : s->arms) {
      if (const PType *t = expr(cond); t && t->kind != PTypeKind::Bool)
        error(cond->loc, "condition must be BOOL, not " + t->str());
      stmts(body);
    }
    stmts(s->elseBody);
    return;
  case StmtKind::Case: {
    const PType *sel = expr(s->value);
    if (sel && !sel->isInteger() && sel->kind != PTypeKind::Enum) {
      error(s->value->loc, "CASE selector must be an integer or an "
                           "enumeration, not " +
                               sel->str());
      sel = nullptr;
    }
    for (auto &arm : s->caseArms) {
      for (auto &l : arm.labels)
        for (Expr *b : {l.lo, l.hi}) {
          if (!b)
            continue;
          expectedEnum = sel && sel->kind == PTypeKind::Enum ? sel : nullptr;
          const PType *lt = expr(b);
          expectedEnum = nullptr;
          int64_t v;
          // CODESYS and TwinCAT: an enumerator labels an integer selector
          // with its value, an integer labels an enumeration's (the
          // lowering compares values then).
          bool enumLabel = lt && baseOf(lt)->kind == PTypeKind::Enum;
          if (lt && sel && sel->kind == PTypeKind::Enum) {
            if (lt != sel && baseOf(lt) != sel &&
                !(baseOf(lt)->isInteger() && baseOf(sel)->enumBase &&
                  constInt(b, v)))
              error(b->loc, "CASE label of type " + lt->str() +
                                " for a selector of type " + sel->str());
          } else if (lt && !constInt(b, v) &&
                     !(enumLabel && b->enumValue >= 0 &&
                       baseOf(lt)->enumBase)) {
            error(b->loc, "CASE label must be a constant");
          }
        }
      stmts(arm.body);
    }
    stmts(s->elseBody);
    return;
  }
  case StmtKind::For: {
    const PType *t = lvalue(s->target);
    if (t && !t->isInteger())
      error(s->target->loc, "FOR variable must be an integer");
    for (Expr *e : {s->from, s->to, s->by})
      if (e && expr(e) && t)
        assignable(t, e, e->loc, "FOR bound");
    ++loopDepth;
    stmts(s->body);
    --loopDepth;
    return;
  }
  case StmtKind::While:
  case StmtKind::Repeat:
    if (const PType *t = expr(s->value); t && t->kind != PTypeKind::Bool)
      error(s->value->loc, "condition must be BOOL, not " + t->str());
    ++loopDepth;
    stmts(s->body);
    --loopDepth;
    return;
  case StmtKind::Exit:
  case StmtKind::Continue:
    if (!loopDepth)
      error(s->loc, Twine(s->kind == StmtKind::Exit ? "EXIT" : "CONTINUE") +
                        " outside a loop");
    return;
  case StmtKind::Return:
    return;
  case StmtKind::Jump:
  case StmtKind::Label:
    // Only where expandJumps did not run (a body another frontend built).
    error(s->loc, "JMP and labels are taken only in a POU's ST body");
    return;
  }
}

bool Checker::charValue(const PType *c, Expr *x) {
  const PType *t = baseOf(x->type);
  if (t->isChar())
    return t->width == c->width;
  std::u16string chars;
  if (x->kind != ExprKind::StringLit || decodeStringLiteral(x->name, chars) ||
      chars.size() != 1 || (c->width == 8 && chars[0] > 255))
    return false;
  x->type = c;
  return true;
}

bool Checker::assignable(const PType *to, Expr *from, SMLoc at,
                         const Twine &what) {
  const PType *ft = from ? from->type : nullptr;
  if (!to || !ft)
    return true; // already reported
  if (instanceAsInterface(to, from, at) || addressAsBase(to, from) ||
      referenceAsBase(to, from))
    return true;
  const PType *tb = baseOf(to), *fb = baseOf(ft);
  // INT_TO_BCD(n) writes the bit string its context wants (IEC 61131-3's
  // ANY_BIT result): as many digits as the target holds.
  if (from->kind == ExprKind::Call && !from->callee &&
      tb->kind == PTypeKind::Int && tb->isBits && tb->width <= 32 &&
      lookupStdFunction(from->name).bitsFromContext) {
    from->type = tb;
    return true;
  }
  auto mismatch = [&] {
    if (!addressAsNumber(to, ft, at))
      error(at, "type mismatch in " + what + ": cannot assign " + ft->str() +
                    " to " + to->str());
    return false;
  };
  switch (tb->kind) {
  case PTypeKind::Bool:
    if (fb->kind == PTypeKind::Bool)
      return true;
    // `x := 1` for a BOOL is common IEC practice for BOOL#1.
    if (fb->kind == PTypeKind::AnyInt && from->kind == ExprKind::IntLit &&
        (from->intValue == 0 || from->intValue == 1))
      return true;
    return mismatch();
  case PTypeKind::Int: {
    if (fb->kind == PTypeKind::AnyInt) {
      if (!literalFits(from, to, at))
        return false;
      int64_t v;
      if (constInt(from, v) && (v < to->lo || v > to->hi)) {
        error(at, "value " + Twine(v) + " is out of range for " + to->str());
        return false;
      }
      return true;
    }
    // An enumerator is its value (CODESYS, TwinCAT), converted where
    // stored (Lowering::coerce).
    if (fb->kind == PTypeKind::Enum && fb->enumBase)
      fb = fb->enumBase;
    if (fb->kind != PTypeKind::Int)
      return mismatch();
    if (fb == tb || to->isSubrange)
      return true;
    bool widening = fb->width < tb->width && (tb->isSigned || !fb->isSigned);
    bool sameWidth = fb->width == tb->width &&
                     (fb->isSigned == tb->isSigned || fb->isBits || tb->isBits);
    if (widening || sameWidth)
      return true;
    // IEC 61131-3 and matiec refuse a conversion that may change the
    // value; CODESYS and TwinCAT compile it with a warning (C0195/C0196)
    // and real code from them relies on it. The value wraps into the
    // target, as the explicit conversion would. To or from a 64-bit
    // unsigned value NetIR converts only values in range: still refused.
    auto unsigned64 = [](const PType *t) {
      return t->width >= 64 && !t->isSigned;
    };
    if (unsigned64(fb) || unsigned64(tb)) {
      error(at, "type mismatch in " + what + ": " + ft->str() +
                    " does not convert implicitly to " + to->str() + " (use " +
                    fb->str() + "_TO_" + tb->str() + ")");
      return false;
    }
    diag.warning(at, "implicit conversion of " + ft->str() + " to " +
                         to->str() + " in " + what +
                         " may change the value; taken as " + fb->str() +
                         "_TO_" + tb->str() +
                         " (CODESYS accepts it with a warning, IEC "
                         "61131-3 and matiec do not)");
    return true;
  }
  case PTypeKind::Real:
    if (fb->kind == PTypeKind::Real || fb->isInteger() ||
        (fb->kind == PTypeKind::Enum && fb->enumBase))
      return true;
    return mismatch();
  case PTypeKind::String:
    // Any length: a longer value is cut to the target's (docs/st.md). A
    // STRING literal fits a WSTRING; otherwise the widths must agree.
    if (tb->isString() && fb->isString() &&
        (tb->width == fb->width ||
         (fb->width < tb->width && from->kind == ExprKind::StringLit)))
      return true;
    if (tb->isChar() && charValue(tb, from))
      return true;
    return mismatch();
  case PTypeKind::Reference:
    return referenceAssignable(tb, from, at, what);
  case PTypeKind::Date:
    // LDT := DT and back: both hold nanoseconds.
    if (fb->kind == PTypeKind::Date && fb->dateKind == tb->dateKind)
      return true;
    return mismatch();
  case PTypeKind::Enum:
    // CODESYS and TwinCAT (without {attribute 'strict'}): an integer is
    // stored as the enumerator of that value; netlift's enumerations hold
    // only their enumerators, so another value is refused (a constant) or
    // a run-time error (Lowering::integerToEnum).
    if (fb->isInteger() && tb->enumBase) {
      int64_t v;
      if (constInt(from, v) && !llvm::is_contained(tb->enumValues, v)) {
        error(at, "value " + Twine(v) + " is none of the values of " +
                      to->str() + "'s enumerators");
        return false;
      }
      return true;
    }
    [[fallthrough]];
  default:
    if (tb->kind == fb->kind &&
        (tb == fb ||
         (tb->kind != PTypeKind::Enum && tb->kind != PTypeKind::Struct &&
          tb->kind != PTypeKind::Array &&
          tb->kind != PTypeKind::FunctionBlock) ||
         (!tb->name.empty() && tb->name == fb->name) || sameArrayType(tb, fb)))
      return true;
    return mismatch();
  }
}

/// Arrays written alike in two places (a parameter's ARRAY[0..1] OF INT
/// and the argument's) are one type: same bounds, same element type.
bool Checker::sameArrayType(const PType *a, const PType *b) {
  if (a->kind != PTypeKind::Array || b->kind != PTypeKind::Array ||
      a->dims != b->dims)
    return false;
  const PType *x = a->elem, *y = b->elem;
  if (x == y || sameArrayType(x, y))
    return true;
  if (x->isSubrange || y->isSubrange)
    return x->isSubrange && y->isSubrange && x->lo == y->lo && x->hi == y->hi &&
           baseOf(x) == baseOf(y);
  return x->kind != PTypeKind::Struct && x->kind != PTypeKind::Enum &&
         x->kind != PTypeKind::FunctionBlock &&
         referenceKey(x) == referenceKey(y);
}

const PType *Checker::commonNumeric(const PType *a, const PType *b, Expr *e) {
  std::string op = e->kind == ExprKind::Call ? e->name : spelling(e->op).str();
  a = baseOf(a);
  b = baseOf(b);
  if (e->kind == ExprKind::Binary && (!literalFits(e->operands[0], b, e->loc) ||
                                      !literalFits(e->operands[1], a, e->loc)))
    return nullptr;
  if (a->kind == PTypeKind::AnyInt)
    return b;
  if (b->kind == PTypeKind::AnyInt)
    return a;
  if (a == b)
    return a;
  if (a->kind == PTypeKind::Int && b->kind == PTypeKind::Int) {
    const PType *wide = a->width >= b->width ? a : b;
    const PType *narrow = wide == a ? b : a;
    if (wide->width > narrow->width && (wide->isSigned || !narrow->isSigned))
      return wide;
    if (wide->width == narrow->width &&
        (wide->isSigned == narrow->isSigned || wide->isBits || narrow->isBits))
      return wide;
    // A signed and an unsigned operand that neither holds: CODESYS
    // computes in the register's width; NetIR's arithmetic is exact, so
    // the result is typed as the smallest signed type that holds both (INT
    // and UINT: DINT) and wraps where it is stored. A 64-bit unsigned
    // operand has none.
    if (wide->width < 64) {
      const PType *common = elementaryType(wide->width >= 32   ? "LINT"
                                           : wide->width >= 16 ? "DINT"
                                                               : "INT");
      diag.warning(e->loc, "operands of '" + op + "' mix " + a->str() +
                               " and " + b->str() + "; computed in " +
                               common->str() +
                               " (CODESYS accepts it with a warning, IEC "
                               "61131-3 and matiec do not)");
      return common;
    }
    error(e->loc, "operands of '" + op +
                      "' have incompatible "
                      "types " +
                      a->str() + " and " + b->str());
    return nullptr;
  }
  if (a->kind == PTypeKind::Real || b->kind == PTypeKind::Real) {
    // A literal takes the other operand's REAL; otherwise the wider wins.
    if (a == anyRealType() && b->kind == PTypeKind::Real)
      return b;
    if (b == anyRealType() && a->kind == PTypeKind::Real)
      return a;
    if (a->kind == PTypeKind::Real && b->kind == PTypeKind::Real)
      return a->width >= b->width ? a : b;
    if ((a->kind == PTypeKind::Real || a->isInteger()) &&
        (b->kind == PTypeKind::Real || b->isInteger()))
      return a->kind == PTypeKind::Real ? a : b;
  }
  error(e->loc, "operands of '" + op +
                    "' have incompatible "
                    "types " +
                    a->str() + " and " + b->str());
  return nullptr;
}
