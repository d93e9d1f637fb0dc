//===- StdLib.h - the IEC 61131-3 standard function blocks ------*- C++ -*-===//
//
// TON, TOF, TP, CTU, CTD, CTUD, R_TRIG, F_TRIG, SR and RS as Structured Text
// netlift ships (StdLib.cpp), added to every PLC unit before checking so
// that ST, IL and LD programs use them like their own function blocks.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_ST_STDLIB_H
#define NETLIFT_FRONTENDS_ST_STDLIB_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

namespace netlift::st {

/// Adds the standard function blocks the unit does not define itself.
bool addStandardLibrary(DiagEngine &diag, plc::Unit &unit);

/// Adds the POUs and globals of a library written in ST (`text`, named
/// `bufferName` in diagnostics) that the unit does not define itself; they
/// are the library's (Pou::isLibrary).
bool addLibraryText(DiagEngine &diag, plc::Unit &unit, llvm::StringRef text,
                    llvm::StringRef bufferName);

/// Adds the models of TwinCAT's libraries (TwinCatLib.cpp) the unit does
/// not define itself: the pure functions and constants of Tc2_Math and
/// Tc2_System that real projects call.
bool addTwinCatLibrary(DiagEngine &diag, plc::Unit &unit);

/// Adds the blocks Beremiz's and OpenPLC's runtime implements
/// (BeremizLib.cpp) the unit does not define itself: LOGGER and the Python
/// extension's blocks, as environment.
bool addBeremizLibrary(DiagEngine &diag, plc::Unit &unit);

/// Is `name` (case-insensitive) one of the standard function blocks?
bool isStandardFunctionBlock(llvm::StringRef name);

} // namespace netlift::st

#endif
