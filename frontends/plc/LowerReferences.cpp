//===- LowerReferences.cpp - references and pointers in NetIR -------------===//
//
// A reference is a small integer: 0 is NULL, 1..n one of the n places of
// the module that may hold a value of its designated type and whose
// address the program takes (REF, ADR, REF=, a REFERENCE TO input bound at
// a call). The places are found before anything is declared, by a
// flow-insensitive, type-based points-to analysis over the instance tree:
// a reference to T gets its value only from REF/ADR of a T, from another
// reference to T, or NULL, so every place it can designate is one of the
// places whose address is taken as a T somewhere in the module — in any
// instance of the POU that takes it. Places come in families: REF(a[i].x)
// takes every a[k].x, numbered in row-major order, so a run-time index
// gives a run-time number. A dereference reads through a selection over
// the families (an indexed access within each) and writes through an IF
// over them; a NULL reference is a run-time error, caught by copying the
// number into a variable of range 1..n first (docs/st.md, "References and
// pointers").
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Planning: which places each reference type can designate
//===----------------------------------------------------------------------===//

/// Every REF/ADR call in `l`, nested expressions included, and in the
/// initial values of `vars`.
static void forEachAddressTaken(StmtList &l, llvm::ArrayRef<VarDecl *> vars,
                                llvm::function_ref<void(Expr *)> fn) {
  auto walk = [&](Expr *top) {
    forEachNestedExpr(top, [&](Expr *e) {
      if (e->kind == ExprKind::Call && !e->callee && !e->var &&
          (e->name == "REF" || e->name == "ADR") && e->args.size() == 1)
        fn(e);
    });
  };
  forEachStmt(
      l, [](Stmt *) {}, walk);
  for (VarDecl *v : vars) {
    if (v->typeSyntax)
      forEachInitialValue(v->typeSyntax->init, walk);
    // The FB_init calls of an instance's declaration (`a : FB(ADR(x))`).
    for (Expr *init : v->elementInitCalls)
      walk(init);
    if (v->initCall)
      walk(v->initCall);
  }
}

/// Every `__UPCAST(r)` (a reference to a derived block used as one to its
/// base; Sema's referenceAsBase) in `unit`'s bodies and initial values.
static void forEachUpcast(Unit &unit, llvm::function_ref<void(Expr *)> fn) {
  auto walk = [&](Expr *top) {
    forEachNestedExpr(top, [&](Expr *e) {
      if (e->kind == ExprKind::Call && e->name == "__UPCAST" && !e->callee)
        fn(e);
    });
  };
  for (Pou *p : unit.pous) {
    forEachStmt(
        p->body, [](Stmt *) {}, walk);
    for (VarDecl *v : p->vars)
      if (v->typeSyntax)
        forEachInitialValue(v->typeSyntax->init, walk);
  }
  for (VarDecl *v : unit.globals)
    if (v->typeSyntax)
      forEachInitialValue(v->typeSyntax->init, walk);
}

/// The same over every POU and global of `unit`.
static void forEachAddressTaken(Unit &unit,
                                llvm::function_ref<void(Expr *)> fn) {
  for (Pou *p : unit.pous)
    forEachAddressTaken(p->body, p->vars, fn);
  StmtList none;
  forEachAddressTaken(none, unit.globals, fn);
  for (Configuration *c : unit.configs)
    forEachAddressTaken(none, c->globals, fn);
}

/// The dereference a place expression reads or writes through, if the
/// selectors above it are fields and indices only.
static Expr *derefBelow(Expr *e) {
  for (; e; e = e->base()) {
    if (e->kind == ExprKind::Deref)
      return e;
    if (e->kind != ExprKind::Field && e->kind != ExprKind::Index)
      return nullptr;
  }
  return nullptr;
}

/// The variable at the root of a place expression, and whether a
/// dereference lies on the way.
static Expr *placeRoot(Expr *e, bool &throughDeref) {
  throughDeref = false;
  for (; e; e = e->base()) {
    if (e->kind == ExprKind::Deref)
      throughDeref = true;
    if (e->kind == ExprKind::Name)
      return e;
  }
  return nullptr;
}

/// The selectors from the root of `place` (or from `from`, a dereference
/// under it) to it, outermost first.
static std::vector<Expr *> placeSelectors(Expr *place, Expr *from = nullptr) {
  std::vector<Expr *> chain;
  for (Expr *e = place; e && e != from && e->kind != ExprKind::Name;
       e = e->base())
    chain.push_back(e);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

/// The family steps of the selectors (every index a wildcard).
static std::vector<RefStep> familySteps(llvm::ArrayRef<Expr *> selectors) {
  std::vector<RefStep> steps;
  for (Expr *x : selectors) {
    const PType *bt = x->base()->type;
    RefStep s;
    if (x->kind == ExprKind::Field) {
      s.kind = bt && bt->kind == PTypeKind::FunctionBlock ? RefStep::Member
                                                          : RefStep::Field;
      s.name = s.kind == RefStep::Member && x->var ? x->var->name : x->name;
    } else {
      s.kind = RefStep::Index;
      s.dims = bt->dims;
      s.ofInstances = instanceBlock(bt) != nullptr;
    }
    steps.push_back(std::move(s));
  }
  return steps;
}

/// What an ADR takes the address of: the place, or (ADR of a STRING
/// where a POINTER TO BYTE or to an ARRAY OF BYTE is wanted, Sema's
/// "BYTES") the bytes the string is held in.
static RefView viewOf(Expr *call) {
  RefView view;
  if (call->typeName == "ELEMENTS") {
    const PType *seen = call->args[0].value->type;
    view.kind = RefView::Elements;
    view.lo = call->type->elem->dims[0].first;
    view.placeLo = seen->dims[0].first;
    view.bytes = seen->dims[0].second - seen->dims[0].first + 1;
    return view;
  }
  if (call->typeName == "SCALAR") {
    view.kind = RefView::Scalar;
    view.seen = baseOf(call->args[0].value->type);
    std::string why;
    int64_t size = memoryLayout(view.seen, why)->size;
    if (call->type->elem->kind == PTypeKind::Array) { // its bytes
      view.lo = call->type->elem->dims[0].first;
      view.bytes = size;
    } else if (baseOf(call->type->elem)->width == 8 && size > 1) {
      view.byteSteps = true; // its bytes, one place each
      view.bytes = size;
    }
    return view;
  }
  if (call->typeName != "BYTES")
    return view;
  const PType *target = call->type->elem;
  view.bytes = int64_t(baseOf(call->args[0].value->type)->strLen) + 1;
  if (target->kind == PTypeKind::Array) {
    view.kind = RefView::ByteArray;
    view.lo = target->dims[0].first;
  } else {
    view.kind = RefView::Bytes;
  }
  return view;
}

/// The type whose places an ADR or REF call's value is numbered among: the
/// place's own, or what it is seen as (a view; an interface the instance's
/// block implements).
static const PType *designatedType(Expr *call, const RefView &view) {
  if (view.kind != RefView::Plain || call->typeName == "INTERFACE" ||
      call->typeName == "BASE")
    return call->type->elem;
  return call->args[0].value->type;
}

/// The elements the index steps of `steps` span together.
static int64_t elementsOf(llvm::ArrayRef<RefStep> steps) {
  int64_t n = 1;
  for (const RefStep &s : steps)
    for (auto &[lo, hi] : s.dims)
      n *= hi - lo + 1;
  return n;
}

static std::string familyKey(const std::string &base,
                             llvm::ArrayRef<RefStep> steps) {
  std::string key = base;
  for (const RefStep &s : steps)
    key += s.kind == RefStep::Index ? "[*]" : "." + s.name;
  return key;
}

/// The instances an element of an array of instances may be, when `steps`
/// index one: every element's path under `base` (row-major, as
/// Lowering::elementPath spells it, members on the way appended), with the
/// steps below the last such index left in `rest`. Empty otherwise.
std::vector<std::string>
Lowering::instanceElementBases(const std::string &base,
                               llvm::ArrayRef<RefStep> steps,
                               std::vector<RefStep> &rest) {
  size_t last = steps.size();
  for (size_t i = 0; i < steps.size(); ++i)
    if (steps[i].kind == RefStep::Index && steps[i].ofInstances)
      last = i;
  if (last == steps.size())
    return {};
  std::vector<std::string> bases = {base};
  for (size_t i = 0; i <= last; ++i) {
    const RefStep &s = steps[i];
    std::vector<std::string> next;
    for (const std::string &b : bases) {
      if (s.kind != RefStep::Index) {
        next.push_back(b + "." + sanitize(s.name));
        continue;
      }
      std::vector<int64_t> index;
      for (auto &[lo, hi] : s.dims)
        index.push_back(lo);
      for (;;) {
        next.push_back(elementPath(b, index));
        size_t d = index.size();
        while (d-- > 0 && ++index[d] > s.dims[d].second)
          index[d] = s.dims[d].first;
        if (d == size_t(-1))
          break;
      }
    }
    bases = std::move(next);
  }
  rest.assign(steps.begin() + last + 1, steps.end());
  return bases;
}

std::vector<std::string>
Lowering::placeBases(VarDecl *v,
                     const std::map<Pou *, std::vector<std::string>> &instances,
                     llvm::ArrayRef<ProgramRun> runs) {
  if (!v->owner)
    return {sanitize(v->name)};
  if (v->section == VarSection::InOut)
    return {}; // refused where the REF is lowered
  if (v->section == VarSection::Stat && v->owner->kind != PouKind::Program)
    return {"static." + sanitize(v->owner->name) + "." + sanitize(v->name)};
  if (v->owner->kind == PouKind::Function)
    return {functionPlace(v)};
  // A program's variables, and those of a function block translated as
  // the top (`--top FB`), which is run as a program is.
  std::vector<std::string> bases;
  for (const ProgramRun &run : runs)
    if (run.pou == v->owner)
      bases.push_back(inputImageName(run.prefix, v)
                          .value_or(run.prefix + sanitize(v->name)));
  if (!bases.empty() || v->owner->kind == PouKind::Program)
    return bases;
  if (auto it = instances.find(v->owner); it != instances.end())
    for (const std::string &path : it->second)
      bases.push_back(path + "." + sanitize(v->name));
  return bases;
}

std::string Lowering::functionPlace(VarDecl *v) {
  return "@" + sanitize(v->owner->name) + "." + sanitize(v->name);
}

std::optional<std::string> Lowering::inputImageName(const std::string &prefix,
                                                    VarDecl *v) {
  if (!v->writtenInput || !runAsProgram(v->owner) || isEnvironmentValue(v) ||
      !(v->area() == 'I' || v->section == VarSection::Input))
    return std::nullopt;
  return prefix + "_in_" + sanitize(v->name);
}

Lowering::ReferencePlan
Lowering::planReferences(llvm::ArrayRef<ProgramRun> runs) {
  // The POUs run as programs decide whose variables are named as a
  // program's (and which reference inputs designate the caller's objects);
  // an IEC 61499 block's are its own.
  runPous.clear();
  if (!eventDriven)
    for (const ProgramRun &run : runs)
      runPous.insert(run.pou);
  // The instance tree: every path of every function block type.
  std::map<Pou *, std::vector<std::string>> instances;
  std::function<void(const std::string &, Pou *)> walk =
      [&](const std::string &path, Pou *fb) {
        auto &paths = instances[fb];
        if (llvm::is_contained(paths, path))
          return;
        paths.push_back(path);
        for (VarDecl *m : fb->vars)
          if (Pou *inner = m->type ? instanceBlock(m->type) : nullptr;
              inner && m->section != VarSection::External &&
              m->section != VarSection::InOut)
            for (const std::string &p :
                 instancePaths(path + "." + sanitize(m->name), m->type))
              walk(p, inner);
      };
  auto walkVariable = [&](const std::string &path, VarDecl *v) {
    if (Pou *fb = v->type ? instanceBlock(v->type) : nullptr)
      for (const std::string &p : instancePaths(path, v->type))
        walk(p, fb);
  };
  for (const ProgramRun &run : runs) {
    for (VarDecl *g : globalsUsedBy(run.pou))
      walkVariable(sanitize(g->name), g);
    for (VarDecl *v : run.pou->vars)
      if (v->section != VarSection::External)
        walkVariable(run.prefix + sanitize(v->name), v);
  }

  // What every call binds to each VAR_IN_OUT: the address of an in-out
  // parameter is that of the caller's argument.
  std::map<VarDecl *, std::vector<Expr *>> inOutArguments;
  auto noteArguments = [&](Expr *c) {
    Pou *callee = c->kind == ExprKind::Call ? calledPou(c) : nullptr;
    if (!callee)
      return;
    for (CallArg &a : c->args)
      if (VarDecl *p = callee->find(a.name);
          p && p->section == VarSection::InOut && !a.isOutput)
        inOutArguments[p].push_back(a.value);
  };
  for (Pou *p : unit.pous)
    forEachStmt(
        p->body, [](Stmt *) {},
        [&](Expr *e) { forEachNestedExpr(e, noteArguments); });

  ReferencePlan plan;
  std::function<void(VarDecl *, std::vector<RefStep>, RefTable &, RefView,
                     unsigned)>
      addPlace = [&](VarDecl *v, std::vector<RefStep> steps, RefTable &table,
                     RefView view, unsigned depth) {
        if (v->section == VarSection::InOut) {
          for (Expr *arg : inOutArguments[v]) {
            bool throughDeref;
            Expr *root = placeRoot(arg, throughDeref);
            if (!root || !root->var || throughDeref || depth > 32)
              continue; // refused where the REF is lowered
            std::vector<RefStep> outer = familySteps(placeSelectors(arg));
            outer.insert(outer.end(), steps.begin(), steps.end());
            addPlace(root->var, outer, table, view, depth + 1);
          }
          return;
        }
        int64_t size =
            elementsOf(steps) * (view.numbersBytes() ? view.bytes : 1);
        for (const std::string &base : placeBases(v, instances, runs)) {
          std::string key = familyKey(base, steps) + view.suffix();
          if (table.byKey.count(key))
            continue;
          // The elements of an array of instances are instances of their
          // own: a family each, numbered one after the other in row-major
          // order, so that the array's key (the first's number) and the
          // index give an element's number as for any array.
          std::vector<RefStep> rest;
          std::vector<std::string> elements =
              instanceElementBases(base, steps, rest);
          if (!elements.empty()) {
            table.byKey[key] = table.families.size();
            int64_t each = size / int64_t(elements.size());
            for (const std::string &element : elements) {
              RefFamily fam;
              fam.key = familyKey(element, rest) + view.suffix();
              if (!table.byKey.emplace(fam.key, table.families.size()).second)
                refuse(v->loc, "internal: an element of an array of "
                               "instances numbered twice ('" +
                                   fam.key + "')");
              fam.base = element;
              fam.view = view;
              fam.steps = rest;
              fam.size = each;
              fam.offset = table.count + 1;
              table.count += each;
              table.families.push_back(std::move(fam));
            }
            continue;
          }
          table.byKey[key] = table.families.size();
          RefFamily fam;
          fam.key = key;
          fam.base = base;
          fam.view = view;
          if (v->owner && v->owner->kind == PouKind::Function) {
            // One family for every call: the running call's variable.
            fam.function = v->owner;
            fam.base = sanitize(v->name);
          }
          fam.steps = steps;
          fam.size = size;
          fam.offset = table.count + 1;
          table.count += size;
          table.families.push_back(std::move(fam));
        }
      };
  // A single place named `base` (a variable, an instance), once.
  auto addSinglePlace = [](RefTable &table, const std::string &base) {
    if (table.byKey.count(base))
      return;
    table.byKey[base] = table.families.size();
    RefFamily fam;
    fam.key = fam.base = base;
    fam.offset = table.count + 1;
    table.count += 1;
    table.families.push_back(std::move(fam));
  };
  // A reference input of the POU run as a program may designate an object
  // of its caller's (the environment's): one place each.
  for (const ProgramRun &run : runs)
    for (VarDecl *v : run.pou->vars)
      if (const PType *elem = callerTarget(v)) {
        std::string base = run.prefix + sanitize(v->name) + "_target";
        if (elem == v->type->elem) {
          addSinglePlace(plan.tables[referenceKey(elem)], base);
          continue;
        }
        // Its first elements, seen with the pointer's bounds.
        RefTable &table = plan.tables[referenceKey(v->type->elem)];
        RefFamily fam;
        fam.view.kind = RefView::Elements;
        fam.view.lo = fam.view.placeLo = elem->dims[0].first;
        fam.view.bytes = elem->dims[0].second - elem->dims[0].first + 1;
        fam.key = base + fam.view.suffix();
        fam.base = base;
        if (table.byKey.count(fam.key))
          continue;
        table.byKey[fam.key] = table.families.size();
        fam.offset = table.count + 1;
        table.count += 1;
        table.families.push_back(std::move(fam));
      }
  std::vector<Expr *> throughReferences, selfInstances;
  forEachAddressTaken(unit, [&](Expr *call) {
    Expr *place = call->args[0].value;
    if (place->selfInstance) {
      selfInstances.push_back(call);
      return;
    }
    bool throughDeref;
    Expr *root = placeRoot(place, throughDeref);
    if (!place->type || place->kind == ExprKind::Deref)
      return; // REF(r^) is r
    if (throughDeref) {
      throughReferences.push_back(place);
      return;
    }
    if (!root || !root->var)
      return;
    RefView view = viewOf(call);
    addPlace(root->var, familySteps(placeSelectors(place)),
             plan.tables[referenceKey(designatedType(call, view))], view, 0);
  });
  // THIS^ as an interface: every instance that runs the block's code (its
  // own type's and those derived from it), after the arrays of instances
  // have numbered their elements in order.
  for (Expr *call : selfInstances) {
    Pou *block = call->args[0].value->callee;
    RefTable &table =
        plan.tables[referenceKey(designatedType(call, viewOf(call)))];
    for (Pou *p : unit.pous) {
      bool runs = false;
      for (Pou *b = p; b && !runs; b = b->base)
        runs = b == block;
      if (!runs)
        continue;
      for (const std::string &path : instances[p])
        addSinglePlace(table, path);
    }
  }
  // A reference to a derived block used as one to its base: every place
  // it may designate is the base's too (same key, renumbered).
  std::vector<Expr *> upcasts;
  forEachUpcast(unit, [&](Expr *e) { upcasts.push_back(e); });
  // REF(r^.f): the field f of every place r may designate, itself
  // perhaps designated through another such REF: to a fixpoint.
  for (bool grew = true; grew;) {
    grew = false;
    for (Expr *e : upcasts) {
      auto from = plan.tables.find(referenceKey(e->args[0].value->type->elem));
      if (from == plan.tables.end())
        continue;
      RefTable &table = plan.tables[referenceKey(e->type->elem)];
      std::vector<RefFamily> sources = from->second.families;
      for (const RefFamily &source : sources) {
        if (table.byKey.count(source.key))
          continue;
        grew = true;
        table.byKey[source.key] = table.families.size();
        RefFamily fam = source;
        fam.offset = table.count + 1;
        table.count += fam.size;
        table.families.push_back(std::move(fam));
      }
    }
    for (Expr *place : throughReferences) {
      Expr *d = derefBelow(place);
      if (!d)
        continue; // refused where it is lowered
      std::vector<RefStep> steps = familySteps(placeSelectors(place, d));
      int64_t extent = elementsOf(steps);
      auto from = plan.tables.find(referenceKey(d->type));
      if (from == plan.tables.end())
        continue;
      RefTable &table = plan.tables[referenceKey(place->type)];
      // `table` may be `from` (a list's REF(r^.next^)): copy first.
      std::vector<RefFamily> sources = from->second.families;
      for (const RefFamily &source : sources) {
        std::string key = familyKey(source.key, steps);
        if (table.byKey.count(key))
          continue;
        grew = true;
        table.byKey[key] = table.families.size();
        RefFamily fam = source;
        fam.key = key;
        fam.steps.insert(fam.steps.end(), steps.begin(), steps.end());
        fam.size = source.size * extent;
        fam.offset = table.count + 1;
        table.count += fam.size;
        table.families.push_back(std::move(fam));
      }
    }
  }
  giveOutsideNumbers(plan);
  return plan;
}

void Lowering::adoptReferencePlan(ReferencePlan plan) {
  refPlan = std::move(plan);
  // A place read through a reference is read from outside its instance.
  for (auto &[key, table] : refPlan.tables)
    for (RefFamily &fam : table.families) {
      std::string name = fam.base;
      externallyRead.insert(name);
      addressTaken.insert(name);
      for (const RefStep &s : fam.steps) {
        if (s.kind != RefStep::Member)
          break;
        name += "." + sanitize(s.name);
        externallyRead.insert(name);
        addressTaken.insert(name);
      }
    }
}

void Lowering::markAddressTaken() {
  forEachAddressTaken(unit, [&](Expr *call) {
    Expr *place = call->args[0].value;
    bool throughDeref;
    if (Expr *root = placeRoot(place, throughDeref); root && root->var) {
      // Written through a reference, perhaps: not a constant.
      written.insert(root->var);
      writtenOtherwise.insert(root->var);
    }
  });
}

int64_t Lowering::referenceCount(const PType *target) {
  auto it = refDomain.find(referenceKey(target));
  return it == refDomain.end() ? 0 : it->second;
}

//===----------------------------------------------------------------------===//
// REF and ADR
//===----------------------------------------------------------------------===//

/// A variable of the scan (reset to `init` at its end) named after `stem`.
std::string Lowering::scanVariable(const std::string &stem,
                                   const net::Type *type, int64_t init,
                                   SMLoc at) {
  std::string name = unique(stem);
  b.addVar(name, type, b.intLit(init, at), at);
  if (resetNames.insert(name).second)
    resets.push_back({name, b.intLit(init, at)});
  return name;
}

std::string netlift::plc::detail::stemOf(Expr *reference) {
  Expr *root = reference;
  while (root->base())
    root = root->base();
  return root->kind == ExprKind::Name ? Lowering::sanitize(root->name)
                                      : "pointer";
}

int64_t netlift::plc::detail::contiguousBlock(const RefFamily &fam) {
  if (fam.view.numbersBytes())
    return fam.view.bytes; // one string's, one scalar's
  if (!fam.steps.empty() && fam.steps.back().kind == RefStep::Index)
    return elementsOf(fam.steps.back());
  return 1;
}

void Lowering::giveOutsideNumbers(ReferencePlan &plan) {
  // The types a program steps pointers through (Sema typed each step as
  // its pointer).
  std::set<std::string> stepped;
  for (Pou *p : unit.pous)
    forEachStmt(
        p->body, [](Stmt *) {},
        [&](Expr *e) {
          forEachNestedExpr(e, [&](Expr *x) {
            if (x->kind == ExprKind::Binary &&
                (x->op == Op::Add || x->op == Op::Sub) && x->type &&
                x->type->isReference() && x->type->elem)
              stepped.insert(referenceKey(x->type->elem));
          });
        });
  for (auto &[key, table] : plan.tables) {
    if (!stepped.count(key))
      continue;
    table.count = 0;
    for (RefFamily &fam : table.families) {
      fam.hasOutside = contiguousBlock(fam) == fam.size;
      int64_t margin = fam.hasOutside ? 2 : 0;
      fam.offset = table.count + 1 + margin;
      table.count += fam.size + 2 * margin;
    }
  }
}

/// `v`, known to lie in lo..hi when it is not a constant, copied into a
/// fresh variable of that range first: an index outside is a run-time
/// error naming `what`.
NExpr *Lowering::checkedRange(NExpr *v, int64_t lo, int64_t hi,
                              const std::string &what, Sink &pre, SMLoc at) {
  if (auto *lit = llvm::dyn_cast<net::IntLit>(v)) {
    if (lit->value < lo || lit->value > hi)
      refuse(at, "index " + Twine(lit->value) + " is outside " + Twine(lo) +
                     ".." + Twine(hi) + " of " + what);
    return v;
  }
  std::string name = scanVariable(what, design.types.getRange(lo, hi), lo, at);
  pre.push_back(b.assign(b.ref(name, at), v, at));
  return b.ref(name, at);
}

NExpr *Lowering::addressOf(Expr *call, Frame &f, Sink &pre) {
  Expr *place = call->args[0].value;
  SMLoc at = call->loc;
  if (place->kind == ExprKind::Deref)
    return expr(place->base(), f, pre); // REF(r^) is r
  if (place->selfInstance) {            // the running instance's number
    std::string path = f.running().second;
    if (!path.empty())
      path.pop_back();
    auto table =
        refPlan.tables.find(referenceKey(designatedType(call, viewOf(call))));
    if (table == refPlan.tables.end() || !table->second.byKey.count(path))
      refuse(at, "internal: no place planned for THIS^ ('" + path + "')");
    return b.intLit(table->second.families[table->second.byKey[path]].offset,
                    at);
  }
  bool throughDeref;
  Expr *root = placeRoot(place, throughDeref);
  if (throughDeref)
    return addressThroughReference(call, f, pre);
  // The selectors from the variable to the place, each with the frame its
  // indices are computed in: a VAR_IN_OUT is the caller's argument, so
  // the argument's selectors come first, in the caller's frame.
  std::vector<std::pair<Expr *, Frame *>> selectors;
  for (Expr *x : placeSelectors(place))
    selectors.push_back({x, &f});
  VarDecl *v = root->var;
  Frame *rf = &f;
  while (v->section == VarSection::InOut) {
    auto source = rf->aliasSources.find(v);
    if (source == rf->aliasSources.end())
      refuse(at, call->name + " of VAR_IN_OUT '" + v->name +
                     "' (it designates the caller's variable) is not "
                     "supported here");
    auto [arg, caller] = source->second;
    Expr *argRoot = placeRoot(arg, throughDeref);
    if (throughDeref || !argRoot || !argRoot->var)
      refuse(at, call->name + " of VAR_IN_OUT '" + v->name +
                     "', bound to what a reference designates, is not "
                     "supported");
    std::vector<std::pair<Expr *, Frame *>> outer;
    for (Expr *x : placeSelectors(arg))
      outer.push_back({x, caller});
    selectors.insert(selectors.begin(), outer.begin(), outer.end());
    v = argRoot->var;
    rf = caller;
  }
  std::vector<Expr *> chain;
  for (auto &[x, fr] : selectors) {
    chain.push_back(x);
    if (x->base()->type && x->base()->type->kind == PTypeKind::Struct &&
        x->base()->type->isUnion)
      refuse(at, call->name + " of a UNION member is not supported");
  }
  // The family this place belongs to.
  std::string base;
  if (!v->owner)
    base = sanitize(v->name);
  else if (v->section == VarSection::Stat && v->owner->kind != PouKind::Program)
    base = "static." + sanitize(v->owner->name) + "." + sanitize(v->name);
  else if (v->owner->kind == PouKind::Function)
    base = functionPlace(v);
  else if (runAsProgram(v->owner))
    base = inputImageName(rf->prefixOf(v), v)
               .value_or(rf->prefixOf(v) + sanitize(v->name));
  else
    base = rf->prefixOf(v) + sanitize(v->name);
  std::vector<RefStep> steps = familySteps(chain);
  RefView view = viewOf(call);
  auto table = refPlan.tables.find(referenceKey(designatedType(call, view)));
  const RefFamily *fam = nullptr;
  if (table != refPlan.tables.end())
    if (auto it =
            table->second.byKey.find(familyKey(base, steps) + view.suffix());
        it != table->second.byKey.end())
      fam = &table->second.families[it->second];
  if (!fam)
    refuse(at, "internal: no place planned for " + call->name + "(" +
                   familyKey(base, steps) + ")");
  // Its number: the family's first, plus the element's row-major offset.
  auto [constant, number] =
      elementOffset(selectors, sanitize(v->name) + "_index", pre, at);
  if (view.numbersBytes()) { // the first byte of the string chosen
    constant *= view.bytes;
    if (number)
      number =
          b.binary(net::BinaryOp::Mul, number, b.intLit(view.bytes, at), at);
  }
  constant += fam->offset;
  if (!number)
    return b.intLit(constant, at);
  return b.binary(net::BinaryOp::Add, number, b.intLit(constant, at), at);
}

std::pair<int64_t, NExpr *>
Lowering::elementOffset(llvm::ArrayRef<std::pair<Expr *, Frame *>> selectors,
                        const std::string &what, Sink &pre, SMLoc at) {
  int64_t constant = 0;
  NExpr *number = nullptr;
  for (auto &[x, fr] : selectors) {
    if (x->kind != ExprKind::Index)
      continue;
    const PType *array = x->base()->type;
    for (size_t d = 0; d < array->dims.size(); ++d) {
      auto [lo, hi] = array->dims[d];
      int64_t extent = hi - lo + 1;
      NExpr *i = checkedRange(expr(x->operands[d + 1], *fr, pre), lo, hi, what,
                              pre, x->loc);
      constant *= extent;
      if (number)
        number = b.binary(net::BinaryOp::Mul, number, b.intLit(extent, at), at);
      if (auto *lit = llvm::dyn_cast<net::IntLit>(i)) {
        constant += lit->value - lo;
        continue;
      }
      NExpr *rel = b.binary(net::BinaryOp::Sub, i, b.intLit(lo, at), at);
      number = number ? b.binary(net::BinaryOp::Add, number, rel, at) : rel;
    }
  }
  return {constant, number};
}

NExpr *Lowering::addressThroughReference(Expr *call, Frame &f, Sink &pre) {
  Expr *place = call->args[0].value;
  SMLoc at = call->loc;
  // Sema lets only fields and indices stand above the dereference.
  Expr *d = derefBelow(place);
  assert(d && "REF through a reference of something not a place");
  std::vector<Expr *> above = placeSelectors(place, d);
  std::vector<std::pair<Expr *, Frame *>> selectors;
  for (Expr *x : above)
    selectors.push_back({x, &f});
  std::vector<RefStep> steps = familySteps(above);
  int64_t extent = elementsOf(steps); // what each designated place spans
  DerefTargets t = derefTargets(place, f, pre);
  auto [constant, offset] =
      elementOffset(selectors, stemOf(d->base()) + "_index", pre, at);
  auto table = refPlan.tables.find(referenceKey(place->type));
  // In each family the reference may designate, the same selection: a
  // family of its own (planned), whose elements follow the designated
  // place's, each spanning `extent`.
  NExpr *r = nullptr;
  for (size_t i = t.live.size(); i-- > 0;) {
    const RefFamily &from = *t.live[i];
    const RefFamily *to = nullptr;
    if (table != refPlan.tables.end())
      if (auto it = table->second.byKey.find(familyKey(from.key, steps));
          it != table->second.byKey.end())
        to = &table->second.families[it->second];
    if (!to)
      refuse(at, "internal: no place planned for " + call->name + "(" +
                     familyKey(from.key, steps) + ")");
    NExpr *n = b.intLit(to->offset + constant, at);
    if (from.size > 1 || offset) {
      NExpr *rel = b.binary(net::BinaryOp::Sub, numberOf(t, at),
                            b.intLit(from.offset, at), at);
      NExpr *within =
          b.binary(net::BinaryOp::Mul, rel, b.intLit(extent, at), at);
      if (offset)
        within = b.binary(net::BinaryOp::Add, within, offset, at);
      n = b.binary(net::BinaryOp::Add, within, n, at);
    }
    r = r ? b.cond(familyTest(from, t), n, r, at) : n;
  }
  // NULL or dangling: the checks made by derefTargets have reported it.
  return r ? r : b.intLit(0, at);
}

//===----------------------------------------------------------------------===//
// Dereferences
//===----------------------------------------------------------------------===//

bool Lowering::throughReference(Expr *e) { return derefBelow(e) != nullptr; }

Lowering::DerefTargets Lowering::derefTargets(Expr *e, Frame &f, Sink &pre) {
  Expr *d = derefBelow(e);
  DerefTargets t;
  t.deref = d;
  const PType *target = d->type;
  auto it = refPlan.tables.find(referenceKey(target));
  t.table = it == refPlan.tables.end() ? nullptr : &it->second;
  int64_t n = t.table ? t.table->count : 0;
  NExpr *ref = expr(d->base(), f, pre);
  if (auto *r = llvm::dyn_cast<net::Ref>(ref))
    for (auto it = knownConstants.rbegin(); it != knownConstants.rend(); ++it)
      if (r->name == it->first) {
        ref = b.intLit(it->second, d->loc);
        break;
      }
  std::string what = stemOf(d->base()) + "_deref";
  // A constant reference (ADR(x) stepped by constants) designates one
  // place, known now.
  if (auto *lit = llvm::dyn_cast<net::IntLit>(ref);
      lit && lit->value >= 1 && lit->value <= n) {
    t.constant = lit->value;
    t.number = what;
    for (const RefFamily &fam : t.table->families) {
      if (fam.hasOutside && lit->value == fam.end())
        refuse(d->loc, "the pointer is dereferenced one past the end of '" +
                           fam.key + "'");
      if (fam.holds(lit->value, /*withOutside=*/true) && !fam.holds(lit->value))
        refuse(d->loc, "the pointer is dereferenced outside '" + fam.key + "'");
      if (fam.holds(lit->value)) {
        if (fam.function && !activeCalls.count(fam.function))
          refuse(d->loc, "a reference to a variable of function '" +
                             fam.function->name +
                             "' is dereferenced outside its call");
        t.live.push_back(&fam);
      }
    }
    return t;
  }
  // NULL (0) or uninitialised: a run-time error naming the reference.
  std::string name = scanVariable(
      what, design.types.getRange(1, std::max<int64_t>(n, 1)), 1, d->loc);
  pre.push_back(b.assign(b.ref(name, d->loc), ref, d->loc));
  t.number = name;
  if (!t.table)
    return t;
  // One past the end of an array, or another address outside it,
  // designates nothing, and a function's variables exist only while a call
  // of it runs (a reference to them dereferenced elsewhere dangles):
  // run-time errors, each named.
  std::vector<NExpr *> pastEnd, outside, dangling;
  for (const RefFamily &fam : t.table->families) {
    auto is = [&](int64_t k) {
      return b.binary(net::BinaryOp::Eq, b.ref(name, d->loc),
                      b.intLit(k, d->loc), d->loc);
    };
    if (fam.hasOutside) {
      pastEnd.push_back(is(fam.end()));
      for (int64_t k : {fam.farBelow(), fam.before(), fam.farAbove()})
        outside.push_back(is(k));
    }
    if (!fam.function || activeCalls.count(fam.function))
      t.live.push_back(&fam);
    else
      dangling.push_back(familyTest(fam, t));
  }
  failWhenAny(pastEnd, stemOf(d->base()) + "_past_end", pre, d->loc);
  failWhenAny(outside, stemOf(d->base()) + "_outside", pre, d->loc);
  failWhenAny(dangling, stemOf(d->base()) + "_dangling", pre, d->loc);
  return t;
}

void Lowering::failWhenAny(llvm::ArrayRef<NExpr *> tests,
                           const std::string &stem, Sink &pre, SMLoc at) {
  if (tests.empty())
    return;
  NExpr *any = tests[0];
  for (NExpr *test : tests.drop_front())
    any = b.binary(net::BinaryOp::Or, any, test, at);
  // A variable of range 1..1 given 0: the engine's range check reports it.
  std::string check = scanVariable(stem, design.types.getRange(1, 1), 1, at);
  pre.push_back(b.assign(
      b.ref(check, at), b.cond(any, b.intLit(0, at), b.intLit(1, at), at), at));
}

NExpr *Lowering::familyRoot(const RefFamily &fam, const DerefTargets &t,
                            std::string &name) {
  SMLoc at = t.deref->loc;
  name = fam.base;
  if (fam.function)
    name = activeCalls[fam.function].back() + fam.base;
  NExpr *x = nullptr;
  auto place = [&]() { return x ? x : (x = b.ref(name, at)); };
  // Row-major: the element number within the family, split per dimension
  // (a string's bytes, innermost, are not a step).
  std::optional<int64_t> known; // the element number, known now
  if (t.constant || fam.size == 1)
    known = t.constant ? *t.constant - fam.offset : 0;
  NExpr *rel = known ? nullptr
                     : b.binary(net::BinaryOp::Sub, numberOf(t, at),
                                b.intLit(fam.offset, at), at);
  int64_t stride = fam.size;
  for (const RefStep &s : fam.steps) {
    switch (s.kind) {
    case RefStep::Member:
      if (x)
        refuse(at, "internal: an instance member after an element");
      name += "." + sanitize(s.name);
      break;
    case RefStep::Field:
      x = b.field(place(), sanitize(s.name), at);
      break;
    case RefStep::Index:
      for (auto &[lo, hi] : s.dims) {
        int64_t extent = hi - lo + 1;
        stride /= extent;
        if (known) {
          x = b.index(place(), b.intLit(*known / stride % extent + lo, at), at);
          continue;
        }
        NExpr *i = rel;
        if (stride > 1)
          i = b.binary(net::BinaryOp::Div, i, b.intLit(stride, at), at);
        if (stride * extent < fam.size)
          i = b.binary(net::BinaryOp::Mod, i, b.intLit(extent, at), at);
        x = b.index(place(),
                    b.binary(net::BinaryOp::Add, i, b.intLit(lo, at), at), at);
      }
      break;
    }
  }
  return x;
}

NExpr *Lowering::familyPlace(const RefFamily &fam, const DerefTargets &t,
                             Expr *e, Frame &f, Sink &pre) {
  if (fam.view.kind == RefView::Bytes || fam.view.kind == RefView::ByteArray)
    refuse(e->loc, "the bytes of a STRING seen through a pointer are read "
                   "and assigned here, not bound, passed or called");
  if (fam.view.kind == RefView::Scalar)
    refuse(e->loc, "a " + fam.view.seen->str() +
                       " seen through a pointer to another type is read and "
                       "assigned here, not bound, passed or called");
  std::string name;
  NExpr *x = familyRoot(fam, t, name);
  SMLoc at = t.deref->loc;
  auto place = [&]() { return x ? x : (x = b.ref(name, at)); };
  std::vector<Expr *> selectors = placeSelectors(e, t.deref);
  if (fam.view.kind == RefView::Elements) {
    // An array seen with other bounds: the viewing index i is element
    // i - lo of the array seen, which must have it.
    if (selectors.empty() || selectors[0]->kind != ExprKind::Index ||
        selectors[0]->operands.size() != 2)
      refuse(e->loc, "an array seen through a pointer to an array with other "
                     "bounds is read and written one element at a time "
                     "(pt^[i])");
    Expr *s = selectors[0];
    NExpr *i = viewedPosition(fam, t, s->operands[1], fam.view.placeLo,
                              "_element", f, pre);
    x = b.index(place(), i, s->loc);
    selectors.erase(selectors.begin());
  }
  // Then what the program selects in the place designated.
  for (Expr *s : selectors) {
    const PType *bt = s->base()->type;
    if (s->kind == ExprKind::Field) {
      if (bt && bt->kind == PTypeKind::FunctionBlock) {
        if (x)
          refuse(s->loc, "internal: an instance member after an element");
        name += "." + sanitize(s->var->name);
      } else {
        x = b.field(place(), sanitize(s->name), s->loc);
      }
      continue;
    }
    NExpr *r = place();
    for (size_t i = 1; i < s->operands.size(); ++i)
      r = b.index(r, expr(s->operands[i], f, pre), s->loc);
    x = r;
  }
  return place();
}

/// Where in a string seen as bytes the dereference `e` lands: the 1-based
/// position of the byte, checked to lie in the string's bytes.
NExpr *Lowering::bytePosition(const RefFamily &fam, const DerefTargets &t,
                              Expr *e, Frame &f, Sink &pre) {
  SMLoc at = e->loc;
  if (fam.view.kind == RefView::Bytes) {
    if (e != t.deref)
      refuse(e->loc, "internal: a selection in a byte");
    if (t.constant)
      return b.intLit((*t.constant - fam.offset) % fam.view.bytes + 1, at);
    NExpr *rel = b.binary(net::BinaryOp::Sub, numberOf(t, at),
                          b.intLit(fam.offset, at), at);
    if (fam.size > fam.view.bytes)
      rel = b.binary(net::BinaryOp::Mod, rel, b.intLit(fam.view.bytes, at), at);
    return b.binary(net::BinaryOp::Add, rel, b.intLit(1, at), at);
  }
  // POINTER TO ARRAY[lo..hi] OF BYTE over a STRING: pt^[i] is byte i - lo,
  // which must lie among the string's.
  if (e->kind != ExprKind::Index || e->base() != t.deref ||
      e->operands.size() != 2)
    refuse(e->loc, "the bytes of a STRING seen as an array are read and "
                   "written one element at a time (pt^[i])");
  return viewedPosition(fam, t, e->operands[1], 1, "_byte", f, pre);
}

NExpr *Lowering::viewedPosition(const RefFamily &fam, const DerefTargets &t,
                                Expr *indexExpr, int64_t first, StringRef what,
                                Frame &f, Sink &pre) {
  SMLoc at = indexExpr->loc;
  int64_t lo = fam.view.lo;
  NExpr *index = expr(indexExpr, f, pre);
  // Checked only where the reference designates this family (a read
  // selects among families after every check has run).
  if (!llvm::isa<net::IntLit>(index) && !t.constant)
    index = b.cond(familyTest(fam, t), index, b.intLit(lo, at), at);
  NExpr *i = checkedRange(index, lo, lo + fam.view.bytes - 1,
                          t.number + what.str(), pre, at);
  if (auto *lit = llvm::dyn_cast<net::IntLit>(i))
    return b.intLit(lit->value - lo + first, at);
  if (lo == first)
    return i;
  return b.binary(net::BinaryOp::Add, i, b.intLit(first - lo, at), at);
}

NExpr *Lowering::scalarByteShift(const RefFamily &fam, const DerefTargets &t,
                                 Expr *e, Frame &f, Sink &pre) {
  NExpr *pos = scalarBytePosition(fam, t, e, f, pre);
  if (!pos)
    return nullptr;
  if (auto *lit = llvm::dyn_cast<net::IntLit>(pos))
    return b.intLit(lit->value * 8, e->loc);
  return b.binary(net::BinaryOp::Mul, pos, b.intLit(8, e->loc), e->loc);
}

NExpr *Lowering::scalarBytePosition(const RefFamily &fam, const DerefTargets &t,
                                    Expr *e, Frame &f, Sink &pre) {
  if (e == t.deref && fam.view.bytes == 0)
    return nullptr; // the whole scalar, as another of its size
  if (fam.view.byteSteps) {
    // The byte the pointer stands on, counted from the scalar's first.
    if (e != t.deref)
      refuse(e->loc, "internal: a selection in a byte");
    SMLoc at = e->loc;
    if (t.constant)
      return b.intLit((*t.constant - fam.offset) % fam.view.bytes, at);
    NExpr *rel = b.binary(net::BinaryOp::Sub, numberOf(t, at),
                          b.intLit(fam.offset, at), at);
    if (fam.size > fam.view.bytes)
      rel = b.binary(net::BinaryOp::Mod, rel, b.intLit(fam.view.bytes, at), at);
    return rel;
  }
  if (fam.view.bytes == 0 || e->kind != ExprKind::Index ||
      e->base() != t.deref || e->operands.size() != 2)
    refuse(e->loc, "the bytes of a " + fam.view.seen->str() +
                       " seen as an array are read and written one element "
                       "at a time (pt^[i])");
  // Little-endian, as the x64 layout SIZEOF assumes: byte 0 is the lowest.
  return viewedPosition(fam, t, e->operands[1], 0, "_byte", f, pre);
}

NExpr *Lowering::familyValue(const RefFamily &fam, const DerefTargets &t,
                             Expr *e, Frame &f, Sink &pre) {
  if (fam.view.kind == RefView::Plain || fam.view.kind == RefView::Elements)
    return familyPlace(fam, t, e, f, pre);
  if (seesRecordBytes(fam.view)) {
    NExpr *pos = scalarBytePosition(fam, t, e, f, pre);
    FreshPlace at = positionValue(pos, 0, fam.view.bytes - 1, pre, e->loc);
    std::string name;
    FreshPlace place = [&] {
      NExpr *x = familyRoot(fam, t, name);
      return x ? x : b.ref(name, e->loc);
    };
    return recordByte(fam.view.seen, place, at, e->loc);
  }
  if (fam.view.kind == RefView::Scalar) {
    // The place's bits, read as the pointer's type (or one byte of them).
    std::string name;
    NExpr *x = familyRoot(fam, t, name);
    NExpr *place = x ? x : b.ref(name, e->loc);
    NExpr *bits = unionBits(fam.view.seen, place, e->loc);
    const PType *as = baseOf(e->type);
    if (NExpr *shift = scalarByteShift(fam, t, e, f, pre))
      bits = b.binary(net::BinaryOp::Shr, bits, shift, e->loc);
    return fromBits(as, bits, as->width, e->loc);
  }
  std::string name;
  NExpr *x = familyRoot(fam, t, name);
  NExpr *text = x ? x : b.ref(name, e->loc);
  return b.call(net::Builtin::Code, {text, bytePosition(fam, t, e, f, pre)},
                e->loc);
}

void Lowering::familyStore(const RefFamily &fam, const DerefTargets &t,
                           Expr *target, NExpr *value, Expr *valueExpr,
                           Frame &f, Sink &pre, Sink &out, SMLoc at) {
  if (fam.view.kind == RefView::Plain || fam.view.kind == RefView::Elements) {
    assign(familyPlace(fam, t, target, f, pre), value, target->type, valueExpr,
           out, at);
    return;
  }
  if (seesRecordBytes(fam.view)) {
    NExpr *pos = scalarBytePosition(fam, t, target, f, pre);
    FreshPlace where = positionValue(pos, 0, fam.view.bytes - 1, pre, at);
    const PType *as = baseOf(target->type);
    FreshPlace byte =
        positionValue(coerce(value, valueExpr ? valueExpr->type : as, as, at),
                      as->lo, as->hi, pre, at);
    std::string name;
    FreshPlace place = [&] {
      NExpr *x = familyRoot(fam, t, name);
      return x ? x : b.ref(name, at);
    };
    storeRecordByte(fam.view.seen, place, where, byte, out, at);
    return;
  }
  if (fam.view.kind == RefView::Scalar) {
    // The value's bits, stored as the place's type (or as one byte of it,
    // the others kept).
    const PType *as = baseOf(target->type);
    std::string name;
    NExpr *x = familyRoot(fam, t, name);
    NExpr *place = x ? x : b.ref(name, at);
    NExpr *bits = unionBits(
        as, coerce(value, valueExpr ? valueExpr->type : as, as, at), at);
    if (NExpr *shift = scalarByteShift(fam, t, target, f, pre)) {
      NExpr *again = familyRoot(fam, t, name);
      bits = insertBits(
          unionBits(fam.view.seen, again ? again : b.ref(name, at), at), bits,
          8, shift, at);
    }
    out.push_back(b.assign(
        place, fromBits(fam.view.seen, bits, fam.view.seen->width, at), at));
    return;
  }
  NExpr *pos = bytePosition(fam, t, target, f, pre);
  std::string name;
  NExpr *x = familyRoot(fam, t, name);
  NExpr *text = x ? x : b.ref(name, at);
  NExpr *again = familyRoot(fam, t, name);
  NExpr *place = again ? again : b.ref(name, at);
  out.push_back(b.assign(
      place, b.call(net::Builtin::WithCode, {text, pos, value}, at), at));
}

NExpr *Lowering::numberOf(const DerefTargets &t, SMLoc at) {
  return t.constant ? b.intLit(*t.constant, at) : b.ref(t.number, at);
}

NExpr *Lowering::familyTest(const RefFamily &fam, const DerefTargets &t) {
  SMLoc at = t.deref->loc;
  NExpr *k = numberOf(t, at);
  if (fam.size == 1)
    return b.binary(net::BinaryOp::Eq, k, b.intLit(fam.offset, at), at);
  return b.binary(net::BinaryOp::And,
                  b.binary(net::BinaryOp::Ge, k, b.intLit(fam.offset, at), at),
                  b.binary(net::BinaryOp::Le, k,
                           b.intLit(fam.offset + fam.size - 1, at), at),
                  at);
}

NExpr *Lowering::readThroughReference(Expr *e, Frame &f, Sink &pre) {
  DerefTargets t = derefTargets(e, f, pre);
  SMLoc at = e->loc;
  if (t.live.empty()) {
    // Nothing of its type has its address taken (or only variables of
    // functions not running here): the reference is NULL or dangling
    // whenever this runs, which the checks above report.
    if (NExpr *v = defaultValue(e->type, at))
      return v;
    refuse(at, "a reference to " + t.deref->type->str() +
                   " is dereferenced, but no REF or ADR of a " +
                   t.deref->type->str() + " gives it a value here");
  }
  auto &fams = t.live;
  if (fams.size() == 1)
    return familyValue(*fams[0], t, e, f, pre);
  const net::Type *nt = netType(e->type, at, "a dereferenced value");
  if (nt->isScalar() || nt->isString()) {
    NExpr *r = familyValue(*fams.back(), t, e, f, pre);
    for (size_t i = fams.size() - 1; i-- > 0;)
      r = b.cond(familyTest(*fams[i], t), familyValue(*fams[i], t, e, f, pre),
                 r, at);
    return r;
  }
  // An array or a structure: copied whole from the place designated.
  std::string value = unique(t.number + "_value");
  declareTemp(value, e->type, at);
  std::vector<NExpr *> tests;
  std::vector<Sink> bodies;
  for (const RefFamily *fam : fams) {
    tests.push_back(familyTest(*fam, t));
    bodies.push_back(
        {b.assign(b.ref(value, at), familyPlace(*fam, t, e, f, pre), at)});
  }
  emitChoice(tests, bodies, pre, at);
  return b.ref(value, at);
}

NExpr *Lowering::placeThroughReference(Expr *e, Frame &f, Sink &pre,
                                       StringRef use) {
  DerefTargets t = derefTargets(e, f, pre);
  if (t.live.size() == 1)
    return familyPlace(*t.live[0], t, e, f, pre);
  refuse(e->loc, "a dereference that may designate " + Twine(t.live.size()) +
                     " different variables is " + use +
                     " here; only an assignment writes through it");
}

void Lowering::writeThroughReference(Expr *target, NExpr *value,
                                     Expr *valueExpr, Frame &f, Sink &out,
                                     SMLoc at) {
  DerefTargets t = derefTargets(target, f, out);
  auto &fams = t.live;
  if (fams.empty())
    return; // the checks above report the NULL or dangling reference
  if (fams.size() == 1) {
    familyStore(*fams[0], t, target, value, valueExpr, f, out, out, at);
    return;
  }
  // The value once, then stored where the reference points.
  value = valueOnce(value, valueExpr ? valueExpr->type : target->type, t.number,
                    out, at);
  std::vector<NExpr *> tests;
  std::vector<Sink> bodies(fams.size());
  for (size_t i = 0; i < fams.size(); ++i) {
    tests.push_back(familyTest(*fams[i], t));
    familyStore(*fams[i], t, target, value, valueExpr, f, bodies[i], bodies[i],
                at);
  }
  emitChoice(tests, bodies, out, at);
}

//===----------------------------------------------------------------------===//
// Interfaces queried
//===----------------------------------------------------------------------===//

NExpr *Lowering::interfaceQuery(NExpr *source, const PType *wanted, Sink &pre,
                                SMLoc at) {
  auto table = refPlan.tables.find(referenceKey(wanted->elem));
  if (table == refPlan.tables.end())
    return b.intLit(0, at); // no instance is ever seen through an interface
  source = valueOnce(source, wanted, "query", pre, at);
  NExpr *yes = nullptr;
  for (const RefFamily &fam : table->second.families) {
    auto type = instanceTypes.find(fam.base);
    if (type == instanceTypes.end() || !type->second)
      refuse(at, "the interface may designate '" + fam.key +
                     "', an instance whose block netlift does not know, so "
                     "it cannot ask it for another interface");
    if (!implementsInterface(unit, type->second, wanted->elem->fb))
      continue;
    NExpr *is =
        b.binary(net::BinaryOp::Eq, source, b.intLit(fam.offset, at), at);
    yes = yes ? b.binary(net::BinaryOp::Or, yes, is, at) : is;
  }
  return yes ? b.cond(yes, source, b.intLit(0, at), at) : b.intLit(0, at);
}

NExpr *Lowering::referenceUpcast(Expr *call, Frame &f, Sink &pre) {
  Expr *source = call->args[0].value;
  SMLoc at = call->loc;
  auto from = refPlan.tables.find(referenceKey(source->type->elem));
  NExpr *value = expr(source, f, pre);
  if (from == refPlan.tables.end())
    return b.intLit(0, at); // it never designates anything
  const RefTable &to = refPlan.tables.at(referenceKey(call->type->elem));
  value = valueOnce(value, source->type, "upcast", pre, at);
  // Each family's numbers to the same family's among the base's places;
  // NULL stays NULL.
  NExpr *out = b.intLit(0, at);
  for (const RefFamily &fam : llvm::reverse(from->second.families)) {
    const RefFamily &same = to.families[to.byKey.at(fam.key)];
    if (fam.hasOutside != same.hasOutside)
      refuse(at, "a pointer to '" + source->type->elem->str() +
                     "' stepped outside '" + fam.key +
                     "' cannot be seen as a pointer to '" +
                     call->type->elem->str() + "'");
    NExpr *in = b.binary(
        net::BinaryOp::And,
        b.binary(net::BinaryOp::Ge, value, b.intLit(fam.first(), at), at),
        b.binary(net::BinaryOp::Le, value, b.intLit(fam.last(), at), at), at);
    NExpr *renumbered =
        same.offset == fam.offset
            ? value
            : b.binary(net::BinaryOp::Add, value,
                       b.intLit(same.offset - fam.offset, at), at);
    out = b.cond(in, renumbered, out, at);
  }
  return out;
}

NExpr *Lowering::queryInterfaceCall(Expr *call, Frame &f, Sink &pre) {
  Expr *to = call->args[1].value;
  NExpr *value = interfaceQuery(expr(call->args[0].value, f, pre), to->type,
                                pre, call->loc);
  NExpr *target = lvalue(to, f, pre);
  pre.push_back(b.assign(target, value, call->loc));
  return b.binary(net::BinaryOp::Ne, lvalue(to, f, pre), b.intLit(0, call->loc),
                  call->loc);
}
