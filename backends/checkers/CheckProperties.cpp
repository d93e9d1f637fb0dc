//===- CheckProperties.cpp - CTL properties on an explored model ----------===//
#include "backends/checkers/CheckProperties.h"
#include "backends/statespace/Exploring.h"

#include "backends/statespace/Writers.h"
#include "engine/TimerReplay.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"

using namespace netlift;
using namespace netlift::checkers;

bool checkers::parseProperties(llvm::ArrayRef<std::string> texts,
                               net::Design &design, net::Module &top,
                               DiagEngine &diag,
                               std::vector<std::unique_ptr<CtlFormula>> &out) {
  for (size_t i = 0; i < texts.size(); ++i) {
    unsigned id = diag.sourceMgr().AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(
            texts[i], "<ctl " + std::to_string(i + 1) + ">"),
        llvm::SMLoc());
    auto f = parseCtl(id, diag, design, top);
    if (!f)
      return false;
    out.push_back(std::move(f));
  }
  return true;
}

/// The explored graph in CSR form, edges of one state together.
static CtlGraph graphOf(const engine::Explorer &explorer,
                        const engine::ExploreResult &r) {
  CtlGraph g;
  size_t n = explorer.store().size();
  g.deadlock.assign(n, 0);
  for (uint32_t d : r.deadlocks)
    g.deadlock[d] = 1;
  g.succStart.assign(n + 1, 0);
  for (const engine::Edge &e : explorer.edges())
    ++g.succStart[e.from + 1];
  for (size_t i = 0; i < n; ++i)
    g.succStart[i + 1] += g.succStart[i];
  g.succ.resize(explorer.edges().size());
  g.succLabel.resize(explorer.edges().size());
  std::vector<uint32_t> fill(g.succStart.begin(), g.succStart.end() - 1);
  for (const engine::Edge &e : explorer.edges()) {
    g.succLabel[fill[e.from]] = e.label;
    g.succ[fill[e.from]++] = e.to;
  }
  return g;
}

static bool isStateFormula(const CtlFormula &f) {
  switch (f.kind) {
  case CtlFormula::True:
  case CtlFormula::False:
  case CtlFormula::Atom:
  case CtlFormula::Deadlock:
    return true;
  case CtlFormula::Not:
    return isStateFormula(*f.lhs);
  case CtlFormula::And:
  case CtlFormula::Or:
  case CtlFormula::Implies:
    return isStateFormula(*f.lhs) && isStateFormula(*f.rhs);
  default:
    return false;
  }
}

bool checkers::isInvariant(const CtlFormula &f) {
  return f.kind == CtlFormula::AG && isStateFormula(*f.lhs);
}

/// A limit stopped the exploration: what the explored part settles is
/// reported all the same. Every stored state is reachable, so a state
/// violating p refutes `AG p` and one satisfying p proves `EF p`, with the
/// path to it (breadth-first, a shortest one: every state closer to the
/// initial one was stored before the limit). Anything else is undecided.
/// Exit code as checkProperties'.
static int
checkExploredPart(engine::ExplorationSetup &setup, engine::Explorer &explorer,
                  const engine::ExploreResult &r,
                  llvm::ArrayRef<std::unique_ptr<CtlFormula>> formulas,
                  const std::string &traceDir, llvm::raw_ostream &out,
                  DiagEngine &diag, bool abstractTimers) {
  sem::Semantics &semantics = setup.semantics();
  size_t n = explorer.store().size();
  CtlGraph g = graphOf(explorer, r);
  out << "the exploration stopped at a limit (" << n
      << " states): the properties it settles are reported, the others "
         "are undecided\n";
  sem::RuntimeError err;
  auto atomValue = [&](const net::Expr *e, uint32_t st) {
    return semantics.evalPredicate(e, explorer.store().state(st), err);
  };
  bool fails = false, undecided = false;
  unsigned index = 0;
  for (const auto &f : formulas) {
    ++index;
    // `deadlock` is unknown in the states the limit left unexpanded.
    bool settles = !abstractTimers &&
                   (f->kind == CtlFormula::AG || f->kind == CtlFormula::EF) &&
                   isStateProposition(*f->lhs, false);
    std::optional<uint32_t> hit;
    bool exists = f->kind == CtlFormula::EF;
    if (settles) {
      // States are numbered as found, breadth-first: the first is closest.
      std::vector<uint8_t> sat = evaluateCtl(*f->lhs, g, atomValue);
      for (uint32_t st = 0; st < n && !hit; ++st)
        if (bool(sat[st]) == exists)
          hit = st;
    }
    if (!hit) {
      undecided = true;
      out << ctlToString(*f) << ": undecided ("
          << (settles ? (exists ? "no state satisfying it" : "no violation")
                      : "the explored part cannot settle it")
          << (settles ? " among the " + std::to_string(n) + " explored" : "")
          << ")\n";
      continue;
    }
    fails |= !exists;
    std::string claim = "a shortest path to a state where " +
                        ctlToString(*f->lhs) +
                        (exists ? " holds" : " does not hold");
    out << ctlToString(*f) << ": " << (exists ? "holds" : "fails") << "\n"
        << (exists ? "witness: " : "counterexample: ") << claim << "\n";
    std::vector<std::pair<uint32_t, uint32_t>> steps = explorer.pathTo(*hit);
    statespace::writePath(explorer, semantics, steps, out,
                          statespace::traceViewOf(setup));
    if (!traceDir.empty()) {
      statespace::TraceFileHeader h{ctlToString(*f), exists, exists, claim};
      if (!statespace::writeTraceFiles(traceDir + "/p" + std::to_string(index),
                                       h, explorer, semantics,
                                       statespace::traceViewOf(setup), steps,
                                       -1, engine::Explorer::kNone, diag))
        return 1;
    }
  }
  if (!err.message.empty()) {
    diag.error(llvm::SMLoc(), "runtime error in a property: " + err.message);
    return 1;
  }
  return fails ? 3 : undecided ? 2 : 0;
}

int checkers::checkProperties(
    engine::ExplorationSetup &setup,
    llvm::ArrayRef<std::unique_ptr<CtlFormula>> formulas,
    const std::string &traceDir, llvm::raw_ostream &out, DiagEngine &diag,
    std::vector<std::string> *spuriousClocks) {
  bool abstractTimers =
      setup.exactSemantics() && !setup.timerAbstraction().abstracted.empty();
  sem::Semantics &semantics = setup.semantics();
  engine::ExploreResult r;
  std::unique_ptr<engine::Explorer> graph =
      statespace::exploreGraph(setup, r, diag);
  if (!graph)
    return 1;
  engine::Explorer &explorer = *graph;
  sem::RuntimeError err;
  if (!traceDir.empty())
    if (std::error_code ec = llvm::sys::fs::create_directories(traceDir)) {
      diag.error(llvm::SMLoc(),
                 "cannot create '" + traceDir + "': " + ec.message());
      return 1;
    }
  if (!r.complete) {
    return checkExploredPart(setup, explorer, r, formulas, traceDir, out, diag,
                             abstractTimers);
  }
  CtlGraph g = graphOf(explorer, r);
  auto atomValue = [&](const net::Expr *e, uint32_t s) {
    return semantics.evalPredicate(e, explorer.store().state(s), err);
  };
  // The label of a step: the first edge between its two states.
  auto labelOf = [&](uint32_t from, uint32_t to) {
    for (uint32_t k = g.succStart[from]; k < g.succStart[from + 1]; ++k)
      if (g.succ[k] == to)
        return g.succLabel[k];
    return engine::Explorer::kNone;
  };
  bool allHold = true, undecided = false;
  unsigned index = 0;
  for (const auto &f : formulas) {
    ++index;
    bool holds = evaluateCtl(*f, g, atomValue)[0];
    allHold = allHold && holds;
    out << ctlToString(*f) << ": "
        << (holds            ? "holds"
            : abstractTimers ? "fails with abstract timers"
                             : "fails")
        << "\n";
    std::optional<CtlTrace> trace = ctlTrace(*f, g, atomValue);
    if (!trace)
      continue;
    std::vector<std::pair<uint32_t, uint32_t>> steps;
    for (size_t i = 0; i < trace->states.size(); ++i)
      steps.push_back({i ? labelOf(trace->states[i - 1], trace->states[i])
                         : engine::Explorer::kNone,
                       trace->states[i]});
    out << (trace->witness ? "witness: " : "counterexample: ") << trace->claim
        << "\n";
    uint32_t loopLabel =
        trace->loopTo >= 0
            ? labelOf(trace->states.back(), trace->states[trace->loopTo])
            : engine::Explorer::kNone;
    statespace::writePath(explorer, semantics, steps, out,
                          statespace::traceViewOf(setup), trace->loopTo,
                          loopLabel);
    if (abstractTimers && !holds) {
      std::vector<std::string> involved;
      if (statespace::replayAndReport(setup, explorer, steps, false, out,
                                      involved) !=
          engine::ReplayOutcome::Confirmed)
        undecided = true;
      if (spuriousClocks)
        spuriousClocks->insert(spuriousClocks->end(), involved.begin(),
                               involved.end());
    }
    if (!traceDir.empty()) {
      statespace::TraceFileHeader h{ctlToString(*f), holds, trace->witness,
                                    trace->claim};
      if (!statespace::writeTraceFiles(traceDir + "/p" + std::to_string(index),
                                       h, explorer, semantics,
                                       statespace::traceViewOf(setup), steps,
                                       trace->loopTo, loopLabel, diag))
        return 1;
    }
  }
  if (!err.message.empty()) {
    diag.error(llvm::SMLoc(), "runtime error in a property: " + err.message);
    return 1;
  }
  if (undecided && (!spuriousClocks || spuriousClocks->empty()))
    return 2; // a replay stopped at its budget
  return allHold ? 0 : 3;
}
