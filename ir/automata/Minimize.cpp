//===- Minimize.cpp - minimal and equivalent Mealy machines ---------------===//
#include "ir/automata/Minimize.h"

#include <algorithm>
#include <deque>
#include <map>
#include <set>

using namespace netlift;
using namespace netlift::automata;

namespace {

/// The completed machine as tables over all 2^n input vectors: next state
/// and output id per (state, vector); the last state is the error sink and
/// output id 0 is "error".
struct Completed {
  uint32_t numStates = 0, numLetters = 0, sink = 0;
  std::vector<uint32_t> next, out;
  std::vector<std::string> outputs{"error"};

  uint32_t outputId(const std::string &o) {
    auto it = std::find(outputs.begin(), outputs.end(), o);
    if (it != outputs.end())
      return uint32_t(it - outputs.begin());
    outputs.push_back(o);
    return uint32_t(outputs.size() - 1);
  }
};

bool matches(const std::string &cube, uint32_t v) {
  size_t n = cube.size();
  for (size_t i = 0; i < n; ++i) {
    char bit = ((v >> (n - 1 - i)) & 1) ? '1' : '0';
    if (cube[i] != '-' && cube[i] != bit)
      return false;
  }
  return true;
}

/// `perm[i]`: which column of the machine's inputs is signal i of the
/// reference order (identity when null).
void complete(const MealyMachine &m, Completed &c,
              const std::vector<size_t> *perm = nullptr) {
  size_t n = m.inputs.size();
  c.numLetters = 1u << n;
  c.numStates = m.states.size() + 1;
  c.sink = m.states.size();
  c.next.assign(size_t(c.numStates) * c.numLetters, c.sink);
  c.out.assign(size_t(c.numStates) * c.numLetters, 0);
  for (const MealyTransition &t : m.transitions) {
    std::string cube = t.input;
    if (perm)
      for (size_t i = 0; i < n; ++i)
        cube[i] = t.input[(*perm)[i]];
    uint32_t id = c.outputId(t.output);
    for (uint32_t v = 0; v < c.numLetters; ++v) {
      if (!matches(cube, v))
        continue;
      size_t k = size_t(t.from) * c.numLetters + v;
      if (c.out[k] == 0) { // first row covering it (rows are deterministic)
        c.next[k] = t.to;
        c.out[k] = id;
      }
    }
  }
}
} // namespace

bool netlift::automata::minimize(const MealyMachine &m, MealyMachine &out,
                                 std::string &why) {
  if (m.inputs.size() > kMaxEnumeratedInputs) {
    why = "minimisation enumerates input vectors: at most " +
          std::to_string(kMaxEnumeratedInputs) + " inputs";
    return false;
  }
  Completed c;
  complete(m, c);
  uint32_t N = c.numStates, K = c.numLetters;
  // Hopcroft's partition refinement, O(k n log n) for k input vectors:
  // start from the classes of equal output rows, then split every class
  // by its predecessors in a splitter class, always queueing the smaller
  // half.
  std::vector<uint32_t> block(N);
  std::vector<std::vector<uint32_t>> members;
  {
    std::map<std::vector<uint32_t>, uint32_t> ids;
    for (uint32_t s = 0; s < N; ++s) {
      std::vector<uint32_t> sig(c.out.begin() + size_t(s) * K,
                                c.out.begin() + size_t(s + 1) * K);
      auto [it, fresh] = ids.try_emplace(sig, members.size());
      if (fresh)
        members.emplace_back();
      block[s] = it->second;
      members[it->second].push_back(s);
    }
  }
  // pred[v][t]: states that go to t on input vector v.
  std::vector<std::vector<std::vector<uint32_t>>> pred(
      K, std::vector<std::vector<uint32_t>>(N));
  for (uint32_t s = 0; s < N; ++s)
    for (uint32_t v = 0; v < K; ++v)
      pred[v][c.next[size_t(s) * K + v]].push_back(s);
  std::vector<std::vector<char>> queued;
  std::deque<std::pair<uint32_t, uint32_t>> work;
  for (uint32_t b = 0; b < members.size(); ++b) {
    queued.emplace_back(K, 1);
    for (uint32_t v = 0; v < K; ++v)
      work.push_back({b, v});
  }
  std::vector<uint32_t> marked(N, 0), count;
  uint32_t stamp = 0;
  while (!work.empty()) {
    auto [splitter, v] = work.front();
    work.pop_front();
    queued[splitter][v] = 0;
    ++stamp;
    std::vector<uint32_t> hit, touched;
    for (uint32_t t : members[splitter])
      for (uint32_t p : pred[v][t])
        if (marked[p] != stamp) {
          marked[p] = stamp;
          hit.push_back(p);
        }
    count.assign(members.size(), 0);
    for (uint32_t p : hit)
      if (count[block[p]]++ == 0)
        touched.push_back(block[p]);
    for (uint32_t y : touched) {
      if (count[y] == members[y].size())
        continue; // the whole class goes into the splitter: no split
      uint32_t z = members.size();
      members.emplace_back();
      queued.emplace_back(K, 0);
      std::vector<uint32_t> keep;
      for (uint32_t s : members[y])
        (marked[s] == stamp ? members[z] : keep).push_back(s);
      members[y] = std::move(keep);
      for (uint32_t s : members[z])
        block[s] = z;
      for (uint32_t w = 0; w < K; ++w) {
        uint32_t add =
            queued[y][w] || members[z].size() <= members[y].size() ? z : y;
        if (!queued[add][w]) {
          queued[add][w] = 1;
          work.push_back({add, w});
        }
      }
    }
  }
  // Build the quotient, reachable part from the initial state, in BFS
  // order. The sink is never a target of a specified row, so it only
  // appears as "no row" (unspecified behaviour).
  out = MealyMachine();
  out.name = m.name;
  out.inputs = m.inputs;
  out.outputs = m.outputs;
  out.inputSymbols = m.inputSymbols;
  out.outputSymbols = m.outputSymbols;
  std::vector<int64_t> newIndex(N, -1); // by block
  std::vector<uint32_t> repr;           // block -> original state
  std::deque<uint32_t> queue;
  auto visit = [&](uint32_t s) -> uint32_t {
    uint32_t b = block[s];
    if (newIndex[b] < 0) {
      newIndex[b] = out.states.size();
      out.states.push_back(m.states[s]);
      repr.push_back(s);
      queue.push_back(b);
    }
    return uint32_t(newIndex[b]);
  };
  out.initial = visit(m.initial);
  while (!queue.empty()) {
    uint32_t b = queue.front();
    queue.pop_front();
    uint32_t s = repr[newIndex[b]];
    for (uint32_t v = 0; v < K; ++v) {
      size_t k = size_t(s) * K + v;
      if (c.out[k] == 0)
        continue; // unspecified: stays unspecified in the quotient
      MealyTransition t;
      t.input = vectorBits(v, m.inputs.size());
      t.from = uint32_t(newIndex[b]);
      t.to = visit(c.next[k]);
      t.output = c.outputs[c.out[k]];
      out.transitions.push_back(std::move(t));
    }
  }
  // One row per input vector above; written back as cubes.
  out.mergeInputCubes();
  return true;
}

bool netlift::automata::checkEquivalence(const MealyMachine &a,
                                         const MealyMachine &b,
                                         EquivalenceResult &r,
                                         std::string &why) {
  if (a.inputs.size() > kMaxEnumeratedInputs) {
    why = "equivalence enumerates input vectors: at most " +
          std::to_string(kMaxEnumeratedInputs) + " inputs";
    return false;
  }
  std::vector<std::string> sa = a.inputs, sb = b.inputs;
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  if (sa != sb || a.outputs.size() != b.outputs.size()) {
    why = "the machines have different input signals or output counts";
    return false;
  }
  if (a.outputs != b.outputs) {
    why = "the machines have different output signals";
    return false;
  }
  // b's columns in a's signal order.
  std::vector<size_t> perm(a.inputs.size());
  for (size_t i = 0; i < a.inputs.size(); ++i)
    perm[i] = size_t(std::find(b.inputs.begin(), b.inputs.end(), a.inputs[i]) -
                     b.inputs.begin());
  Completed ca, cb;
  complete(a, ca);
  complete(b, cb, &perm);
  uint32_t K = ca.numLetters;
  // Breadth-first over state pairs: the first difference is shortest.
  std::map<std::pair<uint32_t, uint32_t>, std::pair<int64_t, uint32_t>>
      parent; // pair -> (parent pair index, letter)
  std::vector<std::pair<uint32_t, uint32_t>> order;
  std::deque<size_t> queue;
  auto start = std::make_pair(a.initial, b.initial);
  parent[start] = {-1, 0};
  order.push_back(start);
  queue.push_back(0);
  while (!queue.empty()) {
    size_t i = queue.front();
    queue.pop_front();
    auto [x, y] = order[i];
    for (uint32_t v = 0; v < K; ++v) {
      size_t kx = size_t(x) * K + v, ky = size_t(y) * K + v;
      const std::string &ox = ca.outputs[ca.out[kx]];
      const std::string &oy = cb.outputs[cb.out[ky]];
      if (ox != oy) {
        r.equivalent = false;
        r.outputA = ox;
        r.outputB = oy;
        std::vector<std::string> seq{vectorBits(v, a.inputs.size())};
        for (int64_t p = int64_t(i); parent[order[p]].first >= 0;
             p = parent[order[p]].first)
          seq.push_back(vectorBits(parent[order[p]].second, a.inputs.size()));
        std::reverse(seq.begin(), seq.end());
        r.witness = std::move(seq);
        return true;
      }
      auto nextPair = std::make_pair(ca.next[kx], cb.next[ky]);
      if (parent.try_emplace(nextPair, std::make_pair(int64_t(i), v)).second) {
        order.push_back(nextPair);
        queue.push_back(order.size() - 1);
      }
    }
  }
  return true;
}

void automata::writeEquivalence(const MealyMachine &m,
                                const EquivalenceResult &r,
                                llvm::raw_ostream &os) {
  if (r.equivalent) {
    os << "equivalent\n";
    return;
  }
  os << "not equivalent: after the inputs";
  for (const std::string &v : r.witness)
    os << ' ' << m.inputLabel(v);
  os << " the outputs are " << m.outputLabel(r.outputA) << " and "
     << m.outputLabel(r.outputB) << "\n";
}
