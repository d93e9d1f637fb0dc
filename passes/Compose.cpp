//===- Compose.cpp - closed-loop composition of modules -------------------===//
//
// `compose` creates `system NAME { inst ...; connect ...; }` over the chosen
// components. Connections from the file come first, in file order; then, if
// name matching is on, every input still undriven is connected to the one
// output of that name among the other components. The verifier then checks
// the system as it checks any hand-written one, so kind and type errors of
// file connections point into the connection file. Name matching checks
// kinds and types itself, because a clash there has no line to point to.
//
// Preserved: every component's behaviour; composition only adds wires. A
// cond/data input has one driver; several event outputs of the same name
// are not merged by guesswork (an error asks for the connection file).
//
//===----------------------------------------------------------------------===//
#include "passes/Compose.h"

#include "ir/net/Builder.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"
#include "ir/net/Types.h"
#include "ir/net/Verifier.h"

#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/Path.h"

using namespace netlift;
using namespace netlift::net;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

struct Component {
  std::string name;
  Module *mod;
};

/// A wire in the order it was made and why, for the report.
struct Wire {
  Endpoint from, to;
  std::string origin; // "file:line" or "by name"
};

class Composer {
public:
  Composer(Design &d, DiagEngine &diag, const ComposeOptions &opts)
      : d(d), diag(diag), opts(opts) {}
  bool run(llvm::raw_ostream *report, Statistics &stats);

private:
  bool chooseComponents();
  bool readConnectionFile();
  bool matchByName();
  bool reportUnconnected(bool match, size_t byName) const;
  const Component *component(StringRef name) const {
    for (const Component &c : comps)
      if (c.name == name)
        return &c;
    return nullptr;
  }
  std::string componentList() const {
    std::string s;
    for (const Component &c : comps)
      s += (s.empty() ? "" : ", ") + c.name;
    return s;
  }
  static std::string endName(const Endpoint &e) {
    return (e.instance + "." + e.port).str();
  }
  void writeReport(llvm::raw_ostream &os) const;

  Design &d;
  DiagEngine &diag;
  const ComposeOptions &opts;
  std::vector<Component> comps;
  std::vector<Wire> wires;
};

bool Composer::chooseComponents() {
  if (!opts.instances.empty()) {
    for (const std::string &spec : opts.instances) {
      auto [name, modName] = StringRef(spec).split(':');
      if (modName.empty())
        std::swap(name, modName);
      name = name.trim();
      modName = modName.trim();
      Module *m = d.lookupModule(modName);
      if (!m) {
        diag.error(SMLoc(),
                   "compose: no module named '" + modName + "' to instantiate");
        return false;
      }
      comps.push_back({name.empty() ? modName.lower() : name.str(), m});
    }
  } else {
    // Modules instantiated by a system are still candidates: a library
    // file may come with a test system of its own.
    llvm::DenseSet<StringRef> instantiated;
    for (auto &m : d.modules)
      if (!m->isSystem)
        for (const Instance &i : m->instances)
          instantiated.insert(i.moduleName);
    for (auto &m : d.modules)
      if (!m->isSystem && !instantiated.count(m->name))
        comps.push_back({m->name.lower(), m.get()});
  }
  llvm::StringSet<> seen;
  for (const Component &c : comps) {
    if (c.mod->isSystem) {
      diag.error(c.mod->loc, "compose: '" + c.mod->name +
                                 "' is a system and cannot be a component");
      return false;
    }
    if (!isIdentifier(c.name)) {
      diag.error(SMLoc(), "compose: '" + c.name +
                              "' is not a valid instance name (letters, "
                              "digits and '_', not a reserved word; give one "
                              "with inst=NAME:" +
                              c.mod->name + ")");
      return false;
    }
    if (!seen.insert(c.name).second) {
      diag.error(SMLoc(), "compose: two components named '" + c.name +
                              "'; name them with inst=NAME:MODULE,...");
      return false;
    }
  }
  if (comps.size() < 2) {
    diag.error(SMLoc(),
               "compose: needs at least two components, found " +
                   llvm::Twine(comps.size()) +
                   (comps.empty() ? "" : " ('" + comps[0].name + "')") +
                   "; list them with inst=NAME:MODULE,...");
    return false;
  }
  return true;
}

bool Composer::readConnectionFile() {
  if (opts.connectFile.empty())
    return true;
  llvm::SourceMgr &sm = diag.sourceMgr();
  unsigned id = addInputFile(sm, opts.connectFile);
  if (!id)
    return false;
  StringRef text = sm.getMemoryBuffer(id)->getBuffer();
  bool ok = true;
  unsigned lineNo = 0;
  while (!text.empty()) {
    auto [line, rest] = text.split('\n');
    text = rest;
    ++lineNo;
    StringRef body = line;
    size_t cut = std::min(body.find("//"), body.find('#'));
    body = body.take_front(cut).rtrim();
    StringRef lead = body.ltrim();
    if (lead.empty())
      continue;
    if (!lead.contains("->")) {
      diag.error(SMLoc::getFromPointer(lead.data()),
                 "expected 'instance.port -> instance.port'");
      ok = false;
      continue;
    }
    Endpoint ends[2];
    auto [lhs, rhs] = lead.split("->");
    StringRef parts[2] = {lhs, rhs};
    bool lineOk = true;
    for (int k = 0; k < 2 && lineOk; ++k) {
      StringRef p = parts[k].trim();
      SMLoc at = SMLoc::getFromPointer(p.empty() ? parts[k].data() : p.data());
      auto [inst, port] = p.split('.');
      if (p.empty() || port.empty() ||
          p.find_first_of(" \t") != StringRef::npos) {
        diag.error(at, "expected 'instance.port' " +
                           llvm::Twine(k == 0 ? "before" : "after") + " '->'");
        lineOk = false;
        break;
      }
      const Component *c = component(inst);
      if (!c) {
        diag.error(at, "no component named '" + inst +
                           "' (components: " + componentList() + ")");
        lineOk = false;
        break;
      }
      ends[k] = {inst, port, at};
    }
    if (!lineOk) {
      ok = false;
      continue;
    }
    wires.push_back({ends[0], ends[1],
                     (llvm::sys::path::filename(opts.connectFile) + ":" +
                      llvm::Twine(lineNo))
                         .str()});
  }
  return ok;
}

bool Composer::matchByName() {
  llvm::StringSet<> driven;
  for (const Wire &w : wires)
    driven.insert(endName(w.to));
  bool ok = true;
  for (const Component &in : comps) {
    for (const Port &q : in.mod->ports) {
      if (!q.isInput() || driven.count(in.name + "." + q.name.str()))
        continue;
      std::vector<std::pair<const Component *, const Port *>> found;
      for (const Component &out : comps) {
        if (&out == &in)
          continue;
        int p = out.mod->findPort(q.name);
        if (p >= 0 && out.mod->ports[p].isOutput())
          found.push_back({&out, &out.mod->ports[p]});
      }
      if (found.empty())
        continue;
      std::string target = in.name + "." + q.name.str();
      if (found.size() > 1) {
        diag.error(q.loc, "compose: input '" + target +
                              "' matches outputs of the same name in '" +
                              found[0].first->name + "' and '" +
                              found[1].first->name +
                              "'; say which drives it in a connection file");
        ok = false;
        continue;
      }
      auto [src, p] = found[0];
      std::string from = src->name + "." + p->name.str();
      if (p->kind != q.kind) {
        diag.error(q.loc, "compose: '" + from + "' (" + spelling(p->kind) +
                              " output) and '" + target + "' (" +
                              spelling(q.kind) +
                              " input) have the same name but different "
                              "kinds; a connection file may wire them to "
                              "other ports");
        ok = false;
        continue;
      }
      if (p->kind == PortKind::Data && p->type != q.type) {
        diag.error(q.loc, "compose: '" + from + "' of type '" + p->type->str() +
                              "' and '" + target + "' of type '" +
                              q.type->str() +
                              "' have the same name but different types");
        ok = false;
        continue;
      }
      wires.push_back({{d.save(src->name), p->name, SMLoc()},
                       {d.save(in.name), q.name, SMLoc()},
                       "by name"});
    }
  }
  return ok;
}

/// A composition that wired nothing by name is almost always a mistake
/// (ports named differently, a forgotten connection file): the components
/// would run side by side with every input free. With --match names asked
/// for, it is an error; by default, without a connection file, a warning
/// naming the unconnected ports.
bool Composer::reportUnconnected(bool match, size_t byName) const {
  if (!match || byName > 0 || comps.size() < 2)
    return true;
  bool asked = opts.matchNames.value_or(false);
  if (!asked && !wires.empty())
    return true;
  std::string inputs, outputs;
  unsigned numInputs = 0, numOutputs = 0;
  llvm::StringSet<> driven;
  for (const Wire &w : wires)
    driven.insert(endName(w.to));
  auto add = [](std::string &list, unsigned &n, const std::string &name) {
    if (n++ < 8)
      list += (list.empty() ? "'" : ", '") + name + "'";
    else if (n == 9)
      list += ", ...";
  };
  for (const Component &c : comps)
    for (const Port &p : c.mod->ports) {
      std::string n = c.name + "." + p.name.str();
      if (p.isInput() && !driven.count(n))
        add(inputs, numInputs, n);
      else if (p.isOutput())
        add(outputs, numOutputs, n);
    }
  std::string msg =
      "compose: no input of " + componentList() +
      " has the name of another component's output, so matching by name "
      "connected nothing; unconnected inputs (" +
      std::to_string(numInputs) + "): " + (inputs.empty() ? "none" : inputs) +
      "; outputs (" + std::to_string(numOutputs) +
      "): " + (outputs.empty() ? "none" : outputs) +
      "; wire them with a connection file (connect=FILE, --connect FILE)";
  if (asked) {
    diag.error(SMLoc(), msg);
    return false;
  }
  diag.warning(SMLoc(), msg + "; the components run side by side, every "
                              "input free");
  return true;
}

void Composer::writeReport(llvm::raw_ostream &os) const {
  os << "system " << opts.systemName << "\n";
  for (const Component &c : comps)
    os << "  inst " << c.name << " : " << c.mod->name << "\n";
  for (const Wire &w : wires)
    os << llvm::formatv("  connect {0} -> {1}", endName(w.from), endName(w.to))
       << "  (" << w.origin << ")\n";
  llvm::StringSet<> driven, used;
  for (const Wire &w : wires) {
    driven.insert(endName(w.to));
    used.insert(endName(w.from));
  }
  unsigned free = 0, unused = 0;
  for (const Component &c : comps)
    for (const Port &p : c.mod->ports) {
      std::string n = c.name + "." + p.name.str();
      if (p.isInput() && !driven.count(n)) {
        os << "  free input " << n << " (" << spelling(p.kind) << ")\n";
        ++free;
      } else if (p.isOutput() && !used.count(n)) {
        os << "  unused output " << n << " (" << spelling(p.kind) << ")\n";
        ++unused;
      }
    }
  os << llvm::formatv("  {0} connections, {1} free inputs, {2} unused "
                      "outputs\n",
                      wires.size(), free, unused);
}

bool Composer::run(llvm::raw_ostream *report, Statistics &stats) {
  if (d.lookupModule(opts.systemName)) {
    diag.error(SMLoc(), "compose: a module named '" + opts.systemName +
                            "' exists already; choose the system's name "
                            "with name=NAME");
    return false;
  }
  if (!chooseComponents() || !readConnectionFile())
    return false;
  bool match = opts.matchNames.value_or(opts.connectFile.empty());
  size_t fromFile = wires.size();
  if (match && !matchByName())
    return false;
  if (!reportUnconnected(match, wires.size() - fromFile))
    return false;
  Builder b(d);
  b.createModule(opts.systemName, /*isSystem=*/true);
  for (const Component &c : comps)
    b.addInstance(c.name, c.mod->name);
  for (const Wire &w : wires)
    b.addConnection(w.from, w.to, w.from.loc);
  if (!verifyDesign(d, diag))
    return false;
  if (report)
    writeReport(*report);
  stats.add("compose", "components", comps.size(), "components instantiated");
  stats.add("compose", "connections", wires.size(), "connections made");
  return true;
}

class ComposePass : public Pass {
public:
  explicit ComposePass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &design, DiagEngine &diag, Statistics &stats) override {
    ComposeOptions co;
    ReportStream report;
    return parseComposeOptions(opts, diag, co) &&
           report.open(opts, "compose", diag) &&
           composeSystem(design, diag, co, report.get(), stats);
  }

private:
  PassOptions opts;
};

} // namespace

bool netlift::composeSystem(Design &design, DiagEngine &diag,
                            const ComposeOptions &opts,
                            llvm::raw_ostream *report, Statistics &stats) {
  return Composer(design, diag, opts).run(report, stats);
}

bool netlift::parseComposeOptions(const PassOptions &opts, DiagEngine &,
                                  ComposeOptions &out) {
  out.instances = opts.list("inst");
  out.connectFile = opts.text("connect");
  if (opts.has("name"))
    out.systemName = opts.text("name");
  if (opts.has("match"))
    out.matchNames = opts.text("match") == "names";
  return true;
}

namespace netlift {
std::unique_ptr<Pass> createComposePass(const PassOptions &opts) {
  return std::make_unique<ComposePass>(opts);
}
} // namespace netlift
