//===- Iec61499Networks.cpp - networks as modules -------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

#include "llvm/ADT/StringSwitch.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

//===----------------------------------------------------------------------===//
// Networks
//===----------------------------------------------------------------------===//

const net::Type *Translator::dataType(StringRef type, SMLoc at) {
  const PType *p = elementaryType(type);
  if (!p)
    fail(at, "data type '" + type +
                 "' of a network port is not supported (elementary types "
                 "only)");
  if (const net::Type *t = scalarNetType(p, design.types))
    return t;
  fail(at, "data type '" + type + "' is not supported by netlift");
}

void Translator::declarePorts(const FbType &t, bool skipGeneric) {
  for (const Event &e : t.eventInputs)
    b.addPort(e.name, net::PortKind::Event, net::PortDir::In, nullptr,
              t.src->locOf(e.node));
  for (const Event &e : t.eventOutputs)
    b.addPort(e.name, net::PortKind::Event, net::PortDir::Out, nullptr,
              t.src->locOf(e.node));
  for (const auto *list : {&t.inputs, &t.outputs})
    for (const Var &v : *list) {
      if (skipGeneric && isGenericType(v.type))
        continue;
      SMLoc at = t.src->locOf(v.node);
      net::PortDir dir =
          list == &t.inputs ? net::PortDir::In : net::PortDir::Out;
      if (StringRef(v.type).equals_insensitive("BOOL") &&
          !v.node.attribute("ArraySize")) {
        b.addPort(v.name, net::PortKind::Cond, dir, nullptr, at);
        continue;
      }
      const net::Type *type = portType(v, at);
      b.addPort(v.name, net::PortKind::Data, dir, type, at);
      if (!type)
        pendingPorts.push_back({b.getModule()->name.str(), v.name, &v});
    }
}

/// A module with one constant output standing for a parameter.
std::string Translator::parameterModule(XmlSource &src, StringRef type,
                                        pugi::xml_node param) {
  SMLoc at = src.locOf(param);
  StringRef text = src.placeAttribute(param, "Value");
  if (text.trim().empty())
    fail(at, "parameter '" + Twine(param.attribute("Name").value()) +
                 "' gives no value (Value is empty or missing): give one, "
                 "or remove the parameter to keep the input's initial value");
  // 4diac writes an array or structure parameter as its initialiser.
  if (text.trim().startswith("[") || text.trim().startswith("("))
    fail(at, "parameter '" + Twine(param.attribute("Name").value()) +
                 "' gives an array or structure value ('" + text.trim() +
                 "'), which netlift does not take as a parameter: connect "
                 "the input, or give the value as the input's InitialValue "
                 "in its type");
  Expr *e = st::parseStExpression(text, diag, unit);
  if (!e)
    throw Failure();
  return constantModule(type, e, text, at);
}

/// The module whose output OUT is the literal `e` (of IEC type `type`).
std::string Translator::constantModule(StringRef type, Expr *e, StringRef text,
                                       SMLoc at) {
  bool negative = false;
  if (e->kind == ExprKind::Unary && e->op == Op::Neg) {
    negative = true;
    e = e->operands[0];
  }
  std::string key;
  if (e->kind == ExprKind::TimeLit) {
    if (!StringRef(type).equals_insensitive("TIME"))
      fail(at, "a duration '" + text.trim() + "' given for a value of type " +
                   type);
    parameterTimes.push_back(e->intValue);
    key = "TIME_" + std::string(negative ? "m" : "") +
          formatDuration(e->intValue);
  } else if (e->kind == ExprKind::IntLit || e->kind == ExprKind::BoolLit) {
    key = StringRef(type).upper() + "_" + (negative ? "m" : "") +
          std::to_string(e->intValue);
  } else if (e->kind == ExprKind::DateLit) {
    // D#, TOD#, DT# (nanoseconds since the epoch or midnight, as in ST).
    auto spelled = [](StringRef t) {
      return llvm::StringSwitch<StringRef>(t.upper())
          .Cases("D", "DATE", "DATE")
          .Cases("TOD", "TIME_OF_DAY", "TIME_OF_DAY")
          .Cases("DT", "DATE_AND_TIME", "DATE_AND_TIME")
          .Cases("LD", "LDATE", "LDATE")
          .Cases("LTOD", "LTIME_OF_DAY", "LTIME_OF_DAY")
          .Cases("LDT", "LDATE_AND_TIME", "LDATE_AND_TIME")
          .Default("");
    };
    const PType *declared = elementaryType(spelled(type));
    if (!declared || declared != elementaryType(spelled(e->typeName)))
      fail(at, "a " + Twine(e->typeName) + " literal '" + text.trim() +
                   "' given for a value of type " + type);
    key = StringRef(type).upper() + "_" + std::to_string(e->intValue);
  } else if (e->kind == ExprKind::RealLit || e->kind == ExprKind::StringLit) {
    bool real = e->kind == ExprKind::RealLit;
    const PType *declared = elementaryType(type);
    if (!declared ||
        declared->kind != (real ? PTypeKind::Real : PTypeKind::String))
      fail(at, std::string(real ? "a real number" : "a string") + " '" +
                   text.trim() + "' given for a value of type " + type);
    if (real) {
      key = StringRef(type).upper() + "_" + (negative ? "m" : "") +
            net::toIdentifier(net::formatReal(e->realValue));
    } else {
      size_t id = stringConstants.emplace(e->name, stringConstants.size())
                      .first->second;
      key = StringRef(type).upper() + "_" + std::to_string(id);
    }
  } else {
    fail(at, "parameter value '" + text.trim() +
                 "' is not supported (integer, real, Boolean, string, "
                 "duration and date and time literals only)");
  }
  std::string module = "Const_" + key;
  if (negative && e->kind != ExprKind::IntLit && e->kind != ExprKind::TimeLit &&
      e->kind != ExprKind::RealLit)
    fail(at, "'-' before a non-number");
  if (negative) {
    e->intValue = -e->intValue;
    e->realValue = -e->realValue;
  }
  constants.try_emplace(module, Constant{module, type.str(), e, at});
  return module;
}

void Translator::networkOf(StringRef name, XmlSource &src, pugi::xml_node net,
                           const FbType *iface, SMLoc at) {
  net::Module *m = b.createModule(net::toIdentifier(name), false, at);
  if (!m)
    fail(at, "a module named '" + name + "' exists already");
  if (iface)
    declarePorts(*iface);
  std::map<std::string, FbType *> instances; // upper-case name -> type
  for (pugi::xml_node fb : blocksOf(net)) {
    std::string inst = fb.attribute("Name").value();
    SMLoc loc = src.locOf(fb);
    FbType *type = findType(fb.attribute("Type").value(), loc);
    if (!instances.emplace(StringRef(inst).upper(), type).second)
      fail(loc, "two function blocks named '" + inst + "'");
    b.addInstance(inst, net::toIdentifier(type->name), loc);
    for (pugi::xml_node p : fb.children("Parameter")) {
      std::string pname = p.attribute("Name").value();
      const Var *var = nullptr;
      for (const Var &v : type->inputs)
        if (StringRef(v.name).equals_insensitive(pname))
          var = &v;
      if (!var)
        fail(src.locOf(p), "parameter '" + pname +
                               "' is not a data input of '" + type->name + "'");
      driveWithConstant(inst, var->name, parameterModule(src, var->type, p),
                        src.locOf(p));
    }
  }
  auto endpoint = [&](pugi::xml_node c, const char *attr) {
    StringRef text = c.attribute(attr).value();
    SMLoc loc = src.locOf(c);
    auto [a, p] = text.split('.');
    if (p.empty())
      return net::Endpoint{"", design.save(a), loc};
    // An element of the enclosing type's own plug or socket.
    if (!instances.count(a.upper()) && iface)
      if (const AdapterUse *own = iface->adapter(a))
        return net::Endpoint{"", design.save(adapterPort(own->name, p)), loc};
    auto inst = instances.find(a.upper());
    if (inst == instances.end())
      fail(loc, Twine(attr) + " '" + text + "' names no function block of '" +
                    name + "'");
    // `B.S.e`: element e of block B's plug or socket S.
    auto [port, element] = p.split('.');
    if (!element.empty())
      if (const AdapterUse *ad = inst->second->adapter(port))
        return net::Endpoint{design.save(a),
                             design.save(adapterPort(ad->name, element)), loc};
    return net::Endpoint{design.save(a), design.save(p), loc};
  };
  std::set<std::pair<std::string, std::string>> driven; // (inst, port) upper
  bool neverMade = false;
  for (pugi::xml_node fb : blocksOf(net))
    for (pugi::xml_node p : fb.children("Parameter"))
      driven.insert({StringRef(fb.attribute("Name").value()).upper(),
                     StringRef(p.attribute("Name").value()).upper()});
  for (pugi::xml_node c :
       child(net, "DataConnections").children("Connection")) {
    net::Endpoint from = endpoint(c, "Source"), to = endpoint(c, "Destination");
    driven.insert({to.instance.upper(), to.port.upper()});
    b.addConnection(from, to, src.locOf(c));
  }
  connectChannels(src, net);
  // The environment's events reach a top type's network through a queue,
  // one per step (like a runtime's external events), not all at once.
  bool queued = iface && tops.count(iface) && !iface->eventInputs.empty();
  if (queued) {
    b.addInstance("_inputs", "_Inputs_" + iface->name, at);
    for (const Event &e : iface->eventInputs)
      b.addConnection({"", design.save(e.name), at},
                      {"_inputs", design.save(e.name), at}, at);
  }
  // Events by source in document order; a relay where relayWays says.
  std::vector<std::string> sources;
  std::map<std::string, std::vector<pugi::xml_node>> bySource =
      eventsBySource(net, &sources);
  for (const std::string &key : sources) {
    const std::vector<pugi::xml_node> &conns = bySource[key];
    net::Endpoint from = endpoint(conns.front(), "Source");
    if (queued && from.instance.empty())
      from = {"_inputs", design.save(from.port.str() + "_o"), from.loc};
    if (size_t ways = relayWays(conns)) {
      std::string fan =
          "_fan_" +
          net::toIdentifier((from.instance.empty() ? from.port.str()
                                                   : from.instance.str() + "_" +
                                                         from.port.str()));
      b.addInstance(fan, fanOutType(ways), from.loc);
      b.addConnection(from, {design.save(fan), "EI", from.loc}, from.loc);
      for (size_t i = 0; i < conns.size(); ++i) {
        net::Endpoint to = endpoint(conns[i], "Destination");
        driven.insert({to.instance.upper(), to.port.upper()});
        b.addConnection({design.save(fan),
                         design.save("EO" + std::to_string(i + 1)), to.loc},
                        to, src.locOf(conns[i]));
      }
      continue;
    }
    for (pugi::xml_node c : conns) {
      net::Endpoint to = endpoint(c, "Destination");
      driven.insert({to.instance.upper(), to.port.upper()});
      b.addConnection(from, to, src.locOf(c));
    }
  }
  // An unconnected input of a block inside a network never sees an event and
  // keeps its initial value (it is not the environment's).
  for (pugi::xml_node fb : blocksOf(net)) {
    std::string inst = fb.attribute("Name").value();
    SMLoc loc = src.locOf(fb);
    FbType *type = instances[StringRef(inst).upper()];
    for (const Event &e : type->eventInputs)
      if (!driven.count({StringRef(inst).upper(), StringRef(e.name).upper()})) {
        if (!neverMade) {
          b.addInstance("_never", "Never", loc);
          neverMade = neverNeeded = true;
        }
        b.addConnection({"_never", "EO", loc},
                        {design.save(inst), design.save(e.name), loc}, loc);
      }
    for (const Var &v : type->inputs) {
      if (driven.count({StringRef(inst).upper(), StringRef(v.name).upper()}))
        continue;
      bool found;
      StringRef text =
          type->src->placeAttribute(v.node, "InitialValue", &found);
      Expr *value = nullptr;
      SMLoc vloc = type->src->locOf(v.node);
      if (!elementaryType(v.type) || v.node.attribute("ArraySize")) {
        // A structure or an array: its value is the one the block's own
        // copy of the input starts with, known once the blocks are lowered.
        std::string module =
            "Init_" + net::toIdentifier(type->name) + "_" + v.name;
        aggregateConstants.try_emplace(module, type, v.name, vloc);
        driveWithConstant(inst, v.name, module, loc);
        continue;
      }
      if (found && !text.trim().empty()) {
        value = st::parseStExpression(text, diag, unit);
        if (!value)
          throw Failure();
      } else if (StringRef(v.type).equals_insensitive("TIME")) {
        value = unit.make<Expr>(ExprKind::TimeLit, vloc);
      } else if (StringRef(v.type).equals_insensitive("BOOL")) {
        value = boolLit(unit, false, vloc);
      } else if (elementaryType(v.type)->kind == PTypeKind::Real) {
        value = unit.make<Expr>(ExprKind::RealLit, vloc);
        text = "0.0";
      } else if (elementaryType(v.type)->kind == PTypeKind::String) {
        value = unit.make<Expr>(ExprKind::StringLit, vloc);
        value->name = "''";
        text = value->name;
      } else {
        value = intLit(unit, 0, vloc);
        text = "0";
      }
      driveWithConstant(inst, v.name, constantModule(v.type, value, text, vloc),
                        loc);
    }
  }
}

/// `_<inst>_<input> : module`, whose OUT drives `inst.input`.
void Translator::driveWithConstant(StringRef inst, StringRef input,
                                   const std::string &module, SMLoc at) {
  std::string driver = "_" + inst.str() + "_" + input.str();
  b.addInstance(driver, module, at);
  b.addConnection({design.save(driver), "OUT", at},
                  {design.save(inst), design.save(input), at}, at);
}

/// Where each block of an application runs (the system's Mapping) is kept
/// as attributes of its instance: `attr boot device = "PLC";` and `attr
/// boot resource = "RES";`. A block inside a subapplication gives the
/// subapplication's instance `mapping = "inner.path -> PLC.RES"`.
void Translator::keepMapping(XmlSource &src, pugi::xml_node sys,
                             pugi::xml_node app) {
  net::Module *m = b.getModule();
  StringRef appName = app.attribute("Name").value();
  std::set<std::string> resources; // DEVICE.RESOURCE
  for (pugi::xml_node mp : sys.children("Mapping")) {
    StringRef from = mp.attribute("From").value();
    auto [fromApp, path] = from.split('.');
    if (!fromApp.equals_insensitive(appName))
      continue;
    llvm::SmallVector<StringRef, 4> to;
    StringRef(mp.attribute("To").value()).split(to, '.');
    if (to.size() < 3)
      fail(src.locOf(mp), "mapping target '" +
                              Twine(mp.attribute("To").value()) +
                              "' is not DEVICE.RESOURCE.BLOCK");
    auto [block, inner] = path.split('.');
    const net::Instance *inst = nullptr;
    for (const net::Instance &i : m->instances)
      if (i.name.equals_insensitive(block))
        inst = &i;
    if (!inst)
      fail(src.locOf(mp), "mapping source '" + from +
                              "' names no block of application '" + appName +
                              "'");
    SMLoc at = src.locOf(mp);
    resources.insert((to[0] + "." + to[1]).str());
    if (inner.empty()) {
      b.addAttribute(inst->name, "device", to[0], at);
      b.addAttribute(inst->name, "resource", to[1], at);
    } else {
      b.addAttribute(inst->name, "mapping",
                     (inner + " -> " + to[0] + "." + to[1]).str(), at);
    }
  }
  // One resource's order for blocks of several under-approximates: runs in
  // which the resources interleave their chains are missing.
  if (resources.size() > 1 && semantics != "sequential") {
    std::string list;
    for (const std::string &r : resources)
      list += (list.empty() ? "" : ", ") + r;
    diag.warning(src.locOf(app),
                 "application '" + appName + "' is mapped to " +
                     Twine(resources.size()) + " resources (" + list +
                     "); under --fb-semantics " + semantics +
                     " netlift runs it as one resource, so runs in which "
                     "the resources interleave their event chains are not "
                     "in the model (--fb-semantics sequential has every "
                     "order)");
  }
}

/// A resource holds a copy of each block mapped to it, with its type
/// again; the runtime runs the copy, netlift the application's block, so
/// the two types must be the same.
void Translator::checkMappedType(XmlSource &src, pugi::xml_node sys,
                                 pugi::xml_node copy, StringRef from) {
  auto [appName, path] = from.split('.');
  if (path.contains('.'))
    return; // inside a subapplication: the copy is of the inner block
  for (pugi::xml_node app : sys.children("Application")) {
    if (!appName.equals_insensitive(app.attribute("Name").value()))
      continue;
    pugi::xml_node net = child(app, "SubAppNetwork");
    if (!net)
      net = child(app, "FBNetwork");
    for (pugi::xml_node fb : blocksOf(net)) {
      StringRef type = declaredType(fb);
      StringRef copyType = copy.attribute("Type").value();
      if (!path.equals_insensitive(fb.attribute("Name").value()) ||
          copyType.empty() || copyType.equals_insensitive(type))
        continue;
      diag.error(src.locOf(copy),
                 "FB '" + Twine(copy.attribute("Name").value()) +
                     "' is typed " + copyType + " in its resource but " + type +
                     " in application '" + appName + "'");
      diag.note(src.locOf(fb), "the application's block");
      throw Failure();
    }
  }
}

void Translator::network(FbType &t) {
  networkOf(t.name, *t.src, t.body, &t, t.src->locOf(t.root));
}

/// Timed service FBs: START begins a delay of DT (ignored while one runs),
/// STOP cancels it. The clock is capped at the longest duration parameter
/// of the translation (a DT may come from outside a composite, so the
/// parameters given to the delays themselves do not suffice); a longer DT
/// at run time is a range error with its trace.
void Translator::serviceModule(FbType &t) {
  int64_t tick = int64_t(design.timescale->nanoseconds());
  int64_t longest = 0;
  for (int64_t ns : parameterTimes)
    longest = std::max(longest, ns);
  // Rounded up: a duration that is no whole number of ticks is reported
  // with its parameter.
  int64_t cap = std::max<int64_t>((longest + tick - 1) / tick, 1);
  bool cyclic = t.name == "E_CYCLE";
  // An idle delay keeps its clock parked at the cap (where ticks leave
  // it), so idle states do not differ by how long ago the delay ended.
  SMLoc at = t.src->locOf(t.root);
  if (!b.createModule(t.name, false, at))
    fail(at, "a module named '" + t.name + "' exists already");
  uint32_t start =
      b.addPort("START", net::PortKind::Event, net::PortDir::In, nullptr, at);
  uint32_t stop =
      b.addPort("STOP", net::PortKind::Event, net::PortDir::In, nullptr, at);
  uint32_t eo =
      b.addPort("EO", net::PortKind::Event, net::PortDir::Out, nullptr, at);
  b.addPort("DT", net::PortKind::Data, net::PortDir::In,
            design.types.getInt(64, true, net::Overflow::Error), at);
  b.addVar("_DT", design.types.getRange(0, cap), b.intLit(0, at), at);
  b.addVar("_t", design.types.getClock(cap), b.intLit(cap, at), at);
  uint32_t idle = b.addPlace("idle", 1, 1, at);
  uint32_t running = b.addPlace("running", 0, 1, at);
  auto assign = [&](StringRef var, net::Expr *value) {
    return b.assign(b.ref(var, at), value, at);
  };
  uint32_t tStart = b.addTransition("start", {net::PreArc{idle, 1, {}}},
                                    {net::PostArc{running, 1}}, at);
  b.setEvents(tStart, {net::EventSource{start, true}});
  b.setAction(tStart,
              {assign("_DT", b.ref("DT", at)), assign("_t", b.intLit(0, at))});
  // 4diac's E_RDELAY: a START while delaying starts the delay again (E_DELAY
  // and E_CYCLE ignore it).
  if (t.name == "E_RDELAY") {
    uint32_t tRestart =
        b.addTransition("restart", {net::PreArc{running, 1, {}}},
                        {net::PostArc{running, 1}}, at);
    b.setEvents(tRestart, {net::EventSource{start, true}});
    b.setAction(tRestart, {assign("_DT", b.ref("DT", at)),
                           assign("_t", b.intLit(0, at))});
  }
  uint32_t tStop = b.addTransition("stop", {net::PreArc{running, 1, {}}},
                                   {net::PostArc{idle, 1}}, at);
  b.setEvents(tStop, {net::EventSource{stop, true}});
  b.setAction(tStop, {assign("_t", b.intLit(cap, at))});
  uint32_t tExpire =
      b.addTransition("expire", {net::PreArc{running, 1, {}}},
                      {net::PostArc{cyclic ? running : idle, 1}}, at);
  b.setGuard(tExpire, b.binary(net::BinaryOp::Ge, b.ref("_t", at),
                               b.ref("_DT", at), at));
  b.setEmits(tExpire, {eo});
  b.setUrgent(tExpire);
  b.setAction(tExpire, {assign("_t", b.intLit(cyclic ? 0 : cap, at))});
}

/// E_RESTART: COLD once, at start-up.
void Translator::restartModule(FbType &t) {
  SMLoc at = t.src->locOf(t.root);
  if (!b.createModule("E_RESTART", false, at))
    fail(at, "a module named 'E_RESTART' exists already");
  uint32_t cold =
      b.addPort("COLD", net::PortKind::Event, net::PortDir::Out, nullptr, at);
  b.addPort("WARM", net::PortKind::Event, net::PortDir::Out, nullptr, at);
  b.addPort("STOP", net::PortKind::Event, net::PortDir::Out, nullptr, at);
  uint32_t boot = b.addPlace("boot", 1, 1, at);
  uint32_t tCold = b.addTransition("cold", {net::PreArc{boot, 1, {}}}, {}, at);
  b.setEmits(tCold, {cold});
  b.setUrgent(tCold);
}
