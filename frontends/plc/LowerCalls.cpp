//===- LowerCalls.cpp - PLC function and FB calls inlined
//-------------------===//
#include "frontends/plc/Lowering.h"

#include "ir/net/Walk.h"

#include "llvm/ADT/ScopeExit.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Calls
//===----------------------------------------------------------------------===//

/// Which implementation a method call runs and on which instances: on
/// the running instance, the override its type has (dynamic dispatch
/// within a block's own code), unless SUPER^ names the base's; on a named
/// instance (or the elements of an array chosen at run time), its type's.
Lowering::MethodTarget Lowering::methodTarget(Expr *call, Frame &f, Sink &pre) {
  MethodTarget t;
  if (call->operands.empty()) {
    auto [type, prefix] = f.running();
    t.selfType = type;
    t.impl = call->ofSuper ? call->callee : findCallee(type, call);
    t.prefixes.push_back(prefix);
    t.tests.push_back(nullptr);
  } else if (throughReference(call->operands[0])) {
    // Through a reference or an interface: each instance it may designate,
    // whose type's implementation runs there.
    Expr *instance = call->operands[0];
    DerefTargets d = derefTargets(instance, f, pre);
    Pou *seenAs = instance->type->fb;
    for (const RefFamily *fam : d.live) {
      auto *ref =
          llvm::dyn_cast<net::Ref>(familyPlace(*fam, d, instance, f, pre));
      if (!ref)
        refuse(call->loc, "internal: an instance in an element");
      Pou *type = instanceTypes[ref->name.str()];
      // Every interface's instances share one numbering: those of blocks
      // that do not implement this one are never designated here.
      if (seenAs->isInterface && type &&
          !implementsInterface(unit, type, seenAs))
        continue;
      Pou *impl = type ? findCallee(type, call) : nullptr;
      if (!impl || impl->isAbstract)
        refuse(call->loc, "internal: no implementation of '" + call->name +
                              "' in '" + ref->name.str() + "'");
      if (t.impl && impl != t.impl)
        t.mixed = true;
      t.impl = impl;
      t.selfTypes.push_back(type);
      t.impls.push_back(impl);
      t.prefixes.push_back(ref->name.str() + ".");
      t.tests.push_back(familyTest(*fam, d));
    }
    if (t.prefixes.empty())
      refuse(call->loc, "no instance is ever assigned to what '" + call->name +
                            "' is called through (an interface or "
                            "reference that is only NULL)");
  } else {
    t.selfType = instanceBlock(call->operands[0]->type);
    for (InstanceChoice &c : instanceChoices(call->operands[0], f, pre)) {
      t.prefixes.push_back(c.path + ".");
      t.tests.push_back(c.test);
      // An in-out instance may be of a block derived from the parameter's:
      // its own type's implementation runs.
      if (auto it = instanceTypes.find(c.path);
          it != instanceTypes.end() && it->second)
        t.selfType = it->second;
    }
    t.impl = findCallee(t.selfType, call);
  }
  if (!t.impl)
    refuse(call->loc, "internal: no implementation of '" + call->name + "'");
  if (activeCalls.count(t.impl))
    refuse(call->loc, "recursive call of method '" + t.impl->methodOf->name +
                          "." + t.impl->name +
                          "': netlift inlines every call and does not model "
                          "recursion");
  // A method call is a call of the instance that passes none of its
  // inputs (they keep what they hold, which the method may read).
  for (const std::string &p : t.prefixes)
    if (!p.empty())
      ++instanceUses[p.substr(0, p.size() - 1)].calls;
  return t;
}

void Lowering::baseBody(Expr *call, Frame &f, Sink &out) {
  Pou *base = call->callee;
  auto [type, prefix] = f.running();
  Frame nf;
  nf.pou = base;
  nf.prefix = prefix;
  nf.self = type;
  nf.selfPrefix = prefix;
  nf.aliases = f.aliases;
  nf.aliasSources = f.aliasSources;
  nf.instanceAliases = f.instanceAliases;
  if (mayJump(base->body, false)) {
    nf.returnFlag = unique(prefix + "_super_return");
    declareTemp(nf.returnFlag, elementaryType("BOOL"), call->loc);
    out.push_back(b.assign(b.ref(nf.returnFlag, call->loc),
                           b.boolLit(false, call->loc), call->loc));
  }
  body(base->body, nf, out, {});
}

NExpr *Lowering::functionCall(Expr *call, Frame &f, Sink &pre) {
  if (!call->method && !call->callee->environment.empty())
    return environmentFunction(call, f, pre);
  if (!call->method)
    return inlineCall(call, call->callee, {}, f, pre);
  if (call->callee->kind == PouKind::FunctionBlock) {
    baseBody(call, f, pre);
    return nullptr;
  }
  MethodTarget target = methodTarget(call, f, pre);
  if (!target.mixed)
    return inlineCall(call, target.impl, target, f, pre);
  // Through an interface, instances of several types: one inlined call per
  // implementation, chosen by the instance, the result through one
  // temporary.
  std::vector<Pou *> impls;
  for (Pou *impl : target.impls)
    if (!llvm::is_contained(impls, impl))
      impls.push_back(impl);
  std::string result;
  if (call->type && call->type->kind != PTypeKind::Void) {
    result = unique(sanitize(call->name) + "_result");
    declareTemp(result, call->type, call->loc);
  }
  std::vector<Sink> bodies;
  std::vector<NExpr *> tests;
  for (Pou *impl : impls) {
    MethodTarget group;
    group.impl = impl;
    NExpr *test = nullptr;
    for (size_t i = 0; i < target.impls.size(); ++i)
      if (target.impls[i] == impl) {
        group.selfTypes.push_back(target.selfTypes[i]);
        group.prefixes.push_back(target.prefixes[i]);
        group.tests.push_back(target.tests[i]);
        test =
            test ? b.binary(net::BinaryOp::Or, test, target.tests[i], call->loc)
                 : target.tests[i];
      }
    Sink body;
    NExpr *value = inlineCall(call, impl, group, f, body);
    if (value && !result.empty())
      body.push_back(b.assign(b.ref(result, call->loc), value, call->loc));
    bodies.push_back(std::move(body));
    tests.push_back(test);
  }
  emitChoice(tests, bodies, pre, call->loc);
  return result.empty() ? nullptr : b.ref(result, call->loc);
}

NExpr *Lowering::inlineCall(Expr *call, Pou *fn, const MethodTarget &target,
                            Frame &f, Sink &pre) {
  if (NExpr * value; callPerBinding(
          call, fn, f, pre,
          [&](Sink &body) { return inlineCall(call, fn, target, f, body); },
          value))
    return value;
  std::string prefix =
      unique(sanitize(call->method ? fn->methodOf->name + "_" + fn->name
                                   : fn->name) +
             "_" + std::to_string(++callSites)) +
      ".";
  Frame nf;
  nf.pou = fn;
  nf.prefix = prefix;
  nf.external = false;
  if (call->method && call->operands.empty()) {
    // On the running instance: the block's in-out parameters stay bound.
    nf.aliases = f.aliases;
    nf.aliasSources = f.aliasSources;
    nf.instanceAliases = f.instanceAliases;
  }
  if (mayJump(fn->body, false)) {
    nf.returnFlag = prefix + "_return";
    declareTemp(nf.returnFlag, elementaryType("BOOL"), call->loc);
    pre.push_back(b.assign(b.ref(nf.returnFlag, call->loc),
                           b.boolLit(false, call->loc), call->loc));
  }
  // Locals and the result live in variables of this call site, reset at
  // the end of the scan (functions have no memory).
  std::vector<VarDecl *> locals = fn->vars;
  if (fn->resultVar)
    locals.push_back(fn->resultVar);
  std::map<std::string, CallArg *> byName;
  for (CallArg &a : call->args)
    byName[StringRef(a.name).upper()] = &a;
  for (VarDecl *v : locals) {
    if (v->section == VarSection::External || v->section == VarSection::Stat)
      continue; // a global's; kept across calls (staticVar)
    auto given = byName.find(StringRef(v->name).upper());
    if (given != byName.end() && given->second->anyClass) {
      anyInput(prefix + sanitize(v->name), v, *given->second, f, pre);
      continue;
    }
    if (v->section == VarSection::InOut && instanceBlock(v->type)) {
      // The caller's instance itself, as for a block's in-out instance.
      nf.instanceAliases[v] = boundInstance(given->second->value, f);
      continue;
    }
    if (v->section == VarSection::InOut) {
      auto chosen = inOutPlaces.find(given->second->value);
      nf.aliases[v] = chosen != inOutPlaces.end()
                          ? chosen->second
                          : lvalue(given->second->value, f, pre);
      nf.aliasSources[v] = {given->second->value, &f};
      continue;
    }
    std::string name = prefix + sanitize(v->name);
    declareTemp(name, v->type, v->loc, nullptr, true);
    NExpr *init;
    if (given != byName.end() && !given->second->isOutput)
      init = expr(given->second->value, f, pre);
    else
      init = initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr,
                          v->type, v->loc); // arrays and structures too
    if (init)
      assign(b.ref(name, v->loc), init, v->type,
             given != byName.end() && !given->second->isOutput
                 ? given->second->value
                 : nullptr,
             pre, call->loc);
  }
  size_t bodyStart = pre.size();
  activeCalls[fn].push_back(prefix);
  if (!call->method) {
    enabledBody(fn, prefix, call, nf, pre);
  } else {
    // The body once per instance it may run on.
    std::vector<Sink> bodies(target.prefixes.size());
    for (size_t i = 0; i < bodies.size(); ++i) {
      Frame on = nf;
      on.self =
          target.selfTypes.empty() ? target.selfType : target.selfTypes[i];
      on.selfPrefix = target.prefixes[i];
      enabledBody(fn, prefix, call, on, bodies[i]);
    }
    emitChoice(target.tests, bodies, pre, call->loc);
  }
  if (activeCalls[fn].pop_back(), activeCalls[fn].empty())
    activeCalls.erase(fn);
  if (fn->isLibrary)
    atCallSite(llvm::ArrayRef<NStmt *>(pre).drop_front(bodyStart), call->loc);
  for (CallArg &a : call->args)
    if (a.isOutput) {
      NExpr *v = b.ref(prefix + sanitize(a.name), a.loc);
      if (a.negated)
        v = b.unary(net::UnaryOp::Not, v, a.loc);
      VarDecl *out = fn->find(a.name);
      pre.push_back(b.assign(
          lvalue(a.value, f, pre),
          coerce(v, out ? out->type : nullptr, a.value->type, a.loc), a.loc));
    }
  if (!fn->resultVar)
    return nullptr; // called as a statement (Sema)
  return b.ref(prefix + sanitize(fn->name), call->loc);
}

void Lowering::anyInput(const std::string &name, VarDecl *v, CallArg &a,
                        Frame &f, Sink &pre) {
  SMLoc at = a.loc;
  declareTemp(name, v->type, v->loc, nullptr, true);
  if (a.anyTemp)
    assign(lvalue(a.anyTemp, f, pre), expr(a.anyValue, f, pre), a.anyTemp->type,
           a.anyValue, pre, at);
  for (auto [field, value] :
       {std::pair{"pValue", a.value}, std::pair{"diSize", a.anySize},
        std::pair{"TypeClass", a.anyClass}})
    pre.push_back(
        b.assign(b.field(b.ref(name, at), field, at), expr(value, f, pre), at));
}

/// A standard function's body (CONCAT_DATE checking its fields) stops with
/// a runtime error at the user's call, not at a line of netlift's library
/// text, and its steps are the call's in a trace.
void Lowering::atCallSite(llvm::ArrayRef<NStmt *> lowered, SMLoc at) {
  auto moveExpr = [&](const NExpr *root) {
    net::walkExpr(root,
                  [&](const NExpr *e) { const_cast<NExpr *>(e)->loc = at; });
  };
  net::forEachStmt(lowered, [&](const NStmt *s) {
    const_cast<NStmt *>(s)->loc = at;
    if (auto *a = llvm::dyn_cast<net::AssignStmt>(s))
      moveExpr(a->target); // a value out of its range is reported there
  });
  net::forEachRead(lowered, moveExpr);
}

/// The body of a called function or FB under IEC's EN/ENO rule: with EN
/// FALSE the body does not run and ENO is FALSE; otherwise ENO starts TRUE
/// and the body may clear it. EN is TRUE when the call does not give it.
void Lowering::enabledBody(Pou *callee, const std::string &prefix, Expr *call,
                           Frame &nf, Sink &out) {
  VarDecl *en = callee->find("EN"), *eno = callee->find("ENO");
  if (en && en->section != VarSection::Input)
    en = nullptr;
  if (eno && eno->section != VarSection::Output)
    eno = nullptr;
  SMLoc at = call->loc;
  if (en) {
    bool given = false;
    for (CallArg &a : call->args)
      given |= !a.isOutput && sameName(a.name, "EN");
    if (!given)
      out.push_back(
          b.assign(b.ref(prefix + en->name, at), b.boolLit(true, at), at));
  }
  if (eno)
    out.push_back(
        b.assign(b.ref(prefix + eno->name, at),
                 en ? b.ref(prefix + en->name, at) : b.boolLit(true, at), at));
  if (!en) {
    body(callee->body, nf, out, {});
    return;
  }
  Sink guarded;
  body(callee->body, nf, guarded, {});
  net::IfArm arm{b.ref(prefix + en->name, at),
                 design.copy(llvm::ArrayRef<NStmt *>(guarded))};
  out.push_back(b.ifStmt({arm}, false, {}, at));
}

std::optional<int64_t> Lowering::upperBound(Expr *e, Frame &f,
                                            std::set<VarDecl *> &visiting) {
  if (auto c = constValue(e, f))
    return c;
  // A variable's own type may bound it more loosely than what it is
  // given: the smaller bound.
  if (Range r = rangeOf(e); r.exact) {
    if (e->kind != ExprKind::Name)
      return r.hi;
    auto given = variableBound(e, f, visiting);
    return given ? std::min(*given, r.hi) : r.hi;
  }
  if (e->kind == ExprKind::Call) {
    // SEL, MUX, MAX, MIN, LIMIT and MOVE yield one of their value inputs.
    StdFnInfo info = e->callee ? StdFnInfo{} : lookupStdFunction(e->name);
    size_t first = info.fn == StdFn::Sel || info.fn == StdFn::Mux ? 1
                   : info.fn == StdFn::Limit                      ? 2
                                                                  : 0;
    if (info.fn != StdFn::Sel && info.fn != StdFn::Mux &&
        info.fn != StdFn::Max && info.fn != StdFn::Min &&
        info.fn != StdFn::Limit && info.fn != StdFn::Move)
      return std::nullopt;
    std::optional<int64_t> best;
    for (size_t i = first; i < e->args.size(); ++i) {
      auto b = upperBound(e->args[i].value, f, visiting);
      if (!b)
        return std::nullopt;
      best = std::max(best.value_or(*b), *b);
    }
    return best;
  }
  // a + b and a * k (k >= 0 constant): bounded by the same of the bounds.
  if (e->kind == ExprKind::Binary && (e->op == Op::Add || e->op == Op::Mul)) {
    Expr *a = e->operands[0], *k = e->operands[1];
    if (e->op == Op::Mul && constValue(a, f))
      std::swap(a, k);
    auto x = upperBound(a, f, visiting);
    auto y = e->op == Op::Add ? upperBound(k, f, visiting) : constValue(k, f);
    int64_t r;
    if (!x || !y || (e->op == Op::Mul && *y < 0) ||
        (e->op == Op::Add ? __builtin_add_overflow(*x, *y, &r)
                          : __builtin_mul_overflow(*x, *y, &r)))
      return std::nullopt;
    return r;
  }
  // An element of an array (`PT := presets[i]`): the largest of its
  // elements' initial values (0, a default one's) and of the values the
  // array is assigned whole. One whose elements are written one by one is
  // in writtenOtherwise: no bound here (its type's, noteClockBound).
  if (e->kind == ExprKind::Index) {
    Expr *root = e;
    while (root->kind == ExprKind::Index)
      root = root->base();
    VarDecl *a = root->kind == ExprKind::Name ? root->var : nullptr;
    if (!a || a->area() == 'I' || a->section == VarSection::Input ||
        a->section == VarSection::InOut || writtenOtherwise.count(a) ||
        !visiting.insert(a).second)
      return std::nullopt;
    auto leave = llvm::make_scope_exit([&] { visiting.erase(a); });
    int64_t best = 0;
    for (Expr *value : assignedValues[a]) {
      auto b = upperBound(value, f, visiting);
      if (!b)
        return std::nullopt;
      best = std::max(best, *b);
    }
    std::function<bool(Initializer *)> elements = [&](Initializer *init) {
      if (!init)
        return true;
      if (init->kind == Initializer::Struct)
        return false;
      if (init->kind == Initializer::Array)
        return llvm::all_of(init->elems,
                            [&](auto &elem) { return elements(elem.second); });
      auto b = upperBound(init->value, f, visiting);
      if (b)
        best = std::max(best, *b);
      return b.has_value();
    };
    if (!elements(a->typeSyntax ? a->typeSyntax->init : nullptr))
      return std::nullopt;
    return best;
  }
  return variableBound(e, f, visiting);
}

std::optional<int64_t> Lowering::variableBound(Expr *e, Frame &f,
                                               std::set<VarDecl *> &visiting) {
  // A function block's input takes what its calls pass (any instance's:
  // an upper bound is all the clock needs); a program's input is free.
  // (A block translated as the top is run as a program: its inputs are
  // free, whatever their declared initial values.)
  VarDecl *v = e->kind == ExprKind::Name ? e->var : nullptr;
  if (!v || v->area() == 'I' || v->section == VarSection::InOut ||
      (v->section == VarSection::Input &&
       (!v->owner || v->owner->kind != PouKind::FunctionBlock ||
        runAsProgram(v->owner))) ||
      writtenOtherwise.count(v) || !visiting.insert(v).second)
    return std::nullopt; // (a cycle through v: no bound from it)
  // The variables being bounded form a path, not a set of visited ones: v
  // may be reached again through another value (`MAX(d, d)`).
  auto leave = llvm::make_scope_exit([&] { visiting.erase(v); });
  // A variable only ever assigned bounded values (and initialised to one).
  Initializer *init = v->typeSyntax ? v->typeSyntax->init : nullptr;
  int64_t best = 0;
  if (init) {
    if (init->kind != Initializer::Value)
      return std::nullopt;
    auto i = upperBound(init->value, f, visiting);
    if (!i)
      return std::nullopt;
    best = *i;
  }
  for (Expr *value : assignedValues[v]) {
    auto b = upperBound(value, f, visiting);
    if (!b)
      return std::nullopt;
    best = std::max(best, *b);
  }
  // A FOR loop's control variable goes from its start past its end by
  // one step.
  for (Stmt *loop : forLoopsOf[v]) {
    auto from = upperBound(loop->from, f, visiting);
    auto to = upperBound(loop->to, f, visiting);
    auto by = loop->by ? constValue(loop->by, f) : std::optional<int64_t>(1);
    if (!from || !to || !by)
      return std::nullopt;
    best = std::max({best, *from, *by > 0 ? *to + *by : *from});
  }
  return best;
}

void Lowering::noteClockBound(const std::string &member, Expr *value, Frame &f,
                              SMLoc at) {
  // The largest value a timer's bounding input (PT) can take wherever it
  // is set is the cap of the timer's clock; PT itself is read at every
  // call, as on a PLC.
  auto it = clockOfBound.find(member);
  if (it == clockOfBound.end())
    return;
  ClockUse &cu = clocks[it->second];
  std::set<VarDecl *> visiting;
  std::optional<int64_t> c = upperBound(value, f, visiting);
  const PType *t = value->type ? baseOf(value->type) : nullptr;
  if (!c && t && t->kind == PTypeKind::Time) {
    // Its type bounds it: the clock counts up to the largest TIME (49
    // days) or LTIME. Exact, but a timer counting that far cannot be
    // explored tick by tick: the free input it comes from asks for a
    // range when explored, and --timers=abstract does not count ticks.
    bool ltime = t->name == "LTIME";
    c = (ltime ? INT64_MAX / 2 : int64_t(UINT32_MAX) * 1000000) / tickNs;
    diag.note(at, cu.member + " of timer '" + cu.path +
                      "' has no bound netlift can find: its clock counts up "
                      "to the largest " +
                      (ltime ? "LTIME" : "TIME") +
                      " (give the input it comes from a range, or explore "
                      "with --timers=abstract)");
    if (!cu.unbounded)
      b.addAttribute(cu.var, net::kUnboundedClockAttribute,
                     design.save(cu.member + " of timer '" + cu.path + "'"),
                     at);
    cu.unbounded = true;
  }
  if (!c)
    refuse(at, cu.member + " of timer '" + cu.path +
                   "' has no bound netlift can find (it bounds the timer's "
                   "clock): set it from constants, or give the input it "
                   "comes from a range");
  cu.cap = std::max(cu.cap, *c);
}

void Lowering::fbCall(Expr *call, Frame &f, Sink &out) {
  Expr callee(ExprKind::Name, call->loc);
  callee.var = call->var;
  callee.name = call->name;
  instanceCall(call, call->var->type->fb, instancePath(&callee, f), f, out);
}

void Lowering::environmentCall(Expr *call, Pou *fb, const std::string &path,
                               Frame &f, Sink &out) {
  if (opts.opaqueRefused)
    refuse(call->loc, "'" + path + "' (" + fb->name + ") " + fb->environment +
                          ", which netlift does not model (--opaque=refuse; "
                          "the default models it as environment)");
  if (notedEnvironment.insert(path).second) {
    std::string outputs;
    for (VarDecl *m : fb->vars)
      if (m->section == VarSection::Output)
        outputs += (outputs.empty() ? "" : ", ") + m->name;
    diag.note(call->loc,
              "'" + path + "' (" + fb->name + ") " + fb->environment +
                  (outputs.empty()
                       ? ": modelled as environment; it has no outputs, so "
                         "a call changes nothing the program sees"
                       : ": modelled as environment, its outputs " + outputs +
                             " are free inputs of the model"));
  }
  // The memory the block writes, first: outputs are copied after the call.
  for (CallArg &a : call->args)
    if (!a.isOutput && llvm::any_of(fb->writesThrough, [&](auto &n) {
          return sameName(n, a.name);
        }))
      writeThrough(a, fb, path, f, out);
  for (CallArg &a : call->args) {
    if (!a.isOutput && llvm::any_of(fb->writesThrough, [&](auto &n) {
          return sameName(n, a.name);
        }))
      continue;
    if (a.isOutput) {
      NExpr *v =
          environmentValueOr(b.ref(path + "." + sanitize(a.name), a.loc), out);
      if (a.negated)
        v = b.unary(net::UnaryOp::Not, v, a.loc);
      out.push_back(b.assign(lvalue(a.value, f, out), v, a.loc));
      continue;
    }
    runArgumentCalls(a.value, f, out);
  }
}

void Lowering::writeThrough(CallArg &a, Pou *fb, const std::string &path,
                            Frame &f, Sink &out) {
  std::string block = "'" + path + "' (" + fb->name + ")";
  Expr *v = a.value;
  auto refuseHere = [&](const std::string &why) {
    refuse(v->loc, block + " " + fb->environment + " and writes the memory " +
                       a.name + " designates: " + why);
  };
  if (v->kind != ExprKind::Call || !sameName(v->name, "ADR") ||
      v->args.size() != 1)
    refuseHere("netlift models it given ADR(variable) in the call");
  // The variable written: whole, whatever part the address is of (the
  // length may run past it into the rest of the variable).
  Expr *root = v->args[0].value;
  while (root->base() &&
         (root->kind == ExprKind::Field || root->kind == ExprKind::Index ||
          root->kind == ExprKind::BitAccess))
    root = root->base();
  if (root->kind != ExprKind::Name || !root->var || !root->var->type)
    refuseHere("netlift models it given ADR(variable) in the call, not the "
               "address of what a reference designates");
  Sink none;
  auto *place = llvm::dyn_cast<net::Ref>(lvalue(root, f, none));
  if (!place || !none.empty())
    refuseHere("'" + root->name +
               "' is the caller's; netlift models a variable of this POU");
  std::string stem = path + "_" + a.name;
  std::replace(stem.begin(), stem.end(), '.', '_');
  ChosenScalars chosen = chooseScalars(
      place->name.str(), sanitize(stem), root->var->type,
      "what " + a.name + " of " + block + " designates", root->name, v->loc);
  for (NStmt *s : samplesOf(chosen))
    out.push_back(s);
  std::string ports =
      chosen.scalars.empty()
          ? std::string("none")
          : "'" + chosen.scalars.front().port + "'" +
                (chosen.scalars.size() > 1
                     ? " to '" + chosen.scalars.back().port + "'"
                     : "");
  diag.note(v->loc, block + " " + fb->environment + ": the runtime writes '" +
                        root->name + "' through " + a.name +
                        ", modelled as any value at every call (the whole "
                        "variable, whatever length is given); free inputs " +
                        ports);
}

void Lowering::runArgumentCalls(Expr *value, Frame &f, Sink &out) {
  // Not stored; what computing it calls still runs.
  bool calls = false;
  forEachNestedExpr(value,
                    [&](Expr *e) { calls |= e->kind == ExprKind::Call; });
  if (!calls)
    return;
  Sink pre;
  expr(value, f, pre);
  out.insert(out.end(), pre.begin(), pre.end());
}

bool Lowering::callPerBinding(Expr *call, Pou *callee, Frame &f, Sink &out,
                              llvm::function_ref<NExpr *(Sink &)> lowerOnce,
                              NExpr *&value) {
  value = nullptr;
  for (CallArg &a : call->args) {
    VarDecl *p = a.isOutput ? nullptr : callee->find(a.name);
    if (!p || p->section != VarSection::InOut || inOutPlaces.count(a.value) ||
        inOutInstances.count(a.value))
      continue;
    // Each place the argument may be, how to bind it, and its test.
    std::vector<NExpr *> tests;
    std::vector<std::function<void(Sink &)>> binds;
    if (instanceBlock(p->type) && !throughReference(a.value)) {
      // An instance passed in-out that is an element chosen at run time.
      if (!chosenAtRunTime(a.value, f))
        continue;
      for (InstanceChoice &c : instanceChoices(a.value, f, out)) {
        tests.push_back(c.test);
        binds.push_back([this, &a, path = c.path](Sink &) {
          inOutInstances[a.value] = path;
        });
      }
    } else if (throughReference(a.value)) {
      DerefTargets t = derefTargets(a.value, f, out);
      for (const RefFamily *fam : t.live) {
        tests.push_back(familyTest(*fam, t));
        binds.push_back([this, &a, &f, t, fam](Sink &body) {
          inOutPlaces[a.value] = familyPlace(*fam, t, a.value, f, body);
        });
      }
      if (binds.empty()) // only NULL: the checks made have reported it
        binds.push_back([](Sink &) {});
    } else {
      continue;
    }
    std::string result;
    if (callee->resultVar && binds.size() > 1) {
      result = unique(sanitize(callee->name) + "_result");
      declareTemp(result, callee->resultVar->type, call->loc);
    }
    std::vector<Sink> bodies(binds.size());
    for (size_t i = 0; i < binds.size(); ++i) {
      binds[i](bodies[i]);
      NExpr *v = lowerOnce(bodies[i]);
      inOutPlaces.erase(a.value);
      inOutInstances.erase(a.value);
      if (binds.size() == 1)
        value = v;
      else if (!result.empty())
        bodies[i].push_back(b.assign(b.ref(result, call->loc), v, call->loc));
    }
    emitChoice(tests, bodies, out, call->loc);
    if (!result.empty())
      value = b.ref(result, call->loc);
    return true;
  }
  return false;
}

void Lowering::instanceCall(Expr *call, Pou *fb, const std::string &path,
                            Frame &f, Sink &out) {
  if (!fb->environment.empty()) {
    environmentCall(call, fb, path, f, out);
    return;
  }
  // An instance whose body is being lowered, called again: a call through
  // a reference closed a cycle of calls.
  if (llvm::is_contained(instancesLowering, path))
    refuse(call->loc, "recursive call of function block instance '" + path +
                          "' (of " + fb->name +
                          ") through a reference: netlift inlines every call "
                          "and does not model recursion");
  if (NExpr * none; callPerBinding(
          call, fb, f, out,
          [&](Sink &body) {
            instanceCall(call, fb, path, f, body);
            return nullptr;
          },
          none))
    return;
  instancesLowering.push_back(path);
  size_t knownBefore = knownConstants.size();
  InstanceUse &use = instanceUses[path];
  ++use.calls;
  Frame nf;
  nf.pou = fb;
  nf.prefix = path + ".";
  if (mayJump(fb->body, false)) {
    nf.returnFlag = path + "._return";
    if (mod->lookup(nf.returnFlag).kind == net::SymKind::None)
      declareTemp(nf.returnFlag, elementaryType("BOOL"), call->loc);
    out.push_back(b.assign(b.ref(nf.returnFlag, call->loc),
                           b.boolLit(false, call->loc), call->loc));
  }
  for (CallArg &a : call->args) {
    if (a.isOutput)
      continue;
    VarDecl *p = fb->find(a.name);
    if (p->section == VarSection::InOut && instanceBlock(p->type)) {
      // The caller's instance itself: the block calls it and reads its
      // outputs under the caller's names.
      nf.instanceAliases[p] = boundInstance(a.value, f);
      continue;
    }
    if (p->section == VarSection::InOut) {
      auto chosen = inOutPlaces.find(a.value);
      nf.aliases[p] = chosen != inOutPlaces.end() ? chosen->second
                                                  : lvalue(a.value, f, out);
      nf.aliasSources[p] = {a.value, &f};
      continue;
    }
    ++use.given[sanitize(p->name)];
    std::string member = path + "." + sanitize(p->name);
    NExpr *v = expr(a.value, f, out);
    if (p->edge) {
      // x : BOOL R_EDGE sees TRUE only at a rising edge of the argument.
      NExpr *prev = b.ref(member + ".prev", a.loc);
      NExpr *edge =
          p->edge == 'R'
              ? b.binary(net::BinaryOp::And, v,
                         b.unary(net::UnaryOp::Not, prev, a.loc), a.loc)
              : b.binary(net::BinaryOp::And,
                         b.unary(net::UnaryOp::Not, v, a.loc),
                         b.ref(member + ".prev", a.loc), a.loc);
      out.push_back(b.assign(b.ref(member, a.loc), edge, a.loc));
      out.push_back(b.assign(b.ref(member + ".prev", a.loc), v, a.loc));
      continue;
    }
    assign(b.ref(member, a.loc), v, p->type, a.value, out, a.loc);
    noteClockBound(member, a.value, f, a.loc);
    // A reference input given a constant (REF(x)), never written in the
    // block nor through a reference, designates x throughout this call:
    // no selection.
    if (auto *lit = llvm::dyn_cast<net::IntLit>(v);
        lit && p->type->isReference() && !written.count(p) &&
        !addressTaken.count(member))
      knownConstants.push_back({member, lit->value});
  }
  for (VarDecl *v : fb->vars)
    if (v->edge) {
      bool given = false;
      for (CallArg &a : call->args)
        given |= !a.isOutput && sameName(a.name, v->name);
      // No new value: no edge.
      if (!given)
        out.push_back(b.assign(b.ref(path + "." + sanitize(v->name), v->loc),
                               b.boolLit(false, v->loc), v->loc));
    }
  // VAR_TEMP starts from its declared initial value at every call.
  for (VarDecl *v : fb->vars)
    if (v->section == VarSection::Temp && !instanceBlock(v->type))
      if (NExpr *init =
              initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr,
                           v->type, v->loc))
        assignParts(b.ref(path + "." + sanitize(v->name), v->loc), init,
                    v->type, 0, out, v->loc);
  size_t bodyStart = out.size();
  enabledBody(fb, path + ".", call, nf, out);
  // netlift's own block (a TON) runs at the user's call: its errors and
  // trace lines are the call's.
  if (fb->isLibrary)
    atCallSite(llvm::ArrayRef<NStmt *>(out).drop_front(bodyStart), call->loc);
  knownConstants.resize(knownBefore);
  for (CallArg &a : call->args)
    if (a.isOutput) {
      std::string member = path + "." + sanitize(a.name);
      externallyRead.insert(member);
      NExpr *v = b.ref(member, a.loc);
      if (a.negated)
        v = b.unary(net::UnaryOp::Not, v, a.loc);
      VarDecl *param = fb->find(a.name);
      v = coerce(v, param ? param->type : nullptr, a.value->type, a.loc);
      if (throughReference(a.value)) {
        writeThroughReference(a.value, v, nullptr, f, out, a.loc);
        continue;
      }
      out.push_back(b.assign(lvalue(a.value, f, out), v, a.loc));
    }
  instancesLowering.pop_back();
}
