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

#include <optional>
#include <string>
#include <vector>

namespace netlift {

/// Reads `path` ("-": standard input, named "<stdin>") into the SourceMgr
/// so diagnostics can point into it. Returns the buffer id, or 0 after
/// printing `netlift: error: cannot read ...`.
unsigned addInputFile(llvm::SourceMgr &sm, llvm::StringRef path);

class DiagEngine {
public:
  explicit DiagEngine(llvm::SourceMgr &sm) : sm(sm) {}

  void error(llvm::SMLoc loc, const llvm::Twine &msg);
  /// A syntax error: reported even while errors are deferred.
  void syntaxError(llvm::SMLoc loc, const llvm::Twine &msg);
  void warning(llvm::SMLoc loc, const llvm::Twine &msg);
  void note(llvm::SMLoc loc, const llvm::Twine &msg);

  /// Between beginDeferral and endDeferral, errors are held back and the
  /// first is kept (with the notes after it dropped): a construct netlift
  /// refuses inside a POU is reported only if the POU is translated.
  /// Syntax errors are never held back. Deferrals nest.
  struct Deferred {
    llvm::SMLoc loc;
    std::string message;
  };
  void beginDeferral() {
    outer.push_back({deferring, std::move(deferred)});
    deferring = true;
    deferred.reset();
  }
  std::optional<Deferred> endDeferral() {
    std::optional<Deferred> held = std::move(deferred);
    deferring = outer.back().first;
    deferred = std::move(outer.back().second);
    outer.pop_back();
    return held;
  }

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
  bool deferring = false;
  std::optional<Deferred> deferred;
  std::vector<std::pair<bool, std::optional<Deferred>>> outer;
};

} // namespace netlift

#endif
