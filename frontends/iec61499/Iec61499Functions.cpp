//===- Iec61499Functions.cpp - 4diac's body-less function FBs -------------===//
//
// 4diac ships many FB types whose behaviour FORTE implements in C++: type
// conversions (F_INT_TO_REAL, INT2INT) and generic functions over ANY_...
// variables (F_ADD, F_SEL, ...). netlift gives them the ST body their name
// means, and gives each generic block a type of its own whose variables
// take the types its data connections, its typed parameters and the blocks
// it is chained to fix. Blocks modelled as environment (PUBLISH_n,
// OUT_ANY_CONSOLE...) with generic ports are typed the same way.
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

/// Whether `t`'s interface is the one typedFunction gives its name: REQ
/// and CNF with every variable, the inputs and the output of those names
/// and types in that order.
static bool hasInterfaceOf(const FbType &t, const TypedFunction &f) {
  auto same = [](const std::vector<Var> &vars,
                 const std::vector<PortSpec> &ports) {
    if (vars.size() != ports.size())
      return false;
    for (size_t i = 0; i < vars.size(); ++i)
      if (!StringRef(vars[i].name).equals_insensitive(ports[i].name) ||
          !StringRef(vars[i].type).equals_insensitive(ports[i].type))
        return false;
    return true;
  };
  return t.eventInputs.size() == 1 && t.eventOutputs.size() == 1 &&
         StringRef(t.eventInputs[0].name).equals_insensitive("REQ") &&
         StringRef(t.eventOutputs[0].name).equals_insensitive("CNF") &&
         same(t.inputs, f.inputs) && same(t.outputs, {f.output});
}

/// Gives body-less `t` the simple FB whose REQ runs `text`.
void Translator::runOnRequest(FbType &t, const std::string &text) {
  t.body = t.root.append_child("SimpleFB");
  pugi::xml_node alg = t.body.append_child("Algorithm");
  alg.append_attribute("Name") = t.eventInputs[0].name.c_str();
  alg.append_child("ST").append_attribute("Text") = text.c_str();
  simpleAsBasic(t);
}

/// 4diac implements its type conversions in FORTE's C++: `F_<A>_TO_<B>`
/// (REQ with IN : A, CNF with OUT : B) and `<A>2<A>` (OUT := IN) have no
/// body in their .fbt. netlift gives them the body their name means, as a
/// simple FB whose REQ algorithm is `OUT := A_TO_B(IN);` (or `OUT := IN;`),
/// so that the conversion is the ST frontend's (a conversion it refuses,
/// such as to REAL or STRING, is refused at that algorithm); the typed
/// functions (typedFunction: F_ADD_DT_TIME, F_BYTE_BCD_TO_USINT...) run
/// the function of their name without `F_` on IN1, IN2 or IN.
bool Translator::modelFunctionFb(FbType &t) {
  if (std::optional<TypedFunction> f = typedFunction(t.name);
      f && hasInterfaceOf(t, *f)) {
    std::string args;
    for (const PortSpec &p : f->inputs)
      args += (args.empty() ? "" : ", ") + p.name;
    runOnRequest(t, "OUT := " + StringRef(t.name).drop_front(2).upper() + "(" +
                        args + ");");
    return true;
  }
  if (t.eventInputs.size() != 1 || t.eventOutputs.size() != 1 ||
      t.inputs.size() != 1 || t.outputs.size() != 1 ||
      !StringRef(t.eventInputs[0].name).equals_insensitive("REQ") ||
      !StringRef(t.eventOutputs[0].name).equals_insensitive("CNF") ||
      !StringRef(t.inputs[0].name).equals_insensitive("IN") ||
      !StringRef(t.outputs[0].name).equals_insensitive("OUT"))
    return false;
  // The name abbreviates (F_DT_TO_DATE, F_TOD_TO_STRING) what the ports
  // spell out (DATE_AND_TIME, TIME_OF_DAY).
  auto shortName = [](StringRef type) -> StringRef {
    if (type.equals_insensitive("DATE_AND_TIME"))
      return "DT";
    if (type.equals_insensitive("TIME_OF_DAY"))
      return "TOD";
    return type;
  };
  StringRef name = t.name, from = shortName(t.inputs[0].type),
            to = shortName(t.outputs[0].type);
  std::string text;
  if (name.equals_insensitive(("F_" + from + "_TO_" + to).str()))
    text = "OUT := " + from.str() + "_TO_" + to.str() + "(IN);";
  else if (name.equals_insensitive((from + "2" + to).str()) &&
           from.equals_insensitive(to))
    text = "OUT := IN;";
  else
    return false;
  runOnRequest(t, text);
  return true;
}

/// The ST that 4diac's generic function FB `name` (its behaviour is in
/// FORTE's C++, its variables typed ANY_...) runs on REQ, over its
/// interface's names; null if netlift has none.
static const char *genericFunctionBody(StringRef name) {
  static const std::pair<const char *, const char *> kBodies[] = {
      {"F_ADD", "OUT := IN1 + IN2;"},
      {"F_ADD_3", "OUT := IN1 + IN2 + IN3;"},
      {"F_SUB", "OUT := IN1 - IN2;"},
      {"F_MUL", "OUT := IN1 * IN2;"},
      {"F_DIV", "OUT := IN1 / IN2;"},
      {"F_MOD", "OUT := IN1 MOD IN2;"},
      {"F_MOVE", "OUT := IN;"},
      {"F_ABS", "OUT := ABS(IN);"},
      {"F_AND", "OUT := IN1 AND IN2;"},
      {"F_AND_3", "OUT := IN1 AND IN2 AND IN3;"},
      {"F_OR", "OUT := IN1 OR IN2;"},
      {"F_OR_3", "OUT := IN1 OR IN2 OR IN3;"},
      {"F_XOR", "OUT := IN1 XOR IN2;"},
      {"F_XOR_3", "OUT := IN1 XOR IN2 XOR IN3;"},
      {"F_NOT", "OUT := NOT IN;"},
      {"F_SHL", "OUT := SHL(IN, N);"},
      {"F_SHR", "OUT := SHR(IN, N);"},
      {"F_ROL", "OUT := ROL(IN, N);"},
      {"F_ROR", "OUT := ROR(IN, N);"},
      {"F_EQ", "OUT := IN1 = IN2;"},
      {"F_NE", "OUT := IN1 <> IN2;"},
      {"F_GT", "OUT := IN1 > IN2;"},
      {"F_GE", "OUT := IN1 >= IN2;"},
      {"F_LT", "OUT := IN1 < IN2;"},
      {"F_LE", "OUT := IN1 <= IN2;"},
      {"F_MAX", "OUT := MAX(IN1, IN2);"},
      {"F_MIN", "OUT := MIN(IN1, IN2);"},
      {"F_LIMIT", "OUT := LIMIT(MN, IN, MX);"},
      {"F_SEL", "OUT := SEL(G, IN0, IN1);"},
      {"F_MUX_2", "OUT := MUX(K, IN1, IN2);"},
      {"F_SQRT", "OUT := SQRT(IN);"},
      {"F_LN", "OUT := LN(IN);"},
      {"F_LOG", "OUT := LOG(IN);"},
      {"F_EXP", "OUT := EXP(IN);"},
      {"F_SIN", "OUT := SIN(IN);"},
      {"F_COS", "OUT := COS(IN);"},
      {"F_TAN", "OUT := TAN(IN);"},
      {"F_ASIN", "OUT := ASIN(IN);"},
      {"F_ACOS", "OUT := ACOS(IN);"},
      {"F_ATAN", "OUT := ATAN(IN);"},
      {"F_EXPT", "OUT := EXPT(IN1, IN2);"},
      {"F_TRUNC", "OUT := TRUNC(IN);"},
      {"F_MULTIME", "OUT := MUL_TIME(IN1, IN2);"},
      {"F_DIVTIME", "OUT := DIV_TIME(IN1, IN2);"},
      {"F_LEN", "OUT := LEN(IN);"},
      {"F_LEFT", "OUT := LEFT(IN, L);"},
      {"F_RIGHT", "OUT := RIGHT(IN, L);"},
      {"F_MID", "OUT := MID(IN, L, P);"},
      {"F_CONCAT", "OUT := CONCAT(IN1, IN2);"},
      {"F_INSERT", "OUT := INSERT(IN1, IN2, P);"},
      {"F_DELETE", "OUT := DELETE(IN, L, P);"},
      {"F_REPLACE", "OUT := REPLACE(IN1, IN2, L, P);"},
      {"F_FIND", "OUT := FIND(IN1, IN2);"},
  };
  for (const auto &[n, body] : kBodies)
    if (name.equals_insensitive(n))
      return body;
  return nullptr;
}

bool netlift::iec61499::detail::isGenericType(StringRef type) {
  return type.startswith_insensitive("ANY");
}

std::string
netlift::iec61499::detail::varListXml(const char *tag,
                                      const std::vector<PortSpec> &vars) {
  std::string text = std::string("<") + tag + ">";
  for (const PortSpec &p : vars)
    text += "<VarDeclaration Name=\"" + p.name + "\" Type=\"" + p.type + "\"/>";
  return text + "</" + tag + ">\n";
}

std::string
netlift::iec61499::detail::interfaceListContents(const InterfaceSpec &spec) {
  std::string text;
  for (const auto &[tag, list] :
       {std::pair{"EventInputs", &spec.eventInputs},
        std::pair{"EventOutputs", &spec.eventOutputs}}) {
    text += std::string("<") + tag + ">";
    for (const EventSpec &e : *list) {
      text += "<Event Name=\"" + e.name + "\">";
      for (const std::string &w : e.with)
        text += "<With Var=\"" + w + "\"/>";
      text += "</Event>";
    }
    text += std::string("</") + tag + ">\n";
  }
  return text + varListXml("InputVars", spec.inputs) +
         varListXml("OutputVars", spec.outputs);
}

std::string netlift::iec61499::detail::interfaceXml(
    const std::string &name, const FbType &t,
    llvm::function_ref<std::string(const Var &)> typeOf) {
  auto kept = [&](StringRef var) {
    for (const auto *list : {&t.inputs, &t.outputs})
      for (const Var &v : *list)
        if (StringRef(v.name).equals_insensitive(var))
          return !typeOf(v).empty();
    return true;
  };
  InterfaceSpec spec;
  auto events = [&](const std::vector<Event> &from,
                    std::vector<EventSpec> &to) {
    for (const Event &e : from) {
      EventSpec &out = to.emplace_back(EventSpec{e.name, {}});
      for (const std::string &w : e.with)
        if (kept(w))
          out.with.push_back(w);
    }
  };
  auto vars = [&](const std::vector<Var> &from, std::vector<PortSpec> &to) {
    for (const Var &v : from)
      if (std::string type = typeOf(v); !type.empty())
        to.push_back({v.name, type});
  };
  events(t.eventInputs, spec.eventInputs);
  events(t.eventOutputs, spec.eventOutputs);
  vars(t.inputs, spec.inputs);
  vars(t.outputs, spec.outputs);
  return "<FBType Name=\"" + name + "\">\n<InterfaceList>\n" +
         interfaceListContents(spec);
}

/// The type a typed literal names (`DINT#7`, `T#1s`, `WORD#16#FF`,
/// `'text'`, `TRUE`), or "" for an untyped one (`5`, `1.5`), which fixes
/// no generic variable (FORTE reads it as the type the variable has).
static std::string typeOfLiteral(StringRef value) {
  value = value.trim();
  if (value.startswith("'"))
    return "STRING";
  if (value.startswith("\""))
    return "WSTRING";
  if (value.equals_insensitive("TRUE") || value.equals_insensitive("FALSE"))
    return "BOOL";
  if (!value.contains('#'))
    return "";
  std::string prefix = value.split('#').first.upper();
  static const std::pair<const char *, const char *> kShort[] = {
      {"T", "TIME"},           {"LT", "LTIME"},
      {"D", "DATE"},           {"LD", "LDATE"},
      {"TOD", "TIME_OF_DAY"},  {"LTOD", "LTIME_OF_DAY"},
      {"DT", "DATE_AND_TIME"}, {"LDT", "LDATE_AND_TIME"}};
  for (const auto &[abbrev, type] : kShort)
    if (prefix == abbrev)
      return type;
  static const char *const kElementary[] = {
      "BOOL",        "SINT",          "INT",   "DINT",  "LINT",   "USINT",
      "UINT",        "UDINT",         "ULINT", "REAL",  "LREAL",  "BYTE",
      "WORD",        "DWORD",         "LWORD", "TIME",  "LTIME",  "DATE",
      "TIME_OF_DAY", "DATE_AND_TIME", "CHAR",  "WCHAR", "STRING", "WSTRING"};
  for (const char *type : kElementary)
    if (prefix == type)
      return type;
  return "";
}

/// A generic function block none of whose generic variables is connected
/// or given a parameter (left over in an application, or only its events
/// used): it keeps its events, REQ answered by CNF, and its data are left
/// out, as nothing reads or drives them; a note says so. One whose generic
/// variables are connected or given values that fix no type is an error.
void Translator::unconnectedGenericFunction(XmlSource &src, pugi::xml_node net,
                                            pugi::xml_node fb, FbType &t) {
  StringRef inst = fb.attribute("Name").value();
  auto generic = [&](StringRef port) {
    for (const auto *list : {&t.inputs, &t.outputs})
      for (const Var &v : *list)
        if (StringRef(v.name).equals_insensitive(port))
          return isGenericType(v.type);
    return false;
  };
  bool used = false;
  for (pugi::xml_node p : fb.children("Parameter"))
    used |= generic(p.attribute("Name").value());
  for (pugi::xml_node c : child(net, "DataConnections").children("Connection"))
    for (const char *end : {"Source", "Destination"}) {
      auto [blk, port] = StringRef(c.attribute(end).value()).split('.');
      used |= blk.equals_insensitive(inst) && generic(port);
    }
  if (used)
    fail(src.locOf(fb),
         "the types of '" + inst + "' (" + t.name +
             ", a generic function) are fixed by no data connection to a "
             "typed port, no typed parameter (INT#5, T#1s) and no chain of "
             "generic blocks reaching one");
  std::string name = t.name + "__UNUSED";
  if (!this->types.count(StringRef(name).upper())) {
    std::string text = interfaceXml(name, t, [](const Var &v) {
      return isGenericType(v.type) ? std::string() : v.type;
    });
    text +=
        "</InterfaceList>\n<SimpleFB><Algorithm Name=\"" +
        (t.eventInputs.empty() ? std::string("REQ") : t.eventInputs[0].name) +
        "\"><ST Text=\"\"/></Algorithm></SimpleFB>\n</FBType>\n";
    generatedType(name, text);
  }
  diag.note(src.locOf(fb),
            "'" + inst + "' (" + t.name +
                ", a generic function) has no data connected: it is kept "
                "with its events and without its data, which nothing reads");
  retype(fb, name);
}

/// 4diac's STRUCT_MUX and STRUCT_DEMUX are configured per block with the
/// structure they build or take apart (`<Attribute Name="StructuredType"
/// Value="Point"/>`; a demultiplexer may show some members only,
/// `VisibleChildren="X,Y"`), and the IDE gives the block a port per
/// member. Such a block gets a simple FB of its own, `STRUCT_MUX__Point`:
/// REQ samples every member input and runs `OUT.X := X; ...` (the
/// demultiplexer `X := IN.X; ...`), then CNF publishes the result. Returns
/// false for any other block, or one not configured.
bool Translator::structManipulator(XmlSource &src, pugi::xml_node fb,
                                   FbType &t) {
  bool mux = StringRef(t.name).equals_insensitive("STRUCT_MUX");
  if (!mux && !StringRef(t.name).equals_insensitive("STRUCT_DEMUX"))
    return false;
  StringRef structName, visible;
  bool anyVisible = false;
  for (pugi::xml_node a : fb.children("Attribute")) {
    StringRef name = a.attribute("Name").value();
    if (name.equals_insensitive("StructuredType"))
      structName = a.attribute("Value").value();
    else if (name.equals_insensitive("VisibleChildren")) {
      visible = a.attribute("Value").value();
      anyVisible = true;
    }
  }
  if (structName.empty())
    return false;
  StringRef inst = fb.attribute("Name").value();
  if (size_t cut = structName.rfind("::"); cut != StringRef::npos)
    structName = structName.drop_front(cut + 2);
  auto [dsrc, root] = findDataType(structName, src.locOf(fb));
  pugi::xml_node members =
      dsrc ? child(root, "StructuredType") : pugi::xml_node();
  if (!members)
    fail(src.locOf(fb), "'" + inst + "' (" + t.name + ") is configured with '" +
                            structName +
                            "', which is no structured data type in the "
                            "inputs or the -I directories");
  if (t.eventInputs.size() != 1 || t.eventOutputs.size() != 1)
    fail(src.locOf(fb), "'" + inst + "' (" + t.name +
                            "): netlift models the type with one input and "
                            "one output event (REQ and CNF)");
  llvm::SmallVector<StringRef, 8> shown;
  visible.split(shown, ',', -1, false);
  auto isShown = [&](StringRef member) {
    if (mux || !anyVisible)
      return true;
    for (StringRef v : shown)
      if (v.trim().equals_insensitive(member))
        return true;
    return false;
  };
  for (StringRef v : shown)
    if (v.contains('.'))
      fail(src.locOf(fb), "'" + inst + "' (" + t.name + ") shows '" + v.trim() +
                              "', a member of a nested structure: netlift "
                              "models a demultiplexer's top-level members");
  const char *whole = mux ? "OUT" : "IN";
  std::string decls, with, body, suffix;
  for (pugi::xml_node m : members.children("VarDeclaration")) {
    StringRef name = m.attribute("Name").value();
    if (!isShown(name))
      continue;
    if (name.equals_insensitive(whole))
      fail(src.locOf(fb), "member '" + name + "' of '" + structName +
                              "' has the name of " + t.name + "'s own " +
                              whole + " in '" + inst + "'");
    StringRef type = m.attribute("Type").value();
    if (size_t cut = type.rfind("::"); cut != StringRef::npos)
      type = type.drop_front(cut + 2);
    decls += "<VarDeclaration Name=\"" + xmlEscape(name) + "\" Type=\"" +
             xmlEscape(type) + "\"";
    if (pugi::xml_attribute size = m.attribute("ArraySize"))
      decls += " ArraySize=\"" + xmlEscape(size.value()) + "\"";
    decls += "/>";
    with += "<With Var=\"" + xmlEscape(name) + "\"/>";
    body += mux ? ("OUT." + name + " := " + name + "; ").str()
                : (name + " := IN." + name + "; ").str();
    suffix += "_" + name.str();
  }
  std::string name = t.name + "__" + structName.str() +
                     (anyVisible && !mux ? suffix : std::string());
  if (!this->types.count(StringRef(name).upper())) {
    std::string wholeDecl = std::string("<VarDeclaration Name=\"") + whole +
                            "\" Type=\"" + xmlEscape(structName) + "\"/>";
    std::string wholeWith = std::string("<With Var=\"") + whole + "\"/>";
    std::string text =
        "<FBType Name=\"" + name +
        "\">\n<InterfaceList>\n<EventInputs><Event Name=\"" +
        t.eventInputs[0].name + "\">" + (mux ? with : wholeWith) +
        "</Event></EventInputs>\n<EventOutputs><Event Name=\"" +
        t.eventOutputs[0].name + "\">" + (mux ? wholeWith : with) +
        "</Event></EventOutputs>\n<InputVars>" + (mux ? decls : wholeDecl) +
        "</InputVars>\n<OutputVars>" + (mux ? wholeDecl : decls) +
        "</OutputVars>\n</InterfaceList>\n<SimpleFB><Algorithm Name=\"" +
        t.eventInputs[0].name + "\"><ST Text=\"" + xmlEscape(body) +
        "\"/></Algorithm></SimpleFB>\n</FBType>\n";
    generatedType(name, text);
  }
  retype(fb, name);
  return true;
}

/// A block of a network whose type is one of 4diac's generic function FBs
/// (see genericFunctionBody) gets a type of its own, `F_ADD__INT`: every
/// variable of one generic type (ANY_NUM, ANY_BIT...) takes the type that a
/// typed port it is connected to, a typed parameter, or a generic block it
/// is chained to fixes (a group nothing fixes takes the first fixed group's,
/// as OUT : ANY_NUM of F_MOD follows IN1 : ANY_INT), and REQ runs the
/// function's ST as a simple FB. The block's Type is rewritten to that type
/// before the network is read.
void Translator::specializeGenericFunctions(XmlSource &src, pugi::xml_node net,
                                            const FbType *owner) {
  std::map<std::string, FbType *> types = blockTypes(src, net);
  std::vector<pugi::xml_node> generic, environment;
  for (pugi::xml_node fb : blocksOf(net)) {
    if (!fb.attribute("Type"))
      continue;
    FbType *type = types.at(StringRef(fb.attribute("Name").value()).upper());
    if (structManipulator(src, fb, *type)) {
      types[StringRef(fb.attribute("Name").value()).upper()] =
          this->types.at(StringRef(fb.attribute("Type").value()).upper()).get();
      continue;
    }
    bool anyGeneric = false;
    for (const auto *list : {&type->inputs, &type->outputs})
      for (const Var &v : *list)
        anyGeneric |= isGenericType(v.type);
    if ((type->kind == TypeKind::Service || type->kind == TypeKind::NoBody) &&
        anyGeneric && genericFunctionBody(type->name))
      generic.push_back(fb);
    else if ((type->kind == TypeKind::Service ||
              type->kind == TypeKind::NoBody) &&
             anyGeneric && opaqueAsEnvironment && !isShipped(type->name))
      environment.push_back(fb);
  }
  // The declared type of `end` ("block.PORT" or an own port), if fixed.
  auto typeAt = [&](StringRef end) -> std::string {
    auto [a, p] = end.split('.');
    const FbType *t = owner;
    StringRef port = a;
    if (!p.empty()) {
      auto it = types.find(a.upper());
      if (it == types.end())
        return "";
      t = it->second;
      port = p;
    }
    if (!t)
      return "";
    for (const auto *list : {&t->inputs, &t->outputs})
      for (const Var &v : *list)
        if (StringRef(v.name).equals_insensitive(port) &&
            !isGenericType(v.type))
          return v.type;
    return "";
  };
  // Each generic block's groups of variables (ANY_NUM, ANY_BIT...), in
  // order, and the types fixed for them so far.
  struct Groups {
    FbType *type;
    std::vector<std::string> order;
    std::map<std::string, std::string> fixed;
    // What a group no connection fixes takes: the first fixed group's
    // type, as OUT : ANY_NUM of F_MOD follows IN1 : ANY_INT.
    std::string concrete(const std::string &group) const {
      if (auto it = fixed.find(group); it != fixed.end())
        return it->second;
      for (const std::string &g : order)
        if (auto it = fixed.find(g); it != fixed.end())
          return it->second;
      return "";
    }
  };
  std::map<std::string, Groups> groups; // block (upper) -> its groups
  auto genericVar = [](const FbType &t, StringRef name) -> const Var * {
    for (const auto *list : {&t.inputs, &t.outputs})
      for (const Var &v : *list)
        if (StringRef(v.name).equals_insensitive(name) && isGenericType(v.type))
          return &v;
    return nullptr;
  };
  for (pugi::xml_node fb : generic) {
    StringRef inst = fb.attribute("Name").value();
    Groups &g = groups[inst.upper()];
    g.type = types.at(inst.upper());
    for (const auto *list : {&g.type->inputs, &g.type->outputs})
      for (const Var &v : *list)
        if (isGenericType(v.type) &&
            std::find(g.order.begin(), g.order.end(), v.type) == g.order.end())
          g.order.push_back(v.type);
    // 4diac IDE 3 configures an F_MOVE with the type it moves.
    for (pugi::xml_node a : fb.children("Attribute"))
      if (StringRef(a.attribute("Name").value()).equals_insensitive("DataType"))
        for (const std::string &group : g.order)
          g.fixed.emplace(group, a.attribute("Value").value());
    // A typed literal (DINT#7, T#1s, 'text') fixes its variable's group.
    for (pugi::xml_node p : fb.children("Parameter"))
      if (const Var *v = genericVar(*g.type, p.attribute("Name").value()))
        if (std::string lit = typeOfLiteral(src.placeAttribute(p, "Value"));
            !lit.empty())
          g.fixed.emplace(v->type, lit);
  }
  // The generic group of `end` ("block.PORT") when it is a generic block's
  // generic variable.
  auto groupAt = [&](StringRef end) -> std::pair<Groups *, std::string> {
    auto [blk, port] = end.split('.');
    auto it = groups.find(blk.upper());
    if (port.empty() || it == groups.end())
      return {nullptr, ""};
    const Var *v = genericVar(*it->second.type, port);
    return {v ? &it->second : nullptr, v ? v->type : ""};
  };
  // Connections fix groups until none changes: a typed port fixes the
  // group it is connected to, and a fixed group the groups of the generic
  // blocks chained to it (F_ADD -> F_MUL -> an INT input types both).
  for (bool changed = true; changed;) {
    changed = false;
    for (pugi::xml_node c :
         child(net, "DataConnections").children("Connection"))
      for (auto [here, there] : {std::pair{"Destination", "Source"},
                                 std::pair{"Source", "Destination"}}) {
        auto [g, group] = groupAt(c.attribute(here).value());
        if (!g || g->fixed.count(group))
          continue;
        std::string other = typeAt(c.attribute(there).value());
        if (auto [h, hgroup] = groupAt(c.attribute(there).value());
            other.empty() && h)
          other = h->concrete(hgroup);
        if (!other.empty()) {
          g->fixed[group] = other;
          changed = true;
        }
      }
  }
  for (pugi::xml_node fb : generic) {
    StringRef inst = fb.attribute("Name").value();
    const Groups &g = groups.at(inst.upper());
    FbType &t = *g.type;
    const std::vector<std::string> &order = g.order;
    if (g.fixed.empty()) {
      unconnectedGenericFunction(src, net, fb, t);
      types[inst.upper()] =
          this->types.at(StringRef(fb.attribute("Type").value()).upper()).get();
      continue;
    }
    auto concrete = [&](const std::string &group) { return g.concrete(group); };
    std::string name = t.name + "_";
    for (const std::string &g : order)
      name += "_" + concrete(g);
    std::string text = interfaceXml(name, t, [&](const Var &v) {
      return isGenericType(v.type) ? concrete(v.type) : v.type;
    });
    text +=
        "</InterfaceList>\n<SimpleFB><Algorithm Name=\"" +
        (t.eventInputs.empty() ? std::string("REQ") : t.eventInputs[0].name) +
        "\"><ST Text=\"" + xmlEscape(genericFunctionBody(t.name)) +
        "\"/></Algorithm></SimpleFB>\n</FBType>\n";
    generatedType(name, text);
    retype(fb, name);
    types[inst.upper()] = this->types.at(StringRef(name).upper()).get();
  }
  // A block modelled as environment (Iec61499Environment.cpp) with generic
  // ports: each port takes the type of the typed port it is connected to,
  // one by one (PUBLISH_2's SD_1 and SD_2 may differ), or of its typed
  // parameter (SD_1 = TRUE); a port of a channel end nothing fixes takes
  // the type of the other end's datum (a SUBSCRIBE_1 whose RD_1 is left
  // unconnected receives what its PUBLISH_1 sends). A generic port fixed by
  // nothing is left out, as nothing reads or drives it.
  std::map<std::string, std::map<std::string, std::string>> fixedOf;
  for (pugi::xml_node fb : environment) {
    StringRef inst = fb.attribute("Name").value();
    FbType &t = *types.at(inst.upper());
    std::map<std::string, std::string> &fixed = fixedOf[inst.upper()];
    for (pugi::xml_node c :
         child(net, "DataConnections").children("Connection"))
      for (auto [here, there] : {std::pair{"Destination", "Source"},
                                 std::pair{"Source", "Destination"}}) {
        auto [blk, port] = StringRef(c.attribute(here).value()).split('.');
        if (!blk.equals_insensitive(inst))
          continue;
        std::string other = typeAt(c.attribute(there).value());
        if (!other.empty())
          fixed.emplace(port.upper(), other);
      }
    for (pugi::xml_node p : fb.children("Parameter"))
      for (const Var &v : t.inputs)
        if (StringRef(v.name).equals_insensitive(p.attribute("Name").value()) &&
            isGenericType(v.type))
          if (std::string lit = typeOfLiteral(src.placeAttribute(p, "Value"));
              !lit.empty())
            fixed.emplace(StringRef(v.name).upper(), lit);
  }
  for (const Channel &c : channelsOf(src, net))
    for (auto [from, to] : {std::pair{&c.publishers, &c.subscribers},
                            std::pair{&c.subscribers, &c.publishers}})
      for (pugi::xml_node sender : *from)
        for (pugi::xml_node receiver : *to) {
          // SD_i of one end is RD_i of the other.
          auto &sent =
              fixedOf[StringRef(sender.attribute("Name").value()).upper()];
          auto &got =
              fixedOf[StringRef(receiver.attribute("Name").value()).upper()];
          for (auto &[port, type] : sent)
            if (StringRef(port).startswith("SD_"))
              got.emplace("RD_" + port.substr(3), type);
        }
  for (pugi::xml_node fb : environment) {
    StringRef inst = fb.attribute("Name").value();
    FbType &t = *types.at(inst.upper());
    const std::map<std::string, std::string> &fixed = fixedOf[inst.upper()];
    for (pugi::xml_node p : fb.children("Parameter"))
      for (const Var &v : t.inputs)
        if (StringRef(v.name).equals_insensitive(p.attribute("Name").value()) &&
            isGenericType(v.type) && !fixed.count(StringRef(v.name).upper()))
          fail(src.locOf(p),
               "parameter '" + v.name + "' of '" + inst +
                   "' has the generic type " + v.type +
                   " and nothing fixes it (connect it, give it a typed "
                   "value such as INT#5, or give the parameter to a typed "
                   "port)");
    auto concrete = [&](const Var &v) -> std::string {
      if (!isGenericType(v.type))
        return v.type;
      auto it = fixed.find(StringRef(v.name).upper());
      return it == fixed.end() ? "" : it->second;
    };
    std::string name = t.name + "_";
    for (const auto *list : {&t.inputs, &t.outputs})
      for (const Var &v : *list)
        if (isGenericType(v.type))
          name += "_" + (concrete(v).empty() ? std::string("X") : concrete(v));
    std::string text = interfaceXml(name, t, concrete);
    text += std::string("</InterfaceList>\n") +
            (t.kind == TypeKind::Service ? "<Service/>\n" : "") + "</FBType>\n";
    generatedType(name, text);
    retype(fb, name);
    types[inst.upper()] = this->types.at(StringRef(name).upper()).get();
  }
}

//===----------------------------------------------------------------------===//
// Function types (.fct)
//===----------------------------------------------------------------------===//

/// The ranges of `text` holding the `PACKAGE p;`, `USING p;` and `IMPORT
/// p;` declarations 4diac writes before a FUNCTION (the ST frontend reads
/// POUs only), skipping comments.
static std::vector<std::pair<size_t, size_t>> packageLines(StringRef text) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t i = 0;
  while (i < text.size()) {
    if (isspace((unsigned char)text[i])) {
      ++i;
    } else if (text.substr(i).startswith("(*") ||
               text.substr(i).startswith("/*")) {
      size_t end = text.find(text[i] == '(' ? "*)" : "*/", i + 2);
      i = end == StringRef::npos ? text.size() : end + 2;
    } else if (text.substr(i).startswith("//")) {
      i = std::min(text.find('\n', i), text.size());
    } else {
      size_t end = i;
      while (end < text.size() &&
             (isalnum((unsigned char)text[end]) || text[end] == '_'))
        ++end;
      StringRef word = text.slice(i, end);
      if (!word.equals_insensitive("PACKAGE") &&
          !word.equals_insensitive("USING") &&
          !word.equals_insensitive("IMPORT"))
        break;
      size_t semi = text.find(';', end);
      if (semi == StringRef::npos)
        break;
      out.push_back({i, semi + 1});
      i = semi + 1;
    }
  }
  return out;
}

/// Renames every use of variable `from` in `e` to `to`.
static void renameVariable(plc::Expr *e, StringRef from, StringRef to) {
  if (!e)
    return;
  if (e->kind == ExprKind::Name && StringRef(e->name).equals_insensitive(from))
    e->name = to.str();
  for (plc::Expr *o : e->operands)
    renameVariable(o, from, to);
  for (plc::CallArg &a : e->args)
    renameVariable(a.value, from, to);
}

/// A 4diac function (`<Function>`, 4diac IDE 3's `.fct`): an interface
/// (REQ, CNF, input and output variables; the return value an output
/// without a name) and a `<FunctionBody>` holding an ST `FUNCTION`. The ST
/// function joins the program under the name `<NAME>__FUNCTION` (the
/// block's module keeps the type's name), and the type becomes the simple
/// FB whose REQ calls it: `NAME := NAME__FUNCTION(IN := IN, ..., Q => Q);`
/// then CNF, so the function's locals start afresh at every call as the
/// ST frontend's calls have them. The unnamed return output is named like
/// the type.
void Translator::functionType(FbType &t) {
  t.function = true;
  pugi::xml_node iface = child(t.root, "InterfaceList");
  bool returns = false;
  for (pugi::xml_node v : child(iface, "OutputVars").children("VarDeclaration"))
    if (StringRef(v.attribute("Name").value()).empty()) {
      v.attribute("Name") = t.name.c_str();
      returns = true;
    }
  for (pugi::xml_node e : child(iface, "EventOutputs").children("Event"))
    for (pugi::xml_node w : e.children("With"))
      if (StringRef(w.attribute("Var").value()).empty())
        w.attribute("Var") = t.name.c_str();
  readInterface(t, iface);
  pugi::xml_node st = child(child(t.root, "FunctionBody"), "ST");
  if (!st)
    fail(t, t.root,
         "function '" + t.name +
             "' has no <FunctionBody> in ST; netlift reads ST functions");
  if (t.eventInputs.size() != 1 || t.eventOutputs.size() != 1)
    fail(t, t.root,
         "function '" + t.name + "' has " + Twine(t.eventInputs.size()) +
             " input and " + Twine(t.eventOutputs.size()) +
             " output events; a function block has REQ and CNF");
  // The body as placed in the file's copy that the SourceMgr owns (so that
  // errors keep their lines and columns), its package lines blanked there.
  StringRef body = t.src->placeText(st);
  t.src->editPlaced(body, [&](llvm::MutableArrayRef<char> placed) {
    for (auto [from, to] : packageLines(body))
      for (size_t i = from; i < to; ++i)
        if (placed[i] != '\n')
          placed[i] = ' ';
    dropPackageQualifiers(placed);
  });
  size_t before = unit.pous.size();
  if (!st::parseStructuredText(body, diag, unit))
    throw Failure();
  Pou *fn = unit.pous.size() == before + 1 ? unit.pous.back() : nullptr;
  if (!fn || fn->kind != PouKind::Function ||
      !StringRef(fn->name).equals_insensitive(t.name))
    fail(t.src->locOf(st), "the <FunctionBody> of function '" + t.name +
                               "' must declare one ST FUNCTION named '" +
                               t.name + "'");
  std::string internalName = t.name + "__FUNCTION";
  plc::forEachStmt(fn->body, nullptr, [&](plc::Expr *e) {
    renameVariable(e, fn->name, internalName);
  });
  fn->name = internalName;
  callFunctionTypes(fn->body);
  // REQ calls the function with every input and output.
  std::string call;
  for (const Var &v : t.inputs)
    call += (call.empty() ? "" : ", ") + v.name + " := " + v.name;
  for (const Var &v : t.outputs)
    if (!StringRef(v.name).equals_insensitive(t.name))
      call += (call.empty() ? "" : ", ") + v.name + " => " + v.name;
  call = internalName + "(" + call + ");";
  if (returns)
    call = t.name + " := " + call;
  t.body = t.root.append_child("SimpleFB");
  pugi::xml_node alg = t.body.append_child("Algorithm");
  alg.append_attribute("Name") = t.eventInputs[0].name.c_str();
  alg.append_child("ST").append_attribute("Text") = call.c_str();
  simpleAsBasic(t);
  t.kind = TypeKind::Basic;
}

FbType *Translator::functionTypeNamed(StringRef name) {
  std::string key = name.upper();
  auto it = types.find(key);
  if (it == types.end()) {
    indexLibraries();
    auto path = libraryIndex.find(key);
    if (path == libraryIndex.end() ||
        !StringRef(path->second).endswith_insensitive(".fct"))
      return nullptr;
    registerTypes(readLibraryFile(path->second, name, SMLoc()), false);
    it = types.find(key);
    if (it == types.end())
      return nullptr;
  }
  return it->second->function ? it->second.get() : nullptr;
}

void Translator::callFunctionTypes(plc::StmtList &body) {
  std::function<void(plc::Expr *)> visit = [&](plc::Expr *e) {
    if (!e)
      return;
    if (e->kind == ExprKind::Call && e->operands.empty())
      if (FbType *f = functionTypeNamed(e->name))
        e->name = f->name + "__FUNCTION";
    for (plc::Expr *o : e->operands)
      visit(o);
    for (plc::CallArg &a : e->args)
      visit(a.value);
  };
  plc::forEachStmt(body, nullptr, visit);
}

void Translator::nameReturnOutputs(XmlSource &src, pugi::xml_node net) {
  std::map<std::string, FbType *> types = blockTypes(src, net);
  for (pugi::xml_node c : child(net, "DataConnections").children("Connection"))
    for (const char *end : {"Source", "Destination"}) {
      pugi::xml_attribute a = c.attribute(end);
      auto [blk, port] = StringRef(a.value()).split('.');
      if (!StringRef(a.value()).endswith(".") || !port.empty())
        continue;
      auto it = types.find(blk.upper());
      if (it != types.end() && it->second->function)
        a = (blk + "." + it->second->name).str().c_str();
    }
}
