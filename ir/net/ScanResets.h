//===- ScanResets.h - the end-of-scan resets of PLC memory -------*- C++
//-*-===//
//
// A PLC frontend resets function-block members the program never reads to
// their initial values at the end of each scan, so that states do not
// differ in values the model does not read; each such variable carries
// `attr NAME scan_reset` (Module.h). The PLC keeps those values, so every
// observer of one must see past the reset: an exploring command keeps an
// observed variable's value (passes/KeepValues.h), and traces are shown
// with no reset at all (sem::Options::scanResets off). This unit finds the
// reset statements, the one fact both rely on.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_SCANRESETS_H
#define NETLIFT_IR_NET_SCANRESETS_H

#include "ir/net/Module.h"

#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/STLFunctionalExtras.h"

namespace netlift::net {

/// The variables of `m` marked `scan_reset`, by index.
llvm::DenseSet<uint32_t> scanResetVars(const Module &m);

/// The reset statements of the variables `resetVar` accepts (by index),
/// among those marked `scan_reset`: in each transition's action, the
/// top-level assignments of a constant to such a variable (or one of its
/// elements) after which the action writes the variable no more.
llvm::DenseSet<const Stmt *>
scanResetStatements(const Module &m,
                    llvm::function_ref<bool(uint32_t)> resetVar);
/// All of them.
llvm::DenseSet<const Stmt *> scanResetStatements(const Module &m);

/// Whether `name` is `scope` or a name under it (`t.ET` under `t`).
bool isNameInScope(llvm::StringRef name, llvm::StringRef scope);

/// Identifiers of `text` (a property, a --find expression, an sr
/// attribute) that name a `scan_reset` variable of `m`, or a scope of
/// such variables (`t` for `t.ET`), as the variables' names.
std::vector<std::string> scanResetVarsNamedIn(const Module &m,
                                              llvm::StringRef text);

} // namespace netlift::net

#endif
