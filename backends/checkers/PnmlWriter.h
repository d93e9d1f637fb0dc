//===- PnmlWriter.h - flat modules as PNML place/transition nets -*- C++
//-*-===//
//
// Writes the place/transition part of a flat module as a PNML P/T net
// (grammar ptnet of 2009, the format of the Model Checking Contest), so
// that other Petri-net tools can analyse it. Node ids are the NetIR names
// (made unique with trailing underscores; also given as <name>), arcs keep
// their weights, places their initial markings. PNML has no capacities: a place
// of finite capacity c gets a complementary place `<name>_cap` holding c minus
// its tokens, which every transition's net effect on the place consumes or
// refills, so a transition is enabled exactly when it keeps the place within c
// after firing, as in NetIR; the reachable markings correspond one to one
// (interleaving). Urgency is dropped because an untimed net never lets
// time pass anyway. Everything beyond P/T (inputs, variables, clocks,
// conditions, events, guards, actions) is refused by name.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_PNMLWRITER_H
#define NETLIFT_BACKENDS_CHECKERS_PNMLWRITER_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::checkers {

/// False, with an error at the first construct outside P/T, when it
/// cannot.
bool writePnml(const net::Module &m, DiagEngine &diag, llvm::raw_ostream &os);

} // namespace netlift::checkers

#endif
