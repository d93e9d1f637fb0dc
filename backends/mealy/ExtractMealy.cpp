//===- ExtractMealy.cpp - the Mealy machine of a controller ---------------===//
#include "backends/mealy/ExtractMealy.h"

#include "engine/ExplorationSetup.h"
#include "engine/Explorer.h"
#include "engine/ScanStep.h"
#include "engine/StateLayout.h"

#include "llvm/ADT/SmallVector.h"

using namespace netlift;
using namespace netlift::mealy;
using namespace netlift::net;

namespace {
/// The Boolean signals of the machine: input leaves in port order (the
/// order Semantics::fixInputs takes them in), output ports in port order.
struct Signals {
  std::vector<uint32_t> inputPorts, outputPorts;
};
} // namespace

static bool collectSignals(const Module &m, const MealyExtractOptions &opts,
                           DiagEngine &diag, Signals &sig) {
  bool ok = true;
  for (uint32_t p = 0; p < m.ports.size(); ++p) {
    const Port &port = m.ports[p];
    const char *role = port.isInput() ? "input" : "output";
    if (port.kind == PortKind::Event) {
      diag.error(port.loc, llvm::Twine("event ") + role + " '" + port.name +
                               "': a Mealy machine reads and writes Boolean "
                               "vectors, not events");
      ok = false;
      continue;
    }
    if (!port.type->isBool()) {
      diag.error(port.loc, llvm::Twine(role) + " '" + port.name + "' is " +
                               port.type->str() +
                               ", not Boolean: a Mealy machine reads and "
                               "writes Boolean signals");
      ok = false;
      continue;
    }
    (port.isInput() ? sig.inputPorts : sig.outputPorts).push_back(p);
  }
  if (ok && sig.inputPorts.size() > opts.maxInputs) {
    diag.error(m.ports[sig.inputPorts[opts.maxInputs]].loc,
               "module '" + m.name + "' has " +
                   llvm::Twine(sig.inputPorts.size()) +
                   " inputs: a Mealy machine of more than " +
                   llvm::Twine(opts.maxInputs) +
                   " inputs (2^N input vectors per state) is not extracted");
    ok = false;
  }
  return ok;
}

namespace {
/// The controller read as a Mealy machine, as a step relation: a state is
/// the controller memory at a cycle boundary; its successors are the
/// post-states of one scan per input vector, in vector order, the step
/// being {vector, output} (the output an index into `outputs`). A
/// controller that is not a Mealy machine there (nondeterministic, stuck)
/// stops the search with `refusal` said.
class ScanPerInputVector final : public engine::StepRelation {
public:
  ScanPerInputVector(sem::Semantics &sem, const Signals &sig,
                     const MealyExtractOptions &opts)
      : sem(sem), sig(sig), opts(opts), n(sig.inputPorts.size()) {}

  uint32_t stateWords() const override { return sem.layout().numWords(); }
  bool initialState(uint64_t *out, sem::RuntimeError &err) override {
    return sem.initialState(out, err);
  }
  void setBudget(Budget *budget) override { sem.setBudget(budget); }
  std::string stepText(llvm::ArrayRef<uint32_t> step) const override {
    return automata::vectorBits(step[0], n) + "/" + outputs[step[1]];
  }
  bool successors(const uint64_t *state, sem::Semantics::Callback each,
                  sem::RuntimeError &err) override;

  /// The output vectors met, by index.
  std::vector<std::string> outputs;
  /// Why the controller is not a Mealy machine (empty: it is one so far),
  /// found expanding `refusedAt` (the search may expand ahead of what it
  /// stores: the first refusal is the one said).
  std::string refusal;
  uint32_t refusedAt = 0;
  /// The state being expanded (its number: states are expanded in order).
  uint32_t expanding = 0;

private:
  bool refuse(uint32_t state, std::string why) {
    if (refusal.empty()) {
      refusal = std::move(why);
      refusedAt = state;
    }
    return false;
  }
  uint32_t outputIndex(const std::string &output) {
    auto [it, fresh] = outputIds.try_emplace(output, outputs.size());
    if (fresh)
      outputs.push_back(output);
    return it->second;
  }
  sem::Semantics &sem;
  const Signals &sig;
  const MealyExtractOptions &opts;
  size_t n;
  llvm::StringMap<uint32_t> outputIds;
};
} // namespace

bool ScanPerInputVector::successors(const uint64_t *state,
                                    sem::Semantics::Callback each,
                                    sem::RuntimeError &err) {
  const Module &m = sem.module();
  const sem::StateLayout &layout = sem.layout();
  uint32_t s = expanding++;
  std::vector<int64_t> leaves(n);
  for (uint32_t v = 0; v < (uint32_t(1) << n); ++v) {
    std::string vector = automata::vectorBits(v, n);
    for (size_t k = 0; k < n; ++k)
      leaves[k] = vector[k] == '1';
    sem.fixInputs(leaves, {});
    auto where = [&] {
      return "in state s" + std::to_string(s) +
             (n ? " with inputs " + vector : std::string());
    };
    // Time passes while no step is possible; the first step is the scan
    // (it is unique, or the controller is not a Mealy machine).
    engine::ScanOutcome scan;
    if (!engine::nextScan(sem, state, opts.maxWaitTicks, scan, err))
      return false;
    if (scan.kind == engine::ScanOutcome::Nondeterministic)
      return refuse(s, "module '" + m.name.str() +
                           "' is not deterministic: " + where() + " both " +
                           scan.step + " and " + scan.other + " can happen");
    if (scan.kind != engine::ScanOutcome::Stepped)
      return refuse(
          s,
          "module '" + m.name.str() + "' never takes a step " + where() +
              (scan.kind == engine::ScanOutcome::Waited
                   ? " (waited " + std::to_string(opts.maxWaitTicks) + " ticks)"
                   : std::string(" (a deadlock)")));
    std::string output;
    for (uint32_t p : sig.outputPorts) {
      const Port &port = m.ports[p];
      int64_t value;
      if (port.definition) {
        err = {};
        value = sem.evalInState(port.definition, scan.after.data(), err);
        if (!err.message.empty())
          return false;
      } else {
        value = layout.get(scan.after.data(), layout.portSlot(p));
      }
      output += value ? '1' : '0';
    }
    uint32_t step[2] = {v, outputIndex(output)};
    each(step, scan.after.data());
  }
  return true;
}

bool netlift::mealy::extractMealy(sem::Semantics &sem,
                                  const MealyExtractOptions &opts,
                                  DiagEngine &diag,
                                  automata::MealyMachine &out) {
  const Module &m = sem.module();
  Signals sig;
  if (!collectSignals(m, opts, diag, sig))
    return false;
  out = automata::MealyMachine();
  out.name = m.name.str();
  for (uint32_t p : sig.inputPorts)
    out.inputs.push_back(m.ports[p].name.str());
  for (uint32_t p : sig.outputPorts)
    out.outputs.push_back(m.ports[p].name.str());

  // Breadth-first from the initial state: states are numbered in the
  // order they are found, edges recorded in expansion order.
  ScanPerInputVector relation(sem, sig, opts);
  engine::ExploreOptions eo;
  eo.recordEdges = true;
  eo.maxStates = opts.maxStates;
  engine::Explorer search(relation, eo);
  engine::ExploreResult r;
  search.run(r);
  sem.fixInputs({}, {});
  if (r.error && !relation.refusal.empty() &&
      r.errorState == relation.refusedAt) {
    diag.error(m.loc, relation.refusal);
    return false;
  }
  if (r.error) {
    engine::reportRuntimeErrorAt(*r.error, diag);
    return false;
  }
  if (r.limitReached == "states") {
    diag.error(m.loc, "module '" + m.name + "' has more than " +
                          std::to_string(opts.maxStates) +
                          " states at cycle boundaries: not extracted");
    return false;
  }
  const size_t n = sig.inputPorts.size();
  for (const engine::Edge &e : search.edges()) {
    llvm::StringRef label = search.label(e.label);
    out.transitions.push_back({label.take_front(n).str(), e.from, e.to,
                               label.drop_front(n + 1).str(), llvm::SMLoc()});
  }
  for (uint32_t s = 0; s < search.store().size(); ++s)
    out.states.push_back("s" + std::to_string(s));
  out.initial = 0;
  out.mergeInputCubes();
  return true;
}
