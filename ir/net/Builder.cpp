//===- Builder.cpp - constructing NetIR -----------------------------------===//
#include "ir/net/Builder.h"

using namespace netlift::net;
using llvm::ArrayRef;
using llvm::SMLoc;
using llvm::StringRef;

Module *Builder::createModule(StringRef name, bool isSystem, SMLoc loc) {
  Module *m = design.createModule(name, loc, isSystem);
  if (m)
    mod = m;
  return m;
}

uint32_t Builder::addPort(StringRef name, PortKind kind, PortDir dir,
                          const Type *type, SMLoc loc) {
  Port p;
  p.name = design.save(name);
  p.loc = loc;
  p.kind = kind;
  p.dir = dir;
  p.type = kind == PortKind::Cond ? design.types.getBool() : type;
  uint32_t i = mod->ports.size();
  mod->ports.push_back(p);
  mod->declare(p.name, {SymKind::Port, i});
  return i;
}

uint32_t Builder::addPlace(StringRef name, uint32_t tokens, uint32_t capacity,
                           SMLoc loc) {
  Place p{design.save(name), loc, tokens, capacity};
  uint32_t i = mod->places.size();
  mod->places.push_back(p);
  mod->declare(p.name, {SymKind::Place, i});
  return i;
}

uint32_t Builder::addTransition(StringRef name, ArrayRef<PreArc> pre,
                                ArrayRef<PostArc> post, SMLoc loc) {
  Transition t;
  t.name = design.save(name);
  t.loc = loc;
  t.setArcs(design.copy(pre), design.copy(post));
  uint32_t i = mod->transitions.size();
  mod->transitions.push_back(t);
  mod->declare(t.name, {SymKind::Transition, i});
  return i;
}

uint32_t Builder::addVar(StringRef name, const Type *type, Expr *init,
                         SMLoc loc) {
  Var v{design.save(name), loc, type, init};
  uint32_t i = mod->vars.size();
  mod->vars.push_back(v);
  mod->declare(v.name, {SymKind::Var, i});
  return i;
}

uint32_t Builder::addInstance(StringRef name, StringRef moduleName, SMLoc loc) {
  Instance inst;
  inst.name = design.save(name);
  inst.loc = loc;
  inst.moduleName = design.save(moduleName);
  inst.moduleLoc = loc;
  uint32_t i = mod->instances.size();
  mod->instances.push_back(inst);
  mod->declare(inst.name, {SymKind::Instance, i});
  return i;
}

void Builder::addConnection(Endpoint from, Endpoint to, SMLoc loc) {
  from.instance = design.save(from.instance);
  from.port = design.save(from.port);
  to.instance = design.save(to.instance);
  to.port = design.save(to.port);
  mod->connections.push_back({loc, from, to});
}

void Builder::addAttribute(StringRef target, StringRef key, StringRef value,
                           SMLoc loc) {
  mod->attributes.push_back(
      {design.save(target), design.save(key), design.save(value), loc});
}

void Builder::addFlow(uint32_t place, ArrayRef<Flow::Equation> eqs, SMLoc loc) {
  Flow f;
  f.loc = loc;
  f.place = place;
  f.placeName = mod->places[place].name;
  std::vector<Flow::Equation> saved(eqs.begin(), eqs.end());
  for (auto &e : saved)
    e.var = design.save(e.var);
  f.equations = design.copy(ArrayRef<Flow::Equation>(saved));
  mod->flows.push_back(f);
}

void Builder::addInvariant(uint32_t place, ArrayRef<Expr *> conditions,
                           SMLoc loc) {
  Invariant inv;
  inv.loc = loc;
  inv.place = place;
  inv.placeName = mod->places[place].name;
  inv.conditions = design.copy(conditions);
  mod->invariants.push_back(inv);
}

TransitionExtras &Builder::extras(uint32_t t) {
  Transition &tr = mod->transitions[t];
  if (!tr.extras)
    tr.extras = design.createExtras();
  return *tr.extras;
}

void Builder::setConds(uint32_t t, ArrayRef<Expr *> conds) {
  extras(t).conds = design.copy(conds);
}

void Builder::setEvents(uint32_t t, ArrayRef<EventSource> events,
                        EventMode mode) {
  extras(t).events = design.copy(events);
  mod->transitions[t].mode = mode;
}

void Builder::setEmits(uint32_t t, ArrayRef<uint32_t> ports) {
  extras(t).emits = design.copy(ports);
}

void Builder::setGuard(uint32_t t, Expr *guard) { extras(t).guard = guard; }

void Builder::setAction(uint32_t t, ArrayRef<Stmt *> body) {
  TransitionExtras &x = extras(t);
  x.action = design.copy(body);
  x.hasAction = true;
}

void Builder::setUrgent(uint32_t t, bool urgent) {
  mod->transitions[t].urgent = urgent;
}

Expr *Builder::intLit(int64_t v, SMLoc loc) {
  return design.create<IntLit>(loc, v);
}
Expr *Builder::boolLit(bool v, SMLoc loc) {
  return design.create<BoolLit>(loc, v);
}
Expr *Builder::realLit(double v, SMLoc loc) {
  return design.create<RealLit>(loc, v);
}
Expr *Builder::stringLit(ArrayRef<char16_t> chars, SMLoc loc) {
  return design.create<StringLit>(loc, design.copy(chars));
}
Expr *Builder::ref(StringRef name, SMLoc loc) {
  return design.create<Ref>(loc, design.save(name));
}
Expr *Builder::unary(UnaryOp op, Expr *a, SMLoc loc) {
  return design.create<UnaryExpr>(loc, op, a);
}
Expr *Builder::binary(BinaryOp op, Expr *a, Expr *b, SMLoc loc) {
  return design.create<BinaryExpr>(loc, op, a, b);
}
Expr *Builder::cond(Expr *c, Expr *a, Expr *b, SMLoc loc) {
  return design.create<CondExpr>(loc, c, a, b);
}
Expr *Builder::index(Expr *base, Expr *idx, SMLoc loc) {
  return design.create<IndexExpr>(loc, base, idx);
}
Expr *Builder::field(Expr *base, StringRef f, SMLoc loc) {
  return design.create<FieldExpr>(loc, base, design.save(f));
}
Expr *Builder::call(Builtin fn, ArrayRef<Expr *> args, SMLoc loc,
                    const Type *to) {
  return design.create<CallExpr>(loc, fn, design.copy(args), to);
}
Expr *Builder::convert(const Type *to, Expr *a, SMLoc loc) {
  return call(Builtin::Convert, {a}, loc, to);
}
Expr *Builder::aggregate(ArrayRef<Expr *> elems, ArrayRef<StringRef> names,
                         SMLoc loc) {
  llvm::SmallVector<StringRef, 8> kept;
  for (StringRef n : names)
    kept.push_back(design.save(n));
  return design.create<AggregateLit>(loc, design.copy(elems),
                                     design.copy(ArrayRef<StringRef>(kept)));
}
Stmt *Builder::assign(Expr *target, Expr *value, SMLoc loc) {
  return design.create<AssignStmt>(loc, target, value);
}
Stmt *Builder::ifStmt(ArrayRef<IfArm> arms, bool hasElse,
                      ArrayRef<Stmt *> elseBody, SMLoc loc) {
  return design.create<IfStmt>(loc, design.copy(arms), hasElse,
                               design.copy(elseBody));
}
Stmt *Builder::caseStmt(Expr *sel, ArrayRef<CaseArm> arms, bool hasElse,
                        ArrayRef<Stmt *> elseBody, SMLoc loc) {
  return design.create<CaseStmt>(loc, sel, design.copy(arms), hasElse,
                                 design.copy(elseBody));
}
Stmt *Builder::forStmt(StringRef var, Expr *lo, Expr *hi, ArrayRef<Stmt *> body,
                       SMLoc loc) {
  return design.create<ForStmt>(loc, design.save(var), lo, hi,
                                design.copy(body));
}
Stmt *Builder::whileStmt(Expr *c, ArrayRef<Stmt *> body, bool testAfter,
                         SMLoc loc) {
  return design.create<WhileStmt>(loc, c, design.copy(body), testAfter);
}
