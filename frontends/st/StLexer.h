//===- StLexer.h - hand-written lexer for Structured Text -------*- C++ -*-===//
//
// Turns an ST buffer into the tokens the generated parser (ST.g4) expects,
// behind ANTLR's TokenSource interface. Hand-written because IEC keywords are
// case-insensitive, comments nest, `T#1h2m`, `16#FF` and `%IX0.1` are single
// tokens, and because the generated lexer of the ANTLR C++ runtime is too
// slow for the throughput netlift promises. Pragmas `{...}` go to the
// hidden channel kPragmaChannel so the builder can attach them to the
// declaration that follows; matiec's `{{ C code }}` is refused here.
//
// Every token's start index is a byte offset into the buffer, so a token
// maps back to an SMLoc for diagnostics.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_ST_STLEXER_H
#define NETLIFT_FRONTENDS_ST_STLEXER_H

#include "ir/support/Diagnostics.h"

#include "antlr4-runtime.h"

#include "llvm/ADT/StringRef.h"

#include <optional>
#include <string>

namespace netlift::st {

inline constexpr size_t kPragmaChannel = 2;

class StLexer : public antlr4::TokenSource {
public:
  /// `text` must stay alive as long as the tokens; `diag` receives lexical
  /// errors (after the first one the lexer returns EOF). With `lineEnds`
  /// (Instruction List bodies) each line end is an EOL token.
  StLexer(llvm::StringRef text, DiagEngine &diag, bool lineEnds = false);

  std::unique_ptr<antlr4::Token> nextToken() override;
  size_t getLine() const override { return line; }
  size_t getCharPositionInLine() override { return pos - lineStart; }
  antlr4::CharStream *getInputStream() override { return nullptr; }
  std::string getSourceName() override { return "st"; }
  antlr4::TokenFactory<antlr4::CommonToken> *getTokenFactory() override {
    return antlr4::CommonTokenFactory::DEFAULT.get();
  }

  bool hadError() const { return failed; }
  /// Lexical errors end the token stream without a message (for scans that
  /// only look for structure; the real parse reports them).
  void setSilent() { silent = true; }
  llvm::SMLoc locAt(size_t offset) const {
    return llvm::SMLoc::getFromPointer(text.data() + offset);
  }

  /// The token type of an IEC keyword (case-insensitive), or 0.
  static size_t keywordType(llvm::StringRef word);

private:
  std::unique_ptr<antlr4::Token> make(size_t type, size_t start,
                                      size_t channel = 0);
  std::unique_ptr<antlr4::Token> fail(size_t at, const llvm::Twine &msg);
  bool skipTrivia(); // false on an unterminated comment
  /// After `(*@KEY@:DESCRIPTION*)`, skips to `(*@KEY@:END_DESCRIPTION*)`.
  bool skipKeySection(size_t commentStart);
  void lexBasedOrDecimal();
  bool endsVariable(size_t type) const;
  void newlinesIn(size_t from, size_t to);

  llvm::StringRef text;
  DiagEngine &diag;
  size_t pos = 0;
  size_t line = 1;
  size_t lineStart = 0;
  size_t tokenLine = 1, tokenCol = 0;
  size_t tokenIndex = 0;
  size_t lastType = 0; // of the last token on the parser's channel
  bool failed = false;
  bool lineEnds = false;
  bool silent = false;
};

/// Moves the default-channel tokens in [begin, end) (never EOF) off the
/// parser's channel, so that a new parse skips them: how the ST and IL
/// frontends take a broken statement out to reach the next mistake. False
/// when there was nothing to move.
bool hideTokens(antlr4::BufferedTokenStream &tokens, size_t begin, size_t end);

/// A pragma inside a body is harmless where it is one of the message and
/// structuring pragmas CODESYS and TwinCAT define. Anything else there is
/// refused: matiec copies such a pragma verbatim into the C it generates
/// (its library's timers and RTC read the PLC clock that way, `{__SET_VAR(
/// ...CURRENT_TIME...)}`), and conditional compilation (`{IF defined(...)}`)
/// would choose statements; read as a comment either would be a silently
/// different program.
/// Returns why the pragma (its text with braces) is refused, or nothing.
std::optional<std::string> refusedBodyPragma(llvm::StringRef pragma);

} // namespace netlift::st

#endif
