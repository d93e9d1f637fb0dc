//===- LowerInstanceArrays.cpp - arrays of function block instances -------===//
//
// `timers : ARRAY[1..8] OF TON` (IEC 61131-3 3rd edition, CODESYS,
// TwinCAT): every element is an instance of its own, flattened like any
// instance into the NetIR variables of its members under the prefix
// `timers_1` (`timers_1_2` for two dimensions, `timers_m1` for index -1).
// An element chosen by a constant index is that instance; one chosen at
// run time (`timers[i](IN := ...)`, `x := timers[i].Q`) is a choice over
// the elements, the index checked against the array's bounds as any
// index is (a scan variable `timers_index` of range lo..hi: leaving it is
// a run-time error with a trace).
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

std::string Lowering::elementPath(const std::string &path,
                                  llvm::ArrayRef<int64_t> index) {
  std::string p = path;
  for (int64_t i : index)
    p += i < 0 ? "_m" + std::to_string(-i) : "_" + std::to_string(i);
  return p;
}

void netlift::plc::detail::forEachIndex(
    const PType *array, llvm::function_ref<void(llvm::ArrayRef<int64_t>)> fn) {
  std::vector<int64_t> index;
  for (auto &[lo, hi] : array->dims)
    index.push_back(lo);
  for (;;) {
    fn(index);
    size_t d = index.size();
    while (d-- > 0 && ++index[d] > array->dims[d].second)
      index[d] = array->dims[d].first;
    if (d == size_t(-1))
      return;
  }
}

/// The initialiser of the element at `index` (nested rows, repeats
/// counted; null where none is given).
static Initializer *elementInitializer(Initializer *init, const PType *array,
                                       llvm::ArrayRef<int64_t> index) {
  for (size_t d = 0; d < index.size() && init; ++d) {
    if (init->kind != Initializer::Array)
      return nullptr;
    int64_t wanted = index[d] - array->dims[d].first, at = 0;
    Initializer *found = nullptr;
    for (auto &[repeat, inner] : init->elems) {
      at += std::max<int64_t>(repeat, 1);
      if (wanted < at) {
        found = inner;
        break;
      }
    }
    init = found;
  }
  return init;
}

void Lowering::declareInstances(const std::string &path, const PType *t,
                                Initializer *init) {
  if (t->kind == PTypeKind::FunctionBlock) {
    declareInstance(path, t->fb, init);
    return;
  }
  forEachIndex(t, [&](llvm::ArrayRef<int64_t> index) {
    std::string element = elementPath(path, index);
    std::string source = sourcePaths[path] + "[";
    for (size_t d = 0; d < index.size(); ++d)
      source += (d ? "," : "") + std::to_string(index[d]);
    sourcePaths[element] = source + "]";
    declareInstances(element, t->elem, elementInitializer(init, t, index));
  });
}

std::vector<std::string> Lowering::instancePaths(const std::string &path,
                                                 const PType *t) {
  if (t->kind == PTypeKind::FunctionBlock)
    return {path};
  std::vector<std::string> out;
  forEachIndex(t, [&](llvm::ArrayRef<int64_t> index) {
    for (std::string &p : instancePaths(elementPath(path, index), t->elem))
      out.push_back(std::move(p));
  });
  return out;
}

std::vector<Lowering::InstanceChoice>
Lowering::instanceChoices(Expr *e, Frame &f, Sink &pre) {
  if (e->kind == ExprKind::Name) {
    if (!e->var)
      refuse(e->loc, "internal: an unresolved instance");
    if (auto alias = f.instanceAliases.find(e->var);
        alias != f.instanceAliases.end())
      return {{nullptr, alias->second}};
    return {{nullptr, e->var->owner
                          ? f.prefixOf(e->var) + sanitize(e->var->name)
                          : sanitize(e->var->name)}};
  }
  // An instance held by an instance (`outer.inner`).
  if (e->kind == ExprKind::Field && e->var && e->base()->type &&
      e->base()->type->kind == PTypeKind::FunctionBlock) {
    std::vector<InstanceChoice> outer = instanceChoices(e->base(), f, pre);
    for (InstanceChoice &c : outer)
      c.path += "." + sanitize(e->var->name);
    return outer;
  }
  if (e->kind != ExprKind::Index || !e->base()->type ||
      e->base()->type->kind != PTypeKind::Array)
    refuse(e->loc, "function block instances are named directly or by an "
                   "index into an array of instances (instances in "
                   "structures are not supported)");
  std::vector<InstanceChoice> bases = instanceChoices(e->base(), f, pre);
  const PType *at = e->base()->type;
  // Each index: one value known now, or every value of its dimension
  // tested against a checked copy of it.
  std::vector<std::vector<std::pair<NExpr *, int64_t>>> perDim;
  for (size_t d = 0; d < at->dims.size(); ++d) {
    auto [lo, hi] = at->dims[d];
    Expr *ix = e->operands[d + 1];
    std::vector<std::pair<NExpr *, int64_t>> values;
    if (auto c = constValue(ix, f)) {
      if (*c < lo || *c > hi)
        refuse(ix->loc, "index " + Twine(*c) + " is outside " + Twine(lo) +
                            ".." + Twine(hi) + " of '" + e->base()->name + "'");
      values.push_back({nullptr, *c});
    } else {
      std::string stem =
          (e->base()->kind == ExprKind::Name ? sanitize(e->base()->name)
                                             : std::string("instance")) +
          "_index";
      std::string k =
          scanVariable(stem, design.types.getRange(lo, hi), lo, ix->loc);
      pre.push_back(b.assign(b.ref(k, ix->loc), expr(ix, f, pre), ix->loc));
      for (int64_t i = lo; i <= hi; ++i)
        values.push_back({b.binary(net::BinaryOp::Eq, b.ref(k, ix->loc),
                                   b.intLit(i, ix->loc), ix->loc),
                          i});
    }
    perDim.push_back(std::move(values));
  }
  auto both = [&](NExpr *x, NExpr *y) {
    return !x ? y : !y ? x : b.binary(net::BinaryOp::And, x, y, e->loc);
  };
  std::vector<InstanceChoice> out;
  std::vector<int64_t> index(perDim.size());
  std::function<void(const InstanceChoice &, size_t, NExpr *)> expand =
      [&](const InstanceChoice &base, size_t d, NExpr *test) {
        if (d == perDim.size()) {
          out.push_back({test, elementPath(base.path, index)});
          return;
        }
        for (auto &[t, i] : perDim[d]) {
          index[d] = i;
          expand(base, d + 1, both(test, t));
        }
      };
  for (const InstanceChoice &base : bases)
    expand(base, 0, base.test);
  return out;
}

bool Lowering::chosenAtRunTime(Expr *instance, Frame &f) {
  for (Expr *x = instance; x && x->kind == ExprKind::Index; x = x->base())
    for (size_t i = 1; i < x->operands.size(); ++i)
      if (!constValue(x->operands[i], f))
        return true;
  return false;
}

std::string Lowering::instancePath(Expr *e, Frame &f) {
  if (chosenAtRunTime(e, f))
    refuse(e->loc, "an instance chosen by an index known only at run time "
                   "is called, or its inputs and outputs are read or "
                   "assigned, but it is not passed or bound");
  Sink none;
  return instanceChoices(e, f, none).front().path;
}

std::string Lowering::boundInstance(Expr *argument, Frame &f) {
  if (argument->selfInstance) { // THIS^: the running instance
    std::string path = f.running().second;
    return path.empty() ? path : path.substr(0, path.size() - 1);
  }
  if (auto chosen = inOutInstances.find(argument);
      chosen != inOutInstances.end())
    return chosen->second;
  if (auto place = inOutPlaces.find(argument); place != inOutPlaces.end()) {
    if (auto *r = llvm::dyn_cast<net::Ref>(place->second))
      return r->name.str();
    refuse(argument->loc, "internal: an instance in an element");
  }
  if (throughReference(argument)) {
    Sink none;
    NExpr *place =
        placeThroughReference(argument, f, none, "passed to a VAR_IN_OUT");
    if (auto *r = llvm::dyn_cast<net::Ref>(place))
      return r->name.str();
    refuse(argument->loc, "internal: an instance in an element");
  }
  return instancePath(argument, f);
}

void Lowering::emitChoice(llvm::ArrayRef<NExpr *> tests,
                          std::vector<Sink> &bodies, Sink &out, SMLoc at) {
  if (bodies.size() == 1) {
    out.insert(out.end(), bodies[0].begin(), bodies[0].end());
    return;
  }
  std::vector<net::IfArm> arms;
  for (size_t i = 0; i + 1 < bodies.size(); ++i)
    arms.push_back({tests[i], design.copy(llvm::ArrayRef<NStmt *>(bodies[i]))});
  out.push_back(b.ifStmt(arms, true, bodies.back(), at));
}

NExpr *Lowering::valueOnce(NExpr *value, const PType *type,
                           const std::string &stem, Sink &out, SMLoc at) {
  if (llvm::isa<net::IntLit, net::BoolLit, net::Ref>(value))
    return value;
  std::string tmp = unique(stem + "_value");
  declareTemp(tmp, type, at);
  out.push_back(b.assign(b.ref(tmp, at), value, at));
  return b.ref(tmp, at);
}

void Lowering::callChosenInstance(Expr *call, Pou *fb,
                                  llvm::ArrayRef<InstanceChoice> choices,
                                  Frame &f, Sink &out) {
  std::vector<NExpr *> tests;
  std::vector<Sink> bodies(choices.size());
  for (size_t i = 0; i < choices.size(); ++i) {
    tests.push_back(choices[i].test);
    instanceCall(call, fb, choices[i].path, f, bodies[i]);
  }
  emitChoice(tests, bodies, out, call->loc);
}

void Lowering::elementCall(Expr *call, Frame &f, Sink &out) {
  Expr *instance = call->operands[0];
  std::vector<InstanceChoice> choices = instanceChoices(instance, f, out);
  callChosenInstance(call, instance->type->fb, choices, f, out);
}

bool Lowering::memberOfChosenInstance(Expr *e, Frame &f) {
  return e->kind == ExprKind::Field && e->base()->type &&
         e->base()->type->kind == PTypeKind::FunctionBlock &&
         e->base()->kind == ExprKind::Index && !throughReference(e) &&
         chosenAtRunTime(e->base(), f);
}

NExpr *Lowering::chosenMemberRead(Expr *e, Frame &f, Sink &pre) {
  std::vector<InstanceChoice> choices = instanceChoices(e->base(), f, pre);
  std::string member = "." + sanitize(e->var->name);
  NExpr *r = nullptr;
  for (auto it = choices.rbegin(); it != choices.rend(); ++it) {
    if (f.external)
      externallyRead.insert(it->path + member);
    NExpr *value = b.ref(it->path + member, e->loc);
    r = r ? b.cond(it->test, value, r, e->loc) : value;
  }
  return r;
}

void Lowering::chosenMemberWrite(Stmt *s, NExpr *value, Frame &f, Sink &out) {
  std::vector<InstanceChoice> choices =
      instanceChoices(s->target->base(), f, out);
  std::string member = "." + sanitize(s->target->var->name);
  // Evaluated once, before the choice.
  value = valueOnce(value, s->value->type, sanitize(s->target->var->name), out,
                    s->loc);
  std::vector<NExpr *> tests;
  std::vector<Sink> bodies(choices.size());
  for (size_t i = 0; i < choices.size(); ++i) {
    noteClockBound(choices[i].path + member, s->value, f, s->loc);
    tests.push_back(choices[i].test);
    assign(b.ref(choices[i].path + member, s->loc), value, s->target->type,
           s->value, bodies[i], s->loc);
  }
  emitChoice(tests, bodies, out, s->loc);
}

NExpr *Lowering::arrayBound(Expr *call, Frame &f) {
  SMLoc at = call->loc;
  Expr *array = call->args[0].value;
  int64_t dim = call->intValue; // Sema's: a constant in 1..dimensions
  // An ARRAY[*] is the argument its call was given, perhaps itself a
  // VAR_IN_OUT of the caller's: followed until the bounds are known.
  const PType *t = baseOf(array->type);
  Frame *rf = &f;
  while (t->anyBounds) {
    auto source = array->kind == ExprKind::Name && array->var
                      ? rf->aliasSources.find(array->var)
                      : rf->aliasSources.end();
    if (source == rf->aliasSources.end())
      refuse(at, "internal: the array an ARRAY[*] is given is not known here");
    array = source->second.first;
    rf = source->second.second;
    t = baseOf(array->type);
  }
  auto [lo, hi] = t->dims[size_t(dim - 1)];
  return b.intLit(StringRef(call->name).upper() == "LOWER_BOUND" ? lo : hi, at);
}
