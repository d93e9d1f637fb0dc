//===- ReduceChains.cpp - fuse invisible steps of a chain -----------------===//
//
// `reduce-chains{observe=...}` removes steps nothing can tell apart from
// waiting: a transition t1 that only moves a token from place p0 to place
// p1, where p1 is then consumed by t2, is fused into t2, which now takes
// the token from p0 with the two delays added up:
//
//     p0 --[a1,b1]--> t1 --> p1 --[a2,b2]--> t2 ...
//     p0 --[a1+a2, b1+b2]--> t2 ...           (t1 not urgent)
//     p0 --[a1+a2, a1+b2]--> t2 ...           (t1 urgent: it fires at a1)
//
// Conditions, each needed for the argument below:
//  - t1 has one pre-arc (p0, weight 1) and one post-arc (p1, weight 1), no
//    condition, guard, action, event in or out, and is not observed;
//  - p0 and p1 have capacity 1, are not observed and no expression reads
//    them; t1 is p0's only consumer; p1 starts empty, t1 is its only
//    producer and t2 its only consumer (weight 1);
//  - a P-semiflow shows that p0 and p1 are never marked together, so no
//    producer of p0 can fire while the token is in p1 (in the fused model
//    it would find p0 still full);
//  - if t2 is urgent, so is t1 (otherwise the original may wait in p0 for
//    as long as it likes and then fire t2 at once, which an urgent fused
//    t2 could not);
//  - if t1 is not urgent, both windows are bounded or both unbounded: a
//    token that misses a bounded window stays for good (under weak timing,
//    a deadlock once nothing else moves), and the fused window is bounded
//    exactly when both are.
// t1 changes nothing anything reads, so every run of the original maps to
// a run of the fused model that fires t2 at the same moment (the time
// spent in p0 and p1 adds up to a delay the fused interval admits), and
// back, choosing t1's moment inside [a1,b1]. Intervals that would exceed
// the clock range are not fused. Repeats until no chain is left, so a
// discretised trajectory of unobserved positions becomes one timed arc.
//
// Preserved: the reachable valuations of every element but p1 and the
// clock of p0, and every property over them that does not count steps,
// under the interleaving step policy; the deadlock verdict. Removed: the
// intermediate states where the token sits in p1, and t1's steps.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/semantics/StructuralBounds.h"

#include "llvm/ADT/StringSet.h"

using namespace netlift;
using namespace netlift::net;

namespace {

/// The end of a delay interval plus another, or kInf when either is
/// unbounded; nullopt past the clock range.
std::optional<uint32_t> addDelays(uint32_t a, uint32_t b) {
  if (a == kInf || b == kInf)
    return kInf;
  uint64_t s = uint64_t(a) + b;
  if (s >= kInf)
    return std::nullopt;
  return uint32_t(s);
}

class ReduceChainsPass : public Pass {
public:
  explicit ReduceChainsPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce-chains");
    if (!m)
      return false;
    auto observed = reduce::observedElements(*m, opts, "reduce-chains", diag);
    if (!observed)
      return false;
    // Observation is by name: indices change as rounds remove entities.
    llvm::StringSet<> observedNames;
    for (uint32_t p = 0; p < m->places.size(); ++p)
      if (observed->place[p])
        observedNames.insert(m->places[p].name);
    for (uint32_t t = 0; t < m->transitions.size(); ++t)
      if (observed->trans[t])
        observedNames.insert(m->transitions[t].name);
    unsigned fused = 0;
    for (unsigned round = 0; round < 64; ++round) {
      unsigned n = fuseRound(*m, observedNames);
      if (!n)
        break;
      fused += n;
      // Expressions name places by index: resolve them again before the
      // next round reads them.
      if (!reduce::reverify(d, diag, "reduce-chains"))
        return false;
    }
    stats.add("reduce-chains", "fused", fused,
              "transitions fused into their successor (with a place each)");
    return true;
  }

private:
  /// One pass over the module fusing chains that share nothing; returns how
  /// many it fused.
  unsigned fuseRound(Module &m, const llvm::StringSet<> &observedNames) {
    size_t np = m.places.size(), nt = m.transitions.size();
    reduce::Uses uses(m);
    std::vector<std::vector<uint32_t>> producers(np), consumers(np);
    std::vector<bool> eventSource(nt);
    for (uint32_t t = 0; t < nt; ++t) {
      const Transition &tr = m.transitions[t];
      for (const PreArc &a : tr.pre())
        consumers[a.place].push_back(t);
      for (const PostArc &a : tr.post())
        producers[a.place].push_back(t);
      for (EventSource s : tr.events())
        if (!s.fromPort)
          eventSource[s.index] = true;
    }
    auto hiddenPlace = [&](uint32_t p) {
      return m.places[p].capacity == 1 && !uses.placeRead[p] &&
             !observedNames.count(m.places[p].name);
    };
    std::vector<std::vector<int64_t>> flows;
    bool flowsKnown = false;
    auto neverBoth = [&](uint32_t p, uint32_t q) {
      if (!flowsKnown) {
        flows = sem::placeSemiflows(m);
        flowsKnown = true;
      }
      for (const auto &y : flows) {
        if (y[p] <= 0 || y[q] <= 0)
          continue;
        int64_t held = 0;
        for (size_t i = 0; i < np; ++i)
          held += y[i] * int64_t(m.places[i].tokens);
        if (held < y[p] + y[q])
          return true;
      }
      return false;
    };

    std::vector<bool> keepPlace(np, true), keepTrans(nt, true),
        touched(nt, false);
    unsigned fused = 0;
    for (uint32_t t1 = 0; t1 < nt; ++t1) {
      const Transition &a = m.transitions[t1];
      if (touched[t1] || a.pre().size() != 1 || a.post().size() != 1 ||
          a.pre()[0].weight != 1 || a.post()[0].weight != 1 ||
          !a.conds().empty() || a.guard() || a.hasAction() || a.isForced() ||
          !a.emits().empty() || eventSource[t1] || observedNames.count(a.name))
        continue;
      uint32_t p0 = a.pre()[0].place, p1 = a.post()[0].place;
      if (p0 == p1 || !hiddenPlace(p0) || !hiddenPlace(p1) ||
          m.places[p1].tokens != 0 || consumers[p0].size() != 1 ||
          producers[p1].size() != 1 || consumers[p1].size() != 1)
        continue;
      uint32_t t2 = consumers[p1][0];
      Transition &b = m.transitions[t2];
      if (t2 == t1 || touched[t2] || (b.urgent && !a.urgent))
        continue;
      PreArc *arc = nullptr;
      for (PreArc &x : b.mutablePre())
        if (x.place == p1)
          arc = &x;
      if (!arc || arc->weight != 1)
        continue;
      Interval first = a.pre()[0].time, second = arc->time;
      // A deadline bounds the wait in its own place; fused, it would bound
      // the sum of both waits.
      if (first.deadline || second.deadline)
        continue;
      // Weak timing lets a token miss a finite window and stay for good
      // (a deadlock once nothing else moves). Waiting in p0 for a lazy t1
      // and in p1 for t2 must both be able to end that way, or neither.
      if (!a.urgent && (first.hi == kInf) != (second.hi == kInf))
        continue;
      auto lo = addDelays(first.lo, second.lo);
      auto hi = addDelays(a.urgent ? first.lo : first.hi, second.hi);
      if (!lo || !hi || !neverBoth(p0, p1))
        continue;
      *arc = PreArc{p0, 1, Interval{*lo, *hi}};
      keepTrans[t1] = false;
      keepPlace[p1] = false;
      touched[t1] = touched[t2] = true;
      // Chains through t2 wait for the next round (their arcs changed).
      for (const PreArc &x : b.pre())
        for (uint32_t u : producers[x.place])
          touched[u] = true;
      for (const PostArc &x : b.post())
        for (uint32_t u : consumers[x.place])
          touched[u] = true;
      ++fused;
    }
    if (fused)
      reduce::compactModule(m, keepPlace, keepTrans,
                            std::vector<bool>(m.vars.size(), true));
    return fused;
  }

  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReduceChainsPass(const PassOptions &opts) {
  return std::make_unique<ReduceChainsPass>(opts);
}
} // namespace netlift
