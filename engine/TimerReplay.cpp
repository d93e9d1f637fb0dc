//===- TimerReplay.cpp - abstract counterexamples replayed in exact time --===//
#include "engine/TimerReplay.h"

#include "passes/AbstractTimers.h"

#include "llvm/ADT/StringSet.h"

#include <deque>
#include <unordered_set>

using namespace netlift;
using namespace netlift::engine;

namespace {

/// The slots both models share that a control state is made of: markings
/// and variables, not place clocks, clock variables or what the
/// abstraction added.
struct Projection {
  std::vector<std::pair<uint32_t, uint32_t>> slots; // (abstract, exact)

  Projection(const sem::StateLayout &abs, const sem::StateLayout &ex,
             llvm::ArrayRef<std::string> abstracted) {
    llvm::StringSet<> skip;
    for (const std::string &c : abstracted) {
      skip.insert(c);
      skip.insert(abstractTickedFlag(c));
    }
    const net::Module &em = ex.module();
    for (uint32_t v = 0; v < em.vars.size(); ++v)
      if (em.vars[v].type->isClock())
        skip.insert(em.vars[v].name);
    llvm::StringMap<uint32_t> exactSlot;
    for (uint32_t s = 0; s < ex.numPacked(); ++s)
      exactSlot[ex.slots()[s].name] = s;
    for (uint32_t s = 0; s < abs.numPacked(); ++s) {
      const sem::Slot &slot = abs.slots()[s];
      llvm::StringRef name = slot.name;
      if (name.startswith("clock(") || skip.count(name) ||
          skip.count(name.split('[').first))
        continue;
      if (auto it = exactSlot.find(name); it != exactSlot.end())
        slots.push_back({s, it->second});
    }
  }

  bool sameControl(const sem::StateLayout &abs, const uint64_t *a,
                   const uint64_t *b) const {
    for (auto [sa, se] : slots)
      if (abs.get(a, sa) != abs.get(b, sa))
        return false;
    return true;
  }

  bool same(const sem::StateLayout &abs, const uint64_t *a,
            const sem::StateLayout &ex, const uint64_t *e) const {
    for (auto [sa, se] : slots)
      if (abs.get(a, sa) != ex.get(e, se))
        return false;
    return true;
  }
};

struct Node {
  std::vector<uint64_t> state;
  size_t target; // the abstract control state reached
  int64_t parent;
  std::string label;
};

} // namespace

ReplayOutcome engine::replayInExactTime(
    sem::Semantics &exact, sem::Semantics &abstract, const Explorer &x,
    llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
    llvm::ArrayRef<std::string> abstracted,
    llvm::function_ref<bool(const uint64_t *)> lastOk, uint64_t budget) {
  const sem::StateLayout &al = abstract.layout(), &el = exact.layout();
  Projection proj(al, el, abstracted);
  // The abstract control states in order, each with its step on the path.
  std::vector<const uint64_t *> targets;
  std::vector<size_t> targetStep;
  for (size_t i = 0; i < path.size(); ++i) {
    const uint64_t *s = x.store().state(path[i].second);
    if (targets.empty() || !proj.sameControl(al, targets.back(), s)) {
      targets.push_back(s);
      targetStep.push_back(i);
    }
  }
  ReplayOutcome out;
  uint32_t words = el.numWords();
  std::vector<Node> nodes;
  std::deque<size_t> queue;
  auto keyOf = [&](const uint64_t *s, size_t target) {
    std::string k(reinterpret_cast<const char *>(s), words * 8);
    k.append(reinterpret_cast<const char *>(&target), sizeof target);
    return k;
  };
  std::unordered_set<std::string> seen;
  std::vector<uint64_t> init(words, 0);
  sem::RuntimeError err;
  size_t deepest = 0;
  auto finish = [&](size_t n) {
    out.verdict = ReplayOutcome::Confirmed;
    std::vector<size_t> chain;
    for (int64_t k = int64_t(n); k >= 0; k = nodes[k].parent)
      chain.push_back(size_t(k));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      out.labels.push_back(nodes[*it].label);
      out.states.push_back(nodes[*it].state);
    }
  };
  if (exact.initialState(init.data(), err) &&
      proj.same(al, targets[0], el, init.data())) {
    nodes.push_back({init, 0, -1, ""});
    seen.insert(keyOf(init.data(), 0));
    queue.push_back(0);
    if (targets.size() == 1 && lastOk(init.data())) {
      finish(0);
      out.visited = 1;
      return out;
    }
  }
  while (!queue.empty()) {
    size_t n = queue.front();
    queue.pop_front();
    if (nodes.size() >= budget) {
      out.verdict = ReplayOutcome::Undecided;
      out.visited = nodes.size();
      return out;
    }
    std::vector<uint64_t> state = nodes[n].state;
    size_t target = nodes[n].target;
    int64_t done = -1;
    bool ok = exact.successors(
        state.data(),
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          if (done >= 0)
            return;
          size_t t = target;
          if (!proj.same(al, targets[t], el, succ)) {
            if (t + 1 < targets.size() &&
                proj.same(al, targets[t + 1], el, succ))
              ++t;
            else
              return; // leaves the abstract path
          }
          std::string key = keyOf(succ, t);
          if (!seen.insert(key).second)
            return;
          nodes.push_back({std::vector<uint64_t>(succ, succ + words), t,
                           int64_t(n),
                           Explorer::stepText(exact.module(), step)});
          deepest = std::max(deepest, t);
          if (t + 1 == targets.size() && lastOk(succ))
            done = int64_t(nodes.size() - 1);
          else
            queue.push_back(nodes.size() - 1);
        },
        err);
    if (done >= 0) {
      finish(size_t(done));
      out.visited = nodes.size();
      return out;
    }
    if (!ok)
      continue; // a runtime error of the exact model ends that run
  }
  out.verdict = ReplayOutcome::Spurious;
  out.visited = nodes.size();
  size_t next = std::min(deepest + 1, targets.size() - 1);
  out.divergesAt = targetStep[next];
  // The abstracted clocks running (set, then ticked, below their cap) in
  // the abstract states from the last one matched to the one missed.
  const net::Module &am = al.module();
  for (const std::string &c : abstracted) {
    net::Symbol clock = am.lookup(c), flag = am.lookup(abstractTickedFlag(c));
    if (clock.kind != net::SymKind::Var || flag.kind != net::SymKind::Var)
      continue;
    int32_t cs = al.varSlot(clock.index), fs = al.varSlot(flag.index);
    bool running = false;
    for (size_t i = targetStep[deepest]; i <= out.divergesAt; ++i) {
      const uint64_t *s = x.store().state(path[i].second);
      running |=
          al.get(s, fs) != 0 && al.get(s, cs) < am.vars[clock.index].type->hi;
    }
    if (running)
      out.involved.push_back(c);
  }
  if (out.involved.empty())
    out.involved.assign(abstracted.begin(), abstracted.end());
  return out;
}
