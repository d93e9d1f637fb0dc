//===- Explorer.cpp - state-space exploration -----------------------------===//
#include "engine/Explorer.h"

#include "llvm/Support/Process.h"
#include "llvm/Support/raw_ostream.h"

#include <chrono>

#include "ir/support/Budget.h"
#include "llvm/ADT/ScopeExit.h"
#include <unistd.h>

using namespace netlift;
using namespace netlift::engine;
using Clock = std::chrono::steady_clock;

namespace {
/// The token figures of the summary (most tokens in a place, most tokens
/// in a marking), read off packed states: 1-bit places are counted a word
/// at a time, the others slot by slot.
class TokenStats {
public:
  explicit TokenStats(const sem::StateLayout &L) : L(L) {
    oneBitMask.assign(L.numWords(), 0);
    for (uint32_t p = 0; p < L.module().places.size(); ++p) {
      uint32_t slot = L.markingSlot(p);
      const sem::Slot &s = L.slots()[slot];
      if (s.width == 1 && s.lo == 0)
        oneBitMask[s.bitOffset / 64] |= uint64_t(1) << (s.bitOffset % 64);
      else
        wideSlots.push_back(slot);
    }
  }
  void account(const uint64_t *state, ExploreResult &r) const {
    uint64_t tokens = 0, most = 0;
    for (uint32_t w = 0; w < oneBitMask.size(); ++w)
      tokens += __builtin_popcountll(state[w] & oneBitMask[w]);
    if (tokens)
      most = 1;
    for (uint32_t slot : wideSlots) {
      uint64_t k = uint64_t(L.get(state, slot));
      tokens += k;
      most = std::max(most, k);
    }
    r.maxTokensInPlace = std::max(r.maxTokensInPlace, most);
    r.maxTokensPerMarking = std::max(r.maxTokensPerMarking, tokens);
  }

private:
  const sem::StateLayout &L;
  std::vector<uint64_t> oneBitMask;
  std::vector<uint32_t> wideSlots;
};
} // namespace

Explorer::Explorer(sem::Semantics &s, ExploreOptions o)
    : ownRelation(std::make_unique<ModuleStepRelation>(s)), rel(*ownRelation),
      opts(o), states(rel.stateWords()) {}

Explorer::Explorer(StepRelation &relation, ExploreOptions o)
    : rel(relation), opts(o), states(rel.stateWords()) {}

std::string ModuleStepRelation::stepText(llvm::ArrayRef<uint32_t> step) const {
  return Explorer::stepText(sem.module(), step);
}

uint32_t Explorer::internConditionLabel(llvm::ArrayRef<uint32_t> step,
                                        llvm::StringRef condition) {
  std::string l = labels[internLabel(step)] + " " + condition.str();
  auto [it, fresh] = labelIds.try_emplace(l, labels.size());
  if (fresh)
    labels.push_back(l);
  return it->second;
}

std::string Explorer::stepText(const net::Module &m,
                               llvm::ArrayRef<uint32_t> step) {
  if (step.empty())
    return "tick";
  std::string l = "{";
  for (size_t i = 0; i < step.size(); ++i)
    l += (i ? "," : "") + m.transitions[step[i]].name.str();
  return l + "}";
}

uint32_t Explorer::internNewLabel(llvm::ArrayRef<uint32_t> step) {
  // One-transition steps and the tick are remembered in a table.
  uint32_t *single = nullptr;
  if (step.size() <= 1) {
    uint32_t key = step.empty() ? 0 : step[0] + 1;
    if (key >= singleLabel.size())
      singleLabel.resize(std::max<size_t>(rel.numMoves(), key) + 1, kNone);
    if (singleLabel[key] != kNone)
      return singleLabel[key];
    single = &singleLabel[key];
  }
  std::string l = rel.stepText(step);
  auto [it, fresh] = labelIds.try_emplace(l, labels.size());
  if (fresh)
    labels.push_back(l);
  if (single)
    *single = it->second;
  return it->second;
}

std::vector<std::pair<uint32_t, uint32_t>> Explorer::pathTo(uint32_t s) const {
  std::vector<std::pair<uint32_t, uint32_t>> path;
  while (s != kNone) {
    path.push_back({tree[s].label, s});
    s = tree[s].parent;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

bool Explorer::run(ExploreResult &r) {
  auto start = Clock::now();
  // Time and memory are checked inside each expansion too (Budget.h).
  Budget budget(opts.timeLimit, opts.maxMemory);
  rel.setBudget(&budget);
  auto noBudget = llvm::make_scope_exit([&] { rel.setBudget(nullptr); });
  std::vector<uint64_t> init(rel.stateWords());
  sem::RuntimeError err;
  if (!rel.initialState(init.data(), err)) {
    r.error = err;
    return false;
  }
  states.insert(init.data());
  tree.push_back({kNone, kNone});
  bool timed = rel.isTimed();
  std::vector<uint8_t> hasStep;
  std::vector<uint32_t> tickSucc;
  std::vector<uint32_t> stack; // depth-first order only
  if (opts.depthFirst)
    stack.push_back(0);
  if (opts.stopAt && opts.stopAt(states.state(0))) {
    r.found = 0;
  }
  bool showProgress = opts.progress && isatty(2);
  auto lastReport = start;
  uint32_t next = 0; // breadth-first: states are expanded in index order
  uint64_t expanded = 0;
  // The successors of a state are generated into a batch and looked up
  // in the store together, so that the cache misses of the lookups
  // overlap. Breadth-first, the lookups of one state's batch are moreover
  // deferred until the next state's successors are generated: its buckets
  // arrive in the cache meanwhile. Batches are committed in expansion
  // order, so states are numbered exactly as without the look-ahead.
  struct Pending {
    uint32_t hash, label;
    bool isTick;
  };
  struct Batch {
    uint32_t from;
    std::vector<Pending> pending;
    std::vector<uint64_t> words;
    bool ok;
    sem::RuntimeError err;
  };
  // Batches generated but not yet committed, oldest first (a ring).
  const uint32_t lookAhead = opts.depthFirst ? 0 : kLookAhead;
  std::vector<Batch> ring(lookAhead + 1);
  uint32_t head = 0, inFlight = 0;
  auto front = [&]() -> Batch & { return ring[head]; };
  auto popFront = [&]() {
    head = (head + 1) % ring.size();
    --inFlight;
  };
  std::optional<TokenStats> tokenStats;
  if (const sem::StateLayout *L = rel.tokenLayout())
    tokenStats.emplace(*L);
  const uint32_t W = rel.stateWords();
  const bool freeInputs = rel.hasFreeInputs();
  auto generate = [&](uint32_t s, Batch &b) {
    b.from = s;
    b.pending.clear();
    b.words.clear();
    b.ok = rel.successors(
        states.state(s),
        [&](llvm::ArrayRef<uint32_t> st, const uint64_t *succ) {
          uint32_t h = states.hash(succ);
          states.prefetchBucket(h);
          uint32_t label = opts.inputLabels && !rel.edgeCondition().empty()
                               ? internConditionLabel(st, rel.edgeCondition())
                               : internLabel(st);
          b.pending.push_back({h, label, st.empty()});
          size_t at = b.words.size();
          b.words.resize(at + W);
          for (uint32_t i = 0; i < W; ++i) // a few words: no memcpy call
            b.words[at + i] = succ[i];
        },
        b.err);
    if (freeInputs) // what splitting saved; nothing to count otherwise
      ++r.inputClasses[rel.lastInputClasses()];
  };
  auto prefetchCandidates = [&](const Batch &b) {
    for (const Pending &p : b.pending)
      states.prefetchCandidate(p.hash);
  };
  // Stores a batch's successors; false when the search stops.
  auto commit = [&](const Batch &b) {
    uint32_t s = b.from;
    // The budget spent inside the expansion: the state stays unexpanded.
    if (!b.ok && b.err.budget) {
      r.limitReached = b.err.budget;
      return false;
    }
    if (tokenStats)
      tokenStats->account(states.state(s), r);
    bool step = false;
    uint32_t tick = kNone;
    for (size_t i = 0; i < b.pending.size(); ++i) {
      const uint64_t *succ = &b.words[i * W];
      const Pending &p = b.pending[i];
      // --max-states: never store more than the limit.
      if (opts.maxStates && states.size() >= opts.maxStates &&
          states.find(succ, p.hash) == kNone) {
        r.limitReached = "states";
        return false;
      }
      auto [t, fresh] = states.insert(succ, p.hash);
      if (p.isTick)
        tick = t;
      else
        step = true;
      ++r.edges;
      if (opts.recordEdges)
        edgeList.push_back({s, t, p.label});
      if (fresh) {
        tree.push_back({s, p.label});
        if (opts.depthFirst)
          stack.push_back(t);
        if (opts.stopAt && opts.stopAt(states.state(t))) {
          r.found = t;
          return false;
        }
      }
    }
    if (!b.ok) {
      r.error = b.err;
      r.errorState = s;
      return false;
    }
    if (b.pending.empty())
      r.deadlocks.push_back(s);
    if (timed) {
      if (hasStep.size() <= s) {
        hasStep.resize(s + 1, 0);
        tickSucc.resize(s + 1, kNone);
      }
      hasStep[s] = step;
      tickSucc[s] = tick;
    }
    return true;
  };
  while (!r.found) {
    uint32_t s;
    if (opts.depthFirst) {
      if (stack.empty())
        break;
      s = stack.back();
      stack.pop_back();
    } else {
      if (next == states.size()) {
        if (!inFlight)
          break;
        // The queue is empty until the deferred batches are stored.
        prefetchCandidates(front());
        bool go = commit(front());
        popFront();
        if (!go)
          break;
        continue;
      }
      s = next++;
    }
    // Limits are checked between expansions, so a stop is clean.
    if ((expanded & 1023) == 0) {
      double secs = std::chrono::duration<double>(Clock::now() - start).count();
      size_t mem = states.bytes() + edgeList.capacity() * sizeof(Edge) +
                   tree.capacity() * sizeof(TreeEdge);
      r.peakBytes = std::max(r.peakBytes, mem);
      if (opts.timeLimit > 0 && secs > opts.timeLimit) {
        r.limitReached = "time";
        break;
      }
      uint64_t resident = 0;
      if (opts.maxMemory > 0 &&
          (mem > opts.maxMemory || budget.overMemory(resident))) {
        r.limitReached = "memory";
        break;
      }
      if (showProgress &&
          std::chrono::duration<double>(Clock::now() - lastReport).count() >
              1.0) {
        lastReport = Clock::now();
        llvm::errs() << "\rstates " << states.size() << "  "
                     << uint64_t(states.size() / std::max(secs, 1e-9))
                     << " states/s  queue "
                     << (opts.depthFirst ? stack.size() : states.size() - next)
                     << "  memory " << (mem >> 20) << " MB  " << uint64_t(secs)
                     << " s   ";
      }
    }
    ++expanded;
    Batch &b = ring[(head + inFlight) % ring.size()];
    generate(s, b);
    ++inFlight;
    if (inFlight > lookAhead) {
      if (lookAhead == 0)
        prefetchCandidates(b);
      bool go = commit(front());
      popFront();
      if (!go)
        break;
      if (inFlight)
        prefetchCandidates(front());
    }
  }
  if (showProgress)
    llvm::errs() << "\r" << std::string(78, ' ') << "\r";
  // Complete: every reachable state was expanded.
  r.complete = !r.error && r.limitReached.empty() && !r.found;
  // Dead states: no step now or after any number of ticks.
  if (!timed) {
    r.deadStates = r.deadlocks.size();
  } else {
    // dead(s) = no step at s and (no tick or its tick successor is dead).
    // Ticks only advance clocks, so tick chains have no cycles.
    std::vector<int8_t> dead(hasStep.size(), -1);
    std::vector<uint32_t> chain;
    for (uint32_t s = 0; s < hasStep.size(); ++s) {
      chain.clear();
      uint32_t x = s;
      int8_t verdict;
      for (;;) {
        if (x == kNone) {
          verdict = 1;
          break;
        }
        if (x >= hasStep.size()) {
          verdict = 0; // not expanded (a limit): not known to be dead
          break;
        }
        if (dead[x] >= 0) {
          verdict = dead[x];
          break;
        }
        if (hasStep[x]) {
          verdict = 0;
          break;
        }
        chain.push_back(x);
        x = tickSucc[x];
      }
      for (uint32_t c : chain)
        dead[c] = verdict;
      if (dead[s] < 0)
        dead[s] = 0;
    }
    for (int8_t d : dead)
      r.deadStates += d == 1;
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.peakBytes = std::max(r.peakBytes, states.bytes() +
                                          edgeList.capacity() * sizeof(Edge) +
                                          tree.capacity() * sizeof(TreeEdge));
  return true;
}
