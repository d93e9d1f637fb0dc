//===- Refinement.cpp - abstract timers, refined on demand ----------------===//
#include "engine/Refinement.h"

using namespace netlift;
using namespace netlift::engine;

int engine::refineUntilSettled(
    ExplorationOptions &options,
    llvm::function_ref<int(ExplorationOptions &, unsigned)> round) {
  for (unsigned r = 0;; ++r) {
    options.timerNotes = r == 0; // the notes of the first round suffice
    int code = round(options, r);
    if (code != kRefine)
      return code;
  }
}

int engine::afterReplay(ReplayOutcome::Verdict verdict,
                        llvm::ArrayRef<std::string> involved, int failCode,
                        ExplorationOptions &options, unsigned round,
                        llvm::raw_ostream &out) {
  if (verdict == ReplayOutcome::Confirmed)
    return failCode;
  if (verdict == ReplayOutcome::Undecided)
    return 2;
  std::vector<std::string> fresh;
  for (const std::string &c : involved)
    if (!options.exactClocks.count(c))
      fresh.push_back(c);
  if (fresh.empty() || round >= options.refineRounds) {
    out << "not refined further (--refine " << options.refineRounds
        << "): the result is undecided; run with --timers=exact\n";
    return 2;
  }
  options.exactClocks.insert(fresh.begin(), fresh.end());
  std::string names;
  for (const std::string &n : fresh)
    names += (names.empty() ? "" : ", ") + n;
  out << "refining (round " << round + 1 << " of " << options.refineRounds
      << "): keeping " << names << " exact\n";
  return kRefine;
}
