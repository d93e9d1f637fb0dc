//===- Replay.cpp - netlift replay ----------------------------------------===//
//
// `netlift replay MODEL LOG.csv`: a log recorded on the PLC run through the
// model, scan by scan; `netlift replay MODEL TRACE.json`: a trace netlift
// wrote followed step by step (backends/statespace/ReplayLog.h).
//
//===----------------------------------------------------------------------===//
#include "backends/statespace/Exploring.h"
#include "tools/netlift/Driver.h"

#include "backends/statespace/ReplayLog.h"

using namespace netlift;
using namespace netlift::driver;

static cl::opt<std::string> replayModel(cl::Positional, cl::desc("<model>"),
                                        cl::Required, cl::sub(replayCommand()));
static cl::opt<std::string> replayLogFile(cl::Positional,
                                          cl::desc("<log.csv|trace.json>"),
                                          cl::Required,
                                          cl::sub(replayCommand()));
static cl::opt<std::string>
    replayHtml("trace-html",
               cl::desc("Also write the replayed run as an HTML timing "
                        "diagram to FILE"),
               cl::value_desc("FILE"), cl::sub(replayCommand()),
               cl::cat(category()));
static cl::opt<uint64_t> replayWait(
    "max-wait-ticks",
    cl::desc("Most ticks one scan of the log may wait for (default 100000)"),
    cl::init(100000), cl::sub(replayCommand()), cl::cat(category()));

/// Exit 0 the model agrees with the log, 3 it differs, 1 an error
/// (docs/reach.md, "Replaying a log").
int driver::runReplay(DiagEngine &diag) {
  engine::ExplorationOptions xo;
  if (!explorationOptions(xo, diag))
    return 1;
  // One run is followed, as the PLC makes it: no end-of-scan resets, so
  // every value a trace or a log records is the PLC's (docs/semantics.md,
  // "Observers").
  xo.semantics.scanResets = false;
  net::Design design;
  std::vector<std::string> inputs{replayModel};
  if (!loadModels(inputs, diag, design))
    return 1;
  auto setup = engine::ExplorationSetup::create(design, xo, diag, "replay");
  if (!setup)
    return 1;
  unsigned log = addInputFile(diag.sourceMgr(), replayLogFile);
  if (!log)
    return 1; // said by addInputFile
  statespace::ReplayLogOptions options;
  options.htmlFile = replayHtml;
  options.maxWaitTicks = replayWait;
  // A JSON trace netlift wrote, or a CSV log recorded on the PLC.
  if (llvm::StringRef(replayLogFile).endswith(".json"))
    return statespace::replayTrace(setup->semantics(), log,
                                   statespace::traceViewOf(*setup), options,
                                   diag, llvm::outs());
  return statespace::replayLog(setup->semantics(), log,
                               statespace::traceViewOf(*setup), options, diag,
                               llvm::outs());
}
