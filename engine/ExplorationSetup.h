//===- ExplorationSetup.h - one state space for every command ---*- C++ -*-===//
//
// What decides which state space a command means: the module explored
// (the design's top or --top, flattened when it has instances, refused
// while it still has hybrid parts), the semantics options (step policy,
// timing, place bits, kernel) and the exploration limits. Every command
// that explores or encodes the step relation — reach, check, sr, mealy and
// the Promela and SMV exports — builds its Semantics through one
// ExplorationSetup from one ExplorationOptions, so that a property checked
// and a state space explored are always about the same model.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_EXPLORATIONSETUP_H
#define NETLIFT_ENGINE_EXPLORATIONSETUP_H

#include "engine/Explorer.h"
#include "engine/Semantics.h"
#include "engine/StateLayout.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "passes/AbstractTimers.h"

#include <memory>
#include <set>
#include <string>
#include <vector>

namespace netlift::engine {

/// The options every exploring command takes alike.
struct ExplorationOptions {
  /// --top: the module explored (empty: the design's top module).
  std::string top;
  /// --semantics, --timing, --place-bits, --interpreter.
  sem::Options semantics;
  /// --max-states, --max-memory, --time-limit (0: no limit).
  uint64_t maxStates = 0;
  uint64_t maxMemory = 0;
  double timeLimit = 0;
  /// The command enumerates the free inputs' values (explicit-state
  /// exploration): an input that still needs a range is refused.
  bool enumeratesInputs = true;
  /// --timers=abstract: the clock variables only compared stop counting
  /// time (passes/AbstractTimers.h), except those named here (kept exact
  /// by --refine).
  bool abstractTimers = false;
  std::set<std::string> exactClocks;
  /// --refine: how many times a spurious counterexample's clocks are made
  /// exact and the search run again.
  unsigned refineRounds = 3;
  /// Note the clocks kept exact because of how they are read.
  bool timerNotes = true;
  /// --replay-states: most exact states a replay of an abstract
  /// counterexample (and the search of the exact model after it) visits.
  uint64_t replayStates = 1000000;
  /// --latch, and the texts of the properties (--ctl, --find) whose named
  /// free inputs are latched as the PLC's input image for this run
  /// (passes/LatchInputs.h).
  std::vector<std::string> latch;
  std::vector<std::string> propertyTexts;
  /// --keep, and the PLC memory the properties name: the function-block
  /// members reset at the end of each scan (attr scan_reset) whose values
  /// this run keeps (passes/KeepValues.h). `keepAll`: every one (a state
  /// file written shows every variable as the PLC has it).
  std::vector<std::string> keep;
  bool keepAll = false;
  /// Texts that observe what they name without latching inputs (sr
  /// attributes, which refuse inputs).
  std::vector<std::string> observerTexts;
  /// --trace-internals: traces show every step and name (TraceView).
  bool traceInternals = false;
  /// --trace-source: each row of a trace lists the source lines its step
  /// executed.
  bool traceSource = false;
};

/// A size such as `512M` or `4G` (suffix K, M, G; none: bytes), for
/// --max-memory; false if malformed.
bool parseByteSize(llvm::StringRef text, uint64_t &bytes);

/// The flat, discrete module a command explores: the design's top (or
/// `topName`), flattened when it has instances. Null after reporting;
/// `command` names the subcommand in the message.
net::Module *explorableTop(net::Design &design, llvm::StringRef topName,
                           DiagEngine &diag, llvm::StringRef command);

class ExplorationSetup {
public:
  /// Finds the top module and builds its state layout and semantics. Null
  /// after reporting.
  static std::unique_ptr<ExplorationSetup>
  create(net::Design &design, const ExplorationOptions &options,
         DiagEngine &diag, llvm::StringRef command);

  net::Module &top() const { return *module; }
  const ExplorationOptions &options() const { return opts; }
  const sem::StateLayout &layout() const { return *stateLayout; }
  sem::Semantics &semantics() { return *sem; }
  /// The design's tick (`timescale`), when it declares one: how long a
  /// trace's `tick` steps last.
  const std::optional<net::Timescale> &timescale() const { return tick; }
  /// Where the model was read from (traces show source lines).
  const llvm::SourceMgr *sourceManager() const { return sources; }

  /// Explorer options with the limits set; callers add what they record.
  ExploreOptions exploreOptions() const;

  /// --timers=abstract: what was abstracted, and the exact model (a copy
  /// of the module before the abstraction) that counterexamples are
  /// replayed in. Null semantics without the option.
  const TimerAbstraction &timerAbstraction() const { return timers; }
  sem::Semantics *exactSemantics() { return exactSem.get(); }
  net::Module *exactModule() { return exactTop; }
  /// `,"timers":{...}` for --summary json, empty without the option;
  /// `,"latched":[...]` when inputs were latched.
  std::string summaryJsonFields() const;
  /// Says which function-block members reset at the end of each scan a
  /// state file leaves out (nothing when none is).
  void noteUnkeptValues(DiagEngine &diag,
                        llvm::StringRef what = "state file") const;
  /// The inputs latched for this run, in the module's port order.
  const std::vector<std::string> &latched() const { return latchedInputs; }

  /// --timers=abstract left clocks abstracted in the model explored.
  bool hasAbstractedClocks() const {
    return opts.abstractTimers && !timers.abstracted.empty();
  }

private:
  ExplorationSetup(net::Module &top, const ExplorationOptions &options);
  net::Module *module;
  ExplorationOptions opts;
  std::unique_ptr<sem::StateLayout> stateLayout;
  std::unique_ptr<sem::Semantics> sem;
  TimerAbstraction timers;
  std::unique_ptr<sem::StateLayout> exactLayout;
  std::unique_ptr<sem::Semantics> exactSem;
  net::Module *exactTop = nullptr;
  std::optional<net::Timescale> tick;
  const llvm::SourceMgr *sources = nullptr;
  std::vector<std::string> latchedInputs;
};

/// `runtime error: ...` at the error's place, and where it is an
/// expression read from NetIR text, a note at the statement of the
/// program it was translated from.
void reportRuntimeErrorAt(const sem::RuntimeError &error, DiagEngine &diag);

} // namespace netlift::engine

#endif
