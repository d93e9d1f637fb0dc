//===- LowerEnvironment.cpp - what the translated POU's caller chooses ----===//
//
// A function block translated as the top (`--top FB`) runs as a program
// does, once per scan, and its caller becomes the environment. NetIR's
// input ports carry scalars and strings, so what the caller passes whole —
// an array or structure input, a VAR_IN_OUT (the caller's variable, which
// the caller may change between two calls) — is chosen scalar by scalar:
// one free input port per scalar, copied into the variable at the start of
// every scan. A VAR_IN_OUT is also an output port, so what the block leaves
// in the caller's variable is observable. Choosing every value afresh each
// scan covers whatever the caller does between calls, the value it left
// unchanged included; it is the sound side of not knowing the caller.
//
// The same choice serves what the runtime answers: a structured output of
// an environment block (chosen at each call), the result of an environment
// function (TwinCAT's LREAL_TO_FMTSTR), and the clock TIME() reads.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

/// The most scalars netlift gives free input ports for one value: past it,
/// a translation would be made of ports, and an exploration could not
/// choose them anyway.
static constexpr size_t kMaxEnvironmentScalars = 4096;

void Lowering::addFreeInputPort(const std::string &port, const PType *t,
                                const std::string &shown, SMLoc at) {
  if (t->kind == PTypeKind::Bool) {
    b.addPort(port, net::PortKind::Cond, net::PortDir::In, nullptr, at);
    return;
  }
  const net::Type *nt = netType(t, at, "input " + shown);
  // A free value of its full type: an exploration asks for a range where
  // it must enumerate one (ExplorationSetup).
  if ((t->kind == PTypeKind::Int && !t->isSubrange) ||
      t->kind == PTypeKind::Time || t->kind == PTypeKind::Date)
    b.addAttribute(port, net::kNeedsRangeAttribute,
                   design.save(shown + " : " + t->str()), at);
  b.addPort(port, net::PortKind::Data, net::PortDir::In, nt, at);
}

Lowering::ChosenScalars Lowering::chooseScalars(
    const std::string &name, const std::string &portStem, const PType *t,
    const std::string &what, const std::string &shown, SMLoc at,
    const std::vector<std::string> *onlyFields, bool portsWhenRead) {
  // The scalars, each with the selectors that reach it from the variable
  // and the suffix its port is named by (`buf_0`, `s_a`, `m_1_m2`).
  struct Selector {
    std::string field; // else the index
    int64_t index = 0;
  };
  struct Scalar {
    std::vector<Selector> path;
    std::string suffix;
    const PType *type = nullptr;
  };
  std::vector<Scalar> scalars;
  std::function<void(const PType *, Scalar &)> collect = [&](const PType *pt,
                                                             Scalar &in) {
    const PType *base = baseOf(pt);
    switch (base->kind) {
    case PTypeKind::Array:
      forEachIndex(base, [&](llvm::ArrayRef<int64_t> index) {
        Scalar inner = in;
        for (int64_t i : index)
          inner.path.push_back({"", i});
        inner.suffix = elementPath(inner.suffix, index);
        collect(base->elem, inner);
      });
      return;
    case PTypeKind::Struct:
      if (base->isUnion)
        break; // one scalar: its bytes (LowerUnions.cpp)
      for (VarDecl *fld : base->fields) {
        Scalar inner = in;
        inner.path.push_back({sanitize(fld->name), 0});
        inner.suffix += "_" + sanitize(fld->name);
        collect(fld->type, inner);
      }
      return;
    case PTypeKind::FunctionBlock:
      refuse(at, what + " is an instance of " + base->str() +
                     " that the caller owns: translate the caller, which "
                     "calls it");
    case PTypeKind::Reference:
      refuse(at, what + " holds a reference (" + base->str() +
                     "): what it designates belongs to the caller; "
                     "translate the caller");
    default:
      break;
    }
    in.type = pt;
    scalars.push_back(in);
    if (scalars.size() > kMaxEnvironmentScalars)
      refuse(at, what + " of type " + t->str() + " has more than " +
                     Twine(kMaxEnvironmentScalars) +
                     " scalars, each a free input of the model; translate "
                     "its caller");
  };
  Scalar whole;
  collect(t, whole);
  if (onlyFields)
    llvm::erase_if(scalars, [&](const Scalar &sc) {
      return llvm::none_of(sc.path, [&](const Selector &step) {
        return llvm::any_of(*onlyFields, [&](const std::string &f) {
          return !step.field.empty() && sameName(step.field, sanitize(f));
        });
      });
    });

  // A port name no declaration of the POU uses.
  auto freeName = [&](std::string n) {
    std::string candidate = n;
    for (unsigned i = 2; mod->lookup(candidate).kind != net::SymKind::None ||
                         (currentProgram && currentProgram->find(candidate));
         ++i)
      candidate = n + "_" + std::to_string(i);
    return candidate;
  };
  ChosenScalars chosen;
  chosen.name = name;
  chosen.at = at;
  for (Scalar &sc : scalars) {
    ChosenScalars::Scalar c;
    c.port = freeName(portStem + sc.suffix);
    if (portsWhenRead)
      portsDeclaredWhenRead[c.port] = {sc.type, shown + sc.suffix};
    else
      addFreeInputPort(c.port, sc.type, shown + sc.suffix, at);
    for (Selector &step : sc.path)
      c.path.push_back({step.field, step.index});
    c.type = sc.type;
    chosen.scalars.push_back(std::move(c));
  }
  return chosen;
}

NExpr *Lowering::scalarOf(const ChosenScalars &chosen,
                          const ChosenScalars::Scalar &c) {
  NExpr *x = b.ref(chosen.name, chosen.at);
  for (auto &[field, index] : c.path)
    x = field.empty() ? b.index(x, b.intLit(index, chosen.at), chosen.at)
                      : b.field(x, field, chosen.at);
  return x;
}

std::vector<NStmt *> Lowering::samplesOf(const ChosenScalars &c) {
  std::vector<NStmt *> out;
  for (const ChosenScalars::Scalar &sc : c.scalars)
    out.push_back(b.assign(scalarOf(c, sc), b.ref(sc.port, c.at), c.at));
  return out;
}

std::vector<NStmt *> Lowering::defaultsOf(const ChosenScalars &c) {
  std::vector<NStmt *> out;
  for (const ChosenScalars::Scalar &sc : c.scalars)
    out.push_back(b.assign(scalarOf(c, sc), defaultValue(sc.type, c.at), c.at));
  return out;
}

void Lowering::declareEnvironmentValue(VarDecl *v, const std::string &name) {
  const PType *t = v->type;
  // A VAR_IN_OUT and a variable shared outside: what the program leaves
  // there, which the environment may change before the next scan.
  bool inOut = v->section == VarSection::InOut || v->sharedOutside;
  std::string what = std::string(v->sharedOutside ? "shared variable '"
                                 : inOut          ? "VAR_IN_OUT '"
                                                  : "input '") +
                     v->name + "'";
  varTypes[name] = t;
  if (t->kind == PTypeKind::Array && t->anyBounds)
    refuse(v->loc, what + " is " + t->str() +
                       ": its bounds are those of the caller's array; "
                       "translate the caller");
  // Its scalars first: what cannot be chosen (an instance, a reference) is
  // refused before anything is declared.
  ChosenScalars chosen = chooseScalars(name, name + (inOut ? "_in" : ""), t,
                                       what, v->name, v->loc);
  // The variable the body reads and writes: a VAR_IN_OUT's is an output
  // port (what the block leaves in the caller's variable); an input's is
  // a variable of the scan.
  if (inOut) {
    uint32_t p = t->kind == PTypeKind::Bool
                     ? b.addPort(name, net::PortKind::Cond, net::PortDir::Out,
                                 nullptr, v->loc)
                     : b.addPort(name, net::PortKind::Data, net::PortDir::Out,
                                 netType(t, v->loc, what), v->loc);
    mod->ports[p].init = defaultValue(t, v->loc);
  } else {
    declareTemp(name, t, v->loc);
  }
  environmentSamples[v] = samplesOf(chosen);
  if (!inOut)
    environmentResets[v] = defaultsOf(chosen);
}

NExpr *Lowering::freeInputRead(const std::string &port, SMLoc at) {
  if (auto it = portsDeclaredWhenRead.find(port);
      it != portsDeclaredWhenRead.end() &&
      mod->lookup(port).kind == net::SymKind::None)
    addFreeInputPort(port, it->second.first, it->second.second, at);
  return b.ref(port, at);
}

void Lowering::addEnvironmentValue(const ChosenScalars &chosen,
                                   const std::string &owner) {
  for (const ChosenScalars::Scalar &c : chosen.scalars) {
    std::string key = chosen.name;
    for (auto &[field, index] : c.path)
      key += field.empty() ? "[" + std::to_string(index) + "]" : "." + field;
    environmentScalarPorts[key] = c.port;
  }
  environmentValues.push_back(chosen);
  environmentOwners[chosen.name] = owner;
}

void Lowering::declareRuntimeRecord(VarDecl *v, const std::string &name) {
  const PType *t = v->type;
  // What the project states is its initial value, back at the end of
  // every scan: the runtime writes the record before the next.
  declareTemp(name, t, v->loc,
              initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr, t),
              true);
  std::string what = "'" + v->name + "' " + v->runtimeRecord;
  // Ports only for what the program reads: a record has many fields.
  ChosenScalars chosen = chooseScalars(name, name, t, what, v->name, v->loc,
                                       &v->runtimeFree, true);
  addEnvironmentValue(chosen, what);
  std::vector<NStmt *> &samples = environmentSamples[v];
  const PType *record = baseOf(t);
  if (!v->runtimeFirst.empty()) {
    // TRUE in the first scan only.
    std::string flag = unique("_first_scan");
    b.addVar(flag, design.types.getBool(), b.boolLit(true, v->loc), v->loc);
    b.addAttribute(flag, net::kInternalAttribute, "first scan", v->loc);
    if (resetNames.insert(flag).second)
      resets.push_back({flag, b.boolLit(false, v->loc)});
    auto setFirst = [&](NExpr *element) {
      samples.push_back(b.assign(b.field(element, v->runtimeFirst, v->loc),
                                 b.ref(flag, v->loc), v->loc));
    };
    if (record->kind == PTypeKind::Array) {
      forEachIndex(record, [&](llvm::ArrayRef<int64_t> index) {
        NExpr *x = b.ref(name, v->loc);
        for (int64_t i : index)
          x = b.index(x, b.intLit(i, v->loc), v->loc);
        setFirst(x);
      });
      record = baseOf(record->elem);
    } else {
      setFirst(b.ref(name, v->loc));
    }
  } else if (record->kind == PTypeKind::Array) {
    record = baseOf(record->elem);
  }
  // Said where the program first reads it (environmentRead).
  std::string known, free;
  for (VarDecl *f : record->fields) {
    bool isFree = llvm::any_of(v->runtimeFree, [&](const std::string &n) {
      return sameName(n, f->name);
    });
    if (isFree || !sameName(f->name, v->runtimeFirst)) {
      std::string &list = isFree ? free : known;
      list += (list.empty() ? "" : ", ") + f->name;
    }
  }
  runtimeRecordNotes[name] =
      what + ": modelled as environment" +
      (known.empty() ? "" : "; the project gives " + known) +
      (v->runtimeFirst.empty()
           ? ""
           : "; " + v->runtimeFirst + " is TRUE in the first scan only") +
      (free.empty() ? "" : "; free inputs read where read: " + free);
}

NExpr *Lowering::taskIndex(Expr *call) {
  // FB_init runs when the application starts, outside any task.
  if (loweringInitCalls)
    return b.intLit(0, call->loc);
  size_t tasks = twinCatTasks(unit).size();
  if (tasks <= 1)
    return b.intLit(1, call->loc);
  // The runtime numbers the tasks; the project does not say how.
  std::string port = "_task_index";
  if (mod->lookup(port).kind == net::SymKind::None) {
    PType *index = unit.make<PType>(*elementaryType("DINT"));
    index->isSubrange = true;
    index->base = elementaryType("DINT");
    index->lo = 1;
    index->hi = int64_t(tasks);
    index->name = "DINT(1.." + std::to_string(tasks) + ")";
    addFreeInputPort(port, index, "GETCURTASKINDEXEX()", call->loc);
    diag.note(call->loc, "GETCURTASKINDEXEX() is the index the runtime gives "
                         "the task that runs the program; the project has " +
                             std::to_string(tasks) +
                             " tasks and does not say which it is: the free "
                             "input '" +
                             port + "'");
  }
  return b.ref(port, call->loc);
}

bool Lowering::isEnvironmentValue(VarDecl *v) const {
  if (!v->owner || !runAsProgram(v->owner) || !v->type)
    return false;
  if (v->section == VarSection::InOut)
    return true;
  const PType *t = baseOf(v->type);
  return v->section == VarSection::Input &&
         (t->kind == PTypeKind::Array ||
          (t->kind == PTypeKind::Struct && !t->isUnion));
}

NExpr *Lowering::clockReading(Expr *call) {
  std::string fn = StringRef(call->name).upper();
  if (opts.opaqueRefused)
    refuse(call->loc, fn + "() reads the PLC's clock, which netlift does not "
                           "model (--opaque=refuse; the default models it as "
                           "environment)");
  // One reading per scan: a scan is one step, and the clock's millisecond
  // (TIME) does not move within one on the PLCs netlift knows of. (4diac's
  // NOW_MONOTONIC and NOW alike: one reading per step of the model.)
  std::string port = "_" + StringRef(fn).lower() + "_now";
  if (mod->lookup(port).kind == net::SymKind::None) {
    addFreeInputPort(port, call->type, fn + "()", call->loc);
    diag.note(call->loc,
              fn +
                  "() reads the PLC's clock: modelled as environment, the "
                  "free input '" +
                  port +
                  (eventDriven ? "' read once per step of the model"
                               : "' read once per scan") +
                  " (any value: the model does not know that the clock "
                  "advances)");
  }
  return b.ref(port, call->loc);
}

NExpr *Lowering::environmentFunction(Expr *call, Frame &f, Sink &pre) {
  Pou *fn = call->callee;
  if (opts.opaqueRefused)
    refuse(call->loc, "'" + fn->name + "' " + fn->environment +
                          ", which netlift does not model (--opaque=refuse; "
                          "the default models it as environment)");
  for (VarDecl *p : fn->vars)
    if (p->section == VarSection::Output || p->section == VarSection::InOut)
      refuse(call->loc, "'" + fn->name + "' " + fn->environment +
                            ": an environment function with outputs is not "
                            "modelled");
  if (fn->isLibrary && sameName(fn->name, "GETCURTASKINDEXEX"))
    return taskIndex(call);
  for (CallArg &a : call->args)
    runArgumentCalls(a.value, f, pre);
  // Called as a statement (ADSLOGSTR(...);): its result is not read.
  if (!call->type || call->type->kind == PTypeKind::Void) {
    diag.note(call->loc, "'" + fn->name + "' " + fn->environment +
                             ": modelled as environment; its result is not "
                             "used, so the call changes nothing the program "
                             "sees");
    return b.intLit(0, call->loc);
  }
  // One free result per call site, read once per scan.
  std::string port = unique(sanitize(fn->name) + "_result");
  addFreeInputPort(port, call->type, fn->name + "()", call->loc);
  diag.note(call->loc, "'" + fn->name + "' " + fn->environment +
                           ": modelled as environment, its result the free "
                           "input '" +
                           port + "'");
  return b.ref(port, call->loc);
}

/// How many scalars a value of type `t` is chosen in (capped past `cap`).
static size_t scalarCount(const PType *t, size_t cap) {
  t = baseOf(t);
  if (t->kind == PTypeKind::Array) {
    size_t n = 1;
    for (auto &[lo, hi] : t->dims)
      n = std::min(cap + 1, n * size_t(hi - lo + 1));
    return std::min(cap + 1, n * scalarCount(t->elem, cap));
  }
  if (t->kind == PTypeKind::Struct && !t->isUnion) {
    size_t n = 0;
    for (VarDecl *f : t->fields)
      n = std::min(cap + 1, n + scalarCount(f->type, cap));
    return n;
  }
  return 1;
}

NExpr *Lowering::environmentRead(NExpr *place, Sink &pre) {
  if (environmentValues.empty())
    return nullptr;
  // The place as a name: fields and constant indices.
  std::function<std::optional<std::string>(NExpr *)> key =
      [&](NExpr *x) -> std::optional<std::string> {
    if (auto *r = llvm::dyn_cast<net::Ref>(x))
      return r->name.str();
    if (auto *fx = llvm::dyn_cast<net::FieldExpr>(x)) {
      auto k = key(fx->base);
      return k ? std::optional<std::string>(*k + "." + fx->field.str()) : k;
    }
    if (auto *ix = llvm::dyn_cast<net::IndexExpr>(x)) {
      auto *lit = llvm::dyn_cast<net::IntLit>(ix->index);
      auto k = lit ? key(ix->base) : std::nullopt;
      return k ? std::optional<std::string>(*k + "[" +
                                            std::to_string(lit->value) + "]")
               : std::nullopt;
    }
    return std::nullopt;
  };
  // The output the place lies in: its name is the place's root, whole or
  // followed by a selector.
  std::optional<std::string> k = key(place);
  std::string root = k ? *k : "";
  if (!k) {
    NExpr *x = place;
    while (true) {
      if (auto *fx = llvm::dyn_cast<net::FieldExpr>(x))
        x = fx->base;
      else if (auto *ix = llvm::dyn_cast<net::IndexExpr>(x))
        x = ix->base;
      else
        break;
    }
    auto *r = llvm::dyn_cast<net::Ref>(x);
    if (!r)
      return nullptr;
    root = r->name.str();
  }
  const ChosenScalars *owner = nullptr;
  for (const ChosenScalars &chosen : environmentValues) {
    StringRef n = chosen.name;
    if (StringRef(root).startswith(n) &&
        (root.size() == n.size() || root[n.size()] == '.' ||
         root[n.size()] == '['))
      owner = &chosen;
  }
  if (!owner)
    return nullptr;
  // Refused where a free scalar is read (a runtime record's known field
  // is the model's own).
  auto refuseIfOpaque = [&] {
    if (opts.opaqueRefused)
      refuse(place->loc, environmentOwners[owner->name] +
                             ", which netlift does not model "
                             "(--opaque=refuse; the default models it as "
                             "environment)");
  };
  if (auto it = runtimeRecordNotes.find(owner->name);
      it != runtimeRecordNotes.end() && !it->second.empty())
    diag.note(place->loc, std::exchange(it->second, ""));
  // A scalar: its free input. Read whole, or at a run-time index: chosen
  // here.
  if (k)
    if (auto it = environmentScalarPorts.find(*k);
        it != environmentScalarPorts.end()) {
      refuseIfOpaque();
      return freeInputRead(it->second, place->loc);
    }
  // A part that holds no free scalar (a runtime record's known field):
  // the variable's own.
  auto holdsFree = [&](const std::string &key) {
    for (auto it = environmentScalarPorts.lower_bound(key);
         it != environmentScalarPorts.end() &&
         StringRef(it->first).startswith(key);
         ++it)
      if (it->first.size() == key.size() || it->first[key.size()] == '.' ||
          it->first[key.size()] == '[')
        return true;
    return false;
  };
  if (k && !holdsFree(*k))
    return place;
  // The selectors below the value: a scalar is chosen only where the place
  // may lie over it (a run-time index over any element).
  struct Step {
    std::string field;            // else an index
    std::optional<int64_t> index; // none: chosen at run time
  };
  std::vector<Step> steps;
  std::string rootName;
  for (NExpr *x = place;;) {
    if (auto *fx = llvm::dyn_cast<net::FieldExpr>(x)) {
      steps.insert(steps.begin(), {fx->field.str(), std::nullopt});
      x = fx->base;
    } else if (auto *ix = llvm::dyn_cast<net::IndexExpr>(x)) {
      auto *lit = llvm::dyn_cast<net::IntLit>(ix->index);
      steps.insert(steps.begin(), {"", lit ? std::optional<int64_t>(lit->value)
                                           : std::nullopt});
      x = ix->base;
    } else {
      rootName = llvm::cast<net::Ref>(x)->name.str();
      break;
    }
  }
  // Selectors spelled into the owner's name (an instance's member) are
  // not the value's.
  while (rootName.size() < owner->name.size() && !steps.empty() &&
         !steps.front().field.empty()) {
    rootName += "." + steps.front().field;
    steps.erase(steps.begin());
  }
  for (const ChosenScalars::Scalar &sc : owner->scalars) {
    bool under = true;
    for (size_t i = 0; i < steps.size() && i < sc.path.size() && under; ++i) {
      const auto &[field, index] = sc.path[i];
      under =
          steps[i].field.empty()
              ? field.empty() && (!steps[i].index || *steps[i].index == index)
              : sameName(field, steps[i].field);
    }
    if (!under)
      continue;
    refuseIfOpaque();
    pre.push_back(b.assign(scalarOf(*owner, sc),
                           freeInputRead(sc.port, place->loc), owner->at));
  }
  return place;
}

const PType *Lowering::callerTarget(VarDecl *v) {
  if (!v->owner || !runAsProgram(v->owner) || !v->type ||
      v->section != VarSection::Input || !v->type->isReference() ||
      v->type->refKind == RefKind::Interface || !v->type->elem)
    return nullptr;
  const PType *elem = v->type->elem;
  const PType *base = baseOf(elem);
  if (base->kind == PTypeKind::FunctionBlock ||
      base->kind == PTypeKind::Reference ||
      (base->kind == PTypeKind::Array && base->anyBounds))
    return nullptr;
  if (scalarCount(elem, kMaxEnvironmentScalars) <= kMaxEnvironmentScalars)
    return elem;
  // OSCAT's `POINTER TO ARRAY[0..32000] OF BYTE`: the first elements.
  if (base->kind != PTypeKind::Array || base->dims.size() != 1 ||
      scalarCount(base->elem, kMaxEnvironmentScalars) *
              size_t(opts.callerElements) >
          kMaxEnvironmentScalars)
    return nullptr;
  const PType *&prefix = callerPrefixes[base];
  if (!prefix) {
    PType *p = unit.make<PType>(*base);
    p->name.clear();
    p->dims = {
        {base->dims[0].first, base->dims[0].first + opts.callerElements - 1}};
    prefix = p;
  }
  return prefix;
}

void Lowering::declareCallerTarget(VarDecl *v, const std::string &name,
                                   const PType *elem) {
  std::string target = name + "_target";
  varTypes[target] = elem;
  uint32_t p = baseOf(elem)->kind == PTypeKind::Bool
                   ? b.addPort(target, net::PortKind::Cond, net::PortDir::Out,
                               nullptr, v->loc)
                   : b.addPort(target, net::PortKind::Data, net::PortDir::Out,
                               netType(elem, v->loc,
                                       "what '" + v->name + "' designates"),
                               v->loc);
  mod->ports[p].init = defaultValue(elem, v->loc);
  ChosenScalars chosen = chooseScalars(
      target, target + "_in", elem, "what input '" + v->name + "' designates",
      v->name + "^", v->loc);
  environmentSamples[v] = samplesOf(chosen);
  // A prefix of a larger array (callerTarget): said with its limit.
  std::string prefix = elem == v->type->elem
                           ? ""
                           : ", its first " +
                                 std::to_string(opts.callerElements) +
                                 " elements (--caller-elements)";
  std::string past = elem == v->type->elem
                         ? ""
                         : "; an element past them is the run-time error '" +
                               name + "_deref_element'";
  diag.note(v->loc, "input '" + v->name + "' may designate its caller's " +
                        v->type->elem->str() + ": modelled as '" + target +
                        "'" + prefix +
                        ", chosen by the environment at every scan as an "
                        "in-out is (or NULL, or what the design's own REF "
                        "and ADR take)" +
                        past);
}
