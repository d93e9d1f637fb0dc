//===- PnmlWriter.cpp - flat modules as PNML place/transition nets --------===//
#include "backends/checkers/PnmlWriter.h"

#include "backends/checkers/PtSubset.h"
#include "ir/support/XmlEscape.h"

#include <set>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;

bool checkers::writePnml(const Module &m, DiagEngine &diag,
                         llvm::raw_ostream &os) {
  if (!refuseBeyondPt(m, "PNML", diag))
    return false;
  auto text = [&](llvm::StringRef tag, const std::string &value) {
    os << "<" << tag << "><text>" << xmlEscape(value) << "</text></" << tag
       << ">";
  };
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<pnml xmlns=\"http://www.pnml.org/version-2009/grammar/pnml\">\n"
        "<net id=\""
     << xmlEscape(m.name)
     << "\" type=\"http://www.pnml.org/version-2009/grammar/ptnet\">\n";
  text("name", m.name.str());
  // Ids are the NetIR names (what netlift's PNML reader names the nodes
  // after), made unique across nodes and arcs by trailing underscores.
  std::set<std::string> used{"page0"};
  auto unique = [&](std::string id) {
    while (!used.insert(id).second)
      id += "_";
    return id;
  };
  std::vector<std::string> placeId(m.places.size()), capId(m.places.size());
  for (uint32_t p = 0; p < m.places.size(); ++p)
    placeId[p] = unique(m.places[p].name.str());
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (m.places[p].capacity != kInf)
      capId[p] = unique(m.places[p].name.str() + "_cap");
  std::vector<std::string> transId;
  for (const Transition &t : m.transitions)
    transId.push_back(unique(t.name.str()));
  os << "\n<page id=\"page0\">\n";
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    const Place &pl = m.places[p];
    os << "<place id=\"" << xmlEscape(placeId[p]) << "\">";
    text("name", pl.name.str());
    if (pl.tokens)
      text("initialMarking", std::to_string(pl.tokens));
    os << "</place>\n";
    if (pl.capacity != kInf) {
      os << "<place id=\"" << xmlEscape(capId[p]) << "\">";
      text("name", pl.name.str() + "_cap");
      if (pl.capacity - pl.tokens)
        text("initialMarking", std::to_string(pl.capacity - pl.tokens));
      os << "</place>\n";
    }
  }
  uint32_t arcs = 0;
  auto arc = [&](const std::string &from, const std::string &to,
                 int64_t weight) {
    os << "<arc id=\"" << xmlEscape(unique("a" + std::to_string(arcs++)))
       << "\" source=\"" << xmlEscape(from) << "\" target=\"" << xmlEscape(to)
       << "\">";
    if (weight != 1)
      text("inscription", std::to_string(weight));
    os << "</arc>\n";
  };
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    const Transition &tr = m.transitions[t];
    const std::string &id = transId[t];
    os << "<transition id=\"" << xmlEscape(id) << "\">";
    text("name", tr.name.str());
    os << "</transition>\n";
    for (const PlaceEffect &e : placeEffects(tr)) {
      const std::string &p = placeId[e.place];
      if (e.pre)
        arc(p, id, e.pre);
      if (e.post)
        arc(id, p, e.post);
      // The complement pays for the net growth and is refilled by the net
      // shrinkage, so m + complement = capacity stays invariant.
      if (m.places[e.place].capacity != kInf && e.pre != e.post) {
        const std::string &c = capId[e.place];
        if (e.post > e.pre)
          arc(c, id, e.post - e.pre);
        else
          arc(id, c, e.pre - e.post);
      }
    }
  }
  os << "</page>\n</net>\n</pnml>\n";
  return true;
}
