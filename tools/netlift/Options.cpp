//===- Options.cpp - the options every reading subcommand shares ----------===//
#include "frontends/plc/PlcAst.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"
#include "ir/support/OutputFile.h"
#include "passes/Pass.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/Path.h"

#include <cstdlib>

using namespace netlift;
using namespace netlift::driver;

cl::OptionCategory &driver::category() {
  static cl::OptionCategory c("netlift options");
  return c;
}

cl::opt<std::string> driver::outputFile("o",
                                        cl::desc("Output file ('-' = stdout)"),
                                        cl::value_desc("file"), cl::init("-"),
                                        readingCommands);
cl::opt<bool> driver::noSourceLocations(
    "no-locations",
    cl::desc("Write NetIR without the program's source locations (the "
             "`source` table and `@N:line:col` after statements)"),
    cl::sub(translateCommand()), cl::sub(optCommand()),
    cl::sub(composeCommand()), cl::sub(emitCommand()), cl::cat(category()));
cl::opt<std::string>
    driver::inputFormat("from",
                        cl::desc("Input format (default: by file extension)"),
                        cl::value_desc("format"), readingCommands);
cl::opt<std::string> driver::topName(
    "top",
    cl::desc("The module to explore; for PLC input also the program, "
             "program instance or function block to translate"),
    cl::value_desc("NAME"), readingCommands);
static cl::alias topAlias("module", cl::desc("Alias for --top"),
                          cl::aliasopt(topName));
cl::list<std::string> driver::properties(
    "ctl",
    cl::desc("A CTL property (repeatable; with emit --to promela or smv, "
             "written as a claim)"),
    cl::value_desc("FORMULA"), cl::sub(checkCommand()), cl::sub(emitCommand()),
    cl::cat(category()));
cl::opt<std::string>
    driver::edgesFile("edges",
                      cl::desc("reach: also write the edges as CSV to FILE; "
                               "sr: read them from FILE (with a CSV state "
                               "file)"),
                      cl::value_desc("FILE"), cl::sub(reachCommand()),
                      cl::sub(srCommand()), cl::cat(category()));

static cl::opt<std::string> timescale(
    "timescale",
    cl::desc("PLC and IEC 61499 input: the length of one tick, e.g. 10ms "
             "(default: the greatest common divisor of the TIME values)"),
    cl::value_desc("DURATION"), readingCommands);
static cl::opt<std::string>
    scanPeriod("scan-period",
               cl::desc("PLC input: the scan period (default: the task "
                        "INTERVAL, else one tick)"),
               cl::value_desc("DURATION"), readingCommands);
static cl::opt<std::string>
    ranges("ranges",
           cl::desc("PLC input: value ranges of integer inputs; hybrid "
                    "input: ranges of reals; one 'NAME LO..HI' a line "
                    "('NAME NOT NULL' for a reference input the caller never "
                    "passes NULL)"),
           cl::value_desc("FILE"), readingCommands);
static cl::list<std::string>
    rangeOptions("range",
                 cl::desc("One range, as a line of --ranges FILE would give "
                          "it (a PLC input's or a hybrid model's real)"),
                 cl::value_desc("NAME=LO..HI"), readingCommands);
static cl::opt<std::string> spaceexConfig(
    "cfg",
    cl::desc("SpaceEx input: the configuration giving the system and the "
             "initial set (default: the .cfg beside the model with its name; "
             "'none': none)"),
    cl::value_desc("FILE"), readingCommands);
static cl::list<std::string>
    params("param",
           cl::desc("SpaceEx input: the value of a constant (overrides the "
                    "configuration's)"),
           cl::value_desc("NAME=VALUE"), readingCommands);
static cl::list<std::string>
    typeLibraries("I",
                  cl::desc("IEC 61499 input: a directory searched (with its "
                           "subdirectories) for the .fbt/.sub types a "
                           "network uses"),
                  cl::value_desc("DIR"), cl::Prefix, readingCommands);
static cl::list<std::string>
    defines("D",
            cl::desc("PLC input: a name defined for conditional compilation "
                     "({IF defined(NAME)}), with a value for hasvalue"),
            cl::value_desc("NAME[=VALUE]"), cl::Prefix, readingCommands);
static cl::opt<bool> warnUnusedRefused(
    "Wunused-refused",
    cl::desc("PLC input: warn about constructs netlift refuses in POUs the "
             "translation does not use"),
    readingCommands);
static cl::opt<std::string> fbSemantics(
    "fb-semantics",
    cl::desc("IEC 61499 input: the execution model, forte (default: one "
             "flat module per resource, events in one FIFO as 4diac FORTE "
             "runs them), sequential (modules mirroring the networks, "
             "events of different blocks in any order) or cyclic (fb2smv's "
             "model: blocks take turns in network order, each reacting to "
             "all its pending events at once)"),
    cl::value_desc("MODEL"), readingCommands);
static cl::opt<unsigned> callerElements(
    "caller-elements",
    cl::desc("Elements modelled of a caller's array a pointer input of the "
             "block run as the top designates, when the array is too large "
             "to choose whole (OSCAT's POINTER TO ARRAY[0..32000] OF BYTE); "
             "an element past them is a run-time error (default 16)"),
    cl::init(16), cl::value_desc("N"), readingCommands);
enum class OpaqueBlocks { Environment, Refuse };
static cl::opt<OpaqueBlocks> opaqueBlocks(
    "opaque",
    cl::desc("Blocks and readings the runtime implements and netlift has "
             "no model of (IEC 61499 service interface FBs, TwinCAT's ADS "
             "and file blocks, the clock TIME() reads)"),
    cl::init(OpaqueBlocks::Environment),
    cl::values(clEnumValN(OpaqueBlocks::Environment, "environment",
                          "modelled as environment, with a note (the "
                          "default): their outputs do what their interface "
                          "allows"),
               clEnumValN(OpaqueBlocks::Refuse, "refuse", "refused")),
    readingCommands);
enum class Channels { Lossless, Lossy };
static cl::opt<Channels> channels(
    "channels",
    cl::desc("IEC 61499 input: publish/subscribe channels between blocks of "
             "one network with the same ID"),
    cl::init(Channels::Lossless),
    cl::values(clEnumValN(Channels::Lossless, "lossless",
                          "every message is delivered (the default)"),
               clEnumValN(Channels::Lossy, "lossy",
                          "each message may be lost")),
    readingCommands);
static cl::opt<plc::SfcDialect> sfcDialect(
    "sfc-dialect", cl::desc("SFC input: the order of a scan (docs/sfc.md)"),
    cl::init(plc::SfcDialect::Iec),
    cl::values(clEnumValN(plc::SfcDialect::Iec, "iec",
                          "evolve the chart, then run the actions of the new "
                          "step activity (IEC 61131-3, matiec)"),
               clEnumValN(plc::SfcDialect::Codesys, "codesys",
                          "run the actions of the current step activity, "
                          "then evolve (CODESYS, TwinCAT)")),
    readingCommands);
static cl::opt<std::string> timeUnit(
    "time-unit",
    cl::desc("PLC input: what TIME_TO_INT, TIME_TO_REAL, INT_TO_TIME and "
             "REAL_TO_TIME count in: s (matiec: OpenPLC, Beremiz) or ms "
             "(CODESYS, TwinCAT); default: s for ST with a textual "
             "CONFIGURATION and PLCopen XML not written by CODESYS or "
             "TwinCAT, else ms (docs/st.md)"),
    cl::value_desc("s|ms"), readingCommands);
// Hidden knobs, so that tests can make small ST inputs take the grouped
// parse of long parts.
static cl::opt<unsigned> stLongPartTokens(
    "st-long-part-tokens", cl::Hidden, cl::init(16384),
    cl::sub(*cl::AllSubCommands),
    cl::desc("ST: parse bodies and VAR blocks of at least this many tokens "
             "in groups"));
static cl::opt<unsigned>
    stGroupTokens("st-group-tokens", cl::Hidden, cl::init(4096),
                  cl::sub(*cl::AllSubCommands),
                  cl::desc("ST: tokens per group of a long body or VAR block"));

bool driver::frontendOptions(FrontendOptions &fo, DiagEngine &diag) {
  fo.top = topName;
  const char *roundTrip = std::getenv("NETLIFT_VERIFY_ROUNDTRIP");
  fo.verifyRoundTrip = roundTrip && llvm::StringRef(roundTrip) != "0";
  fo.rangesFile = ranges;
  fo.rangeOptions.assign(rangeOptions.begin(), rangeOptions.end());
  fo.spaceexConfig = spaceexConfig;
  fo.params.assign(params.begin(), params.end());
  fo.typeLibraries.assign(typeLibraries.begin(), typeLibraries.end());
  fo.fbSemantics = fbSemantics;
  fo.opaqueRefused = opaqueBlocks == OpaqueBlocks::Refuse;
  fo.callerElements = callerElements;
  if (callerElements == 0 || callerElements > 4096) {
    diag.error(llvm::SMLoc(),
               "--caller-elements=" + llvm::Twine(callerElements) +
                   ": give 1 to 4096 elements");
    return false;
  }
  fo.lossyChannels = channels == Channels::Lossy;
  fo.sfcCodesys = sfcDialect == plc::SfcDialect::Codesys;
  fo.timeUnit = timeUnit;
  if (!fo.timeUnit.empty() && fo.timeUnit != "s" && fo.timeUnit != "ms") {
    diag.error(llvm::SMLoc(),
               "--time-unit=" + fo.timeUnit +
                   ": expected s (seconds) or ms (milliseconds)");
    return false;
  }
  fo.warnUnusedRefused = warnUnusedRefused;
  fo.defines.assign(defines.begin(), defines.end());
  fo.stLongPartTokens = stLongPartTokens;
  fo.stGroupTokens = stGroupTokens;
  return parseDurationOption("timescale", timescale, fo.timescaleNs, diag) &&
         parseDurationOption("scan-period", scanPeriod, fo.scanPeriodNs, diag);
}

bool driver::loadModels(llvm::ArrayRef<std::string> paths, DiagEngine &diag,
                        net::Design &design) {
  FrontendOptions fo;
  std::vector<std::string> pipelines;
  if (!frontendOptions(fo, diag) ||
      !loadInputs(paths, inputFormat, fo, diag, design, pipelines))
    return false;
  if (pipelines.empty())
    return true;
  // What a frontend left to passes (the IEC 61499 execution models).
  for (const std::string &pipeline : pipelines) {
    PassManager pm;
    if (!pm.parsePipeline(pipeline, diag) || !pm.run(design, diag))
      return false;
  }
  return net::verifyDesign(design, diag);
}

bool driver::topUsable(llvm::ArrayRef<std::string> inputs,
                       llvm::StringRef command, DiagEngine &diag) {
  if (topName.empty())
    return true;
  for (const std::string &in : inputs)
    if (!(inputFormat == "net" ||
          (inputFormat.empty() && llvm::sys::path::extension(in) == ".net")))
      return true;
  diag.error(llvm::SMLoc(),
             command +
                 ": --top selects the program a PLC frontend translates; "
                 "NetIR input is written whole (explore one module with "
                 "reach --top, flatten one with opt -p 'flatten{top=" +
                 topName + "}')");
  return false;
}

int driver::writeResult(llvm::StringRef path,
                        llvm::function_ref<void(llvm::raw_ostream &)> body,
                        DiagEngine &diag) {
  return writeOutputFile(path, body, diag) ? 0 : 1;
}

int driver::writeDesign(const net::Design &design, DiagEngine &diag) {
  return writeResult(
      outputFile,
      [&](llvm::raw_ostream &os) {
        net::printDesign(design, os,
                         noSourceLocations ? nullptr : &diag.sourceMgr());
      },
      diag);
}
