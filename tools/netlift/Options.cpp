//===- Options.cpp - the subcommands and the options they share -----------===//
#include "frontends/plc/PlcAst.h"
#include "ir/net/Printer.h"
#include "ir/support/OutputFile.h"
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

static cl::opt<sem::StepPolicy> stepPolicy(
    "semantics", cl::desc("Step policy"),
    cl::init(sem::StepPolicy::Interleaving),
    cl::values(clEnumValN(sem::StepPolicy::Interleaving, "interleaving",
                          "one spontaneous transition per step"),
               clEnumValN(sem::StepPolicy::Maximal, "maximal",
                          "a maximal set of spontaneous transitions")),
    exploringCommands, cl::sub(emitCommand()));
static cl::opt<sem::Timing>
    timing("timing", cl::desc("Timing"), cl::init(sem::Timing::Weak),
           cl::values(clEnumValN(sem::Timing::Weak, "weak",
                                 "a passed upper bound disables"),
                      clEnumValN(sem::Timing::Strong, "strong",
                                 "time may not pass an enabled upper bound")),
           exploringCommands, cl::sub(emitCommand()));
static cl::opt<unsigned>
    placeBits("place-bits",
              cl::desc("Bits for the marking of unbounded places (default 8)"),
              cl::init(8), exploringCommands, cl::sub(emitCommand()));
static cl::opt<uint64_t> maxLoopIterations(
    "max-loop-iterations",
    cl::desc("Watchdog: most loop iterations one firing may run "
             "(default 100000)"),
    cl::init(100000), exploringCommands);
enum class InputsMode { Split, Enumerate };
static cl::opt<InputsMode> inputsMode(
    "inputs",
    cl::desc("Free inputs at each step (docs/semantics.md); default split, "
             "or the NETLIFT_INPUTS environment variable"),
    cl::values(clEnumValN(InputsMode::Split, "split",
                          "split their values into classes on demand"),
               clEnumValN(InputsMode::Enumerate, "enumerate",
                          "enumerate every valuation")),
    exploringCommands);
static cl::opt<uint64_t> maxInputValues(
    "max-input-values",
    cl::desc("Most values one free input is split into at one point, or "
             "(enumerating) most valuations of all free inputs per step "
             "(default 65536)"),
    cl::init(uint64_t(1) << 16), exploringCommands);
static cl::opt<uint64_t> maxInputClasses(
    "max-input-classes",
    cl::desc("Most classes of input valuations one step may split into "
             "(default 65536)"),
    cl::init(uint64_t(1) << 16), exploringCommands);
enum class TimersMode { Exact, Abstract };
static cl::opt<TimersMode> timersMode(
    "timers",
    cl::desc("Timers' elapsed time (docs/reach.md, \"Timers abstracted\")"),
    cl::init(TimersMode::Exact),
    cl::values(clEnumValN(TimersMode::Exact, "exact",
                          "counted tick by tick (the default)"),
               clEnumValN(TimersMode::Abstract, "abstract",
                          "not counted: a running timer may expire at any "
                          "later scan (proves invariants; counterexamples "
                          "are replayed in exact time)")),
    cl::sub(reachCommand()), cl::sub(checkCommand()), cl::cat(category()));
static cl::opt<unsigned> refineRounds(
    "refine",
    cl::desc("--timers=abstract: rounds that keep the timers of a spurious "
             "counterexample exact and search again (default 3)"),
    cl::init(3), cl::sub(reachCommand()), cl::sub(checkCommand()),
    cl::cat(category()));
static cl::opt<uint64_t> replayStates(
    "replay-states",
    cl::desc("--timers=abstract: most exact states the replay of a "
             "counterexample visits (default 1000000)"),
    cl::init(1000000), cl::sub(reachCommand()), cl::sub(checkCommand()),
    cl::cat(category()));
static cl::list<std::string> latch(
    "latch",
    cl::desc("Keep these free inputs in the state as the PLC's input image "
             "(what the scan last read); inputs a property or --find names "
             "are latched without it (docs/check.md)"),
    cl::value_desc("NAME,..."), cl::CommaSeparated, cl::sub(reachCommand()),
    cl::sub(checkCommand()), cl::cat(category()));
static cl::list<std::string> keep(
    "keep",
    cl::desc("Keep the values of these function-block members (or every "
             "member of these instances) that the PLC frontend resets at "
             "the end of each scan because the program never reads them; "
             "those a property, --find or --attr names are kept without it "
             "(docs/semantics.md, \"Observers\")"),
    cl::value_desc("NAME,..."), cl::CommaSeparated, cl::sub(reachCommand()),
    cl::sub(checkCommand()), cl::sub(srCommand()), cl::sub(emitCommand()),
    cl::cat(category()));
static cl::opt<bool> keepAll(
    "keep-all",
    cl::desc("Keep the value of every function-block member the PLC "
             "frontend would reset at the end of each scan (no reset: the "
             "state space tells apart everything the PLC holds)"),
    cl::sub(reachCommand()), cl::sub(checkCommand()), cl::sub(srCommand()),
    cl::sub(emitCommand()), cl::cat(category()));
static cl::opt<bool> traceInternals(
    "trace-internals",
    cl::desc("Show traces as the net has them: every step (ticks too) and "
             "every name (clocks, library blocks' state, generated "
             "scaffolding), instead of the program's own names per step"),
    exploringCommands);
static cl::opt<bool> traceSource(
    "trace-source",
    cl::desc("In traces, list under each step the source lines it ran "
             "(statements in the order a PLC debugger would step them)"),
    exploringCommands);
static cl::opt<bool>
    interpreter("interpreter",
                cl::desc("Use the general interpreter even for plain P/T "
                         "nets (to cross-check the compiled P/T kernel)"),
                exploringCommands);
static cl::opt<uint64_t> maxStates("max-states",
                                   cl::desc("Stop after N states"), cl::init(0),
                                   exploringCommands);
static cl::opt<std::string>
    maxMemory("max-memory", cl::desc("Stop above SIZE bytes (suffix K, M, G)"),
              exploringCommands);
static cl::opt<double> timeLimit("time-limit", cl::desc("Stop after SECONDS"),
                                 cl::init(0), exploringCommands);
#undef readingCommands
#undef exploringCommands

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
  return frontendOptions(fo, diag) &&
         loadInputs(paths, inputFormat, fo, diag, design);
}

bool driver::explorationOptions(engine::ExplorationOptions &eo,
                                DiagEngine &diag) {
  eo.top = topName;
  eo.semantics.policy = stepPolicy;
  eo.semantics.timing = timing;
  eo.semantics.unboundedBits = placeBits;
  eo.semantics.compilePT = !interpreter;
  eo.semantics.maxLoopIterations = maxLoopIterations;
  eo.semantics.maxInputValues = maxInputValues;
  eo.semantics.maxInputClasses = maxInputClasses;
  eo.semantics.splitInputs = true;
  if (inputsMode.getNumOccurrences())
    eo.semantics.splitInputs = inputsMode == InputsMode::Split;
  else if (const char *env = std::getenv("NETLIFT_INPUTS")) {
    llvm::StringRef mode(env);
    if (mode != "split" && mode != "enumerate" && !mode.empty()) {
      diag.error(llvm::SMLoc(), "NETLIFT_INPUTS=" + mode.str() +
                                    ": expected split or enumerate");
      return false;
    }
    eo.semantics.splitInputs = mode != "enumerate";
  }
  if (maxInputValues < 1 || maxInputClasses < 1) {
    diag.error(llvm::SMLoc(),
               "--max-input-values and --max-input-classes must be at least 1");
    return false;
  }
  eo.abstractTimers = timersMode == TimersMode::Abstract;
  eo.latch.assign(latch.begin(), latch.end());
  eo.keep.assign(keep.begin(), keep.end());
  eo.keepAll = keepAll;
  eo.traceInternals = traceInternals;
  eo.traceSource = traceSource;
  eo.refineRounds = refineRounds;
  eo.replayStates = replayStates;
  eo.maxStates = maxStates;
  eo.timeLimit = timeLimit;
  if (!maxMemory.empty() && !engine::parseByteSize(maxMemory, eo.maxMemory)) {
    diag.error(llvm::SMLoc(), "--max-memory: '" + maxMemory +
                                  "' is not a size (e.g. 512M, 4G)");
    return false;
  }
  if (placeBits < 1 || placeBits > 32) {
    diag.error(llvm::SMLoc(), "--place-bits must be 1..32");
    return false;
  }
  return true;
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
