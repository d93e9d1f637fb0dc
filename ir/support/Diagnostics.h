//===- Diagnostics.h - file:line:col diagnostics ----------------*- C++ -*-===//
//
// The one way netlift reports problems in its inputs: every frontend, the
// NetIR parser and verifier and every pass report through a DiagEngine,
// which prints `file:line:col: error: message` with the source line and a
// caret via llvm::SourceMgr, counts errors, and stops printing after a limit
// so that a broken input cannot flood the terminal.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_DIAGNOSTICS_H
#define NETLIFT_IR_SUPPORT_DIAGNOSTICS_H

#include "llvm/ADT/Twine.h"
#include "llvm/Support/SMLoc.h"
#include "llvm/Support/SourceMgr.h"

namespace netlift {

/// Reads `path` ("-": standard input, named "<stdin>") into the SourceMgr
/// so diagnostics can point into it. Returns the buffer id, or 0 after
/// printing `netlift: error: cannot read ...`.
unsigned addInputFile(llvm::SourceMgr &sm, llvm::StringRef path);

class DiagEngine {
public:
  explicit DiagEngine(llvm::SourceMgr &sm) : sm(sm) {}

  void error(llvm::SMLoc loc, const llvm::Twine &msg);
  void warning(llvm::SMLoc loc, const llvm::Twine &msg);
  void note(llvm::SMLoc loc, const llvm::Twine &msg);

  unsigned numErrors() const { return errors; }
  bool hadError() const { return errors != 0; }
  llvm::SourceMgr &sourceMgr() { return sm; }
  /// Errors printed before the rest are only counted.
  void setErrorLimit(unsigned n) { limit = n; }

private:
  void print(llvm::SMLoc loc, llvm::SourceMgr::DiagKind kind,
             const llvm::Twine &msg);
  llvm::SourceMgr &sm;
  unsigned errors = 0;
  unsigned limit = 20;
  bool suppressing = false;
};

} // namespace netlift

#endif
