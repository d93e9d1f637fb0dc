//===- Diagnostics.cpp - file:line:col diagnostics ------------------------===//
#include "ir/support/Diagnostics.h"

#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"

using namespace netlift;

void DiagEngine::print(llvm::SMLoc loc, llvm::SourceMgr::DiagKind kind,
                       const llvm::Twine &msg) {
  if (loc.isValid()) {
    sm.PrintMessage(llvm::errs(), loc, kind, msg);
    return;
  }
  // Entities built by a frontend or a pass may have no location.
  llvm::StringRef k = kind == llvm::SourceMgr::DK_Error     ? "error"
                      : kind == llvm::SourceMgr::DK_Warning ? "warning"
                                                            : "note";
  llvm::errs() << "netlift: " << k << ": " << msg << "\n";
}

void DiagEngine::error(llvm::SMLoc loc, const llvm::Twine &msg) {
  ++errors;
  if (errors > limit) {
    if (!suppressing)
      llvm::errs() << "netlift: too many errors; stopping here\n";
    suppressing = true;
    return;
  }
  print(loc, llvm::SourceMgr::DK_Error, msg);
}

void DiagEngine::warning(llvm::SMLoc loc, const llvm::Twine &msg) {
  if (!suppressing)
    print(loc, llvm::SourceMgr::DK_Warning, msg);
}

void DiagEngine::note(llvm::SMLoc loc, const llvm::Twine &msg) {
  if (!suppressing)
    print(loc, llvm::SourceMgr::DK_Note, msg);
}
