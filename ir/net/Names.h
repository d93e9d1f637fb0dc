//===- Names.h - NetIR identifiers ------------------------------*- C++ -*-===//
//
// What a NetIR name may be, and how a foreign name (a PNML id, a PLC
// variable, an IEC 61499 block, a SpaceEx label) becomes one. The parser,
// the printer and every frontend that builds names agree through these.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_NAMES_H
#define NETLIFT_IR_NET_NAMES_H

#include "llvm/ADT/StringRef.h"

#include <string>
#include <vector>

namespace netlift::net {

/// Is `name` a reserved word of the expression language (and so not usable
/// as a NetIR identifier)?
bool isReservedWord(llvm::StringRef name);

/// Is `name` a simple NetIR identifier (letters, digits and '_', not
/// starting with a digit, not reserved)?
bool isIdentifier(llvm::StringRef name);

/// A NetIR identifier made from a foreign name: every other character
/// becomes '_' ('.' is kept when `keepDots`), a leading digit or an empty
/// name gets a '_' in front, and a reserved word a '_' after.
std::string toIdentifier(llvm::StringRef name, bool keepDots = false);

/// Does a component of `name` start with '_' (`_fifo`, `onOff._queue`)?
/// The IEC 61499 frontend and its passes give what they generate such
/// names, and mark it internal (ir/net/Module.h kInternalAttribute).
bool hasGeneratedComponent(llvm::StringRef name);

/// The qualified names a property, a --find expression or an sr attribute
/// mentions: its runs of letters, digits, `_` and `.`, without a trailing
/// dot, in the order they stand.
std::vector<std::string> qualifiedNamesIn(llvm::StringRef text);

} // namespace netlift::net

#endif
