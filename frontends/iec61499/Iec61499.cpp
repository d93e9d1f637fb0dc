//===- Iec61499.cpp - IEC 61499 types and networks into NetIR -------------===//
//
// Reading (types by name from the inputs, the -I directories and the
// built-in library), basic FBs into event-driven PLC blocks (the ECC run to
// completion as statements), networks into modules of instances and
// connections, and the service FBs netlift ships models of. The execution
// model is documented in docs/iec61499.md. This file drives the parts
// (Iec61499Internal.h says which file holds which).
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

//===----------------------------------------------------------------------===//
// Driver
//===----------------------------------------------------------------------===//

bool Translator::run(const std::vector<unsigned> &ids,
                     std::vector<std::string> &pipelines) {
  std::set<std::string> before;
  for (auto &m : design.modules)
    before.insert(m->name.str());
  try {
    std::vector<FbType *> topList;
    for (unsigned id : ids) {
      File &f = readFile(id);
      registerTypes(f, false);
      pugi::xml_node root = f.doc->document_element();
      StringRef kind = localName(root);
      if (kind == "DataType" || kind == "AdapterType" || isPlatformType(kind) ||
          isDeclarationsOnly(kind))
        noteTypeOnlyFile(f);
      else if (kind != "System")
        topList.push_back(
            types[StringRef(root.attribute("Name").value()).upper()].get());
    }
    for (FbType *t : topList)
      tops.insert(t);
    for (auto &[file, sys] : systems)
      adoptResourceBlocks(*file->src, sys);
    for (FbType *t : topList)
      collect(*t);
    for (auto &[file, sys] : systems)
      for (pugi::xml_node app : sys.children("Application")) {
        pugi::xml_node net = child(app, "SubAppNetwork");
        if (!net)
          net = child(app, "FBNetwork");
        collectNetwork(*file->src, net, nullptr);
      }
    collectResourceStarts();
    // A resource's copy of a mapped block must have the block's type (its
    // own blocks were moved into an application by adoptResourceBlocks).
    for (auto &[file, sys] : systems) {
      std::map<std::string, std::string> mappedFrom = mappingsByTarget(sys);
      for (pugi::xml_node dev : sys.children("Device"))
        for (pugi::xml_node res : dev.children("Resource"))
          for (pugi::xml_node fb : blocksOf(child(res, "FBNetwork"))) {
            std::string path = std::string(dev.attribute("Name").value()) +
                               "." + res.attribute("Name").value() + "." +
                               fb.attribute("Name").value();
            auto from = mappedFrom.find(StringRef(path).upper());
            if (from != mappedFrom.end())
              checkMappedType(*file->src, sys, fb, from->second);
          }
    }

    // Basic FBs first: their lowering fixes the tick. The types of internal
    // FBs before those: their owners declare instances of them.
    for (FbType *t : internalOrder)
      if (t->kind == TypeKind::Basic)
        basicBlock(*t, /*asInternal=*/true);
      else
        internalEnvironmentPou(*t);
    for (FbType *t : order) {
      switch (t->kind) {
      case TypeKind::Basic:
        basicBlock(*t);
        break;
      case TypeKind::Service:
      case TypeKind::NoBody:
        if (isShipped(t->name))
          break;
        if (opaqueAsEnvironment) {
          environmentModule(*t);
          break;
        }
        fail(*t, t->root,
             (t->kind == TypeKind::Service ? "service interface FB '"
                                           : "FB type '") +
                 t->name +
                 "' has no body netlift can translate (its behaviour is "
                 "implemented in the runtime) and netlift ships no model "
                 "of it (--opaque=refuse; the default models it as "
                 "environment)");
      default:
        break;
      }
    }
    // Networks, collecting parameters.
    for (FbType *t : order)
      if (t->kind == TypeKind::Composite || t->kind == TypeKind::SubApp)
        network(*t);
    for (auto &[file, sys] : systems)
      for (pugi::xml_node app : sys.children("Application")) {
        pugi::xml_node net = child(app, "SubAppNetwork");
        if (!net)
          net = child(app, "FBNetwork");
        networkOf(app.attribute("Name").value(), *file->src, net, nullptr,
                  file->src->locOf(app));
        keepMapping(*file->src, sys, app);
        resourceConnections(*file->src, sys, app);
      }

    if (!st::addStandardLibrary(diag, unit) || !checkUnit(unit, diag))
      return false;
    LowerOptions opts;
    opts.opaqueRefused = !opaqueAsEnvironment; // the clock, in algorithms
    opts.extraTimesNs = parameterTimes;
    opts.timescaleNs = timescaleNs;
    if (!lowerEventDriven(unit, blocks, opts, diag, design))
      return false;
    if (!design.timescale) {
      net::Timescale ts;
      ts.amount = 1;
      ts.unit = "ms";
      design.timescale = ts;
    }
    int64_t tick = int64_t(design.timescale->nanoseconds());
    for (FbType *t : order)
      if (t->kind == TypeKind::Basic || t->kind == TypeKind::Composite ||
          t->kind == TypeKind::SubApp)
        continue;
      else if (t->name == "E_DELAY" || t->name == "E_RDELAY" ||
               t->name == "E_CYCLE")
        serviceModule(*t);
      else if (t->name == "E_RESTART")
        restartModule(*t);
    if (neverNeeded) {
      // An event output nothing emits: what unconnected inputs listen to.
      b.createModule("Never");
      uint32_t eo = b.addPort("EO", net::PortKind::Event, net::PortDir::Out);
      // Its emitter can never be enabled (no token), rather than missing,
      // which flatten would report for every input it drives.
      uint32_t off = b.addPlace("off");
      uint32_t t = b.addTransition("silent", {net::PreArc{off, 1, {}}},
                                   {net::PostArc{off, 1}});
      b.setEmits(t, {eo});
    }
    resolvePortTypes();
    aggregateConstantModules();
    for (auto &[name, c] : constants) {
      net::Module *m = b.createModule(name, false, c.loc);
      if (!m)
        fail(c.loc, "a module named '" + name + "' exists already");
      if (StringRef(c.type).equals_insensitive("BOOL")) {
        uint32_t p = b.addPort("OUT", net::PortKind::Cond, net::PortDir::Out,
                               nullptr, c.loc);
        m->ports[p].definition = b.boolLit(c.value->intValue != 0, c.loc);
        continue;
      }
      if (c.value->kind == ExprKind::RealLit ||
          c.value->kind == ExprKind::StringLit) {
        uint32_t p = b.addPort("OUT", net::PortKind::Data, net::PortDir::Out,
                               dataType(c.type, c.loc), c.loc);
        if (c.value->kind == ExprKind::RealLit) {
          m->ports[p].definition = b.realLit(c.value->realValue, c.loc);
          continue;
        }
        std::u16string chars;
        if (auto err = plc::decodeStringLiteral(c.value->name, chars))
          fail(c.loc, *err);
        m->ports[p].definition = b.stringLit(
            llvm::ArrayRef<char16_t>(chars.data(), chars.size()), c.loc);
        continue;
      }
      int64_t v = c.value->intValue;
      if (c.value->kind == ExprKind::TimeLit) {
        if (v % tick)
          fail(c.loc, "duration is not a whole number of ticks (one tick is " +
                          design.timescale->str() + "; choose --timescale)");
        v /= tick;
      }
      uint32_t p = b.addPort("OUT", net::PortKind::Data, net::PortDir::Out,
                             dataType(c.type, c.loc), c.loc);
      m->ports[p].definition = b.intLit(v, c.loc);
    }
    // What the frontend generated (queues, internal copies, fan-outs,
    // start blocks) has '_' names; the environment's places model a
    // runtime, not the user's blocks. Traces hide both by default.
    for (auto &m : design.modules) {
      if (before.count(m->name.str()))
        continue;
      auto mark = [&](StringRef name, StringRef why) {
        m->attributes.push_back({design.save(name), net::kInternalAttribute,
                                 design.save(why), m->loc});
      };
      for (const net::Var &v : m->vars)
        if (net::hasGeneratedComponent(v.name))
          mark(v.name, "generated by the IEC 61499 frontend");
      for (const net::Port &p : m->ports)
        if (net::hasGeneratedComponent(p.name))
          mark(p.name, "generated by the IEC 61499 frontend");
      for (const net::Instance &i : m->instances)
        if (net::hasGeneratedComponent(i.name))
          mark(i.name, "generated by the IEC 61499 frontend");
      if (environmentModules.count(m->name.str()))
        for (const net::Place &p : m->places)
          mark(p.name, "state of the environment's model");
    }
    if ((semantics == "forte" || semantics == "cyclic") &&
        (!topList.empty() || !systems.empty())) {
      // Each resource (a translated type or an application) becomes one
      // flat module with one FIFO of events (or one cycle of its blocks);
      // the modules it was built from go (passes/Iec61499Resources.cpp).
      std::string resources, built;
      auto add = [](std::string &list, llvm::StringRef name) {
        list += (list.empty() ? "" : ",") + name.str();
      };
      for (FbType *t : topList)
        add(resources, net::toIdentifier(t->name));
      for (auto &[file, sys] : systems)
        for (pugi::xml_node app : sys.children("Application"))
          add(resources, net::toIdentifier(app.attribute("Name").value()));
      for (auto &m : design.modules)
        if (!before.count(m->name.str()))
          add(built, m->name);
      pipelines.push_back("iec61499-resources{model=" + semantics +
                          ",modules=" + resources +
                          (built.empty() ? "" : ",built=" + built) + "}");
    }
  } catch (Failure &) {
    return false;
  }
  return !diag.hadError();
}

bool iec61499::translate(const std::vector<unsigned> &ids,
                         const Options &options, DiagEngine &diag,
                         net::Design &design,
                         std::vector<std::string> &pipelines) {
  if (options.semantics != "forte" && options.semantics != "sequential" &&
      options.semantics != "cyclic") {
    diag.error(SMLoc(), "unknown IEC 61499 execution model '" +
                            options.semantics +
                            "' (--fb-semantics forte, sequential or cyclic)");
    return false;
  }
  Translator t(diag, design, options);
  return t.run(ids, pipelines);
}
