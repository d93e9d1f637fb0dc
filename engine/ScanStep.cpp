//===- ScanStep.cpp - one scan of a controller with given inputs ----------===//
#include "engine/ScanStep.h"
#include "engine/Explorer.h"

using namespace netlift;
using namespace netlift::engine;

bool engine::nextScan(sem::Semantics &sem, const uint64_t *from,
                      uint64_t maxWaitTicks, ScanOutcome &out,
                      sem::RuntimeError &err) {
  const uint32_t words = sem.layout().numWords();
  out = ScanOutcome();
  std::vector<uint64_t> at(from, from + words), tick(words);
  for (uint64_t waited = 0;; ++waited) {
    std::vector<std::string> steps;
    bool ticks = false;
    if (!sem.successors(
            at.data(),
            [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
              if (step.empty()) {
                ticks = true;
                tick.assign(succ, succ + words);
                return;
              }
              steps.push_back(Explorer::stepText(sem.module(), step));
              if (steps.size() == 1)
                out.after.assign(succ, succ + words);
            },
            err))
      return false;
    if (steps.size() > 1) {
      out.kind = ScanOutcome::Nondeterministic;
      out.step = steps[0];
      out.other = steps[1];
      return true;
    }
    if (steps.size() == 1) {
      out.kind = ScanOutcome::Stepped;
      out.step = steps[0];
      return true;
    }
    if (!ticks) {
      out.kind = ScanOutcome::Deadlock;
      return true;
    }
    if (waited == maxWaitTicks) {
      out.kind = ScanOutcome::Waited;
      return true;
    }
    out.ticks.push_back(tick);
    at.swap(tick);
  }
}
