//===- SfcExpansion.h - a Sequential Function Chart as scan code -*- C++
//-*-===//
//
// Turns the chart of a POU written in SFC (textual or graphical) into the
// statements one scan runs, so that Sema and the lowering treat an SFC POU
// like any other: the chart evolves once per scan (transitions cleared on
// the step activity at the scan's start, every enabled transition firing,
// selection by priority), then every action runs under the standard's
// action control. The rules and their sources are in docs/sfc.md.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_SFCEXPANSION_H
#define NETLIFT_FRONTENDS_PLC_SFCEXPANSION_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

namespace netlift::plc {

/// Fills `pou.body` (and the POU's variables) from `pou.sfc`. Reports a
/// malformed chart (a transition from a step that does not exist, no
/// initial step...) at its place and returns false.
bool expandSfc(Unit &unit, Pou &pou, DiagEngine &diag);

} // namespace netlift::plc

#endif
