//===- SemaCalls.cpp - checking PLC calls
//-----------------------------------===//
#include "frontends/plc/SemaChecker.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

void Checker::functionArgs(Expr *e, Pou *fn) {
  std::vector<VarDecl *> params;
  for (VarDecl *v : fn->vars)
    if (v->section == VarSection::Input || v->section == VarSection::InOut ||
        v->section == VarSection::Output)
      params.push_back(v);
  size_t positional = 0;
  for (CallArg &a : e->args) {
    VarDecl *p = nullptr;
    if (a.name.empty()) {
      // Positional arguments bind the inputs (and in-outs) in order.
      while (positional < params.size() &&
             params[positional]->section == VarSection::Output)
        ++positional;
      if (positional >= params.size()) {
        error(a.loc, "too many arguments for '" + fn->name + "'");
        return;
      }
      p = params[positional++];
    } else {
      p = fn->find(a.name);
      if (!p)
        p = enEno(fn, a.name);
      if (!p ||
          (p->section != VarSection::Input && p->section != VarSection::InOut &&
           p->section != VarSection::Output)) {
        // Through an instance, say its type: `PT c` on a CTU named c.
        error(a.loc, (e->var ? "'" + e->name + "' (" + fn->name + ")"
                             : "'" + fn->name + "'") +
                         " has no parameter '" + a.name + "'");
        return;
      }
    }
    if (a.isOutput != (p->section == VarSection::Output)) {
      error(a.loc, a.isOutput
                       ? "'=>' binds outputs; '" + p->name + "' is a " +
                             spelling(p->section)
                       : "output '" + p->name + "' must be bound with '=>'");
      return;
    }
    if (!fn->environment.empty() && !a.isOutput) {
      // Not stored (the runtime's): only checked to be an expression.
      expr(a.value);
      a.name = p->name;
      continue;
    }
    if (a.isOutput || p->section == VarSection::InOut) {
      // THIS^ passed in-out: the running instance itself.
      const PType *t = !a.isOutput && a.value->selfInstance ? expr(a.value)
                                                            : lvalue(a.value);
      // An instance in-out: of the parameter's block or one derived from
      // it (which has every member and method the block uses).
      if (t && p->type && !a.isOutput && t->kind == PTypeKind::FunctionBlock &&
          p->type->kind == PTypeKind::FunctionBlock &&
          !p->type->fb->isInterface && !derivedFrom(t->fb, p->type->fb)) {
        error(a.loc, "VAR_IN_OUT '" + p->name + "' of type " + p->type->str() +
                         " bound to a " + t->str() +
                         ", which does not EXTEND it");
        return;
      }
      // ARRAY[*]: any array of its element type and dimensions.
      if (t && p->type && p->section == VarSection::InOut &&
          p->type->kind == PTypeKind::Array && p->type->anyBounds &&
          (baseOf(t)->kind != PTypeKind::Array ||
           baseOf(t)->dims.size() != p->type->dims.size() ||
           referenceKey(baseOf(t)->elem) != referenceKey(p->type->elem))) {
        error(a.loc, "VAR_IN_OUT '" + p->name + "' of type " + p->type->str() +
                         " bound to a " + t->str());
        return;
      }
      if (t && p->type &&
          (p->section == VarSection::InOut
               ? baseOf(t) != baseOf(p->type) &&
                     !(t->kind == p->type->kind && t->kind != PTypeKind::Int)
               : false)) {
        error(a.loc, "VAR_IN_OUT '" + p->name + "' of type " + p->type->str() +
                         " bound to a " + t->str());
        return;
      }
      if (a.isOutput && t && p->type) {
        Expr probe(ExprKind::Name, a.loc);
        probe.type = p->type;
        assignable(t, &probe, a.loc, "output '" + p->name + "'");
      }
    } else if (!p->anyGeneric.empty()) {
      anyArgument(a, p);
    } else if (p->type && p->type->isReference() &&
               p->type->refKind == RefKind::Reference) {
      // `fb(r := x)` binds the REFERENCE TO input r to x.
      Expr *call = addressCall(a.value);
      a.value = call;
      if (expr(call))
        assignable(p->type, call, a.loc, "argument '" + p->name + "'");
    } else if (expr(a.value)) {
      assignable(p->type, a.value, a.loc, "argument '" + p->name + "'");
    }
    a.name = p->name; // canonical spelling for the lowering
  }
  for (VarDecl *p : params)
    if (p->section == VarSection::InOut) {
      bool given = false;
      for (CallArg &a : e->args)
        given |= sameName(a.name, p->name);
      if (!given)
        error(e->loc, "VAR_IN_OUT '" + p->name + "' of '" + fn->name +
                          "' must be given");
    }
}

/// Puts the named inputs of a standard function call in parameter order
/// (IEC names: IN; IN1..INn; MN, IN, MX for LIMIT; G, IN0, IN1 for SEL;
/// K, IN0..INn for MUX; IN, N for shifts). All arguments are named or none.
/// The operands of a string function: S a string, L a length, P a
/// position; "S+" for CONCAT's two or more strings.
static StringRef stringOperandShape(StringRef name) {
  return llvm::StringSwitch<StringRef>(StringRef(name).upper())
      .Case("LEN", "S")
      .Cases("LEFT", "RIGHT", "SL")
      .Cases("MID", "DELETE", "SLP")
      .Case("CONCAT", "S+")
      .Case("INSERT", "SSP")
      .Case("REPLACE", "SSLP")
      .Case("FIND", "SS")
      .Default("");
}

const PType *Checker::stringCall(Expr *e, llvm::ArrayRef<const PType *> types) {
  StringRef shape = stringOperandShape(e->name);
  bool variadic = shape == "S+";
  size_t want = variadic ? 2 : shape.size();
  if (types.size() < want || (!variadic && types.size() > want)) {
    error(e->loc, "'" + e->name + "' takes " +
                      (variadic ? Twine(want) + " or more" : Twine(want)) +
                      " argument(s), given " + Twine(types.size()));
    return nullptr;
  }
  // A STRING literal next to a WSTRING reads as one; otherwise the widths
  // must agree.
  const PType *wideOperand = nullptr, *narrowOperand = nullptr;
  uint64_t total = 0;
  for (size_t i = 0; i < types.size(); ++i) {
    const PType *t = baseOf(types[i]);
    Expr *arg = e->args[i].value;
    if (variadic || shape[i] == 'S') {
      if (!t->isString()) {
        error(arg->loc, "'" + e->name + "' needs a STRING or WSTRING as " +
                            "argument " + Twine(i + 1) + ", given " +
                            types[i]->str());
        return nullptr;
      }
      if (t->width == 16)
        wideOperand = t;
      else if (arg->kind != ExprKind::StringLit)
        narrowOperand = t;
      total += t->strLen;
    } else if (!t->isInteger()) {
      error(arg->loc, "'" + e->name + "' needs an integer as argument " +
                          Twine(i + 1) + ", given " + types[i]->str());
      return nullptr;
    }
  }
  if (wideOperand && narrowOperand) {
    error(e->loc, "'" + e->name + "' mixes " + narrowOperand->str() + " and " +
                      wideOperand->str() +
                      " (convert one with STRING_TO_WSTRING or "
                      "WSTRING_TO_STRING)");
    return nullptr;
  }
  if (shape == "S" || shape == "SS") // LEN, FIND
    return elementaryType("INT");
  bool wide = wideOperand != nullptr;
  // CONCAT, INSERT, REPLACE hold both strings whole; the others no more
  // than their string.
  if (variadic || shape.startswith("SS"))
    return stringType(total, wide);
  return stringType(baseOf(types[0])->strLen, wide);
}

bool Checker::orderStdArgs(Expr *e, StdFn fn) {
  size_t named = 0;
  for (CallArg &a : e->args)
    named += !a.name.empty();
  if (named == 0)
    return true;
  if (named != e->args.size()) {
    error(e->loc, "'" + e->name + "': give all arguments by name or none");
    return false;
  }
  auto position = [&](StringRef n) -> int {
    std::string u = n.upper();
    StringRef up(u);
    unsigned k;
    switch (fn) {
    case StdFn::Limit:
      return up == "MN" ? 0 : up == "IN" ? 1 : up == "MX" ? 2 : -1;
    case StdFn::Sel:
      return up == "G" ? 0 : up == "IN0" ? 1 : up == "IN1" ? 2 : -1;
    case StdFn::Mux:
      if (up == "K")
        return 0;
      return up.consume_front("IN") && !up.getAsInteger(10, k) ? int(k) + 1
                                                               : -1;
    case StdFn::Shl:
    case StdFn::Shr:
    case StdFn::Rol:
    case StdFn::Ror:
      return up == "IN" ? 0 : up == "N" ? 1 : -1;
    case StdFn::StringOp: {
      // LEFT(IN, L), MID(IN, L, P), INSERT(IN1, IN2, P),
      // REPLACE(IN1, IN2, L, P), ...: L and P follow the strings. CODESYS
      // and TwinCAT name them STR, STR1, STR2, SIZE (LEFT, RIGHT), LEN
      // (MID, DELETE) and POS.
      StringRef shape = stringOperandShape(e->name);
      std::string codesys;
      if (up.startswith("STR"))
        codesys = "IN" + up.drop_front(3).str();
      else if (up == "SIZE" || up == "LEN")
        codesys = "L";
      else if (up == "POS")
        codesys = "P";
      if (!codesys.empty())
        up = codesys;
      if (up == "L" || up == "P") {
        size_t at = shape.find(up == "L" ? 'L' : 'P');
        return at == StringRef::npos ? -1 : int(at);
      }
      if (up == "IN")
        return 0;
      if (up.consume_front("IN") && !up.getAsInteger(10, k) && k >= 1 &&
          (shape == "S+" || k <= shape.count('S')))
        return int(k) - 1;
      return -1;
    }
    default:
      if (up == "IN")
        return 0;
      return up.consume_front("IN") && !up.getAsInteger(10, k) && k >= 1
                 ? int(k) - 1
                 : -1;
    }
  };
  std::vector<CallArg> ordered(e->args.size());
  std::vector<bool> filled(e->args.size(), false);
  for (CallArg &a : e->args) {
    int p = position(a.name);
    if (p < 0 || size_t(p) >= ordered.size() || filled[p]) {
      error(a.loc, "'" + e->name + "' has no parameter '" + a.name + "' here");
      return false;
    }
    ordered[p] = a;
    filled[p] = true;
  }
  e->args = std::move(ordered);
  return true;
}

static const char *withArticle(VarSection s) {
  switch (s) {
  case VarSection::Input:
    return "an input";
  case VarSection::Output:
    return "an output";
  case VarSection::InOut:
    return "an in-out parameter";
  default:
    return "a local variable";
  }
}

/// Holds a graphical block against the type it calls: the type it is drawn
/// as must be the one its instance is declared with, and each pin must be a
/// parameter of that type in the group it is drawn in.
bool Checker::drawnAsDeclared(Expr *e, Pou *type) {
  const DrawnBlock &d = *e->drawn;
  if (!d.instanceName.empty() && !sameName(d.typeName, type->name)) {
    error(e->loc, "block '" + d.instanceName + "' is drawn as " + d.typeName +
                      " but declared " + type->name);
    return false;
  }
  std::string block = d.instanceName.empty() ? "block " + type->name
                                             : "block '" + d.instanceName +
                                                   "' (" + type->name + ")";
  for (const DrawnPin &pin : d.pins) {
    VarDecl *p = type->find(pin.name);
    if (!p)
      p = enEno(type, pin.name);
    // A function's result leaves through the output pin OUT.
    if (!p && type->kind == PouKind::Function && pin.name.size() == 3 &&
        sameName(pin.name, "OUT") && pin.drawnAs == VarSection::Output)
      continue;
    if (!p ||
        (p->section != VarSection::Input && p->section != VarSection::Output &&
         p->section != VarSection::InOut)) {
      error(pin.loc, block + " has no parameter '" + pin.name + "'");
      return false;
    }
    if (p->section != pin.drawnAs) {
      error(pin.loc, block + ": '" + p->name + "' is " +
                         withArticle(p->section) + ", drawn as " +
                         withArticle(pin.drawnAs));
      return false;
    }
  }
  return true;
}

const PType *Checker::call(Expr *e, bool asStatement) {
  // `Tc2_Math.LTRUNC(x)`: the library's function, called by its name.
  if (e->method && e->operands.size() == 1 &&
      e->operands[0]->kind == ExprKind::Name &&
      libraryNamespace(e->operands[0]->name)) {
    StringRef lib = e->operands[0]->name;
    if (Pou *p = unit.findPou(e->name); p && !p->isLibrary) {
      error(e->loc, "'" + lib + "." + e->name + "' names " + lib + "'s " +
                        e->name + ", but the project declares its own '" +
                        e->name +
                        "', which replaces netlift's model of the library's");
      return nullptr;
    }
    e->method = false;
    e->operands.clear();
  }
  if (e->method)
    return methodCall(e, asStatement);
  // `r^(...)`, or `r(...)` for a REFERENCE TO: the instance r designates.
  if (VarDecl *v = e->operands.empty() ? lookupVar(e->name) : nullptr;
      v && v->type && v->type->isReference() && v->type->elem &&
      v->type->elem->kind == PTypeKind::FunctionBlock) {
    Expr *r = unit.make<Expr>(ExprKind::Name, e->loc);
    r->name = e->name;
    e->operands.push_back(r);
  }
  if (!e->operands.empty()) {
    const PType *t = expr(e->operands[0]);
    if (!t)
      return nullptr;
    if (t->kind != PTypeKind::FunctionBlock) {
      error(e->loc, "'" + e->name + "' is of type " + t->str() +
                        ", not a function block instance");
      return nullptr;
    }
    if (!asStatement) {
      error(e->loc, "function block instance '" + e->name +
                        "' cannot be called inside an expression");
      return nullptr;
    }
    functionArgs(e, t->fb);
    return voidType();
  }
  // An FB instance call (statement only).
  if (VarDecl *v = lookupVar(e->name)) {
    if (!v->type)
      return nullptr;
    if (v->type->kind != PTypeKind::FunctionBlock) {
      error(e->loc, "'" + e->name + "' is a variable of type " +
                        v->type->str() + ", not a function block instance");
      return nullptr;
    }
    if (!asStatement) {
      error(e->loc, "function block instance '" + e->name +
                        "' cannot be called inside an expression");
      return nullptr;
    }
    e->var = v;
    if (e->drawn && !drawnAsDeclared(e, v->type->fb))
      return nullptr;
    functionArgs(e, v->type->fb);
    return voidType();
  }
  if (e->drawn && !e->drawn->instanceName.empty()) {
    error(e->loc, "block '" + e->drawn->instanceName + "' (" +
                      e->drawn->typeName + "): no variable '" +
                      e->drawn->instanceName + "' is declared");
    return nullptr;
  }
  // A method or action of the running instance, called by its name.
  if (Pou *running = runningBlock();
      running && !e->drawn && findMethod(running, e->name)) {
    e->method = true;
    return methodCall(e, asStatement);
  }
  if (Pou *p = unit.findPou(e->name)) {
    if (p->kind != PouKind::Function) {
      if (e->drawn)
        error(e->loc, noInstanceMessage(e->name));
      else
        error(e->loc, "'" + e->name + "' is a " + spelling(p->kind) +
                          "; only functions and function block instances "
                          "can be called");
      return nullptr;
    }
    if (p == current) {
      error(e->loc, "recursive call of function '" + p->name + "'");
      return nullptr;
    }
    e->callee = p;
    if (e->drawn && !drawnAsDeclared(e, p))
      return nullptr;
    functionArgs(e, p);
    if (!asStatement && p->resultType == voidType()) {
      error(e->loc, "function '" + p->name +
                        "' has no result type: call it as a statement and "
                        "read its outputs");
      return nullptr;
    }
    return p->resultType;
  }
  if (auto t = referenceCall(e, asStatement))
    return *t;
  // SIZEOF(x) (CODESYS, TwinCAT): the bytes of x's type, a constant.
  if (sameName(e->name, "SIZEOF")) {
    if (e->args.size() != 1 || e->args[0].isOutput) {
      error(e->loc, "SIZEOF takes one variable");
      return nullptr;
    }
    // A variable, or a type (SIZEOF(INT), SIZEOF(MyStruct)).
    Expr *arg = e->args[0].value;
    const PType *t = nullptr;
    if (arg->kind == ExprKind::Name && !lookupVar(arg->name) &&
        (elementaryType(arg->name) || unit.findType(arg->name)))
      t = resolveNamed(arg->name, arg->loc);
    else
      t = expr(arg);
    if (!t)
      return nullptr;
    std::string why;
    std::optional<MemoryLayout> l = memoryLayout(t, why);
    if (!l) {
      error(e->args[0].loc, "SIZEOF: " + why);
      return nullptr;
    }
    e->kind = ExprKind::IntLit;
    e->intValue = l->size;
    e->args.clear();
    e->name.clear();
    return anyIntType();
  }
  StdFnInfo info = lookupStdFunction(e->name);
  if (info.fn == StdFn::None) {
    error(e->loc,
          "unknown function '" + e->name + "'" + suggestFunction(e->name));
    return nullptr;
  }
  // EN and ENO, as OpenPLC and Beremiz write FBD blocks in ST: the
  // function runs only when EN is TRUE, else gives its type's initial
  // value, and ENO says which (matiec's rule).
  for (size_t i = 0; i < e->args.size();) {
    CallArg &a = e->args[i];
    bool en = !a.isOutput && sameName(a.name, "EN");
    bool eno = a.isOutput && sameName(a.name, "ENO");
    if (!en && !eno) {
      ++i;
      continue;
    }
    (en ? e->enable : e->enableOut) = a.value;
    e->args.erase(e->args.begin() + i);
  }
  if (e->enable && (!expr(e->enable) ||
                    !assignable(boolType(), e->enable, e->enable->loc, "EN")))
    return nullptr;
  if (e->enableOut) {
    const PType *t = lvalue(e->enableOut);
    if (!t)
      return nullptr;
    if (baseOf(t)->kind != PTypeKind::Bool) {
      error(e->enableOut->loc, "ENO goes to a BOOL, not " + t->str());
      return nullptr;
    }
  }
  if (!orderStdArgs(e, info.fn))
    return nullptr;
  std::vector<const PType *> types;
  for (CallArg &a : e->args) {
    if (a.isOutput) {
      error(a.loc, "standard function '" + e->name + "' has no outputs");
      return nullptr;
    }
    const PType *t = expr(a.value);
    if (!t)
      return nullptr;
    types.push_back(t);
  }
  auto arity = [&](size_t lo, size_t hi) {
    if (types.size() < lo || types.size() > hi) {
      error(e->loc, "'" + e->name + "' takes " +
                        (lo == hi ? Twine(lo) : Twine(lo) + " or more") +
                        " argument(s), given " + Twine(types.size()));
      return false;
    }
    return true;
  };
  auto numericOf = [&](size_t from) -> const PType * {
    const PType *t = types[from];
    for (size_t i = from + 1; i < types.size() && t; ++i) {
      // A stand-in for the call in commonNumeric's messages.
      Expr probe(ExprKind::Call, e->loc);
      probe.name = e->name;
      if (baseOf(t)->kind == PTypeKind::Time &&
          baseOf(types[i])->kind == PTypeKind::Time)
        continue;
      if (baseOf(t)->kind == PTypeKind::Bool &&
          baseOf(types[i])->kind == PTypeKind::Bool)
        continue;
      if (baseOf(t)->kind == PTypeKind::Date &&
          baseOf(types[i])->kind == PTypeKind::Date &&
          baseOf(t)->dateKind == baseOf(types[i])->dateKind)
        continue;
      if (baseOf(t)->kind == PTypeKind::Enum && baseOf(types[i]) == baseOf(t))
        continue;
      if (baseOf(t)->isString() && baseOf(types[i])->isString() &&
          baseOf(t)->width == baseOf(types[i])->width) {
        // EQ, SEL, MUX, MIN... on strings: the longer one holds either.
        if (baseOf(types[i])->strLen > baseOf(t)->strLen)
          t = types[i];
        continue;
      }
      t = commonNumeric(t, types[i], &probe);
    }
    return t ? baseOf(t) : nullptr;
  };
  e->callee = nullptr;
  switch (info.fn) {
  case StdFn::Abs:
  case StdFn::Move:
    if (!arity(1, 1))
      return nullptr;
    return baseOf(types[0]);
  case StdFn::Add:
  case StdFn::Sub:
    if (types.size() == 2 && (baseOf(types[0])->kind == PTypeKind::Date ||
                              baseOf(types[1])->kind == PTypeKind::Date)) {
      const PType *t = dateArithmetic(info.fn == StdFn::Add ? Op::Add : Op::Sub,
                                      baseOf(types[0]), baseOf(types[1]));
      if (!t)
        error(e->loc, "'" + e->name + "' on " + types[0]->str() + " and " +
                          types[1]->str());
      return t;
    }
    if (!arity(2, info.fn == StdFn::Add ? 64 : 2))
      return nullptr;
    return numericOf(0);
  case StdFn::Min:
  case StdFn::Max:
  case StdFn::Mul:
    if (!arity(2, 64))
      return nullptr;
    return numericOf(0);
  case StdFn::Div:
  case StdFn::Mod:
    if (!arity(2, 2))
      return nullptr;
    return numericOf(0);
  case StdFn::Limit:
    if (!arity(3, 3))
      return nullptr;
    return numericOf(0);
  case StdFn::Sel:
    if (!arity(3, 3))
      return nullptr;
    if (baseOf(types[0])->kind != PTypeKind::Bool) {
      error(e->args[0].loc, "SEL selector G must be BOOL");
      return nullptr;
    }
    return numericOf(1);
  case StdFn::Mux:
    if (!arity(2, 64))
      return nullptr;
    if (!baseOf(types[0])->isInteger()) {
      error(e->args[0].loc, "MUX selector K must be an integer");
      return nullptr;
    }
    return numericOf(1);
  case StdFn::And:
  case StdFn::Or:
  case StdFn::Xor:
    if (!arity(2, 64))
      return nullptr;
    for (const PType *t : types)
      if (!baseOf(t)->isAnyBit() && !baseOf(t)->isInteger()) {
        error(e->loc, "'" + e->name + "' needs BOOL or bit-string inputs");
        return nullptr;
      }
    return numericOf(0);
  case StdFn::Not:
    if (!arity(1, 1))
      return nullptr;
    return baseOf(types[0]);
  case StdFn::Shl:
  case StdFn::Shr:
  case StdFn::Rol:
  case StdFn::Ror:
    if (!arity(2, 2))
      return nullptr;
    if (baseOf(types[0])->kind != PTypeKind::Int ||
        !baseOf(types[1])->isInteger()) {
      error(e->loc, "'" + e->name + "' shifts a bit string by an integer");
      return nullptr;
    }
    return baseOf(types[0]);
  case StdFn::Gt:
  case StdFn::Ge:
  case StdFn::Eq:
  case StdFn::Le:
  case StdFn::Lt:
    if (!arity(2, 64) || !numericOf(0))
      return nullptr;
    return boolType();
  case StdFn::Ne:
    if (!arity(2, 2) || !numericOf(0))
      return nullptr;
    return boolType();
  case StdFn::Convert: {
    if (!arity(1, 1))
      return nullptr;
    const PType *src = baseOf(types[0]);
    // An enumerator is its value (CODESYS, TwinCAT): DINT_TO_INT(eState).
    if (info.from && info.from->kind == PTypeKind::Int &&
        src->kind == PTypeKind::Enum && src->enumBase)
      return info.to;
    if (info.from && src->kind != PTypeKind::AnyInt && src != info.from &&
        !(src->kind == info.from->kind && src->kind != PTypeKind::Int &&
          src->dateKind == info.from->dateKind)) {
      error(e->args[0].loc, "'" + e->name + "' converts from " +
                                info.from->str() + ", given " + src->str());
      return nullptr;
    }
    return info.to;
  }
  case StdFn::RealMath: {
    bool expt = sameName(e->name, "EXPT") || sameName(e->name, "ATAN2");
    if (!arity(expt ? 2 : 1, expt ? 2 : 1))
      return nullptr;
    for (size_t i = 0; i < types.size(); ++i) {
      const PType *t = baseOf(types[i]);
      if (t->kind != PTypeKind::Real && !t->isInteger()) {
        error(e->args[i].loc,
              "'" + e->name + "' needs a number, given " + types[i]->str());
        return nullptr;
      }
    }
    if (sameName(e->name, "TRUNC"))
      return elementaryType("DINT"); // as CODESYS's TRUNC
    // The type of the (first) operand; LREAL for integers and literals.
    const PType *t = baseOf(types[0]);
    return t->kind == PTypeKind::Real && t != anyRealType()
               ? t
               : elementaryType("LREAL");
  }
  case StdFn::StringOp:
    return stringCall(e, types);
  case StdFn::Bcd: {
    if (!arity(1, 1))
      return nullptr;
    const PType *src = baseOf(types[0]);
    bool fits = info.toBcd ? src->isInteger() && !src->isBits
                           : src->kind == PTypeKind::AnyInt ||
                                 (src->kind == PTypeKind::Int && src->isBits);
    if (!fits ||
        (info.from && src->kind != PTypeKind::AnyInt && src != info.from)) {
      error(e->args[0].loc,
            "'" + e->name + "' converts " +
                (info.from ? info.from->str()
                           : std::string("a bit string (BYTE, WORD, ...)")) +
                (info.toBcd ? " to BCD" : " holding BCD digits") + ", given " +
                src->str());
      return nullptr;
    }
    if (info.to->width > 32 || (info.from && info.from->width > 32) ||
        src->width > 32) {
      error(e->loc, "'" + e->name +
                        "': BCD conversions of 64-bit values are not "
                        "supported");
      return nullptr;
    }
    return info.to;
  }
  case StdFn::Bound: {
    if (!arity(2, 2))
      return nullptr;
    const PType *array = baseOf(types[0]);
    int64_t dim;
    if (array->kind != PTypeKind::Array) {
      error(e->args[0].loc,
            "'" + e->name + "' of a " + types[0]->str() + ", not an array");
      return nullptr;
    }
    if (!constInt(e->args[1].value, dim) || dim < 1 ||
        dim > int64_t(array->dims.size())) {
      error(e->args[1].loc, "'" + e->name +
                                "' takes a dimension, a constant "
                                "1.." +
                                Twine(array->dims.size()));
      return nullptr;
    }
    e->intValue = dim;
    return elementaryType("DINT");
  }
  case StdFn::Clock: {
    if (!arity(0, 0))
      return nullptr;
    // 4diac: NOW_MONOTONIC() is a TIME, NOW() a DATE_AND_TIME.
    std::string fn = StringRef(e->name).upper();
    return elementaryType(fn == "NOW_MONOTONIC" ? "TIME"
                          : fn == "NOW"         ? "DT"
                                                : fn);
  }
  case StdFn::None:
    break;
  }
  return nullptr;
}
