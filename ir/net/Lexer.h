//===- Lexer.h - NetIR text lexer -------------------------------*- C++ -*-===//
//
// Splits NetIR text into tokens. Hand-written for speed: one pass over the
// buffer with no allocation. Qualified names (`c.scan`, `p.pos.x`) are single
// identifier tokens; keywords are contextual and recognised by the parser, so
// a place may be called `end` or `on`.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_LEXER_H
#define NETLIFT_IR_NET_LEXER_H

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"

namespace netlift::net {

enum class Tok : uint8_t {
  Eof,
  Error, // text holds the offending character(s)
  Ident,
  Int,
  Real,
  String, // "..." with \" and \\ escapes; text keeps the quotes
  LBrace,
  RBrace,
  LParen,
  RParen,
  LBrack,
  RBrack,
  Semi,
  Comma,
  Colon,
  Dot,
  DotDot,
  Arrow,  // ->
  Assign, // :=
  Equal,  // =
  EqEq,
  Ne,
  Lt,
  Le,
  Gt,
  Ge,
  Plus,
  Minus,
  Star,
  Slash,
  Percent,
  Amp,
  Pipe,
  Caret,
  Tilde,
  Shl,
  Shr,
  Question,
  Hash,
  Prime,
  At, // @ (a statement's source location)
};

struct Token {
  Tok kind = Tok::Eof;
  llvm::StringRef text;
  llvm::SMLoc loc() const { return llvm::SMLoc::getFromPointer(text.data()); }
  bool is(Tok k) const { return kind == k; }
  bool isIdent(llvm::StringRef s) const {
    return kind == Tok::Ident && text == s;
  }
};

class Lexer {
public:
  explicit Lexer(llvm::StringRef buffer)
      : cur(buffer.begin()), end(buffer.end()) {}
  Token next();
  /// Set when an unterminated comment was seen (reported at its start).
  const char *unterminatedComment = nullptr;

private:
  Token make(Tok k, const char *start) {
    return {k, llvm::StringRef(start, cur - start)};
  }
  Token lexNumber(const char *start);
  void skipTrivia();
  const char *cur;
  const char *end;
};

} // namespace netlift::net

#endif
