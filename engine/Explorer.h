//===- Explorer.h - state-space exploration ---------------------*- C++ -*-===//
//
// Explores the reachable states of a flat module under the semantics of
// ir/semantics: the successor generator (sem::Semantics), the state store
// (StateStore) and the order of expansion (breadth-first by default, so
// that paths to a found state are shortest; depth-first on request) are
// separate pieces. Limits on states, memory and time stop the search
// cleanly with a partial result marked incomplete. Edges are kept only when
// an output needs them; parents are always kept, for traces.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_EXPLORER_H
#define NETLIFT_ENGINE_EXPLORER_H

#include "engine/Semantics.h"
#include "engine/StateStore.h"
#include "engine/StepRelation.h"

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ADT/StringMap.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace netlift::engine {

struct ExploreOptions {
  bool depthFirst = false;
  uint64_t maxStates = 0; // 0: no limit
  uint64_t maxMemory = 0; // bytes; 0: no limit
  double timeLimit = 0;   // seconds; 0: no limit
  bool recordEdges = false;
  bool progress = false; // print progress on stderr
  /// Label each edge also with the input valuations that take it
  /// (--edge-labels inputs; the semantics must record them).
  bool inputLabels = false;
  /// Stop at the first state satisfying this (checked as states are
  /// found); set `found` in the result.
  llvm::function_ref<bool(const uint64_t *)> stopAt = nullptr;
};

struct Edge {
  uint32_t from, to, label;
};

struct ExploreResult {
  bool complete = false;
  std::string limitReached; // "states", "memory" or "time" when incomplete
  uint64_t edges = 0;
  std::vector<uint32_t> deadlocks;
  uint64_t deadStates = 0;
  uint64_t maxTokensInPlace = 0;
  uint64_t maxTokensPerMarking = 0;
  double seconds = 0;
  size_t peakBytes = 0;
  std::optional<sem::RuntimeError> error;
  uint32_t errorState = 0; // the state whose successors raised `error`
  std::optional<uint32_t> found;
  /// How many classes of input valuations the step ran for, per expanded
  /// state: classes -> states (what splitting saved, --summary json).
  std::map<uint64_t, uint64_t> inputClasses;
};

class Explorer {
public:
  /// The search of a module's states under its semantics.
  Explorer(sem::Semantics &semantics, ExploreOptions opts);
  /// The search of any step relation's states (`relation` outlives it).
  Explorer(StepRelation &relation, ExploreOptions opts);
  /// Runs to completion or to a limit. False only if the initial state
  /// itself is invalid (error set).
  bool run(ExploreResult &result);

  const StateStore &store() const { return states; }
  /// The semantics explored; only for a module's search.
  const sem::Semantics &semantics() const { return *rel.semantics(); }
  StepRelation &relation() const { return rel; }
  const std::vector<Edge, HugePageAllocator<Edge>> &edges() const {
    return edgeList;
  }
  const std::string &label(uint32_t id) const { return labels[id]; }
  const ExploreOptions &options() const { return opts; }
  /// The label of a step: `{t}`, `{t,u}` (transitions in step order),
  /// `tick` for the empty step.
  static std::string stepText(const net::Module &m,
                              llvm::ArrayRef<uint32_t> step);
  /// The path from the initial state to `s`: (label, state) pairs, the
  /// first being ("", 0).
  std::vector<std::pair<uint32_t, uint32_t>> pathTo(uint32_t s) const;
  static constexpr uint32_t kNone = UINT32_MAX;
  /// States whose successors are generated ahead of being stored
  /// (breadth-first only; see run()).
  static constexpr uint32_t kLookAhead = 2;

private:
  /// The label id of a step; one-transition steps and the tick are looked
  /// up in a table (every edge asks).
  uint32_t internLabel(llvm::ArrayRef<uint32_t> step) {
    if (step.size() <= 1) {
      uint32_t key = step.empty() ? 0 : step[0] + 1;
      if (key < singleLabel.size() && singleLabel[key] != kNone)
        return singleLabel[key];
    }
    return internNewLabel(step);
  }
  uint32_t internNewLabel(llvm::ArrayRef<uint32_t> step);
  /// The label of `step` followed by the input condition, interned.
  uint32_t internConditionLabel(llvm::ArrayRef<uint32_t> step,
                                llvm::StringRef condition);

  std::unique_ptr<StepRelation> ownRelation;
  StepRelation &rel;
  ExploreOptions opts;
  StateStore states;
  std::vector<Edge, HugePageAllocator<Edge>> edgeList;
  /// How each state was first reached (its BFS tree edge), in one array
  /// on huge pages: every new state appends to it.
  struct TreeEdge {
    uint32_t parent, label;
  };
  std::vector<TreeEdge, HugePageAllocator<TreeEdge>> tree;
  llvm::StringMap<uint32_t> labelIds;
  std::vector<uint32_t> singleLabel; // tick (0) and one-transition steps
  std::vector<std::string> labels;
};

} // namespace netlift::engine

#endif
