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

#include "llvm/ADT/DenseMap.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

#include <string>
#include <vector>

namespace netlift::net {

/// Numbers the source files that statements were lowered from, for the
/// `source N = "file";` lines and the `@N:line:col` after each statement,
/// so the program's own lines survive a NetIR file (translate, compose and
/// opt write it; reach and check read it back for their traces).
class SourceTable {
public:
  explicit SourceTable(const llvm::SourceMgr &sm);
  /// `@N:line:col` for a location in a program file; empty for no location,
  /// netlift's own text and NetIR files (whose lines are the text itself).
  std::string reference(llvm::SMLoc loc);
  llvm::ArrayRef<std::string> fileNames() const { return files; }
  /// Is a buffer of this name a source whose lines a NetIR file carries?
  static bool carriesLocations(llvm::StringRef bufferName);

private:
  const llvm::SourceMgr &sm;
  llvm::DenseMap<unsigned, unsigned> numbers; // buffer id -> N (0: none)
  std::vector<std::string> files;
};

/// With `sources`, statements carry their source locations (`@N:line:col`
/// after a `source` table); without, the text is the bare model.
void printDesign(const Design &d, llvm::raw_ostream &os,
                 const llvm::SourceMgr *sources = nullptr);
void printModule(const Module &m, llvm::raw_ostream &os,
                 SourceTable *sources = nullptr);
void printExpr(const Expr *e, llvm::raw_ostream &os);
std::string exprToString(const Expr *e);

} // namespace netlift::net

#endif
