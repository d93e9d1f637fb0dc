//===- PnmlFrontend.cpp - PNML place/transition nets into NetIR -----------===//
//
// Reads ISO/IEC 15909-2 PNML P/T nets (net type
// http://www.pnml.org/version-2009/grammar/ptnet), as used by the Model
// Checking Contest, into one NetIR system: every place becomes a place with
// its initial marking and unbounded capacity (P/T nets have no capacities),
// every transition a transition, every arc a weighted flow arc. Pages are
// merged. Anything that is not a plain P/T net — another net type (coloured,
// symmetric), inhibitor or other typed arcs, reference nodes, several nets —
// is refused with the location of the element.
//
// PNML ids may use characters NetIR names do not allow; such characters
// become '_', a leading digit gets a '_' prefix, reserved words get a '_'
// suffix, and a clash gets a numeric suffix. docs/formats.md states this.
//
//===----------------------------------------------------------------------===//
#include "frontends/FrontendRegistry.h"
#include "frontends/XmlSupport.h"

#include "ir/net/Builder.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"

#include <pugixml.hpp>

#include <algorithm>

using namespace netlift;
using namespace netlift::net;
using llvm::StringRef;

namespace {

constexpr const char *kPtNetType =
    "http://www.pnml.org/version-2009/grammar/ptnet";

class PnmlReader {
public:
  PnmlReader(unsigned bufferID, DiagEngine &diag, Design &design)
      : diag(diag), design(design), b(design) {
    buffer = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  }
  bool run();

private:
  llvm::SMLoc locOf(const pugi::xml_node &n) const {
    return XmlBuffer(buffer).locOf(n);
  }
  bool error(const pugi::xml_node &n, const llvm::Twine &msg) {
    diag.error(locOf(n), msg);
    return false;
  }
  std::string netliftName(StringRef id);
  bool collect(const pugi::xml_node &page);
  bool readInt(const pugi::xml_node &holder, const char *what, uint64_t &out,
               uint64_t dflt);

  DiagEngine &diag;
  Design &design;
  Builder b;
  StringRef buffer;
  llvm::StringSet<> usedNames;
  struct Node {
    bool isPlace;
    uint32_t index;
  };
  llvm::StringMap<Node> byId;
  std::vector<pugi::xml_node> arcs;
};

std::string PnmlReader::netliftName(StringRef id) {
  std::string n = toIdentifier(id);
  std::string unique = n;
  for (unsigned k = 2; !usedNames.insert(unique).second; ++k)
    unique = n + "_" + std::to_string(k);
  return unique;
}

bool PnmlReader::readInt(const pugi::xml_node &holder, const char *what,
                         uint64_t &out, uint64_t dflt) {
  pugi::xml_node text = holder.child(what).child("text");
  if (!holder.child(what)) {
    out = dflt;
    return true;
  }
  StringRef s = StringRef(text.child_value()).trim();
  if (s.getAsInteger(10, out))
    return error(holder.child(what),
                 llvm::Twine("expected a natural number in <") + what +
                     ">, found '" + s + "'");
  if (out >= kInf)
    return error(holder.child(what),
                 llvm::Twine("<") + what + "> value " + s + " is too large");
  return true;
}

bool PnmlReader::collect(const pugi::xml_node &page) {
  for (pugi::xml_node n : page.children()) {
    StringRef tag = n.name();
    if (tag == "page") {
      if (!collect(n))
        return false;
    } else if (tag == "place" || tag == "transition") {
      StringRef id = n.attribute("id").value();
      if (id.empty())
        return error(n, "<" + tag + "> without an id");
      if (byId.count(id))
        return error(n, "duplicate PNML id '" + id + "'");
      std::string name = netliftName(id);
      if (tag == "place") {
        uint64_t m;
        if (!readInt(n, "initialMarking", m, 0))
          return false;
        byId[id] = {true, b.addPlace(name, uint32_t(m), kInf, locOf(n))};
      } else {
        byId[id] = {false, b.addTransition(name, {}, {}, locOf(n))};
      }
    } else if (tag == "arc") {
      arcs.push_back(n);
    } else if (tag == "referencePlace" || tag == "referenceTransition") {
      return error(n, "<" + tag +
                          "> is not supported (reference nodes "
                          "across pages); flatten the net first");
    } else if (tag == "declaration") {
      return error(n, "<declaration> (sorts and variables of a coloured "
                      "net) is not part of a P/T net; netlift reads P/T "
                      "nets only");
    } else if (tag == "name" || tag == "graphics" || tag == "toolspecific") {
      // Presentation and tool metadata: no meaning for the net.
    } else {
      return error(n,
                   "unsupported PNML element <" + tag + "> in a P/T net page");
    }
  }
  return true;
}

bool PnmlReader::run() {
  pugi::xml_document doc;
  if (!XmlBuffer(buffer).parse(doc, diag))
    return false;
  pugi::xml_node root = doc.child("pnml");
  if (!root)
    return error(doc.first_child(), "not a PNML file: the root element is <" +
                                        llvm::Twine(doc.first_child().name()) +
                                        ">, expected <pnml>");
  pugi::xml_node net = root.child("net");
  if (!net)
    return error(root, "<pnml> holds no <net>");
  if (net.next_sibling("net"))
    return error(net.next_sibling("net"),
                 "several nets in one PNML file are not supported");
  StringRef type = net.attribute("type").value();
  if (type != kPtNetType)
    return error(net, "unsupported PNML net type '" + type +
                          "'; netlift reads P/T nets (" + kPtNetType + ")");
  std::string netName = netliftName(net.attribute("id").value());
  if (!b.createModule(netName, /*isSystem=*/true, locOf(net)))
    return error(net, "a module named '" + netName + "' exists already");
  if (!collect(net))
    return false;

  // Arcs, merged per (place, transition) pair in document order.
  Module *m = b.getModule();
  std::vector<std::vector<PreArc>> pre(m->transitions.size());
  std::vector<std::vector<PostArc>> post(m->transitions.size());
  for (const pugi::xml_node &a : arcs) {
    StringRef arcType = a.attribute("type").value();
    if (!arcType.empty() && arcType != "normal")
      return error(a, "'" + arcType + "' arcs are not part of P/T nets (arc '" +
                          a.attribute("id").value() + "')");
    StringRef src = a.attribute("source").value();
    StringRef dst = a.attribute("target").value();
    auto s = byId.find(src), d = byId.find(dst);
    if (s == byId.end())
      return error(a, "arc source '" + src + "' is not a place or transition");
    if (d == byId.end())
      return error(a, "arc target '" + dst + "' is not a place or transition");
    if (s->second.isPlace == d->second.isPlace)
      return error(a, "arc from '" + src + "' to '" + dst + "' joins two " +
                          (s->second.isPlace ? "places" : "transitions"));
    uint64_t w;
    if (!readInt(a, "inscription", w, 1))
      return false;
    if (w == 0)
      return error(a, "arc weight 0");
    // Several arcs between one place and one transition add up.
    auto merge = [&](auto &arcs, uint32_t place, auto fresh) {
      for (auto &x : arcs)
        if (x.place == place) {
          if (uint64_t(x.weight) + w >= kInf)
            return error(a, "the arcs between '" + src + "' and '" + dst +
                                "' add up to a weight too large");
          x.weight += uint32_t(w);
          return true;
        }
      arcs.push_back(fresh);
      return true;
    };
    bool ok = s->second.isPlace
                  ? merge(pre[d->second.index], s->second.index,
                          PreArc{s->second.index, uint32_t(w), {}})
                  : merge(post[s->second.index], d->second.index,
                          PostArc{d->second.index, uint32_t(w)});
    if (!ok)
      return false;
  }

  for (uint32_t t = 0; t < m->transitions.size(); ++t)
    m->transitions[t].setArcs(design.copy(llvm::ArrayRef<PreArc>(pre[t])),
                              design.copy(llvm::ArrayRef<PostArc>(post[t])));
  return true;
}

} // namespace

bool netlift::loadPnml(FrontendContext &, unsigned bufferID, DiagEngine &diag,
                       Design &design) {
  return PnmlReader(bufferID, diag, design).run();
}
