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
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <map>
#include <optional>
#include <string>

namespace netlift::plc {

struct LowerOptions {
  /// The program, program instance or function block to translate; empty:
  /// every program the configuration runs (or every program).
  std::string top;
  /// Length of one tick; default: the greatest common divisor of every
  /// TIME literal and task interval the translated code uses.
  std::optional<int64_t> timescaleNs;
  /// Scan period; default: the task's INTERVAL, else one tick.
  std::optional<int64_t> scanPeriodNs;
  /// Value ranges of integer inputs by (upper-case) variable name, from
  /// --ranges; pragmas `{range lo..hi}` on the declaration also work.
  std::map<std::string, std::pair<int64_t, int64_t>> ranges;
};

/// Lowers the checked unit into `design`. Returns false after reporting.
bool lowerToNet(Unit &unit, const LowerOptions &opts, DiagEngine &diag,
                net::Design &design);

} // namespace netlift::plc

#endif
