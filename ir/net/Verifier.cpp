//===- Verifier.cpp - NetIR well-formedness -------------------------------===//
#include "ir/net/Verifier.h"

#include "ir/net/Printer.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringSwitch.h"

#include <algorithm>
#include <functional>

using namespace netlift;
using namespace netlift::net;
using llvm::SMLoc;
using llvm::StringRef;
using llvm::Twine;

bool netlift::net::hasHybridParts(const Module &m) {
  if (!m.flows.empty() || !m.invariants.empty())
    return true;
  for (const Var &v : m.vars)
    if (v.type->isReal())
      return true;
  return false;
}

namespace {

/// Where an expression is read; decides which names it may use.
enum class Ctx {
  Signal,   // condition arcs: places and cond ports only
  Guard,    // guards, definitions, action right-hand sides, flows
  State,    // properties of a state (reach --find, sr, check): no free inputs
  Constant, // initial values, case labels, loop bounds
};

class ModuleVerifier {
public:
  ModuleVerifier(Design &d, Module &m, DiagEngine &diag)
      : d(d), m(m), diag(diag), types(d.types) {}
  void run();
  bool checkPredicate(Expr *e) {
    return expectBool(e, Ctx::State, "a predicate");
  }

private:
  void error(SMLoc loc, const Twine &msg) { diag.error(loc, msg); }
  std::string typeName(const Type *t) { return t->str(); }
  std::vector<std::string> moduleNames() const {
    std::vector<std::string> names;
    for (auto &mod : d.modules)
      names.push_back(mod->name.str());
    return names;
  }
  SMLoc locOf(Symbol s);
  void checkNames();
  void checkAttributes();
  void checkPorts();
  void checkVars();
  void checkPlaces();
  void checkTransition(uint32_t ti);
  void checkFlows();
  void checkInvariants();
  void checkInstancesAndConnections();
  void checkEventCycles();
  void checkDefinitionCycles();

  const Type *check(Expr *e, Ctx ctx);
  const Type *checkRef(Ref *r, Ctx ctx);
  const Type *checkCall(CallExpr *c, Ctx ctx);
  bool expectBool(Expr *e, Ctx ctx, StringRef what);
  /// The input port `p` is, or the first one its definition reads.
  const Port *inputRead(const Port &p);
  const Port *inputRead(const Expr *e);
  bool checkInit(Expr *init, const Type *type, StringRef what);
  void checkBlock(Block b);
  void checkStmt(Stmt *s);
  /// The `between(a, b)` being checked as the whole value of an assignment
  /// (the only place it may appear).
  const CallExpr *resetValue = nullptr;
  const Type *checkTarget(Expr *e);
  bool isNumeric(const Type *t) {
    return t->isInteger() || t->isReal() || t->isFloat();
  }
  /// Gives a constant real expression (type `real`) the float type `ft` of
  /// its context, down to its literals.
  void adopt(Expr *e, const Type *ft);
  /// The float type two operands of `e` share (a constant real adopts the
  /// other's; two constant reals are real64); null with an error when
  /// they mix a float with anything else. Only called when one is a float
  /// or both are constant reals.
  const Type *commonFloat(Expr *e, Expr *a, Expr *b, StringRef op);
  /// A narrow string literal (or a choice between them) next to a wstring
  /// becomes a wstring literal: its characters fit.
  void widen(Expr *e, const Type *to);
  /// The string type two operands of `e` share (the longer length, the
  /// wider characters after widening literals); null with an error when
  /// one is not a string or they mix string and wstring.
  const Type *commonString(Expr *e, Expr *a, Expr *b, StringRef op);
  const Type *checkStringCall(CallExpr *c);
  /// A uint64 operand computes in unsigned arithmetic: the other operand
  /// must be a uint64 too or a constant in its range. Returns the uint64
  /// type; null with an error when they mix.
  const Type *commonUnsigned64(Expr *e, Expr *a, Expr *b, StringRef op);
  /// Can `value` be written to a uint64 (or read from one into `to`)?
  bool fitsUnsigned64(const Type *to, Expr *value);
  /// Can a variable of type `to` take `value` (assigned, initial, a
  /// definition)? A constant real and a narrow string literal take `to`'s
  /// float or wstring type on the way.
  bool takes(const Type *to, Expr *value) {
    widen(value, to);
    bool ok = isAssignable(to, value->type) ||
              (to->isUnsigned64() && fitsUnsigned64(to, value));
    if (ok && to->isFloat())
      adopt(value, to);
    return ok;
  }
  /// Is this an operand pair computed in floating point?
  static bool involvesFloat(const Type *a, const Type *b) {
    return a->isFloat() || b->isFloat();
  }

  Design &d;
  Module &m;
  DiagEngine &diag;
  TypeTable &types;
  std::vector<StringRef> loopVars;
  /// Constant reals are hybrid values in a module with hybrid parts.
  bool hybrid = false;
};

SMLoc ModuleVerifier::locOf(Symbol s) {
  switch (s.kind) {
  case SymKind::Place:
    return m.places[s.index].loc;
  case SymKind::Transition:
    return m.transitions[s.index].loc;
  case SymKind::Port:
    return m.ports[s.index].loc;
  case SymKind::Var:
    return m.vars[s.index].loc;
  case SymKind::Instance:
    return m.instances[s.index].loc;
  default:
    return {};
  }
}

void ModuleVerifier::checkNames() {
  auto check = [&](StringRef name, SMLoc loc, Symbol self) {
    Symbol s = m.lookup(name);
    if (s == self)
      return;
    error(loc, "redefinition of '" + name + "' in module '" + m.name + "'");
    diag.note(locOf(s), "previous definition is here");
  };
  for (uint32_t i = 0; i < m.ports.size(); ++i)
    check(m.ports[i].name, m.ports[i].loc, {SymKind::Port, i});
  for (uint32_t i = 0; i < m.places.size(); ++i)
    check(m.places[i].name, m.places[i].loc, {SymKind::Place, i});
  for (uint32_t i = 0; i < m.transitions.size(); ++i)
    check(m.transitions[i].name, m.transitions[i].loc,
          {SymKind::Transition, i});
  for (uint32_t i = 0; i < m.vars.size(); ++i)
    check(m.vars[i].name, m.vars[i].loc, {SymKind::Var, i});
  for (uint32_t i = 0; i < m.instances.size(); ++i)
    check(m.instances[i].name, m.instances[i].loc, {SymKind::Instance, i});
}

void ModuleVerifier::checkAttributes() {
  for (const Attribute &a : m.attributes)
    if (!m.isAttributeTarget(a.target))
      error(a.loc, "attribute '" + a.key + "' is attached to '" + a.target +
                       "', which is not a port, place, transition, "
                       "variable, instance or scope of module '" +
                       m.name + "'");
}

bool ModuleVerifier::checkInit(Expr *init, const Type *type, StringRef what) {
  if (!init)
    return true;
  if (auto *agg = llvm::dyn_cast<AggregateLit>(init)) {
    if (type->isScalar()) {
      error(init->loc, "initial value of " + what + " is an aggregate, but '" +
                           typeName(type) + "' is not an array or record");
      return false;
    }
    if (type->kind == TypeKind::Array) {
      uint64_t n = uint64_t(type->indexHi - type->indexLo + 1);
      if (agg->isRecord() || agg->elems.size() != n) {
        error(init->loc, "initial value of " + what + " must list the " +
                             Twine(n) + " elements of '" + typeName(type) +
                             "' as [e, ...]");
        return false;
      }
      bool ok = true;
      for (size_t i = 0; i < n; ++i)
        ok &= checkInit(
            agg->elems[i], type->elem,
            ("element [" + Twine(type->indexLo + int64_t(i)) + "] of " + what)
                .str());
      agg->type = type;
      return ok;
    }
    bool sameFields =
        agg->isRecord() && agg->fieldNames.size() == type->fields.size();
    for (size_t i = 0; sameFields && i < type->fields.size(); ++i)
      sameFields = agg->fieldNames[i] == type->fields[i].name;
    if (!sameFields) {
      std::string names;
      for (const Field &f : type->fields)
        names += (names.empty() ? "" : ", ") + f.name.str() + ": ...";
      error(init->loc, "initial value of " + what +
                           " must give the fields of '" + typeName(type) +
                           "' in order, as {" + names + "}");
      return false;
    }
    bool ok = true;
    for (size_t i = 0; i < type->fields.size(); ++i)
      ok &=
          checkInit(agg->elems[i], type->fields[i].type,
                    ("field '" + type->fields[i].name + "' of " + what).str());
    agg->type = type;
    return ok;
  }
  const Type *t = check(init, Ctx::Constant);
  if (!t)
    return false;
  if (!takes(type, init)) {
    error(init->loc, "initial value of " + what + " has type '" +
                         typeName(init->type) + "', expected '" +
                         typeName(type) + "'");
    return false;
  }
  int64_t v;
  if (type->isInteger() && evalConstInt(init, v) &&
      (v < type->lo || v > type->hi)) {
    error(init->loc, "initial value " + Twine(v) + " of " + what +
                         " is outside its type '" + typeName(type) + "'");
    return false;
  }
  return true;
}

void ModuleVerifier::checkPorts() {
  if (m.isSystem && !m.ports.empty())
    error(m.ports[0].loc, "system '" + m.name + "' cannot have ports");
  for (Port &p : m.ports) {
    if (p.kind == PortKind::Data) {
      if (!p.type) {
        error(p.loc, "data port '" + p.name + "' has no type");
        continue;
      }
      if (p.type->isClock() || p.type->isReal()) {
        error(p.loc, "data port '" + p.name + "' cannot have type '" +
                         typeName(p.type) + "'");
        continue;
      }
    }
    if (p.kind == PortKind::Event || p.isInput()) {
      if (p.definition || p.init)
        error(p.definition ? p.definitionLoc : p.init->loc,
              "only cond and data outputs can be defined or initialised");
      continue;
    }
    if (p.definition) {
      if (check(p.definition, Ctx::Guard) && !takes(p.type, p.definition))
        error(p.definition->loc, "output '" + p.name + "' of type '" +
                                     typeName(p.type) +
                                     "' is defined by an expression of type '" +
                                     typeName(p.definition->type) + "'");
    }
    checkInit(p.init, p.type, ("output '" + p.name + "'").str());
  }
}

void ModuleVerifier::checkVars() {
  for (Var &v : m.vars) {
    if (!v.type) {
      error(v.loc, "variable '" + v.name + "' has no type");
      continue;
    }
    checkInit(v.init, v.type, ("variable '" + v.name + "'").str());
    if (!v.initHi)
      continue;
    if (!v.type->isReal()) {
      error(v.initHi->loc, "only a hybrid real starts in an interval ('" +
                               v.name + "' is not one)");
      continue;
    }
    checkInit(v.initHi, v.type, ("variable '" + v.name + "'").str());
    auto lo = evalConstReal(v.init), hi = evalConstReal(v.initHi);
    if (!lo || !hi)
      error(v.init->loc, "the initial interval of real '" + v.name +
                             "' has bounds that are not constants");
    else if (*lo > *hi)
      error(v.init->loc,
            "the initial interval of real '" + v.name + "' is empty");
  }
}

void ModuleVerifier::checkPlaces() {
  for (const Place &p : m.places) {
    if (p.capacity == 0)
      error(p.loc, "place '" + p.name + "' has capacity 0");
    else if (p.capacity != kInf && p.tokens > p.capacity)
      error(p.loc, "initial marking of place '" + p.name + "' (" +
                       Twine(p.tokens) + ") exceeds its capacity " +
                       Twine(p.capacity));
  }
}

void ModuleVerifier::checkTransition(uint32_t ti) {
  Transition &t = m.transitions[ti];
  // Arcs built through the Builder carry no locations of their own; the
  // parser already refused these mistakes at the arc itself.
  llvm::SmallDenseSet<uint32_t, 8> seen;
  for (const PreArc &a : t.pre()) {
    if (a.place >= m.places.size()) {
      error(t.loc, "transition '" + t.name + "' has a pre-arc to no place");
      return;
    }
    if (a.weight == 0)
      error(t.loc, "arc weight must be at least 1 (pre-arc from '" +
                       m.places[a.place].name + "' of '" + t.name + "')");
    if (a.time.lo > a.time.hi)
      error(t.loc, "empty time interval on the arc from '" +
                       m.places[a.place].name + "' to '" + t.name + "'");
    if (a.time.deadline && a.time.hi == kInf)
      error(t.loc, "the deadline on the arc from '" + m.places[a.place].name +
                       "' to '" + t.name + "' has no finite upper bound");
    if (!seen.insert(a.place).second)
      error(t.loc, "place '" + m.places[a.place].name +
                       "' appears twice in the pre-set of '" + t.name +
                       "'; give the arc a weight instead");
  }
  seen.clear();
  for (const PostArc &a : t.post()) {
    if (a.place >= m.places.size()) {
      error(t.loc, "transition '" + t.name + "' has a post-arc to no place");
      return;
    }
    if (a.weight == 0)
      error(t.loc, "arc weight must be at least 1 (post-arc to '" +
                       m.places[a.place].name + "' of '" + t.name + "')");
    if (!seen.insert(a.place).second)
      error(t.loc, "place '" + m.places[a.place].name +
                       "' appears twice in the post-set of '" + t.name +
                       "'; give the arc a weight instead");
  }
  for (Expr *c : t.conds())
    expectBool(c, Ctx::Signal, "a condition arc");
  auto events = t.events();
  for (size_t i = 0; i < events.size(); ++i) {
    const EventSource &s = events[i];
    SMLoc loc = t.extras->eventLocs.size() > i ? t.extras->eventLocs[i] : t.loc;
    if (s.fromPort) {
      if (s.index >= m.ports.size() ||
          m.ports[s.index].kind != PortKind::Event ||
          !m.ports[s.index].isInput())
        error(loc,
              "event arc into '" + t.name + "' must come from an event input");
    } else if (s.index >= m.transitions.size()) {
      error(loc, "event arc into '" + t.name + "' comes from no transition");
    } else if (s.index == ti) {
      error(loc, "transition '" + t.name + "' cannot force itself");
    }
  }
  for (uint32_t p : t.emits())
    if (p >= m.ports.size() || m.ports[p].kind != PortKind::Event ||
        !m.ports[p].isOutput())
      error(t.loc, "transition '" + t.name +
                       "' emits to a port that is not "
                       "an event output");
  if (Expr *g = t.guard())
    expectBool(g, Ctx::Guard, "a guard");
  checkBlock(t.action());
}

void ModuleVerifier::checkFlows() {
  for (Flow &f : m.flows) {
    if (f.place >= m.places.size()) {
      error(f.loc, "flow of no place");
      continue;
    }
    llvm::SmallDenseSet<uint32_t, 4> vars;
    for (const Flow::Equation &ceq : f.equations) {
      auto &eq = const_cast<Flow::Equation &>(ceq);
      Symbol s = m.lookup(eq.var);
      if (s.kind != SymKind::Var || !m.vars[s.index].type->isReal()) {
        error(eq.loc, "'" + eq.var +
                          "' is not a real variable; flows (x' = "
                          "rate) are for real variables");
        continue;
      }
      eq.varIndex = s.index;
      if (!vars.insert(s.index).second)
        error(eq.loc, "two flows for '" + eq.var + "' in place '" +
                          m.places[f.place].name + "'");
      for (Expr *rate : {eq.rate, eq.rateHi}) {
        if (!rate)
          continue;
        const Type *t = check(rate, Ctx::Guard);
        if (t && !isNumeric(t))
          error(rate->loc, "the rate of '" + eq.var +
                               "' must be a number, not '" + typeName(t) + "'");
      }
      if (!eq.rateHi)
        continue;
      auto lo = evalConstReal(eq.rate), hi = evalConstReal(eq.rateHi);
      if (lo && hi && *lo > *hi)
        error(eq.rate->loc, "the rates of '" + eq.var + "' in place '" +
                                m.places[f.place].name +
                                "' are an empty "
                                "interval [" +
                                exprToString(eq.rate) + ", " +
                                exprToString(eq.rateHi) + "]");
    }
  }
}

void ModuleVerifier::checkInvariants() {
  for (Invariant &inv : m.invariants) {
    if (inv.place >= m.places.size()) {
      error(inv.loc, "invariant of no place");
      continue;
    }
    for (Expr *c : inv.conditions)
      expectBool(c, Ctx::Guard, "an invariant");
  }
}

bool ModuleVerifier::expectBool(Expr *e, Ctx ctx, StringRef what) {
  const Type *t = check(e, ctx);
  if (!t)
    return false;
  if (!t->isBool()) {
    error(e->loc, what + " must be Boolean, but '" + exprToString(e) +
                      "' has type '" + typeName(t) + "'");
    return false;
  }
  return true;
}

const Type *ModuleVerifier::checkRef(Ref *r, Ctx ctx) {
  StringRef name = r->name;
  // Typed enumerator `Color#red`.
  if (name.contains('#')) {
    auto [tn, en] = name.split('#');
    const Type *t = types.lookup(tn);
    if (!t || t->kind != TypeKind::Enum) {
      error(r->loc, "'" + tn + "' is not an enumeration type");
      return nullptr;
    }
    int idx = t->enumIndex(en);
    if (idx < 0) {
      error(r->loc, "'" + en + "' is not an enumerator of '" + tn + "'");
      return nullptr;
    }
    r->sym = {SymKind::EnumLit, uint32_t(idx)};
    return r->type = t;
  }
  for (size_t i = loopVars.size(); i-- > 0;)
    if (loopVars[i] == name) {
      if (ctx == Ctx::Signal) {
        error(r->loc,
              "loop variable '" + name + "' cannot be used in a condition arc");
        return nullptr;
      }
      r->sym = {SymKind::LoopVar, uint32_t(i)};
      return r->type = types.getInteger();
    }
  Symbol s = m.lookup(name);
  llvm::SmallVector<StringRef, 2> fieldNames;
  if (s.kind == SymKind::None && name.contains('.')) {
    // Longest declared prefix, the rest being record fields.
    StringRef prefix = name;
    while (s.kind == SymKind::None && prefix.contains('.')) {
      auto [head, tail] = prefix.rsplit('.');
      fieldNames.insert(fieldNames.begin(), tail);
      prefix = head;
      s = m.lookup(prefix);
    }
    if (s.kind != SymKind::Var && s.kind != SymKind::Port)
      s = Symbol(), fieldNames.clear();
  }
  if (s.kind == SymKind::None) {
    // A bare enumerator, if exactly one enumeration has it.
    const Type *found = nullptr;
    int idx = -1;
    for (const auto &nt : types.namedTypes()) {
      if (nt.isAlias || nt.type->kind != TypeKind::Enum)
        continue;
      int i = nt.type->enumIndex(name);
      if (i < 0)
        continue;
      if (found) {
        error(r->loc, "'" + name + "' is an enumerator of both '" +
                          found->name + "' and '" + nt.type->name +
                          "'; write " + found->name + "#" + name + " or " +
                          nt.type->name + "#" + name);
        return nullptr;
      }
      found = nt.type;
      idx = i;
    }
    if (found) {
      r->sym = {SymKind::EnumLit, uint32_t(idx)};
      return r->type = found;
    }
    error(r->loc, "unknown name '" + name + "' in module '" + m.name + "'" +
                      didYouMean(name, m.declaredNames()));
    return nullptr;
  }
  if (ctx == Ctx::Constant) {
    error(r->loc, "'" + name + "' is not a constant");
    return nullptr;
  }
  const Type *t = nullptr;
  switch (s.kind) {
  case SymKind::Place:
    // A place read in an expression means "is marked".
    t = types.getBool();
    break;
  case SymKind::Port: {
    const Port &p = m.ports[s.index];
    if (p.kind == PortKind::Event) {
      error(r->loc,
            "event port '" + name + "' has no value; use it in 'on' or 'emit'");
      return nullptr;
    }
    if (ctx == Ctx::Signal && p.kind == PortKind::Data) {
      error(r->loc, "condition arcs carry Boolean signals; data port '" + name +
                        "' belongs in a guard");
      return nullptr;
    }
    // A free input takes every value at every step; no state holds it
    // (nor an output defined from one).
    const Port *input = ctx == Ctx::State ? inputRead(p) : nullptr;
    if (input && input != &p) {
      error(r->loc, "output '" + name + "' is defined from input '" +
                        input->name +
                        "', which is not part of a state: a state property "
                        "reads places, variables and outputs defined from "
                        "them");
      return nullptr;
    }
    if (input) {
      error(r->loc, "input '" + name +
                        "' is not part of a state (free inputs take every "
                        "value at every step): a state property reads "
                        "places, variables and outputs");
      return nullptr;
    }
    t = p.type;
    break;
  }
  case SymKind::Var:
    if (ctx == Ctx::Signal) {
      error(r->loc, "condition arcs carry signals (places and cond ports); "
                    "variable '" +
                        name + "' belongs in a guard");
      return nullptr;
    }
    t = m.vars[s.index].type;
    break;
  case SymKind::Transition:
    error(r->loc, "'" + name + "' is a transition and has no value");
    return nullptr;
  case SymKind::Instance:
    error(r->loc, "'" + name + "' is an instance and has no value");
    return nullptr;
  default:
    return nullptr;
  }
  r->sym = s;
  if (!fieldNames.empty()) {
    llvm::SmallVector<uint32_t, 2> idx;
    for (StringRef f : fieldNames) {
      int fi = t->kind == TypeKind::Record ? t->fieldIndex(f) : -1;
      if (fi < 0) {
        error(r->loc, "'" + f + "' is not a field of '" + typeName(t) + "'");
        return nullptr;
      }
      idx.push_back(uint32_t(fi));
      t = t->fields[fi].type;
    }
    r->fields = d.copy(llvm::ArrayRef<uint32_t>(idx));
  }
  return r->type = t;
}

const Type *ModuleVerifier::check(Expr *e, Ctx ctx) {
  switch (e->getKind()) {
  case ExprKind::Aggregate:
    error(e->loc, "an aggregate ([...] or {...}) is allowed only as the "
                  "initial value of an array or record variable");
    return nullptr;
  case ExprKind::IntLit:
    return e->type = types.getInteger();
  case ExprKind::BoolLit:
    return e->type = types.getBool();
  case ExprKind::RealLit:
    return e->type = types.getAnyReal();
  case ExprKind::StringLit: {
    auto *l = llvm::cast<StringLit>(e);
    bool wide = llvm::any_of(l->chars, [](char16_t c) { return c > 0xff; });
    return e->type = types.getString(uint32_t(l->chars.size()), wide);
  }
  case ExprKind::Ref:
    return checkRef(llvm::cast<Ref>(e), ctx);
  case ExprKind::Index: {
    auto *x = llvm::cast<IndexExpr>(e);
    const Type *bt = check(x->base, ctx);
    const Type *it = check(x->index, ctx == Ctx::Signal ? Ctx::Guard : ctx);
    if (!bt || !it)
      return nullptr;
    if (bt->kind != TypeKind::Array) {
      error(e->loc, "'" + exprToString(x->base) + "' of type '" + typeName(bt) +
                        "' is not an array");
      return nullptr;
    }
    if (!it->isInteger()) {
      error(x->index->loc, "an array index must be an integer");
      return nullptr;
    }
    int64_t v;
    if (evalConstInt(x->index, v) && (v < bt->indexLo || v > bt->indexHi)) {
      error(x->index->loc, "index " + Twine(v) + " is outside " +
                               Twine(bt->indexLo) + ".." + Twine(bt->indexHi));
      return nullptr;
    }
    return e->type = bt->elem;
  }
  case ExprKind::Field: {
    auto *f = llvm::cast<FieldExpr>(e);
    const Type *bt = check(f->base, ctx);
    if (!bt)
      return nullptr;
    int fi = bt->kind == TypeKind::Record ? bt->fieldIndex(f->field) : -1;
    if (fi < 0) {
      error(e->loc,
            "'" + f->field + "' is not a field of '" + typeName(bt) + "'");
      return nullptr;
    }
    f->fieldIndex = uint32_t(fi);
    return e->type = bt->fields[fi].type;
  }
  case ExprKind::Unary: {
    auto *u = llvm::cast<UnaryExpr>(e);
    const Type *t = check(u->operand, ctx);
    if (!t)
      return nullptr;
    switch (u->op) {
    case UnaryOp::Not:
      if (!t->isBool()) {
        error(e->loc,
              "'not' needs a Boolean operand, not '" + typeName(t) + "'");
        return nullptr;
      }
      return e->type = t;
    case UnaryOp::Neg:
      if (t->isUnsigned64()) {
        error(e->loc, "'-' of a uint64; subtract it from a uint64 instead");
        return nullptr;
      }
      if (!isNumeric(t)) {
        error(e->loc, "'-' needs a number, not '" + typeName(t) + "'");
        return nullptr;
      }
      if (t->isFloat())
        return e->type = t;
      return e->type = t->isReal() ? types.getAnyReal() : types.getInteger();
    case UnaryOp::BitNot:
      if (!t->isInteger()) {
        error(e->loc, "'~' needs an integer, not '" + typeName(t) + "'");
        return nullptr;
      }
      return e->type = t->isUnsigned64() ? t : types.getInteger();
    }
    return nullptr;
  }
  case ExprKind::Binary: {
    auto *bin = llvm::cast<BinaryExpr>(e);
    const Type *a = check(bin->lhs, ctx);
    const Type *b = check(bin->rhs, ctx);
    if (!a || !b)
      return nullptr;
    // In a property (`buf >= 2`, `a + b == 3`), a place compared or
    // counted with numbers stands for its token count; next to a Boolean
    // it still means "is marked".
    bool countsPlaces =
        ctx == Ctx::State && (isComparison(bin->op) || isArithmetic(bin->op));
    if (countsPlaces) {
      auto isPlace = [](const Expr *x) {
        auto *r = llvm::dyn_cast<Ref>(x);
        return r && r->sym.kind == SymKind::Place && r->fields.empty();
      };
      auto count = [&](Expr *x, const Type *&t) {
        uint32_t cap = m.places[llvm::cast<Ref>(x)->sym.index].capacity;
        t = x->type = cap == kInf ? types.getInteger() : types.getRange(0, cap);
      };
      bool lp = isPlace(bin->lhs), rp = isPlace(bin->rhs);
      if (lp && (rp || !b->isBool()))
        count(bin->lhs, a);
      if (rp && (lp || !a->isBool()))
        count(bin->rhs, b);
    }
    StringRef op = spelling(bin->op);
    auto mismatch = [&](StringRef need) -> const Type * {
      error(e->loc, "'" + op + "' needs " + need +
                        ", but the operands have "
                        "types '" +
                        typeName(a) + "' and '" + typeName(b) + "'");
      return nullptr;
    };
    bool inFloat = involvesFloat(a, b) || (a->isAnyReal() && b->isAnyReal() &&
                                           ctx != Ctx::Constant && !hybrid);
    bool shift = bin->op == BinaryOp::Shl || bin->op == BinaryOp::Shr;
    if ((a->isUnsigned64() || (b->isUnsigned64() && !shift)) &&
        a->isInteger() && b->isInteger() && !countsPlaces) {
      const Type *u = shift ? a : commonUnsigned64(e, bin->lhs, bin->rhs, op);
      if (!u)
        return nullptr;
      bool logical = bin->op == BinaryOp::And || bin->op == BinaryOp::Or ||
                     bin->op == BinaryOp::Xor;
      if (logical)
        return mismatch("Boolean operands");
      return e->type = isComparison(bin->op) ? types.getBool() : u;
    }
    switch (bin->op) {
    case BinaryOp::Or:
    case BinaryOp::Xor:
    case BinaryOp::And:
      if (!a->isBool() || !b->isBool())
        return mismatch("Boolean operands");
      return e->type = types.getBool();
    case BinaryOp::Eq:
    case BinaryOp::Ne:
      if (a->isString() || b->isString())
        return commonString(e, bin->lhs, bin->rhs, op)
                   ? e->type = types.getBool()
                   : nullptr;
      if (inFloat && isNumeric(a) && isNumeric(b))
        return commonFloat(e, bin->lhs, bin->rhs, op)
                   ? e->type = types.getBool()
                   : nullptr;
      if (!isComparable(a, b))
        return mismatch("operands of the same type");
      return e->type = types.getBool();
    case BinaryOp::Lt:
    case BinaryOp::Le:
    case BinaryOp::Gt:
    case BinaryOp::Ge:
      if (a->isString() || b->isString())
        return commonString(e, bin->lhs, bin->rhs, op)
                   ? e->type = types.getBool()
                   : nullptr;
      if (!isNumeric(a) || !isNumeric(b))
        return mismatch("numbers or strings");
      if (inFloat && !commonFloat(e, bin->lhs, bin->rhs, op))
        return nullptr;
      return e->type = types.getBool();
    case BinaryOp::BitOr:
    case BinaryOp::BitXor:
    case BinaryOp::BitAnd:
    case BinaryOp::Shl:
    case BinaryOp::Shr:
      if (!a->isInteger() || !b->isInteger())
        return mismatch("integers");
      return e->type = types.getInteger();
    case BinaryOp::Mod:
      if (!a->isInteger() || !b->isInteger())
        return mismatch("integers");
      return e->type = types.getInteger();
    case BinaryOp::Add:
    case BinaryOp::Sub:
    case BinaryOp::Mul:
    case BinaryOp::Div:
      if (!isNumeric(a) || !isNumeric(b))
        return mismatch("numbers");
      if (involvesFloat(a, b))
        return e->type = commonFloat(e, bin->lhs, bin->rhs, op);
      return e->type = (a->isReal() || b->isReal()) ? types.getAnyReal()
                                                    : types.getInteger();
    }
    return nullptr;
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    if (!expectBool(c->cond, ctx, "the condition of '?:'"))
      return nullptr;
    const Type *a = check(c->thenExpr, ctx);
    const Type *b = check(c->elseExpr, ctx);
    if (!a || !b)
      return nullptr;
    if (a->isString() || b->isString())
      return e->type = commonString(e, c->thenExpr, c->elseExpr, "?:");
    if (a->isUnsigned64() || b->isUnsigned64())
      return e->type = commonUnsigned64(e, c->thenExpr, c->elseExpr, "?:");
    if (!isComparable(a, b)) {
      error(e->loc, "the branches of '?:' have types '" + typeName(a) +
                        "' and '" + typeName(b) + "'");
      return nullptr;
    }
    if (involvesFloat(a, b))
      return e->type = commonFloat(e, c->thenExpr, c->elseExpr, "?:");
    if (a->isInteger() && b->isInteger() && a != b)
      return e->type = types.getInteger();
    if (a->isReal() || b->isReal())
      return e->type = types.getAnyReal();
    return e->type = a;
  }
  case ExprKind::Call:
    return checkCall(llvm::cast<CallExpr>(e), ctx);
  }
  return nullptr;
}

void ModuleVerifier::adopt(Expr *e, const Type *ft) {
  if (!e->type || !e->type->isAnyReal())
    return;
  e->type = ft;
  if (auto *u = llvm::dyn_cast<UnaryExpr>(e))
    adopt(u->operand, ft);
  else if (auto *b = llvm::dyn_cast<BinaryExpr>(e)) {
    adopt(b->lhs, ft);
    adopt(b->rhs, ft);
  } else if (auto *c = llvm::dyn_cast<CondExpr>(e)) {
    adopt(c->thenExpr, ft);
    adopt(c->elseExpr, ft);
  } else if (auto *c = llvm::dyn_cast<CallExpr>(e)) {
    if (c->fn != Builtin::Convert && c->fn != Builtin::Trunc &&
        c->fn != Builtin::Bits && c->fn != Builtin::Real32FromBits &&
        c->fn != Builtin::Real64FromBits)
      for (Expr *a : c->args)
        adopt(a, ft);
  }
}

const Type *ModuleVerifier::commonFloat(Expr *e, Expr *a, Expr *b,
                                        StringRef op) {
  const Type *ta = a->type, *tb = b->type;
  const Type *ft = ta->isFloat() ? ta : tb->isFloat() ? tb : types.getFloat(64);
  auto fits = [&](const Type *t) { return t == ft || t->isAnyReal(); };
  if (!fits(ta) || !fits(tb)) {
    const Type *other = fits(ta) ? tb : ta;
    error(e->loc, "'" + op + "' mixes '" + typeName(ft) + "' and '" +
                      typeName(other) + "'; convert one (" +
                      (other->isFloat() || !other->isInteger()
                           ? "real32(x) or real64(x)"
                           : typeName(ft) + "(x)") +
                      ")");
    return nullptr;
  }
  adopt(a, ft);
  adopt(b, ft);
  return ft;
}

void ModuleVerifier::widen(Expr *e, const Type *to) {
  if (!to->isWideString() || !e->type || !e->type->isString() ||
      e->type->isWideString())
    return;
  if (auto *c = llvm::dyn_cast<CondExpr>(e)) {
    widen(c->thenExpr, to);
    widen(c->elseExpr, to);
    if (!c->thenExpr->type->isWideString() ||
        !c->elseExpr->type->isWideString())
      return;
  } else if (!llvm::isa<StringLit>(e)) {
    return;
  }
  e->type = types.getString(e->type->maxLen, true);
}

const Type *ModuleVerifier::commonString(Expr *e, Expr *a, Expr *b,
                                         StringRef op) {
  const Type *ta = a->type, *tb = b->type;
  if (!ta->isString() || !tb->isString()) {
    error(e->loc, "'" + op +
                      "' needs two strings, but the operands have "
                      "types '" +
                      typeName(ta) + "' and '" + typeName(tb) + "'");
    return nullptr;
  }
  widen(a, tb);
  widen(b, ta);
  ta = a->type;
  tb = b->type;
  if (ta->width != tb->width) {
    error(e->loc, "'" + op + "' mixes '" + typeName(ta) + "' and '" +
                      typeName(tb) + "'; convert one (wstring[n](x) or " +
                      "string[n](x))");
    return nullptr;
  }
  return types.getString(std::max(ta->maxLen, tb->maxLen), ta->isWideString());
}

bool ModuleVerifier::fitsUnsigned64(const Type *to, Expr *value) {
  const Type *from = value->type;
  if (to->isUnsigned64() == from->isUnsigned64())
    return true;
  int64_t v;
  // A constant may go either way when the value fits.
  return to->isUnsigned64() && evalConstInt(value, v) && v >= 0;
}

const Type *ModuleVerifier::commonUnsigned64(Expr *e, Expr *a, Expr *b,
                                             StringRef op) {
  const Type *u = a->type->isUnsigned64() ? a->type : b->type;
  for (Expr *x : {a, b})
    if (!fitsUnsigned64(u, x)) {
      error(e->loc, "'" + op + "' mixes '" + typeName(u) + "' and '" +
                        typeName(x->type) + "'; convert one (uint64(x) or " +
                        "int64(x))");
      return nullptr;
    }
  return u;
}

const Type *ModuleVerifier::checkStringCall(CallExpr *c) {
  // Operand kinds per built-in: 's' a string, 'i' an integer.
  StringRef shape = llvm::StringSwitch<StringRef>(spelling(c->fn))
                        .Case("len", "s")
                        .Cases("left", "right", "code", "si")
                        .Case("with_code", "sii")
                        .Cases("mid", "delete", "sii")
                        .Cases("concat", "find", "ss")
                        .Case("insert", "ssi")
                        .Case("replace", "ssii")
                        .StartsWith("format_", "i")
                        .StartsWith("parse_", "s")
                        .Default("");
  for (size_t i = 0; i < c->args.size(); ++i) {
    const Type *t = c->args[i]->type;
    bool ok = shape[i] == 's' ? t->isString() : t->isInteger();
    if (!ok) {
      error(c->args[i]->loc, spelling(c->fn) + "() needs " +
                                 (shape[i] == 's' ? "a string" : "an integer") +
                                 " as operand " + Twine(i + 1) + ", not '" +
                                 typeName(t) + "'");
      return nullptr;
    }
  }
  Expr *x = c->args[0];
  if (shape.startswith("ss")) {
    const Type *both = commonString(c, c->args[0], c->args[1], spelling(c->fn));
    if (!both)
      return nullptr;
    if (c->fn == Builtin::Find)
      return c->type = types.getInteger();
    // The result holds both operands whole; an assignment cuts it.
    uint64_t len =
        uint64_t(c->args[0]->type->maxLen) + c->args[1]->type->maxLen;
    return c->type = types.getString(uint32_t(std::min<uint64_t>(len, 65535)),
                                     both->isWideString());
  }
  if (c->fn == Builtin::Len || c->fn == Builtin::Code || shape == "s")
    return c->type = types.getInteger(); // len, code, parse_*
  if (shape == "i") // format_*: the longest, LTIME's, is 35 characters
    return c->type = types.getString(40, false);
  return c->type = x->type; // left, right, mid, delete: no longer than s
}

const Type *ModuleVerifier::checkCall(CallExpr *c, Ctx ctx) {
  for (Expr *a : c->args)
    if (!check(a, ctx))
      return nullptr;
  if (isStringBuiltin(c->fn))
    return checkStringCall(c);
  switch (c->fn) {
  case Builtin::Between:
    if (c != resetValue) {
      error(c->loc, "between() is a hybrid reset to an interval: only the "
                    "whole value assigned to a real variable");
      return nullptr;
    }
    for (Expr *a : c->args)
      if (!isNumeric(a->type)) {
        error(a->loc,
              "between() needs numbers, not '" + typeName(a->type) + "'");
        return nullptr;
      }
    return c->type = types.getAnyReal();
  case Builtin::Convert:
    if (c->to->isString() || c->args[0]->type->isString()) {
      const Type *from = c->args[0]->type;
      bool ok =
          c->to->isString()
              ? (isNumeric(from) || from->isBool() || from->isString())
              : (from->isString() &&
                 (c->to->isBool() || c->to->isInteger() || c->to->isFloat()));
      if (!ok || from->isReal()) {
        error(c->loc, "cannot convert a value of type '" + typeName(from) +
                          "' with " + calleeSpelling(c) + "()");
        return nullptr;
      }
      adopt(c->args[0], types.getFloat(64));
      return c->type = c->to;
    }
    if (c->to->isBool()) {
      error(c->loc, "bool() converts a string; compare a number with 0");
      return nullptr;
    }
    break;
  default:
    break;
  }
  bool anyFloat = false, anyReal = false; // anyReal: hybrid or constant
  for (Expr *a : c->args) {
    const Type *t = a->type;
    if (!isNumeric(t) && !(c->fn == Builtin::Convert && t->isBool())) {
      error(a->loc,
            calleeSpelling(c) + "() needs numbers, not '" + typeName(t) + "'");
      return nullptr;
    }
    anyFloat |= t->isFloat();
    anyReal |= t->isReal();
  }
  Expr *x = c->args[0];
  switch (c->fn) {
  case Builtin::Convert:
    if (x->type->isAnyReal())
      adopt(x, types.getFloat(64));
    else if (x->type->isReal()) {
      error(x->loc, "a hybrid 'real' cannot be converted");
      return nullptr;
    }
    return c->type = c->to;
  case Builtin::Bits:
    if (!x->type->isFloat()) {
      error(x->loc, "bits() needs a float, not '" + typeName(x->type) + "'");
      return nullptr;
    }
    return c->type = types.getInteger();
  case Builtin::Real32FromBits:
  case Builtin::Real64FromBits:
    if (!x->type->isInteger()) {
      error(x->loc, spelling(c->fn) + "() needs an integer, not '" +
                        typeName(x->type) + "'");
      return nullptr;
    }
    return c->type = types.getFloat(c->fn == Builtin::Real32FromBits ? 32 : 64);
  case Builtin::Trunc:
    if (!x->type->isFloat() && !x->type->isAnyReal()) {
      error(x->loc, "trunc() needs a float, not '" + typeName(x->type) + "'");
      return nullptr;
    }
    adopt(x, types.getFloat(64));
    return c->type = types.getInteger();
  case Builtin::Min:
  case Builtin::Max:
  case Builtin::Abs:
    if (x->type->isUnsigned64() ||
        (c->args.size() == 2 && c->args[1]->type->isUnsigned64()))
      return c->type = c->args.size() == 1
                           ? x->type
                           : commonUnsigned64(c, c->args[0], c->args[1],
                                              spelling(c->fn));
    if (anyFloat) {
      return c->type =
                 c->args.size() == 1
                     ? x->type
                     : commonFloat(c, c->args[0], c->args[1], spelling(c->fn));
    }
    return c->type = anyReal ? types.getAnyReal() : types.getInteger();
  default: // the float functions
    // Of hybrid reals too (a tank's outflow k*sqrt(h)): discretise
    // integrates such rates; nothing else computes with hybrid reals.
    if (anyReal && !anyFloat)
      return c->type = types.getAnyReal();
    for (Expr *a : c->args)
      if (!a->type->isFloat() && !a->type->isAnyReal()) {
        error(a->loc, spelling(c->fn) + "() needs a float, not '" +
                          typeName(a->type) + "'; convert it (real64(x))");
        return nullptr;
      }
    if (c->args.size() == 2)
      return c->type = commonFloat(c, c->args[0], c->args[1], spelling(c->fn));
    return c->type = x->type;
  }
}

const Type *ModuleVerifier::checkTarget(Expr *e) {
  // Find the root name of the target.
  Expr *root = e;
  while (true) {
    if (auto *x = llvm::dyn_cast<IndexExpr>(root))
      root = x->base;
    else if (auto *f = llvm::dyn_cast<FieldExpr>(root))
      root = f->base;
    else
      break;
  }
  auto *r = llvm::dyn_cast<Ref>(root);
  if (!r) {
    error(e->loc, "'" + exprToString(e) + "' cannot be assigned");
    return nullptr;
  }
  const Type *t = check(e, Ctx::Guard);
  if (!t)
    return nullptr;
  switch (r->sym.kind) {
  case SymKind::Var:
    return t;
  case SymKind::Port: {
    const Port &p = m.ports[r->sym.index];
    if (p.isInput()) {
      error(e->loc, "cannot assign to input '" + p.name + "'");
      return nullptr;
    }
    if (p.definition) {
      error(e->loc, "cannot assign to output '" + p.name +
                        "': it is defined by an expression");
      return nullptr;
    }
    return t;
  }
  case SymKind::Place:
    error(e->loc, "cannot assign to place '" + r->name +
                      "'; tokens move only along flow arcs");
    return nullptr;
  case SymKind::LoopVar:
    error(e->loc, "cannot assign to loop variable '" + r->name + "'");
    return nullptr;
  default:
    error(e->loc, "'" + exprToString(e) + "' cannot be assigned");
    return nullptr;
  }
}

void ModuleVerifier::checkBlock(Block b) {
  for (Stmt *s : b)
    checkStmt(s);
}

void ModuleVerifier::checkStmt(Stmt *s) {
  switch (s->getKind()) {
  case StmtKind::Assign: {
    auto *a = llvm::cast<AssignStmt>(s);
    const Type *tt = checkTarget(a->target);
    auto *reset = llvm::dyn_cast<CallExpr>(a->value);
    if (reset && reset->fn == Builtin::Between) {
      if (tt && !tt->isReal()) {
        error(a->value->loc, "between() resets a hybrid real; '" +
                                 exprToString(a->target) + "' is not one");
        return;
      }
      resetValue = reset;
    }
    const Type *vt = check(a->value, Ctx::Guard);
    resetValue = nullptr;
    if (!tt || !vt)
      return;
    if (reset && reset->fn == Builtin::Between) {
      auto lo = evalConstReal(reset->args[0]),
           hi = evalConstReal(reset->args[1]);
      if (lo && hi && *lo > *hi)
        error(a->value->loc, "between() of an empty interval");
    }
    if (!takes(tt, a->value)) {
      error(a->value->loc, "cannot assign a value of type '" +
                               typeName(a->value->type) + "' to '" +
                               exprToString(a->target) + "' of type '" +
                               typeName(tt) + "'");
      return;
    }
    int64_t v;
    if (tt->isInteger() && evalConstInt(a->value, v) &&
        (v < tt->lo || v > tt->hi) &&
        !(tt->kind == TypeKind::Int && tt->overflow == Overflow::Wrap))
      error(a->value->loc, "value " + Twine(v) + " is outside the type '" +
                               typeName(tt) + "' of '" +
                               exprToString(a->target) + "'");
    return;
  }
  case StmtKind::If: {
    auto *i = llvm::cast<IfStmt>(s);
    for (const IfArm &arm : i->arms) {
      expectBool(arm.cond, Ctx::Guard, "an 'if' condition");
      checkBlock(arm.body);
    }
    checkBlock(i->elseBody);
    return;
  }
  case StmtKind::Case: {
    auto *c = llvm::cast<CaseStmt>(s);
    const Type *st = check(c->selector, Ctx::Guard);
    if (st && !st->isInteger() && st->kind != TypeKind::Enum) {
      error(c->selector->loc, "a case selector must be an integer or an "
                              "enumeration, not '" +
                                  typeName(st) + "'");
      st = nullptr;
    }
    for (const CaseArm &arm : c->arms) {
      for (const CaseLabel &l : arm.labels) {
        for (Expr *x : {l.lo, l.hi}) {
          if (!x)
            continue;
          const Type *lt = check(x, Ctx::Constant);
          int64_t v;
          if (lt && !evalConstInt(x, v))
            error(x->loc, "a case label must be a constant");
          else if (lt && st && !isComparable(st, lt))
            error(x->loc, "case label of type '" + typeName(lt) +
                              "' does not match the selector's type '" +
                              typeName(st) + "'");
        }
      }
      checkBlock(arm.body);
    }
    checkBlock(c->elseBody);
    return;
  }
  case StmtKind::For: {
    auto *f = llvm::cast<ForStmt>(s);
    for (Expr *bound : {f->lo, f->hi})
      if (const Type *t = check(bound, Ctx::Guard); t && !t->isInteger())
        error(bound->loc, "the bounds of a 'for' loop must be integers, not '" +
                              typeName(t) + "'");
    loopVars.push_back(f->var);
    checkBlock(f->body);
    loopVars.pop_back();
    return;
  }
  case StmtKind::While: {
    auto *w = llvm::cast<WhileStmt>(s);
    expectBool(w->cond, Ctx::Guard,
               w->testAfter ? "a 'repeat' condition" : "a 'while' condition");
    checkBlock(w->body);
    return;
  }
  }
}

void ModuleVerifier::checkDefinitionCycles() {
  // An output defined (transitively) in terms of itself has no value.
  std::vector<uint8_t> state(m.ports.size(), 0); // 0 new, 1 active, 2 done
  std::function<bool(uint32_t)> visit;
  std::function<bool(const Expr *)> walk = [&](const Expr *e) -> bool {
    switch (e->getKind()) {
    case ExprKind::Ref: {
      auto *r = llvm::cast<Ref>(e);
      if (r->sym.kind == SymKind::Port && m.ports[r->sym.index].definition)
        return visit(r->sym.index);
      return true;
    }
    case ExprKind::Index:
      return walk(llvm::cast<IndexExpr>(e)->base) &&
             walk(llvm::cast<IndexExpr>(e)->index);
    case ExprKind::Field:
      return walk(llvm::cast<FieldExpr>(e)->base);
    case ExprKind::Unary:
      return walk(llvm::cast<UnaryExpr>(e)->operand);
    case ExprKind::Binary:
      return walk(llvm::cast<BinaryExpr>(e)->lhs) &&
             walk(llvm::cast<BinaryExpr>(e)->rhs);
    case ExprKind::Cond: {
      auto *c = llvm::cast<CondExpr>(e);
      return walk(c->cond) && walk(c->thenExpr) && walk(c->elseExpr);
    }
    case ExprKind::Call:
      for (const Expr *a : llvm::cast<CallExpr>(e)->args)
        if (!walk(a))
          return false;
      return true;
    default:
      return true;
    }
  };
  visit = [&](uint32_t p) -> bool {
    if (state[p] == 2)
      return true;
    if (state[p] == 1) {
      error(m.ports[p].definitionLoc,
            "output '" + m.ports[p].name + "' is defined in terms of itself");
      return false;
    }
    state[p] = 1;
    bool ok = walk(m.ports[p].definition);
    state[p] = 2;
    return ok;
  };
  for (uint32_t p = 0; p < m.ports.size(); ++p)
    if (m.ports[p].definition && !visit(p))
      return;
}

void ModuleVerifier::checkEventCycles() {
  // u listens to t: edge t -> u. A cycle would make a step force itself.
  size_t n = m.transitions.size();
  std::vector<std::vector<uint32_t>> succ(n);
  bool any = false;
  for (uint32_t u = 0; u < n; ++u)
    for (const EventSource &s : m.transitions[u].events())
      if (!s.fromPort && s.index < n) {
        succ[s.index].push_back(u);
        any = true;
      }
  if (!any)
    return;
  std::vector<uint8_t> color(n, 0);
  std::vector<uint32_t> stack;
  // Iterative DFS so that long event chains cannot exhaust the stack.
  for (uint32_t root = 0; root < n; ++root) {
    if (color[root])
      continue;
    std::vector<std::pair<uint32_t, size_t>> work{{root, 0}};
    color[root] = 1;
    stack.push_back(root);
    while (!work.empty()) {
      auto &[v, i] = work.back();
      if (i < succ[v].size()) {
        uint32_t w = succ[v][i++];
        if (color[w] == 1) {
          std::string path;
          auto it = std::find(stack.begin(), stack.end(), w);
          for (; it != stack.end(); ++it)
            path += (m.transitions[*it].name + " -> ").str();
          path += m.transitions[w].name.str();
          error(m.transitions[w].loc,
                "event cycle among forced transitions: " + path);
          return;
        }
        if (color[w] == 0) {
          color[w] = 1;
          stack.push_back(w);
          work.push_back({w, 0});
        }
      } else {
        color[v] = 2;
        stack.pop_back();
        work.pop_back();
      }
    }
  }
}

void ModuleVerifier::checkInstancesAndConnections() {
  for (Instance &i : m.instances) {
    i.module = d.lookupModule(i.moduleName);
    if (!i.module)
      error(i.moduleLoc.isValid() ? i.moduleLoc : i.loc,
            "unknown module '" + i.moduleName + "'" +
                didYouMean(i.moduleName, moduleNames()));
    else if (i.module->isSystem)
      error(i.moduleLoc.isValid() ? i.moduleLoc : i.loc,
            "'" + i.moduleName + "' is a system and cannot be instantiated");
  }
  // Resolve an endpoint to (module, port index).
  auto resolve = [&](Endpoint &e, const Module *&owner) -> int {
    owner = &m;
    if (!e.instance.empty() && m.lookup(e.instance).kind != SymKind::Instance) {
      std::string whole = (e.instance + "." + e.port).str();
      if (m.findPort(whole) >= 0) {
        e.port = d.save(whole);
        e.instance = "";
      }
    }
    if (!e.instance.empty()) {
      Symbol s = m.lookup(e.instance);
      if (s.kind != SymKind::Instance) {
        error(e.loc,
              "'" + e.instance + "' is not an instance in '" + m.name + "'");
        return -1;
      }
      owner = m.instances[s.index].module;
      if (!owner)
        return -1;
    }
    int p = owner->findPort(e.port);
    if (p < 0) {
      error(e.loc, "module '" + owner->name + "' has no port '" + e.port + "'");
      return -1;
    }
    return p;
  };
  auto endName = [](const Endpoint &e) {
    return e.instance.empty() ? e.port.str()
                              : (e.instance + "." + e.port).str();
  };
  llvm::StringMap<SMLoc> driven;
  for (Connection &c : m.connections) {
    const Module *fm, *tm;
    int fp = resolve(c.from, fm);
    int tp = resolve(c.to, tm);
    if (fp < 0 || tp < 0)
      continue;
    const Port &f = fm->ports[fp];
    const Port &t = tm->ports[tp];
    bool fromOk = c.from.instance.empty() ? f.isInput() : f.isOutput();
    bool toOk = c.to.instance.empty() ? t.isOutput() : t.isInput();
    if (!fromOk) {
      error(c.from.loc, "'" + endName(c.from) + "' is " +
                            (f.isInput() ? "an input" : "an output") +
                            " and cannot drive a connection");
      continue;
    }
    if (!toOk) {
      error(c.to.loc, "'" + endName(c.to) + "' is " +
                          (t.isInput() ? "an input" : "an output") +
                          " and cannot be driven by a connection");
      continue;
    }
    if (f.kind != t.kind) {
      error(c.loc, "cannot connect " + spelling(f.kind) + " port '" +
                       endName(c.from) + "' to " + spelling(t.kind) +
                       " port '" + endName(c.to) + "'");
      continue;
    }
    if (f.kind == PortKind::Data && f.type != t.type) {
      error(c.loc, "cannot connect '" + endName(c.from) + "' of type '" +
                       typeName(f.type) + "' to '" + endName(c.to) +
                       "' of type '" + typeName(t.type) + "'");
      continue;
    }
    if (c.to.instance.empty() && (t.definition || t.init)) {
      error(c.to.loc, "output '" + t.name +
                          "' is defined in the module and cannot also be "
                          "driven by a connection");
      continue;
    }
    // Several events may be merged into one event input; a signal has one
    // driver.
    if (f.kind != PortKind::Event) {
      auto [it, inserted] = driven.try_emplace(endName(c.to), c.loc);
      if (!inserted) {
        error(c.loc, "'" + endName(c.to) + "' is driven twice");
        diag.note(it->second, "first driven here");
      }
    }
  }
}

void ModuleVerifier::run() {
  hybrid = hasHybridParts(m);
  checkNames();
  checkPorts();
  checkVars();
  checkPlaces();
  for (uint32_t i = 0; i < m.transitions.size(); ++i)
    checkTransition(i);
  checkFlows();
  checkInvariants();
  checkInstancesAndConnections();
  checkAttributes();
  if (!diag.hadError()) {
    checkDefinitionCycles();
    checkEventCycles();
  }
}

/// Instantiation must be a tree: report a module that contains itself.
void checkRecursion(Design &d, DiagEngine &diag) {
  llvm::DenseMap<const Module *, uint8_t> color;
  std::function<bool(const Module *)> visit = [&](const Module *m) -> bool {
    uint8_t &c = color[m];
    if (c == 2)
      return true;
    c = 1;
    for (const Instance &i : m->instances) {
      if (!i.module)
        continue;
      uint8_t ci = color.lookup(i.module);
      if (ci == 1) {
        diag.error(i.loc, "recursive instantiation: module '" + i.module->name +
                              "' contains itself through '" + m->name + "." +
                              i.name + "'");
        return false;
      }
      if (ci == 0 && !visit(i.module))
        return false;
    }
    color[m] = 2;
    return true;
  };
  for (auto &m : d.modules)
    if (!visit(m.get()))
      return;
}

const Port *ModuleVerifier::inputRead(const Port &p) {
  if (p.isInput())
    return &p;
  return p.definition ? inputRead(p.definition) : nullptr;
}

const Port *ModuleVerifier::inputRead(const Expr *e) {
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    return r->sym.kind == SymKind::Port ? inputRead(m.ports[r->sym.index])
                                        : nullptr;
  }
  case ExprKind::Index: {
    auto *x = llvm::cast<IndexExpr>(e);
    const Port *p = inputRead(x->base);
    return p ? p : inputRead(x->index);
  }
  case ExprKind::Field:
    return inputRead(llvm::cast<FieldExpr>(e)->base);
  case ExprKind::Unary:
    return inputRead(llvm::cast<UnaryExpr>(e)->operand);
  case ExprKind::Binary: {
    auto *b = llvm::cast<BinaryExpr>(e);
    const Port *p = inputRead(b->lhs);
    return p ? p : inputRead(b->rhs);
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    for (const Expr *x : {c->cond, c->thenExpr, c->elseExpr})
      if (const Port *p = inputRead(x))
        return p;
    return nullptr;
  }
  case ExprKind::Call:
    for (const Expr *a : llvm::cast<CallExpr>(e)->args)
      if (const Port *p = inputRead(a))
        return p;
    return nullptr;
  default:
    return nullptr;
  }
}

} // namespace

bool netlift::net::verifyPredicate(Design &d, Module &m, Expr *e,
                                   DiagEngine &diag) {
  return ModuleVerifier(d, m, diag).checkPredicate(e);
}

bool netlift::net::verifyDesign(Design &d, DiagEngine &diag) {
  unsigned before = diag.numErrors();
  for (auto &m : d.modules)
    ModuleVerifier(d, *m, diag).run();
  if (diag.numErrors() == before)
    checkRecursion(d, diag);
  return diag.numErrors() == before;
}
