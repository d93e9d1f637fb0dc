//===- IlFrontend.h - Instruction List into the PLC model -------*- C++ -*-===//
//
// Reads IEC 61131-3 Instruction List: POU declarations are parsed as
// Structured Text (they are the same language), bodies with IL.g4, and
// each instruction list is lowered into the PLC model's statements with
// the current result (the accumulator) made explicit. The result is the
// same kind of unit the ST frontend gives, so IL and ST programs translate
// through the same checker and lowering.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_IL_ILFRONTEND_H
#define NETLIFT_FRONTENDS_IL_ILFRONTEND_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

namespace netlift::il {

/// Parses the IL file in SourceMgr buffer `bufferID` into `unit`. Returns
/// false after reporting an error.
bool parseInstructionList(unsigned bufferID, DiagEngine &diag, plc::Unit &unit);

/// Parses one POU's instruction list (`body`, a slice of a SourceMgr
/// buffer) and appends its statements to `pou`, whose declarations are
/// already read (PLCopen XML keeps the two apart). `result`, if given,
/// receives the current result after the last instruction (an SFC
/// transition condition written in IL; null when nothing set it).
bool parseInstructionListBody(llvm::StringRef body, DiagEngine &diag,
                              plc::Unit &unit, plc::Pou *pou,
                              plc::Expr **result = nullptr);

} // namespace netlift::il

#endif
