//===- SemaObjects.cpp - checking calls of methods and actions ------------===//
//
// The object-oriented calls of IEC 61131-3 3rd edition and CODESYS/TwinCAT:
// `inst.M(...)` on an instance, `M(...)` and `THIS^.M(...)` on the running
// instance, `SUPER^.M(...)` (the base's implementation) and `SUPER^()`
// (the base's body). A method is checked as a function whose names fall
// back to its block's variables (Checker::lookupVar); which implementation
// an instance runs is the lowering's choice (an override is found by the
// instance's own type, LowerCalls.cpp).
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/SemaChecker.h"

#include <functional>
#include <set>

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

/// Does code running in `caller` (a block, or null) see `m` under its
/// access specifier?
static bool accessible(const Pou *m, const Pou *caller) {
  if (m->access != "PRIVATE" && m->access != "PROTECTED")
    return true; // PUBLIC, INTERNAL (one project is one namespace here)
  for (const Pou *b = caller; b; b = b->base) {
    if (b == m->methodOf)
      return true;
    if (m->access == "PRIVATE")
      return false; // not from a derived block
  }
  return false;
}

const PType *Checker::methodCall(Expr *e, bool asStatement) {
  Pou *running = runningBlock();
  Pou *klass = nullptr;
  if (e->operands.empty()) {
    if (!running || running->kind == PouKind::Function) {
      error(e->loc, "'" + e->name +
                        "' is called on the running instance, but no "
                        "function block or program runs here");
      return nullptr;
    }
    klass = e->ofSuper ? running->base : running;
    if (!klass) {
      error(e->loc, "SUPER^ in '" + running->name +
                        "', which EXTENDS no function block");
      return nullptr;
    }
    if (e->name == "SUPER^") { // the base's body, on this instance
      if (!asStatement || !e->args.empty()) {
        error(e->loc, "SUPER^() runs the base's body: a statement without "
                      "arguments");
        return nullptr;
      }
      e->callee = klass;
      return voidType();
    }
  } else {
    const PType *t = expr(e->operands[0]);
    if (!t)
      return nullptr;
    e->operands[0] = throughInterface(e->operands[0]);
    t = e->operands[0]->type;
    if (t->kind != PTypeKind::FunctionBlock) {
      error(e->loc, "calling '" + e->name + "' on a value of type " + t->str() +
                        " (methods and actions belong to "
                        "function block instances)");
      return nullptr;
    }
    klass = t->fb;
  }
  Pou *m = findCallee(klass, e);
  if (!m) {
    if (e->property)
      error(e->loc, "PROPERTY '" + e->name + "' of '" + klass->name +
                        "' has no " + (e->property == 'S' ? "SET" : "GET") +
                        (e->property == 'S' ? ": it cannot be assigned"
                                            : ": it cannot be read"));
    else
      error(e->loc,
            "'" + klass->name + "' has no method or action '" + e->name + "'");
    return nullptr;
  }
  if (!accessible(m, running)) {
    error(e->loc, "method '" + klass->name + "." + m->name + "' is " +
                      m->access + " and cannot be called from '" +
                      (running ? running->name : std::string("here")) + "'");
    return nullptr;
  }
  if (e->ofSuper && m->isAbstract) {
    error(e->loc,
          "SUPER^." + m->name + " is ABSTRACT in '" + m->methodOf->name + "'");
    return nullptr;
  }
  if (m == current) {
    error(e->loc, "recursive call of method '" + m->name + "'");
    return nullptr;
  }
  e->callee = m;
  functionArgs(e, m);
  if (!asStatement && m->resultType == voidType()) {
    error(e->loc, Twine(m->isAction ? "action '" : "method '") + m->name +
                      "' has no result type: call it as a statement");
    return nullptr;
  }
  return m->resultType;
}

bool Checker::hasProperty(const Pou *block, StringRef name) {
  return block &&
         (findProperty(block, name, false) || findProperty(block, name, true));
}

const PType *Checker::propertyRead(Expr *e, Expr *instance) {
  e->kind = ExprKind::Call;
  e->method = true;
  e->property = 'G';
  e->operands.clear();
  if (instance)
    e->operands.push_back(instance);
  return methodCall(e, false);
}

bool Checker::propertyWrite(Stmt *s) {
  Expr *target = s->target, *instance = nullptr;
  if (target->kind == ExprKind::Name) {
    if (target->ofSuper || lookupVar(target->name, target->ofThis) ||
        (current && current->resultVar && !target->ofThis &&
         sameName(current->name, target->name)) ||
        !hasProperty(runningBlock(), target->name))
      return false;
  } else if (target->kind == ExprKind::Field) {
    // (`GVL.x`, `Enum.v`: names, not instances; Checker::qualifiedName.)
    if (Expr *q = target->base();
        q->kind == ExprKind::Name && !q->ofThis && !lookupVar(q->name))
      return false;
    const PType *bt = expr(target->base());
    if (bt) {
      target->operands[0] = throughInterface(target->base());
      bt = target->base()->type;
    }
    if (!bt || bt->kind != PTypeKind::FunctionBlock ||
        bt->fb->find(target->name) || !hasProperty(bt->fb, target->name))
      return false;
    instance = target->base();
  } else {
    return false;
  }
  Expr *c = unit.make<Expr>(ExprKind::Call, target->loc);
  c->name = target->name;
  c->method = true;
  c->property = 'S';
  if (instance)
    c->operands.push_back(instance);
  CallArg value;
  value.name = target->name;
  value.value = s->value;
  value.loc = s->value->loc;
  c->args.push_back(value);
  s->kind = StmtKind::Call;
  s->target = nullptr;
  s->value = c;
  methodCall(c, true);
  return true;
}

void Checker::checkImplements(Pou *block) {
  std::set<const Pou *> seen;
  std::function<void(const Pou *)> check = [&](const Pou *itf) {
    if (!itf || !seen.insert(itf).second)
      return;
    for (const Pou *m : itf->methods) {
      const Pou *impl = m->property
                            ? findProperty(block, m->name, m->property == 'S')
                            : findMethod(block, m->name);
      if ((!impl || impl->isAbstract || impl->methodOf->isInterface) &&
          !block->isAbstract)
        error(block->loc,
              "'" + block->name + "' IMPLEMENTS '" + itf->name +
                  "' but has no " +
                  (m->property ? Twine("PROPERTY '") + m->name + "' with " +
                                     (m->property == 'S' ? "SET" : "GET")
                               : Twine("method '") + m->name + "'"));
    }
    for (const Pou *inner : itf->extendedInterfaces)
      check(inner);
  };
  for (const Pou *b = block; b; b = b->base)
    for (const std::string &n : b->implements)
      check(unit.findPou(n));
}

Expr *Checker::throughInterface(Expr *x) {
  if (!x->type || !x->type->isReference() ||
      x->type->refKind != RefKind::Interface)
    return x;
  Expr *d = unit.make<Expr>(ExprKind::Deref, x->loc);
  d->operands.push_back(x);
  d->type = x->type->elem;
  return d;
}

bool Checker::addressAsBase(const PType *to, Expr *from) {
  const PType *ft = from->type;
  if (!to->isReference() || to->refKind == RefKind::Interface || !to->elem ||
      to->elem->kind != PTypeKind::FunctionBlock || to->elem->fb->isInterface ||
      from->kind != ExprKind::Call || !from->typeName.empty() ||
      (from->name != "REF" && from->name != "ADR") || !ft->isReference() ||
      !ft->elem || ft->elem->kind != PTypeKind::FunctionBlock ||
      ft->elem->fb == to->elem->fb || !derivedFrom(ft->elem->fb, to->elem->fb))
    return false;
  // Numbered among the base's places (LowerReferences.cpp's
  // designatedType); a call through it runs the instance's own type's
  // implementation.
  from->typeName = "BASE";
  from->type = to;
  return true;
}

bool Checker::referenceAsBase(const PType *to, Expr *from) {
  const PType *ft = from->type;
  if (!to->isReference() || to->refKind == RefKind::Interface || !to->elem ||
      to->elem->kind != PTypeKind::FunctionBlock || to->elem->fb->isInterface ||
      !ft->isReference() || ft->refKind != to->refKind || !ft->elem ||
      ft->elem->kind != PTypeKind::FunctionBlock ||
      ft->elem->fb == to->elem->fb || !derivedFrom(ft->elem->fb, to->elem->fb))
    return false;
  // The value is renumbered among the base's places, which hold every
  // place the derived reference may designate (LowerReferences.cpp,
  // referenceUpcast); a call through it runs the instance's own type's
  // implementation.
  Expr *inner = unit.make<Expr>(*from);
  Expr upcast(ExprKind::Call, from->loc);
  upcast.name = "__UPCAST";
  CallArg arg;
  arg.value = inner;
  arg.loc = from->loc;
  upcast.args.push_back(arg);
  upcast.type = to;
  *from = upcast;
  return true;
}

bool Checker::instanceAsInterface(const PType *to, Expr *from, SMLoc at) {
  const PType *ft = from->type;
  if (!to->isReference() || to->refKind != RefKind::Interface || !ft)
    return false;
  if (ft->isReference() && ft->refKind == RefKind::Interface &&
      !implementsInterface(unit, ft->elem->fb, to->elem->fb)) {
    // (One that extends it is one; the other way needs a query.)
    error(at, "'" + ft->str() + "' is not '" + to->str() +
                  "' nor EXTENDS it: an interface is assigned only to one "
                  "it extends");
    return true;
  }
  if (ft->kind != PTypeKind::FunctionBlock || ft->fb->isInterface)
    return false;
  if (!implementsInterface(unit, ft->fb, to->elem->fb)) {
    error(at, "'" + ft->fb->name + "' does not IMPLEMENT '" + to->str() +
                  "': its instance cannot be assigned to the interface");
    return true;
  }
  // The instance's address, taken as the interface (LowerReferences.cpp
  // plans it among the interface's places).
  Expr *place = unit.make<Expr>(*from);
  from->kind = ExprKind::Call;
  from->name = "REF";
  from->typeName = "INTERFACE";
  from->operands.clear();
  from->var = nullptr;
  from->callee = nullptr;
  from->args.clear();
  CallArg arg;
  arg.value = place;
  arg.loc = place->loc;
  from->args.push_back(arg);
  from->type = to;
  return true;
}

void Checker::initCall(VarDecl *v) {
  const PType *t = v->type;
  std::vector<std::vector<CallArg>> &each = v->typeSyntax->elementArgs;
  if (!each.empty()) {
    // An array of instances, each element with its own arguments.
    int64_t elements = 1;
    for (auto &[lo, hi] : t->dims)
      elements *= hi - lo + 1;
    if (int64_t(each.size()) != elements) {
      error(v->loc, "'" + v->name + "' has " + Twine(elements) +
                        " elements but arguments for " + Twine(each.size()));
      return;
    }
    for (std::vector<CallArg> &args : each)
      if (Expr *call = initCallWith(v, t->elem, args))
        v->elementInitCalls.push_back(call);
    return;
  }
  v->initCall = initCallWith(v, t, v->typeSyntax->instanceArgs);
}

Expr *Checker::initCallWith(VarDecl *v, const PType *t,
                            std::vector<CallArg> &args) {
  Pou *fb = t->kind == PTypeKind::FunctionBlock ? t->fb : nullptr;
  Pou *init = fb ? findMethod(fb, "FB_init") : nullptr;
  if (!init) {
    if (!args.empty())
      error(args[0].loc, "'" + v->name +
                             "' is declared with arguments, which are for an "
                             "FB_init, but " +
                             (fb ? "'" + fb->name + "' has none"
                                 : t->str() + " is no function "
                                              "block"));
    return nullptr;
  }
  // Arguments in order (`fb : FB_T(1, 2)`) are FB_init's own inputs in
  // order: TwinCAT passes bInitRetains and bInCopyCode itself.
  size_t next = 0;
  for (CallArg &a : args) {
    if (!a.name.empty())
      continue;
    while (next < init->vars.size() &&
           (init->vars[next]->section != VarSection::Input ||
            sameName(init->vars[next]->name, "bInitRetains") ||
            sameName(init->vars[next]->name, "bInCopyCode")))
      ++next;
    if (next == init->vars.size()) {
      error(a.loc, "'" + v->name +
                       "' is declared with more arguments than "
                       "its FB_init takes");
      return nullptr;
    }
    a.name = init->vars[next++]->name;
  }
  Expr *call = unit.make<Expr>(ExprKind::Call, v->loc);
  call->name = init->name;
  call->method = true;
  call->callee = init;
  call->args = args;
  functionArgs(call, init);
  return call;
}
