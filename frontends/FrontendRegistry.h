//===- FrontendRegistry.h - reading any supported input ---------*- C++ -*-===//
//
// The single entry point through which every netlift command reads a model:
// it picks the frontend by --from, else by the file's extension, loads the
// file (or standard input for "-") into the SourceMgr so diagnostics can
// point into it, and produces a verified Design. Frontends are listed in
// FrontendRegistry.def; adding one there makes every subcommand accept it.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_FRONTENDREGISTRY_H
#define NETLIFT_FRONTENDS_FRONTENDREGISTRY_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringRef.h"

#include <optional>
#include <string>
#include <vector>

namespace netlift {

/// Options of the PLC frontends, set by the driver from its command line
/// (translate --top/--timescale/--scan-period/--ranges).
struct FrontendOptions {
  std::string top;
  std::optional<int64_t> timescaleNs;
  std::optional<int64_t> scanPeriodNs;
  std::string rangesFile;
  /// -I: directories holding IEC 61499 types.
  std::vector<std::string> typeLibraries;
  /// --fb-semantics: the IEC 61499 execution model (empty: the default).
  std::string fbSemantics;
};
FrontendOptions &frontendOptions();

struct FrontendInfo {
  llvm::StringRef id;
  llvm::StringRef description;
  llvm::StringRef extensions;
  bool (*load)(unsigned bufferID, DiagEngine &diag, net::Design &design);
};

/// All registered frontends, in registry order.
llvm::ArrayRef<FrontendInfo> frontends();

/// Reads every path ("-" is standard input) with the frontend `from`
/// (empty: chosen by each file's extension, NetIR text by default) into one
/// `design`, then verifies it as a whole (a module may instantiate one from
/// another file). Returns false after reporting an error.
bool loadInputs(llvm::ArrayRef<std::string> paths, llvm::StringRef from,
                DiagEngine &diag, net::Design &design);

/// Frontend implementations (one per line of FrontendRegistry.def).
bool loadNetIR(unsigned bufferID, DiagEngine &diag, net::Design &design);
bool loadPnml(unsigned bufferID, DiagEngine &diag, net::Design &design);
bool loadStructuredText(unsigned bufferID, DiagEngine &diag,
                        net::Design &design);
bool loadInstructionList(unsigned bufferID, DiagEngine &diag,
                         net::Design &design);
bool loadTwinCat(unsigned bufferID, DiagEngine &diag, net::Design &design);
bool loadPlcOpen(unsigned bufferID, DiagEngine &diag, net::Design &design);
bool loadHybridChart(unsigned bufferID, DiagEngine &diag, net::Design &design);
bool loadSpaceEx(unsigned bufferID, DiagEngine &diag, net::Design &design);
bool loadIec61499(unsigned bufferID, DiagEngine &diag, net::Design &design);

/// PLC sources are collected across all input files (a program and the
/// function blocks it uses may live in different files) and translated
/// together once every file is read. Returns false after reporting.
bool finishPlcInputs(DiagEngine &diag, net::Design &design);

/// IEC 61499 files likewise: a network and the types it uses are read
/// together. Returns false after reporting.
bool finishIec61499Inputs(DiagEngine &diag, net::Design &design);

} // namespace netlift

#endif
