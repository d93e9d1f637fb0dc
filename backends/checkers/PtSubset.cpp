//===- PtSubset.cpp - the place/transition part of a module ---------------===//
#include "backends/checkers/PtSubset.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;

bool checkers::refuseBeyondPt(const Module &m, llvm::StringRef format,
                              DiagEngine &diag) {
  std::string why = ("the " + format +
                     " export covers place/transition nets (weights, "
                     "capacities, urgency) so far")
                        .str();
  for (const Port &p : m.ports)
    if (p.isInput()) {
      diag.error(p.loc, "free input '" + p.name + "' cannot be exported to " +
                            format + ": " + why);
      return false;
    } else if (p.isStored()) {
      diag.error(p.loc, "stored output '" + p.name +
                            "' cannot be exported to " + format + ": " + why);
      return false;
    }
  for (const Var &v : m.vars) {
    diag.error(v.loc, "variable '" + v.name + "' cannot be exported to " +
                          format + ": " + why);
    return false;
  }
  for (const Transition &t : m.transitions) {
    const char *what = t.isForced()         ? "an event arc"
                       : !t.conds().empty() ? "a condition arc"
                       : t.guard()          ? "a guard"
                       : t.hasAction()      ? "an action"
                                            : nullptr;
    for (const PreArc &a : t.pre())
      if (!what && !a.time.isTrivial())
        what = "a timed arc";
    if (what) {
      diag.error(t.loc, "transition '" + t.name + "' has " + what +
                            ", which the " + format +
                            " export does not cover: " + why);
      return false;
    }
  }
  return true;
}
