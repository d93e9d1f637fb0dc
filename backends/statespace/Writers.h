//===- Writers.h - state spaces as files ------------------------*- C++ -*-===//
//
// Writes an explored state space: Aldebaran `.aut` (CADP, mCRL2, TINA),
// Graphviz DOT, ViVe-style `.arc`, JSON (every state with its attributes and
// every edge; the input of structural reasoning, docs/formats.md), the
// one-object summary of `reach --summary json`, and readable traces (a table of
// steps and the values each step changed). All deterministic: states in
// discovery order, edges in generation order.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STATESPACE_WRITERS_H
#define NETLIFT_BACKENDS_STATESPACE_WRITERS_H

#include "engine/Explorer.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/JSON.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

#include <optional>

namespace netlift::statespace {

/// The formats `reach --format` writes a state space in.
enum class GraphFormat { None, Aut, Dot, Json, Csv, Arc };
/// Writes the state space in `format` (None: nothing).
void writeStateSpace(GraphFormat format, const engine::Explorer &x,
                     sem::Semantics &sem, const engine::ExploreResult &r,
                     llvm::raw_ostream &os);

void writeAut(const engine::Explorer &x, llvm::raw_ostream &os);
/// A state's values as `name=value` items joined by `separator`: marked
/// places only, then clocks, variables and outputs.
std::string describeState(sem::Semantics &sem, const uint64_t *state,
                          llvm::StringRef separator);
void writeDot(const engine::Explorer &x, sem::Semantics &sem,
              llvm::raw_ostream &os);
/// ViVe-style reachability graph text (docs/formats.md): per state a line
/// `state nr. N`, its marked places and values, then one line
/// `== {t1,t3} ==> M` per step leaving it.
void writeArc(const engine::Explorer &x, sem::Semantics &sem,
              llvm::raw_ostream &os);
void writeJson(const engine::Explorer &x, sem::Semantics &sem,
               const engine::ExploreResult &r, llvm::raw_ostream &os);
/// CSV: a header `id,deadlock,<attribute>...` and one row per state.
void writeCsvStates(const engine::Explorer &x, sem::Semantics &sem,
                    const engine::ExploreResult &r, llvm::raw_ostream &os);
/// CSV: `from,label,to`, one row per edge.
void writeCsvEdges(const engine::Explorer &x, llvm::raw_ostream &os);
/// `extraFields` (`,"key":value...`) goes before the closing brace.
void writeSummaryJson(const engine::Explorer &x, const engine::ExploreResult &r,
                      llvm::raw_ostream &os, llvm::StringRef extraFields = "");
/// `reach`'s text summary: states, transitions, deadlocks, dead states,
/// complete.
void writeSummaryText(const engine::Explorer &x, const engine::ExploreResult &r,
                      llvm::raw_ostream &os);
/// How a trace is shown as text (docs/reach.md, "Traces").
struct TraceView {
  /// --trace-internals: every step (ticks too) and every name, clocks and
  /// what frontends generated included, as the net has them. Otherwise the
  /// program's view: time folded into a column, a row per step that is not
  /// a tick, the inputs that took it, then the outputs and the other
  /// values it changed, internal names hidden.
  bool internals = false;
  /// The design's tick: the unit of the time column (none: ticks).
  std::optional<net::Timescale> tick;
  /// Where the model was read from: a change shows the source line of the
  /// assignment that made it (`q: 0 -> 1 (delay.st:7)`; lines of netlift's
  /// own library and generated text are left out). Null: no lines.
  const llvm::SourceMgr *sources = nullptr;
  /// --trace-source: each row also lists every source line its step ran.
  bool source = false;
};

/// The path to `target` as a table: the initial values, then for each step
/// its label and the values it changed.
void writeTrace(const engine::Explorer &x, sem::Semantics &sem, uint32_t target,
                llvm::raw_ostream &os, const TraceView &view = {});
/// The same table for any path: (label of the step into it, state) pairs,
/// the first label unused. `loopTo` >= 0 adds a closing line: the step
/// `loopLabel` leads back to that step and the run goes round forever.
void writePath(const engine::Explorer &x, sem::Semantics &sem,
               llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
               llvm::raw_ostream &os, const TraceView &view = {},
               int64_t loopTo = -1,
               uint32_t loopLabel = engine::Explorer::kNone);

/// Adds to each step's label the classes of input valuations that take
/// it, `{scan} [go=1, level=91..100]`, found by running the step again from
/// the state before it (the input values a trace took, which the states
/// do not hold).
void withInputClasses(sem::Semantics &sem, std::vector<std::string> &labels,
                      llvm::ArrayRef<const uint64_t *> states);

/// The same table for states held anywhere: `labels[i]` is the step into
/// `states[i]` (the first unused); a `loopTo` >= 0 as for writePath.
void writeStatePath(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
                    llvm::ArrayRef<const uint64_t *> states,
                    llvm::raw_ostream &os, const TraceView &view = {},
                    int64_t loopTo = -1, llvm::StringRef loopLabel = "");

/// The same path as a Value Change Dump (IEEE 1364, what GTKWave opens):
/// every variable and output of the state listing (Booleans as wires,
/// integers as `integer` vectors, reals as `real`; strings, which VCD
/// has no type for, as a comment), and `step`, the number of the last
/// step at each time. Time advances by `tick` (the design's timescale,
/// else 1 ns) at each `tick` step; the steps between two ticks take no
/// time, so a time shows the values after its last step (a PLC: after
/// its scan).
void writeVcd(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
              llvm::ArrayRef<const uint64_t *> states,
              const std::optional<net::Timescale> &tick, llvm::raw_ostream &os);

/// The path to `target` as a VCD in `file`; false after reporting.
bool writeVcdFile(const engine::Explorer &x, sem::Semantics &sem,
                  uint32_t target, const std::optional<net::Timescale> &tick,
                  llvm::StringRef file, DiagEngine &diag);

/// `reach --find` and `--deadlock-trace` after a run: the shortest path to
/// the state found (or to a closest deadlock) or that there is none.
/// Returns the exit code: 0 found / no deadlock, 3 not found / a deadlock,
/// `limitCode` (2) when a limit stopped the search before either was
/// decided.
/// With a `vcdFile`, the path is also written there as a VCD (the view's
/// tick the design's timescale).
int reportSearch(const engine::Explorer &x, sem::Semantics &sem,
                 const engine::ExploreResult &r, llvm::StringRef findText,
                 bool deadlockTrace, int limitCode, llvm::raw_ostream &os,
                 const TraceView &view = {}, llvm::StringRef vcdFile = "",
                 DiagEngine *diag = nullptr);

/// What a trace file says of the path it holds.
struct TraceFileHeader {
  std::string formula;
  bool holds = false;
  bool witness = false; // else a counterexample
  std::string claim;    // what the path shows, in words
};

/// The `time_unit` and `steps` members of a JSON trace (docs/formats.md,
/// "JSON traces"): per step its label, the input classes that took it,
/// the time in ticks, and the values (step 0) or the values it changed.
void writeJsonSteps(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
                    llvm::ArrayRef<const uint64_t *> states,
                    const std::optional<net::Timescale> &tick,
                    llvm::json::OStream &j);

/// A path as a self-contained HTML page: a timing diagram of the
/// program's view (signals as rows, steps as columns; the pointer on a
/// cell shows its value, time and source line). `loopTo` >= 0 as for
/// writePath.
void writeHtmlTrace(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
                    llvm::ArrayRef<const uint64_t *> states,
                    const TraceFileHeader &header, const TraceView &view,
                    int64_t loopTo, llvm::StringRef loopLabel,
                    llvm::raw_ostream &os);

/// The path to `target` as an HTML page in `file` (reach --trace-html).
/// False after reporting.
bool writeHtmlTraceFile(const engine::Explorer &x, sem::Semantics &sem,
                        uint32_t target, const TraceFileHeader &header,
                        const TraceView &view, llvm::StringRef file,
                        DiagEngine &diag);

/// Every JSON trace file written is read back and replayed on the model at
/// once, so a suite run shows that each ends in the state it claims (the
/// driver sets it from NETLIFT_VERIFY_TRACES, as `lit --param roundtrip=1`
/// runs the suite). Off by default.
void setTraceFileVerification(bool on);

/// The path to `target` as a JSON trace document in `file` (reach
/// --trace-json). False after reporting.
bool writeJsonTraceFile(const engine::Explorer &x, sem::Semantics &sem,
                        uint32_t target, const TraceFileHeader &header,
                        const std::optional<net::Timescale> &tick,
                        llvm::StringRef file, DiagEngine &diag);

/// Writes a path as `BASE.json` (the header, the states by id as `reach`
/// numbers them, the step labels, the loop, and the steps as
/// writeJsonSteps writes them), `BASE.aut` (the path as an Aldebaran graph,
/// the loop as an edge back), `BASE.vcd` (writeVcd) and `BASE.html`
/// (writeHtmlTrace). False after reporting.
bool writeTraceFiles(const std::string &base, const TraceFileHeader &header,
                     const engine::Explorer &x, sem::Semantics &sem,
                     const TraceView &view,
                     llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
                     int64_t loopTo, uint32_t loopLabel, DiagEngine &diag);

} // namespace netlift::statespace

#endif
