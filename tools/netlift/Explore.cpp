//===- Explore.cpp - reach and check: exploring a model -------------------===//
#include "backends/checkers/CheckProperties.h"
#include "backends/statespace/Exploring.h"
#include "backends/statespace/Writers.h"
#include "engine/Refinement.h"
#include "engine/TimerReplay.h"
#include "ir/net/Parser.h"
#include "ir/net/Verifier.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/MemoryBuffer.h"

using namespace netlift;
using namespace netlift::driver;

static cl::opt<std::string> reachInput(cl::Positional, cl::desc("<input>"),
                                       cl::Required, cl::sub(reachCommand()));
using statespace::GraphFormat;
static cl::opt<GraphFormat> graphFormat(
    "format", cl::desc("Write the state space"), cl::init(GraphFormat::None),
    cl::values(clEnumValN(GraphFormat::Aut, "aut", "Aldebaran .aut"),
               clEnumValN(GraphFormat::Dot, "dot", "Graphviz (small graphs)"),
               clEnumValN(GraphFormat::Json, "json",
                          "every state with its values, every edge"),
               clEnumValN(GraphFormat::Csv, "csv",
                          "every state with its values (edges: --edges)"),
               clEnumValN(GraphFormat::Arc, "arc",
                          "ViVe-style reachability graph text")),
    cl::sub(reachCommand()), cl::cat(category()));
enum class Summary { Text, Json };
static cl::opt<Summary>
    summary("summary", cl::desc("The summary printed"), cl::init(Summary::Text),
            cl::values(clEnumValN(Summary::Text, "text", "text (the default)"),
                       clEnumValN(Summary::Json, "json", "one JSON object")),
            cl::sub(reachCommand()), cl::cat(category()));
static cl::opt<std::string> findText(
    "find", cl::desc("Find a shortest path to a state satisfying EXPR"),
    cl::value_desc("EXPR"), cl::sub(reachCommand()), cl::cat(category()));
static cl::opt<bool>
    deadlockTrace("deadlock-trace",
                  cl::desc("Print a shortest path to a deadlock"),
                  cl::sub(reachCommand()), cl::cat(category()));
static cl::opt<std::string>
    traceVcd("trace-vcd",
             cl::desc("Also write the path --find or --deadlock-trace "
                      "prints as a Value Change Dump (GTKWave) to FILE"),
             cl::value_desc("FILE"), cl::sub(reachCommand()),
             cl::cat(category()));
static cl::opt<std::string>
    traceJson("trace-json",
              cl::desc("Also write the path --find or --deadlock-trace "
                       "prints as a JSON trace (docs/formats.md) to FILE"),
              cl::value_desc("FILE"), cl::sub(reachCommand()),
              cl::cat(category()));
static cl::opt<std::string>
    traceHtml("trace-html",
              cl::desc("Also write the path --find or --deadlock-trace "
                       "prints as an HTML timing diagram to FILE"),
              cl::value_desc("FILE"), cl::sub(reachCommand()),
              cl::cat(category()));
static cl::opt<bool> depthFirst("dfs", cl::desc("Depth-first order"),
                                cl::sub(reachCommand()), cl::cat(category()));
static cl::opt<bool> noProgress("q", cl::desc("No progress output"),
                                cl::sub(reachCommand()), cl::cat(category()));
enum class EdgeLabels { Transitions, Inputs };
static cl::opt<EdgeLabels> edgeLabels(
    "edge-labels", cl::desc("What an edge's label says"),
    cl::init(EdgeLabels::Transitions),
    cl::values(clEnumValN(EdgeLabels::Transitions, "transitions",
                          "the transitions of the step (the default)"),
               clEnumValN(EdgeLabels::Inputs, "inputs",
                          "also the classes of input valuations that take "
                          "it, [go=1, level=91..100] | [go=0]")),
    cl::sub(reachCommand()), cl::cat(category()));

static int reachOnce(engine::ExplorationOptions &xo, unsigned round,
                     DiagEngine &diag);

/// `--find EXPR` as a predicate over `top`'s states; null after reporting.
static net::Expr *parseFind(const std::string &text, net::Design &design,
                            net::Module &top, DiagEngine &diag) {
  unsigned id = diag.sourceMgr().AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, "<find>"), llvm::SMLoc());
  net::Expr *e = net::parseExpression(id, diag, design);
  return e && net::verifyPredicate(design, top, e, diag) ? e : nullptr;
}

/// Exit codes (docs/reach.md): 0 complete, 1 error, 2 a limit stopped the
/// search, 3 the property checked is violated.
int driver::runReach(DiagEngine &diag) {
  engine::ExplorationOptions xo;
  if (!explorationOptions(xo, diag))
    return 1;
  // --timers=abstract: a spurious counterexample's clocks are kept exact
  // and the search runs again, up to --refine times.
  return engine::refineUntilSettled(
      xo, [&](engine::ExplorationOptions &o, unsigned round) {
        return reachOnce(o, round, diag);
      });
}

static int reachOnce(engine::ExplorationOptions &xo, unsigned round,
                     DiagEngine &diag) {
  net::Design design;
  std::vector<std::string> inputs{reachInput};
  xo.propertyTexts.clear();
  if (!findText.empty())
    xo.propertyTexts.push_back(findText);
  if (!loadModels(inputs, diag, design))
    return 1;
  if (edgeLabels == EdgeLabels::Inputs) {
    if (!xo.semantics.splitInputs) {
      diag.error(llvm::SMLoc(), "--edge-labels=inputs needs --inputs=split "
                                "(enumerated, an edge's inputs are every "
                                "valuation taking it)");
      return 1;
    }
    xo.semantics.inputConditions = true;
  }
  auto setup = engine::ExplorationSetup::create(design, xo, diag, "reach");
  if (!setup)
    return 1;
  sem::Semantics &semantics = setup->semantics();
  net::Expr *findExpr = nullptr;
  if (!findText.empty() &&
      !(findExpr = parseFind(findText, design, setup->top(), diag)))
    return 1;
  engine::ExploreOptions eo = setup->exploreOptions();
  eo.depthFirst = depthFirst;
  eo.recordEdges = graphFormat != GraphFormat::None || !edgesFile.empty();
  eo.progress = !noProgress;
  eo.inputLabels = edgeLabels == EdgeLabels::Inputs;
  sem::RuntimeError findErr;
  auto stop = [&](const uint64_t *s) {
    return semantics.evalPredicate(findExpr, s, findErr);
  };
  if (findExpr)
    eo.stopAt = stop;
  engine::Explorer explorer(semantics, eo);
  engine::ExploreResult r;
  if (!statespace::exploreAndReport(*setup, explorer, r, diag))
    return 1;
  if (graphFormat != GraphFormat::None && graphFormat != GraphFormat::Aut)
    setup->noteUnkeptValues(diag);
  if (writeResult(
          outputFile,
          [&](llvm::raw_ostream &os) {
            statespace::writeStateSpace(graphFormat, explorer, semantics, r,
                                        os);
          },
          diag) ||
      (!edgesFile.empty() && writeResult(
                                 edgesFile,
                                 [&](llvm::raw_ostream &os) {
                                   statespace::writeCsvEdges(explorer, os);
                                 },
                                 diag)))
    return 1;
  llvm::raw_ostream &out = llvm::outs();
  if (summary == Summary::Json) {
    statespace::writeSummaryJson(explorer, r, out, setup->summaryJsonFields());
  } else if (graphFormat == GraphFormat::None && !findExpr && !deadlockTrace) {
    statespace::writeSummaryText(explorer, r, out);
    if (!r.deadlocks.empty() && !setup->timerAbstraction().abstracted.empty())
      out << "(abstract timers: a deadlock may need a timer to expire sooner "
             "or later than it can; --deadlock-trace replays the closest in "
             "exact time)\n";
  }
  int code = r.limitReached.empty() ? 0 : 2;
  if (!r.limitReached.empty())
    llvm::errs() << "netlift: the " << r.limitReached
                 << " limit stopped the search; the result is incomplete\n";
  std::optional<uint32_t> violation;
  if (findExpr && r.found)
    violation = *r.found;
  else if (deadlockTrace && !r.deadlocks.empty())
    violation = *std::min_element(r.deadlocks.begin(), r.deadlocks.end());
  if (violation && (!traceJson.empty() || !traceHtml.empty())) {
    statespace::TraceFileHeader h;
    h.formula = findExpr ? findText : std::string("deadlock");
    h.holds = bool(findExpr);
    h.witness = bool(findExpr);
    h.claim = findExpr ? "a shortest path to a state satisfying " + findText
                       : std::string("a shortest path to a deadlock");
    if (!traceJson.empty() &&
        !statespace::writeJsonTraceFile(explorer, semantics, *violation, h,
                                        design.timescale, traceJson, diag))
      return 1;
    if (!traceHtml.empty() &&
        !statespace::writeHtmlTraceFile(explorer, semantics, *violation, h,
                                        statespace::traceViewOf(*setup),
                                        traceHtml, diag))
      return 1;
  }
  if (!xo.abstractTimers || !violation ||
      setup->timerAbstraction().abstracted.empty())
    return statespace::reportSearch(
        explorer, semantics, r, findExpr ? llvm::StringRef(findText) : "",
        deadlockTrace, code, out, statespace::traceViewOf(*setup), traceVcd,
        &diag);
  auto path = explorer.pathTo(*violation);
  out << (findExpr ? "found a state satisfying '" + findText + "'"
                   : std::string("deadlock"))
      << " after " << path.size() - 1 << " steps with abstract timers ("
      << setup->timerAbstraction().abstracted.size() << " abstracted):\n";
  statespace::writeTrace(explorer, semantics, *violation, out,
                         statespace::traceViewOf(*setup));
  if (!traceVcd.empty() &&
      !statespace::writeVcdFile(explorer, semantics, *violation,
                                design.timescale, traceVcd, diag))
    return 1;
  std::vector<std::string> involved;
  auto verdict = statespace::replayAndReport(*setup, explorer, path, !findExpr,
                                             out, involved);
  if (verdict != engine::ReplayOutcome::Confirmed) {
    net::Expr *exactFind = nullptr;
    if (findExpr &&
        !(exactFind = parseFind(findText, design, *setup->exactModule(), diag)))
      return 1;
    if (int code =
            statespace::searchExactModel(*setup, exactFind, findText, out);
        code != engine::kRefine)
      return code;
  }
  return engine::afterReplay(verdict, involved, findExpr ? 0 : 3, xo, round,
                             out);
}

static cl::opt<std::string> checkInput(cl::Positional, cl::desc("<model>"),
                                       cl::Required, cl::sub(checkCommand()));
static cl::opt<std::string>
    traceDir("trace-dir",
             cl::desc("Also write each property's trace as DIR/p<N>.json, "
                      "DIR/p<N>.aut and DIR/p<N>.vcd"),
             cl::value_desc("DIR"), cl::sub(checkCommand()),
             cl::cat(category()));

/// Exit 0 all hold, 3 some fail, 2 the exploration was stopped by a limit,
/// 1 an error (docs/check.md).
int driver::runCheck(DiagEngine &diag) {
  if (properties.empty()) {
    diag.error(llvm::SMLoc(), "check needs a property (--ctl FORMULA)");
    return 1;
  }
  engine::ExplorationOptions xo;
  if (!explorationOptions(xo, diag))
    return 1;
  xo.propertyTexts.assign(properties.begin(), properties.end());
  return engine::refineUntilSettled(xo, [&](engine::ExplorationOptions &xo,
                                            unsigned round) {
    net::Design design;
    std::vector<std::string> inputs{checkInput};
    if (!loadModels(inputs, diag, design))
      return 1;
    auto setup = engine::ExplorationSetup::create(design, xo, diag, "check");
    std::vector<std::unique_ptr<checkers::CtlFormula>> formulas;
    if (!setup || !checkers::parseProperties(properties, design, setup->top(),
                                             diag, formulas))
      return 1;
    if (xo.abstractTimers)
      for (const auto &f : formulas)
        if (!checkers::isInvariant(*f)) {
          diag.error(f->loc, "--timers=abstract decides invariants only (AG "
                             "p, p without temporal operators): the "
                             "abstract model has more runs than the exact "
                             "one, so '" +
                                 checkers::ctlToString(*f) +
                                 "' could hold there and fail exactly, or "
                                 "the other way round; use --timers=exact");
          return 1;
        }
    std::vector<std::string> involved;
    int code = checkers::checkProperties(*setup, formulas, traceDir,
                                         llvm::outs(), diag, &involved);
    if (code != 3 || involved.empty())
      return code;
    // A counterexample was spurious: refine as reach does.
    return engine::afterReplay(engine::ReplayOutcome::Spurious, involved, 3, xo,
                               round, llvm::outs());
  });
}
