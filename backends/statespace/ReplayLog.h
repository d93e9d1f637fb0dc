//===- ReplayLog.h - a field log run through the model ----------*- C++ -*-===//
//
// `netlift replay MODEL LOG.csv` (docs/reach.md, "Replaying a log"): a CSV
// log recorded on the PLC — a header naming the model's free inputs and
// any outputs or variables, then one row per scan — is run through the
// model scan by scan (nextScan with the row's inputs fixed). Every value
// the log recorded besides the inputs is compared with the model's after
// that scan; the first difference is the diagnosis: the log's row, the
// name, both values, and the trace that leads there in the program's
// view (the text table, or an HTML page).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STATESPACE_REPLAYLOG_H
#define NETLIFT_BACKENDS_STATESPACE_REPLAYLOG_H

#include "backends/statespace/Writers.h"
#include "engine/Semantics.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

#include <functional>

namespace netlift::statespace {

struct ReplayLogOptions {
  /// Most ticks a scan waits for (a task's period is far shorter).
  uint64_t maxWaitTicks = 100000;
  /// Also write the replayed run as an HTML trace here.
  std::string htmlFile;
  /// How a verdict names a row (1-based, the header not counted); by
  /// default `LOG.csv:LINE`. enforce names the vectors it replays.
  std::function<std::string(size_t row)> rowName;
  /// What the recorded values are called in a verdict.
  std::string recordName = "log";
};

/// Replays the log in buffer `bufferID` on `sem` and prints the run and
/// the verdict on `os`. Returns the exit code: 0 the model agrees with
/// every recorded value, 3 it differs (or cannot take a scan), 1 a
/// malformed log or a runtime error of the model (reported).
int replayLog(sem::Semantics &sem, unsigned bufferID, const TraceView &view,
              const ReplayLogOptions &options, DiagEngine &diag,
              llvm::raw_ostream &os);

/// A replayed run (`kept` states, one label each, the first "") as the
/// trace table on `os`, and as an HTML page when `options.htmlFile` is set
/// (`claim` says what the page shows). False after reporting.
bool showReplayedRun(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
                     llvm::ArrayRef<std::vector<uint64_t>> kept,
                     const TraceView &view, const ReplayLogOptions &options,
                     llvm::StringRef source, llvm::StringRef claim,
                     DiagEngine &diag, llvm::raw_ostream &os);

/// Follows the JSON trace in buffer `bufferID` (docs/formats.md, "JSON
/// traces"; ReplayTrace.cpp) on `sem`: each step must be one the model can
/// take with the step's label, reaching exactly the recorded values, and a
/// lasso's last state must step back to its loop. Prints the run and the
/// verdict on `os`; returns 0 the model follows it, 3 it does not, 1 a
/// malformed trace or a runtime error (reported).
int replayTrace(sem::Semantics &sem, unsigned bufferID, const TraceView &view,
                const ReplayLogOptions &options, DiagEngine &diag,
                llvm::raw_ostream &os);

} // namespace netlift::statespace

#endif
