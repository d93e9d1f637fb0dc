//===- StructuralReasoning.h - regions of a state space ---------*- C++ -*-===//
//
// The structural reasoning of Lobov and Lastra over a state space: k
// selected attributes (Boolean predicates over a state) split the states
// into regions (the subset of attributes that holds). From the regions come
// the attribute graph (regions with their state counts, state-space edges
// between and inside regions, deadlocks per region), the density of each
// attribute, the necklace distribution (how many states have exactly j of
// the k attributes) and the key-attribute search (the smallest sets of
// attributes that cover every state exactly once). Memory is proportional
// to the number of regions and region pairs, not to the number of states.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STRUCTURAL_STRUCTURALREASONING_H
#define NETLIFT_BACKENDS_STRUCTURAL_STRUCTURALREASONING_H

#include "llvm/Support/raw_ostream.h"

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace netlift::structural {

using Region = uint32_t; // bit i: attribute i holds

class Analysis {
public:
  explicit Analysis(std::vector<std::string> attributeNames);

  /// Feeds one state (its region, whether it is a deadlock) and the edges
  /// (source region, target region), in any order.
  void addState(Region r, bool deadlock);
  void addEdge(Region from, Region to);

  const std::vector<std::string> &attributes() const { return names; }
  uint64_t numStates() const { return states; }
  uint64_t numEdges() const { return edges; }
  const std::map<Region, uint64_t> &regionCounts() const { return counts; }
  const std::map<Region, uint64_t> &deadlockCounts() const { return deadlocks; }
  /// Edges between (and inside) regions, ordered.
  const std::map<std::pair<Region, Region>, uint64_t> &edgeCounts() const;
  /// States in region `r` (0 if it never occurs), and its deadlocks.
  uint64_t statesIn(Region r) const;
  uint64_t deadlocksIn(Region r) const;
  /// States in which attribute i holds.
  uint64_t attributeCount(size_t i) const;
  /// necklace[j]: states with exactly j attributes.
  std::vector<uint64_t> necklaces() const;

  struct KeyAttributes {
    bool exact = false;
    /// Every minimum exact cover (attribute index sets), or the best
    /// partial cover (one set) when there is none.
    std::vector<std::vector<size_t>> sets;
    uint64_t coveredOnce = 0; // states with exactly one key attribute
    /// False when the partial cover comes from a greedy search (too many
    /// attributes and regions to try every subset).
    bool exhaustive = true;
    /// "exact cover", "no exact cover; best partial cover", ...
    std::string kindText() const;
  };
  /// Exact covers by Knuth's Algorithm X over the occurring regions (all
  /// of minimum size); without one, the subset with the most states
  /// having exactly one attribute, tried exhaustively up to 2^k * regions
  /// = 2e8, greedily beyond.
  KeyAttributes keyAttributes() const;

  /// The occurring regions no edge leaves: once the system is in one of
  /// their states it stays in the region for ever (the paper's lifter with
  /// a pallet stuck and no actuator on, where the controller keeps
  /// scanning, so that no state is a deadlock). Empty when the state space
  /// came without edges.
  std::vector<Region> regionsNeverLeft() const;

  std::string regionName(Region r) const;
  /// Checks the invariants: node counts sum to the states, edge counts to
  /// the edges. Aborts if violated (they are facts, not inputs).
  void checkInvariants() const;

  void writeText(llvm::raw_ostream &os, bool allRegions) const;
  void writeJson(llvm::raw_ostream &os, bool allRegions) const;
  void writeDot(llvm::raw_ostream &os, bool allRegions) const;

private:
  std::vector<std::string> names;
  uint64_t states = 0, edges = 0;
  std::map<Region, uint64_t> counts, deadlocks;
  // Counted in a hash table (a state space has many edges, visiting the
  // region pairs in no order); ordered once when asked for.
  std::unordered_map<uint64_t, uint64_t> edgeHash;
  mutable std::map<std::pair<Region, Region>, uint64_t> edgeMap;
  mutable bool edgeMapStale = false;
};

} // namespace netlift::structural

#endif
