//===- ExplorationOptions.cpp - the options of every exploring command ----===//
//
// Declared once and attached to every exploring subcommand of the table
// (exploringCommands); explorationOptions fills engine::ExplorationOptions
// from them.
//
//===----------------------------------------------------------------------===//
#include "tools/netlift/Driver.h"

using namespace netlift;
using namespace netlift::driver;

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
