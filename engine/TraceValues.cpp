//===- TraceValues.cpp - a path shown with the values the PLC has ---------===//
#include "engine/TraceValues.h"

#include "engine/Explorer.h"
#include "ir/net/ScanResets.h"

using namespace netlift;
using namespace netlift::engine;

PlcPath engine::plcValues(sem::Semantics &sem,
                          llvm::ArrayRef<std::string> labels,
                          llvm::ArrayRef<const uint64_t *> states) {
  PlcPath out;
  out.states.assign(states.begin(), states.end());
  if (!sem.options().scanResets || states.empty())
    return out;
  const net::Module &m = sem.module();
  const sem::StateLayout &L = sem.layout();
  llvm::DenseSet<uint32_t> resetVars = net::scanResetVars(m);
  if (resetVars.empty()) // (keep-values drops the mark with the reset)
    return out;
  std::vector<bool> reset(L.numSlots(), false);
  for (uint32_t v : resetVars)
    if (int32_t first = L.varSlot(v); first >= 0)
      for (uint32_t i = 0; i < sem::StateLayout::slotsOf(m.vars[v].type); ++i)
        reset[first + i] = true;
  std::vector<uint32_t> compared;
  for (uint32_t s = 0; s < L.numPacked(); ++s)
    if (!reset[s])
      compared.push_back(s);

  sem::Options o = sem.options();
  o.scanResets = false;
  o.inputConditions = false;
  out.semantics = std::make_unique<sem::Semantics>(m, L, o);
  uint32_t words = L.numWords();
  out.storage.reserve(states.size());
  out.storage.emplace_back(states[0], states[0] + words);
  for (size_t i = 1; i < states.size(); ++i) {
    std::string taken = i < labels.size()
                            ? llvm::StringRef(labels[i]).split(" [").first.str()
                            : std::string();
    const uint64_t *prev = out.storage.back().data();
    std::vector<uint64_t> next;
    sem::RuntimeError err;
    out.semantics->successors(
        prev,
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          if (!next.empty() || Explorer::stepText(m, step) != taken)
            return;
          for (uint32_t s : compared)
            if (L.get(succ, s) != L.get(states[i], s))
              return;
          next.assign(succ, succ + words);
        },
        err);
    // Found always, as the resets touch only what is never read; should a
    // model break that, the explored state is shown rather than none.
    if (next.empty())
      next.assign(states[i], states[i] + words);
    out.storage.push_back(std::move(next));
  }
  for (size_t i = 0; i < states.size(); ++i)
    out.states[i] = out.storage[i].data();
  return out;
}
