//===- PtSubset.cpp - the place/transition part of a module ---------------===//
#include "backends/checkers/PtSubset.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;

std::optional<BeyondPt> checkers::firstBeyondPt(const Module &m) {
  for (const Port &p : m.ports)
    if (p.isInput())
      return BeyondPt{p.loc, "free input '" + p.name.str() + "'"};
    else if (p.isStored())
      return BeyondPt{p.loc, "stored output '" + p.name.str() + "'"};
  for (const Var &v : m.vars)
    return BeyondPt{v.loc, "variable '" + v.name.str() + "'"};
  for (const Transition &t : m.transitions) {
    const char *what = t.isForced()         ? "an event arc"
                       : !t.conds().empty() ? "a condition arc"
                       : t.guard()          ? "a guard"
                       : t.hasAction()      ? "an action"
                                            : nullptr;
    for (const PreArc &a : t.pre())
      if (!what && !a.time.isTrivial())
        what = "a timed arc";
    if (what)
      return BeyondPt{t.loc, "transition '" + t.name.str() + "' has " + what};
  }
  return std::nullopt;
}

bool checkers::refuseBeyondPt(const Module &m, llvm::StringRef format,
                              DiagEngine &diag) {
  std::optional<BeyondPt> beyond = firstBeyondPt(m);
  if (!beyond)
    return true;
  diag.error(beyond->loc, beyond->what + ", which the " + format.str() +
                              " export does not cover: it covers "
                              "place/transition nets (weights, capacities, "
                              "urgency) so far");
  return false;
}
