//===- Iec61499Basic.cpp - basic FBs as PLC blocks ------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

//===----------------------------------------------------------------------===//
// Basic function blocks
//===----------------------------------------------------------------------===//

/// Whether `name` is one the scaffolding of a basic FB's module uses (the
/// ECC state, the event queue, a reaction's scratch variables): a
/// variable of the FB's own by that name is renamed.
static bool scaffoldingName(StringRef name) {
  std::string u = name.upper();
  return u == "ECC" || u == "_QUEUE" || u == "_QUEUED" || u == "_LIVE" ||
         u == "_EVENT" || u == "_FIRED" || u == "_STEP" ||
         u == "_ECC_DOES_NOT_SETTLE" || StringRef(u).startswith("_EV_");
}

/// The name under which the model keeps variable `name` of the FB: `_X`
/// for the internal copy of interface variable X, the name itself for an
/// internal variable; a trailing `_` where that is a scaffolding name
/// (an input STEP is kept in `_STEP_`: IEC identifiers never end in `_`).
static std::string modelName(StringRef name, bool copy) {
  std::string n = (copy ? "_" : "") + name.str();
  return scaffoldingName(n) ? n + "_" : n;
}

std::string Translator::internal(StringRef name) const {
  auto it = copied.find(StringRef(name).upper());
  return it != copied.end() ? it->second : modelName(name, true);
}
/// Under the cyclic model: whether event `name` is pending.
static std::string eventFlag(StringRef name) { return "_ev_" + name.str(); }

void Translator::rename(Expr *e) {
  if (!e)
    return;
  // `S.x`, element x of plug or socket S, is the port it became.
  if (e->kind == ExprKind::Field && current && e->operands.size() == 1 &&
      e->operands[0]->kind == ExprKind::Name)
    if (const AdapterUse *a = current->adapter(e->operands[0]->name)) {
      e->kind = ExprKind::Name;
      e->name = adapterPort(a->name, e->name);
      e->operands.clear();
    }
  if (e->kind == ExprKind::Name)
    if (auto it = copied.find(StringRef(e->name).upper()); it != copied.end())
      e->name = it->second;
  for (Expr *o : e->operands)
    rename(o);
  for (CallArg &a : e->args)
    rename(a.value);
}

void Translator::rename(StmtList &l) {
  plc::forEachStmt(l, nullptr, [&](Expr *e) { rename(e); });
}

StmtList Translator::algorithm(FbType &t, StringRef name, pugi::xml_node at) {
  for (pugi::xml_node a : t.body.children("Algorithm")) {
    if (!StringRef(a.attribute("Name").value()).equals_insensitive(name))
      continue;
    StringRef text = stText(t, a, "algorithm");
    StmtList out;
    std::vector<VarDecl *> temps;
    if (!st::parseAlgorithmBody(text, diag, unit, temps, out))
      throw Failure();
    callFunctionTypes(out);
    callInternalFbs(t, out);
    if (temps.empty()) {
      rename(out);
      return out;
    }
    // The algorithm's VAR_TEMPs become temporaries of the block's POU
    // under names of their own (`_tmp_REQ_i`), back at their initial value
    // at the end of every reaction, and set to it where the algorithm
    // starts (so a second run in one reaction starts afresh too).
    std::map<std::string, std::string> outer = copied;
    StmtList start;
    AstMaker make(unit);
    for (VarDecl *v : temps) {
      std::string model = "_tmp_" + name.str() + "_" + v->name;
      copied[StringRef(v->name).upper()] = model;
      v->name = model;
      if (algorithmTemps.insert(StringRef(model).upper()).second)
        currentPou->vars.push_back(v);
      Initializer *init = v->typeSyntax ? v->typeSyntax->init : nullptr;
      Expr *value =
          init && init->kind == Initializer::Value ? init->value : nullptr;
      if (!init && v->typeSyntax &&
          v->typeSyntax->kind == TypeSyntaxKind::Named) {
        StringRef type = v->typeSyntax->name;
        if (type.equals_insensitive("BOOL"))
          value = make.boolLit(false, v->loc);
        else if (llvm::is_contained(
                     std::initializer_list<StringRef>{
                         "SINT", "INT", "DINT", "LINT", "USINT", "UINT",
                         "UDINT", "ULINT", "BYTE", "WORD", "DWORD", "LWORD"},
                     type.upper()))
          value = make.intLit(0, v->loc);
        else if (type.equals_insensitive("REAL") ||
                 type.equals_insensitive("LREAL"))
          value = make.make(ExprKind::RealLit, v->loc); // 0.0
        else if (type.equals_insensitive("TIME"))
          value = make.make(ExprKind::TimeLit, v->loc); // T#0s
      }
      if (value)
        start.push_back(
            make.assign(make.nameRef(model, v->loc), value, v->loc));
    }
    out.insert(out.begin(), start.begin(), start.end());
    rename(out);
    copied = std::move(outer);
    return out;
  }
  fail(t, at,
       "ECC action names algorithm '" + name + "', which '" + t.name +
           "' does not define");
}

// Strings and comments are left alone (docs/iec61499.md, "Packages").
void netlift::iec61499::detail::dropPackageQualifiers(
    llvm::MutableArrayRef<char> text) {
  size_t n = text.size(), i = 0;
  auto isIdStart = [](char c) { return isalpha((unsigned char)c) || c == '_'; };
  auto isId = [](char c) { return isalnum((unsigned char)c) || c == '_'; };
  auto skipTo = [&](StringRef end) {
    while (i < n &&
           StringRef(text.data() + i, n - i).substr(0, end.size()) != end)
      ++i;
    i = std::min(n, i + end.size());
  };
  while (i < n) {
    char c = text[i];
    StringRef rest(text.data() + i, n - i);
    if (c == '\'' || c == '"') {
      // A string; `$'` escapes the quote.
      for (++i; i < n && text[i] != c; ++i)
        if (text[i] == '$')
          ++i;
      ++i;
    } else if (rest.startswith("(*")) {
      i += 2;
      skipTo("*)");
    } else if (rest.startswith("/*")) {
      i += 2;
      skipTo("*/");
    } else if (rest.startswith("//")) {
      skipTo("\n");
    } else if (isIdStart(c)) {
      size_t start = i;
      while (i < n && isId(text[i]))
        ++i;
      if (i + 1 < n && text[i] == ':' && text[i + 1] == ':') {
        i += 2;
        std::fill(text.begin() + start, text.begin() + i, ' ');
      }
    } else {
      ++i;
    }
  }
}

StringRef Translator::stText(FbType &t, pugi::xml_node element,
                             const char *what) {
  pugi::xml_node st = child(element, "ST");
  if (!st) {
    pugi::xml_node other = element.first_child();
    fail(t, element,
         Twine(what) + " '" + element.attribute("Name").value() + "' of '" +
             t.name + "' is written in " +
             (other ? "<" + localName(other).str() + ">" : "no language") +
             "; netlift reads ST " + what + "s only");
  }
  bool found;
  StringRef text = t.src->placeAttribute(st, "Text", &found);
  if (!found)
    text = t.src->placeText(st);
  if (text.contains("::"))
    t.src->editPlaced(text, dropPackageQualifiers);
  return text;
}

void Translator::method(FbType &t, pugi::xml_node m) {
  StringRef name = m.attribute("Name").value();
  StringRef text = stText(t, m, "method");
  // 4diac IDE 3 keeps a method's body (its VAR blocks and statements),
  // its name and result type apart (<Method Name Type>); earlier versions
  // wrote the whole METHOD ... END_METHOD.
  bool whole = text.find_insensitive("END_METHOD") != StringRef::npos;
  Pou *pou = whole
                 ? st::parseMethod(text, diag, unit, currentPou)
                 : st::parseMethodBody(text, name, m.attribute("Type").value(),
                                       t.src->locOf(m), diag, unit, currentPou);
  if (!pou)
    throw Failure();
  if (!StringRef(pou->name).equals_insensitive(name))
    fail(pou->loc, "method '" + pou->name + "' is declared in <Method Name=\"" +
                       name + "\"> of '" + t.name + "'");
  // The body sees the block's variables (its copies of the ports) where
  // its own parameters and locals do not hide them.
  std::map<std::string, std::string> outer = copied;
  for (VarDecl *v : pou->vars)
    copied.erase(StringRef(v->name).upper());
  copied.erase(StringRef(pou->name).upper());
  callFunctionTypes(pou->body);
  callInternalFbs(t, pou->body);
  rename(pou->body);
  copied = std::move(outer);
}

/// The condition of an ECC transition: `EI`, `EI[guard]`, `1` or `guard`;
/// `event` is set to the event it waits for (empty: none).
Expr *Translator::guard(FbType &t, pugi::xml_node tr, std::string &event) {
  SMLoc at = t.src->locOf(tr);
  bool found;
  StringRef text = t.src->placeAttribute(tr, "Condition", &found);
  StringRef trimmed = text.trim();
  event.clear();
  if (trimmed.empty() || trimmed == "1" || trimmed.equals_insensitive("TRUE"))
    return boolLit(unit, true, at);
  // 4diac writes a guard without an event in brackets: `[K = 0]`.
  if (trimmed.startswith("[") && trimmed.endswith("]"))
    trimmed = trimmed.drop_front().drop_back().trim();
  size_t id = 0;
  auto word = [&] {
    while (id < trimmed.size() &&
           (isalnum((unsigned char)trimmed[id]) || trimmed[id] == '_'))
      ++id;
  };
  word();
  std::string head = trimmed.take_front(id).str();
  // `S.e`: event e of plug or socket S.
  if (id < trimmed.size() && trimmed[id] == '.')
    if (const AdapterUse *a = t.adapter(head)) {
      size_t from = ++id;
      word();
      head = adapterPort(a->name, trimmed.slice(from, id));
    }
  StringRef rest = trimmed.drop_front(id).trim();
  for (const Event &e : t.eventInputs)
    if (StringRef(e.name).equals_insensitive(head) &&
        (rest.empty() || rest.startswith("[") || rest.startswith("&"))) {
      event = e.name;
      if (rest.empty())
        return boolLit(unit, true, at);
      // IEC 61499-1 Ed. 1 wrote `EI & guard`.
      if (rest.startswith("&")) {
        Expr *g = st::parseStExpression(rest.drop_front().trim(), diag, unit);
        if (!g)
          throw Failure();
        rename(g);
        return g;
      }
      if (!rest.endswith("]"))
        fail(SMLoc::getFromPointer(rest.data()),
             "expected ']' closing the guard of an ECC transition");
      StringRef inner = rest.drop_front().drop_back();
      if (inner.trim().empty())
        return boolLit(unit, true, at);
      Expr *g = st::parseStExpression(inner, diag, unit);
      if (!g)
        throw Failure();
      rename(g);
      return g;
    }
  Expr *g = st::parseStExpression(trimmed, diag, unit);
  if (!g)
    throw Failure();
  rename(g);
  return g;
}

/// A simple FB (IEC 61499-1 Ed. 2) has no ECC: each input event runs the
/// algorithm of the same name and then sends the output event of the same
/// index, as 4diac FORTE's CSimpleFB does (REQ runs REQ, then CNF), unless
/// the type lists what the event does (4diac IDE 3 writes an `<ECState>`
/// named after the event, with its `<ECAction>`s). It is translated as the
/// basic FB with that ECC, written into the type's own element (so the
/// algorithms keep their places in the file): START, and per input event a
/// state running its actions, left at once.
void Translator::simpleAsBasic(FbType &t) {
  if (child(t.body, "ECC"))
    fail(t, t.body, "simple FB '" + t.name + "' has an ECC");
  std::map<std::string, pugi::xml_node> listed; // event (upper) -> ECState
  for (pugi::xml_node st : t.body.children("ECState")) {
    StringRef name = st.attribute("Name").value();
    bool known = false;
    for (const Event &e : t.eventInputs)
      known |= StringRef(e.name).equals_insensitive(name);
    if (!known)
      fail(t, st,
           "state '" + name + "' of simple FB '" + t.name +
               "' is named after no input event (a simple FB's states "
               "say what each input event does)");
    listed[name.upper()] = st;
  }
  for (size_t i = 0; i < t.eventInputs.size(); ++i) {
    const Event &e = t.eventInputs[i];
    if (listed.count(StringRef(e.name).upper()))
      continue;
    bool found = false;
    for (pugi::xml_node a : t.body.children("Algorithm"))
      found |=
          StringRef(a.attribute("Name").value()).equals_insensitive(e.name);
    if (!found)
      fail(t, e.node,
           "event '" + e.name + "' of simple FB '" + t.name +
               "' has no algorithm of its name (a simple FB runs the "
               "algorithm named after the event)");
    if (i >= t.eventOutputs.size())
      fail(t, e.node,
           "event '" + e.name + "' of simple FB '" + t.name +
               "' has no output event at its position to confirm it");
  }
  pugi::xml_node ecc = t.body.append_child("ECC");
  pugi::xml_node start = ecc.append_child("ECState");
  start.append_attribute("Name") = "START";
  for (size_t i = 0; i < t.eventInputs.size(); ++i) {
    std::string state = "RUN_" + t.eventInputs[i].name;
    pugi::xml_node st = ecc.insert_child_after("ECState", start);
    st.append_attribute("Name") = state.c_str();
    if (auto it = listed.find(StringRef(t.eventInputs[i].name).upper());
        it != listed.end()) {
      for (pugi::xml_node a : it->second.children("ECAction"))
        st.append_copy(a);
    } else {
      pugi::xml_node act = st.append_child("ECAction");
      act.append_attribute("Algorithm") = t.eventInputs[i].name.c_str();
      act.append_attribute("Output") = t.eventOutputs[i].name.c_str();
    }
    start = st;
  }
  for (size_t i = 0; i < t.eventInputs.size(); ++i) {
    std::string state = "RUN_" + t.eventInputs[i].name;
    pugi::xml_node go = ecc.append_child("ECTransition");
    go.append_attribute("Source") = "START";
    go.append_attribute("Destination") = state.c_str();
    go.append_attribute("Condition") = t.eventInputs[i].name.c_str();
    pugi::xml_node back = ecc.append_child("ECTransition");
    back.append_attribute("Source") = state.c_str();
    back.append_attribute("Destination") = "START";
    back.append_attribute("Condition") = "1";
  }
}

void Translator::basicBlock(FbType &t, bool asInternal) {
  SMLoc at = t.src->locOf(t.root);
  auto *pou = unit.make<Pou>();
  pou->kind = asInternal ? PouKind::FunctionBlock : PouKind::Program;
  pou->name = asInternal ? internalFbPou(t.name) : t.name;
  pou->loc = at;
  unit.pous.push_back(pou);
  copied.clear();
  current = &t;
  currentPou = pou;
  algorithmTemps.clear();
  // The environment's queue stays event-driven: it feeds the cycle.
  // An internal FB reacts when its owner calls it, whatever the model.
  bool cyclic = semantics == "cyclic" && !asInternal &&
                !StringRef(t.name).startswith("_Inputs_");

  auto declare = [&](StringRef name, TypeSyntax *ts, VarSection s, SMLoc loc) {
    if (pou->find(name))
      fail(loc, "'" + name + "' is declared twice in '" + t.name +
                    "' (netlift keeps interface variables in internal "
                    "copies named _NAME)");
    return addVar(unit, *pou, name, ts, s, loc);
  };
  auto named = [&](StringRef type, SMLoc loc) {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, loc);
    ts->name = type.str();
    return ts;
  };

  // Interface variables: the port, and the copy the algorithms use.
  std::set<std::string> sampled;
  for (const Event &e : t.eventInputs)
    for (const std::string &w : e.with)
      sampled.insert(StringRef(w).upper());
  for (const Var &v : t.inputs) {
    SMLoc loc = t.src->locOf(v.node);
    // The port and its copy share one type (an array type written twice
    // would be two types to the checker).
    TypeSyntax *type = typeOf(*t.src, v.node);
    declare(v.name, type, VarSection::Input, loc);
    // An input no event samples is read where it stands (a parameter).
    if (sampled.count(StringRef(v.name).upper())) {
      std::string copy = modelName(v.name, true);
      declare(copy, type, VarSection::Var, loc);
      copied[StringRef(v.name).upper()] = copy;
    }
  }
  for (const Var &v : t.outputs) {
    SMLoc loc = t.src->locOf(v.node);
    TypeSyntax *type = typeOf(*t.src, v.node);
    declare(v.name, type, VarSection::Output, loc);
    std::string copy = modelName(v.name, true);
    declare(copy, type, VarSection::Var, loc);
    copied[StringRef(v.name).upper()] = copy;
  }
  for (const char *list : {"InternalVars", "InternalConstVars"})
    for (pugi::xml_node v : child(t.body, list).children()) {
      if (localName(v) == "FB" && StringRef(list) == "InternalVars") {
        StringRef name = v.attribute("Name").value();
        for (auto &[n, inner] : t.internalFbs)
          if (n == name) {
            if (scaffoldingName(name))
              fail(t, v,
                   "internal FB '" + name + "' of '" + t.name +
                       "' has a name netlift's model of the block uses; "
                       "rename it");
            declare(name, internalFbDecl(t, v, *inner), VarSection::Var,
                    t.src->locOf(v));
          }
        continue;
      }
      if (localName(v) != "VarDeclaration")
        continue;
      StringRef name = v.attribute("Name").value();
      std::string kept = modelName(name, false);
      if (kept != name)
        copied[name.upper()] = kept;
      VarDecl *d =
          declare(kept, typeOf(*t.src, v), VarSection::Var, t.src->locOf(v));
      d->constant = StringRef(list) == "InternalConstVars";
    }
  // 4diac IDE 3's global constants: read where an algorithm names them.
  declareGlobalConstantsUsed(t, declare);
  // What else a body holds would change the block's behaviour unseen.
  for (pugi::xml_node e : t.body.children()) {
    StringRef kind = localName(e);
    if (e.type() == pugi::node_element &&
        !llvm::is_contained(
            std::initializer_list<StringRef>{
                "InternalVars", "InternalConstVars", "ECC", "ECState",
                "Algorithm", "Method", "Attribute"},
            kind))
      fail(t, e,
           "<" + kind + "> in the body of '" + t.name +
               "' is not read by netlift (it reads InternalVars, "
               "InternalConstVars, ECC and ST algorithms)");
  }
  for (pugi::xml_node m : t.body.children("Method"))
    method(t, m);
  auto checkWith = [&](const Event &e, const std::vector<Var> &vars) {
    for (const std::string &w : e.with) {
      bool known = false;
      for (const Var &v : vars)
        known |= StringRef(v.name).equals_insensitive(w);
      if (!known)
        fail(t, e.node,
             "event '" + e.name + "' is associated (With) with '" + w +
                 "', which is not a data " +
                 (&vars == &t.inputs ? "input" : "output") + " of '" + t.name +
                 "'");
    }
  };
  for (const Event &e : t.eventInputs)
    checkWith(e, t.inputs);
  for (const Event &e : t.eventOutputs)
    checkWith(e, t.outputs);

  // The ECC: states as an enumeration, the first one initial.
  pugi::xml_node ecc = child(t.body, "ECC");
  std::vector<pugi::xml_node> states, transitions;
  for (pugi::xml_node s : ecc.children("ECState"))
    states.push_back(s);
  for (pugi::xml_node tr : ecc.children("ECTransition"))
    transitions.push_back(tr);
  if (states.empty())
    fail(t, ecc ? ecc : t.body, "basic FB '" + t.name + "' has no ECC states");
  // An internal FB's function block has states of its own type: the type
  // may be a block of a network too.
  std::string eccType = pou->name + "_ECC";
  auto *enumSyntax = unit.make<TypeSyntax>(TypeSyntaxKind::Enum, at);
  std::map<std::string, pugi::xml_node> stateByName;
  for (pugi::xml_node s : states) {
    std::string name = s.attribute("Name").value();
    if (!stateByName.emplace(StringRef(name).upper(), s).second)
      fail(t, s, "ECC state '" + name + "' is defined twice");
    enumSyntax->enumerators.push_back({name, nullptr, t.src->locOf(s)});
  }
  auto *td = unit.make<TypeDecl>();
  td->name = eccType;
  td->loc = at;
  td->type = enumSyntax;
  unit.types.push_back(td);
  auto stateLit = [&](StringRef name, SMLoc loc) {
    Expr *e = unit.make<Expr>(ExprKind::EnumLit, loc);
    e->typeName = eccType;
    e->name = name.str();
    return e;
  };
  auto *eccInit = named(eccType, at);
  eccInit->init = unit.make<Initializer>(Initializer::Value, at);
  eccInit->init->value = stateLit(states.front().attribute("Name").value(), at);
  declare("ECC", eccInit, VarSection::Var, at);
  // Output events wait in a FIFO queue, by number (1 = the first output).
  auto subrange = [&](int64_t lo, int64_t hi) {
    auto *r = unit.make<TypeSyntax>(TypeSyntaxKind::Subrange, at);
    r->name = "INT";
    r->lo = intLit(unit, lo, at);
    r->hi = intLit(unit, hi, at);
    return r;
  };
  std::vector<std::pair<std::string, SMLoc>> eventOutputs;
  for (const Event &e : t.eventOutputs)
    eventOutputs.push_back({e.name, t.src->locOf(e.node)});
  if (asInternal)
    declare(kInternalEvent, subrange(0, int64_t(t.eventInputs.size())),
            VarSection::Input, at);
  else if (!t.eventOutputs.empty()) {
    auto *queue = unit.make<TypeSyntax>(TypeSyntaxKind::Array, at);
    queue->dims.push_back(
        {intLit(unit, 0, at), intLit(unit, kMaxQueued - 1, at)});
    queue->elem = subrange(0, int64_t(t.eventOutputs.size()));
    declare("_queue", queue, VarSection::Var, at);
    declare("_queued", subrange(0, kMaxQueued), VarSection::Var, at);
  }
  declare("_live", named("BOOL", at), VarSection::Temp, at);
  if (cyclic)
    for (const Event &e : t.eventInputs)
      declare(eventFlag(e.name), named("BOOL", at), VarSection::Var,
              t.src->locOf(e.node));
  else
    declare("_event", named("BOOL", at), VarSection::Temp, at);
  declare("_fired", named("BOOL", at), VarSection::Temp, at);
  int64_t limit = int64_t(transitions.size()) * kRunawayFactor + 1;
  declare("_step", subrange(0, std::max<int64_t>(limit, kMaxQueued) + 1),
          VarSection::Temp, at);
  auto *never = unit.make<TypeSyntax>(TypeSyntaxKind::Subrange, at);
  never->name = "INT";
  never->lo = intLit(unit, 0, at);
  never->hi = intLit(unit, 0, at);
  declare("_ECC_does_not_settle", never, VarSection::Var, at);

  for (pugi::xml_node tr : transitions)
    for (const char *end : {"Source", "Destination"})
      if (!stateByName.count(StringRef(tr.attribute(end).value()).upper()))
        fail(t, tr,
             "ECC transition " + StringRef(end).lower() + " '" +
                 tr.attribute(end).value() + "' is not a state of '" + t.name +
                 "'");

  auto queueAt = [&](Expr *index, SMLoc loc) {
    Expr *e = unit.make<Expr>(ExprKind::Index, loc);
    e->operands = {nameRef(unit, "_queue", loc), index};
    return e;
  };

  // What entering a state does: its actions in order.
  auto enter = [&](pugi::xml_node state) {
    StmtList out;
    for (pugi::xml_node a : state.children("ECAction")) {
      SMLoc loc = t.src->locOf(a);
      if (StringRef alg = a.attribute("Algorithm").value(); !alg.empty()) {
        StmtList body = algorithm(t, alg, a);
        out.insert(out.end(), body.begin(), body.end());
      }
      if (StringRef o = a.attribute("Output").value(); !o.empty()) {
        std::string port = o.str();
        if (auto [name, element] = o.split('.'); !element.empty())
          if (const AdapterUse *ad = t.adapter(name))
            port = adapterPort(ad->name, element);
        o = port;
        const Event *ev = nullptr;
        for (const Event &e : t.eventOutputs)
          if (StringRef(e.name).equals_insensitive(o))
            ev = &e;
        if (!ev)
          fail(loc, "ECC action emits '" + o +
                        "', which is not an event "
                        "output of '" +
                        t.name + "'");
        for (const std::string &w : ev->with)
          out.push_back(assign(unit, nameRef(unit, w, loc),
                               nameRef(unit, internal(w), loc), loc));
        // An internal FB's output events are connected to nothing.
        if (asInternal)
          continue;
        int64_t number = ev - &t.eventOutputs.front() + 1;
        out.push_back(assign(unit, queueAt(nameRef(unit, "_queued", loc), loc),
                             intLit(unit, number, loc), loc));
        out.push_back(
            assign(unit, nameRef(unit, "_queued", loc),
                   binary(unit, Op::Add, nameRef(unit, "_queued", loc),
                          intLit(unit, 1, loc), loc),
                   loc));
      }
    }
    return out;
  };

  EventDrivenBlock block;
  block.pou = pou;
  for (const Event &e : t.eventInputs)
    block.eventInputs.push_back({e.name, t.src->locOf(e.node)});
  block.eventOutputs = eventOutputs;
  // Sending the queue's head: the rest moves up.
  for (const Event &e : t.eventOutputs) {
    if (asInternal)
      break;
    SMLoc loc = t.src->locOf(e.node);
    int64_t number = &e - &t.eventOutputs.front() + 1;
    EventSend send;
    send.event = e.name;
    send.loc = loc;
    send.guard = binary(unit, Op::Eq, queueAt(intLit(unit, 0, loc), loc),
                        intLit(unit, number, loc), loc);
    Stmt *shift = unit.make<Stmt>(StmtKind::For, loc);
    shift->target = nameRef(unit, "_step", loc);
    shift->from = intLit(unit, 0, loc);
    shift->to = intLit(unit, kMaxQueued - 2, loc);
    shift->body.push_back(
        assign(unit, queueAt(nameRef(unit, "_step", loc), loc),
               queueAt(binary(unit, Op::Add, nameRef(unit, "_step", loc),
                              intLit(unit, 1, loc), loc),
                       loc),
               loc));
    send.body.push_back(shift);
    send.body.push_back(assign(unit,
                               queueAt(intLit(unit, kMaxQueued - 1, loc), loc),
                               intLit(unit, 0, loc), loc));
    send.body.push_back(
        assign(unit, nameRef(unit, "_queued", loc),
               binary(unit, Op::Sub, nameRef(unit, "_queued", loc),
                      intLit(unit, 1, loc), loc),
               loc));
    // Checked with the rest of the POU.
    pou->body.push_back(when(unit, send.guard, send.body, loc));
    block.sends.push_back(std::move(send));
  }

  // Running the ECC to completion: from the current state the first
  // transition (document order) whose condition holds fires, its new
  // state's actions run, and evaluation repeats until none fires. An event
  // condition holds only at the first evaluation: `eventCond` gives it
  // (null: the transition cannot fire in this reaction), and `consumed`
  // runs after every evaluation, taking the events away. Appended to `h`:
  // `_live := TRUE`, the statements `armed` (which arm the events), the
  // loop.
  auto runEcc = [&](StmtList &h, StmtList armed,
                    llvm::function_ref<Expr *(StringRef, SMLoc)> eventCond,
                    llvm::function_ref<StmtList(SMLoc)> consumed, SMLoc loc) {
    Stmt *sel = unit.make<Stmt>(StmtKind::Case, loc);
    sel->value = nameRef(unit, "ECC", loc);
    for (pugi::xml_node s : states) {
      Stmt *chain = unit.make<Stmt>(StmtKind::If, loc);
      for (pugi::xml_node tr : transitions) {
        if (!StringRef(tr.attribute("Source").value())
                 .equals_insensitive(s.attribute("Name").value()))
          continue;
        std::string event;
        Expr *g = guard(t, tr, event);
        SMLoc tloc = t.src->locOf(tr);
        if (!event.empty()) {
          Expr *e = eventCond(event, tloc);
          if (!e)
            continue;
          g = g->kind == ExprKind::BoolLit ? e
                                           : binary(unit, Op::And, e, g, tloc);
        }
        pugi::xml_node dst =
            stateByName[StringRef(tr.attribute("Destination").value()).upper()];
        StmtList body;
        body.push_back(
            assign(unit, nameRef(unit, "_ECC_does_not_settle", tloc),
                   binary(unit, Op::Div, nameRef(unit, "_step", tloc),
                          intLit(unit, limit, tloc), tloc),
                   tloc));
        body.push_back(assign(unit, nameRef(unit, "ECC", tloc),
                              stateLit(dst.attribute("Name").value(), tloc),
                              tloc));
        body.push_back(assign(unit, nameRef(unit, "_fired", tloc),
                              boolLit(unit, true, tloc), tloc));
        StmtList entered = enter(dst);
        body.insert(body.end(), entered.begin(), entered.end());
        chain->arms.push_back({g, std::move(body)});
      }
      if (chain->arms.empty())
        continue;
      CaseArmSyntax arm;
      arm.labels.push_back(
          {stateLit(s.attribute("Name").value(), t.src->locOf(s)), nullptr});
      arm.body.push_back(chain);
      sel->caseArms.push_back(std::move(arm));
    }
    StmtList once;
    once.push_back(assign(unit, nameRef(unit, "_fired", loc),
                          boolLit(unit, false, loc), loc));
    if (!sel->caseArms.empty())
      once.push_back(sel);
    StmtList taken = consumed(loc);
    once.insert(once.end(), taken.begin(), taken.end());
    Expr *notFired = unit.make<Expr>(ExprKind::Unary, loc);
    notFired->op = Op::Not;
    notFired->operands.push_back(nameRef(unit, "_fired", loc));
    once.push_back(when(unit, notFired,
                        {assign(unit, nameRef(unit, "_live", loc),
                                boolLit(unit, false, loc), loc)},
                        loc));
    Stmt *loop = unit.make<Stmt>(StmtKind::For, loc);
    loop->target = nameRef(unit, "_step", loc);
    loop->from = intLit(unit, 0, loc);
    loop->to = intLit(unit, limit, loc);
    loop->body.push_back(when(unit, nameRef(unit, "_live", loc), once, loc));
    h.push_back(assign(unit, nameRef(unit, "_live", loc),
                       boolLit(unit, true, loc), loc));
    h.insert(h.end(), armed.begin(), armed.end());
    h.push_back(loop);
  };
  // As an internal FB: `CASE _call OF 1: <reaction to the first event>...`.
  Stmt *selectEvent = unit.make<Stmt>(StmtKind::Case, at);
  selectEvent->value = nameRef(unit, kInternalEvent, at);
  auto handle = [&](StringRef event, StmtList h, SMLoc loc,
                    bool latch = false) {
    if (asInternal) {
      CaseArmSyntax arm;
      arm.labels.push_back(
          {intLit(unit, int64_t(selectEvent->caseArms.size()) + 1, loc),
           nullptr});
      arm.body = std::move(h);
      selectEvent->caseArms.push_back(std::move(arm));
      return;
    }
    pou->body.insert(pou->body.end(), h.begin(), h.end());
    block.handlers.push_back({event.str(), std::move(h), loc, latch});
  };

  if (cyclic) {
    // fb2smv's cyclic model: an arriving event only sets its flag; when the
    // block's turn in the cycle comes (`_run`, ordered by CyclicOrder), it
    // samples the data of its pending events and runs the ECC with all of
    // them at once, then forgets them.
    for (const Event &ei : t.eventInputs) {
      if (StringRef(ei.name).equals_insensitive(kCycleTurn))
        fail(t, ei.node,
             "event input '" + ei.name +
                 "' has the name netlift gives a block's turn under "
                 "--fb-semantics cyclic; rename it");
      SMLoc loc = t.src->locOf(ei.node);
      handle(ei.name,
             {assign(unit, nameRef(unit, eventFlag(ei.name), loc),
                     boolLit(unit, true, loc), loc)},
             loc, /*latch=*/true);
    }
    StmtList h;
    for (const Var &v : t.inputs) {
      Expr *pending = nullptr;
      SMLoc loc = t.src->locOf(v.node);
      for (const Event &ei : t.eventInputs)
        for (const std::string &w : ei.with)
          if (StringRef(w).equals_insensitive(v.name)) {
            Expr *f = nameRef(unit, eventFlag(ei.name), loc);
            pending = pending ? binary(unit, Op::Or, pending, f, loc) : f;
          }
      if (pending)
        h.push_back(when(unit, pending,
                         {assign(unit, nameRef(unit, internal(v.name), loc),
                                 nameRef(unit, v.name, loc), loc)},
                         loc));
    }
    runEcc(
        h, {},
        [&](StringRef event, SMLoc loc) -> Expr * {
          return nameRef(unit, eventFlag(event), loc);
        },
        [&](SMLoc loc) {
          StmtList forget;
          for (const Event &ei : t.eventInputs)
            forget.push_back(assign(unit,
                                    nameRef(unit, eventFlag(ei.name), loc),
                                    boolLit(unit, false, loc), loc));
          return forget;
        },
        at);
    handle(kCycleTurn, std::move(h), at);
    block.eventInputs.push_back({kCycleTurn, at});
  } else {
    for (const Event &ei : t.eventInputs) {
      SMLoc loc = t.src->locOf(ei.node);
      StmtList h;
      for (const std::string &w : ei.with)
        h.push_back(assign(unit, nameRef(unit, internal(w), loc),
                           nameRef(unit, w, loc), loc));
      // Only this event's transitions, and only at the first evaluation.
      runEcc(
          h,
          {assign(unit, nameRef(unit, "_event", loc), boolLit(unit, true, loc),
                  loc)},
          [&](StringRef event, SMLoc at) -> Expr * {
            if (!event.equals_insensitive(ei.name))
              return nullptr;
            return nameRef(unit, "_event", at);
          },
          [&](SMLoc at) -> StmtList {
            return {assign(unit, nameRef(unit, "_event", at),
                           boolLit(unit, false, at), at)};
          },
          loc);
      handle(ei.name, std::move(h), loc);
    }
  }
  if (asInternal) {
    pou->body.push_back(selectEvent);
    return;
  }
  blocks.push_back(std::move(block));
}
