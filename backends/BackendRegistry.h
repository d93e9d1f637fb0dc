//===- BackendRegistry.h - the formats `emit` writes ------------*- C++ -*-===//
//
// Every output format of `netlift emit --to`, declared once in
// BackendRegistry.def: its name, extension, what it takes (the design, the
// flattened top, or the top's step relation) and its writer. `emit`,
// `--help` and the generated table of docs/formats.md read this registry,
// so a format added there is usable and documented everywhere at once.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_BACKENDREGISTRY_H
#define NETLIFT_BACKENDS_BACKENDREGISTRY_H

#include "backends/checkers/Ctl.h"
#include "engine/ExplorationSetup.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/raw_ostream.h"

namespace netlift {

/// What a backend takes.
enum class EmitInputKind { Design, FlatTop, Steps };

struct EmitInput {
  const net::Design *design = nullptr;
  /// FlatTop and Steps: the flattened top.
  const net::Module *top = nullptr;
  /// Steps: the top's semantics.
  engine::ExplorationSetup *setup = nullptr;
  /// Steps: the --ctl properties.
  llvm::ArrayRef<const checkers::CtlFormula *> properties;
  /// NetIR text: statements carry their source locations (`@N:line:col`).
  bool sourceLocations = true;
};

struct BackendInfo {
  llvm::StringRef id;
  llvm::StringRef extension;
  EmitInputKind input;
  llvm::StringRef summary;
  bool (*write)(const EmitInput &in, DiagEngine &diag, llvm::raw_ostream &os);
};

/// All registered backends, in registry order.
llvm::ArrayRef<BackendInfo> backends();

/// The backend named `id`, or null.
const BackendInfo *findBackend(llvm::StringRef id);

/// One line per backend, `id - summary`, for `emit --to`'s help.
std::string describeBackends();

/// The table of docs/formats.md's "Output formats of emit" section.
void printBackendTable(llvm::raw_ostream &os);

} // namespace netlift

#endif
