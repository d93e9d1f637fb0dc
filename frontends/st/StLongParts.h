//===- StLongParts.h - long ST bodies parsed in groups ----------*- C++ -*-===//
//
// ANTLR's C++ runtime keeps every token and tree node of a parse until the
// parser dies, so the ST frontend takes long POU bodies and VAR blocks out
// of a file's parse (SkippingSource) and parses them in groups of whole
// statements or declarations (findLongParts). Internal to frontends/st.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_ST_STLONGPARTS_H
#define NETLIFT_FRONTENDS_ST_STLONGPARTS_H

#include "frontends/st/StFrontend.h"
#include "frontends/st/StLexer.h"

#include "antlr4-runtime.h"

#include <map>
#include <utility>
#include <vector>

namespace netlift::st {

/// Long POU bodies and VAR blocks, found by one pass of the lexer. ANTLR's
/// C++ runtime keeps every token and every tree node of a parse until the
/// parser dies (about 300 bytes per source byte), so a long body or block
/// is taken out of the file's parse and parsed in groups of about
/// groupTokens tokens, each with a parser of its own: statements cut after
/// a `;` outside any IF/CASE/FOR/WHILE/REPEAT, declarations after a `;`
/// outside any STRUCT. Groups are contiguous, so comments and pragmas stay
/// with the declaration they precede.
struct LongParts {
  std::vector<std::pair<size_t, size_t>> ranges; // [begin, end) in order
  /// The groups, by the offset of the token that closes the part
  /// (END_PROGRAM, END_FUNCTION_BLOCK, END_FUNCTION or END_VAR).
  std::map<size_t, std::vector<llvm::StringRef>> groups;
};

/// The long parts of `text` (none when it is short).
LongParts findLongParts(llvm::StringRef text, DiagEngine &diag,
                        const ParseOptions &options);

/// The lexer's tokens without those of the long parts.
class SkippingSource : public antlr4::TokenSource {
public:
  SkippingSource(StLexer &lexer,
                 const std::vector<std::pair<size_t, size_t>> &skip)
      : lexer(lexer), skip(skip) {}
  std::unique_ptr<antlr4::Token> nextToken() override {
    for (;;) {
      std::unique_ptr<antlr4::Token> t = lexer.nextToken();
      if (t->getType() == antlr4::Token::EOF)
        return t;
      size_t at = t->getStartIndex();
      while (next < skip.size() && at >= skip[next].second)
        ++next;
      if (next == skip.size() || at < skip[next].first)
        return t;
    }
  }
  size_t getLine() const override { return lexer.getLine(); }
  size_t getCharPositionInLine() override {
    return lexer.getCharPositionInLine();
  }
  antlr4::CharStream *getInputStream() override { return nullptr; }
  std::string getSourceName() override { return lexer.getSourceName(); }
  antlr4::TokenFactory<antlr4::CommonToken> *getTokenFactory() override {
    return lexer.getTokenFactory();
  }

private:
  StLexer &lexer;
  const std::vector<std::pair<size_t, size_t>> &skip;
  size_t next = 0;
};

} // namespace netlift::st

#endif
