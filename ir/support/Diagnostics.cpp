//===- Diagnostics.cpp - file:line:col diagnostics ------------------------===//
#include "ir/support/Diagnostics.h"

#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>

using namespace netlift;

void DiagEngine::print(llvm::SMLoc loc, llvm::SourceMgr::DiagKind kind,
                       const llvm::Twine &msg) {
  if (loc.isValid()) {
    unsigned buf = sm.FindBufferContainingLoc(loc);
    llvm::StringRef text = sm.getMemoryBuffer(buf)->getBuffer();
    const char *p = loc.getPointer();
    const char *lineStart = p, *lineEnd = p;
    while (lineStart > text.begin() && lineStart[-1] != '\n')
      --lineStart;
    while (lineEnd < text.end() && *lineEnd != '\n')
      ++lineEnd;
    constexpr size_t kMaxLine = 512;
    if (size_t(lineEnd - lineStart) <= kMaxLine) {
      sm.PrintMessage(llvm::errs(), loc, kind, msg);
      return;
    }
    // A huge line (a generated or binary file) is shown as an excerpt
    // around the column rather than echoed whole.
    auto [line, col] = sm.getLineAndColumn(loc, buf);
    llvm::StringRef k = kind == llvm::SourceMgr::DK_Error     ? "error"
                        : kind == llvm::SourceMgr::DK_Warning ? "warning"
                                                              : "note";
    llvm::errs() << sm.getMemoryBuffer(buf)->getBufferIdentifier() << ":"
                 << line << ":" << col << ": " << k << ": " << msg << "\n";
    const char *from = std::max(lineStart, p - 40);
    const char *to = std::min(lineEnd, p + 40);
    llvm::errs() << "..." << llvm::StringRef(from, to - from) << "...\n";
    llvm::errs().indent(3 + (p - from)) << "^\n";
    return;
  }
  // Entities built by a frontend or a pass may have no location.
  llvm::StringRef k = kind == llvm::SourceMgr::DK_Error     ? "error"
                      : kind == llvm::SourceMgr::DK_Warning ? "warning"
                                                            : "note";
  llvm::errs() << "netlift: " << k << ": " << msg << "\n";
}

void DiagEngine::error(llvm::SMLoc loc, const llvm::Twine &msg) {
  if (deferring) {
    if (!deferred)
      deferred = Deferred{loc, msg.str()};
    return;
  }
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

void DiagEngine::syntaxError(llvm::SMLoc loc, const llvm::Twine &msg) {
  bool was = deferring;
  deferring = false;
  error(loc, msg);
  deferring = was;
}

void DiagEngine::note(llvm::SMLoc loc, const llvm::Twine &msg) {
  if (deferring && deferred)
    return; // belongs to the held-back error
  if (!suppressing)
    print(loc, llvm::SourceMgr::DK_Note, msg);
}

unsigned netlift::addInputFile(llvm::SourceMgr &sm, llvm::StringRef path) {
  auto bufOr = path == "-" ? llvm::MemoryBuffer::getSTDIN()
                           : llvm::MemoryBuffer::getFile(path);
  if (!bufOr) {
    llvm::errs() << "netlift: error: cannot read '" << path
                 << "': " << bufOr.getError().message() << "\n";
    return 0;
  }
  std::unique_ptr<llvm::MemoryBuffer> buf = std::move(*bufOr);
  if (path == "-")
    buf = llvm::MemoryBuffer::getMemBufferCopy(buf->getBuffer(), "<stdin>");
  return sm.AddNewSourceBuffer(std::move(buf), llvm::SMLoc());
}
