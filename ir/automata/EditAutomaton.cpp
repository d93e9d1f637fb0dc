//===- EditAutomaton.cpp - edit automata over I/O vectors -----------------===//
//
// Step 1: one validation transition per (expanded) Mealy transition, the
// event being the input vector followed by the output vector.
//
// Step 2: a transition s --in/out--> s' whose input vector differs in two
// or more inputs from a vector `prev` with which s can be entered may be
// read by the PLC in several scans. Every reading order is a chain
// prev = r0 < r1 < ... < rk = in of input vectors, each ri flipping a
// non-empty part of the bits still to change. While the plant already
// shows `in`, the machine reacts to the partial readings: from s, r1 gives
// q1 and outputs o1, observed as the vector in.o1; r2 from q1 gives q2, o2,
// observed in.o2; ... The chain is admissible when the final reading of
// `in` (from q_{k-1}) reaches s' with outputs `out`. For admissible chains
// the observed intermediate vectors become suppression transitions into
// intermediate states (one per machine state and observed vector under
// this specified transition), and the final vector a validation into s'.
// A chain whose first observed vector the specification itself validates
// from s is already explained and adds nothing.
//
//===----------------------------------------------------------------------===//
#include "ir/automata/EditAutomaton.h"

#include <algorithm>
#include <functional>
#include <set>
#include <tuple>

using namespace netlift;
using namespace netlift::automata;

const EditTransition *EditAutomaton::step(uint32_t state,
                                          const std::string &event) const {
  auto it = index.find({state, event});
  return it == index.end() ? nullptr : &transitions[it->second];
}

std::vector<std::string> EditAutomaton::expected(uint32_t state) const {
  std::vector<std::string> out;
  for (const EditTransition &t : transitions)
    if (t.from == state)
      out.push_back(t.event);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool EditAutomaton::add(const EditTransition &t) {
  auto [it, fresh] = index.try_emplace({t.from, t.event}, transitions.size());
  if (!fresh) {
    const EditTransition &o = transitions[it->second];
    return o.kind == t.kind && o.to == t.to;
  }
  transitions.push_back(t);
  return true;
}

namespace {

/// Concrete vectors of a cube ('-' expanded).
std::vector<std::string> expand(const std::string &cube) {
  std::vector<std::string> out{""};
  for (char c : cube) {
    std::vector<std::string> next;
    for (const std::string &p : out) {
      if (c != '1')
        next.push_back(p + '0');
      if (c != '0')
        next.push_back(p + '1');
    }
    out = std::move(next);
  }
  return out;
}

struct Concrete {
  uint32_t from, to;
  uint32_t in;
  std::string out; // concrete outputs
};
} // namespace

/// Step 3 (netlift's extension, docs/enforce.md): the observer sees new
/// inputs while the machine, in state `s`, still shows the outputs `p` it
/// arrived with, because the PLC has not reacted yet. That vector is
/// suppressed into a "lagging" state (or into the desynchronisation
/// state already reached on it from `s`) from which the reactions that
/// explain the lag are validated: with delayed outputs, the reaction of
/// `s` to these same inputs; with synchronised inputs, its reaction to the
/// inputs after a second change of another input, read in the same scan.
static bool addLaggingReadings(
    const MealyMachine &m, const std::vector<Concrete> &rows,
    const std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> &react,
    const EditAutomatonOptions &opts, EditAutomaton &ea, std::string &why) {
  if (!opts.delayedOutputs && !opts.synchronisedInputs)
    return true;
  size_t n = m.inputs.size();
  // (inputs, outputs) each state is entered with.
  std::vector<std::set<std::pair<uint32_t, std::string>>> arrivals(
      m.states.size());
  for (const Concrete &r : rows)
    arrivals[r.to].insert({r.in, r.out});
  auto reactions = [&](uint32_t s, uint32_t in) -> const std::vector<size_t> * {
    auto it = react.find({s, in});
    return it == react.end() ? nullptr : &it->second;
  };
  for (uint32_t s = 0; s < m.states.size(); ++s)
    for (const auto &[prev, p] : arrivals[s]) {
      // The input vectors the plant may show before the PLC reacts, each
      // with the reactions that explain the lag.
      std::map<uint32_t, std::vector<size_t>> lagging;
      if (opts.delayedOutputs)
        for (uint32_t in = 0; in < (uint32_t(1) << n); ++in)
          if (in != prev)
            if (const auto *ks = reactions(s, in))
              for (size_t k : *ks)
                if (rows[k].out != p)
                  lagging[in].push_back(k);
      if (opts.synchronisedInputs)
        for (size_t a = 0; a < n; ++a)
          for (size_t b = 0; b < n; ++b) {
            if (a == b)
              continue;
            uint32_t first = prev ^ (uint32_t(1) << a);
            uint32_t both = first ^ (uint32_t(1) << b);
            if (const auto *ks = reactions(s, both))
              for (size_t k : *ks)
                lagging[first].push_back(k);
          }
      for (auto &[in, ks] : lagging) {
        std::string seen = vectorBits(in, n) + p;
        const EditTransition *known = ea.step(s, seen);
        if (known && known->kind == EditKind::Validate)
          continue; // the specification explains the vector
        uint32_t lag = known ? known->to : uint32_t(ea.states.size());
        if (!known) {
          ea.states.push_back(
              {m.states[s] + "~" + seen + "#" + std::to_string(lag), false});
          ea.add({s, seen, EditKind::Suppress, lag});
        }
        for (size_t k : ks) {
          std::string shown = vectorBits(rows[k].in, n) + rows[k].out;
          if (!ea.add({lag, shown, EditKind::Validate, rows[k].to})) {
            why = "a lagging reaction in state '" + m.states[s] + "' after " +
                  seen + " makes the automaton nondeterministic on " + shown;
            return false;
          }
        }
      }
    }
  return true;
}

bool netlift::automata::buildEditAutomaton(const MealyMachine &m,
                                           EditAutomaton &ea, std::string &why,
                                           const EditAutomatonOptions &opts) {
  size_t n = m.inputs.size();
  if (n > 16) {
    why = "edit automata enumerate input vectors: at most 16 inputs";
    return false;
  }
  ea = EditAutomaton();
  ea.signals = m.inputs;
  ea.signals.insert(ea.signals.end(), m.outputs.begin(), m.outputs.end());
  ea.numInputs = n;
  for (const std::string &s : m.states)
    ea.states.push_back({s, true});
  ea.initial = m.initial;

  // The machine on concrete vectors: delta/lambda per (state, input).
  std::vector<Concrete> rows;
  std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> react;
  for (const MealyTransition &t : m.transitions)
    for (const std::string &in : expand(t.input))
      for (const std::string &out : expand(t.output)) {
        uint32_t v = uint32_t(std::stoul(in.empty() ? "0" : in, nullptr, 2));
        react[{t.from, v}].push_back(rows.size());
        rows.push_back({t.from, t.to, v, out});
      }
  // Step 1.
  for (const Concrete &r : rows)
    if (!ea.add(
            {r.from, vectorBits(r.in, n) + r.out, EditKind::Validate, r.to})) {
      why = "the specification gives two reactions to " + vectorBits(r.in, n) +
            r.out + " in state '" + m.states[r.from] + "'";
      return false;
    }
  // Vectors with which each state can be entered.
  std::vector<std::set<uint32_t>> arrivals(m.states.size());
  for (const Concrete &r : rows)
    arrivals[r.to].insert(r.in);

  // Step 2.
  // Intermediate states are keyed by the specified transition's source and
  // input vector (rows that differ only in unspecified output bits share
  // them), the machine state reached and the observed vector.
  std::map<std::tuple<uint32_t, uint32_t, uint32_t, std::string>, uint32_t>
      inter;
  // A bound on the search, so that a specification with many simultaneous
  // input changes is refused rather than left to run for hours.
  constexpr uint64_t kMaxVisits = 5000000;
  uint64_t visits = 0;
  for (size_t ri = 0; ri < rows.size(); ++ri) {
    const Concrete &tr = rows[ri];
    for (uint32_t prev : arrivals[tr.from]) {
      uint32_t diff = prev ^ tr.in;
      if (__builtin_popcount(diff) < 2)
        continue;
      std::string target = vectorBits(tr.in, n) + tr.out;
      // Depth-first over reading chains; `path` holds the observed
      // intermediate steps (machine state, observed vector).
      std::vector<std::pair<uint32_t, std::string>> path;
      // (machine state, inputs read) pairs known to admit no chain: every
      // chain through them is skipped, so each pair is searched once.
      std::set<std::pair<uint32_t, uint32_t>> hopeless;
      // The chain in `path` has arrived (the machine shows the target
      // vector in the target state): its observed vectors become
      // suppressions into intermediate states, the target vector the
      // validation out of the last one. False (with `why`) if that breaks
      // determinism.
      auto arrive = [&]() {
        if (path.empty())
          return true; // the specified transition itself
        // A first observed vector the specification already validates from
        // this state is explained by it: the chain adds nothing (and would
        // break determinism).
        const EditTransition *known = ea.step(tr.from, path.front().second);
        if (known && known->kind == EditKind::Validate)
          return true;
        uint32_t from = tr.from;
        for (auto &[mq, vec] : path) {
          auto key = std::make_tuple(tr.from, tr.in, mq, vec);
          auto [slot, fresh] = inter.try_emplace(key, ea.states.size());
          if (fresh)
            ea.states.push_back({m.states[tr.from] + ">" + m.states[tr.to] +
                                     "#" + std::to_string(ea.states.size()),
                                 false});
          if (!ea.add({from, vec, EditKind::Suppress, slot->second})) {
            why = "desynchronisation of " + target + " from state '" +
                  m.states[tr.from] +
                  "' makes the automaton nondeterministic on " + vec;
            return false;
          }
          from = slot->second;
        }
        if (!ea.add({from, target, EditKind::Validate, tr.to})) {
          why = "nondeterministic validation of " + target;
          return false;
        }
        return true;
      };
      std::function<bool(uint32_t, uint32_t)> explore = [&](uint32_t q,
                                                            uint32_t read) {
        if (++visits > kMaxVisits) {
          why = "the desynchronised readings of the specification are too "
                "many to enumerate (more than " +
                std::to_string(kMaxVisits) + " reading steps)";
          return false;
        }
        bool admissible = false;
        uint32_t rest = (read ^ tr.in) & diff;
        // Read everything left: admissible if it reaches the target.
        if (!path.empty()) {
          auto it = react.find({q, tr.in});
          if (it != react.end())
            for (size_t k : it->second)
              if (rows[k].to == tr.to && rows[k].out == tr.out) {
                admissible = true;
                if (!arrive())
                  return false;
                break;
              }
        }
        // Read a non-empty part of the remaining changes, not all.
        for (uint32_t sub = (rest - 1) & rest; sub && why.empty();
             sub = (sub - 1) & rest) {
          uint32_t r2 = read ^ sub;
          auto it = react.find({q, r2});
          if (it == react.end())
            continue;
          for (size_t k : it->second) {
            if (hopeless.count({rows[k].to, r2}))
              continue;
            // Already in the target state showing the target vector: the
            // chain has arrived. Reading the rest later is the machine's
            // reaction to `in` from the target state, which the
            // specification validates from there: continuing the chain
            // would only duplicate that (docs/enforce.md).
            if (rows[k].to == tr.to && rows[k].out == tr.out) {
              admissible = true;
              if (!arrive())
                return false;
              continue;
            }
            path.push_back({rows[k].to, vectorBits(tr.in, n) + rows[k].out});
            bool below = explore(rows[k].to, r2);
            path.pop_back();
            if (!why.empty())
              return false;
            if (below)
              admissible = true;
            else
              hopeless.insert({rows[k].to, r2});
          }
        }
        return admissible;
      };
      explore(tr.from, prev);
      if (!why.empty())
        return false;
    }
  }
  return addLaggingReadings(m, rows, react, opts, ea, why);
}
