//===- ParseLocations.cpp - statements' source locations in NetIR text ----===//
//
// A NetIR file written from a program keeps where each statement came from:
// `source N = "delay.st";` lines before the modules and `@N:line:col` after
// a statement. Reading them back points the statements into the program
// file itself (loaded into the SourceMgr), so traces and run-time errors of
// a model read from NetIR name the program's lines, as they do when the
// program is explored directly. A file that is gone or no longer has the
// line is replaced by a blank stand-in of the same name: the location still
// prints as `delay.st:7`, without the line's text.
//
//===----------------------------------------------------------------------===//
#include "ir/net/ParserImpl.h"

#include "llvm/ADT/SmallString.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::net::detail;

bool Parser::parseSourceDecl() {
  SMLoc loc = tok.loc();
  consume(); // source
  int64_t number;
  if (!parseInt(number, "a source file number"))
    return false;
  if (number <= 0)
    return error(loc, "a source file number must be positive");
  if (sourceFiles.count(number))
    return error(loc, "source " + llvm::Twine(number) + " given twice");
  if (!expect(Tok::Equal, "'='"))
    return false;
  SourceFile file;
  file.declLoc = loc;
  if (!parseQuotedText(file.path))
    return false;
  if (file.path.empty())
    return error(loc, "a source file needs a name");
  sourceFiles.emplace(number, std::move(file));
  return expect(Tok::Semi, "';'");
}

bool Parser::parseStmtLocation(Stmt *s) {
  SMLoc loc = tok.loc();
  consume(); // @
  int64_t file, line, col;
  if (!parseInt(file, "a source file number"))
    return false;
  if (!sourceFiles.count(file))
    return error(loc, "no 'source " + llvm::Twine(file) +
                          " = \"...\";' before the modules");
  if (!expect(Tok::Colon, "':' and a line number") ||
      !parseInt(line, "a line number") ||
      !expect(Tok::Colon, "':' and a column number") ||
      !parseInt(col, "a column number"))
    return false;
  if (line <= 0 || col <= 0)
    return error(loc, "a source location's line and column start at 1");
  // A stand-in file is as long as the lines used: keep it plausible.
  if (line > (1 << 24) || col > (1 << 16))
    return error(loc, "source location " + llvm::Twine(line) + ":" +
                          llvm::Twine(col) + " is beyond any program file");
  pendingLocations.push_back({s, file, unsigned(line), unsigned(col)});
  return true;
}

namespace {

/// The buffer already holding `path`, or the file read under that name
/// (found as written, else beside the NetIR file); 0 if it cannot be read.
unsigned loadSourceFile(llvm::SourceMgr &sm, StringRef path,
                        const char *netirText) {
  for (unsigned id = 1; id <= sm.getNumBuffers(); ++id)
    if (sm.getMemoryBuffer(id)->getBufferIdentifier() == path)
      return id;
  auto file = llvm::MemoryBuffer::getFile(path);
  if (!file && llvm::sys::path::is_relative(path)) {
    if (unsigned here =
            sm.FindBufferContainingLoc(SMLoc::getFromPointer(netirText))) {
      llvm::SmallString<256> beside(llvm::sys::path::parent_path(
          sm.getMemoryBuffer(here)->getBufferIdentifier()));
      llvm::sys::path::append(beside, path);
      file = llvm::MemoryBuffer::getFile(beside);
    }
  }
  if (!file)
    return 0;
  // Named as written, so printing the model again gives the same text.
  return sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy((*file)->getBuffer(), path),
      SMLoc());
}

/// Is (line, col) inside buffer `id`, and where?
SMLoc locate(llvm::SourceMgr &sm, unsigned id, unsigned line, unsigned col) {
  SMLoc loc = sm.FindLocForLineAndColumn(id, line, col);
  if (!loc.isValid() || sm.getLineAndColumn(loc, id) != std::pair(line, col))
    return SMLoc();
  return loc;
}

} // namespace

void Parser::resolveStmtLocations() {
  if (pendingLocations.empty())
    return;
  llvm::SourceMgr &sm = diag.sourceMgr();
  for (auto &[number, file] : sourceFiles) {
    std::vector<PendingLocation *> uses;
    for (PendingLocation &p : pendingLocations)
      if (p.file == number)
        uses.push_back(&p);
    if (uses.empty())
      continue;
    unsigned id = loadSourceFile(sm, file.path, bufferStart);
    bool matches = id != 0;
    for (PendingLocation *p : uses) {
      if (!matches)
        break;
      if (SMLoc loc = locate(sm, id, p->line, p->col); loc.isValid())
        p->stmt->loc = loc;
      else
        matches = false;
    }
    if (matches)
      continue;
    // A stand-in: blank lines long enough for every column used.
    std::vector<unsigned> width;
    for (PendingLocation *p : uses) {
      if (width.size() < p->line)
        width.resize(p->line, 0);
      width[p->line - 1] = std::max(width[p->line - 1], p->col);
    }
    std::string text;
    for (unsigned w : width)
      text.append(w, ' ').push_back('\n');
    id = sm.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(text, file.path), SMLoc());
    for (PendingLocation *p : uses)
      p->stmt->loc = locate(sm, id, p->line, p->col);
  }
  pendingLocations.clear();
}
