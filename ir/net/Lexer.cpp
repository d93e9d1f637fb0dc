//===- Lexer.cpp - NetIR text lexer ---------------------------------------===//
#include "ir/net/Lexer.h"

using namespace netlift::net;

static inline bool isIdentStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static inline bool isIdentChar(char c) {
  return isIdentStart(c) || (c >= '0' && c <= '9');
}
static inline bool isDigit(char c) { return c >= '0' && c <= '9'; }

void Lexer::skipTrivia() {
  while (cur != end) {
    char c = *cur;
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      ++cur;
      continue;
    }
    if (c == '/' && cur + 1 != end && cur[1] == '/') {
      while (cur != end && *cur != '\n')
        ++cur;
      continue;
    }
    if (c == '/' && cur + 1 != end && cur[1] == '*') {
      const char *start = cur;
      cur += 2;
      while (cur != end && !(*cur == '*' && cur + 1 != end && cur[1] == '/'))
        ++cur;
      if (cur == end) {
        unterminatedComment = start;
        return;
      }
      cur += 2;
      continue;
    }
    return;
  }
}

Token Lexer::lexNumber(const char *start) {
  while (cur != end && isDigit(*cur))
    ++cur;
  // `1.5` is a real; `0..3` is a range.
  if (cur + 1 < end && *cur == '.' && isDigit(cur[1])) {
    ++cur;
    while (cur != end && isDigit(*cur))
      ++cur;
    if (cur != end && (*cur == 'e' || *cur == 'E')) {
      const char *save = cur;
      ++cur;
      if (cur != end && (*cur == '+' || *cur == '-'))
        ++cur;
      if (cur == end || !isDigit(*cur))
        cur = save;
      while (cur != end && isDigit(*cur))
        ++cur;
    }
    return make(Tok::Real, start);
  }
  return make(Tok::Int, start);
}

Token Lexer::next() {
  skipTrivia();
  if (unterminatedComment) {
    const char *s = unterminatedComment;
    return {Tok::Error, llvm::StringRef(s, 2)};
  }
  if (cur == end)
    return {Tok::Eof, llvm::StringRef(end, 0)};
  const char *start = cur;
  char c = *cur++;
  if (isIdentStart(c)) {
    for (;;) {
      while (cur != end && isIdentChar(*cur))
        ++cur;
      // A dot joins qualified names only when an identifier follows.
      if (cur + 1 < end && *cur == '.' && isIdentStart(cur[1])) {
        ++cur;
        continue;
      }
      break;
    }
    return make(Tok::Ident, start);
  }
  if (isDigit(c))
    return lexNumber(start);
  auto two = [&](char n) {
    if (cur != end && *cur == n) {
      ++cur;
      return true;
    }
    return false;
  };
  switch (c) {
  case '"':
    // A string ends at the next unescaped quote on the same line.
    while (cur != end && *cur != '"' && *cur != '\n') {
      if (*cur == '\\' && cur + 1 != end && cur[1] != '\n')
        ++cur;
      ++cur;
    }
    if (cur == end || *cur != '"')
      return {Tok::Error, llvm::StringRef(start, 1)};
    ++cur;
    return make(Tok::String, start);
  case '{':
    return make(Tok::LBrace, start);
  case '}':
    return make(Tok::RBrace, start);
  case '(':
    return make(Tok::LParen, start);
  case ')':
    return make(Tok::RParen, start);
  case '[':
    return make(Tok::LBrack, start);
  case ']':
    return make(Tok::RBrack, start);
  case ';':
    return make(Tok::Semi, start);
  case ',':
    return make(Tok::Comma, start);
  case ':':
    return make(two('=') ? Tok::Assign : Tok::Colon, start);
  case '.':
    return make(two('.') ? Tok::DotDot : Tok::Dot, start);
  case '-':
    return make(two('>') ? Tok::Arrow : Tok::Minus, start);
  case '=':
    return make(two('=') ? Tok::EqEq : Tok::Equal, start);
  case '!':
    if (two('='))
      return make(Tok::Ne, start);
    return make(Tok::Error, start);
  case '<':
    if (two('='))
      return make(Tok::Le, start);
    return make(two('<') ? Tok::Shl : Tok::Lt, start);
  case '>':
    if (two('='))
      return make(Tok::Ge, start);
    return make(two('>') ? Tok::Shr : Tok::Gt, start);
  case '+':
    return make(Tok::Plus, start);
  case '*':
    return make(Tok::Star, start);
  case '/':
    return make(Tok::Slash, start);
  case '%':
    return make(Tok::Percent, start);
  case '&':
    return make(Tok::Amp, start);
  case '|':
    return make(Tok::Pipe, start);
  case '^':
    return make(Tok::Caret, start);
  case '~':
    return make(Tok::Tilde, start);
  case '?':
    return make(Tok::Question, start);
  case '#':
    return make(Tok::Hash, start);
  case '@':
    return make(Tok::At, start);
  case '\'':
    return make(Tok::Prime, start);
  default:
    return make(Tok::Error, start);
  }
}
