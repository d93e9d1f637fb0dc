//===- JumpExpansion.h - JMP and labels in ST as structured code -*- C++
//-*-===//
//
// CODESYS lets Structured Text jump (`JMP l;`) to a label at the top level
// of the body (`l:`). expandJumps rewrites such a body into the structured
// statements Sema and the lowering know: the body is cut into segments at
// its labels; a jump records its target and skips the rest of its segment
// (EXIT leaves the loops it is in); with forward jumps only, each segment
// runs unless a jump past it is pending, and with a backward jump the
// segments run in a WHILE loop over a segment counter, which the watchdog
// bounds as any loop (docs/st.md, "JMP and labels").
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_JUMPEXPANSION_H
#define NETLIFT_FRONTENDS_PLC_JUMPEXPANSION_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

namespace netlift::plc {

/// Rewrites the jumps and labels of `pou.body` (a body without any is left
/// alone). Reports a jump to a label the body does not have, a label
/// twice, or EXIT/CONTINUE outside a loop, and returns false.
bool expandJumps(Unit &unit, Pou &pou, DiagEngine &diag);

} // namespace netlift::plc

#endif
