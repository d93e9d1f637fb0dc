//===- StructuralReasoning.cpp - regions of a state space -----------------===//
#include "backends/structural/StructuralReasoning.h"
#include "backends/structural/EdwardsVenn.h"

#include "llvm/Support/JSON.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <set>

using namespace netlift;
using namespace netlift::structural;

Analysis::Analysis(std::vector<std::string> attributeNames)
    : names(std::move(attributeNames)) {}

void Analysis::addState(Region r, bool deadlock) {
  ++states;
  ++counts[r];
  if (deadlock)
    ++deadlocks[r];
}

void Analysis::addEdge(Region from, Region to) {
  ++edges;
  ++edgeHash[uint64_t(from) << 32 | to];
  edgeMapStale = true;
}

const std::map<std::pair<Region, Region>, uint64_t> &
Analysis::edgeCounts() const {
  if (edgeMapStale) {
    edgeMap.clear();
    for (auto &[key, c] : edgeHash)
      edgeMap[{Region(key >> 32), Region(key)}] = c;
    edgeMapStale = false;
  }
  return edgeMap;
}

uint64_t Analysis::statesIn(Region r) const {
  auto it = counts.find(r);
  return it == counts.end() ? 0 : it->second;
}

uint64_t Analysis::deadlocksIn(Region r) const {
  auto it = deadlocks.find(r);
  return it == deadlocks.end() ? 0 : it->second;
}

uint64_t Analysis::attributeCount(size_t i) const {
  uint64_t n = 0;
  for (auto &[r, c] : counts)
    if ((r >> i) & 1)
      n += c;
  return n;
}

std::vector<uint64_t> Analysis::necklaces() const {
  std::vector<uint64_t> out(names.size() + 1, 0);
  for (auto &[r, c] : counts)
    out[__builtin_popcount(r)] += c;
  return out;
}

std::string Analysis::KeyAttributes::kindText() const {
  if (exact)
    return "exact cover";
  return exhaustive ? "no exact cover; best partial cover"
                    : "no exact cover; a partial cover found greedily (too "
                      "many attributes to try every subset)";
}

namespace {
/// Enumerates the exact covers of the occurring regions by attributes
/// (Algorithm X): every region must hold exactly one chosen attribute.
struct CoverSearch {
  std::vector<Region> regions;  // occurring, non-empty
  std::vector<Region> together; // per attribute: attributes sharing a region
  std::vector<Region> found;
  size_t bestSize = SIZE_MAX;

  void run(std::vector<uint8_t> &covered, Region chosen, Region allowed) {
    if (size_t(__builtin_popcount(chosen)) > bestSize)
      return;
    // The uncovered region with the fewest allowed attributes.
    int pick = -1;
    int fewest = 64;
    for (size_t i = 0; i < regions.size(); ++i)
      if (!covered[i]) {
        int n = __builtin_popcount(regions[i] & allowed);
        if (n < fewest) {
          fewest = n;
          pick = int(i);
        }
      }
    if (pick < 0) {
      size_t size = __builtin_popcount(chosen);
      if (size < bestSize) {
        bestSize = size;
        found.clear();
      }
      found.push_back(chosen);
      return;
    }
    for (Region cand = regions[pick] & allowed; cand; cand &= cand - 1) {
      unsigned a = __builtin_ctz(cand);
      std::vector<size_t> newly;
      for (size_t i = 0; i < regions.size(); ++i)
        if (!covered[i] && ((regions[i] >> a) & 1)) {
          covered[i] = 1;
          newly.push_back(i);
        }
      run(covered, chosen | (Region(1) << a), allowed & ~together[a]);
      for (size_t i : newly)
        covered[i] = 0;
      // Later candidates must not cover the picked region twice: they
      // exclude this one, which is implied since each branch picks one.
    }
  }
};

std::vector<size_t> indices(Region set, size_t k) {
  std::vector<size_t> idx;
  for (size_t i = 0; i < k; ++i)
    if ((set >> i) & 1)
      idx.push_back(i);
  return idx;
}
} // namespace

Analysis::KeyAttributes Analysis::keyAttributes() const {
  KeyAttributes best;
  size_t k = names.size();
  if (k == 0 || states == 0)
    return best;
  std::vector<std::pair<Region, uint64_t>> occurring(counts.begin(),
                                                     counts.end());
  // Exact covers: impossible if some state has no attribute at all.
  if (!counts.count(0)) {
    CoverSearch search;
    search.together.assign(k, 0);
    for (auto &[r, c] : occurring) {
      search.regions.push_back(r);
      for (Region a = r; a; a &= a - 1)
        search.together[__builtin_ctz(a)] |= r;
    }
    for (size_t a = 0; a < k; ++a)
      search.together[a] |= Region(1) << a;
    std::vector<uint8_t> covered(search.regions.size(), 0);
    search.run(covered, 0, (Region(1) << k) - 1);
    if (!search.found.empty()) {
      std::sort(search.found.begin(), search.found.end());
      best.exact = true;
      best.coveredOnce = states;
      for (Region set : search.found)
        best.sets.push_back(indices(set, k));
      return best;
    }
  }
  auto coveredOnce = [&](Region set) {
    uint64_t once = 0;
    for (auto &[r, c] : occurring)
      if (__builtin_popcount(r & set) == 1)
        once += c;
    return once;
  };
  // No exact cover: the subset covering the most states exactly once
  // (smallest first, then lowest bits), exhaustively when affordable.
  if ((uint64_t(1) << k) * occurring.size() <= 200000000) {
    Region bestSet = 0;
    for (size_t size = 1; size <= k; ++size)
      for (Region set = 1; set < (Region(1) << k); ++set) {
        if (size_t(__builtin_popcount(set)) != size)
          continue;
        uint64_t once = coveredOnce(set);
        if (once > best.coveredOnce) {
          best.coveredOnce = once;
          bestSet = set;
        }
      }
    if (bestSet)
      best.sets = {indices(bestSet, k)};
    return best;
  }
  // Greedy: add (or drop) the attribute that helps most until nothing does.
  best.exhaustive = false;
  Region set = 0;
  uint64_t value = 0;
  for (bool improved = true; improved;) {
    improved = false;
    Region bestMove = 0;
    for (size_t a = 0; a < k; ++a) {
      Region next = set ^ (Region(1) << a);
      uint64_t v = coveredOnce(next);
      if (v > value) {
        value = v;
        bestMove = next;
        improved = true;
      }
    }
    if (improved)
      set = bestMove;
  }
  best.coveredOnce = value;
  if (set)
    best.sets = {indices(set, k)};
  return best;
}

std::string Analysis::regionName(Region r) const {
  std::string s = "{";
  bool first = true;
  for (size_t i = 0; i < names.size(); ++i)
    if ((r >> i) & 1) {
      s += (first ? "" : ",") + names[i];
      first = false;
    }
  return s + "}";
}

void Analysis::checkInvariants() const {
  uint64_t n = 0, e = 0;
  for (auto &[r, c] : counts)
    n += c;
  for (auto &[p, c] : edgeCounts())
    e += c;
  // Every state and edge falls in exactly one region (pair): a bug in
  // netlift otherwise, never a property of the input.
  assert(n == states && e == edges && "region counts do not add up");
  (void)n;
  (void)e;
}

std::vector<Region> Analysis::regionsNeverLeft() const {
  std::vector<Region> out;
  if (edges == 0)
    return out;
  std::set<Region> left;
  for (auto &[p, c] : edgeCounts())
    if (p.first != p.second)
      left.insert(p.first);
  for (auto &[r, c] : counts)
    if (c && !left.count(r))
      out.push_back(r);
  return out;
}

void Analysis::writeText(llvm::raw_ostream &os, bool allRegions) const {
  checkInvariants();
  os << "states: " << states << ", edges: " << edges
     << ", attributes: " << names.size() << "\n\ndensities:\n";
  for (size_t i = 0; i < names.size(); ++i) {
    uint64_t c = attributeCount(i);
    os << fmt::format("  {:<20} {:>10} {:.4f}\n", names[i], c,
                      states ? double(c) / states : 0.0);
  }
  os << "\nnecklaces (states with exactly j attributes):\n";
  std::vector<uint64_t> nk = necklaces();
  for (size_t j = 0; j < nk.size(); ++j)
    os << fmt::format("  j={:<3} {:>10} {:.4f}\n", j, nk[j],
                      states ? double(nk[j]) / states : 0.0);
  os << "\nregions:\n";
  for (Region r = 0; r < (Region(1) << names.size()); ++r) {
    uint64_t c = statesIn(r), d = deadlocksIn(r);
    if (c == 0 && !allRegions)
      continue;
    os << "  " << regionName(r) << ": " << c;
    if (d)
      os << " (" << d << " deadlocked)";
    if (c == 0)
      os << " (never occurs)";
    os << "\n";
  }
  os << "\nedges between regions:\n";
  for (auto &[p, c] : edgeCounts())
    os << "  " << regionName(p.first) << " -> " << regionName(p.second) << ": "
       << c << (p.first == p.second ? " (inside the region)" : "") << "\n";
  if (edges) {
    os << "\nregions never left:";
    std::vector<Region> trapped = regionsNeverLeft();
    if (trapped.empty())
      os << " none";
    os << "\n";
    for (Region r : trapped)
      os << "  " << regionName(r) << ": " << statesIn(r) << " states\n";
  }
  KeyAttributes key = keyAttributes();
  os << "\nkey attributes: ";
  if (key.sets.empty()) {
    os << "none\n";
    return;
  }
  os << key.kindText() << " (" << key.coveredOnce << " of " << states
     << " states have exactly one)\n";
  for (const auto &set : key.sets) {
    os << "  {";
    for (size_t i = 0; i < set.size(); ++i)
      os << (i ? "," : "") << names[set[i]];
    os << "}\n";
  }
}

void Analysis::writeJson(llvm::raw_ostream &os, bool allRegions) const {
  checkInvariants();
  llvm::json::OStream j(os, 1);
  KeyAttributes key = keyAttributes();
  j.object([&] {
    j.attribute("states", int64_t(states));
    j.attribute("edges", int64_t(edges));
    j.attributeArray("attributes", [&] {
      for (size_t i = 0; i < names.size(); ++i)
        j.object([&] {
          j.attribute("name", names[i]);
          j.attribute("states", int64_t(attributeCount(i)));
        });
    });
    j.attributeArray("necklaces", [&] {
      for (uint64_t n : necklaces())
        j.value(int64_t(n));
    });
    j.attributeArray("regions", [&] {
      for (Region r = 0; r < (Region(1) << names.size()); ++r) {
        if (!statesIn(r) && !allRegions)
          continue;
        j.object([&] {
          j.attribute("region", regionName(r));
          j.attribute("states", int64_t(statesIn(r)));
          j.attribute("deadlocks", int64_t(deadlocksIn(r)));
        });
      }
    });
    j.attributeArray("edges_between_regions", [&] {
      for (auto &[p, c] : edgeCounts())
        j.object([&] {
          j.attribute("from", regionName(p.first));
          j.attribute("to", regionName(p.second));
          j.attribute("edges", int64_t(c));
        });
    });
    j.attributeArray("regions_never_left", [&] {
      for (Region r : regionsNeverLeft())
        j.object([&] {
          j.attribute("region", regionName(r));
          j.attribute("states", int64_t(statesIn(r)));
        });
    });
    j.attributeObject("key_attributes", [&] {
      j.attribute("exact", key.exact);
      j.attribute("covered_once", int64_t(key.coveredOnce));
      j.attribute("exhaustive", key.exhaustive);
      j.attributeArray("sets", [&] {
        for (const auto &set : key.sets)
          j.array([&] {
            for (size_t i : set)
              j.value(names[i]);
          });
      });
    });
  });
  os << "\n";
}

void Analysis::writeDot(llvm::raw_ostream &os, bool allRegions) const {
  checkInvariants();
  os << "digraph attribute_graph {\n  node [shape=ellipse, "
        "fontname=Helvetica];\n  edge [fontname=Helvetica, fontsize=10];\n";
  for (Region r = 0; r < (Region(1) << names.size()); ++r) {
    uint64_t c = statesIn(r), d = deadlocksIn(r);
    if (c == 0 && !allRegions)
      continue;
    std::string label = regionName(r) + "\\n" + std::to_string(c);
    if (d)
      label += "\\n" + std::to_string(d) + " deadlocked";
    // Filled like the region in the Edwards-Venn diagram.
    os << "  r" << r << " [label=\"" << label << "\""
       << (d ? ", color=red, penwidth=2" : "")
       << (c == 0 ? ", style=dashed"
                  : ", style=filled, fillcolor=\"" +
                        regionColour(r, names.size()) + "\"")
       << ", id=\"ag-r" << r << "\"];\n";
  }
  for (auto &[p, c] : edgeCounts())
    os << "  r" << p.first << " -> r" << p.second << " [label=\"" << c
       << "\"];\n";
  os << "}\n";
}
