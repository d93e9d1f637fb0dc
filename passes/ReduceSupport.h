//===- ReduceSupport.h - what the reduction passes share --------*- C++ -*-===//
//
// The reduction passes (reduce-dead, reduce-consts, reduce-ranges,
// reduce-clocks, reduce-coi) all work on the design's flat top module and
// all need the same few things: which module that is, who reads and who
// writes each variable, a way to remove entities while keeping every index
// consistent, and a re-verification afterwards so that the next pass sees
// resolved names again. They live here, written once; the walks over what
// a module reads and writes are NetIR's own (ir/net/Walk.h).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_REDUCESUPPORT_H
#define NETLIFT_PASSES_REDUCESUPPORT_H

#include "ir/net/Builder.h"
#include "ir/net/Walk.h"
#include "passes/Pass.h"

#include "llvm/ADT/STLFunctionalExtras.h"

#include <optional>
#include <vector>

namespace netlift::reduce {

/// The module reductions work on: `top=` or the design's top, which must
/// have no instances, with every name resolved (the design is verified
/// first). Null after reporting (naming `pass`).
net::Module *flatTop(net::Design &d, DiagEngine &diag, const PassOptions &opts,
                     llvm::StringRef pass);

/// Per variable: the transitions writing it, and whether anything reads
/// it. Per place: whether an expression mentions it.
struct Uses {
  std::vector<std::vector<uint32_t>> writers; // per var
  std::vector<bool> varRead;                  // per var
  std::vector<bool> placeRead;                // per place
  explicit Uses(const net::Module &m);
};

/// Removes the places, transitions and variables whose keep flag is false,
/// renumbering arcs, event arcs and flows, and rebuilds the symbol table.
/// Nothing kept may still mention what is removed.
void compactModule(net::Module &m, const std::vector<bool> &keepPlace,
                   const std::vector<bool> &keepTrans,
                   const std::vector<bool> &keepVar);

/// Removes the ports whose keep flag is false, renumbering the events
/// transitions emit and listen to (the symbol table is the caller's to
/// rebuild, e.g. by compactModule). Nothing kept may still mention them.
void removePorts(net::Design &d, net::Module &m,
                 const std::vector<bool> &keepPort);

/// What a reduction must keep observable: the elements `observe=` names
/// (places, variables, ports, transitions), or every output without it.
struct Observed {
  std::vector<bool> place, var, port, trans;
};
/// Null after reporting a name in `observe=` that is none of those.
std::optional<Observed> observedElements(const net::Module &m,
                                         const PassOptions &opts,
                                         llvm::StringRef pass,
                                         DiagEngine &diag);

/// Resolves the design again after a rewrite. False after reporting.
bool reverify(net::Design &d, DiagEngine &diag, llvm::StringRef pass);

} // namespace netlift::reduce

#endif
