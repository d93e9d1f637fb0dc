//===- Mealy.cpp - Mealy machines over Boolean vectors --------------------===//
#include "ir/automata/Mealy.h"

#include <algorithm>
#include <map>

using namespace netlift;
using namespace netlift::automata;

std::string netlift::automata::vectorBits(uint32_t v, size_t n) {
  std::string s(n, '0');
  for (size_t i = 0; i < n; ++i)
    if ((v >> (n - 1 - i)) & 1)
      s[i] = '1';
  return s;
}

uint32_t MealyMachine::stateIndex(const std::string &s) {
  auto it = std::find(states.begin(), states.end(), s);
  if (it != states.end())
    return uint32_t(it - states.begin());
  states.push_back(s);
  return uint32_t(states.size() - 1);
}

bool MealyMachine::cubesIntersect(const std::string &a, const std::string &b) {
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    if (a[i] != '-' && b[i] != '-' && a[i] != b[i])
      return false;
  return true;
}

static bool outputsConflict(const std::string &a, const std::string &b) {
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    if (a[i] != '-' && b[i] != '-' && a[i] != b[i])
      return true;
  return false;
}

bool MealyMachine::checkDeterminism(DiagEngine &diag) const {
  bool ok = true;
  std::vector<std::vector<uint32_t>> byState(states.size());
  for (uint32_t i = 0; i < transitions.size(); ++i)
    byState[transitions[i].from].push_back(i);
  for (const auto &list : byState)
    for (size_t x = 0; x < list.size(); ++x)
      for (size_t y = x + 1; y < list.size(); ++y) {
        const MealyTransition &a = transitions[list[x]];
        const MealyTransition &b = transitions[list[y]];
        if (!cubesIntersect(a.input, b.input))
          continue;
        if (a.to == b.to && !outputsConflict(a.output, b.output))
          continue;
        ok = false;
        diag.error(b.loc,
                   "nondeterministic: in state '" + states[b.from] + "', " +
                       (isSymbolic()
                            ? "two edges read '" + inputLabel(b.input) + "'"
                            : "inputs " + b.input + " overlap " + a.input) +
                       " but lead to " +
                       (a.to != b.to ? "different states ('" + states[a.to] +
                                           "', '" + states[b.to] + "')"
                                     : std::string("contradicting "
                                                   "outputs")));
        diag.note(a.loc, "the overlapping transition is here");
      }
  return ok;
}

std::vector<int64_t> MealyMachine::unspecifiedVectors() const {
  std::vector<int64_t> out(states.size(), -1);
  if (inputs.size() > 24)
    return out;
  // A machine over symbols has only its alphabet's codes to cover.
  uint64_t n =
      isSymbolic() ? inputSymbols.size() : uint64_t(1) << inputs.size();
  std::vector<std::vector<const std::string *>> cubes(states.size());
  for (const MealyTransition &t : transitions)
    cubes[t.from].push_back(&t.input);
  for (size_t s = 0; s < states.size(); ++s) {
    int64_t missing = 0;
    for (uint64_t v = 0; v < n; ++v) {
      bool covered = false;
      for (const std::string *c : cubes[s]) {
        bool match = true;
        for (size_t i = 0; i < inputs.size() && match; ++i) {
          char bit = ((v >> (inputs.size() - 1 - i)) & 1) ? '1' : '0';
          match = (*c)[i] == '-' || (*c)[i] == bit;
        }
        if (match) {
          covered = true;
          break;
        }
      }
      missing += !covered;
    }
    out[s] = missing;
  }
  return out;
}

void netlift::automata::cubeVectors(const std::string &cube,
                                    std::vector<uint32_t> &out) {
  size_t n = cube.size();
  uint32_t base = 0;
  std::vector<uint32_t> free;
  for (size_t i = 0; i < n; ++i) {
    uint32_t bit = uint32_t(1) << (n - 1 - i);
    if (cube[i] == '1')
      base |= bit;
    else if (cube[i] == '-')
      free.push_back(bit);
  }
  for (uint32_t k = 0; k < (uint32_t(1) << free.size()); ++k) {
    uint32_t v = base;
    for (size_t j = 0; j < free.size(); ++j)
      if ((k >> j) & 1)
        v |= free[j];
    out.push_back(v);
  }
}

/// Disjoint cubes covering exactly `vectors` (n-bit, distinct).
static std::vector<std::string> mergeVectors(std::vector<uint32_t> vectors,
                                             size_t n) {
  // A cube as (value, mask of '-' positions); merging at position j joins
  // two cubes equal but for bit j, both specified there.
  std::vector<std::pair<uint32_t, uint32_t>> cubes;
  for (uint32_t v : vectors)
    cubes.push_back({v, 0});
  for (size_t i = 0; i < n; ++i) {
    uint32_t bit = uint32_t(1) << (n - 1 - i);
    std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> halves;
    for (size_t c = 0; c < cubes.size(); ++c) {
      if (cubes[c].second & bit)
        continue;
      auto &h =
          halves.try_emplace({cubes[c].first & ~bit, cubes[c].second}, -1, -1)
              .first->second;
      (cubes[c].first & bit ? h.second : h.first) = int(c);
    }
    std::vector<char> gone(cubes.size(), 0);
    std::vector<std::pair<uint32_t, uint32_t>> merged;
    for (auto &[key, h] : halves)
      if (h.first >= 0 && h.second >= 0) {
        gone[h.first] = gone[h.second] = 1;
        merged.push_back({key.first, key.second | bit});
      }
    if (merged.empty())
      continue;
    for (size_t c = 0; c < cubes.size(); ++c)
      if (!gone[c])
        merged.push_back(cubes[c]);
    cubes = std::move(merged);
  }
  std::sort(cubes.begin(), cubes.end());
  std::vector<std::string> out;
  for (auto [value, mask] : cubes) {
    std::string s = vectorBits(value, n);
    for (size_t i = 0; i < n; ++i)
      if ((mask >> (n - 1 - i)) & 1)
        s[i] = '-';
    out.push_back(std::move(s));
  }
  return out;
}

void MealyMachine::mergeInputCubes() {
  if (inputs.size() > 24 || isSymbolic())
    return;
  struct Group {
    uint32_t from, to;
    std::string output;
    std::vector<uint32_t> vectors;
  };
  std::vector<Group> groups;
  std::vector<std::vector<uint32_t>> groupsOf(states.size());
  for (const MealyTransition &t : transitions) {
    Group *g = nullptr;
    for (uint32_t k : groupsOf[t.from])
      if (groups[k].to == t.to && groups[k].output == t.output)
        g = &groups[k];
    if (!g) {
      groupsOf[t.from].push_back(groups.size());
      g = &groups.emplace_back(Group{t.from, t.to, t.output, {}});
    }
    cubeVectors(t.input, g->vectors);
  }
  std::vector<MealyTransition> rows;
  for (uint32_t s = 0; s < states.size(); ++s) {
    // Pairs in order of their smallest vector.
    std::vector<uint32_t> order = groupsOf[s];
    for (uint32_t k : order) {
      std::sort(groups[k].vectors.begin(), groups[k].vectors.end());
      groups[k].vectors.erase(
          std::unique(groups[k].vectors.begin(), groups[k].vectors.end()),
          groups[k].vectors.end());
    }
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return groups[a].vectors[0] < groups[b].vectors[0];
    });
    for (uint32_t k : order)
      for (std::string &cube : mergeVectors(groups[k].vectors, inputs.size()))
        rows.push_back({std::move(cube), s, groups[k].to, groups[k].output,
                        llvm::SMLoc()});
  }
  transitions = std::move(rows);
}

unsigned MealyMachine::symbolWidth(size_t n) {
  unsigned bits = 1;
  while ((size_t(1) << bits) < n)
    ++bits;
  return bits;
}

static uint32_t vectorValue(const std::string &v) {
  uint32_t x = 0;
  for (char c : v)
    x = (x << 1) | (c == '1');
  return x;
}

static std::string symbolOf(const std::vector<std::string> &symbols,
                            const std::string &vector) {
  if (symbols.empty() || vector.find_first_not_of("01") != std::string::npos)
    return vector;
  uint32_t code = vectorValue(vector);
  return code < symbols.size() ? symbols[code] : vector;
}

std::string MealyMachine::inputLabel(const std::string &vector) const {
  return symbolOf(inputSymbols, vector);
}

std::string MealyMachine::outputLabel(const std::string &vector) const {
  return symbolOf(outputSymbols, vector);
}

static void namedSignals(std::vector<std::string> &names, size_t n,
                         char prefix) {
  names.clear();
  for (size_t i = 0; i < n; ++i)
    names.push_back(prefix + std::to_string(i + 1));
}

void MealyMachine::recodeSymbols(const std::vector<std::string> &newInputs,
                                 const std::vector<std::string> &newOutputs) {
  auto codeMap = [](const std::vector<std::string> &from,
                    const std::vector<std::string> &to) {
    std::vector<uint32_t> map;
    for (const std::string &sym : from)
      map.push_back(
          uint32_t(std::find(to.begin(), to.end(), sym) - to.begin()));
    return map;
  };
  std::vector<uint32_t> inMap = codeMap(inputSymbols, newInputs),
                        outMap = codeMap(outputSymbols, newOutputs);
  unsigned inBits = symbolWidth(newInputs.size()),
           outBits = symbolWidth(newOutputs.size());
  std::vector<MealyTransition> rows;
  std::vector<uint32_t> codes;
  for (const MealyTransition &t : transitions) {
    codes.clear();
    cubeVectors(t.input, codes);
    for (uint32_t c : codes)
      if (c < inMap.size())
        rows.push_back({vectorBits(inMap[c], inBits), t.from, t.to,
                        vectorBits(outMap[vectorValue(t.output)], outBits),
                        t.loc});
  }
  transitions = std::move(rows);
  inputSymbols = newInputs;
  outputSymbols = newOutputs;
  namedSignals(inputs, inBits, 'i');
  namedSignals(outputs, outBits, 'o');
}

bool netlift::automata::alignAlphabets(MealyMachine &a, MealyMachine &b,
                                       std::string &why) {
  if (!a.isSymbolic() && !b.isSymbolic())
    return true;
  if (a.isSymbolic() != b.isSymbolic()) {
    why = "one machine reads input symbols, the other Boolean signals";
    return false;
  }
  auto unite = [](std::vector<std::string> x,
                  const std::vector<std::string> &y) {
    for (const std::string &s : y)
      if (std::find(x.begin(), x.end(), s) == x.end())
        x.push_back(s);
    return x;
  };
  std::vector<std::string> in = unite(a.inputSymbols, b.inputSymbols),
                           out = unite(a.outputSymbols, b.outputSymbols);
  a.recodeSymbols(in, out);
  b.recodeSymbols(in, out);
  return true;
}
