//===- Iec61499.h - IEC 61499 function blocks into NetIR --------*- C++ -*-===//
//
// IEC 61499-2 XML (`.fbt` function block types, `.sub` subapplication
// types, `.sys` systems) into NetIR, following docs/iec61499.md. A basic
// FB becomes a module with the FB's interface (event ports, data ports;
// BOOL data as cond ports) whose forced transition `recv_<EI>` samples the
// event's With data and runs the ECC to completion (ST algorithms through
// the ST frontend and the PLC lowering), queueing output events that urgent
// transitions `send_<EO>` deliver one per step. Composite FBs,
// subapplications and applications become modules of instances and
// connections mirroring their networks one to one. Types come from the
// input files, then the -I directories, then netlift's own library
// (lib/iec61499: the standard event FBs).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_IEC61499_IEC61499_H
#define NETLIFT_FRONTENDS_IEC61499_IEC61499_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <optional>
#include <string>
#include <vector>

namespace netlift::iec61499 {

struct Options {
  /// -I directories.
  std::vector<std::string> typeLibraries;
  std::optional<int64_t> timescaleNs;
  /// "forte" (one flat module per resource, events in one FIFO),
  /// "sequential" (modules mirroring the networks, events of different
  /// blocks in any order) or "cyclic" (fb2smv's: one flat module per
  /// resource whose blocks take turns in network order).
  std::string semantics = "forte";
  /// Blocks the runtime implements that netlift ships no model of: modelled
  /// as environment (true, the default) or refused (--opaque=refuse).
  bool opaqueAsEnvironment = true;
  /// Publish/subscribe channels may lose messages (--channels=lossy).
  bool lossyChannels = false;
};

/// Translates the IEC 61499 files `bufferIDs` (already in the SourceMgr)
/// and every type they use into `design`. Under the forte and cyclic
/// models, the pass pipeline that makes each resource one flat module
/// (`iec61499-resources`) is appended to `pipelines`, for the caller to run
/// once every input is read. Returns false after reporting.
bool translate(const std::vector<unsigned> &bufferIDs, const Options &options,
               DiagEngine &diag, net::Design &design,
               std::vector<std::string> &pipelines);

} // namespace netlift::iec61499

#endif
