//===- NcesXml.cpp - flat modules for NCES tools (ViVe XML, .pnt) ---------===//
#include "backends/nces/NcesXml.h"
#include "backends/checkers/PtSubset.h"
#include "ir/net/Printer.h"
#include "ir/support/OutputFile.h"
#include "ir/support/XmlEscape.h"

#include "llvm/Support/Casting.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

#include <functional>
#include <set>

#include <string>
#include <vector>

using namespace netlift;
using namespace netlift::net;

namespace {
/// The place or condition port a signal expression names, as the NCES
/// element an arc starts from; empty when it is an expression.
std::string signalSource(const Module &m, const Expr *e) {
  auto *r = llvm::dyn_cast<Ref>(e);
  if (!r || !r->fields.empty())
    return "";
  if (r->sym.kind == SymKind::Place)
    return m.places[r->sym.index].name.str();
  if (r->sym.kind == SymKind::Port &&
      m.ports[r->sym.index].kind == PortKind::Cond &&
      m.ports[r->sym.index].isInput())
    return m.ports[r->sym.index].name.str();
  return "";
}

bool refuse(DiagEngine &diag, llvm::SMLoc loc, const std::string &what,
            const char *hint) {
  diag.error(loc, what + " cannot be written as NCES: " + hint);
  return false;
}

const char *kNoData = "NCES has no data; run the lower-data pass first "
                      "(netlift opt -p 'flatten,lower-data')";
const char *kSignal = "an NCES condition arc starts at a place or a "
                      "condition input, not at an expression";

/// The XML declaration, the FBType element and its InterfaceList: event
/// ports as events, condition ports as BOOL variables.
void writeHeader(const Module &m, llvm::raw_ostream &os) {
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
     << "<!-- Module '" << xmlEscape(m.name)
     << "' as ViVe NCES XML (netlift emit --to nces-xml) -->\n"
     << "<FBType Name=\"" << xmlEscape(m.name) << "\">\n"
     << "  <InterfaceList>\n";
  auto section = [&](const char *tag, const char *item, PortKind kind,
                     bool input) {
    bool any = false;
    for (const Port &p : m.ports)
      if (p.kind == kind && p.isInput() == input) {
        if (!any)
          os << "    <" << tag << ">\n";
        any = true;
        os << "      <" << item << " Name=\"" << xmlEscape(p.name) << "\""
           << (kind == PortKind::Cond ? " Type=\"BOOL\"" : "") << "/>\n";
      }
    if (any)
      os << "    </" << tag << ">\n";
  };
  section("EventInputs", "Event", PortKind::Event, true);
  section("EventOutputs", "Event", PortKind::Event, false);
  section("InputVars", "VarDeclaration", PortKind::Cond, true);
  section("OutputVars", "VarDeclaration", PortKind::Cond, false);
  os << "  </InterfaceList>\n";
}
/// The hint for data NCES cannot hold: lower-data when it can lower all of
/// the module's data (Boolean only), else the exports that keep data, so
/// that following the hint leads somewhere.
std::string noDataHint(const Module &m) {
  auto notBool = [](const Type *t) { return t && t->kind != TypeKind::Bool; };
  for (const Var &v : m.vars)
    if (notBool(v.type))
      return "NCES has no data, and lower-data turns only Boolean data into "
             "places (variable '" +
             v.name.str() + "' is " + v.type->str() +
             "); write this model with --to smv or --to promela, which keep "
             "its data";
  for (const Port &p : m.ports)
    if (p.kind == PortKind::Data && notBool(p.type))
      return "NCES has no data, and lower-data turns only Boolean data into "
             "places (port '" +
             p.name.str() + "' is " + p.type->str() +
             "); write this model with --to smv or --to promela, which keep "
             "its data";
  return kNoData;
}

} // namespace

bool nces::writeNcesXml(const Module &m, DiagEngine &diag,
                        llvm::raw_ostream &os) {
  std::string noData = noDataHint(m);
  for (const Var &v : m.vars)
    return refuse(diag, v.loc, "variable '" + v.name.str() + "'",
                  noData.c_str());
  for (const Port &p : m.ports) {
    if (p.kind == PortKind::Data)
      return refuse(diag, p.loc, "data port '" + p.name.str() + "'",
                    noData.c_str());
    if (p.isStored())
      return refuse(diag, p.loc, "stored output '" + p.name.str() + "'",
                    noData.c_str());
    if (p.definition && signalSource(m, p.definition).empty())
      return refuse(diag, p.definitionLoc,
                    "output '" + p.name.str() +
                        "' = " + exprToString(p.definition),
                    kSignal);
  }
  for (const Transition &t : m.transitions) {
    if (t.guard() || t.hasAction())
      return refuse(diag, t.loc,
                    "transition '" + t.name.str() + "' with " +
                        (t.guard() ? "a guard" : "an action"),
                    noData.c_str());
    for (const Expr *c : t.conds())
      if (signalSource(m, c).empty())
        return refuse(diag, c->loc,
                      "condition '" + exprToString(c) + "' of transition '" +
                          t.name.str() + "'",
                      kSignal);
    for (const PreArc &a : t.pre())
      if (a.time.deadline)
        return refuse(diag, t.loc,
                      "the deadline on the arc from '" +
                          m.places[a.place].name.str() + "' to '" +
                          t.name.str() + "'",
                      "NCES time intervals are weak (a token may stay past "
                      "the upper bound); explore it with `netlift reach`");
  }

  writeHeader(m, os);
  os << "  <SNS>\n";
  // Layout: places in a row, transitions in the row below, so that a
  // drawing tool shows something legible before the user arranges it.
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    const Place &pl = m.places[p];
    os << "    <place Name=\"" << xmlEscape(pl.name) << "\" Num=\"" << p
       << "\" Mark=\"" << pl.tokens << "\" Clock=\"0\" Capacity=\""
       << (pl.capacity == kInf ? std::string("-1")
                               : std::to_string(pl.capacity))
       << "\" X=\"" << 100 * p << "\" Y=\"0\"/>\n";
  }
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    const Transition &t = m.transitions[ti];
    os << "    <trans Name=\"" << xmlEscape(t.name) << "\" Type=\""
       << (t.mode == EventMode::And ? "AND" : "OR") << "\" SwitchMode=\""
       << (t.urgent ? "urgent" : "normal") << "\" X=\"" << 100 * ti
       << "\" Y=\"100\"/>\n";
  }
  auto arc = [&](const char *tag, llvm::StringRef from, llvm::StringRef to,
                 uint32_t weight, const std::string &extra) {
    os << "    <" << tag << " StartPoint=\"" << xmlEscape(from)
       << "\" EndPoint=\"" << xmlEscape(to) << "\" ArcWeight=\"" << weight
       << "\"" << extra << "/>\n";
  };
  for (const Transition &t : m.transitions) {
    for (const PreArc &a : t.pre())
      arc("arc", m.places[a.place].name, t.name, a.weight,
          a.time.isTrivial()
              ? std::string()
              : " TimeValue=\"" + std::to_string(a.time.lo) + ";" +
                    (a.time.hi == kInf ? std::string("-2")
                                       : std::to_string(a.time.hi)) +
                    "\"");
    for (const PostArc &a : t.post())
      arc("arc", t.name, m.places[a.place].name, a.weight, "");
    for (const Expr *c : t.conds())
      arc("condarc", signalSource(m, c), t.name, 1, "");
    for (const EventSource &e : t.events())
      arc("evarc",
          e.fromPort ? m.ports[e.index].name : m.transitions[e.index].name,
          t.name, 1, "");
    for (uint32_t port : t.emits())
      arc("evarc", t.name, m.ports[port].name, 1, "");
  }
  for (const Port &p : m.ports)
    if (p.definition)
      arc("condarc", signalSource(m, p.definition), p.name, 1, "");
  os << "  </SNS>\n</FBType>\n";
  return true;
}

bool nces::writePnt(const Module &m, DiagEngine &diag, llvm::raw_ostream &os) {
  if (!checkers::refuseBeyondPt(m, ".pnt", diag))
    return false;
  // Per place: the transitions that put tokens in (PRE) and take them out
  // (POST), `t:w` where the weight is not 1.
  std::vector<std::string> pre(m.places.size()), post(m.places.size());
  auto add = [](std::string &list, uint32_t t, uint32_t w) {
    list += " " + std::to_string(t) + (w == 1 ? "" : ":" + std::to_string(w));
  };
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    for (const PostArc &a : m.transitions[ti].post())
      add(pre[a.place], ti, a.weight);
    for (const PreArc &a : m.transitions[ti].pre())
      add(post[a.place], ti, a.weight);
  }
  os << "P   M   PRE,POST  NETZ 0:" << m.name << "\n";
  for (uint32_t p = 0; p < m.places.size(); ++p)
    os << p << " " << m.places[p].tokens << "  " << pre[p] << "," << post[p]
       << "\n";
  os << "@\nplace nr.             name capacity time\n";
  for (uint32_t p = 0; p < m.places.size(); ++p)
    os << "     " << p << ": " << m.places[p].name << "   "
       << (m.places[p].capacity == kInf ? std::string("oo")
                                        : std::to_string(m.places[p].capacity))
       << "    0\n";
  os << "@\ntrans nr.             name priority time\n";
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    os << "     " << t << ": " << m.transitions[t].name << "   "
       << (m.transitions[t].urgent ? 1 : 0) << "    0\n";
  os << "@\n";
  return true;
}

bool nces::writeNcesComposite(const Module &m, DiagEngine &diag,
                              llvm::raw_ostream &os) {
  if (!m.places.empty() || !m.transitions.empty() || !m.vars.empty())
    return refuse(diag, m.loc,
                  "module '" + m.name.str() +
                      "' with both instances and a net of its own",
                  "an NCES module is either basic (a net) or composite "
                  "(instances and connections); move its own net into a "
                  "module it instantiates");
  for (const Port &p : m.ports) {
    if (p.kind == PortKind::Data)
      return refuse(diag, p.loc, "data port '" + p.name.str() + "'", kNoData);
    if (p.definition)
      return refuse(diag, p.definitionLoc,
                    "output '" + p.name.str() +
                        "' = " + exprToString(p.definition),
                    "a composite NCES module's outputs are connected, not "
                    "defined");
  }
  // A connection carries what its (verified) source port is: events or
  // conditions, as data ports are refused with the modules that have them.
  auto sourceIsEvent = [&](const Connection &c) {
    const Module *owner = &m;
    for (const Instance &i : m.instances)
      if (i.name == c.from.instance)
        owner = i.module;
    return owner->ports[owner->findPort(c.from.port)].kind == PortKind::Event;
  };
  std::string events, conditions;
  auto endpoint = [](const Endpoint &e) {
    return xmlEscape(e.instance.empty()
                         ? e.port.str()
                         : e.instance.str() + "." + e.port.str());
  };
  for (const Connection &c : m.connections) {
    (sourceIsEvent(c) ? events : conditions) +=
        "      <Connection Source=\"" + endpoint(c.from) + "\" Destination=\"" +
        endpoint(c.to) + "\"/>\n";
  }
  writeHeader(m, os);
  os << "  <FBNetwork>\n";
  for (uint32_t i = 0; i < m.instances.size(); ++i)
    os << "    <FB Name=\"" << xmlEscape(m.instances[i].name) << "\" Type=\""
       << xmlEscape(m.instances[i].moduleName) << "\" X=\"" << 300 * i
       << "\" Y=\"0\"/>\n";
  if (!events.empty())
    os << "    <EventConnections>\n" << events << "    </EventConnections>\n";
  if (!conditions.empty())
    os << "    <DataConnections>\n" << conditions << "    </DataConnections>\n";
  os << "  </FBNetwork>\n</FBType>\n";
  return true;
}

bool nces::writeNcesModules(const Module &top, llvm::StringRef dir,
                            DiagEngine &diag) {
  std::vector<std::pair<std::string, std::string>> files; // name, text
  std::set<const Module *> done;
  std::function<bool(const Module &)> build = [&](const Module &m) -> bool {
    if (!done.insert(&m).second)
      return true;
    for (const Instance &i : m.instances)
      if (!build(*i.module))
        return false;
    std::string text;
    llvm::raw_string_ostream buf(text);
    if (m.instances.empty() ? !writeNcesXml(m, diag, buf)
                            : !writeNcesComposite(m, diag, buf))
      return false;
    files.push_back({m.name.str() + ".xml", buf.str()});
    return true;
  };
  if (!build(top))
    return false;
  if (std::error_code ec = llvm::sys::fs::create_directories(dir)) {
    diag.error(llvm::SMLoc(), "cannot create '" + dir + "': " + ec.message());
    return false;
  }
  for (const auto &[name, text] : files) {
    llvm::SmallString<128> path(dir);
    llvm::sys::path::append(path, name);
    if (!writeOutputFile(
            path, [&](llvm::raw_ostream &os) { os << text; }, diag))
      return false;
  }
  return true;
}

bool nces::writeNcesModules(const Design &design, llvm::StringRef topName,
                            llvm::StringRef dir, DiagEngine &diag) {
  std::string why;
  Module *top = design.findTop(topName, why);
  if (!top) {
    diag.error(llvm::SMLoc(), "emit: " + why);
    return false;
  }
  return writeNcesModules(*top, dir, diag);
}
