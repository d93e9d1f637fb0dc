//===- StructuralReasoning.cpp - regions of a state space -----------------===//
#include "backends/structural/StructuralReasoning.h"
#include "backends/structural/EdwardsVenn.h"

#include "llvm/Support/JSON.h"

#include <cstdlib>
#include <fmt/format.h>

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
  ++edgeMap[{from, to}];
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

Analysis::KeyAttributes Analysis::keyAttributes() const {
  KeyAttributes best;
  size_t k = names.size();
  // Smallest sizes first; every exact cover of the smallest size.
  for (size_t size = 1; size <= k && !best.exact; ++size) {
    for (Region set = 0; set < (Region(1) << k); ++set) {
      if (size_t(__builtin_popcount(set)) != size)
        continue;
      uint64_t once = 0;
      for (auto &[r, c] : counts)
        if (__builtin_popcount(r & set) == 1)
          once += c;
      std::vector<size_t> idx;
      for (size_t i = 0; i < k; ++i)
        if ((set >> i) & 1)
          idx.push_back(i);
      if (once == states) {
        if (!best.exact) {
          best.exact = true;
          best.sets.clear();
        }
        best.sets.push_back(idx);
        best.coveredOnce = once;
      } else if (!best.exact && once > best.coveredOnce) {
        best.sets = {idx};
        best.coveredOnce = once;
      }
    }
  }
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
  for (auto &[p, c] : edgeMap)
    e += c;
  if (n != states || e != edges) {
    llvm::errs() << "netlift: internal error: region counts do not add up\n";
    abort();
  }
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
    auto it = counts.find(r);
    if (it == counts.end() && !allRegions)
      continue;
    uint64_t c = it == counts.end() ? 0 : it->second;
    os << "  " << regionName(r) << ": " << c;
    auto d = deadlocks.find(r);
    if (d != deadlocks.end())
      os << " (" << d->second << " deadlocked)";
    if (c == 0)
      os << " (never occurs)";
    os << "\n";
  }
  os << "\nedges between regions:\n";
  for (auto &[p, c] : edgeMap)
    os << "  " << regionName(p.first) << " -> " << regionName(p.second) << ": "
       << c << (p.first == p.second ? " (inside the region)" : "") << "\n";
  KeyAttributes key = keyAttributes();
  os << "\nkey attributes: ";
  if (key.sets.empty()) {
    os << "none\n";
    return;
  }
  os << (key.exact ? "exact cover" : "no exact cover; best partial cover")
     << " (" << key.coveredOnce << " of " << states
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
        auto it = counts.find(r);
        if (it == counts.end() && !allRegions)
          continue;
        j.object([&] {
          j.attribute("region", regionName(r));
          j.attribute("states", int64_t(it == counts.end() ? 0 : it->second));
          auto d = deadlocks.find(r);
          j.attribute("deadlocks",
                      int64_t(d == deadlocks.end() ? 0 : d->second));
        });
      }
    });
    j.attributeArray("edges_between_regions", [&] {
      for (auto &[p, c] : edgeMap)
        j.object([&] {
          j.attribute("from", regionName(p.first));
          j.attribute("to", regionName(p.second));
          j.attribute("edges", int64_t(c));
        });
    });
    j.attributeObject("key_attributes", [&] {
      j.attribute("exact", key.exact);
      j.attribute("covered_once", int64_t(key.coveredOnce));
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
    auto it = counts.find(r);
    if (it == counts.end() && !allRegions)
      continue;
    uint64_t c = it == counts.end() ? 0 : it->second;
    std::string label = regionName(r) + "\\n" + std::to_string(c);
    auto d = deadlocks.find(r);
    if (d != deadlocks.end())
      label += "\\n" + std::to_string(d->second) + " deadlocked";
    // Filled like the region in the Edwards-Venn diagram.
    os << "  r" << r << " [label=\"" << label << "\""
       << (d != deadlocks.end() ? ", color=red, penwidth=2" : "")
       << (c == 0 ? ", style=dashed"
                  : ", style=filled, fillcolor=\"" +
                        regionColour(r, names.size()) + "\"")
       << ", id=\"ag-r" << r << "\"];\n";
  }
  for (auto &[p, c] : edgeMap)
    os << "  r" << p.first << " -> r" << p.second << " [label=\"" << c
       << "\"];\n";
  os << "}\n";
}
