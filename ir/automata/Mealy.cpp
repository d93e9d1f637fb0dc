//===- Mealy.cpp - Mealy machines over Boolean vectors --------------------===//
#include "ir/automata/Mealy.h"

#include <algorithm>

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
                   "nondeterministic: in state '" + states[b.from] +
                       "', inputs " + b.input + " overlap " + a.input +
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
  uint64_t n = uint64_t(1) << inputs.size();
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
