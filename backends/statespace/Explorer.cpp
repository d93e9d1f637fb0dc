//===- Explorer.cpp - state-space exploration -----------------------------===//
#include "backends/statespace/Explorer.h"

#include "llvm/Support/Process.h"
#include "llvm/Support/raw_ostream.h"

#include <chrono>
#include <unistd.h>

using namespace netlift;
using namespace netlift::statespace;
using Clock = std::chrono::steady_clock;

Explorer::Explorer(sem::Semantics &s, ExploreOptions o)
    : sem(s), opts(o), states(s.layout().numWords()) {}

uint32_t Explorer::internLabel(llvm::ArrayRef<uint32_t> step) {
  // Most steps are one transition or a tick: look those up directly.
  if (step.size() <= 1) {
    uint32_t key = step.empty() ? 0 : step[0] + 1;
    if (key >= singleLabel.size())
      singleLabel.resize(sem.module().transitions.size() + 1, kNone);
    if (singleLabel[key] != kNone)
      return singleLabel[key];
    std::string l =
        step.empty() ? std::string("tick")
                     : "{" + sem.module().transitions[step[0]].name.str() + "}";
    auto [it, fresh] = labelIds.try_emplace(l, labels.size());
    if (fresh)
      labels.push_back(l);
    return singleLabel[key] = it->second;
  }
  std::string l;
  if (step.empty()) {
    l = "tick";
  } else {
    l = "{";
    for (size_t i = 0; i < step.size(); ++i) {
      if (i)
        l += ",";
      l += sem.module().transitions[step[i]].name.str();
    }
    l += "}";
  }
  auto [it, fresh] = labelIds.try_emplace(l, labels.size());
  if (fresh)
    labels.push_back(l);
  return it->second;
}

std::vector<std::pair<uint32_t, uint32_t>> Explorer::pathTo(uint32_t s) const {
  std::vector<std::pair<uint32_t, uint32_t>> path;
  while (s != kNone) {
    path.push_back({parentLabel[s], s});
    s = parent[s];
  }
  std::reverse(path.begin(), path.end());
  return path;
}

bool Explorer::run(ExploreResult &r) {
  const sem::StateLayout &L = sem.layout();
  const net::Module &m = sem.module();
  auto start = Clock::now();
  std::vector<uint64_t> init(L.numWords());
  sem::RuntimeError err;
  if (!sem.initialState(init.data(), err)) {
    r.error = err;
    return false;
  }
  states.insert(init.data());
  parent.push_back(kNone);
  parentLabel.push_back(kNone);
  bool timed = sem.isTimed();
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
  std::vector<uint64_t> cur(L.numWords());
  while (!r.found) {
    uint32_t s;
    if (opts.depthFirst) {
      if (stack.empty())
        break;
      s = stack.back();
      stack.pop_back();
    } else {
      if (next == states.size())
        break;
      s = next++;
    }
    // Limits are checked between expansions, so a stop is clean.
    if ((expanded & 1023) == 0) {
      double secs = std::chrono::duration<double>(Clock::now() - start).count();
      size_t mem = states.bytes() + edgeList.capacity() * sizeof(Edge) +
                   parent.capacity() * 8;
      r.peakBytes = std::max(r.peakBytes, mem);
      if (opts.timeLimit > 0 && secs > opts.timeLimit) {
        r.limitReached = "time";
        break;
      }
      if (opts.maxMemory > 0 && mem > opts.maxMemory) {
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
    // Copy: the store's arena may move while successors are inserted.
    std::copy(states.state(s), states.state(s) + L.numWords(), cur.begin());
    uint64_t tokens = 0;
    for (uint32_t p = 0; p < m.places.size(); ++p) {
      uint64_t k = L.get(cur.data(), L.markingSlot(p));
      tokens += k;
      r.maxTokensInPlace = std::max(r.maxTokensInPlace, k);
    }
    r.maxTokensPerMarking = std::max(r.maxTokensPerMarking, tokens);
    bool any = false, step = false;
    uint32_t tick = kNone;
    bool stopped = false;
    bool ok = sem.successors(
        cur.data(),
        [&](llvm::ArrayRef<uint32_t> st, const uint64_t *succ) {
          if (stopped)
            return;
          any = true;
          // --max-states: never store more than the limit.
          if (opts.maxStates && states.size() >= opts.maxStates &&
              states.find(succ) == kNone) {
            r.limitReached = "states";
            stopped = true;
            return;
          }
          auto [t, fresh] = states.insert(succ);
          uint32_t label = internLabel(st);
          if (st.empty())
            tick = t;
          else
            step = true;
          ++r.edges;
          if (opts.recordEdges)
            edgeList.push_back({s, t, label});
          if (fresh) {
            parent.push_back(s);
            parentLabel.push_back(label);
            if (opts.depthFirst)
              stack.push_back(t);
            if (opts.stopAt && opts.stopAt(states.state(t))) {
              r.found = t;
              stopped = true;
            }
          }
        },
        err);
    if (!ok) {
      r.error = err;
      r.errorState = s;
      break;
    }
    if (!r.limitReached.empty())
      break;
    if (!any)
      r.deadlocks.push_back(s);
    if (timed) {
      if (hasStep.size() <= s) {
        hasStep.resize(s + 1, 0);
        tickSucc.resize(s + 1, kNone);
      }
      hasStep[s] = step;
      tickSucc[s] = tick;
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
                                          parent.capacity() * 8);
  return true;
}
