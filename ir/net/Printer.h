//===- Printer.h - canonical NetIR text -------------------------*- C++ -*-===//
//
// Prints a Design as NetIR text in canonical form: one declaration per line,
// entities in their stored order, a fixed clause order on transitions and
// the fewest parentheses that preserve the tree. Printing what the parser
// read gives the same text again, which golden tests and the round-trip
// check (NETLIFT_VERIFY_ROUNDTRIP) rely on.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_PRINTER_H
#define NETLIFT_IR_NET_PRINTER_H

#include "ir/net/Module.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::net {

void printDesign(const Design &d, llvm::raw_ostream &os);
void printModule(const Module &m, llvm::raw_ostream &os);
void printExpr(const Expr *e, llvm::raw_ostream &os);
std::string exprToString(const Expr *e);

} // namespace netlift::net

#endif
