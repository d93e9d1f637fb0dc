//===- Compose.h - closed-loop composition of modules -----------*- C++ -*-===//
//
// Composition puts modules side by side in a new `system` and wires their
// ports: a controller and its plant model become one closed loop whose state
// space contains both (the closed-loop modelling paper, sections I, III, V).
// Wiring comes from a connection file (`ctrl.valve -> plant.extend`, one per
// line) and/or from equal port names, an output of one component driving
// the inputs of that name of the others (the MVC pattern: a plant whose
// interface mirrors the controller's needs no file). What stays unwired is
// listed: unconnected inputs are the free environment, unconnected outputs
// stay observable. The `compose` pass and the `netlift compose` command are
// both this one function.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_COMPOSE_H
#define NETLIFT_PASSES_COMPOSE_H

#include "passes/Pass.h"

#include <optional>
#include <string>
#include <vector>

namespace netlift {

struct ComposeOptions {
  /// Components as `name:Module` or `Module` (instance name: the module name
  /// in lower case). Empty: every module that is not a system and that no
  /// other module instantiates, in design order.
  std::vector<std::string> instances;
  /// Connection file (empty: none).
  std::string connectFile;
  /// Match remaining inputs to outputs of the same name. Default: on when
  /// there is no connection file.
  std::optional<bool> matchNames;
  /// Name of the system created.
  std::string systemName = "Closed";
};

/// Builds the system; `report` (may be null) receives the wiring and the
/// list of free inputs and unused outputs. False after reporting an error.
bool composeSystem(net::Design &design, DiagEngine &diag,
                   const ComposeOptions &opts, llvm::raw_ostream *report,
                   Statistics &stats);

/// Reads the pass options (`inst=`, `connect=`, `match=`, `name=`) into
/// `out`; false after reporting a malformed value.
bool parseComposeOptions(const PassOptions &opts, DiagEngine &diag,
                         ComposeOptions &out);

} // namespace netlift

#endif
