//===- ReduceSupport.h - what the reduction passes share --------*- C++ -*-===//
//
// The reduction passes (reduce-dead, reduce-consts, reduce-ranges,
// reduce-clocks, reduce-coi) all work on the design's flat top module and
// all need the same few things: which module that is, who reads and who
// writes each variable, a way to remove entities while keeping every index
// consistent, and a re-verification afterwards so that the next pass sees
// resolved names again. They live here, written once.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_REDUCESUPPORT_H
#define NETLIFT_PASSES_REDUCESUPPORT_H

#include "ir/net/Builder.h"
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

/// Calls `f` on `e` and every sub-expression.
void walkExpr(const net::Expr *e,
              llvm::function_ref<void(const net::Expr *)> f);

/// Every expression the module evaluates, with the transition it belongs to
/// (-1: an output definition or initial value): guards, condition arcs,
/// and in actions the conditions, selectors, labels, loop bounds, values
/// assigned and indices of assignment targets.
void forEachRead(const net::Module &m,
                 llvm::function_ref<void(const net::Expr *, int)> f);

/// Every assignment in every action, with its transition.
void forEachAssign(const net::Module &m,
                   llvm::function_ref<void(const net::AssignStmt *, int)> f);

/// Every assignment in `block`, nested ones included.
void forEachAssign(net::Block block,
                   llvm::function_ref<void(const net::AssignStmt *)> f);

/// `block` without the assignments `keep` rejects (nested ones included).
net::Block
dropAssignments(net::Builder &b, net::Block block,
                llvm::function_ref<bool(const net::AssignStmt *)> keep);

/// The initial value of a scalar variable (its `init` or the type's
/// default: false, the low bound of a range, 0), or nullopt if the
/// initialiser is not a constant.
std::optional<int64_t> initialValue(const net::Var &v);

/// The variable or port an assignment target writes (through indices and
/// fields).
net::Symbol targetRoot(const net::Expr *target);

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
                                         llvm::StringRef pass);

/// Resolves the design again after a rewrite. False after reporting.
bool reverify(net::Design &d, DiagEngine &diag, llvm::StringRef pass);

} // namespace netlift::reduce

#endif
