//===- TimerReplay.cpp - abstract counterexamples replayed in exact time --===//
#include "engine/TimerReplay.h"

#include "passes/AbstractTimers.h"

#include "llvm/ADT/StringSet.h"

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

/// The exact model paired with how far along the abstract path a run has
/// come: a state is the exact state and, in one more word, the index of
/// the abstract control state it matches. A step of the exact model is a
/// step of the pair when the run stays in that control state or moves on
/// to the next one; the rest leave the path and are not followed.
class AlongAbstractPath final : public StepRelation {
public:
  AlongAbstractPath(sem::Semantics &exact, const sem::StateLayout &abs,
                    const Projection &proj,
                    llvm::ArrayRef<const uint64_t *> targets)
      : exact(exact), abs(abs), proj(proj), targets(targets),
        words(exact.layout().numWords()), buffer(words + 1) {}

  uint32_t stateWords() const override { return words + 1; }
  bool initialState(uint64_t *out, sem::RuntimeError &err) override {
    out[words] = 0;
    return exact.initialState(out, err);
  }
  std::string stepText(llvm::ArrayRef<uint32_t> step) const override {
    return Explorer::stepText(exact.module(), step);
  }
  uint32_t numMoves() const override {
    return uint32_t(exact.module().transitions.size());
  }
  bool successors(const uint64_t *state, sem::Semantics::Callback each,
                  sem::RuntimeError &) override {
    size_t target = state[words];
    sem::RuntimeError err;
    exact.successors(
        state,
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          size_t t = target;
          const sem::StateLayout &el = exact.layout();
          if (!proj.same(abs, targets[t], el, succ)) {
            if (t + 1 < targets.size() &&
                proj.same(abs, targets[t + 1], el, succ))
              ++t;
            else
              return; // leaves the abstract path
          }
          std::copy(succ, succ + words, buffer.begin());
          buffer[words] = t;
          deepest = std::max(deepest, t);
          each(step, buffer.data());
        },
        err);
    // A runtime error of the exact model ends that run only.
    return true;
  }

  /// The furthest abstract control state an exact run reached.
  size_t deepest = 0;

private:
  sem::Semantics &exact;
  const sem::StateLayout &abs;
  const Projection &proj;
  llvm::ArrayRef<const uint64_t *> targets;
  uint32_t words;
  std::vector<uint64_t> buffer;
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
  AlongAbstractPath relation(exact, al, proj, targets);
  // A run that does not start in the path's first control state follows
  // none of it.
  std::vector<uint64_t> init(words + 1, 0);
  sem::RuntimeError err;
  bool starts = relation.initialState(init.data(), err) &&
                proj.same(al, targets[0], el, init.data());
  if (starts) {
    // Breadth-first, so that the exact run found is a shortest one.
    ExploreOptions eo;
    eo.maxStates = budget;
    auto arrived = [&](const uint64_t *s) {
      return s[words] + 1 == targets.size() && lastOk(s);
    };
    eo.stopAt = arrived;
    Explorer search(relation, eo);
    ExploreResult r;
    search.run(r);
    out.visited = search.store().size();
    if (r.found) {
      out.verdict = ReplayOutcome::Confirmed;
      for (auto [label, state] : search.pathTo(*r.found)) {
        const uint64_t *words0 = search.store().state(state);
        out.labels.push_back(label == Explorer::kNone ? std::string()
                                                      : search.label(label));
        out.states.emplace_back(words0, words0 + words);
      }
      return out;
    }
    if (!r.complete) {
      out.verdict = ReplayOutcome::Undecided;
      return out;
    }
  }
  size_t deepest = relation.deepest;
  out.verdict = ReplayOutcome::Spurious;
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
