//===- Iec61499InternalFbs.cpp - internal FBs of basic and simple FBs ----===//
//
// 4diac IDE 2 and later let a basic or simple FB hold FB instances of its
// own (`<FB Name Type>` among its InternalVars), whose events its
// algorithms call: `t.REQ(IN := x, OUT => y);` sets the inputs given, runs
// the instance's reaction to REQ to its end, and copies the outputs named
// (FORTE's generated code does exactly that; the instance's output events
// are connected to nothing and go nowhere). Here each type used so becomes
// an ST function block (basicBlock with asInternal) whose input `_call`
// selects the event, and an event call becomes a call of it: the ST
// lowering inlines it at its place, so the instance's state is the owner's.
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

static const char *kindName(TypeKind k) {
  switch (k) {
  case TypeKind::Basic:
    return "a basic FB";
  case TypeKind::Composite:
    return "a composite FB";
  case TypeKind::SubApp:
    return "a subapplication";
  case TypeKind::Service:
    return "a service interface FB";
  case TypeKind::Adapter:
    return "an adapter";
  case TypeKind::NoBody:
    return "an FB without a body";
  }
  return "type";
}

void Translator::collectInternalFbs(FbType &t) {
  if (internalDone.count(&t) || t.kind != TypeKind::Basic)
    return;
  internalVisiting.insert(&t);
  for (pugi::xml_node fb : child(t.body, "InternalVars").children("FB")) {
    SMLoc loc = t.src->locOf(fb);
    StringRef name = fb.attribute("Name").value();
    StringRef typeName = fb.attribute("Type").value();
    FbType *inner = findType(typeName, loc);
    checkPackage(fb, *inner, loc);
    if ((inner->kind == TypeKind::Service || inner->kind == TypeKind::NoBody) &&
        !isShipped(inner->name) && modelFunctionFb(*inner))
      inner->kind = TypeKind::Basic;
    bool generic = false;
    for (const std::vector<Var> *list : {&inner->inputs, &inner->outputs})
      for (const Var &v : *list)
        generic |= isGenericType(v.type);
    // A runtime-implemented one is environment, as in a network.
    bool environment =
        (inner->kind == TypeKind::Service || inner->kind == TypeKind::NoBody) &&
        !generic && !isShipped(inner->name);
    if ((inner->kind != TypeKind::Basic && !environment) ||
        isShipped(inner->name))
      fail(loc, "internal FB '" + name + "' of '" + t.name + "' is " +
                    (isShipped(inner->name) ? "a timed service FB"
                     : generic ? "a generic FB (netlift fixes its types "
                                 "per block in a network)"
                               : kindName(inner->kind)) +
                    " ('" + inner->name +
                    "'); netlift models internal FBs of basic and simple "
                    "types, and of service FBs as environment");
    if (!inner->adapterDecls.empty())
      fail(loc, "internal FB '" + name + "' of '" + t.name + "' has type '" +
                    inner->name +
                    "', which has plugs or sockets (an internal FB's "
                    "adapters cannot be connected)");
    if (internalVisiting.count(inner))
      fail(loc, "internal FB '" + name + "' of '" + t.name + "' has type '" +
                    inner->name + "', which is or holds '" + t.name +
                    "' (an FB cannot contain itself)");
    for (auto &[other, type] : t.internalFbs)
      if (StringRef(other).equals_insensitive(name))
        fail(loc, "internal FB '" + name + "' is declared twice in '" + t.name +
                      "'");
    // The types it uses come first.
    collectInternalFbs(*inner);
    if (!llvm::is_contained(internalOrder, inner))
      internalOrder.push_back(inner);
    t.internalFbs.push_back({name.str(), inner});
  }
  internalVisiting.erase(&t);
  internalDone.insert(&t);
}

void Translator::internalEnvironmentPou(FbType &t) {
  SMLoc at = t.src->locOf(t.root);
  auto *pou = unit.make<Pou>();
  pou->kind = PouKind::FunctionBlock;
  pou->name = internalFbPou(t.name);
  pou->loc = at;
  pou->environment = "is " + std::string(kindName(t.kind)) + " ('" + t.name +
                     "'), implemented by the runtime";
  auto declare = [&](StringRef name, TypeSyntax *ts, VarSection s, SMLoc loc) {
    addVar(unit, *pou, name, ts, s, loc);
  };
  auto *events = unit.make<TypeSyntax>(TypeSyntaxKind::Subrange, at);
  events->name = "INT";
  events->lo = intLit(unit, 0, at);
  events->hi = intLit(unit, int64_t(t.eventInputs.size()), at);
  declare(kInternalEvent, events, VarSection::Input, at);
  for (const Var &v : t.inputs)
    declare(v.name, typeOf(*t.src, v.node), VarSection::Input,
            t.src->locOf(v.node));
  for (const Var &v : t.outputs)
    declare(v.name, typeOf(*t.src, v.node), VarSection::Output,
            t.src->locOf(v.node));
  unit.pous.push_back(pou);
}

TypeSyntax *Translator::internalFbDecl(FbType &owner, pugi::xml_node fb,
                                       const FbType &inner) {
  SMLoc loc = owner.src->locOf(fb);
  auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, loc);
  ts->name = internalFbPou(inner.name);
  for (pugi::xml_node p : fb.children("Parameter")) {
    StringRef input = p.attribute("Name").value();
    bool known = false;
    for (const Var &v : inner.inputs)
      known |= StringRef(v.name).equals_insensitive(input);
    if (!known)
      fail(owner, p,
           "parameter '" + input + "' of internal FB '" +
               fb.attribute("Name").value() + "' is not a data input of '" +
               inner.name + "'");
    StringRef text = owner.src->placeAttribute(p, "Value");
    if (text.trim().empty())
      fail(owner, p,
           "parameter '" + input + "' of internal FB '" +
               fb.attribute("Name").value() +
               "' gives no value (Value is empty or missing): give one, or "
               "remove the parameter to keep the input's initial value");
    Expr *value = st::parseStExpression(text, diag, unit);
    if (!value)
      throw Failure();
    if (!ts->init)
      ts->init = unit.make<Initializer>(Initializer::Struct, loc);
    auto *init = unit.make<Initializer>(Initializer::Value, value->loc);
    init->value = value;
    ts->init->fields.push_back({input.str(), init});
  }
  return ts;
}

void Translator::callInternalFbs(FbType &t, StmtList &body) {
  if (t.internalFbs.empty())
    return;
  auto instance = [&](StringRef name) -> const FbType * {
    for (auto &[n, inner] : t.internalFbs)
      if (StringRef(n).equals_insensitive(name))
        return inner;
    return nullptr;
  };
  // Event calls are statements (FORTE's code has no value for them).
  plc::forEachStmt(body, [&](Stmt *s) {
    Expr *c = s->kind == StmtKind::Call ? s->value : nullptr;
    if (!c || c->kind != ExprKind::Call)
      return;
    if (!c->method && instance(c->name))
      fail(c->loc, "internal FB '" + c->name +
                       "' is called without an event; call one of its "
                       "input events (`" +
                       c->name + "." +
                       (instance(c->name)->eventInputs.empty()
                            ? std::string("REQ")
                            : instance(c->name)->eventInputs[0].name) +
                       "(...)`)");
    if (!c->method || c->operands.size() != 1 ||
        c->operands[0]->kind != ExprKind::Name)
      return;
    StringRef fb = c->operands[0]->name;
    const FbType *inner = instance(fb);
    if (!inner)
      return;
    int64_t number = 0;
    for (size_t i = 0; i < inner->eventInputs.size(); ++i)
      if (StringRef(inner->eventInputs[i].name).equals_insensitive(c->name))
        number = int64_t(i) + 1;
    if (!number)
      fail(c->loc, "'" + c->name + "' is not an input event of internal FB '" +
                       fb + "' (type '" + inner->name + "')");
    c->method = false;
    c->name = fb.str();
    c->operands.clear();
    CallArg event;
    event.name = kInternalEvent;
    event.value = intLit(unit, number, c->loc);
    event.loc = c->loc;
    c->args.insert(c->args.begin(), event);
  });
  // What is left naming an internal FB's event is inside an expression.
  std::function<void(Expr *)> visit = [&](Expr *e) {
    if (!e)
      return;
    if (e->kind == ExprKind::Call && e->method && e->operands.size() == 1 &&
        e->operands[0]->kind == ExprKind::Name &&
        instance(e->operands[0]->name))
      fail(e->loc, "event '" + e->name + "' of internal FB '" +
                       e->operands[0]->name +
                       "' is called inside an expression; call it as a "
                       "statement and read its outputs after");
    for (Expr *o : e->operands)
      visit(o);
    for (CallArg &a : e->args)
      visit(a.value);
  };
  plc::forEachStmt(body, nullptr, [&](Expr *e) {
    if (e->kind == ExprKind::Call && !e->method && e->args.size() &&
        e->args[0].name == kInternalEvent) {
      for (CallArg &a : e->args)
        visit(a.value);
      return;
    }
    visit(e);
  });
}
