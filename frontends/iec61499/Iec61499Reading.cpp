//===- Iec61499Reading.cpp - reading IEC 61499 types ----------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

//===----------------------------------------------------------------------===//
// Reading
//===----------------------------------------------------------------------===//

/// Service FBs netlift has a model of (whatever file declares them).
bool netlift::iec61499::detail::isShipped(StringRef name) {
  return name == "E_DELAY" || name == "E_RDELAY" || name == "E_CYCLE" ||
         name == "E_RESTART";
}

File &Translator::readFile(unsigned id) {
  auto f = std::make_unique<File>();
  f->doc = std::make_unique<pugi::xml_document>();
  f->src = std::make_unique<XmlSource>(id, diag);
  if (!f->src->parse(*f->doc, diag))
    throw Failure();
  unqualifyTypeNames(f->doc->document_element());
  files.push_back(std::move(f));
  return *files.back();
}

void Translator::readInterface(FbType &t, pugi::xml_node iface) {
  auto events = [&](pugi::xml_node list, std::vector<Event> &out) {
    for (pugi::xml_node e : list.children()) {
      StringRef kind = localName(e);
      if (kind != "Event" && kind != "SubAppEvent")
        continue;
      Event ev;
      ev.name = e.attribute("Name").value();
      ev.node = e;
      if (ev.name.empty())
        fail(t, e, "<" + kind + "> without a Name");
      for (pugi::xml_node w : e.children("With"))
        ev.with.push_back(w.attribute("Var").value());
      out.push_back(ev);
    }
  };
  auto vars = [&](pugi::xml_node list, std::vector<Var> &out) {
    for (pugi::xml_node v : list.children("VarDeclaration")) {
      Var var{v.attribute("Name").value(), v.attribute("Type").value(), v};
      if (var.name.empty())
        fail(t, v, "<VarDeclaration> without a Name");
      out.push_back(var);
    }
  };
  events(child(iface, "EventInputs"), t.eventInputs);
  events(child(iface, "SubAppEventInputs"), t.eventInputs);
  events(child(iface, "EventOutputs"), t.eventOutputs);
  events(child(iface, "SubAppEventOutputs"), t.eventOutputs);
  vars(child(iface, "InputVars"), t.inputs);
  vars(child(iface, "OutputVars"), t.outputs);
  for (pugi::xml_node v : child(iface, "InOutVars").children("VarDeclaration"))
    fail(t, v,
         "in-out variable '" + Twine(v.attribute("Name").value()) + "' of '" +
             t.name +
             "' (<InOutVars>, VAR_IN_OUT) is not supported: netlift reads "
             "input and output variables");
  for (const char *adapters : {"Plugs", "Sockets"})
    for (pugi::xml_node a :
         child(iface, adapters).children("AdapterDeclaration"))
      t.adapterDecls.push_back({a, StringRef(adapters) == "Plugs"});
}

/// A plug or socket of adapter type A becomes ports of the type it is
/// declared in: what flows from plug to socket (A's event outputs and
/// output variables) leaves through a plug and enters through a socket;
/// A's event inputs and input variables flow the other way. Each port is
/// named `<plug or socket>_<element>`, so that a plug is wired to a socket
/// by one event or data connection per element.
void Translator::expandAdapters(FbType &t) {
  if (t.adapterDecls.empty())
    return;
  pugi::xml_node copies = t.root.append_child("_netliftAdapterPorts");
  for (auto [decl, isPlug] : t.adapterDecls) {
    std::string name = decl.attribute("Name").value();
    SMLoc at = t.src->locOf(decl);
    if (name.empty())
      fail(at, "<AdapterDeclaration> without a Name");
    FbType *a = findType(decl.attribute("Type").value(), at, "adapter");
    checkPackage(decl, *a, at);
    if (a->kind != TypeKind::Adapter)
      fail(at, "'" + a->name + "' of " + (isPlug ? "plug" : "socket") + " '" +
                   name + "' is not an adapter type");
    if (t.adapter(name))
      fail(at, "two plugs or sockets named '" + name + "'");
    t.adapters.push_back({name, isPlug, a, decl});
    auto taken = [&](StringRef n) {
      for (const auto *list : {&t.eventInputs, &t.eventOutputs})
        for (const Event &e : *list)
          if (StringRef(e.name).equals_insensitive(n))
            return true;
      for (const auto *list : {&t.inputs, &t.outputs})
        for (const Var &v : *list)
          if (StringRef(v.name).equals_insensitive(n))
            return true;
      return false;
    };
    // Copies in the type's own document keep the declarations' attributes
    // readable (elements netlift adds have no place in the text).
    auto copy = [&](pugi::xml_node orig) {
      std::string port = adapterPort(name, orig.attribute("Name").value());
      if (taken(port))
        fail(at, "port '" + port + "' of " + (isPlug ? "plug" : "socket") +
                     " '" + name + "' clashes with a name of '" + t.name + "'");
      pugi::xml_node c = copies.append_copy(orig);
      c.attribute("Name") = port.c_str();
      return c;
    };
    auto events = [&](const std::vector<Event> &from, std::vector<Event> &to) {
      for (const Event &e : from) {
        Event ev;
        ev.node = copy(e.node);
        ev.name = ev.node.attribute("Name").value();
        for (const std::string &w : e.with)
          ev.with.push_back(adapterPort(name, w));
        to.push_back(ev);
      }
    };
    auto vars = [&](const std::vector<Var> &from, std::vector<Var> &to) {
      for (const Var &v : from) {
        pugi::xml_node c = copy(v.node);
        to.push_back({c.attribute("Name").value(), v.type, c});
      }
    };
    events(a->eventOutputs, isPlug ? t.eventOutputs : t.eventInputs);
    events(a->eventInputs, isPlug ? t.eventInputs : t.eventOutputs);
    vars(a->outputs, isPlug ? t.outputs : t.inputs);
    vars(a->inputs, isPlug ? t.inputs : t.outputs);
  }
}

void Translator::registerTypes(File &f, bool builtin) {
  pugi::xml_node root = f.doc->document_element();
  StringRef kind = localName(root);
  if (kind == "System") {
    systems.push_back({&f, root});
    return;
  }
  if (kind == "DataType") {
    StringRef name = root.attribute("Name").value();
    if (name.empty())
      fail(f.src->locOf(root), "<DataType> without a Name");
    auto [it, fresh] = dataTypes.try_emplace(name.upper(), f.src.get(), root);
    if (!fresh) {
      diag.error(f.src->locOf(root),
                 "data type '" + name + "' is defined twice");
      diag.note(it->second.first->locOf(it->second.second),
                "the first definition");
      throw Failure();
    }
    return;
  }
  if (kind == "GlobalConstants")
    addGlobalConstants(f);
  if (isPlatformType(kind) || isDeclarationsOnly(kind))
    return;
  auto t = std::make_unique<FbType>();
  t->name = root.attribute("Name").value();
  t->package = child(root, "CompilerInfo").attribute("packageName").value();
  t->src = f.src.get();
  t->root = root;
  t->builtin = builtin;
  if (kind != "FBType" && kind != "SubAppType" && kind != "AdapterType" &&
      kind != "Function")
    fail(*t, root,
         "not an IEC 61499 type or system: root element <" + kind +
             "> (known: FBType, SubAppType, AdapterType, Function, DataType, "
             "System, DeviceType, ResourceType, SegmentType)");
  if (t->name.empty())
    fail(*t, root, "<" + kind + "> without a Name");
  if (kind == "AdapterType") {
    readInterface(*t, child(root, "InterfaceList"));
    t->kind = TypeKind::Adapter;
  } else if (kind == "Function") {
    functionType(*t);
  } else if (kind == "SubAppType") {
    readInterface(*t, child(root, "SubAppInterfaceList"));
    t->kind = TypeKind::SubApp;
    t->body = child(root, "SubAppNetwork");
  } else {
    readInterface(*t, child(root, "InterfaceList"));
    if ((t->body = child(root, "BasicFB")))
      t->kind = TypeKind::Basic;
    else if ((t->body = child(root, "FBNetwork")))
      t->kind = TypeKind::Composite;
    else if ((t->body = child(root, "SimpleFB"))) {
      simpleAsBasic(*t);
      t->kind = TypeKind::Basic;
    } else if ((t->body = child(root, "Service")))
      t->kind = TypeKind::Service;
    if (t->kind == TypeKind::Basic)
      runtimeAlgorithms(*t);
  }
  std::string key = StringRef(t->name).upper();
  auto [it, fresh] = types.try_emplace(key, nullptr);
  if (!fresh) {
    if (builtin || it->second->builtin == builtin)
      fail(*t, root,
           "type '" + t->name + "' is defined twice (first at line " +
               Twine(diag.sourceMgr()
                         .getLineAndColumn(
                             it->second->src->locOf(it->second->root))
                         .first) +
               ")");
  }
  it->second = std::move(t);
}

void Translator::indexLibraries() {
  if (indexed)
    return;
  indexed = true;
  // First match in directory order given, then sorted paths.
  for (const std::string &dir : libs) {
    std::vector<std::string> found;
    std::error_code ec;
    for (llvm::sys::fs::recursive_directory_iterator it(dir, ec), end;
         it != end && !ec; it.increment(ec)) {
      StringRef ext = llvm::sys::path::extension(it->path());
      if (ext.equals_insensitive(".fbt") || ext.equals_insensitive(".sub") ||
          ext.equals_insensitive(".adp") || ext.equals_insensitive(".dtp") ||
          ext.equals_insensitive(".fct"))
        found.push_back(it->path());
      else if (ext.equals_insensitive(".gcf"))
        globalConstantFiles.push_back(it->path());
    }
    if (ec)
      fail(SMLoc(), "-I " + dir + ": " + ec.message());
    std::sort(found.begin(), found.end());
    for (const std::string &p : found)
      (llvm::sys::path::extension(p).equals_insensitive(".dtp") ? dataTypeIndex
                                                                : libraryIndex)
          .try_emplace(llvm::sys::path::stem(p).upper(), p);
  }
}

FbType *Translator::searchLibraries(StringRef name, SMLoc use) {
  indexLibraries();
  std::string key = name.upper();
  if (auto it = libraryIndex.find(key); it != libraryIndex.end()) {
    registerTypes(readLibraryFile(it->second, name, use), false);
    if (auto t = types.find(key); t != types.end())
      return t->second.get();
  }
  return libraryType(name, use);
}

File &Translator::readPath(const std::string &path) {
  auto buf = llvm::MemoryBuffer::getFile(path);
  if (!buf)
    fail(SMLoc(), "cannot read '" + path + "': " + buf.getError().message());
  return readFile(
      diag.sourceMgr().AddNewSourceBuffer(std::move(*buf), SMLoc()));
}

File &Translator::readLibraryFile(const std::string &path, StringRef name,
                                  SMLoc use) {
  File &f = readPath(path);
  // The file is found by its name; the type it declares must be the one
  // asked for, or the block would silently run another type (or
  // netlift's own model of the name).
  pugi::xml_node root = f.doc->document_element();
  StringRef declared = root.attribute("Name").value();
  if (localName(root) != "System" && !declared.equals_insensitive(name)) {
    diag.error(use, "type '" + name + "' is found in '" + path +
                        "', which declares type '" + declared + "'");
    diag.note(f.src->locOf(root), "the type declared there");
    throw Failure();
  }
  return f;
}

FbType *Translator::libraryType(StringRef name, SMLoc use) {
  for (const LibraryFile &lf : kLibraryFiles)
    if (llvm::sys::path::stem(lf.name).equals_insensitive(name)) {
      unsigned id = diag.sourceMgr().AddNewSourceBuffer(
          llvm::MemoryBuffer::getMemBuffer(
              lf.text, ("<netlift library>/" + Twine(lf.name)).str()),
          SMLoc());
      registerTypes(readFile(id), true);
      if (auto t = types.find(name.upper()); t != types.end())
        return t->second.get();
    }
  std::optional<std::string> xml = standardTypeXml(name);
  if (!xml)
    return nullptr;
  unsigned id = diag.sourceMgr().AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(
          *xml, ("<netlift library>/" + name + ".fbt").str()),
      SMLoc());
  registerTypes(readFile(id), true);
  diag.note(use, "type '" + name +
                     "' is in neither the inputs nor the -I directories: "
                     "netlift takes it as 4diac's standard library type of "
                     "that name (docs/iec61499.md)");
  auto t = types.find(name.upper());
  return t == types.end() ? nullptr : t->second.get();
}

FbType *Translator::findType(StringRef name, SMLoc use, const char *what) {
  if (auto it = types.find(name.upper()); it != types.end())
    return it->second.get();
  // The timed and start-up FBs are always netlift's models (4diac's are
  // service FBs, or composites taking DT from outside).
  if (isShipped(name))
    return libraryType(name);
  if (FbType *t = searchLibraries(name, use))
    return t;
  fail(use, "unknown " + Twine(what) + " type '" + name +
                "' (not in the inputs, the -I directories or netlift's "
                "library)");
}

/// The function blocks and subapplications of a network, in order.
std::vector<pugi::xml_node>
netlift::iec61499::detail::blocksOf(pugi::xml_node net) {
  std::vector<pugi::xml_node> out;
  for (pugi::xml_node fb : net.children())
    if (localName(fb) == "FB" || localName(fb) == "SubApp")
      out.push_back(fb);
  return out;
}

static constexpr const char *kDeclaredType = "netlift.DeclaredType";

void netlift::iec61499::detail::retype(pugi::xml_node fb,
                                       const std::string &type) {
  if (!fb.attribute(kDeclaredType))
    fb.append_attribute(kDeclaredType) = fb.attribute("Type").value();
  fb.attribute("Type") = type.c_str();
}

StringRef netlift::iec61499::detail::declaredType(pugi::xml_node fb) {
  if (pugi::xml_attribute a = fb.attribute(kDeclaredType))
    return a.value();
  return fb.attribute("Type").value();
}

/// A basic or simple FB with an algorithm or method in another language
/// than ST (4diac's <Other Language="C++">: FB_RANDOM's generator) runs code
/// netlift cannot read: like a service FB, it is modelled as environment
/// (or refused, with --opaque=refuse, where its algorithm is read).
void Translator::runtimeAlgorithms(FbType &t) {
  if (!opaqueAsEnvironment)
    return;
  for (pugi::xml_node a : t.body.children())
    if ((localName(a) == "Algorithm" || localName(a) == "Method") &&
        !child(a, "ST")) {
      pugi::xml_node other = a.first_child();
      std::string language = other.attribute("Language").value();
      diag.note(t.src->locOf(a),
                std::string(localName(a) == "Algorithm" ? "algorithm '"
                                                        : "method '") +
                    a.attribute("Name").value() + "' of '" + t.name +
                    "' is written in " +
                    (other ? "<" + localName(other).str() + ">" +
                                 (language.empty() ? "" : " (" + language + ")")
                           : std::string("no language")) +
                    ", which netlift does not read: the block is modelled as "
                    "environment, like a service FB (--opaque=refuse "
                    "refuses it)");
      t.kind = TypeKind::NoBody;
      return;
    }
}

/// Finds every type `t` uses, depth first, so that a type is translated
/// after those it instantiates.
void Translator::collect(FbType &t) {
  if (t.translated)
    return;
  t.translated = true;
  expandAdapters(t);
  if ((t.kind == TypeKind::Service || t.kind == TypeKind::NoBody) &&
      !isShipped(t.name) && modelFunctionFb(t))
    t.kind = TypeKind::Basic;
  if (t.kind == TypeKind::Composite || t.kind == TypeKind::SubApp) {
    if (tops.count(&t) && !t.eventInputs.empty())
      collect(generatedType("_Inputs_" + t.name, inputQueueType(t)));
    collectNetwork(*t.src, t.body, &t);
  }
  collectInternalFbs(t);
  order.push_back(&t);
}

/// An untyped subapplication (its interface and network inline, as 4diac
/// saves a subapplication not made a type) becomes a subapplication type of
/// its own, read where it stands (errors point into the system's file),
/// named after the network it is in and its own name.
void Translator::untypedSubApp(XmlSource &src, pugi::xml_node fb,
                               const FbType *owner) {
  std::string base = (owner ? owner->name : std::string("App")) + "_" +
                     fb.attribute("Name").value();
  std::string name = base;
  for (int k = 2; types.count(StringRef(name).upper()); ++k)
    name = base + "_" + std::to_string(k);
  auto t = std::make_unique<FbType>();
  t->name = name;
  t->src = &src;
  t->root = fb;
  readInterface(*t, child(fb, "SubAppInterfaceList"));
  t->kind = TypeKind::SubApp;
  t->body = child(fb, "SubAppNetwork");
  if (!t->body)
    fail(src.locOf(fb), "subapplication '" +
                            Twine(fb.attribute("Name").value()) +
                            "' has neither a Type nor a <SubAppNetwork>");
  types[StringRef(name).upper()] = std::move(t);
  fb.append_attribute("Type") = name.c_str();
}

void Translator::collectNetwork(XmlSource &src, pugi::xml_node net,
                                const FbType *owner) {
  // 4diac leaves out the end of a connection it cannot resolve (a block or
  // port missing from the library: an error marker in the IDE).
  for (const char *list :
       {"EventConnections", "DataConnections", "AdapterConnections"})
    for (pugi::xml_node c : child(net, list).children("Connection"))
      for (const char *end : {"Source", "Destination"})
        if (StringRef(c.attribute(end).value()).trim().empty())
          fail(src.locOf(c),
               "connection without a " + Twine(end) +
                   " (4diac writes one so where the block or port it "
                   "connects is missing: an error marker in the IDE)");
  for (pugi::xml_node fb : blocksOf(net))
    if (localName(fb) == "SubApp" && !fb.attribute("Type"))
      untypedSubApp(src, fb, owner);
  nameReturnOutputs(src, net);
  specializeGenericFunctions(src, net, owner);
  makeChannelEnds(src, net);
  for (pugi::xml_node fb : blocksOf(net)) {
    FbType *type = findType(fb.attribute("Type").value(), src.locOf(fb));
    checkPackage(fb, *type, src.locOf(fb));
    if (type->kind == TypeKind::Adapter)
      fail(src.locOf(fb), "'" + type->name +
                              "' is an adapter type, not a "
                              "function block type");
    collect(*type);
  }
  expandAdapterConnections(src, net, owner);
  for (auto &[source, conns] : eventsBySource(net, nullptr))
    if (size_t ways = relayWays(conns))
      collect(generatedType(fanOutType(ways), ""));
}

std::map<std::string, std::vector<pugi::xml_node>>
Translator::eventsBySource(pugi::xml_node net,
                           std::vector<std::string> *order) {
  std::map<std::string, std::vector<pugi::xml_node>> bySource;
  for (pugi::xml_node c :
       child(net, "EventConnections").children("Connection")) {
    std::string key = StringRef(c.attribute("Source").value()).upper();
    if (order && !bySource.count(key))
      order->push_back(key);
    bySource[key].push_back(c);
  }
  return bySource;
}

size_t Translator::relayWays(const std::vector<pugi::xml_node> &conns) const {
  if (semantics == "cyclic")
    return 0;
  if (conns.size() > 1)
    return conns.size();
  auto block = [](StringRef end) {
    auto [name, port] = end.split('.');
    return port.empty() ? StringRef() : name;
  };
  StringRef from = block(conns.front().attribute("Source").value());
  return !from.empty() && from.equals_insensitive(block(
                              conns.front().attribute("Destination").value()))
             ? 1
             : 0;
}

std::map<std::string, FbType *> Translator::blockTypes(XmlSource &src,
                                                       pugi::xml_node net) {
  std::map<std::string, FbType *> out;
  for (pugi::xml_node fb : blocksOf(net))
    if (fb.attribute("Type"))
      out[StringRef(fb.attribute("Name").value()).upper()] =
          findType(fb.attribute("Type").value(), src.locOf(fb));
  return out;
}

/// Each adapter connection `A.P -> B.S` (a plug to a socket of the same
/// adapter type) becomes one event or data connection per element of the
/// adapter, in the direction the element flows, added to the network's
/// connections before anything reads them.
void Translator::expandAdapterConnections(XmlSource &src, pugi::xml_node net,
                                          const FbType *owner) {
  pugi::xml_node list = child(net, "AdapterConnections");
  if (!list)
    return;
  std::map<std::string, FbType *> types = blockTypes(src, net);
  for (pugi::xml_node c : list.children("Connection")) {
    SMLoc at = src.locOf(c);
    // An end is a block's plug or socket (`b.P`), or one of the network's
    // own type (`S`): inside the network, the type's own socket is where
    // the adapter's plug-to-socket elements come in (it stands for the
    // plug outside), its own plug where they leave.
    struct End {
      std::string prefix; // "b." or "" for the network's own
      const AdapterUse *use;
      bool own;
    };
    auto end = [&](const char *attr) -> End {
      StringRef text = c.attribute(attr).value();
      auto [inst, name] = text.split('.');
      if (name.empty()) {
        const AdapterUse *a = owner ? owner->adapter(inst) : nullptr;
        if (!a)
          fail(at, Twine(attr) + " '" + text + "' names no plug or socket of " +
                       (owner ? "'" + owner->name + "'" : "the application"));
        return {"", a, true};
      }
      auto it = types.find(inst.upper());
      if (it == types.end())
        fail(at, Twine(attr) + " '" + text + "' names no function block");
      const AdapterUse *a = it->second->adapter(name);
      if (!a)
        fail(at, "'" + inst + "' (" + it->second->name +
                     ") has no plug or socket '" + name + "'");
      return {inst.str() + ".", a, false};
    };
    End from = end("Source"), to = end("Destination");
    // Plug-to-socket elements leave the source end and enter the
    // destination end: a block's plug or the network's own socket, then a
    // block's socket or the network's own plug.
    auto role = [](const End &e) {
      return e.own ? (e.use->isPlug ? "its own plug" : "its own socket")
                   : (e.use->isPlug ? "a plug" : "a socket");
    };
    if (from.use->isPlug == from.own || to.use->isPlug != to.own)
      fail(at, "an adapter connection goes from a plug (or the network's own "
               "socket) to a socket (or the network's own plug); '" +
                   from.use->name + "' is " + role(from) + ", '" +
                   to.use->name + "' " + role(to));
    if (from.use->type != to.use->type)
      fail(at, "'" + from.use->name + "' is a '" + from.use->type->name +
                   "' and '" + to.use->name + "' a '" + to.use->type->name +
                   "'");
    const AdapterUse *plug = from.use, *socket = to.use;
    auto add = [&](const char *kind, StringRef element, bool toSocket) {
      pugi::xml_node conns = child(net, kind);
      if (!conns)
        conns = net.append_child(kind);
      std::string p = from.prefix + adapterPort(plug->name, element),
                  s = to.prefix + adapterPort(socket->name, element);
      pugi::xml_node conn = conns.append_child("Connection");
      conn.append_attribute("Source") = (toSocket ? p : s).c_str();
      conn.append_attribute("Destination") = (toSocket ? s : p).c_str();
    };
    const FbType &a = *plug->type;
    for (const Event &e : a.eventOutputs)
      add("EventConnections", e.name, true);
    for (const Event &e : a.eventInputs)
      add("EventConnections", e.name, false);
    for (const Var &v : a.outputs)
      add("DataConnections", v.name, true);
    for (const Var &v : a.inputs)
      add("DataConnections", v.name, false);
  }
  net.remove_child(list);
}

/// A type netlift makes up (its text is kept in the SourceMgr so that its
/// locations print).
FbType &Translator::generatedType(const std::string &name,
                                  const std::string &text) {
  if (auto it = types.find(StringRef(name).upper()); it != types.end())
    return *it->second;
  std::string body = text;
  if (body.empty()) {
    // _FanOut<k>: EO1..EOk in order, one per step.
    size_t ways = std::stoul(name.substr(strlen("_FanOut")));
    body = "<FBType Name=\"" + name +
           "\">\n<InterfaceList>\n<EventInputs><Event Name=\"EI\"/>"
           "</EventInputs>\n<EventOutputs>";
    for (size_t i = 1; i <= ways; ++i)
      body += "<Event Name=\"EO" + std::to_string(i) + "\"/>";
    body += "</EventOutputs>\n</InterfaceList>\n<BasicFB><ECC>\n<ECState "
            "Name=\"START\"/>\n<ECState Name=\"FAN\">";
    for (size_t i = 1; i <= ways; ++i)
      body += "<ECAction Output=\"EO" + std::to_string(i) + "\"/>";
    body += "</ECState>\n<ECTransition Source=\"START\" Destination=\"FAN\" "
            "Condition=\"EI\"/>\n<ECTransition Source=\"FAN\" "
            "Destination=\"START\" Condition=\"1\"/>\n</ECC></BasicFB>\n"
            "</FBType>\n";
  }
  unsigned id = diag.sourceMgr().AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(body, "<netlift generated>/" + name +
                                                     ".fbt"),
      SMLoc());
  registerTypes(readFile(id), true);
  return *types.at(StringRef(name).upper());
}

std::string Translator::fanOutType(size_t ways) {
  return "_FanOut" + std::to_string(ways);
}

/// The queue of the environment's events for top type `t`: input E is
/// passed on as E_o in a later step. An event arriving while one waits is
/// not taken (the environment offers it again later), so the queue never
/// overflows and no order of arrivals and deliveries is lost.
std::string Translator::inputQueueType(const FbType &t) {
  std::string body = "<FBType Name=\"_Inputs_" + t.name +
                     "\">\n<InterfaceList>\n<EventInputs>";
  for (const Event &e : t.eventInputs)
    body += "<Event Name=\"" + e.name + "\"/>";
  body += "</EventInputs>\n<EventOutputs>";
  for (const Event &e : t.eventInputs)
    body += "<Event Name=\"" + e.name + "_o\"/>";
  body += "</EventOutputs>\n</InterfaceList>\n<BasicFB><ECC>\n<ECState "
          "Name=\"START\"/>\n";
  for (const Event &e : t.eventInputs)
    body += "<ECState Name=\"S_" + e.name + "\"><ECAction Output=\"" + e.name +
            "_o\"/></ECState>\n";
  for (const Event &e : t.eventInputs)
    body += "<ECTransition Source=\"START\" Destination=\"S_" + e.name +
            "\" Condition=\"" + e.name + "[_queued = 0]" +
            "\"/>\n<ECTransition Source=\"S_" + e.name +
            "\" Destination=\"START\" Condition=\"1\"/>\n";
  body += "</ECC></BasicFB>\n</FBType>\n";
  return body;
}
