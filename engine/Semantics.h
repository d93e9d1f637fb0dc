//===- Semantics.h - the step semantics of NetIR ----------------*- C++ -*-===//
//
// The meaning of a flat NetIR module, exactly as docs/semantics.md states it
// (design §3.3), as a successor function over packed states: token,
// condition, time and guard enabling; spontaneous and forced transitions
// with `|`/`&` event modes; steps closed under forced transitions, every
// maximal choice among conflicting forced transitions its own successor;
// the `interleaving` and `maximal` policies; urgency; ticks under weak and
// strong timing with saturating place clocks and clock variables; actions
// that read the pre-state and write together, with write conflicts, range
// errors, division by zero and token overflow reported as runtime errors;
// free inputs split into classes of valuations on demand (or enumerated).
// Every analysis uses this one implementation.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_SEMANTICS_H
#define NETLIFT_ENGINE_SEMANTICS_H

#include "engine/StateLayout.h"
#include "ir/net/StringOps.h"

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/Support/SMLoc.h"

#include <memory>
#include <string>
#include <vector>

namespace netlift {
class Budget;
}

namespace netlift::sem {

enum class StepPolicy : uint8_t { Interleaving, Maximal };
enum class Timing : uint8_t { Weak, Strong };

struct Options {
  StepPolicy policy = StepPolicy::Interleaving;
  Timing timing = Timing::Weak;
  /// Bits for the marking of unbounded places (an overflow is an error).
  unsigned unboundedBits = 8;
  /// Split the free inputs into classes on demand (docs/semantics.md,
  /// "Free inputs"); off, every valuation is enumerated at every step.
  bool splitInputs = true;
  /// Enumerating: most valuations of all free inputs per state. Splitting:
  /// most values one input is decided into at one point (a value stored,
  /// an expression of it that is not a comparison), and most values an
  /// expression is evaluated at to find where its value changes.
  uint64_t maxInputValues = 1u << 16;
  /// Splitting: most classes of input valuations one step may split into
  /// (the bound enumeration had per state).
  uint64_t maxInputClasses = 1u << 16;
  /// Splitting: say for each edge which input valuations take it
  /// (edgeCondition()); successors are then reported once all classes ran.
  bool inputConditions = false;
  /// The watchdog: most loop iterations one transition's firing may run
  /// (every loop of its action counted together) before it is a runtime
  /// error, as a PLC's watchdog stops the CPU.
  uint64_t maxLoopIterations = 100000;
  /// Expand plain P/T nets with the compiled kernel (PtKernel.h); off, the
  /// general interpreter does it (the two must agree: a cross-check).
  bool compilePT = true;
  /// Run the end-of-scan resets of PLC memory the model never reads
  /// (ir/net/ScanResets.h). Off, every variable keeps the value the PLC
  /// gives it: the successors are those of the model without the resets,
  /// which traces are shown in (they agree on every other variable).
  bool scanResets = true;
};

/// A runtime error of the model (write conflict, out-of-range write,
/// division by zero, token overflow), with where it happened.
struct RuntimeError {
  std::string message;
  llvm::SMLoc loc;
  /// Not an error of the model but a limit of the exploration (an input
  /// with more values than --max-input-values where each is needed).
  bool limit = false;
  /// The statement running when it happened (none in a guard or output).
  llvm::SMLoc statement;
  /// "time" or "memory": not an error but the run's budget spent inside
  /// one expansion (setBudget); the exploration stops as at a limit.
  const char *budget = nullptr;
};

class Semantics {
public:
  Semantics(const net::Module &m, const StateLayout &layout, Options opts);

  const StateLayout &layout() const { return L; }
  const net::Module &module() const { return m; }
  const Options &options() const { return opts; }
  /// Does the model have place clocks or clock variables?
  bool isTimed() const { return timed; }

  /// The time and memory the run may take, checked at every class of input
  /// valuations and every 1024 loop iterations of a firing: a successors()
  /// call that spends it fails with RuntimeError::budget set. Null: none.
  void setBudget(Budget *b);

  /// Writes the initial state. False (and `err`) if an initial value does
  /// not fit.
  bool initialState(uint64_t *out, RuntimeError &err) const;

  /// One successor: the transitions of the step (in transition order;
  /// empty for a tick) and the packed successor state.
  using Callback = llvm::function_ref<void(llvm::ArrayRef<uint32_t> step,
                                           const uint64_t *succ)>;
  /// Calls `cb` once per distinct (step, successor) pair of `state`. A tick
  /// that changes nothing is not a successor. Returns false and sets `err`
  /// on a runtime error.
  bool successors(const uint64_t *state, Callback cb, RuntimeError &err);
  /// Classes of input valuations the last successors() call ran the step
  /// for (valuations, when enumerating; 1 without free inputs).
  uint64_t lastInputClasses() const;
  /// While `successors` reports an edge, with Options::inputConditions:
  /// the classes of input valuations that take it, `[go=1, level=91..100]
  /// | [go=0]` (inputs a class leaves free are not listed); empty for a
  /// tick and without free inputs.
  const std::string &edgeCondition() const;
  /// Does the module have free inputs (cond, data or event input ports)?
  bool hasFreeInputs() const;

  /// What the actions of one fired step executed: every statement in the
  /// order it ran (an `if` before the branch it took), and each slot
  /// written with the assignment that wrote it last.
  struct ExecutionLog {
    std::vector<llvm::SMLoc> statements;
    std::vector<std::pair<uint32_t, llvm::SMLoc>> writes;
  };
  /// Keeps an ExecutionLog of each step fired (traces' source lines; off by
  /// default, it costs a branch per statement).
  void recordExecution(bool on);
  /// While successors() reports a step (without Options::inputConditions,
  /// which reports after every class ran): what its actions executed.
  const ExecutionLog &lastExecution() const;

  /// Restricts successors() and evalInState() to one valuation of the free
  /// inputs (the Mealy view of a controller: one input vector per step).
  /// `leafValues[k]` is the value of the k-th scalar leaf of the cond/data
  /// input ports (ports in module order, leaves in slot order);
  /// `eventsPresent[k]` says whether the k-th event input port is present.
  /// Two empty arrays restore the default: every valuation, enumerated.
  void fixInputs(llvm::ArrayRef<int64_t> leafValues,
                 llvm::ArrayRef<uint8_t> eventsPresent);

  /// Evaluates a verified Boolean expression of the module in a state
  /// (inputs read as their lowest value, or as fixed by fixInputs).
  bool evalPredicate(const net::Expr *e, const uint64_t *state,
                     RuntimeError &err);
  /// Value of slot-free signals (defined outputs) in a state.
  int64_t evalInState(const net::Expr *e, const uint64_t *state,
                      RuntimeError &err);
  /// Value of a string-typed expression in a state.
  net::StringValue evalStringInState(const net::Expr *e, const uint64_t *state,
                                     RuntimeError &err);

  /// The interpreter behind this API (internal: SemanticsImpl.h).
  struct Impl;

private:
  /// The state's slots and the inputs as evalInState reads them.
  std::vector<int64_t> &predicateValuation(const uint64_t *state);
  const net::Module &m;
  const StateLayout &L;
  Options opts;
  bool timed = false;
  std::shared_ptr<Impl> impl;
};

} // namespace netlift::sem

#endif
