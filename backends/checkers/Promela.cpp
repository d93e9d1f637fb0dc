//===- Promela.cpp - flat modules as Promela models for spin --------------===//
#include "backends/checkers/Promela.h"
#include "backends/checkers/PtSubset.h"

#include <string>
#include <vector>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;

namespace {
/// A Promela identifier for place `i`: its index keeps names unique, the
/// name (non-identifier characters replaced) keeps them readable.
std::string placeName(const Module &m, uint32_t i) {
  std::string out = "P" + std::to_string(i) + "_";
  for (char c : m.places[i].name)
    out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

const char *typeFor(int64_t hi) {
  if (hi <= 1)
    return "bit";
  if (hi <= 255)
    return "byte";
  if (hi <= 32767)
    return "short";
  return "int";
}

} // namespace

bool checkers::writePromela(const Module &m, const sem::StateLayout &L,
                            DiagEngine &diag, llvm::raw_ostream &os) {
  if (!refuseBeyondPt(m, "Promela", diag))
    return false;
  std::vector<std::string> names;
  for (uint32_t p = 0; p < m.places.size(); ++p)
    names.push_back(placeName(m, p));
  auto hiOf = [&](uint32_t p) { return L.slotMax(L.markingSlot(p)); };

  // Enabling of each transition as a Promela expression.
  std::vector<std::string> enabling;
  bool anyUrgent = false;
  for (const Transition &t : m.transitions) {
    std::string cond;
    auto conj = [&](const std::string &c) {
      cond += (cond.empty() ? "" : " && ") + c;
    };
    for (const PlaceEffect &e : placeEffects(t)) {
      const std::string &n = names[e.place];
      if (e.pre > 0)
        conj(n + " >= " + std::to_string(e.pre));
      uint32_t cap = m.places[e.place].capacity;
      if (e.post > e.pre && cap != kInf && !L.isStructurallyBounded(e.place))
        conj(n + " + " + std::to_string(e.post - e.pre) +
             " <= " + std::to_string(cap));
    }
    enabling.push_back(cond.empty() ? "true" : "(" + cond + ")");
    anyUrgent |= t.urgent;
  }

  os << "/* Module '" << m.name
     << "' as Promela (netlift emit --to promela).\n"
        "   One d_step per transition, interleaving: spin's reachable "
        "states are\n"
        "   netlift's. Check: spin -a FILE && cc -O2 -DBFS -DNOREDUCE "
        "-DSAFETY -o pan pan.c\n"
        "   && ./pan   (deadlocks are valid end states: label `end`). */\n";
  for (uint32_t p = 0; p < m.places.size(); ++p)
    os << typeFor(hiOf(p)) << " " << names[p] << " = " << m.places[p].tokens
       << ";\n";
  os << "\nactive proctype net() {\nend:\n  do\n";
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    const Transition &t = m.transitions[ti];
    std::string guard = enabling[ti];
    if (anyUrgent && !t.urgent)
      for (uint32_t u = 0; u < m.transitions.size(); ++u)
        if (m.transitions[u].urgent)
          guard += " && !" + enabling[u];
    os << "  :: d_step { " << guard << " ->\n";
    bool any = false;
    for (const PlaceEffect &e : placeEffects(t)) {
      int64_t gain = e.post - e.pre;
      if (gain == 0)
        continue;
      const std::string &n = names[e.place];
      // An unbounded place past its encoding: a runtime error in netlift.
      if (gain > 0 && m.places[e.place].capacity == kInf &&
          !L.isStructurallyBounded(e.place))
        os << "       assert(" << n << " + " << gain << " <= " << hiOf(e.place)
           << ");\n";
      os << "       " << n << " = " << n << (gain > 0 ? " + " : " - ")
         << (gain > 0 ? gain : -gain) << ";\n";
      any = true;
    }
    if (!any)
      os << "       skip;\n";
    os << "     } /* " << t.name << " */\n";
  }
  os << "  od\n}\n";
  return true;
}
