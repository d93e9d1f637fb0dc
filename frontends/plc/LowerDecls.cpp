//===- LowerDecls.cpp - PLC types and declarations in NetIR
//-----------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Types and declarations
//===----------------------------------------------------------------------===//

std::string Lowering::sanitize(StringRef name) {
  std::string bare;
  for (char c : name)
    if (c != '%')
      bare += c;
  return net::toIdentifier(bare);
}

std::string Lowering::unique(std::string name) {
  std::string n = name;
  for (unsigned i = 2; mod->lookup(n).kind != net::SymKind::None; ++i)
    n = name + "_" + std::to_string(i);
  return n;
}

const net::Type *Lowering::netType(const PType *t, SMLoc at, StringRef what) {
  auto it = typeCache.find(t);
  if (it != typeCache.end())
    return it->second;
  net::TypeTable &tt = design.types;
  const net::Type *r = nullptr;
  switch (t->kind) {
  case PTypeKind::Bool:
  case PTypeKind::AnyInt:
  case PTypeKind::Time:
    r = scalarNetType(t, tt);
    break;
  case PTypeKind::Int:
    r = scalarNetType(t, tt);
    break;
  case PTypeKind::Real:
    r = floatType(t);
    break;
  case PTypeKind::String:
    r = t->isChar() ? scalarNetType(t, tt) : stringType(t, at, what);
    break;
  case PTypeKind::Date:
    r = scalarNetType(t, tt);
    break;
  case PTypeKind::Enum: {
    std::string name = sanitize(t->name.empty() ? "Enum" : t->name);
    if (const net::Type *existing = tt.lookup(name)) {
      r = existing;
      break;
    }
    std::vector<StringRef> names;
    for (auto &e : t->enumerators)
      names.push_back(design.save(sanitize(e)));
    r = tt.createEnum(design.save(name), names);
    break;
  }
  case PTypeKind::Array: {
    const net::Type *elem = netType(t->elem, at, what);
    for (size_t d = t->dims.size(); d-- > 0;)
      elem = tt.getArray(elem, t->dims[d].first, t->dims[d].second);
    r = elem;
    break;
  }
  case PTypeKind::Struct: {
    if (t->isUnion) {
      r = unionType(t, at);
      break;
    }
    std::string name = sanitize(t->name.empty() ? "Struct" : t->name);
    if (const net::Type *existing = tt.lookup(name)) {
      r = existing;
      break;
    }
    std::vector<net::Field> fields;
    for (VarDecl *f : t->fields)
      fields.push_back({design.save(sanitize(f->name)),
                        netType(f->type, f->loc, "field " + f->name)});
    r = tt.createRecord(design.save(name), fields);
    break;
  }
  case PTypeKind::Reference:
    // 0 is NULL, 1..n the places it may designate (LowerReferences.cpp).
    r = tt.getRange(0, t->elem ? referenceCount(t->elem) : 0);
    break;
  case PTypeKind::FunctionBlock:
  case PTypeKind::Void:
    refuse(at, "internal: no NetIR type for " + t->str());
  }
  typeCache[t] = r;
  return r;
}

const net::Type *plc::scalarNetType(const PType *t, net::TypeTable &tt) {
  switch (t->kind) {
  case PTypeKind::Bool:
    return tt.getBool();
  case PTypeKind::Int:
    if (t->isSubrange)
      return tt.getRange(t->lo, t->hi);
    return tt.getInt(t->width, t->isSigned, net::Overflow::Wrap);
  case PTypeKind::AnyInt:
    return tt.getInt(64, true, net::Overflow::Wrap);
  case PTypeKind::Time:
  case PTypeKind::Date: // nanoseconds (LowerDates.cpp)
    return tt.getInt(64, true, net::Overflow::Error);
  case PTypeKind::Real:
    return tt.getFloat(t->width == 32 ? 32 : 64);
  case PTypeKind::String:
    // CHAR and WCHAR hold a character's code.
    return t->isString() ? tt.getString(t->strLen, t->width == 16)
                         : tt.getInt(t->width, false, net::Overflow::Wrap);
  default:
    return nullptr;
  }
}

NExpr *Lowering::defaultValue(const PType *t, SMLoc at) {
  if (t->kind == PTypeKind::Struct && t->isUnion)
    return b.intLit(0, at); // all bytes zero
  switch (t->kind) {
  case PTypeKind::Bool:
    return b.boolLit(false, at);
  case PTypeKind::Int:
    return b.intLit(t->isSubrange ? t->lo : 0, at);
  case PTypeKind::Time:
  case PTypeKind::AnyInt:
  case PTypeKind::Date: // 1970-01-01, midnight: CODESYS's and TwinCAT's 0
    return b.intLit(0, at);
  case PTypeKind::Real:
    return b.realLit(0.0, at);
  case PTypeKind::String:
    return t->isChar() ? b.intLit(0, at) : b.stringLit({}, at);
  case PTypeKind::Enum:
    return b.ref(sanitize(t->name) + "#" + sanitize(t->enumerators[0]), at);
  case PTypeKind::Reference:
    return b.intLit(0, at); // NULL
  default:
    return nullptr; // aggregates: NetIR's defaults match IEC's
  }
}

/// Whether a value of type `t` starts anywhere else than at IEC's default
/// (a structure field with its own initial value).
static bool hasDeclaredInitial(const PType *t) {
  if (t->kind == PTypeKind::Array)
    return hasDeclaredInitial(t->elem);
  if (t->kind == PTypeKind::Struct)
    for (VarDecl *f : t->fields)
      if ((f->typeSyntax && f->typeSyntax->init) || hasDeclaredInitial(f->type))
        return true;
  return false;
}

NExpr *Lowering::aggregateValue(VarDecl *v, Initializer *init, const PType *t,
                                size_t dim, SMLoc at) {
  // Sema has checked the initialiser's shape against the type (array list
  // for an array, field list for a structure, one dimension); the count is
  // checked here.
  std::vector<NExpr *> elems;
  std::vector<StringRef> names;
  if (t->kind == PTypeKind::Array) {
    auto [lo, hi] = t->dims[dim];
    size_t n = size_t(hi - lo + 1);
    auto element = [&](Initializer *e) {
      return dim + 1 < t->dims.size() ? aggregateValue(v, e, t, dim + 1, at)
                                      : initialValue(v, e, t->elem, at);
    };
    if (init) {
      for (auto &[count, inner] : init->elems)
        for (int64_t k = 0; k < count; ++k) {
          if (elems.size() == n)
            refuse(init->loc, "the initialiser of '" + v->name +
                                  "' has more than the " + Twine(n) +
                                  " elements of its array");
          elems.push_back(element(inner));
        }
    }
    // IEC 61131-3: elements the list does not reach keep their default.
    while (elems.size() < n)
      elems.push_back(element(nullptr));
  } else {
    for (VarDecl *f : t->fields) {
      Initializer *given = f->typeSyntax ? f->typeSyntax->init : nullptr;
      if (init)
        for (auto &[name, inner] : init->fields)
          if (sameName(name, f->name))
            given = inner;
      elems.push_back(initialValue(f, given, f->type, at));
      names.push_back(design.save(sanitize(f->name)));
    }
  }
  return b.aggregate(elems, names, init ? init->loc : at);
}

NExpr *Lowering::initialValue(VarDecl *v, Initializer *init, const PType *t,
                              std::optional<SMLoc> at) {
  SMLoc loc = at ? *at : v->loc;
  if (t->kind == PTypeKind::Struct && t->isUnion)
    return unionInitialValue(v, init, t, loc);
  if (t->kind == PTypeKind::Array || t->kind == PTypeKind::Struct) {
    // Aggregates start at IEC's defaults unless something says otherwise,
    // and NetIR's defaults are the same: no initial value needed then.
    if (!init && !at && !hasDeclaredInitial(t))
      return nullptr;
    return aggregateValue(v, init, t, 0, loc);
  }
  if (!init)
    return defaultValue(t, loc);
  if (init->kind != Initializer::Value)
    refuse(init->loc, "an array or structure initialiser for '" + v->name +
                          "' of type " + t->str());
  Frame none;
  Expr *e = init->value;
  if (t->kind == PTypeKind::Enum) {
    if (e->enumValue < 0)
      refuse(e->loc, "initial value must be an enumerator");
    return b.ref(sanitize(t->name) + "#" +
                     sanitize(t->enumerators[e->enumValue]),
                 e->loc);
  }
  if (t->kind == PTypeKind::String) {
    // A literal, or a CONSTANT whose initial value is one.
    Expr *lit = e;
    while (lit->kind == ExprKind::Name && lit->var && lit->var->constant &&
           lit->var->typeSyntax && lit->var->typeSyntax->init &&
           lit->var->typeSyntax->init->kind == Initializer::Value)
      lit = lit->var->typeSyntax->init->value;
    if (lit->kind != ExprKind::StringLit)
      refuse(e->loc, "initial value of '" + v->name +
                         "' must be a string literal or a CONSTANT");
    return t->isChar() ? charLiteral(lit) : stringLiteral(lit);
  }
  if (t->kind == PTypeKind::Real || t->kind == PTypeKind::Date) {
    Sink pre;
    NExpr *r = coerce(expr(e, none, pre), e->type, t, e->loc);
    if (!pre.empty())
      refuse(e->loc, "initial value of '" + v->name + "' must be a constant");
    return r;
  }
  if (e->kind == ExprKind::IntLit && e->beyondInt64)
    return unsigned64Literal(uint64_t(e->intValue), e->loc);
  if (t->kind == PTypeKind::Reference) {
    // NULL, or REF/ADR of a place with constant indices: a number known
    // now, in the instance being declared.
    Frame here;
    here.pou = v->owner;
    here.prefix = declaringPrefix; // a structure field's too
    Sink pre;
    NExpr *r = expr(e, here, pre);
    if (!pre.empty() || !llvm::isa<net::IntLit>(r))
      refuse(e->loc, "initial value of '" + v->name +
                         "' must be NULL or REF/ADR of a variable with "
                         "constant indices");
    return r;
  }
  std::optional<int64_t> c = constValue(e, none);
  if (!c)
    refuse(e->loc, "initial value of '" + v->name + "' must be a constant");
  if (t->kind == PTypeKind::Bool)
    return b.boolLit(*c != 0, e->loc);
  return b.intLit(*c, e->loc);
}

std::optional<std::pair<int64_t, int64_t>> Lowering::inputRange(VarDecl *v) {
  auto parse = [](StringRef s) -> std::optional<std::pair<int64_t, int64_t>> {
    s = s.trim().trim("'\"").trim();
    auto [a, c] = s.split("..");
    int64_t lo, hi;
    if (a.trim().getAsInteger(10, lo) || c.trim().getAsInteger(10, hi) ||
        lo > hi)
      return std::nullopt;
    return std::make_pair(lo, hi);
  };
  for (auto &a : v->attrs) {
    StringRef t(a.text);
    t.consume_front("netlift");
    t = t.trim();
    // `{range 0..100}`, `{netlift range 0..100}`,
    // `{attribute 'range' := '0..100'}`.
    if (t.consume_front("range")) {
      if (auto r = parse(t))
        return r;
      refuse(a.loc, "malformed range pragma (write {range LO..HI})");
    }
    if (t.consume_front("attribute") && t.trim().consume_front("'range'")) {
      StringRef rest = t.trim();
      rest.consume_front("'range'");
      rest = rest.trim();
      rest.consume_front(":=");
      if (auto r = parse(rest))
        return r;
      refuse(a.loc, "malformed range attribute (write {attribute 'range' := "
                    "'LO..HI'})");
    }
  }
  for (const std::string &key : {v->name, v->location}) {
    if (key.empty())
      continue;
    rangeCandidates.push_back(key);
    auto it = opts.ranges.find(StringRef(key).upper());
    if (it != opts.ranges.end()) {
      rangesUsed.insert(it->first);
      if (it->second.notNull != (v->type && v->type->isReference()))
        refuse(it->second.loc,
               it->second.notNull
                   ? "--ranges: 'NOT NULL' is for a reference input, and '" +
                         v->name + "' is " + v->type->str()
                   : "--ranges: input '" + v->name + "' is a " +
                         v->type->str() +
                         ": give 'NOT NULL' (the caller never passes NULL), "
                         "not a range");
      return std::make_pair(it->second.lo, it->second.hi);
    }
  }
  return std::nullopt;
}

void Lowering::declareProgramVar(VarDecl *v) {
  if (!v->type)
    refuse(v->loc, "internal: untyped variable");
  const PType *t = v->type;
  if (v->section == VarSection::External)
    return; // the global is declared once
  std::string name = (v->owner ? programPrefix : "") + sanitize(v->name);
  declaringPrefix = programPrefix;
  declaringLoc = v->loc;
  if (v->generated)
    b.addAttribute(name, net::kInternalAttribute, "generated for an element",
                   v->loc);
  // The caller's variable, or one shared with code outside the design: the
  // environment's (LowerEnvironment.cpp).
  if (v->section == VarSection::InOut || v->sharedOutside) {
    declareEnvironmentValue(v, name);
    return;
  }
  if (!v->runtimeRecord.empty()) {
    declareRuntimeRecord(v, name);
    return;
  }
  if (instanceBlock(t)) {
    keepPragmas(name, v->attrs);
    sourcePaths[name] = (v->owner                ? v->owner->name + "."
                         : v->globalList.empty() ? std::string()
                                                 : v->globalList + ".") +
                        v->name;
    declareInstances(name, t, v->typeSyntax ? v->typeSyntax->init : nullptr);
    return;
  }
  keepPragmas(name, v->attrs);
  // An input bound to a global by a program argument is fed from it.
  bool isInput = (v->area() == 'I' || v->section == VarSection::Input) &&
                 !boundInputs.count(v);
  bool isOutput = v->area() == 'Q' || v->section == VarSection::Output;
  varTypes[name] = t;
  if (isInput) {
    if (t->kind == PTypeKind::Bool) {
      b.addPort(name, net::PortKind::Cond, net::PortDir::In, nullptr, v->loc);
      return;
    }
    const net::Type *nt = nullptr;
    if (t->isReference()) {
      nt = netType(t, v->loc, "input " + v->name);
      // NOT NULL: one of the places, never 0.
      if (inputRange(v)) {
        if (nt->hi < 1)
          refuse(v->loc, "input '" + v->name +
                             "' is NOT NULL, but nothing of its type has "
                             "its address taken");
        nt = design.types.getRange(1, nt->hi);
      }
    } else if (auto r = inputRange(v)) {
      if (t->kind != PTypeKind::Int && t->kind != PTypeKind::Time)
        refuse(v->loc,
               "a range is given for non-integer input '" + v->name + "'");
      if (r->first < t->lo || r->second > t->hi)
        if (t->kind == PTypeKind::Int)
          refuse(v->loc, "range " + Twine(r->first) + ".." + Twine(r->second) +
                             " of input '" + v->name + "' exceeds " + t->str());
      nt = design.types.getRange(r->first, r->second);
      inputRanges[v] = *r;
    } else if (eventDriven || t->kind == PTypeKind::Enum ||
               (t->kind == PTypeKind::Int && t->isSubrange)) {
      nt = netType(t, v->loc, "input " + v->name);
    } else if (t->kind == PTypeKind::Int || t->kind == PTypeKind::Time ||
               t->kind == PTypeKind::Date) {
      // A free input of its full type: translation needs no range, but an
      // exploration would enumerate every value at every step, so the
      // exploring commands ask for one (ExplorationSetup).
      nt = netType(t, v->loc, "input " + v->name);
      b.addAttribute(name, net::kNeedsRangeAttribute,
                     design.save(v->name + " : " + t->str()), v->loc);
    } else {
      nt = netType(t, v->loc, "input " + v->name);
    }
    // An IEC 61499 block's inputs are connected in its network (what is
    // left free at the top is refused when explored); a PLC program's are
    // the environment's, which chooses scalars.
    if (!eventDriven && !nt->isScalar() && !nt->isString()) {
      declareEnvironmentValue(v, name);
      return;
    }
    b.addPort(name, net::PortKind::Data, net::PortDir::In, nt, v->loc);
    if (const PType *elem = callerTarget(v))
      declareCallerTarget(v, name, elem);
    return;
  }
  if (v->section == VarSection::Temp) {
    // Back at its declared initial value for the next scan or call.
    declareTemp(
        name, t, v->loc,
        initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr, t),
        true);
    return;
  }
  NExpr *init =
      initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr, t);
  if (v->owner)
    if (NExpr *p = instancePathValue(v, v->owner->name))
      init = p;
  if (isOutput) {
    const net::Type *nt = netType(t, v->loc, "output " + v->name);
    uint32_t p = t->kind == PTypeKind::Bool
                     ? b.addPort(name, net::PortKind::Cond, net::PortDir::Out,
                                 nullptr, v->loc)
                     : b.addPort(name, net::PortKind::Data, net::PortDir::Out,
                                 nt, v->loc);
    mod->ports[p].init = init;
    return;
  }
  b.addVar(name, netType(t, v->loc, "variable " + v->name), init, v->loc);
}

void Lowering::declareInstance(const std::string &path, Pou *fb,
                               Initializer *init) {
  instanceTypes[path] = fb;
  if (!fb->environment.empty()) {
    declareEnvironment(path, fb);
    return;
  }
  // The block type's pragmas go to the instance, as flatten would carry a
  // module's. netlift's own blocks' pragmas are directives to netlift.
  if (!fb->isLibrary)
    keepPragmas(path, fb->attrs);
  for (VarDecl *m : fb->vars) {
    if (m->section == VarSection::External || m->section == VarSection::Stat)
      continue; // a global's; the block type's (staticVar)
    std::string name = path + "." + sanitize(m->name);
    declaringPrefix = path + ".";
    declaringLoc = m->loc;
    if (!fb->isLibrary)
      keepPragmas(name, m->attrs);
    Initializer *mi = m->typeSyntax ? m->typeSyntax->init : nullptr;
    if (init && init->kind == Initializer::Struct)
      for (auto &[fname, finit] : init->fields)
        if (sameName(fname, m->name))
          mi = finit;
    if (m->section == VarSection::InOut)
      continue; // an alias of the caller's variable (or instance) per call
    // What netlift's own blocks keep besides their interface (a timer's
    // state and clock) is not the user's: traces hide it by default.
    // An SFC step's inputs are the chart's machinery too: the user reads
    // its X and T.
    bool sfcStepInput = fb->isLibrary &&
                        llvm::StringRef(fb->name).startswith("NETLIFT_SFC_") &&
                        m->section == VarSection::Input;
    if ((fb->isLibrary && m->section == VarSection::Var) || m->generated ||
        sfcStepInput)
      b.addAttribute(name, net::kInternalAttribute,
                     m->generated   ? "generated for an element"
                     : sfcStepInput ? "SFC step of the chart"
                                    : "state of " + fb->name,
                     m->loc);
    if (instanceBlock(m->type)) {
      sourcePaths[name] = sourcePaths[path] + "." + m->name;
      declareInstances(name, m->type, mi);
      continue;
    }
    varTypes[name] = m->type;
    bool isClock = false;
    std::string bound;
    for (auto &a : m->attrs) {
      StringRef t(a.text);
      if (t.consume_front("netlift clock")) {
        isClock = true;
        bound = t.trim().str();
      }
    }
    if (isClock) {
      // The cap is fixed once every call is lowered (see run()).
      b.addVar(name, design.types.getClock(1), nullptr, m->loc);
      ClockUse &cu = clocks[name];
      cu.var = name;
      cu.member = bound;
      cu.path = path;
      clockOfBound[path + "." + sanitize(bound)] = name;
      for (VarDecl *o : fb->vars)
        if (o->type && o->type->kind == PTypeKind::Time && o != m)
          cu.timeMembers.push_back(path + "." + sanitize(o->name));
      continue;
    }
    if (m->section == VarSection::Temp) {
      declareTemp(name, m->type, m->loc, nullptr, true);
      continue;
    }
    NExpr *init = initialValue(m, mi, m->type);
    if (NExpr *p = instancePathValue(m, sourcePaths[path]))
      init = p;
    b.addVar(name, netType(m->type, m->loc, "member " + m->name), init, m->loc);
    instanceMembers.push_back(name);
    if (m->sharedOutside) {
      // An HMI_<T> member: the web HMI may write it between scans.
      std::string port = name;
      std::replace(port.begin(), port.end(), '.', '_');
      scanSamples[programPrefix].push_back(
          chooseScalars(name, port + "_in", m->type,
                        "HMI variable '" + name + "'", name, m->loc));
    }
    if (m->edge) { // what the caller passed last time
      b.addVar(name + ".prev", design.types.getBool(), b.boolLit(false, m->loc),
               m->loc);
      b.addAttribute(name + ".prev", net::kInternalAttribute, "edge detection",
                     m->loc);
    }
  }
}

/// An instance of a block with effects netlift does not model: each of its
/// outputs is a free input of the model (an integer one as a program's
/// unranged input is), its inputs are not stored. Refused by
/// --opaque=refuse where it is called.
void Lowering::declareEnvironment(const std::string &path, Pou *fb) {
  std::string sampled;
  for (VarDecl *m : fb->vars) {
    if (m->section != VarSection::Output)
      continue;
    std::string name = path + "." + sanitize(m->name);
    varTypes[name] = m->type;
    if (m->type->kind == PTypeKind::Bool) {
      b.addPort(name, net::PortKind::Cond, net::PortDir::In, nullptr, m->loc);
      continue;
    }
    const net::Type *nt = netType(m->type, m->loc, "output " + m->name);
    if (!nt->isScalar() && !nt->isString()) {
      // A structure or array: the block's variable, its scalars chosen at
      // every call and where it is read whole (LowerEnvironment.cpp), so
      // what is left at the end of a scan is never read: reset there.
      declareTemp(name, m->type, m->loc);
      ChosenScalars chosen = chooseScalars(
          name, name, m->type, "output '" + m->name + "' of " + fb->name, name,
          m->loc);
      // Updated by the environment whether or not the program calls the
      // block: a scalar of it read is its free input, read there; a part
      // read whole is chosen where it is read (environmentRead).
      addEnvironmentValue(chosen, "'" + path + "' (" + fb->name + ") " +
                                      fb->environment);
      sampled += (sampled.empty() ? "" : ", ") + m->name;
      continue;
    }
    b.addPort(name, net::PortKind::Data, net::PortDir::In, nt, m->loc);
    if (m->type->kind == PTypeKind::Int || m->type->kind == PTypeKind::Time)
      b.addAttribute(name, net::kNeedsRangeAttribute,
                     design.save(name + " : " + m->type->str()), m->loc);
  }
  if (sampled.empty())
    return;
  // Read whether or not the program calls it (an axis's status): said
  // where it is declared (refused where it is read, with --opaque=refuse).
  if (!opts.opaqueRefused && notedEnvironment.insert(path).second)
    diag.note(declaringLoc,
              "'" + path + "' (" + fb->name + ") " + fb->environment +
                  ": modelled as environment, its outputs are free inputs "
                  "of the model (" +
                  sampled + " too, where they are read)");
}

/// VAR_STAT of a function block or function: one variable for every
/// instance and call, kept from scan to scan (CODESYS's static variables),
/// declared where it is first used.
std::string Lowering::staticVar(VarDecl *v, SMLoc at) {
  std::string name =
      "static." + sanitize(v->owner->name) + "." + sanitize(v->name);
  if (mod->lookup(name).kind == net::SymKind::None) {
    varTypes[name] = v->type;
    b.addVar(
        name, netType(v->type, v->loc, "variable " + v->name),
        initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr, v->type),
        v->loc);
  }
  return name;
}

uint32_t Lowering::declareTemp(const std::string &name, const PType *t,
                               SMLoc at, NExpr *initial, bool local) {
  varTypes[name] = t;
  NExpr *init = initial ? initial : defaultValue(t, at);
  uint32_t x = b.addVar(name, netType(t, at, "variable " + name), init, at);
  // An array or structure is reset to its type's initial value too: a
  // function's local buffer must not make states differ after the scan.
  NExpr *reset = init;
  if (!reset && local &&
      (t->kind == PTypeKind::Array ||
       (t->kind == PTypeKind::Struct && !t->isUnion)))
    reset = aggregateValue(nullptr, nullptr, t, 0, at);
  if (resetNames.insert(name).second && reset)
    resets.push_back({name, reset});
  return x;
}

NExpr *Lowering::instancePathValue(VarDecl *v, const std::string &source) {
  bool wanted = false;
  for (const Attribute &a : v->attrs)
    wanted |= StringRef(a.text).contains_insensitive("'instance-path'");
  const PType *t = v->type ? baseOf(v->type) : nullptr;
  if (!wanted || !t || !t->isString())
    return nullptr;
  // The device tree's path, as TwinCAT gives it: the project, then the
  // program and the instances down to this one, cut to the string's length.
  std::string root = unit.projectName.empty() ? "PLC" : unit.projectName;
  std::string text = root + "." + source;
  if (text.size() > t->strLen)
    text.resize(t->strLen);
  if (instancePathsNoted.insert(v).second)
    diag.note(v->loc, "'" + v->name + "' holds its instance's path, as '" +
                          text + "'" +
                          (unit.projectName.empty()
                               ? " (the project's name is not known without "
                                 "a .plcproj: 'PLC' stands for it)"
                               : ""));
  std::u16string chars(text.begin(), text.end());
  return b.stringLit(llvm::ArrayRef<char16_t>(chars.data(), chars.size()),
                     v->loc);
}
