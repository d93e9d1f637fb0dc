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

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace netlift {

namespace plc {
struct Unit;
} // namespace plc

/// The options the frontends take, set by the driver from its command
/// line (--top, --timescale, --scan-period, --ranges, -I, --fb-semantics).
struct FrontendOptions {
  std::string top;
  std::optional<int64_t> timescaleNs;
  std::optional<int64_t> scanPeriodNs;
  /// --ranges FILE and each --range NAME=LO..HI: value ranges of PLC
  /// inputs and of hybrid models' reals (readRangeLines reads both).
  std::string rangesFile;
  std::vector<std::string> rangeOptions;
  /// -I: directories holding IEC 61499 types.
  std::vector<std::string> typeLibraries;
  /// --fb-semantics: the IEC 61499 execution model (empty: the default).
  std::string fbSemantics;
  /// --opaque: blocks the runtime implements (IEC 61499 service interface
  /// FBs and the like) modelled as environment (the default) or refused.
  bool opaqueRefused = false;
  /// --caller-elements (plc::LowerOptions::callerElements).
  int64_t callerElements = 16;
  /// --channels=lossy: IEC 61499 publish/subscribe channels may lose
  /// messages.
  bool lossyChannels = false;
  /// Check that NetIR input read alone prints, parses back and prints the
  /// same (the driver sets it from NETLIFT_VERIFY_ROUNDTRIP, as
  /// `lit --param roundtrip=1` runs the suite).
  bool verifyRoundTrip = false;
  /// --sfc-dialect: the order of an SFC scan, iec (default) or codesys.
  bool sfcCodesys = false;
  /// --time-unit: what TIME_TO_INT and the like count in, "s" or "ms";
  /// empty: what the inputs show (plc::TimeNumbers).
  std::string timeUnit;
  /// -D NAME[=VALUE]: names defined for PLC conditional compilation
  /// (`{IF defined(NAME)}`), with a project's compiler defines.
  std::vector<std::string> defines;
  /// The PLC project the inputs are (a `.plcproj`'s `<Name>`, else its
  /// file name without extension); empty when none was given.
  std::string projectName;
  /// -Wunused-refused: warn about refused constructs in PLC POUs the
  /// translation does not use.
  bool warnUnusedRefused = false;
  /// --cfg: the SpaceEx configuration of a SpaceEx model (empty: the .cfg
  /// beside it, "none": none).
  std::string spaceexConfig;
  /// --param NAME=VALUE: values of hybrid models' constants.
  std::vector<std::string> params;
  /// How ST parses long bodies and VAR blocks (hidden knobs for tests).
  unsigned stLongPartTokens = 16384;
  unsigned stGroupTokens = 4096;
};

/// One range a user gives, `NAME LO..HI` (or `NAME NOT NULL` for a PLC
/// reference input), with the place it was written (in the file, or in a
/// buffer `<--range>` holding the options one a line). The bounds are left
/// as text: PLC inputs take integers, hybrid reals any number.
struct RangeLine {
  llvm::StringRef name, lo, hi;
  bool notNull = false;
  llvm::SMLoc loc;
};

/// Reads --ranges FILE, then each --range option; false after reporting a
/// file that cannot be read or a malformed line.
bool readRangeLines(const FrontendOptions &fo, DiagEngine &diag,
                    std::vector<RangeLine> &out);

/// A duration option such as `--timescale 10ms` into nanoseconds (empty
/// text: left unset); false after reporting a malformed or non-positive one.
bool parseDurationOption(llvm::StringRef flag, llvm::StringRef text,
                         std::optional<int64_t> &ns, DiagEngine &diag);

/// One reading of a set of input files: the options the driver set, and
/// what frontends collect across files until every file is read (a PLC
/// program and the function blocks it uses, an IEC 61499 network and its
/// types, may come from different files). loadInputs makes one per call
/// and hands it to each frontend's load (per file) and finish (per design)
/// phase, so nothing is kept between two readings.
class FrontendContext {
public:
  explicit FrontendContext(const FrontendOptions &options);
  ~FrontendContext();
  FrontendContext(const FrontendContext &) = delete;
  FrontendContext &operator=(const FrontendContext &) = delete;

  const FrontendOptions &options;
  /// The PLC sources read so far (ST, IL, TwinCAT, PLCopen), made on first
  /// use; taken by the PLC frontends' finish phase.
  plc::Unit &plcUnit();
  std::unique_ptr<plc::Unit> takePlcUnit();
  /// The buffer of the first PLC source read (0: none).
  unsigned firstPlcFile = 0;
  /// IEC 61499 files read so far (buffer ids), translated together.
  std::vector<unsigned> iec61499Files;
  /// Pass pipelines a frontend asks for, run in order once every input is
  /// read (`iec61499-resources{...}`): what a frontend leaves to passes so
  /// that it builds modules only.
  std::vector<std::string> pipelines;

private:
  std::unique_ptr<plc::Unit> plc;
};

/// A frontend of FrontendRegistry.def. `load` reads one file (a buffer of
/// diag's SourceMgr) and either adds its modules to the design or keeps
/// what it read in the context; `finish`, when there is one, runs once
/// after every file is read and adds what was kept to the design.
struct FrontendInfo {
  llvm::StringRef id;
  llvm::StringRef description;
  llvm::StringRef extensions;
  bool (*load)(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
               net::Design &design);
  bool (*finish)(FrontendContext &ctx, DiagEngine &diag, net::Design &design);
};

/// All registered frontends, in registry order.
llvm::ArrayRef<FrontendInfo> frontends();

/// Reads every path ("-" is standard input) with the frontend `from`
/// (empty: chosen by each file's extension, NetIR text by default) into one
/// `design`, then verifies it as a whole (a module may instantiate one from
/// another file). Returns false after reporting an error.
///
/// A frontend may leave part of its lowering to passes (the IEC 61499
/// execution models, `iec61499-resources{...}`): those pipelines are
/// returned in `pipelines`, in order, for the caller to run through its
/// PassManager (a frontend runs no passes); the design is then verified by
/// the caller, after them.
bool loadInputs(llvm::ArrayRef<std::string> paths, llvm::StringRef from,
                const FrontendOptions &options, DiagEngine &diag,
                net::Design &design, std::vector<std::string> &pipelines);

/// The files a translation reads for `paths`: a TwinCAT `.plcproj` stands
/// for the sources it compiles, a directory for the `.plcproj` files under
/// it or else every PLC source under it (PlcProject.cpp); other paths stand
/// for themselves. None after reporting an error.
/// A project's compiler defines (`<CompilerDefines>`) are added to
/// `options.defines`, its name set as `options.projectName`.
std::optional<std::vector<std::string>>
expandProjectInputs(llvm::ArrayRef<std::string> paths, DiagEngine &diag,
                    FrontendOptions &options);

/// Frontend implementations (one per line of FrontendRegistry.def).
bool loadNetIR(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
               net::Design &design);
bool loadPnml(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
              net::Design &design);
bool loadStructuredText(FrontendContext &ctx, unsigned bufferID,
                        DiagEngine &diag, net::Design &design);
bool loadInstructionList(FrontendContext &ctx, unsigned bufferID,
                         DiagEngine &diag, net::Design &design);
bool loadTwinCat(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
                 net::Design &design);
bool loadPlcOpen(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
                 net::Design &design);
bool loadHybridChart(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
                     net::Design &design);
bool loadSpaceEx(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
                 net::Design &design);
bool loadIec61499(FrontendContext &ctx, unsigned bufferID, DiagEngine &diag,
                  net::Design &design);

/// The PLC sources of all input files, checked and lowered together.
bool finishPlcInputs(FrontendContext &ctx, DiagEngine &diag,
                     net::Design &design);

/// The IEC 61499 files, translated together with the types they use.
bool finishIec61499Inputs(FrontendContext &ctx, DiagEngine &diag,
                          net::Design &design);

} // namespace netlift

#endif
