//===- Parser.h - NetIR text parser -----------------------------*- C++ -*-===//
//
// Reads the NetIR text form (docs/netir.md) into a Design. Hand-written
// recursive descent in the LLVM style: the first syntax error is reported as
// `file:line:col: error:` with the line and a caret, and parsing stops, so a
// mistake never produces a cascade. Names used in arcs are resolved at the
// end of each module (declaration order is free); names in expressions are
// resolved by the verifier.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_PARSER_H
#define NETLIFT_IR_NET_PARSER_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

namespace netlift::net {

/// Parses buffer `bufferID` of the diagnostic engine's SourceMgr into
/// `design`. Returns false (after reporting) on a syntax error.
bool parseNetIR(unsigned bufferID, DiagEngine &diag, Design &design);

/// Parses buffer `bufferID` as one expression (e.g. a predicate given on
/// the command line). Null after reporting an error.
Expr *parseExpression(unsigned bufferID, DiagEngine &diag, Design &design);

/// Is `name` usable as a NetIR identifier as it stands (not a reserved word
/// of the expression language)?
bool isReservedWord(llvm::StringRef name);

} // namespace netlift::net

#endif
