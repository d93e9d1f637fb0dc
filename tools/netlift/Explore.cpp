//===- Explore.cpp - reach and check: exploring a model -------------------===//
#include "backends/checkers/CheckProperties.h"
#include "backends/statespace/Writers.h"
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

/// Exit codes (docs/reach.md): 0 complete, 1 error, 2 a limit stopped the
/// search, 3 the property checked is violated.
int driver::runReach(DiagEngine &diag) {
  net::Design design;
  std::vector<std::string> inputs{reachInput};
  statespace::ExplorationOptions xo;
  if (!loadModels(inputs, diag, design) || !explorationOptions(xo, diag))
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
  auto setup = statespace::ExplorationSetup::create(design, xo, diag, "reach");
  if (!setup)
    return 1;
  sem::Semantics &semantics = setup->semantics();
  net::Expr *findExpr = nullptr;
  if (!findText.empty()) {
    unsigned id = diag.sourceMgr().AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(findText, "<find>"),
        llvm::SMLoc());
    findExpr = net::parseExpression(id, diag, design);
    if (!findExpr ||
        !net::verifyPredicate(design, setup->top(), findExpr, diag))
      return 1;
  }
  statespace::ExploreOptions eo = setup->exploreOptions();
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
  statespace::Explorer explorer(semantics, eo);
  statespace::ExploreResult r;
  if (!setup->explore(explorer, r, diag))
    return 1;
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
    statespace::writeSummaryJson(explorer, r, out);
  } else if (graphFormat == GraphFormat::None && !findExpr && !deadlockTrace) {
    statespace::writeSummaryText(explorer, r, out);
  }
  int code = r.limitReached.empty() ? 0 : 2;
  if (!r.limitReached.empty())
    llvm::errs() << "netlift: the " << r.limitReached
                 << " limit stopped the search; the result is incomplete\n";
  return statespace::reportSearch(explorer, semantics, r,
                                  findExpr ? llvm::StringRef(findText) : "",
                                  deadlockTrace, code, out);
}

static cl::opt<std::string> checkInput(cl::Positional, cl::desc("<model>"),
                                       cl::Required, cl::sub(checkCommand()));
static cl::opt<std::string>
    traceDir("trace-dir",
             cl::desc("Also write each property's trace as DIR/p<N>.json and "
                      "DIR/p<N>.aut"),
             cl::value_desc("DIR"), cl::sub(checkCommand()),
             cl::cat(category()));

/// Exit 0 all hold, 3 some fail, 2 the exploration was stopped by a limit,
/// 1 an error (docs/check.md).
int driver::runCheck(DiagEngine &diag) {
  if (properties.empty()) {
    diag.error(llvm::SMLoc(), "check needs a property (--ctl FORMULA)");
    return 1;
  }
  net::Design design;
  std::vector<std::string> inputs{checkInput};
  statespace::ExplorationOptions xo;
  if (!loadModels(inputs, diag, design) || !explorationOptions(xo, diag))
    return 1;
  auto setup = statespace::ExplorationSetup::create(design, xo, diag, "check");
  std::vector<std::unique_ptr<checkers::CtlFormula>> formulas;
  if (!setup || !checkers::parseProperties(properties, design, setup->top(),
                                           diag, formulas))
    return 1;
  return checkers::checkProperties(*setup, formulas, traceDir, llvm::outs(),
                                   diag);
}
