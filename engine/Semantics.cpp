//===- Semantics.cpp - the step semantics of NetIR ------------------------===//
//
// A direct implementation of docs/semantics.md over unpacked valuations:
// clarity first, with the structure (precomputed arc lists, one valuation
// buffer reused across states, no allocation per enabled check) that the
// fast paths of later work keep.
//
//===----------------------------------------------------------------------===//
#include "engine/SemanticsImpl.h"
#include "ir/net/ScanResets.h"

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::sem::detail;

/// Every maximal subset of `cand` (kept in `cand` order) that `fits`
/// accepts. `fits` must be monotone: a subset of a fitting set fits.
std::vector<std::vector<uint32_t>> netlift::sem::detail::maximalSubsets(
    const std::vector<uint32_t> &cand,
    const std::function<bool(const std::vector<uint32_t> &)> &fits) {
  std::vector<std::vector<uint32_t>> maximal;
  std::vector<uint32_t> chosen;
  std::function<void(size_t)> choose = [&](size_t i) {
    if (i == cand.size()) {
      for (auto &mx : maximal)
        if (std::includes(mx.begin(), mx.end(), chosen.begin(), chosen.end()))
          return;
      // Drop earlier choices this one contains.
      maximal.erase(std::remove_if(maximal.begin(), maximal.end(),
                                   [&](const std::vector<uint32_t> &mx) {
                                     return std::includes(chosen.begin(),
                                                          chosen.end(),
                                                          mx.begin(), mx.end());
                                   }),
                    maximal.end());
      maximal.push_back(chosen);
      return;
    }
    chosen.push_back(cand[i]);
    if (fits(chosen))
      choose(i + 1);
    chosen.pop_back();
    choose(i + 1);
  };
  choose(0);
  return maximal;
}

Semantics::Semantics(const Module &mod, const StateLayout &layout, Options o)
    : m(mod), L(layout), opts(o), impl(std::make_shared<Impl>(m, L, opts)) {
  Impl &I = *impl;
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    (m.transitions[t].isForced() ? I.forcedList : I.spontaneous).push_back(t);
  I.eventInputIndex.assign(m.ports.size(), -1);
  if (!opts.scanResets)
    I.skipped = scanResetStatements(m);
  for (uint32_t p = 0; p < m.ports.size(); ++p) {
    const Port &port = m.ports[p];
    if (!port.isInput())
      continue;
    if (port.kind == PortKind::Event) {
      I.eventInputIndex[p] = I.eventInputs.size();
      I.eventInputs.push_back(p);
    } else {
      uint32_t first = L.portSlot(p);
      for (uint32_t i = 0; i < StateLayout::slotsOf(port.type); ++i)
        I.inputSlots.push_back(first + i);
    }
  }
  for (uint32_t v = 0; v < m.vars.size(); ++v)
    if (m.vars[v].type->isClock()) {
      I.clockVarSlots.push_back(L.varSlot(v));
      timed = true;
    }
  for (uint32_t p = 0; p < m.places.size(); ++p)
    timed |= L.clockSlot(p) >= 0;
  I.kernel = PtKernel::compile(m, L, opts);
  if (opts.splitInputs)
    I.analyseInputUses();
  I.vals.assign(L.numSlots(), 0);
  I.present.assign(I.eventInputs.size(), 0);
  I.en.assign(m.transitions.size(), 0);
  if (opts.splitInputs)
    I.resetLeaves();
}

bool Semantics::initialState(uint64_t *out, RuntimeError &err) const {
  Impl &I = *impl;
  std::vector<int64_t> v(L.numSlots(), 0);
  for (uint32_t s = 0; s < L.numSlots(); ++s)
    v[s] = L.slots()[s].initial; // false / 0 for PLC integers / low bound
  try {
    for (uint32_t p = 0; p < m.places.size(); ++p) {
      uint32_t s = L.markingSlot(p);
      if (m.places[p].tokens > L.slotMax(s))
        throw EvalError{"initial marking of '" + m.places[p].name.str() +
                            "' does not fit the encoding of an unbounded "
                            "place; raise --place-bits",
                        m.places[p].loc};
      v[s] = m.places[p].tokens;
    }
    std::vector<uint32_t> written;
    std::function<void(int32_t, const Type *, const Expr *)> init =
        [&](int32_t first, const Type *t, const Expr *e) {
          if (!e || first < 0)
            return;
          if (auto *agg = llvm::dyn_cast<AggregateLit>(e)) {
            // Elements and fields lie one after another in the layout.
            // (The verifier admits only aggregates for arrays and records.)
            for (size_t i = 0; i < agg->elems.size(); ++i) {
              const Type *et =
                  t->kind == TypeKind::Array ? t->elem : t->fields[i].type;
              init(first, et, agg->elems[i]);
              first += int32_t(StateLayout::slotsOf(et));
            }
            return;
          }
          if (t->isString())
            I.storeStr(e, uint32_t(first), t, I.evalStr(e, v), v, written);
          else
            I.store(e, uint32_t(first), I.eval(e, v), v, written);
        };
    for (uint32_t x = 0; x < m.vars.size(); ++x)
      init(L.varSlot(x), m.vars[x].type, m.vars[x].init);
    for (uint32_t p = 0; p < m.ports.size(); ++p)
      if (m.ports[p].isStored())
        init(L.portSlot(p), m.ports[p].type, m.ports[p].init);
  } catch (const EvalError &e) {
    err = {e.message, e.loc, e.limit, e.statement};
    return false;
  }
  I.pack(v, out);
  return true;
}

void Semantics::setBudget(Budget *b) { impl->budget = b; }

bool Semantics::successors(const uint64_t *state, Callback cb,
                           RuntimeError &err) {
  Impl &I = *impl;
  I.classes = 1;
  if (I.kernel) {
    I.succScratch.resize(L.numWords());
    if (I.kernel->successors(state, I.succScratch.data(),
                             [&](uint32_t t, const uint64_t *succ) {
                               cb(llvm::ArrayRef<uint32_t>(t), succ);
                             }))
      return true;
    // An overflow: the interpreter below reports it.
  }
  I.unpack(state);
  I.cur = state;
  // Split: one execution per class of input valuations, the classes found
  // by the splitter as the executions go. Enumerate: one per valuation.
  bool split = opts.splitInputs && !I.inputsFixed;
  uint64_t combos = uint64_t(1) << std::min<size_t>(I.eventInputs.size(), 63);
  if (I.inputsFixed)
    combos = 1;
  else if (!split)
    for (uint32_t s : I.inputSlots) {
      uint64_t span = uint64_t(L.slots()[s].hi - L.slots()[s].lo) + 1;
      if (span == 0 || combos > opts.maxInputValues / span) {
        err = {"the free inputs have more than " +
                   std::to_string(opts.maxInputValues) +
                   " valuations per step; connect them or narrow their types",
               {}};
        return false;
      }
      combos *= span;
    }
  bool manyValuations =
      split ? !I.inputSlots.empty() || !I.eventInputs.empty() : combos > 1;
  bool dedupe = manyValuations || !I.forcedList.empty() ||
                opts.policy == StepPolicy::Maximal;
  // The successor buffer is reused across states (no allocation per state).
  std::vector<uint64_t> &succ = I.succScratch;
  succ.resize(L.numWords());
  if (dedupe)
    I.emitted.clear();
  // With input conditions, an edge is reported once every class has run,
  // with the classes that take it.
  bool conditions = split && opts.inputConditions && manyValuations;
  I.edgeCond.clear();
  if (conditions)
    I.recordClasses.clear();
  auto emit = [&](llvm::ArrayRef<uint32_t> step) {
    bool fresh = !dedupe || I.emitted.insert(step, succ);
    if (conditions) {
      uint32_t r = I.emitted.lastRecord();
      if (r >= I.recordClasses.size())
        I.recordClasses.resize(r + 1);
      if (!step.empty())
        I.recordClasses[r].push_back(I.currentClass());
      return;
    }
    if (fresh)
      cb(step, succ.data());
  };
  if (split)
    I.splitter.reset();
  I.resetInputs();
  bool tickAllowed = false;
  I.classes = 1;
  try {
    for (uint64_t n = 0; split || n < combos; ++n) {
      I.checkBudget();
      if (split && n > 0) {
        if (!I.splitter.advance())
          break;
        if (I.splitter.classesRun() > opts.maxInputClasses)
          I.tooManyClasses();
        I.startClass();
      } else if (n > 0) {
        // Next valuation: an odometer over event inputs, then data inputs.
        bool carry = true;
        for (size_t e = 0; e < I.present.size() && carry; ++e) {
          I.present[e] ^= 1;
          carry = I.present[e] == 0;
        }
        for (size_t k = 0; k < I.inputSlots.size() && carry; ++k) {
          uint32_t s = I.inputSlots[k];
          if (I.vals[s] < L.slots()[s].hi) {
            ++I.vals[s];
            carry = false;
          } else {
            I.vals[s] = L.slots()[s].lo;
          }
        }
      }
      bool anyUrgent = false, strongBlocks = false;
      for (uint32_t t = 0; t < m.transitions.size(); ++t) {
        I.en[t] = I.enabled(t);
        if (!I.en[t])
          continue;
        const Transition &tr = m.transitions[t];
        anyUrgent |= tr.urgent;
        // Strong timing makes every finite upper bound a deadline.
        for (const PreArc &a : tr.pre())
          if ((a.time.deadline || opts.timing == Timing::Strong) &&
              !a.time.isTrivial() && a.time.hi != kInf &&
              I.vals[L.clockSlot(a.place)] >= int64_t(a.time.hi))
            strongBlocks = true;
      }
      if (!anyUrgent && !strongBlocks)
        tickAllowed = true;

      // Seeds: spontaneous transitions by policy; present input events
      // may also start a step on their own.
      std::vector<uint32_t> &spont = I.spontScratch;
      spont.clear();
      for (uint32_t t : I.spontaneous)
        if (I.en[t])
          spont.push_back(t);
      // The common case (interleaving, no forced transitions): every
      // enabled transition is a step of its own; no closure to compute.
      if (opts.policy == StepPolicy::Interleaving && I.forcedList.empty()) {
        std::vector<uint32_t> &step = I.stepScratch;
        for (uint32_t t : spont) {
          if (anyUrgent && !m.transitions[t].urgent)
            continue;
          step.assign(1, t);
          I.fire(step, succ.data());
          emit(step);
        }
        continue;
      }
      llvm::SmallVector<Step, 8> seeds;
      if (opts.policy == StepPolicy::Interleaving) {
        for (uint32_t t : spont)
          seeds.push_back(Step{t});
      } else if (!spont.empty()) {
        if (I.jointlyEnabled(spont)) {
          seeds.push_back(Step(spont.begin(), spont.end()));
        } else {
          for (auto &mx :
               maximalSubsets(spont, [&](const std::vector<uint32_t> &cur) {
                 return I.jointlyEnabled(cur);
               }))
            seeds.push_back(Step(mx.begin(), mx.end()));
        }
      }
      if (std::find(I.present.begin(), I.present.end(), 1) != I.present.end())
        seeds.push_back({});
      for (auto &seed : seeds) {
        llvm::SmallVector<Step, 4> steps;
        I.closure(std::move(seed), steps);
        for (auto &step : steps) {
          if (step.empty())
            continue;
          std::sort(step.begin(), step.end());
          if (anyUrgent) {
            bool hasUrgent = false;
            for (uint32_t t : step)
              hasUrgent |= m.transitions[t].urgent;
            if (!hasUrgent)
              continue;
          }
          I.fire(step, succ.data());
          emit(step);
        }
      }
    }
    I.classes = split ? I.splitter.classesRun() : combos;
    I.unsplit = 0;
    if (tickAllowed && I.tick(succ.data()))
      emit({});
    if (conditions) {
      llvm::SmallVector<uint32_t, 8> step;
      for (uint32_t r = 0; r < I.emitted.size(); ++r) {
        const uint64_t *words = I.emitted.record(r, step);
        I.edgeCond.clear();
        if (r < I.recordClasses.size() && !I.recordClasses[r].empty())
          I.edgeCond = I.conditionText(std::move(I.recordClasses[r]));
        cb(step, words);
      }
      I.edgeCond.clear();
    }
  } catch (const EvalError &e) {
    I.unsplit = 0;
    err = {e.message, e.loc, e.limit, e.statement, e.budget};
    if (e.budget)
      return false;
    // Which inputs the failing step saw: its class, as far as it was split.
    if (split && manyValuations && !e.limit)
      err.message +=
          " (inputs of the step: " + I.conditionText({I.currentClass()}) + ")";
    return false;
  }
  return true;
}

uint64_t Semantics::lastInputClasses() const { return impl->classes; }

const std::string &Semantics::edgeCondition() const { return impl->edgeCond; }

void Semantics::recordExecution(bool on) { impl->recording = on; }

const Semantics::ExecutionLog &Semantics::lastExecution() const {
  return impl->log;
}

bool Semantics::hasFreeInputs() const {
  return !impl->inputSlots.empty() || !impl->eventInputs.empty();
}

void Semantics::fixInputs(llvm::ArrayRef<int64_t> leafValues,
                          llvm::ArrayRef<uint8_t> eventsPresent) {
  Impl &I = *impl;
  I.inputsFixed = !leafValues.empty() || !eventsPresent.empty();
  if (!I.inputsFixed)
    return;
  assert(leafValues.size() == I.inputSlots.size() &&
         eventsPresent.size() == I.eventInputs.size() &&
         "one value per input leaf and event input");
  I.fixedLeaves.assign(leafValues.begin(), leafValues.end());
  I.fixedPresent.assign(eventsPresent.begin(), eventsPresent.end());
}

bool Semantics::evalPredicate(const Expr *e, const uint64_t *state,
                              RuntimeError &err) {
  return evalInState(e, state, err) != 0;
}

std::vector<int64_t> &Semantics::predicateValuation(const uint64_t *state) {
  // A buffer of its own: predicates are evaluated while successors() is
  // still enumerating from its working valuation.
  Impl &I = *impl;
  std::vector<int64_t> &v = I.predicateVals;
  v.assign(L.numSlots(), 0);
  for (uint32_t s = 0; s < L.numPacked(); ++s)
    v[s] = L.get(state, s);
  for (size_t k = 0; k < I.inputSlots.size(); ++k)
    v[I.inputSlots[k]] =
        I.inputsFixed ? I.fixedLeaves[k] : L.slots()[I.inputSlots[k]].lo;
  return v;
}

/// `f()`, or `fallback` with `err` set if it fails with an EvalError.
template <typename F, typename T>
static T orReport(F f, T fallback, RuntimeError &err) {
  try {
    return f();
  } catch (const EvalError &x) {
    err = {x.message, x.loc, x.limit, x.statement};
    return fallback;
  }
}

int64_t Semantics::evalInState(const Expr *e, const uint64_t *state,
                               RuntimeError &err) {
  std::vector<int64_t> &v = predicateValuation(state);
  return orReport([&] { return impl->eval(e, v); }, int64_t(0), err);
}

net::StringValue Semantics::evalStringInState(const Expr *e,
                                              const uint64_t *state,
                                              RuntimeError &err) {
  std::vector<int64_t> &v = predicateValuation(state);
  return orReport([&] { return impl->evalStr(e, v); }, net::StringValue(), err);
}
