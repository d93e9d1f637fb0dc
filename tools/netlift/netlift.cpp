//===- netlift.cpp - the netlift driver -----------------------------------===//
//
// One binary, git-style subcommands. The driver is thin: it parses options,
// reads inputs through the frontend registry, and hands the Design to the
// libraries (passes, backends). Outputs are written to a temporary file and
// renamed into place, so an error never leaves a half-written file behind.
//
//===----------------------------------------------------------------------===//
#include "backends/checkers/Ctl.h"
#include "backends/checkers/PnmlWriter.h"
#include "backends/checkers/Promela.h"
#include "backends/checkers/Smv.h"
#include "backends/enforce/EditAutomatonJson.h"
#include "backends/enforce/Enforce.h"
#include "backends/mealy/ExtractMealy.h"
#include "backends/mealy/MealyWriters.h"
#include "backends/nces/NcesXml.h"
#include "backends/nces/NetDot.h"
#include "backends/statespace/ExplorationSetup.h"
#include "backends/statespace/Explorer.h"
#include "backends/statespace/Writers.h"
#include "backends/structural/DensityChart.h"
#include "backends/structural/EdwardsVenn.h"
#include "backends/structural/HtmlReport.h"
#include "backends/structural/StateFile.h"
#include "backends/structural/StructuralReasoning.h"
#include "frontends/FrontendRegistry.h"
#include "frontends/dot/DotMealyReader.h"
#include "frontends/kiss2/Kiss2Reader.h"
#include "frontends/st/StFrontend.h"
#include "ir/automata/EditAutomaton.h"
#include "ir/automata/Minimize.h"
#include "ir/net/Parser.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"
#include "ir/semantics/Semantics.h"
#include "passes/Compose.h"
#include "passes/Pass.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/JSON.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Program.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <functional>
#include <set>

using namespace netlift;
namespace cl = llvm::cl;

#ifndef NETLIFT_VERSION
#define NETLIFT_VERSION "0.0.0"
#endif

static cl::OptionCategory category("netlift options");

static cl::SubCommand
    translateCmd("translate",
                 "Read models in any supported format, verify them and "
                 "print them as canonical NetIR text");
static cl::SubCommand optCmd("opt",
                             "Run a pipeline of NetIR passes over a model");
static cl::SubCommand
    reachCmd("reach",
             "Explore the reachable states of a model (its top module, "
             "flattened)");
static cl::SubCommand mealyCmd(
    "mealy",
    "Read a Mealy machine (KISS2, DOT) or extract one from a controller "
    "model (PLC program, NetIR), check that it is deterministic, "
    "and write it as KISS2 or DOT");
static cl::SubCommand eaCmd("edit-automaton",
                            "Build the edit automaton of a Mealy specification "
                            "(desynchronised reading of simultaneous input "
                            "changes)");
static cl::SubCommand
    enforceCmd("enforce", "Enforce an observed I/O trace (CSV) against a Mealy "
                          "specification and give a verdict");
static cl::SubCommand
    srCmd("sr",
          "Structural reasoning over a model's state space: regions of "
          "selected attributes, attribute graph, densities, necklaces, key "
          "attributes");
static cl::SubCommand checkCmd("check",
                               "Check CTL properties on a model's state space "
                               "(docs/check.md)");
static cl::SubCommand
    composeCmd("compose",
               "Compose a controller and plant models (any input formats) "
               "into one closed-loop system (docs/compose.md)");
static cl::SubCommand emitCmd("emit",
                              "Write a model in another format (net, dot, "
                              "promela, smv, pnml, nces-xml, pnt)");

static cl::list<std::string> translateInputs(cl::Positional,
                                             cl::desc("<input files>"),
                                             cl::OneOrMore,
                                             cl::sub(translateCmd));
// Optional so that `opt --list-passes` needs no input; checked in runOpt.
static cl::opt<std::string> optInput(cl::Positional, cl::desc("<input>"),
                                     cl::sub(optCmd));
static cl::list<std::string> composeInputs(cl::Positional,
                                           cl::desc("<controller> <plant>..."),
                                           cl::OneOrMore, cl::sub(composeCmd));
static cl::opt<std::string> composeConnect(
    "connect", cl::desc("Connections 'a.out -> b.in', one per line"),
    cl::value_desc("FILE"), cl::sub(composeCmd), cl::cat(category));
static cl::opt<std::string> composeMatch(
    "match",
    cl::desc("names: wire inputs still undriven to outputs of the same name "
             "(default without --connect); none: do not"),
    cl::value_desc("names|none"), cl::sub(composeCmd), cl::cat(category));
static cl::list<std::string>
    composeInst("inst",
                cl::desc("A component NAME:MODULE (repeatable; default: every "
                         "module no other instantiates, named in lower case)"),
                cl::value_desc("NAME:MODULE"), cl::sub(composeCmd),
                cl::cat(category));
static cl::opt<std::string>
    composeName("name", cl::desc("Name of the system (default Closed)"),
                cl::value_desc("NAME"), cl::init("Closed"), cl::sub(composeCmd),
                cl::cat(category));
static cl::opt<bool>
    composeQuiet("q",
                 cl::desc("Do not list the wiring, free inputs and unused "
                          "outputs on stderr"),
                 cl::sub(composeCmd), cl::cat(category));
static cl::opt<std::string> emitInput(cl::Positional, cl::desc("<input>"),
                                      cl::Required, cl::sub(emitCmd));
static cl::opt<std::string> mealyInput(cl::Positional, cl::desc("<input>"),
                                       cl::Required, cl::sub(mealyCmd));
enum class MealyFormat { Kiss2, Dot };
static cl::opt<MealyFormat> mealyTo(
    "to", cl::desc("Output format"), cl::init(MealyFormat::Kiss2),
    cl::values(clEnumValN(MealyFormat::Kiss2, "kiss2", "KISS2"),
               clEnumValN(MealyFormat::Dot, "dot", "Graphviz (AALpy style)")),
    cl::sub(mealyCmd), cl::cat(category));
static cl::opt<bool> mealyMinimize("minimize",
                                   cl::desc("Write the minimal equivalent "
                                            "machine"),
                                   cl::sub(mealyCmd), cl::cat(category));
static cl::opt<std::string>
    mealyEquiv("equiv",
               cl::desc("Compare with machine B: exit 0 if equivalent, 3 and a "
                        "shortest distinguishing input sequence if not"),
               cl::value_desc("B"), cl::sub(mealyCmd), cl::cat(category));
static cl::opt<bool> mealyInfo("info",
                               cl::desc("Print signals, states and how "
                                        "complete the machine is"),
                               cl::sub(mealyCmd), cl::cat(category));
static cl::opt<std::string> eaInput(cl::Positional, cl::desc("<spec>"),
                                    cl::Required, cl::sub(eaCmd));
enum class EaFormat { Table, Dot, Json };
static cl::opt<EaFormat> eaTo(
    "to", cl::desc("Output format"), cl::init(EaFormat::Table),
    cl::values(clEnumValN(EaFormat::Table, "table", "one transition a line"),
               clEnumValN(EaFormat::Dot, "dot",
                          "Graphviz (suppressions dashed, intermediate "
                          "states shaded)"),
               clEnumValN(EaFormat::Json, "json",
                          "JSON, read back by enforce and edit-automaton")),
    cl::sub(eaCmd), cl::cat(category));
static cl::opt<bool> delayedOutputs(
    "delayed-outputs",
    cl::desc("Also tolerate outputs that appear one observation after the "
             "inputs that caused them (docs/enforce.md)"),
    cl::sub(eaCmd), cl::sub(enforceCmd), cl::cat(category));
static cl::opt<bool> synchronisedInputs(
    "synchronised-inputs",
    cl::desc("Also tolerate two changes of different inputs read in one scan "
             "(docs/enforce.md)"),
    cl::sub(eaCmd), cl::sub(enforceCmd), cl::cat(category));
static cl::list<std::string> enforceInputs(cl::Positional,
                                           cl::desc("<spec> <trace.csv>"),
                                           cl::OneOrMore, cl::sub(enforceCmd));
static cl::opt<std::string> srInput(cl::Positional, cl::desc("<model>"),
                                    cl::Required, cl::sub(srCmd));
static cl::list<std::string>
    srAttrs("attr",
            cl::desc("An attribute: a place or Boolean signal NAME, or "
                     "NAME=PREDICATE (repeatable)"),
            cl::value_desc("NAME[=PREDICATE]"), cl::sub(srCmd),
            cl::cat(category));
static cl::opt<bool> srAllRegions("all-regions",
                                  cl::desc("Also list regions that never "
                                           "occur"),
                                  cl::sub(srCmd), cl::cat(category));
static cl::opt<std::string> srReport("report",
                                     cl::desc("Report format: text, json or "
                                              "html (one self-contained file)"),
                                     cl::init("text"), cl::sub(srCmd),
                                     cl::cat(category));
static cl::opt<std::string>
    srAg("ag",
         cl::desc("Write the attribute graph as DOT, or as SVG (drawn by "
                  "graphviz's dot) when FILE ends in .svg"),
         cl::value_desc("FILE.dot|FILE.svg"), cl::sub(srCmd),
         cl::cat(category));
static cl::opt<std::string>
    srEv("ev",
         cl::desc("Write the Edwards-Venn diagram as SVG (at most 10 "
                  "attributes)"),
         cl::value_desc("FILE.svg"), cl::sub(srCmd), cl::cat(category));
static cl::opt<std::string>
    srOrder("order",
            cl::desc("Edwards-Venn curves: gray (cos, neighbouring regions "
                     "differ in one attribute) or binary (sin)"),
            cl::init("gray"), cl::sub(srCmd), cl::cat(category));
static cl::opt<std::string> srDensity(
    "density",
    cl::desc("Write the attribute densities and the necklace distribution "
             "as SVG bar charts"),
    cl::value_desc("FILE.svg"), cl::sub(srCmd), cl::cat(category));
static cl::opt<bool>
    srEvNecklaces("ev-necklaces",
                  cl::desc("Colour the Edwards-Venn regions by necklace"),
                  cl::sub(srCmd), cl::cat(category));
static cl::opt<std::string> reachInput(cl::Positional, cl::desc("<input>"),
                                       cl::Required, cl::sub(reachCmd));

static cl::opt<std::string>
    outputFile("o", cl::desc("Output file ('-' = stdout)"),
               cl::value_desc("file"), cl::init("-"), cl::sub(translateCmd),
               cl::sub(composeCmd), cl::sub(optCmd), cl::sub(emitCmd),
               cl::sub(reachCmd), cl::sub(mealyCmd), cl::sub(eaCmd),
               cl::sub(enforceCmd), cl::sub(srCmd), cl::cat(category));
static cl::opt<std::string>
    inputFormat("from", cl::desc("Input format (default: by file extension)"),
                cl::value_desc("format"), cl::sub(translateCmd),
                cl::sub(composeCmd), cl::sub(optCmd), cl::sub(emitCmd),
                cl::sub(reachCmd), cl::sub(mealyCmd), cl::sub(eaCmd),
                cl::sub(enforceCmd), cl::sub(srCmd), cl::sub(checkCmd),
                cl::cat(category));

// Options of the PLC frontends (ST, TwinCAT), for every command that reads
// a model.
static cl::opt<std::string>
    plcTop("top",
           cl::desc("The module to explore; for PLC input also the program, "
                    "program instance or function block to translate"),
           cl::value_desc("NAME"), cl::sub(translateCmd), cl::sub(composeCmd),
           cl::sub(optCmd), cl::sub(emitCmd), cl::sub(reachCmd), cl::sub(srCmd),
           cl::sub(mealyCmd), cl::sub(eaCmd), cl::sub(enforceCmd),
           cl::sub(checkCmd), cl::cat(category));
static cl::alias plcModule("module", cl::desc("Alias for --top"),
                           cl::aliasopt(plcTop));
static cl::opt<std::string> plcTimescale(
    "timescale",
    cl::desc("PLC input: the length of one tick, e.g. 10ms (default: the "
             "greatest common divisor of the program's TIME values)"),
    cl::value_desc("DURATION"), cl::sub(translateCmd), cl::sub(composeCmd),
    cl::sub(optCmd), cl::sub(emitCmd), cl::sub(reachCmd), cl::sub(srCmd),
    cl::sub(mealyCmd), cl::sub(eaCmd), cl::sub(enforceCmd), cl::cat(category));
static cl::opt<std::string> plcScanPeriod(
    "scan-period",
    cl::desc("PLC input: the scan period (default: the task INTERVAL, else "
             "one tick)"),
    cl::value_desc("DURATION"), cl::sub(translateCmd), cl::sub(composeCmd),
    cl::sub(optCmd), cl::sub(emitCmd), cl::sub(reachCmd), cl::sub(srCmd),
    cl::sub(mealyCmd), cl::sub(eaCmd), cl::sub(enforceCmd), cl::cat(category));
static cl::opt<std::string> plcRanges(
    "ranges",
    cl::desc("PLC input: value ranges of integer inputs, one 'NAME LO..HI' "
             "a line"),
    cl::value_desc("FILE"), cl::sub(translateCmd), cl::sub(composeCmd),
    cl::sub(optCmd), cl::sub(emitCmd), cl::sub(reachCmd), cl::sub(srCmd),
    cl::sub(mealyCmd), cl::sub(eaCmd), cl::sub(enforceCmd), cl::cat(category));

static cl::list<std::string> typeLibraries(
    "I",
    cl::desc("IEC 61499 input: a directory searched (with its "
             "subdirectories) for the .fbt/.sub types a network uses"),
    cl::value_desc("DIR"), cl::Prefix, cl::sub(translateCmd),
    cl::sub(composeCmd), cl::sub(optCmd), cl::sub(emitCmd), cl::sub(reachCmd),
    cl::sub(srCmd), cl::sub(mealyCmd), cl::sub(eaCmd), cl::sub(enforceCmd),
    cl::sub(checkCmd), cl::cat(category));

static cl::opt<std::string> fbSemantics(
    "fb-semantics",
    cl::desc("IEC 61499 input: the execution model, forte (default: one "
             "flat module per resource, events in one FIFO as 4diac FORTE "
             "runs them), sequential (modules mirroring the networks, "
             "events of different blocks in any order) or cyclic (fb2smv's "
             "model: blocks take turns in network order, each reacting to "
             "all its pending events at once)"),
    cl::value_desc("MODEL"), cl::sub(translateCmd), cl::sub(composeCmd),
    cl::sub(optCmd), cl::sub(emitCmd), cl::sub(reachCmd), cl::sub(srCmd),
    cl::sub(mealyCmd), cl::sub(eaCmd), cl::sub(enforceCmd), cl::sub(checkCmd),
    cl::cat(category));

// Hidden knobs, so that tests can make small ST inputs take the grouped
// parse of long parts.
static cl::opt<unsigned> stLongPartTokens(
    "st-long-part-tokens", cl::Hidden, cl::init(16384),
    cl::sub(*cl::AllSubCommands),
    cl::desc("ST: parse bodies and VAR blocks of at least this many "
             "tokens in groups"));
static cl::opt<unsigned>
    stGroupTokens("st-group-tokens", cl::Hidden, cl::init(4096),
                  cl::sub(*cl::AllSubCommands),
                  cl::desc("ST: tokens per group of a long body or VAR block"));

/// The frontends' options from the command line.
static FrontendOptions frontendOptionsStorage;
static const FrontendOptions &frontendOptions() {
  return frontendOptionsStorage;
}

/// Collects the frontends' options; false after an error message.
static bool setFrontendOptions() {
  FrontendOptions &fo = frontendOptionsStorage;
  fo.stLongPartTokens = stLongPartTokens;
  fo.stGroupTokens = stGroupTokens;
  fo.top = plcTop;
  fo.rangesFile = plcRanges;
  fo.typeLibraries.assign(typeLibraries.begin(), typeLibraries.end());
  fo.fbSemantics = fbSemantics;
  auto duration = [](const std::string &flag, const std::string &text,
                     std::optional<int64_t> &out) {
    if (text.empty())
      return true;
    int64_t ns;
    std::string error;
    if (!st::parseDuration("T#" + text, ns, error) || ns <= 0) {
      llvm::errs() << "netlift: error: --" << flag << "=" << text
                   << ": expected a positive duration such as 10ms"
                   << (error.empty() ? "" : " (" + error + ")") << "\n";
      return false;
    }
    out = ns;
    return true;
  };
  return duration("timescale", plcTimescale, fo.timescaleNs) &&
         duration("scan-period", plcScanPeriod, fo.scanPeriodNs);
}

static cl::opt<std::string> pipelineText("p",
                                         cl::desc("Pass pipeline, e.g. "
                                                  "'flatten,foo{k=v}'"),
                                         cl::value_desc("pipeline"),
                                         cl::sub(optCmd), cl::cat(category));
static cl::alias pipelineAlias("passes", cl::aliasopt(pipelineText));
static cl::opt<bool> listPasses("list-passes",
                                cl::desc("List the registered passes"),
                                cl::sub(optCmd), cl::cat(category));
static cl::opt<bool> listPassesMarkdown(
    "list-passes-markdown",
    cl::desc("List the registered passes as markdown (docs/passes.md)"),
    cl::sub(optCmd), cl::Hidden);
static cl::opt<bool> verifyEach("verify-each",
                                cl::desc("Verify the IR after every pass"),
                                cl::sub(optCmd), cl::cat(category));
static cl::opt<bool> printAfterAll("print-after-all",
                                   cl::desc("Print the IR after every pass "
                                            "(to stderr)"),
                                   cl::sub(optCmd), cl::cat(category));
static cl::opt<bool> showStats("stats",
                               cl::desc("Print the passes' counters to "
                                        "stderr"),
                               cl::sub(optCmd), cl::cat(category));

enum class EmitFormat { Net, Dot, Promela, Smv, Pnml, NcesXml, Pnt };
static cl::opt<EmitFormat>
    emitFormat("to", cl::desc("Output format"), cl::Required,
               cl::values(clEnumValN(EmitFormat::Net, "net", "NetIR text"),
                          clEnumValN(EmitFormat::Dot, "dot",
                                     "Graphviz drawing of the "
                                     "net"),
                          clEnumValN(EmitFormat::Promela, "promela",
                                     "Promela for spin (the flattened top; "
                                     "--ctl properties as ltl claims)"),
                          clEnumValN(EmitFormat::Smv, "smv",
                                     "SMV for NuSMV/nuXmv (the flattened "
                                     "top; --ctl properties as CTLSPECs)"),
                          clEnumValN(EmitFormat::Pnml, "pnml",
                                     "PNML P/T net (the flattened top; "
                                     "capacities as complementary places)"),
                          clEnumValN(EmitFormat::NcesXml, "nces-xml",
                                     "ViVe NCES XML (the flattened top; no "
                                     "data: lower-data first)"),
                          clEnumValN(EmitFormat::Pnt, "pnt",
                                     "INA/SESA .pnt table (the flattened top; "
                                     "place/transition nets)")),
               cl::sub(emitCmd), cl::cat(category));

static cl::opt<bool> emitModular(
    "modular",
    cl::desc("nces-xml: one FBType file per module in the -o directory, "
             "modules of instances as composite FBTypes (FBNetwork)"),
    cl::sub(emitCmd), cl::cat(category));

enum class GraphFormat { None, Aut, Dot, Json, Csv, Arc };
static cl::opt<GraphFormat> reachFormat(
    "format", cl::desc("Write the state space"), cl::init(GraphFormat::None),
    cl::values(clEnumValN(GraphFormat::Aut, "aut", "Aldebaran .aut"),
               clEnumValN(GraphFormat::Dot, "dot", "Graphviz (small graphs)"),
               clEnumValN(GraphFormat::Json, "json",
                          "every state with its values, every edge"),
               clEnumValN(GraphFormat::Csv, "csv",
                          "every state with its values (edges: --edges)"),
               clEnumValN(GraphFormat::Arc, "arc",
                          "ViVe-style reachability graph text")),
    cl::sub(reachCmd), cl::cat(category));
static cl::opt<std::string>
    reachEdges("edges",
               cl::desc("reach: also write the edges as CSV to FILE; sr: "
                        "read them from FILE (with a CSV state file)"),
               cl::value_desc("FILE"), cl::sub(reachCmd), cl::sub(srCmd),
               cl::cat(category));
static cl::opt<std::string>
    reachSummary("summary",
                 cl::desc("Print a summary: 'json' or 'text' (default)"),
                 cl::init("text"), cl::sub(reachCmd), cl::cat(category));
static cl::opt<std::string>
    reachFind("find",
              cl::desc("Find a shortest path to a state satisfying EXPR"),
              cl::value_desc("EXPR"), cl::sub(reachCmd), cl::cat(category));
static cl::opt<bool>
    reachDeadlockTrace("deadlock-trace",
                       cl::desc("Print a shortest path to a deadlock"),
                       cl::sub(reachCmd), cl::cat(category));
// The exploration set-up: every command that explores or encodes the step
// relation takes the same semantics options, so they mean the same model.
#define NETLIFT_EXPLORING                                                      \
  cl::sub(reachCmd), cl::sub(checkCmd), cl::sub(srCmd), cl::sub(mealyCmd),     \
      cl::sub(eaCmd), cl::sub(enforceCmd)
static cl::opt<sem::StepPolicy> reachPolicy(
    "semantics", cl::desc("Step policy"),
    cl::init(sem::StepPolicy::Interleaving),
    cl::values(clEnumValN(sem::StepPolicy::Interleaving, "interleaving",
                          "one spontaneous transition per step"),
               clEnumValN(sem::StepPolicy::Maximal, "maximal",
                          "a maximal set of spontaneous transitions")),
    NETLIFT_EXPLORING, cl::sub(emitCmd), cl::cat(category));
static cl::opt<sem::Timing> reachTiming(
    "timing", cl::desc("Timing"), cl::init(sem::Timing::Weak),
    cl::values(clEnumValN(sem::Timing::Weak, "weak",
                          "a passed upper bound disables"),
               clEnumValN(sem::Timing::Strong, "strong",
                          "time may not pass an enabled upper bound")),
    NETLIFT_EXPLORING, cl::sub(emitCmd), cl::cat(category));
static cl::opt<uint64_t> reachMaxStates("max-states",
                                        cl::desc("Stop after N states"),
                                        cl::init(0), NETLIFT_EXPLORING,
                                        cl::cat(category));
static cl::opt<std::string> checkInput(cl::Positional, cl::desc("<model>"),
                                       cl::Required, cl::sub(checkCmd));
static cl::list<std::string>
    checkFormulas("ctl",
                  cl::desc("A CTL property (repeatable; with emit --to "
                           "promela, written as an ltl claim)"),
                  cl::value_desc("FORMULA"), cl::sub(checkCmd),
                  cl::sub(emitCmd), cl::cat(category));
static cl::opt<std::string>
    checkTraceDir("trace-dir",
                  cl::desc("Also write each property's trace as "
                           "DIR/p<N>.json and DIR/p<N>.aut"),
                  cl::value_desc("DIR"), cl::sub(checkCmd), cl::cat(category));
static cl::opt<std::string>
    reachMaxMemory("max-memory",
                   cl::desc("Stop above SIZE bytes (suffix K, M, G)"),
                   NETLIFT_EXPLORING, cl::cat(category));
static cl::opt<double> reachTimeLimit("time-limit",
                                      cl::desc("Stop after SECONDS"),
                                      cl::init(0), NETLIFT_EXPLORING,
                                      cl::cat(category));
static cl::opt<bool> reachDfs("dfs", cl::desc("Depth-first order"),
                              cl::sub(reachCmd), cl::cat(category));
static cl::opt<bool> reachQuiet("q", cl::desc("No progress output"),
                                cl::sub(reachCmd), cl::cat(category));
static cl::opt<unsigned> reachPlaceBits(
    "place-bits",
    cl::desc("Bits for the marking of unbounded places (default 8)"),
    cl::init(8), NETLIFT_EXPLORING, cl::sub(emitCmd), cl::cat(category));
static cl::opt<bool> reachInterpreter(
    "interpreter",
    cl::desc("Use the general interpreter even for plain P/T nets (to "
             "cross-check the compiled P/T kernel)"),
    NETLIFT_EXPLORING, cl::cat(category));
#undef NETLIFT_EXPLORING

static bool parseSize(llvm::StringRef text, uint64_t &out);

/// The exploration options of the command line; false after an error.
static bool explorationOptions(statespace::ExplorationOptions &eo,
                               DiagEngine &diag) {
  eo.top = plcTop;
  eo.semantics.policy = reachPolicy;
  eo.semantics.timing = reachTiming;
  eo.semantics.unboundedBits = reachPlaceBits;
  eo.semantics.compilePT = !reachInterpreter;
  eo.maxStates = reachMaxStates;
  eo.timeLimit = reachTimeLimit;
  if (!reachMaxMemory.empty() && !parseSize(reachMaxMemory, eo.maxMemory)) {
    diag.error(llvm::SMLoc(), "--max-memory: '" + reachMaxMemory +
                                  "' is not a size (e.g. 512M, 4G)");
    return false;
  }
  if (reachPlaceBits < 1 || reachPlaceBits > 32) {
    diag.error(llvm::SMLoc(), "--place-bits must be 1..32");
    return false;
  }
  return true;
}

/// Writes through `body` to `path` ("-": stdout) via a temporary file that
/// is renamed into place only when everything was written.
static bool writeOutput(llvm::StringRef path,
                        const std::function<void(llvm::raw_ostream &)> &body) {
  if (path == "-") {
    body(llvm::outs());
    llvm::outs().flush();
    return true;
  }
  // A device or pipe (/dev/null, a FIFO) is written in place: renaming a
  // temporary over it would replace the device with a regular file.
  llvm::sys::fs::file_status st;
  if (!llvm::sys::fs::status(path, st) &&
      st.type() != llvm::sys::fs::file_type::regular_file &&
      st.type() != llvm::sys::fs::file_type::file_not_found) {
    std::error_code ec;
    llvm::raw_fd_ostream os(path, ec);
    if (ec) {
      llvm::errs() << "netlift: error: cannot write '" << path
                   << "': " << ec.message() << "\n";
      return false;
    }
    body(os);
    return true;
  }
  llvm::SmallString<128> tmp;
  int fd;
  std::string model = (path + ".tmp-%%%%%%").str();
  if (std::error_code ec = llvm::sys::fs::createUniqueFile(model, fd, tmp)) {
    llvm::errs() << "netlift: error: cannot write '" << path
                 << "': " << ec.message() << "\n";
    return false;
  }
  {
    llvm::raw_fd_ostream os(fd, /*shouldClose=*/true);
    body(os);
    os.close();
    if (os.has_error()) {
      llvm::errs() << "netlift: error: cannot write '" << path
                   << "': " << os.error().message() << "\n";
      os.clear_error();
      llvm::sys::fs::remove(tmp);
      return false;
    }
  }
  if (std::error_code ec = llvm::sys::fs::rename(tmp, path)) {
    llvm::errs() << "netlift: error: cannot write '" << path
                 << "': " << ec.message() << "\n";
    llvm::sys::fs::remove(tmp);
    return false;
  }
  return true;
}

/// Writes the design as NetIR text to -o; the exit code of the subcommand.
static int writeDesign(const net::Design &design) {
  return writeOutput(
             outputFile,
             [&](llvm::raw_ostream &os) { net::printDesign(design, os); })
             ? 0
             : 1;
}

/// translate, opt and emit write the whole design: `--top` only chooses
/// what a PLC frontend translates. Given with NetIR input alone it would
/// do nothing, so it is refused rather than ignored.
static bool topUsable(const std::vector<std::string> &inputs,
                      llvm::StringRef command) {
  if (plcTop.empty())
    return true;
  for (const std::string &in : inputs)
    if (!(inputFormat == "net" ||
          (inputFormat.empty() && llvm::sys::path::extension(in) == ".net")))
      return true;
  llvm::errs() << "netlift: error: " << command
               << ": --top selects the program a PLC frontend translates; "
                  "NetIR input is written whole (explore one module with "
                  "reach --top, flatten one with opt -p 'flatten{top="
               << plcTop << "}')\n";
  return false;
}

static int runTranslate() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  net::Design design;
  if (!topUsable(translateInputs, "translate") ||
      !loadInputs(translateInputs, inputFormat, frontendOptions(), diag,
                  design))
    return 1;
  return writeDesign(design);
}

static int runCompose() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  ComposeOptions co;
  co.instances = composeInst;
  co.connectFile = composeConnect;
  co.systemName = composeName;
  if (composeMatch == "names")
    co.matchNames = true;
  else if (composeMatch == "none")
    co.matchNames = false;
  else if (!composeMatch.empty()) {
    llvm::errs() << "netlift: error: --match takes names or none\n";
    return 1;
  }
  net::Design design;
  Statistics stats;
  if (!loadInputs(composeInputs, inputFormat, frontendOptions(), diag,
                  design) ||
      !composeSystem(design, diag, co, composeQuiet ? nullptr : &llvm::errs(),
                     stats))
    return 1;
  return writeDesign(design);
}

static int runOpt() {
  if (listPasses || listPassesMarkdown) {
    if (!listPassesMarkdown)
      llvm::outs() << "Passes (use with -p 'a,b{key=value}'):\n";
    printPassList(llvm::outs(), listPassesMarkdown);
    return 0;
  }
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  if (optInput.empty()) {
    llvm::errs() << "netlift: error: opt needs an input file ('-' for "
                    "standard input)\n";
    return 1;
  }
  if (pipelineText.getNumOccurrences() == 0) {
    llvm::errs() << "netlift: error: opt needs a pipeline (-p 'pass,...'); "
                    "netlift opt --list-passes lists the passes\n";
    return 1;
  }
  PassManager pm;
  if (!pm.parsePipeline(pipelineText, diag))
    return 1;
  net::Design design;
  std::vector<std::string> inputs{optInput};
  if (!topUsable(inputs, "opt") ||
      !loadInputs(inputs, inputFormat, frontendOptions(), diag, design))
    return 1;
  pm.verifyEach = verifyEach;
  if (printAfterAll)
    pm.printAfterAll = &llvm::errs();
  bool ok = pm.run(design, diag);
  if (showStats)
    pm.stats.print(llvm::errs());
  if (!ok)
    return 1;
  // The result of a pipeline is always checked before it is written.
  if (!verifyEach && !net::verifyDesign(design, diag)) {
    llvm::errs() << "netlift: error: the pipeline produced invalid IR\n";
    return 1;
  }
  return writeDesign(design);
}

/// Parses the --ctl properties over the flat top (errors point into them).
static bool
parseProperties(DiagEngine &diag, net::Design &design, net::Module &top,
                std::vector<std::unique_ptr<checkers::CtlFormula>> &out) {
  for (size_t i = 0; i < checkFormulas.size(); ++i) {
    unsigned id = diag.sourceMgr().AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(
            checkFormulas[i], "<ctl " + std::to_string(i + 1) + ">"),
        llvm::SMLoc());
    auto f = checkers::parseCtl(id, diag, design, top);
    if (!f)
      return false;
    out.push_back(std::move(f));
  }
  return true;
}

/// `emit --to nces-xml --modular`: the top module and every module it
/// instantiates, each as DIR/<name>.xml, instantiated modules first.
static bool writeNcesModules(net::Design &design, DiagEngine &diag) {
  std::string why;
  net::Module *top = design.findTop(plcTop, why);
  if (!top) {
    llvm::errs() << "netlift: error: emit: " << why << "\n";
    return false;
  }
  // Every file is built before any is written: an error leaves nothing.
  std::vector<std::pair<std::string, std::string>> files; // name, text
  std::set<const net::Module *> done;
  std::function<bool(const net::Module &)> build =
      [&](const net::Module &m) -> bool {
    if (!done.insert(&m).second)
      return true;
    for (const net::Instance &i : m.instances)
      if (!build(*i.module))
        return false;
    std::string text;
    llvm::raw_string_ostream buf(text);
    if (m.instances.empty() ? !nces::writeNcesXml(m, diag, buf)
                            : !nces::writeNcesComposite(m, diag, buf))
      return false;
    files.push_back({m.name.str() + ".xml", buf.str()});
    return true;
  };
  if (!build(*top))
    return false;
  if (std::error_code ec = llvm::sys::fs::create_directories(outputFile)) {
    llvm::errs() << "netlift: error: cannot create '" << outputFile
                 << "': " << ec.message() << "\n";
    return false;
  }
  for (const auto &[name, text] : files) {
    llvm::SmallString<128> path(outputFile.getValue());
    llvm::sys::path::append(path, name);
    if (!writeOutput(path, [&](llvm::raw_ostream &os) { os << text; }))
      return false;
  }
  return true;
}

static int runEmit() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  net::Design design;
  std::vector<std::string> inputs{emitInput};
  bool flatTop = emitFormat != EmitFormat::Net && emitFormat != EmitFormat::Dot;
  if (!checkFormulas.empty() && emitFormat != EmitFormat::Promela &&
      emitFormat != EmitFormat::Smv) {
    llvm::errs() << "netlift: error: --ctl goes with emit --to promela or "
                    "smv (or netlift check)\n";
    return 1;
  }
  if (emitModular && (emitFormat != EmitFormat::NcesXml || outputFile.empty() ||
                      outputFile == "-")) {
    llvm::errs() << "netlift: error: --modular goes with --to nces-xml and "
                    "-o DIRECTORY\n";
    return 1;
  }
  if ((!flatTop && !topUsable(inputs, "emit")) ||
      !loadInputs(inputs, inputFormat, frontendOptions(), diag, design))
    return 1;
  if (emitModular)
    return writeNcesModules(design, diag) ? 0 : 1;
  if (flatTop) {
    // Checker formats take the flattened top module.
    statespace::ExplorationOptions xo;
    if (!explorationOptions(xo, diag))
      return 1;
    auto setup = statespace::ExplorationSetup::create(design, xo, diag, "emit");
    if (!setup)
      return 1;
    net::Module *top = &setup->top();
    std::string text;
    llvm::raw_string_ostream buf(text);
    if (emitFormat == EmitFormat::Pnml) {
      if (!checkers::writePnml(*top, diag, buf))
        return 1;
    } else if (emitFormat == EmitFormat::NcesXml) {
      if (!nces::writeNcesXml(*top, diag, buf))
        return 1;
    } else if (emitFormat == EmitFormat::Pnt) {
      if (!nces::writePnt(*top, diag, buf))
        return 1;
    } else {
      std::vector<std::unique_ptr<checkers::CtlFormula>> formulas;
      if (!parseProperties(diag, design, *top, formulas))
        return 1;
      std::vector<const checkers::CtlFormula *> properties;
      for (const auto &f : formulas)
        properties.push_back(f.get());
      if (emitFormat == EmitFormat::Smv
              ? !checkers::writeSmv(setup->semantics(), diag, buf, properties)
              : !checkers::writePromela(setup->semantics(), diag, buf,
                                        properties))
        return 1;
    }
    return writeOutput(outputFile, [&](llvm::raw_ostream &os) { os << text; })
               ? 0
               : 1;
  }
  return writeOutput(outputFile,
                     [&](llvm::raw_ostream &os) {
                       switch (emitFormat) {
                       case EmitFormat::Net:
                         net::printDesign(design, os);
                         break;
                       case EmitFormat::Dot:
                         writeDot(design, os);
                         break;
                       case EmitFormat::Promela:
                       case EmitFormat::Smv:
                       case EmitFormat::Pnml:
                       case EmitFormat::NcesXml:
                       case EmitFormat::Pnt:
                         break; // above
                       }
                     })
             ? 0
             : 1;
}

/// Reads the specification of mealy, edit-automaton and enforce: a
/// deterministic KISS2 machine, or any model (a PLC program, NetIR ...)
/// whose controller's Mealy machine is extracted (docs/enforce.md).
static bool readMealy(const std::string &path, DiagEngine &diag,
                      automata::MealyMachine &m) {
  llvm::SourceMgr &sm = diag.sourceMgr();
  llvm::StringRef ext = llvm::sys::path::extension(path);
  bool isKiss = inputFormat == "kiss2" ||
                (inputFormat.empty() &&
                 (ext == ".kiss2" || ext == ".kiss" || ext == ".kis"));
  if (isKiss) {
    unsigned id = addInputFile(sm, path);
    if (!id)
      return false;
    return readKiss2(id, diag, m) && m.checkDeterminism(diag);
  }
  if (inputFormat == "dot" || (inputFormat.empty() && ext == ".dot")) {
    unsigned id = addInputFile(sm, path);
    if (!id)
      return false;
    return readMealyDot(id, diag, m) && m.checkDeterminism(diag);
  }
  net::Design design;
  std::vector<std::string> inputs{path};
  if (!loadInputs(inputs, inputFormat, frontendOptions(), diag, design))
    return false;
  statespace::ExplorationOptions xo;
  if (!explorationOptions(xo, diag))
    return false;
  auto setup = statespace::ExplorationSetup::create(design, xo, diag, "mealy");
  if (!setup)
    return false;
  MealyExtractOptions opts;
  if (xo.maxStates)
    opts.maxStates = uint32_t(std::min<uint64_t>(xo.maxStates, UINT32_MAX));
  return extractMealy(setup->semantics(), opts, diag, m);
}

static int runMealy() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  auto read = [&](const std::string &path, automata::MealyMachine &m) {
    return readMealy(path, diag, m);
  };
  automata::MealyMachine m;
  if (!read(mealyInput, m))
    return 1;
  std::string why;
  if (!mealyEquiv.empty()) {
    automata::MealyMachine other;
    if (!read(mealyEquiv, other))
      return 1;
    automata::EquivalenceResult r;
    if (!automata::alignAlphabets(m, other, why) ||
        !automata::checkEquivalence(m, other, r, why)) {
      llvm::errs() << "netlift: error: " << why << "\n";
      return 1;
    }
    if (r.equivalent) {
      llvm::outs() << "equivalent\n";
      return 0;
    }
    llvm::outs() << "not equivalent: after the inputs";
    for (const std::string &v : r.witness)
      llvm::outs() << ' ' << m.inputLabel(v);
    llvm::outs() << " the outputs are " << m.outputLabel(r.outputA) << " and "
                 << m.outputLabel(r.outputB) << "\n";
    return 3;
  }
  if (mealyMinimize) {
    automata::MealyMachine minimal;
    if (!automata::minimize(m, minimal, why)) {
      llvm::errs() << "netlift: error: " << why << "\n";
      return 1;
    }
    m = std::move(minimal);
  }
  if (mealyInfo) {
    std::vector<int64_t> missing = m.unspecifiedVectors();
    int64_t incomplete = 0;
    for (int64_t n : missing)
      incomplete += n > 0;
    if (m.isSymbolic())
      llvm::errs() << "input symbols: " << m.inputSymbols.size()
                   << ", output symbols: " << m.outputSymbols.size() << ", ";
    llvm::errs() << "inputs: " << m.inputs.size()
                 << ", outputs: " << m.outputs.size()
                 << ", states: " << m.states.size()
                 << ", transitions: " << m.transitions.size()
                 << ", initial: " << m.states[m.initial] << "\n";
    if (!missing.empty() && missing[0] < 0)
      llvm::errs() << "completeness: not checked (more than 24 inputs)\n";
    else if (incomplete == 0)
      llvm::errs() << "completeness: complete\n";
    else
      for (size_t s = 0; s < missing.size(); ++s)
        if (missing[s] > 0)
          llvm::errs() << "state " << m.states[s] << ": " << missing[s]
                       << (m.isSymbolic() ? " input symbols" : " input vectors")
                       << " unspecified\n";
  }
  return writeOutput(outputFile,
                     [&](llvm::raw_ostream &os) {
                       if (mealyTo == MealyFormat::Kiss2)
                         writeKiss2(m, os);
                       else
                         writeMealyDot(m, os);
                     })
             ? 0
             : 1;
}

/// Reads an edit automaton written as JSON, or a Mealy specification and
/// builds its edit automaton.
static bool specAutomaton(const std::string &path, DiagEngine &diag,
                          automata::EditAutomaton &ea) {
  if (inputFormat == "json" ||
      (inputFormat.empty() && llvm::sys::path::extension(path) == ".json")) {
    if (delayedOutputs || synchronisedInputs) {
      llvm::errs() << "netlift: error: " << path
                   << " is a built edit automaton: the phenomena it tolerates "
                      "were chosen when it was built\n";
      return false;
    }
    unsigned id = addInputFile(diag.sourceMgr(), path);
    return id && readEditAutomatonJson(id, diag, ea);
  }
  automata::MealyMachine m;
  if (!readMealy(path, diag, m))
    return false;
  std::string why;
  if (m.isSymbolic()) {
    llvm::errs() << "netlift: error: " << path
                 << " reads input symbols, not Boolean signals: the PLC's "
                    "desynchronised reading is defined per input signal\n";
    return false;
  }
  automata::EditAutomatonOptions opts;
  opts.delayedOutputs = delayedOutputs;
  opts.synchronisedInputs = synchronisedInputs;
  if (!automata::buildEditAutomaton(m, ea, why, opts)) {
    llvm::errs() << "netlift: error: " << why << "\n";
    return false;
  }
  return true;
}

static int runEditAutomaton() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  automata::EditAutomaton ea;
  if (!specAutomaton(eaInput, diag, ea))
    return 1;
  return writeOutput(outputFile,
                     [&](llvm::raw_ostream &os) {
                       if (eaTo == EaFormat::Dot)
                         writeEditAutomatonDot(ea, os);
                       else if (eaTo == EaFormat::Json)
                         writeEditAutomatonJson(ea, os);
                       else
                         writeEditAutomatonTable(ea, os);
                     })
             ? 0
             : 1;
}

/// Exit 0 conform, 3 not conform, 1 error.
static int runEnforce() {
  if (enforceInputs.size() != 2) {
    llvm::errs() << "netlift: error: enforce needs a specification and a "
                    "trace: netlift enforce SPEC.kiss2 TRACE.csv\n";
    return 1;
  }
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  automata::EditAutomaton ea;
  if (!specAutomaton(enforceInputs[0], diag, ea))
    return 1;
  unsigned id = addInputFile(sm, enforceInputs[1]);
  if (!id)
    return 1;
  EnforceResult r;
  uint64_t emitted = 0;
  llvm::raw_ostream &out = llvm::outs();
  // Stream: each enforced vector is written as it is emitted, to stdout and
  // to -o (a temporary renamed into place at the end).
  auto run = [&](llvm::raw_ostream *csv) {
    if (csv) {
      for (size_t i = 0; i < ea.signals.size(); ++i)
        *csv << (i ? "," : "") << ea.signals[i];
      *csv << "\n";
    }
    return enforceTrace(
        ea, id, diag,
        [&](const std::string &v) {
          ++emitted;
          out << v << "\n";
          if (csv) {
            for (size_t i = 0; i < v.size(); ++i)
              *csv << (i ? "," : "") << v[i];
            *csv << "\n";
          }
        },
        r);
  };
  bool ok = true;
  if (outputFile == "-")
    ok = run(nullptr);
  else if (!writeOutput(outputFile,
                        [&](llvm::raw_ostream &os) { ok = run(&os); }))
    return 1;
  if (!ok) {
    if (outputFile != "-")
      llvm::sys::fs::remove(outputFile);
    return 1;
  }
  if (r.conform) {
    out << "verdict: conform (" << r.vectors << " vectors read, " << emitted
        << " emitted)\n";
    return 0;
  }
  if (r.stopped) {
    out << "verdict: not conform: stopped at vector " << r.stopIndex << " ("
        << r.stopVector << "); expected one of:";
    for (const std::string &e : r.expected)
      out << ' ' << e;
    out << "\n";
  } else {
    out << "verdict: not conform: the trace ends inside a desynchronised "
           "reading (an intermediate state)\n";
  }
  return 3;
}

static bool parseSize(llvm::StringRef text, uint64_t &out) {
  uint64_t mult = 1;
  if (text.endswith_insensitive("k"))
    mult = 1ull << 10;
  else if (text.endswith_insensitive("m"))
    mult = 1ull << 20;
  else if (text.endswith_insensitive("g"))
    mult = 1ull << 30;
  if (mult != 1)
    text = text.drop_back();
  if (text.getAsInteger(10, out))
    return false;
  out *= mult;
  return true;
}

/// The attribute graph as SVG by graphviz's `dot`, or "" when it is not
/// installed or fails (the report then shows the DOT text).
static std::string renderWithGraphviz(const structural::Analysis &an,
                                      bool allRegions) {
  llvm::ErrorOr<std::string> dot = llvm::sys::findProgramByName("dot");
  if (!dot)
    return "";
  llvm::SmallString<128> in, out;
  if (llvm::sys::fs::createTemporaryFile("netlift-ag", "dot", in) ||
      llvm::sys::fs::createTemporaryFile("netlift-ag", "svg", out))
    return "";
  {
    std::error_code ec;
    llvm::raw_fd_ostream os(in, ec);
    if (ec)
      return "";
    an.writeDot(os, allRegions);
  }
  llvm::StringRef args[] = {*dot, "-Tsvg", in};
  llvm::Optional<llvm::StringRef> redirects[] = {
      llvm::None, llvm::StringRef(out), llvm::StringRef("")};
  int rc = llvm::sys::ExecuteAndWait(*dot, args, llvm::None, redirects);
  std::string svg;
  if (rc == 0)
    if (auto buf = llvm::MemoryBuffer::getFile(out))
      svg = (*buf)->getBuffer().str();
  llvm::sys::fs::remove(in);
  llvm::sys::fs::remove(out);
  return svg;
}

/// `netlift sr`: explores the model and classifies every state by the
/// selected attributes (docs/sr.md).
static int runSr() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  if (srAttrs.empty() || srAttrs.size() > 20) {
    llvm::errs() << "netlift: error: sr needs 1 to 20 attributes (--attr)\n";
    return 1;
  }
  if (srReport != "text" && srReport != "json" && srReport != "html") {
    llvm::errs() << "netlift: error: --report is text, json or html\n";
    return 1;
  }
  if (srOrder != "gray" && srOrder != "binary") {
    llvm::errs() << "netlift: error: --order is gray or binary\n";
    return 1;
  }
  if (!srEv.empty() && srAttrs.size() > structural::kMaxVennAttributes) {
    llvm::errs() << "netlift: error: an Edwards-Venn diagram is drawn for at "
                    "most "
                 << structural::kMaxVennAttributes << " attributes, not "
                 << srAttrs.size() << "\n";
    return 1;
  }
  // Each attribute: NAME alone, or NAME=PREDICATE, parsed as NetIR.
  net::Design design;
  std::vector<std::string> names;
  std::vector<net::Expr *> preds;
  std::vector<bool> plain;
  for (const std::string &a : srAttrs) {
    auto [name, pred] = llvm::StringRef(a).split('=');
    name = name.trim();
    llvm::StringRef text = pred.empty() ? name : pred.trim();
    unsigned id = sm.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(text, "<attr " + name.str() + ">"),
        llvm::SMLoc());
    net::Expr *e = net::parseExpression(id, diag, design);
    if (!e)
      return 1;
    names.push_back(name.str());
    preds.push_back(e);
    plain.push_back(pred.empty());
  }
  structural::Analysis an(names);
  structural::HtmlReportInputs html;
  html.title = llvm::sys::path::filename(srInput).str();
  bool complete = true;

  llvm::StringRef ext = llvm::sys::path::extension(srInput);
  bool csv =
      inputFormat == "states-csv" || (inputFormat.empty() && ext == ".csv");
  bool stateFile =
      csv || inputFormat == "states" || (inputFormat.empty() && ext == ".json");
  if (!reachEdges.empty() && !csv) {
    llvm::errs() << "netlift: error: --edges goes with a CSV state file\n";
    return 1;
  }
  if (stateFile) {
    // A state space written by `reach --format json|csv`, streamed.
    unsigned id = addInputFile(sm, srInput);
    unsigned edgesID = reachEdges.empty() ? 0 : addInputFile(sm, reachEdges);
    if (!id || (!reachEdges.empty() && !edgesID))
      return 1;
    std::vector<structural::StateFileAttribute> attrs;
    for (size_t i = 0; i < names.size(); ++i)
      attrs.push_back({names[i], plain[i] ? nullptr : preds[i]});
    structural::StateFileResult sr;
    sr.collectExamples = srReport == "html";
    if (csv ? !structural::analyseStateCsv(id, edgesID, diag, attrs, an, sr)
            : !structural::analyseStateFile(id, diag, attrs, an, sr))
      return 1;
    complete = sr.complete;
    html.examples = std::move(sr.examples);
  } else {
    std::vector<std::string> inputs{srInput};
    if (!loadInputs(inputs, inputFormat, frontendOptions(), diag, design))
      return 1;
    statespace::ExplorationOptions xo;
    if (!explorationOptions(xo, diag))
      return 1;
    auto setup = statespace::ExplorationSetup::create(design, xo, diag, "sr");
    if (!setup)
      return 1;
    for (net::Expr *e : preds)
      if (!net::verifyPredicate(design, setup->top(), e, diag))
        return 1;
    sem::Semantics &semantics = setup->semantics();
    statespace::ExploreOptions eo = setup->exploreOptions();
    eo.recordEdges = true;
    statespace::Explorer explorer(semantics, eo);
    statespace::ExploreResult r;
    bool started = explorer.run(r);
    if (r.error) {
      statespace::reportRuntimeError(r, started, explorer, semantics, diag);
      return 1;
    }
    complete = r.complete;
    // Region of every state, then the counts (memory: one word per state
    // here; the counts themselves are per region).
    std::vector<structural::Region> region(explorer.store().size());
    for (uint32_t s = 0; s < region.size(); ++s)
      for (size_t i = 0; i < preds.size(); ++i) {
        sem::RuntimeError err;
        if (semantics.evalPredicate(preds[i], explorer.store().state(s), err))
          region[s] |= structural::Region(1) << i;
      }
    std::vector<char> dead(region.size(), 0);
    for (uint32_t d : r.deadlocks)
      dead[d] = 1;
    for (uint32_t s = 0; s < region.size(); ++s)
      an.addState(region[s], dead[s]);
    for (const statespace::Edge &e : explorer.edges())
      an.addEdge(region[e.from], region[e.to]);
    // The first state (in discovery order) of each region is its example.
    if (srReport == "html")
      for (uint32_t s = 0; s < region.size(); ++s)
        if (!html.examples.count(region[s]))
          html.examples[region[s]] = statespace::describeState(
              semantics, explorer.store().state(s), ", ");
  }

  if (!srAg.empty()) {
    std::string svg;
    if (llvm::StringRef(srAg).endswith(".svg")) {
      svg = renderWithGraphviz(an, srAllRegions);
      if (svg.empty()) {
        llvm::errs() << "netlift: error: --ag " << srAg
                     << ": drawing SVG needs graphviz's `dot` (write .dot "
                        "instead)\n";
        return 1;
      }
    }
    if (!writeOutput(srAg, [&](llvm::raw_ostream &os) {
          if (svg.empty())
            an.writeDot(os, srAllRegions);
          else
            os << svg;
        }))
      return 1;
  }
  if (!srDensity.empty() && !writeOutput(srDensity, [&](llvm::raw_ostream &os) {
        structural::writeDensityChart(an, os);
      }))
    return 1;
  structural::VennOptions vo;
  vo.grayOrder = srOrder == "gray";
  vo.necklaces = srEvNecklaces;
  if (!srEv.empty()) {
    if (!writeOutput(srEv, [&](llvm::raw_ostream &os) {
          structural::writeEdwardsVenn(an, vo, os);
        }))
      return 1;
    for (structural::Region r : structural::undrawnRegions(an, vo.grayOrder))
      llvm::errs() << "netlift: warning: the binary-order diagram has no area "
                      "for region "
                   << an.regionName(r) << " (" << an.regionCounts().at(r)
                   << " states); --order gray draws every region\n";
  }
  if (srReport == "html") {
    html.venn = vo;
    html.attributeGraphSvg = renderWithGraphviz(an, false);
  }
  if (!writeOutput(outputFile, [&](llvm::raw_ostream &os) {
        if (srReport == "html")
          structural::writeHtmlReport(an, html, os);
        else if (srReport == "json")
          an.writeJson(os, srAllRegions);
        else
          an.writeText(os, srAllRegions);
      }))
    return 1;
  return complete ? 0 : 2;
}

/// Writes a property's trace as `BASE.json` (formula, verdict, the states
/// by id as `reach` numbers them, the step labels, the loop) and
/// `BASE.aut` (the path as an Aldebaran graph, the loop as an edge back).
static bool writeTraceFiles(const std::string &base,
                            const checkers::CtlFormula &f, bool holds,
                            const checkers::CtlTrace &t,
                            llvm::ArrayRef<std::pair<uint32_t, uint32_t>> steps,
                            uint32_t loopLabel, const statespace::Explorer &x) {
  auto label = [&](uint32_t l) {
    return l == statespace::Explorer::kNone ? std::string("tau") : x.label(l);
  };
  bool ok = writeOutput(base + ".json", [&](llvm::raw_ostream &os) {
    llvm::json::OStream j(os, 1);
    j.object([&] {
      j.attribute("formula", checkers::ctlToString(f));
      j.attribute("holds", holds);
      j.attribute("trace", t.witness ? "witness" : "counterexample");
      j.attribute("claim", t.claim);
      j.attributeArray("states", [&] {
        for (const auto &step : steps)
          j.value(int64_t(step.second));
      });
      j.attributeArray("labels", [&] {
        for (size_t i = 1; i < steps.size(); ++i)
          j.value(label(steps[i].first));
      });
      if (t.loopTo >= 0) {
        j.attribute("loop_to", t.loopTo);
        j.attribute("loop_label", label(loopLabel));
      } else {
        j.attribute("loop_to", nullptr);
      }
    });
    os << "\n";
  });
  // The path as an Aldebaran graph, labels as `reach --format aut` writes
  // them.
  ok = ok && writeOutput(base + ".aut", [&](llvm::raw_ostream &os) {
         size_t edges = steps.size() - 1 + (t.loopTo >= 0);
         os << "des (0, " << edges << ", " << steps.size() << ")\n";
         for (size_t i = 1; i < steps.size(); ++i)
           os << "(" << i - 1 << ",\"" << label(steps[i].first) << "\"," << i
              << ")\n";
         if (t.loopTo >= 0)
           os << "(" << steps.size() - 1 << ",\"" << label(loopLabel) << "\","
              << t.loopTo << ")\n";
       });
  return ok;
}

/// `netlift check`: explores the model, then checks each CTL property on
/// the state space (docs/check.md). Exit 0 all hold, 3 some fail, 2 the
/// exploration was stopped by a limit, 1 an error.
static int runCheck() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  if (checkFormulas.empty()) {
    llvm::errs() << "netlift: error: check needs a property (--ctl FORMULA)\n";
    return 1;
  }
  net::Design design;
  std::vector<std::string> inputs{checkInput};
  if (!loadInputs(inputs, inputFormat, frontendOptions(), diag, design))
    return 1;
  statespace::ExplorationOptions xo;
  if (!explorationOptions(xo, diag))
    return 1;
  auto setup = statespace::ExplorationSetup::create(design, xo, diag, "check");
  if (!setup)
    return 1;
  std::vector<std::unique_ptr<checkers::CtlFormula>> formulas;
  if (!parseProperties(diag, design, setup->top(), formulas))
    return 1;
  sem::Semantics &semantics = setup->semantics();
  statespace::ExploreOptions eo = setup->exploreOptions();
  eo.recordEdges = true;
  statespace::Explorer explorer(semantics, eo);
  statespace::ExploreResult r;
  bool started = explorer.run(r);
  if (r.error) {
    statespace::reportRuntimeError(r, started, explorer, semantics, diag);
    return 1;
  }
  if (!r.complete) {
    llvm::outs() << "undecided: the exploration stopped at a limit ("
                 << explorer.store().size() << " states)\n";
    return 2;
  }
  // The graph in CSR form, edges of one state together.
  checkers::CtlGraph g;
  size_t n = explorer.store().size();
  g.deadlock.assign(n, 0);
  for (uint32_t d : r.deadlocks)
    g.deadlock[d] = 1;
  g.succStart.assign(n + 1, 0);
  for (const statespace::Edge &e : explorer.edges())
    ++g.succStart[e.from + 1];
  for (size_t i = 0; i < n; ++i)
    g.succStart[i + 1] += g.succStart[i];
  g.succ.resize(explorer.edges().size());
  g.succLabel.resize(explorer.edges().size());
  std::vector<uint32_t> fill(g.succStart.begin(), g.succStart.end() - 1);
  for (const statespace::Edge &e : explorer.edges()) {
    g.succLabel[fill[e.from]] = e.label;
    g.succ[fill[e.from]++] = e.to;
  }
  sem::RuntimeError err;
  auto atomValue = [&](const net::Expr *e, uint32_t s) {
    return semantics.evalPredicate(e, explorer.store().state(s), err);
  };
  bool allHold = true;
  if (!checkTraceDir.empty())
    if (std::error_code ec = llvm::sys::fs::create_directories(checkTraceDir)) {
      llvm::errs() << "netlift: error: cannot create '" << checkTraceDir
                   << "': " << ec.message() << "\n";
      return 1;
    }
  unsigned index = 0;
  for (const auto &f : formulas) {
    ++index;
    std::vector<uint8_t> sat = checkers::evaluateCtl(*f, g, atomValue);
    bool holds = sat[0];
    allHold = allHold && holds;
    llvm::outs() << checkers::ctlToString(*f) << ": "
                 << (holds ? "holds" : "fails") << "\n";
    std::optional<checkers::CtlTrace> trace =
        checkers::ctlTrace(*f, g, atomValue);
    if (!trace)
      continue;
    // The label of each step: the first edge between the two states.
    auto labelOf = [&](uint32_t from, uint32_t to) {
      for (uint32_t k = g.succStart[from]; k < g.succStart[from + 1]; ++k)
        if (g.succ[k] == to)
          return g.succLabel[k];
      return statespace::Explorer::kNone;
    };
    std::vector<std::pair<uint32_t, uint32_t>> steps;
    for (size_t i = 0; i < trace->states.size(); ++i)
      steps.push_back({i ? labelOf(trace->states[i - 1], trace->states[i])
                         : statespace::Explorer::kNone,
                       trace->states[i]});
    llvm::outs() << (trace->witness ? "witness: " : "counterexample: ")
                 << trace->claim << "\n";
    uint32_t loopLabel =
        trace->loopTo >= 0
            ? labelOf(trace->states.back(), trace->states[trace->loopTo])
            : statespace::Explorer::kNone;
    statespace::writePath(explorer, semantics, steps, llvm::outs(),
                          trace->loopTo, loopLabel);
    if (!checkTraceDir.empty()) {
      std::string base = checkTraceDir + "/p" + std::to_string(index);
      if (!writeTraceFiles(base, *f, holds, *trace, steps, loopLabel, explorer))
        return 1;
    }
  }
  if (!err.message.empty()) {
    llvm::errs() << "netlift: error: runtime error in a property: "
                 << err.message << "\n";
    return 1;
  }
  return allHold ? 0 : 3;
}

/// Exit codes of `reach` (docs/reach.md): 0 complete, 1 error, 2 a limit
/// stopped the search, 3 the property checked is violated.
static int runReach() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  net::Design design;
  std::vector<std::string> inputs{reachInput};
  if (!loadInputs(inputs, inputFormat, frontendOptions(), diag, design))
    return 1;
  statespace::ExplorationOptions xo;
  if (!explorationOptions(xo, diag))
    return 1;
  auto setup = statespace::ExplorationSetup::create(design, xo, diag, "reach");
  if (!setup)
    return 1;
  net::Module *top = &setup->top();
  sem::Semantics &semantics = setup->semantics();

  net::Expr *findExpr = nullptr;
  if (!reachFind.empty()) {
    unsigned id = sm.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(reachFind, "<find>"),
        llvm::SMLoc());
    findExpr = net::parseExpression(id, diag, design);
    if (!findExpr || !net::verifyPredicate(design, *top, findExpr, diag))
      return 1;
  }
  statespace::ExploreOptions eo = setup->exploreOptions();
  eo.depthFirst = reachDfs;
  eo.recordEdges = reachFormat != GraphFormat::None || !reachEdges.empty();
  eo.progress = !reachQuiet;
  sem::RuntimeError findErr;
  auto stop = [&](const uint64_t *s) {
    return semantics.evalPredicate(findExpr, s, findErr);
  };
  if (findExpr)
    eo.stopAt = stop;
  statespace::Explorer explorer(semantics, eo);
  statespace::ExploreResult r;
  bool started = explorer.run(r);
  if (r.error) {
    statespace::reportRuntimeError(r, started, explorer, semantics, diag);
    return 1;
  }
  if (!writeOutput(outputFile, [&](llvm::raw_ostream &os) {
        switch (reachFormat) {
        case GraphFormat::None:
          break;
        case GraphFormat::Aut:
          statespace::writeAut(explorer, os);
          break;
        case GraphFormat::Dot:
          statespace::writeDot(explorer, semantics, os);
          break;
        case GraphFormat::Json:
          statespace::writeJson(explorer, semantics, r, os);
          break;
        case GraphFormat::Csv:
          statespace::writeCsvStates(explorer, semantics, r, os);
          break;
        case GraphFormat::Arc:
          statespace::writeArc(explorer, semantics, os);
          break;
        }
      }))
    return 1;
  if (!reachEdges.empty() &&
      !writeOutput(reachEdges, [&](llvm::raw_ostream &os) {
        statespace::writeCsvEdges(explorer, os);
      }))
    return 1;
  llvm::raw_ostream &out = llvm::outs();
  if (reachSummary == "json") {
    statespace::writeSummaryJson(explorer, r, out);
  } else if (reachFormat == GraphFormat::None && !findExpr &&
             !reachDeadlockTrace) {
    out << "states: " << explorer.store().size() << "\n"
        << "transitions: " << r.edges << "\n"
        << "deadlocks: " << r.deadlocks.size() << "\n"
        << "dead states: " << r.deadStates << "\n"
        << "complete: " << (r.complete ? "yes" : "no") << "\n";
  }
  int code = r.limitReached.empty() ? 0 : 2;
  if (!r.limitReached.empty())
    llvm::errs() << "netlift: the " << r.limitReached
                 << " limit stopped the search; the result is incomplete\n";
  if (findExpr) {
    if (r.found) {
      out << "found a state satisfying '" << reachFind << "' after "
          << explorer.pathTo(*r.found).size() - 1 << " steps:\n";
      statespace::writeTrace(explorer, semantics, *r.found, out);
      return 0;
    }
    if (code == 0) {
      out << "no reachable state satisfies '" << reachFind << "'\n";
      return 3;
    }
  }
  if (reachDeadlockTrace) {
    if (!r.deadlocks.empty()) {
      // Breadth-first numbering: the smallest index is a closest deadlock.
      uint32_t d = *std::min_element(r.deadlocks.begin(), r.deadlocks.end());
      out << "deadlock after " << explorer.pathTo(d).size() - 1 << " steps:\n";
      statespace::writeTrace(explorer, semantics, d, out);
      return 3;
    }
    if (code == 0)
      out << "no deadlock\n";
  }
  return code;
}

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  cl::SetVersionPrinter([](llvm::raw_ostream &os) {
    os << "netlift " << NETLIFT_VERSION << "\n";
  });
  cl::HideUnrelatedOptions({&category});
  if (!cl::ParseCommandLineOptions(
          argc, argv,
          "netlift: lift industrial control software into formal models\n\n"
          "  netlift translate IN... [-o OUT] [--from FMT] [--top NAME] "
          "[--timescale 10ms] [--ranges FILE]\n"
          "  netlift opt IN -p PIPELINE [-o OUT] [--verify-each] "
          "[--print-after-all] [--stats]\n"
          "  netlift compose CTRL PLANT... [--connect FILE] [--match "
          "names|none] [--inst NAME:MODULE]... [-o OUT]\n"
          "  netlift emit IN --to net|dot|promela|smv|pnml|nces-xml|pnt [-o "
          "OUT]\n"
          "  netlift reach IN [--format aut|dot|json|csv|arc] [-o OUT] "
          "[--summary "
          "json] [--find EXPR]\n"
          "  netlift mealy IN.kiss2|IN.dot|MODEL [--to kiss2|dot] [-o OUT] "
          "[--info] "
          "[--minimize]\n"
          "  netlift edit-automaton SPEC [--to table|dot|json] [-o OUT]\n"
          "  netlift enforce SPEC TRACE.csv [-o ENFORCED.csv]\n"
          "  netlift check MODEL --ctl FORMULA...\n"
          "  netlift sr MODEL --attr NAME[=PRED]... [--report text|json|html] "
          "[--ev "
          "F.svg] "
          "[--ag FILE.dot]\n\n"
          "Run 'netlift <subcommand> --help' for a subcommand's options.\n",
          &llvm::errs()))
    return 1;
  if (!setFrontendOptions())
    return 1;
  if (translateCmd)
    return runTranslate();
  if (optCmd)
    return runOpt();
  if (composeCmd)
    return runCompose();
  if (emitCmd)
    return runEmit();
  if (reachCmd)
    return runReach();
  if (mealyCmd)
    return runMealy();
  if (eaCmd)
    return runEditAutomaton();
  if (enforceCmd)
    return runEnforce();
  if (srCmd)
    return runSr();
  if (checkCmd)
    return runCheck();
  llvm::errs()
      << "netlift: error: no subcommand given (translate, opt, "
         "compose, emit, reach, check, sr, mealy, edit-automaton, enforce); "
         "see netlift --help\n";
  return 1;
}
