//===- LowerStmts.cpp - PLC statements and loops in NetIR
//-------------------===//
#include "frontends/plc/Lowering.h"

#include <cstring>

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

bool Lowering::mayJump(const StmtList &l, bool loopLevel) {
  for (Stmt *s : l) {
    switch (s->kind) {
    case StmtKind::Return:
      return true;
    case StmtKind::Exit:
    case StmtKind::Continue:
      if (loopLevel)
        return true;
      break;
    case StmtKind::If:
      for (auto &[c, body] : s->arms)
        if (mayJump(body, loopLevel))
          return true;
      if (mayJump(s->elseBody, loopLevel))
        return true;
      break;
    case StmtKind::Case:
      for (auto &arm : s->caseArms)
        if (mayJump(arm.body, loopLevel))
          return true;
      if (mayJump(s->elseBody, loopLevel))
        return true;
      break;
    case StmtKind::For:
    case StmtKind::While:
    case StmtKind::Repeat:
      // EXIT/CONTINUE inside bind to the inner loop; RETURN still escapes.
      if (mayJump(s->body, false))
        return true;
      break;
    default:
      break;
    }
  }
  return false;
}

void Lowering::assign(NExpr *target, NExpr *value, const PType *targetType,
                      Expr *valueExpr, Sink &out, SMLoc at) {
  if (targetType && targetType->kind == PTypeKind::Bool && valueExpr &&
      valueExpr->type && valueExpr->type->kind == PTypeKind::AnyInt)
    value = b.boolLit(valueExpr->intValue != 0, at);
  if (valueExpr && targetType && baseOf(targetType)->kind == PTypeKind::Enum &&
      valueExpr->type && baseOf(valueExpr->type)->isInteger())
    value = integerToEnum(value, targetType, out, at);
  else if (valueExpr)
    value = coerce(value, valueExpr->type, targetType, at);
  assignParts(target, value, targetType, 0, out, at);
}

/// Do `a` and `b` denote the same constant (literals, enumerators and
/// aggregates of them)?
static bool sameConstant(NExpr *a, NExpr *b) {
  if (a->getKind() != b->getKind())
    return false;
  if (auto *x = llvm::dyn_cast<net::IntLit>(a))
    return x->value == llvm::cast<net::IntLit>(b)->value;
  if (auto *x = llvm::dyn_cast<net::BoolLit>(a))
    return x->value == llvm::cast<net::BoolLit>(b)->value;
  if (auto *x = llvm::dyn_cast<net::RealLit>(a))
    return std::memcmp(&x->value, &llvm::cast<net::RealLit>(b)->value,
                       sizeof(double)) == 0;
  if (auto *x = llvm::dyn_cast<net::Ref>(a))
    return x->name == llvm::cast<net::Ref>(b)->name && x->fields.empty() &&
           llvm::cast<net::Ref>(b)->fields.empty();
  if (auto *x = llvm::dyn_cast<net::StringLit>(a))
    return x->chars == llvm::cast<net::StringLit>(b)->chars;
  if (auto *x = llvm::dyn_cast<net::AggregateLit>(a)) {
    auto *y = llvm::cast<net::AggregateLit>(b);
    if (x->elems.size() != y->elems.size() || x->fieldNames != y->fieldNames)
      return false;
    for (size_t i = 0; i < x->elems.size(); ++i)
      if (!sameConstant(x->elems[i], y->elems[i]))
        return false;
    return true;
  }
  return false;
}

void Lowering::assignParts(NExpr *target, NExpr *value, const PType *t,
                           size_t dim, Sink &out, SMLoc at) {
  // NetIR takes an aggregate only as an initial value: a function's local
  // array or structure, set again at each call, and a VAR_TEMP one, reset
  // at the end of the scan, are set element by element (indexed from the
  // array's own bounds); an array whose elements are all one value by a
  // loop, so that a 256-byte buffer is not 256 statements.
  auto *agg = llvm::dyn_cast<net::AggregateLit>(value);
  if (!agg || !t) {
    out.push_back(b.assign(target, value, at));
    return;
  }
  auto part = [&](NExpr *element, NExpr *v, Sink &into) {
    if (dim + 1 < t->dims.size())
      assignParts(element, v, t, dim + 1, into, at);
    else
      assignParts(element, v, t->elem, 0, into, at);
  };
  if (!agg->isRecord() && agg->elems.size() > 4 &&
      llvm::all_of(agg->elems,
                   [&](NExpr *e) { return sameConstant(e, agg->elems[0]); })) {
    std::string k = "_k" + std::to_string(++loopVars);
    int64_t lo = t->dims[dim].first;
    Sink each;
    part(b.index(target, b.ref(k, at), at), agg->elems[0], each);
    out.push_back(b.forStmt(k, b.intLit(lo, at),
                            b.intLit(lo + int64_t(agg->elems.size()) - 1, at),
                            each, at));
    return;
  }
  for (size_t i = 0; i < agg->elems.size(); ++i) {
    if (agg->isRecord())
      assignParts(b.field(target, agg->fieldNames[i], at), agg->elems[i],
                  i < t->fields.size() ? t->fields[i]->type : nullptr, 0, out,
                  at);
    else
      part(b.index(target, b.intLit(t->dims[dim].first + int64_t(i), at), at),
           agg->elems[i], out);
  }
}

void Lowering::appendResets(
    const std::vector<std::pair<std::string, NExpr *>> &list, Sink &out) {
  for (auto &[name, init] : list) {
    auto type = varTypes.find(name);
    assignParts(b.ref(name, init->loc), init,
                type == varTypes.end() ? nullptr : type->second, 0, out,
                init->loc);
  }
}

void Lowering::body(StmtList &list, Frame &f, Sink &out,
                    const std::vector<LoopCtx> &loops) {
  for (size_t i = 0; i < list.size(); ++i) {
    Stmt *s = list[i];
    previous = i ? list[i - 1] : nullptr;
    stmt(s, f, out, loops);
    if (i + 1 == list.size())
      break;
    StmtList one{s};
    if (!mayJump(one, !loops.empty()))
      continue;
    // The rest runs only if no RETURN/EXIT/CONTINUE has been taken.
    NExpr *taken = nullptr;
    auto add = [&](const std::string &flag) {
      if (flag.empty())
        return;
      NExpr *r = b.ref(flag, s->loc);
      taken = taken ? b.binary(net::BinaryOp::Or, taken, r, s->loc) : r;
    };
    add(f.returnFlag);
    if (!loops.empty()) {
      add(loops.back().exitFlag);
      add(loops.back().continueFlag);
    }
    Sink rest;
    StmtList tail(list.begin() + i + 1, list.end());
    body(tail, f, rest, loops);
    if (!taken) {
      out.insert(out.end(), rest.begin(), rest.end());
      return;
    }
    net::IfArm arm{b.unary(net::UnaryOp::Not, taken, s->loc),
                   design.copy(llvm::ArrayRef<NStmt *>(rest))};
    out.push_back(b.ifStmt({arm}, false, {}, s->loc));
    return;
  }
}

/// An upper bound on the iterations of a WHILE or REPEAT loop of the form
///   i := c0;  WHILE i < C DO ... i := i + s; ... END_WHILE
///   i := c0;  REPEAT ... i := i + s; ... UNTIL i >= C END_REPEAT
/// (any of < <= > >= <>, the counter on either side, s of either sign):
/// the counter is set to a constant just before the loop, changed by
/// exactly one top-level `i := i +/- s` in the body and written nowhere
/// else in it, and compared with a constant. Null when no bound is proved.
std::optional<int64_t> Lowering::loopBound(Stmt *loop, Stmt *before, Frame &f) {
  Expr *cond = loop->value;
  if (!cond || cond->kind != ExprKind::Binary)
    return std::nullopt;
  Op op = cond->op;
  Expr *lhs = cond->operands[0], *rhs = cond->operands[1];
  if (lhs->kind != ExprKind::Name || !lhs->var) {
    std::swap(lhs, rhs);
    static const std::map<Op, Op> mirror = {{Op::Lt, Op::Gt}, {Op::Gt, Op::Lt},
                                            {Op::Le, Op::Ge}, {Op::Ge, Op::Le},
                                            {Op::Ne, Op::Ne}, {Op::Eq, Op::Eq}};
    auto m = mirror.find(op);
    if (m == mirror.end())
      return std::nullopt;
    op = m->second;
  }
  if (lhs->kind != ExprKind::Name || !lhs->var)
    return std::nullopt;
  VarDecl *i = lhs->var;
  std::optional<int64_t> limit = constValue(rhs, f);
  if (!limit)
    return std::nullopt;
  // The constant start.
  if (!before || before->kind != StmtKind::Assign ||
      before->target->kind != ExprKind::Name || before->target->var != i)
    return std::nullopt;
  std::optional<int64_t> start = constValue(before->value, f);
  if (!start)
    return std::nullopt;
  // The one step.
  std::optional<int64_t> step;
  StmtList others;
  for (Stmt *st : loop->body) {
    if (st->kind == StmtKind::Assign && st->target->kind == ExprKind::Name &&
        st->target->var == i && st->value->kind == ExprKind::Binary &&
        (st->value->op == Op::Add || st->value->op == Op::Sub) &&
        st->value->operands[0]->kind == ExprKind::Name &&
        st->value->operands[0]->var == i && !step) {
      step = constValue(st->value->operands[1], f);
      if (!step)
        return std::nullopt;
      if (st->value->op == Op::Sub)
        step = -*step;
      continue;
    }
    others.push_back(st);
  }
  if (!step || *step == 0)
    return std::nullopt;
  std::set<VarDecl *> w;
  collectWritten(others, w);
  if (w.count(i))
    return std::nullopt;
  // Iterations while the condition holds (WHILE) or until it holds
  // (REPEAT, at least one).
  bool isWhile = loop->kind == StmtKind::While;
  auto holds = [&](int64_t v) {
    switch (op) {
    case Op::Lt:
      return v < *limit;
    case Op::Le:
      return v <= *limit;
    case Op::Gt:
      return v > *limit;
    case Op::Ge:
      return v >= *limit;
    case Op::Ne:
      return v != *limit;
    case Op::Eq:
      return v == *limit;
    default:
      return false;
    }
  };
  const int64_t kMax = 100000;
  int64_t v = *start;
  for (int64_t n = 0; n <= kMax; ++n) {
    if (isWhile ? !holds(v) : (n > 0 && holds(v)))
      return n;
    v += *step;
  }
  return std::nullopt;
}

void Lowering::stmt(Stmt *s, Frame &f, Sink &out,
                    const std::vector<LoopCtx> &loops) {
  auto flagVar = [&](const char *what) { return newFlag(what, s->loc); };
  switch (s->kind) {
  case StmtKind::Assign: {
    NExpr *value = expr(s->value, f, out);
    if (s->assignKind == AssignKind::Attempt) {
      // `?=` between interfaces: the instance's if its block implements
      // the target's; between references to different types: never one
      // of the target's, so NULL (SemaReferences.cpp).
      const PType *t = s->target->type;
      if (t && t->isReference() && t->refKind == RefKind::Interface)
        value = interfaceQuery(value, t, out, s->loc);
      else
        value = b.intLit(0, s->loc);
      out.push_back(b.assign(lvalue(s->target, f, out), value, s->loc));
      return;
    }
    if (isStringIndex(s->target)) {
      stringByteWrite(s->target, value, f, out, s->loc);
      return;
    }
    if (s->target->kind != ExprKind::BitAccess && throughReference(s->target)) {
      writeThroughReference(s->target, value, s->value, f, out, s->loc);
      return;
    }
    if (s->target->kind == ExprKind::BitAccess) {
      partWrite(s->target, value, f, out, s->loc);
      return;
    }
    if (auto part = unionPart(s->target, f, out)) {
      out.push_back(unionWrite(*part, value, s->value->type, f, out, s->loc));
      return;
    }
    if (memberOfChosenInstance(s->target, f)) {
      chosenMemberWrite(s, value, f, out);
      return;
    }
    NExpr *target = lvalue(s->target, f, out);
    if (auto *r = llvm::dyn_cast<net::Ref>(target))
      noteClockBound(r->name.str(), s->value, f, s->loc);
    assign(target, value, s->target->type, s->value, out, s->loc);
    return;
  }
  case StmtKind::Call: {
    Expr *c = s->value;
    if (c->method) {
      functionCall(c, f, out);
      return;
    }
    if (!c->operands.empty()) {
      if (throughReference(c->operands[0]))
        callThroughReference(c, f, out);
      else
        elementCall(c, f, out);
      return;
    }
    if (c->var) {
      fbCall(c, f, out);
      return;
    }
    if (c->callee) {
      functionCall(c, f, out);
      return;
    }
    Sink pre;
    expr(c, f, pre); // a standard function whose result is dropped
    out.insert(out.end(), pre.begin(), pre.end());
    return;
  }
  case StmtKind::If: {
    // Conditions after the first that need hoisted calls start a nested IF
    // in the ELSE branch, so their calls run only when reached.
    std::function<void(size_t, Sink &)> build = [&](size_t from, Sink &dst) {
      std::vector<net::IfArm> arms;
      for (size_t k = from; k < s->arms.size(); ++k) {
        Sink pre;
        NExpr *c = expr(s->arms[k].first, f, pre);
        if (!pre.empty() && k != from) {
          // Finish this IF with an ELSE holding the rest.
          Sink elseBody;
          build(k, elseBody);
          dst.push_back(b.ifStmt(arms, true,
                                 design.copy(llvm::ArrayRef<NStmt *>(elseBody)),
                                 s->loc));
          return;
        }
        dst.insert(dst.end(), pre.begin(), pre.end());
        Sink armBody;
        body(s->arms[k].second, f, armBody, loops);
        arms.push_back({c, design.copy(llvm::ArrayRef<NStmt *>(armBody))});
      }
      Sink elseBody;
      body(s->elseBody, f, elseBody, loops);
      dst.push_back(b.ifStmt(arms, s->hasElse && !elseBody.empty(),
                             design.copy(llvm::ArrayRef<NStmt *>(elseBody)),
                             s->loc));
    };
    build(0, out);
    return;
  }
  case StmtKind::Case: {
    NExpr *sel = expr(s->value, f, out);
    // Values are compared where an integer meets an enumerator (an
    // enumeration's selector with an integer label, or the reverse).
    const PType *selType = baseOf(s->value->type);
    bool byValue = selType->kind != PTypeKind::Enum;
    for (auto &arm : s->caseArms)
      for (auto &l : arm.labels)
        for (Expr *x : {l.lo, l.hi})
          byValue |= x && x->enumValue < 0;
    if (byValue && selType->kind == PTypeKind::Enum)
      sel = enumToInteger(sel, selType, s->loc);
    std::vector<net::CaseArm> arms;
    for (auto &arm : s->caseArms) {
      std::vector<net::CaseLabel> labels;
      for (auto &l : arm.labels) {
        auto label = [&](Expr *e) -> NExpr * {
          if (e->enumValue >= 0 && byValue)
            return b.intLit(baseOf(e->type)->enumValues[e->enumValue], e->loc);
          if (e->enumValue >= 0)
            return b.ref(sanitize(e->type->name) + "#" +
                             sanitize(e->type->enumerators[e->enumValue]),
                         e->loc);
          std::optional<int64_t> c = constValue(e, f);
          if (!c)
            refuse(e->loc, "CASE label must be a constant");
          return b.intLit(*c, e->loc);
        };
        labels.push_back({label(l.lo), l.hi ? label(l.hi) : nullptr});
      }
      Sink armBody;
      body(arm.body, f, armBody, loops);
      arms.push_back({design.copy(llvm::ArrayRef<net::CaseLabel>(labels)),
                      design.copy(llvm::ArrayRef<NStmt *>(armBody))});
    }
    Sink elseBody;
    body(s->elseBody, f, elseBody, loops);
    out.push_back(b.caseStmt(sel, arms, s->hasElse,
                             design.copy(llvm::ArrayRef<NStmt *>(elseBody)),
                             s->loc));
    return;
  }
  case StmtKind::For: {
    std::optional<int64_t> from = constValue(s->from, f);
    std::optional<int64_t> to = constValue(s->to, f);
    std::optional<int64_t> by = s->by ? constValue(s->by, f) : int64_t(1);
    if (!from || !to || !by) {
      runtimeFor(s, f, out, loops);
      return;
    }
    if (*by == 0)
      refuse(s->by->loc, "FOR loop step is 0");
    // Assigning the loop variable inside the body is not allowed (IEC).
    int64_t n = *by > 0 ? (*to >= *from ? (*to - *from) / *by + 1 : 0)
                        : (*from >= *to ? (*from - *to) / -*by + 1 : 0);
    LoopCtx loop;
    if (mayJump(s->body, true)) {
      loop.exitFlag = flagVar("exit");
      loop.continueFlag = flagVar("continue");
      out.push_back(b.assign(b.ref(loop.exitFlag, s->loc),
                             b.boolLit(false, s->loc), s->loc));
    }
    std::vector<LoopCtx> inner = loops;
    inner.push_back(loop);
    NExpr *var = lvalue(s->target, f, out);
    std::string k = "_k" + std::to_string(++loopVars);
    Sink iter;
    NExpr *value = b.binary(net::BinaryOp::Add, b.intLit(*from, s->loc),
                            b.binary(net::BinaryOp::Mul, b.ref(k, s->loc),
                                     b.intLit(*by, s->loc), s->loc),
                            s->loc);
    iter.push_back(b.assign(var, value, s->loc));
    if (!loop.continueFlag.empty())
      iter.push_back(b.assign(b.ref(loop.continueFlag, s->loc),
                              b.boolLit(false, s->loc), s->loc));
    body(s->body, f, iter, inner);
    Sink loopBody;
    NExpr *stop = nullptr;
    if (!loop.exitFlag.empty())
      stop = b.ref(loop.exitFlag, s->loc);
    if (!f.returnFlag.empty())
      stop = stop ? b.binary(net::BinaryOp::Or, stop,
                             b.ref(f.returnFlag, s->loc), s->loc)
                  : b.ref(f.returnFlag, s->loc);
    if (stop) {
      net::IfArm arm{b.unary(net::UnaryOp::Not, stop, s->loc),
                     design.copy(llvm::ArrayRef<NStmt *>(iter))};
      loopBody.push_back(b.ifStmt({arm}, false, {}, s->loc));
    } else {
      loopBody = iter;
    }
    if (n > 0)
      out.push_back(b.forStmt(k, b.intLit(0, s->loc), b.intLit(n - 1, s->loc),
                              loopBody, s->loc));
    // After a loop that ran to its end the variable is one step past it.
    NExpr *final = b.intLit(*from + n * *by, s->loc);
    NStmt *after = b.assign(lvalue(s->target, f, out), final, s->loc);
    if (stop) {
      net::IfArm arm{b.unary(net::UnaryOp::Not, stop, s->loc),
                     design.copy(llvm::ArrayRef<NStmt *>(after))};
      out.push_back(b.ifStmt({arm}, false, {}, s->loc));
    } else {
      out.push_back(after);
    }
    return;
  }
  case StmtKind::While:
  case StmtKind::Repeat: {
    bool isWhile = s->kind == StmtKind::While;
    // A proved bound gives a `for` every backend can encode; otherwise
    // the loop runs as it is, under the watchdog.
    std::optional<int64_t> n = loopBound(s, previous, f);
    if (!n && !mayJump(s->body, true) && f.returnFlag.empty()) {
      Sink cond;
      NExpr *c = expr(s->value, f, cond);
      if (cond.empty()) {
        Sink bodyStmts;
        body(s->body, f, bodyStmts, loops);
        out.push_back(b.whileStmt(c, bodyStmts, !isWhile, s->loc));
        return;
      }
    }
    // for k in 0..n-1 { if <still looping> { body } }: the bound is an
    // upper bound, the condition keeps the iteration count exact.
    LoopCtx loop;
    loop.exitFlag = flagVar("exit");
    if (mayJump(s->body, true))
      loop.continueFlag = flagVar("continue");
    out.push_back(b.assign(b.ref(loop.exitFlag, s->loc),
                           b.boolLit(false, s->loc), s->loc));
    std::vector<LoopCtx> inner = loops;
    inner.push_back(loop);
    Sink iter;
    if (isWhile) {
      // Leaving the loop is an EXIT at the top of the iteration.
      Sink cond;
      NExpr *c = expr(s->value, f, cond);
      iter.insert(iter.end(), cond.begin(), cond.end());
      net::IfArm stop{
          b.unary(net::UnaryOp::Not, c, s->loc),
          design.copy(llvm::ArrayRef<NStmt *>(b.assign(
              b.ref(loop.exitFlag, s->loc), b.boolLit(true, s->loc), s->loc)))};
      iter.push_back(b.ifStmt({stop}, false, {}, s->loc));
    }
    Sink bodyStmts;
    if (!loop.continueFlag.empty())
      bodyStmts.push_back(b.assign(b.ref(loop.continueFlag, s->loc),
                                   b.boolLit(false, s->loc), s->loc));
    body(s->body, f, bodyStmts, inner);
    if (!isWhile) {
      Sink cond;
      NExpr *c = expr(s->value, f, cond);
      bodyStmts.insert(bodyStmts.end(), cond.begin(), cond.end());
      net::IfArm stop{c, design.copy(llvm::ArrayRef<NStmt *>(
                             b.assign(b.ref(loop.exitFlag, s->loc),
                                      b.boolLit(true, s->loc), s->loc)))};
      bodyStmts.push_back(b.ifStmt({stop}, false, {}, s->loc));
    }
    NExpr *running =
        b.unary(net::UnaryOp::Not, b.ref(loop.exitFlag, s->loc), s->loc);
    if (!f.returnFlag.empty())
      running = b.binary(
          net::BinaryOp::And, running,
          b.unary(net::UnaryOp::Not, b.ref(f.returnFlag, s->loc), s->loc),
          s->loc);
    net::IfArm run{running, design.copy(llvm::ArrayRef<NStmt *>(bodyStmts))};
    iter.push_back(b.ifStmt({run}, false, {}, s->loc));
    std::string k = "_k" + std::to_string(++loopVars);
    if (!n) {
      NExpr *more =
          b.unary(net::UnaryOp::Not, b.ref(loop.exitFlag, s->loc), s->loc);
      if (!f.returnFlag.empty())
        more = b.binary(
            net::BinaryOp::And, more,
            b.unary(net::UnaryOp::Not, b.ref(f.returnFlag, s->loc), s->loc),
            s->loc);
      out.push_back(b.whileStmt(more, iter, false, s->loc));
    } else if (*n > 0)
      out.push_back(b.forStmt(k, b.intLit(0, s->loc), b.intLit(*n - 1, s->loc),
                              iter, s->loc));
    return;
  }
  case StmtKind::Exit:
  case StmtKind::Continue: {
    const LoopCtx &loop = loops.back();
    const std::string &flag =
        s->kind == StmtKind::Exit ? loop.exitFlag : loop.continueFlag;
    out.push_back(
        b.assign(b.ref(flag, s->loc), b.boolLit(true, s->loc), s->loc));
    return;
  }
  case StmtKind::Return:
    if (f.returnFlag.empty())
      refuse(s->loc, "internal: RETURN without a flag");
    out.push_back(
        b.assign(b.ref(f.returnFlag, s->loc), b.boolLit(true, s->loc), s->loc));
    return;
  case StmtKind::Jump:
  case StmtKind::Label:
    refuse(s->loc, "internal: a jump expandJumps left");
  }
}

/// FOR with bounds known only at run time: the start, end and step are
/// evaluated once, when the loop starts, and the loop runs as it is, under
/// the watchdog (a control variable that wraps around before passing the
/// end runs until the watchdog stops it, as on a PLC).
std::string Lowering::newFlag(const char *what, SMLoc at) {
  std::string name = unique(std::string("_") + what + std::to_string(++flags));
  declareTemp(name, elementaryType("BOOL"), at);
  b.addAttribute(name, net::kInternalAttribute, "loop control", at);
  return name;
}

void Lowering::runtimeFor(Stmt *s, Frame &f, Sink &out,
                          const std::vector<LoopCtx> &loops) {
  SMLoc at = s->loc;
  const PType *vt = s->target->type;
  auto temp = [&](const char *what, Expr *e) -> NExpr * {
    if (std::optional<int64_t> c = e ? constValue(e, f) : int64_t(1))
      return b.intLit(*c, at);
    NExpr *v = expr(e, f, out);
    std::string name =
        unique(std::string("_for_") + what + std::to_string(++loopVars));
    declareTemp(name, vt, at);
    out.push_back(b.assign(b.ref(name, at), v, at));
    return b.ref(name, at);
  };
  NExpr *start = expr(s->from, f, out);
  NExpr *to = temp("to", s->to);
  NExpr *by = temp("by", s->by);
  out.push_back(b.assign(lvalue(s->target, f, out), start, at));
  auto var = [&] { return lvalue(s->target, f, out); };
  LoopCtx loop;
  if (mayJump(s->body, true)) {
    loop.exitFlag = newFlag("exit", at);
    loop.continueFlag = newFlag("continue", at);
    out.push_back(b.assign(b.ref(loop.exitFlag, at), b.boolLit(false, at), at));
  }
  // "EXIT or RETURN taken", built afresh for each use (null: neither can).
  auto stopped = [&]() -> NExpr * {
    NExpr *r = loop.exitFlag.empty() ? nullptr : b.ref(loop.exitFlag, at);
    if (!f.returnFlag.empty())
      r = r ? b.binary(net::BinaryOp::Or, r, b.ref(f.returnFlag, at), at)
            : b.ref(f.returnFlag, at);
    return r;
  };
  // Up while i <= to for a step >= 0, down while i >= to otherwise.
  NExpr *up = b.binary(net::BinaryOp::Le, var(), to, at);
  NExpr *down = b.binary(net::BinaryOp::Ge, var(), to, at);
  NExpr *more;
  if (auto *lit = llvm::dyn_cast<net::IntLit>(by))
    more = lit->value >= 0 ? up : down;
  else
    more = b.cond(b.binary(net::BinaryOp::Ge, by, b.intLit(0, at), at), up,
                  down, at);
  if (NExpr *stop = stopped())
    more = b.binary(net::BinaryOp::And, more,
                    b.unary(net::UnaryOp::Not, stop, at), at);
  std::vector<LoopCtx> inner = loops;
  inner.push_back(loop);
  Sink iter;
  if (!loop.continueFlag.empty())
    iter.push_back(
        b.assign(b.ref(loop.continueFlag, at), b.boolLit(false, at), at));
  body(s->body, f, iter, inner);
  NStmt *step = b.assign(var(),
                         wrapTo(b.binary(net::BinaryOp::Add, var(), by, at), vt,
                                {0, 0, false}, at),
                         at);
  if (NExpr *stop = stopped()) // CONTINUE steps on; EXIT and RETURN do not
    iter.push_back(
        b.ifStmt({net::IfArm{b.unary(net::UnaryOp::Not, stop, at),
                             design.copy(llvm::ArrayRef<NStmt *>(step))}},
                 false, {}, at));
  else
    iter.push_back(step);
  out.push_back(b.whileStmt(more, iter, false, at));
}

//===----------------------------------------------------------------------===//
// What statements write
//===----------------------------------------------------------------------===//

static void writtenBy(Expr *target, std::set<VarDecl *> &w) {
  // Through a reference the place written is what it designates (counted
  // where its address is taken), not the reference.
  while (target && target->kind != ExprKind::Name) {
    if (target->kind == ExprKind::Deref)
      return;
    target = target->base();
  }
  if (target && target->var)
    w.insert(target->var);
}

void netlift::plc::detail::collectInOutWritten(StmtList &l,
                                               std::set<VarDecl *> &w) {
  auto inOutArguments = [&](Expr *e) {
    Pou *callee = e->kind == ExprKind::Call ? calledPou(e) : nullptr;
    if (callee)
      for (CallArg &a : e->args)
        if (VarDecl *p = callee->find(a.name);
            p && p->section == VarSection::InOut && !a.isOutput)
          writtenBy(a.value, w);
  };
  forEachStmt(
      l, [](Stmt *) {}, [&](Expr *e) { forEachNestedExpr(e, inOutArguments); });
}

void netlift::plc::detail::collectWritten(StmtList &l, std::set<VarDecl *> &w) {
  forEachStmt(l, [&](Stmt *s) {
    if (s->kind == StmtKind::Assign || s->kind == StmtKind::For)
      writtenBy(s->target, w);
    if (s->kind == StmtKind::Call)
      for (CallArg &a : s->value->args)
        if (a.isOutput)
          writtenBy(a.value, w);
  });
  // An argument bound to a VAR_IN_OUT is written by the callee.
  collectInOutWritten(l, w);
}

void Lowering::collectAssignments(StmtList &l) {
  forEachStmt(l, [&](Stmt *s) {
    // `v := e`, and `inst.in := e` for a function block's input.
    if (s->kind == StmtKind::Assign && s->target->var &&
        (s->target->kind == ExprKind::Name ||
         (s->target->kind == ExprKind::Field &&
          s->target->var->section == VarSection::Input)))
      assignedValues[s->target->var].push_back(s->value);
    else if (s->kind == StmtKind::For && s->target->kind == ExprKind::Name &&
             s->target->var)
      forLoopsOf[s->target->var].push_back(s);
    else if (s->kind == StmtKind::Assign || s->kind == StmtKind::For)
      writtenBy(s->target, writtenOtherwise);
    if (s->kind != StmtKind::Call)
      return;
    // A function block call passes values to the type's inputs (whether
    // the instance is named, an element or designated by a reference).
    Pou *callee = calledPou(s->value);
    for (CallArg &a : s->value->args)
      if (a.isOutput)
        writtenBy(a.value, writtenOtherwise);
      else if (callee && callee->kind == PouKind::FunctionBlock)
        if (VarDecl *p = callee->find(a.name))
          assignedValues[p].push_back(a.value);
  });
}

/// Names read anywhere in NetIR statements (assignment targets excluded,
/// except the bases of indexed or field targets, which are read-modify-
/// write).

NExpr *Lowering::partRead(Expr *e, Frame &f, Sink &pre) {
  NExpr *base = expr(e->base(), f, pre);
  const PType *t = baseOf(e->base()->type);
  if (e->partWidth >= 64)
    return base; // LWORD.%L0: all of it
  NExpr *shifted =
      b.binary(net::BinaryOp::Shr, base,
               b.intLit(e->intValue * e->partWidth, e->loc), e->loc);
  NExpr *part = b.binary(net::BinaryOp::BitAnd, shifted,
                         b.intLit(partMask(e->partWidth), e->loc), e->loc);
  if (e->partWidth == 1)
    return b.binary(net::BinaryOp::Ne, part, b.intLit(0, e->loc), e->loc);
  return isUnsigned64(t) ? fromUnsigned64(part, baseOf(e->type), e->loc) : part;
}

void Lowering::partWrite(Expr *target, NExpr *value, Frame &f, Sink &out,
                         SMLoc at) {
  Expr *base = target->base();
  const PType *t = baseOf(base->type);
  bool wide = isUnsigned64(t);
  unsigned width = target->partWidth;
  if (width == 1 && !wide) {
    // x.3 := v  is  x := v ? x | 8 : x & ~8  (masked to x's width).
    int64_t bit = int64_t(1) << target->intValue;
    NExpr *set = b.binary(net::BinaryOp::BitOr, lvalue(base, f, out),
                          b.intLit(bit, at), at);
    NExpr *clear = b.binary(net::BinaryOp::BitAnd, lvalue(base, f, out),
                            b.intLit(~bit, at), at);
    NExpr *r = b.cond(value, wrapTo(set, t, {0, 0, false}, at), clear, at);
    out.push_back(b.assign(lvalue(base, f, out), r, at));
    return;
  }
  const PType *partType = baseOf(target->type);
  if (width >= 64) {
    out.push_back(b.assign(lvalue(base, f, out), value, at));
    return;
  }
  // x.%B1 := v  is  x := (x & ~(255 << 8)) | ((v & 255) << 8), wrapped to
  // x's type (computed in uint64 for a ULINT or LWORD).
  NExpr *bits =
      width == 1 ? b.cond(value, b.intLit(1, at), b.intLit(0, at), at) : value;
  int64_t shift = target->intValue * width;
  uint64_t mask = uint64_t(partMask(width));
  uint64_t keep = ~(mask << shift);
  if (!wide)
    keep &= uint64_t(partMask(t->width));
  NExpr *keepLit = keep > uint64_t(INT64_MAX) ? unsigned64Literal(keep, at)
                                              : b.intLit(int64_t(keep), at);
  NExpr *kept =
      b.binary(net::BinaryOp::BitAnd, lvalue(base, f, out), keepLit, at);
  NExpr *masked =
      b.binary(net::BinaryOp::BitAnd, bits, b.intLit(int64_t(mask), at), at);
  if (wide)
    masked = asUnsigned64(masked, width == 1 ? t : partType, at);
  NExpr *part = b.binary(net::BinaryOp::Shl, masked, b.intLit(shift, at), at);
  NExpr *r = b.binary(net::BinaryOp::BitOr, kept, part, at);
  out.push_back(b.assign(lvalue(base, f, out),
                         wide ? r : wrapTo(r, t, {0, 0, false}, at), at));
}
