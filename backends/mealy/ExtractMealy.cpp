//===- ExtractMealy.cpp - the Mealy machine of a controller ---------------===//
#include "backends/mealy/ExtractMealy.h"

#include "engine/ExplorationSetup.h"
#include "engine/ScanStep.h"
#include "engine/StateLayout.h"
#include "engine/StateStore.h"

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

bool netlift::mealy::extractMealy(sem::Semantics &sem,
                                  const MealyExtractOptions &opts,
                                  DiagEngine &diag,
                                  automata::MealyMachine &out) {
  const Module &m = sem.module();
  const sem::StateLayout &layout = sem.layout();
  Signals sig;
  if (!collectSignals(m, opts, diag, sig))
    return false;
  const uint32_t W = layout.numWords();
  const size_t n = sig.inputPorts.size();

  out = automata::MealyMachine();
  out.name = m.name.str();
  for (uint32_t p : sig.inputPorts)
    out.inputs.push_back(m.ports[p].name.str());
  for (uint32_t p : sig.outputPorts)
    out.outputs.push_back(m.ports[p].name.str());

  auto runtimeError = [&](const sem::RuntimeError &e) {
    engine::reportRuntimeErrorAt(e, diag);
    return false;
  };
  engine::StateStore states(W);
  std::vector<uint64_t> init(W);
  sem::RuntimeError err;
  if (!sem.initialState(init.data(), err))
    return runtimeError(err);
  states.insert(init.data());

  std::vector<int64_t> leaves(n);
  for (uint32_t s = 0; s < states.size(); ++s) {
    for (uint32_t v = 0; v < (uint32_t(1) << n); ++v) {
      std::string vector = automata::vectorBits(v, n);
      for (size_t k = 0; k < n; ++k)
        leaves[k] = vector[k] == '1';
      sem.fixInputs(leaves, {});
      auto where = [&] {
        return "in state s" + std::to_string(s) +
               (n ? " with inputs " + vector : std::string());
      };
      // Time passes while no step is possible; the first step is the
      // scan (it is unique, or the controller is not a Mealy machine).
      engine::ScanOutcome scan;
      if (!engine::nextScan(sem, states.state(s), opts.maxWaitTicks, scan, err))
        return runtimeError(err);
      if (scan.kind == engine::ScanOutcome::Nondeterministic) {
        diag.error(m.loc, "module '" + m.name +
                              "' is not deterministic: " + where() + " both " +
                              scan.step + " and " + scan.other + " can happen");
        return false;
      }
      if (scan.kind != engine::ScanOutcome::Stepped) {
        diag.error(m.loc,
                   "module '" + m.name + "' never takes a step " + where() +
                       (scan.kind == engine::ScanOutcome::Waited
                            ? " (waited " + std::to_string(opts.maxWaitTicks) +
                                  " ticks)"
                            : std::string(" (a deadlock)")));
        return false;
      }
      std::vector<uint64_t> &next = scan.after;
      std::string output;
      for (uint32_t p : sig.outputPorts) {
        const Port &port = m.ports[p];
        int64_t value;
        if (port.definition) {
          err = {};
          value = sem.evalInState(port.definition, next.data(), err);
          if (!err.message.empty())
            return runtimeError(err);
        } else {
          value = layout.get(next.data(), layout.portSlot(p));
        }
        output += value ? '1' : '0';
      }
      if (states.size() >= opts.maxStates &&
          states.find(next.data()) == engine::StateStore::kNotFound) {
        diag.error(m.loc, "module '" + m.name + "' has more than " +
                              std::to_string(opts.maxStates) +
                              " states at cycle boundaries: not extracted");
        return false;
      }
      uint32_t target = states.insert(next.data()).first;
      out.transitions.push_back({vector, s, target, output, llvm::SMLoc()});
    }
  }
  sem.fixInputs({}, {});
  for (uint32_t s = 0; s < states.size(); ++s)
    out.states.push_back("s" + std::to_string(s));
  out.initial = 0;
  out.mergeInputCubes();
  return true;
}
