//===- Exploring.cpp - what the engine found, said to the user ------------===//
#include "backends/statespace/Exploring.h"

#include "engine/Refinement.h"
#include "engine/TraceValues.h"

using namespace netlift;
using namespace netlift::engine;
using namespace netlift::statespace;

TraceView statespace::traceViewOf(const ExplorationSetup &setup) {
  return {setup.options().traceInternals, setup.timescale(),
          setup.sourceManager(), setup.options().traceSource};
}

bool statespace::exploreAndReport(ExplorationSetup &setup, Explorer &explorer,
                                  ExploreResult &r, DiagEngine &diag) {
  bool started = explorer.run(r);
  if (!r.error)
    return true;
  reportRuntimeError(r, started, explorer, setup.semantics(), diag,
                     traceViewOf(setup));
  if (!r.error->limit && setup.hasAbstractedClocks())
    diag.note(llvm::SMLoc(),
              "found with abstract timers: the error may need a timer to "
              "expire sooner or later than it can; --timers=exact decides");
  return false;
}

std::unique_ptr<Explorer> statespace::exploreGraph(ExplorationSetup &setup,
                                                   ExploreResult &r,
                                                   DiagEngine &diag) {
  ExploreOptions eo = setup.exploreOptions();
  eo.recordEdges = true;
  auto explorer = std::make_unique<Explorer>(setup.semantics(), eo);
  if (!exploreAndReport(setup, *explorer, r, diag))
    return nullptr;
  return explorer;
}

void statespace::reportRuntimeError(const ExploreResult &r, bool started,
                                    Explorer &explorer,
                                    sem::Semantics &semantics, DiagEngine &diag,
                                    const TraceView &view) {
  reportRuntimeErrorAt(*r.error, diag);
  if (started) {
    llvm::errs() << "trace to the state where it happens (the next step "
                    "fails):\n";
    writeTrace(explorer, semantics, r.errorState, llvm::errs(), view);
  }
}

void statespace::writeReplayedRun(sem::Semantics &exact, const ReplayOutcome &o,
                                  llvm::raw_ostream &os,
                                  const TraceView &view) {
  std::vector<const uint64_t *> states;
  for (const std::vector<uint64_t> &s : o.states)
    states.push_back(s.data());
  std::vector<std::string> labels(o.labels.begin(), o.labels.end());
  PlcPath plc = plcValues(exact, labels, states);
  withInputClasses(plc.in(exact), labels, plc.states);
  writeStatePath(plc.in(exact), labels, plc.states, os, view);
}

ReplayOutcome::Verdict
statespace::replayAndReport(ExplorationSetup &setup, const Explorer &x,
                            llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
                            bool deadlock, llvm::raw_ostream &out,
                            std::vector<std::string> &involved) {
  sem::Semantics &exact = *setup.exactSemantics();
  auto endsRun = [&](const uint64_t *s) {
    if (!deadlock)
      return true;
    bool moves = false;
    sem::RuntimeError err;
    exact.successors(
        s, [&](llvm::ArrayRef<uint32_t>, const uint64_t *) { moves = true; },
        err);
    return !moves;
  };
  ReplayOutcome o = replayInExactTime(exact, setup.semantics(), x, path,
                                      setup.timerAbstraction().abstracted,
                                      endsRun, setup.options().replayStates);
  switch (o.verdict) {
  case ReplayOutcome::Confirmed:
    out << "confirmed in exact time: " << o.states.size() - 1 << " steps ("
        << o.visited << " exact states searched):\n";
    writeReplayedRun(exact, o, out, traceViewOf(setup));
    break;
  case ReplayOutcome::Undecided:
    out << "undecided: the replay in exact time stopped after " << o.visited
        << " states; run with --timers=exact\n";
    break;
  case ReplayOutcome::Spurious: {
    std::string names;
    for (const std::string &n : o.involved)
      names += (names.empty() ? "" : ", ") + n;
    out << "spurious: no run of the exact model follows it past step "
        << o.divergesAt << " (" << o.visited
        << " exact states searched; abstract clocks running there: " << names
        << ")\n";
    involved = o.involved;
    break;
  }
  }
  return o.verdict;
}

int statespace::searchExactModel(ExplorationSetup &setup, const net::Expr *find,
                                 llvm::StringRef findText,
                                 llvm::raw_ostream &out) {
  sem::Semantics &exact = *setup.exactSemantics();
  ExploreOptions eo;
  eo.maxStates = setup.options().replayStates;
  sem::RuntimeError err;
  auto stop = [&](const uint64_t *s) {
    return exact.evalPredicate(find, s, err);
  };
  if (find)
    eo.stopAt = stop; // a function_ref: `stop` outlives the search
  Explorer x(exact, eo);
  ExploreResult r;
  if (!x.run(r) || r.error)
    return kRefine; // the exact model fails on its own: refinement says so
  std::optional<uint32_t> hit;
  if (find && r.found)
    hit = *r.found;
  else if (!find && !r.deadlocks.empty())
    hit = *std::min_element(r.deadlocks.begin(), r.deadlocks.end());
  if (hit) {
    out << "confirmed by a search of the exact model (" << x.store().size()
        << " states), " << x.pathTo(*hit).size() - 1 << " steps:\n";
    writeTrace(x, exact, *hit, out, traceViewOf(setup));
    return find ? 0 : 3;
  }
  if (!r.complete)
    return kRefine;
  out << "the exact model (" << x.store().size() << " states, all searched) "
      << (find ? "has no state satisfying '" + findText.str() + "'"
               : std::string("has no deadlock"))
      << "\n";
  return find ? 3 : 0;
}
