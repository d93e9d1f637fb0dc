//===- LowerToNet.h - a checked PLC program as a NetIR controller -*- C++ -*-=//
//
// Design §3.4: one controller module per program. BOOL inputs and outputs
// become cond ports, other located or declared inputs and outputs data
// ports, memory and function-block state data variables (FB instances are
// flattened into `inst.member` variables), timers' elapsed time clock
// variables, and one urgent transition `scan` on a `cycle` place with
// interval [T,T] runs the whole program body as its action. Functions and
// FB bodies are inlined at each call. What cannot be modelled faithfully —
// REAL arithmetic, strings, unbounded loops, unbounded integer inputs — is
// refused with its location; nothing is dropped.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_LOWERTONET_H
#define NETLIFT_FRONTENDS_PLC_LOWERTONET_H

#include "frontends/plc/PlcAst.h"
#include "frontends/plc/Sema.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace netlift::plc {

struct LowerOptions {
  /// The program, program instance or function block to translate; empty:
  /// every program the configuration runs (or every program).
  std::string top;
  /// --opaque=refuse: an instance of a library block with effects netlift
  /// does not model (Pou::environment) is refused instead of modelled as
  /// environment.
  bool opaqueRefused = false;
  /// --caller-elements: how many elements of a caller's array too large
  /// to choose whole (a `POINTER TO ARRAY[0..32000] OF BYTE` input of the
  /// block run as the top) are modelled; an element past them is a
  /// run-time error.
  int64_t callerElements = 16;
  /// Length of one tick; default: the greatest common divisor of every
  /// TIME literal and task interval the translated code uses.
  std::optional<int64_t> timescaleNs;
  /// Scan period; default: the task's INTERVAL, else one tick.
  std::optional<int64_t> scanPeriodNs;
  /// Value ranges of integer inputs by (upper-case) variable name or
  /// location, from --ranges (where each line is, for errors); pragmas
  /// `{range lo..hi}` on the declaration also work. An entry that names no
  /// integer input of the translated programs is an error.
  struct RangeEntry {
    int64_t lo, hi;
    std::string name;
    llvm::SMLoc loc;
    /// `NAME NOT NULL`: a reference input the caller never passes NULL.
    bool notNull = false;
  };
  std::map<std::string, RangeEntry> ranges;
  /// Durations used outside the PLC code (IEC 61499 parameters), counted
  /// when the tick is chosen.
  std::vector<int64_t> extraTimesNs;
  /// Where the first input file starts: errors about the unit as a whole
  /// (no program in it) point there when no declaration can be named.
  llvm::SMLoc unitStart;
};

/// An IEC 61499 function block's reaction to one event input: `body` runs
/// in the step in which the event arrives (docs/iec61499.md).
struct EventHandler {
  std::string event;
  StmtList body;
  llvm::SMLoc loc;
  /// Only records that the event came (the cyclic model's flags): it
  /// neither waits for the block's turn (`ready`) nor resets temporaries,
  /// so events arriving together are all recorded in one step.
  bool latch = false;
};

/// An output event: an urgent transition `send_<event>` emits it whenever
/// `guard` holds, running `body` (which takes it off the block's queue).
struct EventSend {
  std::string event;
  Expr *guard = nullptr;
  StmtList body;
  llvm::SMLoc loc;
};

/// A function block executed by events instead of a scan: its VAR_INPUT
/// and VAR_OUTPUT become data ports (BOOL ones cond ports) of their full
/// types, its other variables data variables, and each handler a forced
/// transition `recv_<event>` on the event input. Handler bodies and send
/// guards and bodies must have been checked with the POU (Sema), e.g. by
/// being part of its body too.
struct EventDrivenBlock {
  Pou *pou = nullptr;
  std::vector<std::pair<std::string, llvm::SMLoc>> eventInputs, eventOutputs;
  std::vector<EventHandler> handlers;
  std::vector<EventSend> sends;
};

/// Lowers event-driven blocks of the checked unit into `design`, one
/// module each, named like the POU.
bool lowerEventDriven(Unit &unit, std::vector<EventDrivenBlock> &blocks,
                      const LowerOptions &opts, DiagEngine &diag,
                      net::Design &design);

/// A duration in the largest unit that keeps it whole: 1s, 300ms, 1500us.
std::string formatDuration(int64_t ns);

/// The NetIR type of an elementary value as the lowering declares it
/// (TIME in ticks, REAL as real32, STRING[n] as string[n], ULINT and LWORD
/// as uint64); null for the types netlift does not model (dates, CHAR).
const net::Type *scalarNetType(const PType *t, net::TypeTable &types);

/// Lowers the checked unit into `design`. Returns false after reporting.
bool lowerToNet(Unit &unit, const LowerOptions &opts, DiagEngine &diag,
                net::Design &design);

/// Is the unit a library: function blocks, no PROGRAM, no configuration
/// running one?
bool isLibrary(const Unit &unit);

/// A library: each of its function blocks lowered as a module of its own
/// (as `--top` would), those Sema refused skipped (their errors are
/// reported), one tick for all. Returns false if any was refused.
bool lowerLibrary(Unit &unit, const LowerOptions &opts, DiagEngine &diag,
                  net::Design &design);

} // namespace netlift::plc

#endif
