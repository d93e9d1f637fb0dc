//===- LowerToNet.cpp - a checked PLC program as a NetIR controller -------===//
//
// How the scan body is built:
//  - Every variable of the program, and every member of every FB instance
//    (recursively, named `inst.member`), is a NetIR variable or port.
//  - An FB call assigns the instance's inputs, runs the FB body inlined with
//    the instance's names, then copies the outputs bound with `=>`.
//  - A function call is inlined before the statement that uses it, into
//    variables private to that call site (`F_1.x`); calls are hoisted in
//    evaluation order, and an ELSIF whose condition calls a function
//    becomes a nested IF so the call runs only when the IEC order says so.
//  - RETURN, EXIT and CONTINUE set flag variables; the statements after one
//    run under `if not flag`.
//  - Integer arithmetic is exact in NetIR; where an intermediate IEC result
//    could leave its type (INT + INT), it is wrapped explicitly to that
//    type's width, and stores wrap through the `wrap` integer types. An
//    interval analysis skips the wrap where overflow is impossible.
//  - Variables whose value cannot matter in the next scan are reset at the
//    end of the scan action, so states do not differ in dead values: the
//    locals of inlined functions, VAR_TEMP, control flags, FB members never
//    read, and FB inputs every call passes and nobody reads from outside.
//    The FB members' resets are marked (`scan_reset`): they are real PLC
//    memory, and a command that observes one keeps its value.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

#include "ir/net/Walk.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Time
//===----------------------------------------------------------------------===//

void Lowering::collectTimesExpr(Expr *e, std::set<Pou *> &seen,
                                std::vector<int64_t> &ns) {
  if (!e)
    return;
  if (e->kind == ExprKind::TimeLit && e->intValue != 0)
    ns.push_back(std::abs(e->intValue));
  for (Expr *o : e->operands)
    collectTimesExpr(o, seen, ns);
  // (An environment block's inputs are not stored: their durations do not
  // count.)
  Pou *called = e->kind == ExprKind::Call ? calledPou(e) : nullptr;
  for (CallArg &a : e->args)
    if (!called || called->environment.empty() || a.isOutput)
      collectTimesExpr(a.value, seen, ns);
  if (e->callee)
    collectTimes(e->callee, seen, ns);
  if (Pou *callee = e->kind == ExprKind::Call ? calledPou(e) : nullptr;
      callee && !e->callee)
    collectTimes(callee, seen, ns);
}

void Lowering::collectTimesStmts(StmtList &l, std::set<Pou *> &seen,
                                 std::vector<int64_t> &ns) {
  for (Stmt *s : l) {
    for (Expr *e : {s->target, s->value, s->from, s->to, s->by})
      collectTimesExpr(e, seen, ns);
    for (auto &[c, body] : s->arms) {
      collectTimesExpr(c, seen, ns);
      collectTimesStmts(body, seen, ns);
    }
    for (auto &arm : s->caseArms)
      collectTimesStmts(arm.body, seen, ns);
    collectTimesStmts(s->elseBody, seen, ns);
    collectTimesStmts(s->body, seen, ns);
  }
}

static void initTimes(Initializer *init, std::vector<int64_t> &ns) {
  forEachInitialValue(init, [&](Expr *v) {
    if (v->kind == ExprKind::TimeLit && v->intValue)
      ns.push_back(std::abs(v->intValue));
  });
}

void Lowering::collectTimes(Pou *p, std::set<Pou *> &seen,
                            std::vector<int64_t> &ns) {
  if (!seen.insert(p).second || !p->environment.empty())
    return; // an environment block's inputs are not stored
  for (VarDecl *v : p->vars) {
    if (v->typeSyntax)
      initTimes(v->typeSyntax->init, ns);
    if (Pou *fb = v->type ? instanceBlock(v->type) : nullptr)
      collectTimes(fb, seen, ns);
  }
  collectTimesStmts(p->body, seen, ns);
}

std::string plc::formatDuration(int64_t ns) {
  static const struct {
    const char *unit;
    int64_t ns;
  } units[] = {{"h", 3600000000000}, {"m", 60000000000}, {"s", 1000000000},
               {"ms", 1000000},      {"us", 1000},       {"ns", 1}};
  for (auto &u : units)
    if (ns % u.ns == 0)
      return std::to_string(ns / u.ns) + u.unit;
  return std::to_string(ns) + "ns";
}

int64_t Lowering::ticks(int64_t ns, SMLoc at) {
  if (ns % tickNs != 0)
    refuse(at, "time value " + formatDuration(ns) +
                   " is not a whole number of ticks (one tick is " +
                   formatDuration(tickNs) + "; choose --timescale)");
  return ns / tickNs;
}

//===----------------------------------------------------------------------===//
// Modules
//===----------------------------------------------------------------------===//

/// Every name `body` reads: what it evaluates anywhere (conditions, loop
/// bounds and conditions, values, indices), and the variables of targets
/// written in part (`x.f := v`, `a[i] := v` keep the rest of x and a).
static void readNames(net::Block body, llvm::StringSet<> &out) {
  auto names = [&](const NExpr *e) {
    net::walkExpr(e, [&](const NExpr *x) {
      if (auto *r = llvm::dyn_cast<net::Ref>(x))
        out.insert(r->name);
    });
  };
  net::forEachRead(body, names);
  net::forEachAssign(body, [&](const net::AssignStmt *a) {
    if (!llvm::isa<net::Ref>(a->target))
      names(a->target);
  });
}

std::vector<VarDecl *>
Lowering::inDeclarationOrder(const std::set<VarDecl *> &globals) {
  // Not by address (a set of pointers): the output must not depend on
  // where the allocator put each declaration.
  std::map<const VarDecl *, size_t> position;
  for (VarDecl *g : unit.globals)
    position.emplace(g, position.size());
  for (Configuration *c : unit.configs)
    for (VarDecl *g : c->globals)
      position.emplace(g, position.size());
  auto key = [&](const VarDecl *g) {
    auto it = position.find(g);
    return std::make_pair(it == position.end() ? SIZE_MAX : it->second,
                          g->name);
  };
  std::vector<VarDecl *> ordered(globals.begin(), globals.end());
  std::stable_sort(ordered.begin(), ordered.end(),
                   [&](VarDecl *a, VarDecl *b) { return key(a) < key(b); });
  return ordered;
}

std::vector<VarDecl *> Lowering::globalsUsedBy(Pou *program) {
  std::set<VarDecl *> globalsUsed;
  std::function<void(Expr *)> scanExpr = [&](Expr *e) {
    if (!e)
      return;
    if (e->var && !e->var->owner && e->var->section == VarSection::Global)
      globalsUsed.insert(e->var);
    for (Expr *o : e->operands)
      scanExpr(o);
    Pou *called = e->kind == ExprKind::Call ? calledPou(e) : nullptr;
    for (CallArg &a : e->args)
      if (!called || called->environment.empty() || a.isOutput)
        scanExpr(a.value); // (an environment block's inputs are not stored)
  };
  std::set<Pou *> visited;
  std::function<void(Pou *)> scanPou;
  std::function<void(StmtList &)> scanStmts = [&](StmtList &l) {
    for (Stmt *s : l) {
      for (Expr *e : {s->target, s->value, s->from, s->to, s->by})
        scanExpr(e);
      if (s->kind == StmtKind::Call)
        if (Pou *callee = calledPou(s->value))
          scanPou(callee);
      if (s->value && s->value->callee)
        scanPou(s->value->callee);
      for (auto &[c, body] : s->arms) {
        scanExpr(c);
        scanStmts(body);
      }
      for (auto &arm : s->caseArms)
        scanStmts(arm.body);
      scanStmts(s->elseBody);
      scanStmts(s->body);
    }
  };
  scanPou = [&](Pou *p) {
    // An environment block's inputs (and their defaults) are not stored.
    if (!visited.insert(p).second || !p->environment.empty())
      return;
    scanStmts(p->body);
    // Initial values may name globals (`d2r : LREAL := PI / 180.0`), and
    // the blocks a POU holds instances of are run by it.
    for (VarDecl *v : p->vars) {
      if (v->typeSyntax)
        forEachInitialValue(v->typeSyntax->init, scanExpr);
      if (Pou *fb = v->type ? instanceBlock(v->type) : nullptr)
        scanPou(fb);
    }
    forEachMethod(p, [&](Pou *m) { scanPou(m); });
  };
  scanPou(program);
  if (auto it = argumentsOf.find(program); it != argumentsOf.end())
    for (CallArg &a : it->second->args)
      globalsUsed.insert(a.value->var);
  return inDeclarationOrder(globalsUsed);
}

void Lowering::startModule(const std::string &name, SMLoc loc) {
  mod = b.createModule(name, false, loc);
  if (!mod)
    refuse(loc, "a module named '" + name + "' exists already");
  resets.clear();
  resetNames.clear();
  instanceMembers.clear();
  externallyRead.clear();
  instanceUses.clear();
  clocks.clear();
  clockOfBound.clear();
  instanceTypes.clear();
  varTypes.clear();
  pendingPragmas.clear();
}

void Lowering::declareProgram(ProgramRun &run) {
  InProgram in(*this, run);
  Pou *program = run.pou;
  run.membersBegin = instanceMembers.size();
  // A module of its own takes the program's pragmas; in a module of
  // several programs they go to the program's scope.
  keepPragmas(run.prefix.empty() ? ""
                                 : run.prefix.substr(0, run.prefix.size() - 1),
              program->attrs);
  // Program arguments: inputs read their global at the start of the scan,
  // outputs write theirs at the end (IEC 61131-3 2.7.1).
  boundInputs.clear();
  if (auto it = argumentsOf.find(program); it != argumentsOf.end())
    for (CallArg &a : it->second->args)
      if (!a.isOutput)
        boundInputs.insert(program->find(a.name));
  // Globals this program uses are variables of the module (declared by
  // the first program of the module that uses them).
  for (VarDecl *g : globalsUsedBy(program)) {
    if (mod->lookup(sanitize(g->name)).kind == net::SymKind::None)
      declareProgramVar(g);
  }
  for (VarDecl *v : program->vars)
    declareProgramVar(v);
  run.membersEnd = instanceMembers.size();
}

/// Clock caps, and the TIME members they bound.
void Lowering::capClocks() {
  auto varIndex = [&](StringRef name) -> int32_t {
    net::Symbol sym = mod->lookup(name);
    return sym.kind == net::SymKind::Var ? int32_t(sym.index) : -1;
  };
  for (auto &[name, cu] : clocks) {
    int32_t x = varIndex(name);
    // The instance's own initial PT counts too (never called: cap 0).
    int32_t bound = varIndex(cu.path + "." + sanitize(cu.member));
    if (bound >= 0)
      if (auto *lit =
              llvm::dyn_cast_or_null<net::IntLit>(mod->vars[bound].init))
        cu.cap = std::max(cu.cap, lit->value);
    int64_t cap = std::max<int64_t>(cu.cap, 1);
    mod->vars[x].type = design.types.getClock(cap);
    // The clock parks at PT when idle, so it starts there too.
    mod->vars[x].init = b.intLit(cap, mod->vars[x].loc);
    for (auto &tm : cu.timeMembers)
      if (int32_t i = varIndex(tm); i >= 0)
        mod->vars[i].type = design.types.getRange(0, cap);
  }
}

/// A pragma goes to the port, variable or instance scope its declaration
/// became. A declaration that became none (a constant, a block without
/// state) gives its pragma to the module, with the declaration's name in
/// front, so that no pragma is lost.
void Lowering::attachPragmas() {
  for (auto &[target, a] : pendingPragmas) {
    if (mod->isAttributeTarget(target))
      b.addAttribute(target, "pragma", a->text, a->loc);
    else
      b.addAttribute("", "pragma", target + ": " + a->text, a->loc);
  }
  pendingPragmas.clear();
}

/// The FB_init calls of instance `v` at `path` (its members' first, then a
/// base's before each derived block's own), or of every element of an
/// array of instances (with the declaration's arguments for each, or
/// without), appended to `calls`.
void Lowering::initCallsOf(VarDecl *v, const PType *type,
                           const std::string &path, Frame &in, Sink &calls,
                           Expr *given) {
  if (type && type->kind == PTypeKind::Array) {
    size_t k = 0;
    bool own = type == v->type && !v->elementInitCalls.empty();
    forEachIndex(type, [&](llvm::ArrayRef<int64_t> index) {
      initCallsOf(v, type->elem, elementPath(path, index), in, calls,
                  own ? v->elementInitCalls[k++] : nullptr);
    });
    return;
  }
  Pou *fb = type && type->kind == PTypeKind::FunctionBlock ? type->fb : nullptr;
  if (!fb || !fb->environment.empty())
    return;
  Frame inner;
  inner.pou = fb;
  inner.prefix = path + ".";
  for (VarDecl *m : fb->vars)
    if (m->section != VarSection::InOut && m->section != VarSection::External)
      initCallsOf(m, m->type, inner.prefix + sanitize(m->name), inner, calls);
  std::vector<Pou *> chain;
  for (Pou *b = fb; b; b = b->base)
    for (Pou *m : b->methods)
      if (!m->property && sameName(m->name, "FB_init"))
        chain.insert(chain.begin(), m);
  if (chain.empty())
    return;
  // A declared instance has its call (with the declaration's arguments);
  // an element of an array its own, or one without arguments.
  if (type == v->type)
    given = v->initCall;
  for (Pou *impl : chain) {
    Expr *call = unit.make<Expr>(ExprKind::Call, v->loc);
    if (given) {
      *call = *given;
      call->args.clear();
      for (CallArg &a : given->args)
        if (impl->find(a.name))
          call->args.push_back(a);
    } else {
      call->name = impl->name;
      call->method = true;
    }
    call->callee = impl;
    MethodTarget target;
    target.impl = impl;
    target.selfType = fb;
    target.prefixes.push_back(path + ".");
    target.tests.push_back(nullptr);
    bool wasInit = std::exchange(loweringInitCalls, true);
    inlineCall(call, impl, target, in, calls);
    loweringInitCalls = wasInit;
  }
}

/// FB_init of every instance the program holds, once, before the first
/// scan: at the start of the first scan, under a flag that is then set for
/// good. The global instances' run before any program's
/// (globalInitCalls).
void Lowering::runInitCalls(ProgramRun &run, Frame &top, Sink &action) {
  Sink calls;
  for (VarDecl *v : run.pou->vars)
    if (v->section != VarSection::InOut && v->section != VarSection::External)
      initCallsOf(v, v->type, run.prefix + sanitize(v->name), top, calls);
  if (calls.empty())
    return;
  SMLoc at = run.pou->loc;
  std::string done = unique(run.prefix + "_initialised");
  b.addVar(done, design.types.getBool(), b.boolLit(false, at), at);
  b.addAttribute(done, net::kInternalAttribute, "first-scan initialisation",
                 at);
  calls.push_back(b.assign(b.ref(done, at), b.boolLit(true, at), at));
  net::IfArm arm{b.unary(net::UnaryOp::Not, b.ref(done, at), at),
                 design.copy(llvm::ArrayRef<NStmt *>(calls))};
  action.push_back(b.ifStmt({arm}, false, {}, at));
}

Sink Lowering::globalInitCalls(std::vector<ProgramRun> &runs) {
  std::set<VarDecl *> globals;
  for (ProgramRun &run : runs)
    for (VarDecl *g : globalsUsedBy(run.pou))
      globals.insert(g);
  std::vector<VarDecl *> ordered = inDeclarationOrder(globals);
  Frame none;
  none.pou = runs.front().pou;
  none.prefix = runs.front().prefix;
  Sink calls;
  for (VarDecl *g : ordered)
    initCallsOf(g, g->type, sanitize(g->name), none, calls);
  if (calls.empty())
    return calls;
  SMLoc at = runs.front().pou->loc;
  std::string done = unique("_globals_initialised");
  b.addVar(done, design.types.getBool(), b.boolLit(false, at), at);
  b.addAttribute(done, net::kInternalAttribute, "first-scan initialisation",
                 at);
  calls.push_back(b.assign(b.ref(done, at), b.boolLit(true, at), at));
  net::IfArm arm{b.unary(net::UnaryOp::Not, b.ref(done, at), at),
                 design.copy(llvm::ArrayRef<NStmt *>(calls))};
  Sink out{b.ifStmt({arm}, false, {}, at)};
  return out;
}

void Lowering::lowerProgramBody(ProgramRun &run) {
  InProgram in(*this, run);
  Pou *program = run.pou;
  std::vector<std::pair<VarDecl *, VarDecl *>> argIn, argOut; // (var, global)
  if (auto it = argumentsOf.find(program); it != argumentsOf.end())
    for (CallArg &a : it->second->args)
      (a.isOutput ? argOut : argIn)
          .push_back({program->find(a.name), a.value->var});

  Frame top;
  top.pou = program;
  top.prefix = run.prefix;
  top.external = true;
  Sink &action = run.action;
  if (mayJump(program->body, false)) {
    top.returnFlag = unique(run.prefix + "_return");
    declareTemp(top.returnFlag, elementaryType("BOOL"), program->loc);
  }
  for (auto &[v, g] : argIn)
    action.push_back(b.assign(b.ref(run.prefix + sanitize(v->name), v->loc),
                              b.ref(sanitize(g->name), v->loc), v->loc));
  // What the environment chooses whole, scalar by scalar (also what it
  // shares with the program outside the design).
  std::vector<VarDecl *> chosenByEnvironment(program->vars.begin(),
                                             program->vars.end());
  for (VarDecl *g : globalsUsedBy(program))
    if (g->sharedOutside || !g->runtimeRecord.empty())
      chosenByEnvironment.push_back(g);
  for (VarDecl *v : chosenByEnvironment)
    if (auto it = environmentSamples.find(v); it != environmentSamples.end())
      action.insert(action.end(), it->second.begin(), it->second.end());
  std::vector<std::string> prefixes{""};
  if (!run.prefix.empty())
    prefixes.push_back(run.prefix);
  for (const std::string &prefix : prefixes)
    if (auto it = scanSamples.find(prefix); it != scanSamples.end())
      for (const ChosenScalars &chosen : it->second)
        for (NStmt *s : samplesOf(chosen))
          action.push_back(s);
  // An input the program writes is read through a copy the scan samples
  // first; what the program writes stands until the next scan samples it.
  std::vector<VarDecl *> inputs(program->vars.begin(), program->vars.end());
  for (VarDecl *g : globalsUsedBy(program))
    inputs.push_back(g);
  std::set<VarDecl *> bound;
  for (auto &[v, g] : argIn)
    bound.insert(v);
  for (VarDecl *v : inputs) {
    if (!v->writtenInput || v->section == VarSection::External ||
        bound.count(v) || isEnvironmentValue(v) ||
        !(v->area() == 'I' || v->section == VarSection::Input))
      continue;
    std::string port = (v->owner ? run.prefix : "") + sanitize(v->name);
    std::string image = *inputImageName(run.prefix, v);
    if (mod->lookup(image).kind != net::SymKind::None)
      refuse(v->loc, "the copy of input '" + v->name + "' would be named '" +
                         image + "', which the program already uses");
    declareTemp(image, v->type, v->loc);
    top.aliases[v] = b.ref(image, v->loc);
    action.push_back(
        b.assign(b.ref(image, v->loc), b.ref(port, v->loc), v->loc));
  }
  runInitCalls(run, top, action);
  body(program->body, top, action, {});
  for (VarDecl *v : program->vars)
    if (auto it = environmentResets.find(v); it != environmentResets.end())
      action.insert(action.end(), it->second.begin(), it->second.end());
  for (auto &[v, g] : argOut)
    action.push_back(b.assign(b.ref(sanitize(g->name), v->loc),
                              b.ref(run.prefix + sanitize(v->name), v->loc),
                              v->loc));
}

/// FB members nobody reads after the scan go back to their initial values
/// at its end, so that states do not differ by values no one will see.
void Lowering::deadValueResets(ProgramRun &run) {
  auto varIndex = [&](StringRef name) -> int32_t {
    net::Symbol sym = mod->lookup(name);
    return sym.kind == net::SymKind::Var ? int32_t(sym.index) : -1;
  };
  llvm::StringSet<> read;
  readNames(run.action, read);
  for (size_t k = run.membersBegin; k < run.membersEnd; ++k) {
    const std::string &m = instanceMembers[k];
    bool dead = !read.count(m) && !externallyRead.count(m);
    if (!dead) {
      // An input every call passes and nobody reads from outside.
      size_t dot = m.rfind('.');
      std::string path = m.substr(0, dot), member = m.substr(dot + 1);
      auto use = instanceUses.find(path);
      Pou *fb = instanceTypes[path];
      VarDecl *decl = fb ? fb->find(member) : nullptr;
      if (decl && decl->section == VarSection::Input &&
          use != instanceUses.end() && use->second.calls > 0 &&
          use->second.given[member] == use->second.calls &&
          !externallyRead.count(m))
        dead = true;
      // A timer's bounding input keeps its value: the clock parks at it.
      if (clockOfBound.count(m))
        dead = false;
    }
    if (!dead || resetNames.count(m))
      continue;
    int32_t i = varIndex(m);
    if (i >= 0 && mod->vars[i].init) {
      run.resets.push_back({m, mod->vars[i].init});
      resetNames.insert(m);
      // Marked, so that a command observing the member keeps its value
      // (net::kScanResetAttribute).
      b.addAttribute(m, net::kScanResetAttribute,
                     "no statement reads it before a scan writes it",
                     mod->vars[i].loc);
    }
  }
}

void Lowering::lowerPrograms(const std::string &name, SMLoc loc,
                             std::vector<ProgramRun> &runs) {
  startModule(name, loc);
  adoptReferencePlan(planReferences(runs)); // (sets runPous)
  for (ProgramRun &run : runs)
    declareProgram(run);
  for (ProgramRun &run : runs)
    lowerProgramBody(run);
  // Run by whichever task's scan comes first.
  Sink globalInits = globalInitCalls(runs);
  capClocks();
  attachPragmas();
  for (ProgramRun &run : runs)
    deadValueResets(run);
  // One urgent scan per task, every `period` ticks: its programs in order,
  // each followed by its end-of-scan resets.
  for (size_t i = 0; i < runs.size(); ++i) {
    bool first = true;
    for (size_t j = 0; j < i; ++j)
      first &= runs[j].scan != runs[i].scan;
    if (!first)
      continue;
    Sink action = globalInits;
    for (ProgramRun &run : runs) {
      if (run.scan != runs[i].scan)
        continue;
      action.insert(action.end(), run.action.begin(), run.action.end());
      appendResets(run.resets, action);
    }
    SMLoc at = runs[i].pou->loc;
    uint32_t period = uint32_t(runs[i].period);
    uint32_t cycle = b.addPlace(runs[i].cycle, 1, 1, at);
    b.addAttribute(runs[i].cycle, net::kInternalAttribute,
                   "the task's scan cycle", at);
    net::PreArc pre{cycle, 1, net::Interval{period, period}};
    net::PostArc post{cycle, 1};
    uint32_t scan = b.addTransition(runs[i].scan, {pre}, {post}, at);
    b.setUrgent(scan);
    b.setAction(scan, action);
  }
}

void Lowering::chooseTick(std::vector<int64_t> ns) {
  ns.insert(ns.end(), opts.extraTimesNs.begin(), opts.extraTimesNs.end());
  if (opts.scanPeriodNs)
    ns.push_back(*opts.scanPeriodNs);
  // A NetIR or hybrid file read with the program (a plant model) fixes
  // the tick already: the program's times are counted in it.
  std::optional<int64_t> designNs;
  if (design.timescale)
    designNs = int64_t(design.timescale->nanoseconds());
  if (opts.timescaleNs && designNs && *opts.timescaleNs != *designNs)
    refuse(SMLoc(), "--timescale " + formatDuration(*opts.timescaleNs) +
                        " differs from the timescale " +
                        design.timescale->str() +
                        " of a model read with the program");
  if (opts.timescaleNs) {
    tickNs = *opts.timescaleNs;
  } else if (designNs) {
    tickNs = *designNs;
  } else {
    int64_t g = 0;
    for (int64_t v : ns)
      g = std::gcd(g, v);
    tickNs = g ? g : 1000000; // no time at all: 1 ms, unused
  }
  if (!design.timescale && (!ns.empty() || opts.timescaleNs)) {
    static const struct {
      const char *unit;
      int64_t ns;
    } units[] = {{"h", 3600000000000}, {"min", 60000000000}, {"s", 1000000000},
                 {"ms", 1000000},      {"us", 1000},         {"ns", 1}};
    for (auto &u : units)
      if (tickNs % u.ns == 0) {
        net::Timescale ts;
        ts.amount = uint64_t(tickNs / u.ns);
        ts.unit = u.unit;
        design.timescale = ts;
        break;
      }
  }
}

/// A --ranges entry no input took is a misspelt or stale name; ignored, it
/// would leave the input it meant unbounded (refused) or let the reader
/// believe a range holds that does not.
void Lowering::checkRangesUsed() {
  for (const auto &[key, entry] : opts.ranges)
    if (!rangesUsed.count(key))
      diag.error(entry.loc, "--ranges: '" + entry.name +
                                "' names no integer input of the translated "
                                "program" +
                                didYouMean(entry.name, rangeCandidates));
}

bool Lowering::run() {
  // Which programs.
  std::vector<std::pair<Pou *, Task *>> tops;
  auto taskOf = [&](Configuration *c, StringRef name) -> Task * {
    for (Task &t : c->tasks)
      if (sameName(t.name, name))
        return &t;
    return nullptr;
  };
  if (!opts.top.empty()) {
    for (Configuration *c : unit.configs)
      for (ProgramInstance &pi : c->programs)
        if (sameName(pi.name, opts.top) || sameName(pi.typeName, opts.top))
          if (Pou *p = unit.findPou(pi.typeName)) {
            tops.push_back({p, taskOf(c, pi.task)});
            instanceOf.try_emplace(p, &pi, c);
          }
    if (tops.empty()) {
      Pou *p = unit.findPou(opts.top);
      if (!p || p->kind == PouKind::Function || p->isLibrary) {
        diag.error(SMLoc(), "no program, program instance or function block "
                            "named '" +
                                opts.top + "' (--top)");
        return false;
      }
      tops.push_back({p, nullptr});
    }
  } else {
    for (Configuration *c : unit.configs)
      for (ProgramInstance &pi : c->programs)
        if (Pou *p = unit.findPou(pi.typeName)) {
          bool dup = false;
          for (auto &[q, t] : tops)
            dup |= q == p;
          if (!dup) {
            tops.push_back({p, taskOf(c, pi.task)});
            instanceOf.try_emplace(p, &pi, c);
          }
        }
    if (tops.empty())
      for (Pou *p : unit.pous)
        if (p->kind == PouKind::Program)
          tops.push_back({p, nullptr});
    if (tops.empty()) {
      SMLoc at; // not in netlift's own library
      for (Pou *p : unit.pous)
        if (!p->isLibrary) {
          at = p->loc;
          break;
        }
      if (at.isValid()) {
        diag.error(at, "no PROGRAM or function block to translate: the "
                       "input declares functions only (each was checked; "
                       "a function is translated where a program calls "
                       "it)");
        return false;
      }
      // The user's first type or global, not one of netlift's library.
      at = opts.unitStart;
      for (VarDecl *g : llvm::reverse(unit.globals))
        if (!g->isLibrary)
          at = g->loc;
      for (TypeDecl *t : llvm::reverse(unit.types))
        if (!t->isLibrary)
          at = t->loc;
      diag.error(at, "no PROGRAM to translate: the input declares no "
                     "program, function block or function (only types or "
                     "global variables)");
      return false;
    }
  }
  // Program instance arguments bind the program's inputs and outputs to
  // globals; netlift writes one module per program, so a program can have
  // its arguments from one instance only.
  for (Configuration *c : unit.configs)
    for (ProgramInstance &pi : c->programs) {
      Pou *p = unit.findPou(pi.typeName);
      bool translated = false;
      for (auto &[q, t] : tops)
        translated |= q == p;
      if (!translated || pi.args.empty())
        continue;
      auto [it, fresh] = argumentsOf.try_emplace(p, &pi);
      if (!fresh) {
        diag.error(pi.loc, "program '" + p->name +
                               "' has arguments in two instances ('" +
                               it->second->name + "' and '" + pi.name +
                               "'), but netlift writes one module per program");
        return false;
      }
    }

  try {
    for (Pou *p : unit.pous)
      collectAssignments(p->body);
    // Variables written anywhere are not constants.
    for (Pou *p : unit.pous) {
      collectWritten(p->body, written);
      // Written by a callee: no bound from the values assigned directly.
      collectInOutWritten(p->body, writtenOtherwise);
    }
    markAddressTaken();

    // The tick.
    std::vector<int64_t> ns;
    std::set<Pou *> seen;
    for (auto &[p, task] : tops) {
      collectTimes(p, seen, ns);
      if (task && task->interval && task->interval->kind == ExprKind::TimeLit)
        ns.push_back(task->interval->intValue);
    }
    // The globals the programs use (a library's constants they do not
    // read, such as TwinCAT's DEFAULT_ADS_TIMEOUT, do not count).
    std::set<VarDecl *> used;
    for (auto &[p, task] : tops)
      for (VarDecl *g : globalsUsedBy(p))
        used.insert(g);
    for (VarDecl *g : unit.globals)
      if (g->typeSyntax && used.count(g))
        initTimes(g->typeSyntax->init, ns);
    chooseTick(std::move(ns));

    std::vector<ProgramRun> runs;
    for (auto &[p, task] : tops) {
      int64_t period = 1;
      SMLoc at = p->loc;
      if (opts.scanPeriodNs) {
        period = ticks(*opts.scanPeriodNs, at);
      } else if (task && task->interval) {
        if (task->interval->kind != ExprKind::TimeLit)
          refuse(task->interval->loc, "task INTERVAL must be a duration "
                                      "literal");
        period = ticks(task->interval->intValue, task->interval->loc);
      } else if (tickNs > 0 && design.timescale) {
        // A silent default would be a trap: the same logic in two
        // languages differs only because their literals' GCD differs.
        diag.note(at, "the scan period of '" + p->name + "' is one tick, " +
                          formatDuration(tickNs) +
                          " (the greatest common divisor of its durations): "
                          "no task INTERVAL or --scan-period fixes it");
      }
      if (task && task->single)
        refuse(task->single->loc, "event tasks (SINGLE) are not supported");
      if (period <= 0)
        refuse(at, "the scan period must be positive");
      ProgramRun run;
      run.pou = p;
      run.period = period;
      run.scan = "scan";
      run.cycle = "cycle";
      if (task) {
        run.scan = sanitize(task->name) + ".scan";
        run.cycle = sanitize(task->name) + ".cycle";
      }
      runs.push_back(std::move(run));
    }
    // Programs that share a variable (a global neither constant nor an FB
    // instance) run in one module; otherwise each is a module of its own.
    std::map<VarDecl *, unsigned> users;
    bool shared = false;
    for (ProgramRun &run : runs)
      for (VarDecl *g : globalsUsedBy(run.pou)) {
        if (g->constant || ++users[g] < 2)
          continue;
        if (g->type && instanceBlock(g->type))
          refuse(g->loc, "function block instance '" + g->name +
                             "' is a global called by several programs; "
                             "netlift does not model a shared instance");
        shared = true;
      }
    // A reference's NetIR type is the same in every module: 0..the most
    // places of its type any module has.
    auto countPlaces = [&](llvm::ArrayRef<ProgramRun> group) {
      for (auto &[key, table] : planReferences(group).tables)
        refDomain[key] = std::max(refDomain[key], table.count);
    };
    if (!shared) {
      for (ProgramRun &run : runs) {
        ProgramRun alone = run;
        alone.prefix.clear();
        countPlaces({alone});
      }
    } else {
      for (ProgramRun &run : runs) {
        auto it = instanceOf.find(run.pou);
        run.prefix = sanitize(it != instanceOf.end() ? it->second.first->name
                                                     : run.pou->name) +
                     ".";
      }
      countPlaces(runs);
    }
    if (!shared) {
      for (ProgramRun &run : runs) {
        std::vector<ProgramRun> one{std::move(run)};
        one[0].scan = "scan";
        one[0].cycle = "cycle";
        lowerPrograms(sanitize(one[0].pou->name), one[0].pou->loc, one);
      }
    } else {
      // One module for them all, named after their configuration: each
      // program's own names under its instance's name, the globals
      // bare, one scan per task (or `scan` alone when there is one task).
      std::string name = "Programs";
      SMLoc at = runs[0].pou->loc;
      if (auto it = instanceOf.find(runs[0].pou); it != instanceOf.end()) {
        name = sanitize(it->second.second->name);
        at = it->second.second->loc;
      }
      // Each program's names are under its instance's (set above).
      bool oneScan = true;
      for (ProgramRun &run : runs)
        oneScan &= run.scan == runs[0].scan;
      if (oneScan)
        for (ProgramRun &run : runs) {
          run.scan = "scan";
          run.cycle = "cycle";
        }
      lowerPrograms(name, at, runs);
    }
    checkRangesUsed();
  } catch (Refusal &) {
    return false;
  }
  return !diag.hadError();
}

void Lowering::lowerEventBlock(EventDrivenBlock &block) {
  eventDriven = true;
  Pou *pou = block.pou;
  startModule(sanitize(pou->name), pou->loc);
  ProgramRun run;
  run.pou = pou;
  ReferencePlan plan = planReferences({run});
  for (auto &[key, table] : plan.tables)
    refDomain[key] = std::max(refDomain[key], table.count);
  adoptReferencePlan(std::move(plan));
  declareProgram(run);
  resets = std::move(run.resets); // its temporaries, reset after reactions
  std::map<std::string, uint32_t> eventPorts;
  for (auto &[name, loc] : block.eventInputs)
    eventPorts[name] =
        b.addPort(name, net::PortKind::Event, net::PortDir::In, nullptr, loc);
  for (auto &[name, loc] : block.eventOutputs)
    eventPorts[name] =
        b.addPort(name, net::PortKind::Event, net::PortDir::Out, nullptr, loc);
  // One event at a time: reactions and sends share this token, so events
  // that arrive together are taken one per successor, never two in one
  // step, and a block never sends while it reacts.
  uint32_t ready = b.addPlace("ready", 1, 1, pou->loc);
  b.addAttribute("ready", net::kInternalAttribute, "one event at a time",
                 pou->loc);
  for (EventHandler &h : block.handlers) {
    Frame top;
    top.pou = pou;
    top.external = true;
    Sink action;
    if (mayJump(h.body, false))
      refuse(h.loc, "RETURN or a jump out of an algorithm is not supported "
                    "in an IEC 61499 function block");
    body(h.body, top, action, {});
    // Temporaries are back at their initial values after every reaction.
    if (!h.latch)
      appendResets(resets, action);
    uint32_t t = h.latch ? b.addTransition("recv_" + h.event, {}, {}, h.loc)
                         : b.addTransition("recv_" + h.event,
                                           {net::PreArc{ready, 1, {}}},
                                           {net::PostArc{ready, 1}}, h.loc);
    b.setEvents(t, {net::EventSource{eventPorts.at(h.event), true}});
    b.setAction(t, action);
  }
  for (EventSend &send : block.sends) {
    Frame top;
    top.pou = pou;
    top.external = true;
    Sink pre, action;
    NExpr *guard = expr(send.guard, top, pre);
    if (!pre.empty())
      refuse(send.loc, "internal: a send guard needs statements");
    body(send.body, top, action, {});
    appendResets(resets, action);
    uint32_t t =
        b.addTransition("send_" + send.event, {net::PreArc{ready, 1, {}}},
                        {net::PostArc{ready, 1}}, send.loc);
    b.setGuard(t, guard);
    b.setEmits(t, {eventPorts.at(send.event)});
    b.setUrgent(t);
    b.setAction(t, action);
  }
  capClocks();
  attachPragmas();
  eventDriven = false;
}

bool Lowering::runEventDriven(std::vector<EventDrivenBlock> &blocks) {
  try {
    for (Pou *p : unit.pous)
      collectWritten(p->body, written);
    std::vector<int64_t> ns;
    std::set<Pou *> seen;
    for (EventDrivenBlock &block : blocks) {
      collectTimes(block.pou, seen, ns);
      for (EventHandler &h : block.handlers)
        collectTimesStmts(h.body, seen, ns);
    }
    chooseTick(std::move(ns));
    for (EventDrivenBlock &block : blocks)
      lowerEventBlock(block);
  } catch (Refusal &) {
    return false;
  }
  return !diag.hadError();
}

bool plc::lowerEventDriven(Unit &unit, std::vector<EventDrivenBlock> &blocks,
                           const LowerOptions &opts, DiagEngine &diag,
                           net::Design &design) {
  Lowering l(unit, opts, diag, design);
  return l.runEventDriven(blocks);
}

bool plc::lowerToNet(Unit &unit, const LowerOptions &opts, DiagEngine &diag,
                     net::Design &design) {
  Lowering l(unit, opts, diag, design);
  return l.run();
}

/// A block a library translates to a module of its own: not an interface,
/// not ABSTRACT (neither has instances).
static bool translatedBlock(const Pou *p) {
  return !p->isLibrary && p->kind == PouKind::FunctionBlock &&
         !p->isInterface && !p->isAbstract;
}

bool plc::isLibrary(const Unit &unit) {
  for (Configuration *c : unit.configs)
    if (!c->programs.empty())
      return false;
  bool blocks = false;
  for (Pou *p : unit.pous) {
    if (p->isLibrary)
      continue;
    if (p->kind == PouKind::Program)
      return false;
    blocks |= translatedBlock(p);
  }
  return blocks;
}

bool plc::lowerLibrary(Unit &unit, const LowerOptions &opts, DiagEngine &diag,
                       net::Design &design) {
  std::vector<Pou *> blocks;
  for (Pou *p : unit.pous)
    if (translatedBlock(p))
      blocks.push_back(p);
  // One tick for every block: the durations of them all.
  LowerOptions each = opts;
  std::set<Pou *> seen;
  for (Pou *fb : blocks)
    Lowering::collectTimes(fb, seen, each.extraTimesNs);
  unsigned translated = 0;
  for (Pou *fb : blocks) {
    bool clean = true;
    for (Pou *p : reachedPous(unit, fb->name))
      clean &= !p->checkFailed;
    if (!clean)
      continue; // its errors are reported
    each.top = fb->name;
    // (Errors reported for other blocks make lowerToNet's answer false.)
    unsigned errorsBefore = diag.numErrors();
    lowerToNet(unit, each, diag, design);
    translated += diag.numErrors() == errorsBefore;
  }
  diag.note(blocks.front()->loc,
            "no PROGRAM: the input is a library; each of its " +
                llvm::Twine(blocks.size()) +
                " function blocks is a module of its own (" +
                llvm::Twine(translated) +
                " translated; --top NAME translates one)");
  return translated == blocks.size();
}
