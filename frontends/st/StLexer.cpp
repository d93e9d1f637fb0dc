//===- StLexer.cpp - hand-written lexer for Structured Text ---------------===//
#include "frontends/st/StLexer.h"

#include "ST.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSwitch.h"

#include <cctype>

using namespace netlift;
using namespace netlift::st;
using llvm::StringRef;
using P = stgen::ST;

namespace {

bool isIdentStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isIdentChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

const llvm::StringMap<size_t> &keywordTable() {
  static const llvm::StringMap<size_t> table = [] {
    llvm::StringMap<size_t> t;
    auto add = [&](const char *w, size_t type) { t[w] = type; };
    add("PROGRAM", P::PROGRAM);
    add("END_PROGRAM", P::END_PROGRAM);
    add("FUNCTION_BLOCK", P::FUNCTION_BLOCK);
    add("END_FUNCTION_BLOCK", P::END_FUNCTION_BLOCK);
    add("FUNCTION", P::FUNCTION);
    add("END_FUNCTION", P::END_FUNCTION);
    add("TYPE", P::TYPE);
    add("END_TYPE", P::END_TYPE);
    add("STRUCT", P::STRUCT);
    add("END_STRUCT", P::END_STRUCT);
    add("UNION", P::UNION);
    add("END_UNION", P::END_UNION);
    add("CONFIGURATION", P::CONFIGURATION);
    add("END_CONFIGURATION", P::END_CONFIGURATION);
    add("RESOURCE", P::RESOURCE);
    add("END_RESOURCE", P::END_RESOURCE);
    add("ON", P::ON);
    add("TASK", P::TASK);
    add("WITH", P::WITH);
    add("VAR", P::VAR);
    add("VAR_INPUT", P::VAR_INPUT);
    add("VAR_OUTPUT", P::VAR_OUTPUT);
    add("VAR_IN_OUT", P::VAR_IN_OUT);
    add("VAR_EXTERNAL", P::VAR_EXTERNAL);
    add("VAR_GLOBAL", P::VAR_GLOBAL);
    add("VAR_TEMP", P::VAR_TEMP);
    add("VAR_ACCESS", P::VAR_ACCESS);
    add("VAR_CONFIG", P::VAR_CONFIG);
    add("VAR_STAT", P::VAR_STAT);
    add("VAR_INST", P::VAR_INST);
    add("END_VAR", P::END_VAR);
    add("CONSTANT", P::CONSTANT);
    add("RETAIN", P::RETAIN);
    add("NON_RETAIN", P::NON_RETAIN);
    add("PERSISTENT", P::PERSISTENT);
    add("AT", P::AT);
    add("ARRAY", P::ARRAY);
    add("OF", P::OF);
    add("STRING", P::STRING_KW);
    add("WSTRING", P::WSTRING_KW);
    add("POINTER", P::POINTER);
    add("REFERENCE", P::REFERENCE);
    add("TO", P::TO);
    add("REF_TO", P::REF_TO);
    add("METHOD", P::METHOD);
    add("END_METHOD", P::END_METHOD);
    add("PROPERTY", P::PROPERTY);
    add("END_PROPERTY", P::END_PROPERTY);
    add("END_GET", P::END_GET);
    add("END_SET", P::END_SET);
    add("INTERFACE", P::INTERFACE);
    add("END_INTERFACE", P::END_INTERFACE);
    add("EXTENDS", P::EXTENDS);
    add("IMPLEMENTS", P::IMPLEMENTS);
    add("ACTION", P::ACTION);
    add("END_ACTION", P::END_ACTION);
    add("ACTIONS", P::ACTIONS);
    add("END_ACTIONS", P::END_ACTIONS);
    add("CLASS", P::CLASS);
    add("END_CLASS", P::END_CLASS);
    add("NAMESPACE", P::NAMESPACE);
    add("END_NAMESPACE", P::END_NAMESPACE);
    add("INITIAL_STEP", P::INITIAL_STEP);
    add("STEP", P::STEP);
    add("END_STEP", P::END_STEP);
    add("TRANSITION", P::TRANSITION);
    add("END_TRANSITION", P::END_TRANSITION);
    add("FROM", P::FROM);
    add("ABSTRACT", P::ABSTRACT);
    add("FINAL", P::FINAL);
    add("PUBLIC", P::PUBLIC);
    add("PRIVATE", P::PRIVATE);
    add("PROTECTED", P::PROTECTED);
    add("INTERNAL", P::INTERNAL);
    add("OVERRIDE", P::OVERRIDE);
    add("IF", P::IF);
    add("THEN", P::THEN);
    add("ELSIF", P::ELSIF);
    add("ELSE", P::ELSE);
    add("END_IF", P::END_IF);
    add("CASE", P::CASE);
    add("END_CASE", P::END_CASE);
    add("FOR", P::FOR);
    add("BY", P::BY);
    add("DO", P::DO);
    add("END_FOR", P::END_FOR);
    add("WHILE", P::WHILE);
    add("END_WHILE", P::END_WHILE);
    add("REPEAT", P::REPEAT);
    add("UNTIL", P::UNTIL);
    add("END_REPEAT", P::END_REPEAT);
    add("EXIT", P::EXIT);
    add("CONTINUE", P::CONTINUE);
    add("RETURN", P::RETURN);
    add("JMP", P::JMP);
    add("OR", P::OR);
    add("XOR", P::XOR);
    add("AND", P::AND);
    add("NOT", P::NOT);
    add("MOD", P::MOD);
    add("AND_THEN", P::AND_THEN);
    add("OR_ELSE", P::OR_ELSE);
    add("TRUE", P::TRUE);
    add("FALSE", P::FALSE);
    return t;
  }();
  return table;
}

/// What a `PREFIX#` introduces when the literal after it is not an ordinary
/// token: durations, times of day, dates, dates and times.
size_t literalPrefixType(StringRef upper) {
  return llvm::StringSwitch<size_t>(upper)
      .Cases("T", "TIME", "LT", "LTIME", P::DURATION)
      .Cases("TOD", "TIME_OF_DAY", "LTOD", "LTIME_OF_DAY", P::TOD_LIT)
      .Cases("D", "DATE", "LD", "LDATE", P::DATE_LIT)
      .Cases("DT", "DATE_AND_TIME", "LDT", "LDATE_AND_TIME", P::DT_LIT)
      .Default(0);
}

std::string upper(StringRef s) {
  std::string u(s.size(), ' ');
  for (size_t i = 0; i < s.size(); ++i)
    u[i] = std::toupper(static_cast<unsigned char>(s[i]));
  return u;
}

} // namespace

size_t StLexer::keywordType(StringRef word) {
  char buf[32];
  if (word.size() >= sizeof(buf))
    return 0;
  for (size_t i = 0; i < word.size(); ++i)
    buf[i] = std::toupper(static_cast<unsigned char>(word[i]));
  auto it = keywordTable().find(StringRef(buf, word.size()));
  return it == keywordTable().end() ? 0 : it->second;
}

StLexer::StLexer(StringRef text, DiagEngine &diag, bool lineEnds)
    : text(text), diag(diag), lineEnds(lineEnds) {
  if (text.startswith("\xEF\xBB\xBF")) // UTF-8 byte order mark
    pos = lineStart = 3;
}

void StLexer::newlinesIn(size_t from, size_t to) {
  for (size_t i = from; i < to; ++i)
    if (text[i] == '\n') {
      ++line;
      lineStart = i + 1;
    }
}

std::unique_ptr<antlr4::Token> StLexer::make(size_t type, size_t start,
                                             size_t channel) {
  auto tok = std::make_unique<antlr4::CommonToken>(
      std::make_pair(static_cast<antlr4::TokenSource *>(this),
                     static_cast<antlr4::CharStream *>(nullptr)),
      type, channel, start, pos == start ? start : pos - 1);
  tok->setText(text.substr(start, pos - start).str());
  tok->setLine(tokenLine);
  tok->setCharPositionInLine(tokenCol);
  tok->setTokenIndex(tokenIndex++);
  if (channel == 0)
    lastType = type;
  return tok;
}

std::unique_ptr<antlr4::Token> StLexer::fail(size_t at,
                                             const llvm::Twine &msg) {
  if (!silent)
    diag.syntaxError(locAt(at), msg);
  failed = true;
  pos = text.size();
  return make(antlr4::Token::EOF, pos);
}

// Text exports that mark their sections with `(*@KEY@:NAME*)` comments
// (MULTIPROG/PC WORX-style, a form OSCAT is also passed around in) carry a
// POU's description as free text between `(*@KEY@:DESCRIPTION*)` and
// `(*@KEY@:END_DESCRIPTION*)`: it is not ST, so the whole section is a
// comment. Other sections are left to be read as ST.
bool StLexer::skipKeySection(size_t commentStart) {
  if (text.slice(commentStart + 2, pos - 2).trim() != "@KEY@:DESCRIPTION")
    return true;
  StringRef closing = "(*@KEY@:END_DESCRIPTION*)";
  size_t end = text.find(closing, pos);
  if (end == StringRef::npos) {
    fail(commentStart,
         "section '(*@KEY@:DESCRIPTION*)' has no '" + closing + "'");
    return false;
  }
  newlinesIn(pos, end);
  pos = end + closing.size();
  return true;
}

bool StLexer::skipTrivia() {
  while (pos < text.size()) {
    char c = text[pos];
    if (c == '\n' && lineEnds)
      return true; // an EOL token
    if (c == '\n') {
      ++pos;
      ++line;
      lineStart = pos;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos;
    } else if (c == '(' && pos + 1 < text.size() && text[pos + 1] == '*') {
      // IEC 61131-3 3rd edition: comments nest.
      size_t start = pos;
      size_t startLine = line, startLineStart = lineStart;
      unsigned depth = 0;
      while (pos < text.size()) {
        if (text[pos] == '(' && pos + 1 < text.size() && text[pos + 1] == '*') {
          ++depth;
          pos += 2;
        } else if (text[pos] == '*' && pos + 1 < text.size() &&
                   text[pos + 1] == ')') {
          pos += 2;
          if (--depth == 0)
            break;
        } else {
          if (text[pos] == '\n') {
            ++line;
            lineStart = pos + 1;
          }
          ++pos;
        }
      }
      if (depth != 0) {
        // Nesting leaves it open to the end; read without nesting (the 2nd
        // edition's reading, matiec's, common in libraries ported from
        // it) it ends at its first '*)'.
        size_t end = text.find("*)", start + 2);
        if (end == StringRef::npos) {
          fail(start, "unterminated comment '(*'");
          return false;
        }
        line = startLine;
        lineStart = startLineStart;
        newlinesIn(start, end);
        pos = end + 2;
        if (!silent)
          diag.note(locAt(start),
                    "this comment holds an unclosed '(*', so nested it would "
                    "run to the end of the text; it is read without nesting, "
                    "ending at its first '*)'");
      }
      if (!skipKeySection(start))
        return false;
    } else if (c == '/' && pos + 1 < text.size() && text[pos + 1] == '*') {
      size_t start = pos;
      size_t end = text.find("*/", pos + 2);
      if (end == StringRef::npos) {
        fail(start, "unterminated comment '/*'");
        return false;
      }
      newlinesIn(pos, end);
      pos = end + 2;
    } else if (c == '/' && pos + 1 < text.size() && text[pos + 1] == '/') {
      while (pos < text.size() && text[pos] != '\n')
        ++pos;
    } else {
      return true;
    }
  }
  return true;
}

void StLexer::lexBasedOrDecimal() {
  while (
      pos < text.size() &&
      (std::isdigit(static_cast<unsigned char>(text[pos])) || text[pos] == '_'))
    ++pos;
}

// Can a token of this type end a variable access (a name, including the
// words IEC reserves only in some places, an index, a dereference, a bit
// number, a direct address)?
bool StLexer::endsVariable(size_t type) const {
  switch (type) {
  case P::IDENT:
  case P::RBRACKET:
  case P::CARET:
  case P::INTEGER:
  case P::DIRECT:
  case P::ON:
  case P::STEP:
  case P::FROM:
  case P::ACTION:
  case P::ACTIONS:
  case P::CLASS:
  case P::METHOD:
  case P::PROPERTY:
  case P::INTERFACE:
  case P::NAMESPACE:
  case P::ABSTRACT:
  case P::FINAL:
  case P::PUBLIC:
  case P::PRIVATE:
  case P::PROTECTED:
  case P::INTERNAL:
  case P::OVERRIDE:
  case P::POINTER:
  case P::REFERENCE:
  case P::TRANSITION:
    return true;
  default:
    return false;
  }
}

std::unique_ptr<antlr4::Token> StLexer::nextToken() {
  if (failed || !skipTrivia()) {
    pos = text.size();
    return make(antlr4::Token::EOF, pos);
  }
  size_t start = pos;
  tokenLine = line;
  tokenCol = pos - lineStart;
  if (pos >= text.size())
    return make(antlr4::Token::EOF, pos);
  char c = text[pos];
  auto peek = [&](size_t k) -> char {
    return pos + k < text.size() ? text[pos + k] : '\0';
  };

  if (isIdentStart(c)) {
    while (pos < text.size() && isIdentChar(text[pos]))
      ++pos;
    StringRef word = text.substr(start, pos - start);
    if (peek(0) == '#') {
      std::string up = upper(word);
      if (size_t type = literalPrefixType(up)) {
        ++pos; // '#'
        while (pos < text.size() &&
               (isIdentChar(text[pos]) || text[pos] == '.' ||
                text[pos] == '-' || text[pos] == ':' || text[pos] == '+'))
          ++pos;
        // A trailing '.' belongs to the next token (`T#1s..`, never seen,
        // but a statement may not end in '.').
        while (pos > start && text[pos - 1] == '.')
          --pos;
        return make(type, start);
      }
    }
    // `r REF= x` (CODESYS's and TwinCAT's reference binding), not `=>`.
    if (word.equals_insensitive("REF") && peek(0) == '=' && peek(1) != '>') {
      ++pos;
      return make(P::REF_ASSIGN, start);
    }
    // `x S= c`, `x R= c` (CODESYS's set and reset assignments): only right
    // after a variable, where a name cannot follow; `IF S=1` compares S.
    if ((word.equals_insensitive("S") || word.equals_insensitive("R")) &&
        peek(0) == '=' && peek(1) != '>' && endsVariable(lastType)) {
      ++pos;
      return make(word.equals_insensitive("S") ? P::SET_ASSIGN
                                               : P::RESET_ASSIGN,
                  start);
    }
    if (size_t kw = keywordType(word))
      return make(kw, start);
    return make(P::IDENT, start);
  }

  if (std::isdigit(static_cast<unsigned char>(c))) {
    lexBasedOrDecimal();
    if (peek(0) == '#') {
      // Based integer 2#1010, 8#17, 16#FF.
      ++pos;
      size_t digits = pos;
      while (pos < text.size() &&
             (std::isxdigit(static_cast<unsigned char>(text[pos])) ||
              text[pos] == '_'))
        ++pos;
      if (pos == digits)
        return fail(start, "based integer literal without digits");
      return make(P::INTEGER, start);
    }
    bool isReal = false;
    if (peek(0) == '.' && std::isdigit(static_cast<unsigned char>(peek(1)))) {
      isReal = true;
      ++pos;
      lexBasedOrDecimal();
    }
    if ((peek(0) == 'e' || peek(0) == 'E') &&
        (std::isdigit(static_cast<unsigned char>(peek(1))) ||
         ((peek(1) == '+' || peek(1) == '-') &&
          std::isdigit(static_cast<unsigned char>(peek(2)))))) {
      isReal = true;
      pos += 2;
      lexBasedOrDecimal();
    }
    return make(isReal ? P::REAL_LIT : P::INTEGER, start);
  }

  switch (c) {
  case '\n': {
    ++pos;
    auto tok = make(P::EOL, start);
    ++line;
    lineStart = pos;
    return tok;
  }
  case '\'':
  case '"': {
    ++pos;
    while (pos < text.size() && text[pos] != c && text[pos] != '\n') {
      if (text[pos] == '$' && pos + 1 < text.size())
        ++pos;
      ++pos;
    }
    if (pos >= text.size() || text[pos] != c)
      return fail(start, "unterminated string literal");
    ++pos;
    return make(c == '\'' ? P::STRING_LIT : P::WSTRING_LIT, start);
  }
  case '{': {
    if (peek(1) == '{') {
      // matiec's embedded C: one token, so that a POU holding it is refused
      // only where a translation uses it (OpenPLC prefixes every program
      // with a LOGGER block written in C).
      size_t end = text.find("}}", pos + 2);
      if (end == StringRef::npos)
        return fail(start, "unterminated embedded C code '{{'");
      newlinesIn(pos, end);
      pos = end + 2;
      return make(P::EMBEDDED_C, start);
    }
    size_t end = text.find('}', pos);
    if (end == StringRef::npos)
      return fail(start, "unterminated pragma '{'");
    newlinesIn(pos, end);
    pos = end + 1;
    return make(P::STRING_LIT, start, kPragmaChannel);
  }
  case '%': {
    ++pos;
    while (pos < text.size() &&
           (isIdentChar(text[pos]) || text[pos] == '*' ||
            (text[pos] == '.' &&
             std::isdigit(static_cast<unsigned char>(peek(1))))))
      ++pos;
    if (pos == start + 1)
      return fail(start, "'%' must start a direct address such as %IX0.0");
    return make(P::DIRECT, start);
  }
  case ':':
    ++pos;
    if (peek(0) == '=') {
      ++pos;
      return make(P::ASSIGN, start);
    }
    return make(P::COLON, start);
  case '=':
    ++pos;
    if (peek(0) == '>') {
      ++pos;
      return make(P::OUTPUT_ASSIGN, start);
    }
    return make(P::EQ, start);
  case '?':
    if (peek(1) == '=') {
      pos += 2;
      return make(P::ATTEMPT_ASSIGN, start);
    }
    break;
  case '<':
    ++pos;
    if (peek(0) == '=') {
      ++pos;
      return make(P::LE, start);
    }
    if (peek(0) == '>') {
      ++pos;
      return make(P::NE, start);
    }
    return make(P::LT, start);
  case '>':
    ++pos;
    if (peek(0) == '=') {
      ++pos;
      return make(P::GE, start);
    }
    return make(P::GT, start);
  case '*':
    ++pos;
    if (peek(0) == '*') {
      ++pos;
      return make(P::POWER, start);
    }
    return make(P::STAR, start);
  case '.':
    ++pos;
    if (peek(0) == '.') {
      ++pos;
      return make(P::DOTDOT, start);
    }
    return make(P::DOT, start);
  case '+':
    ++pos;
    return make(P::PLUS, start);
  case '-':
    ++pos;
    return make(P::MINUS, start);
  case '/':
    ++pos;
    return make(P::SLASH, start);
  case '&':
    ++pos;
    return make(P::AMP, start);
  case '^':
    ++pos;
    return make(P::CARET, start);
  case '(':
    ++pos;
    return make(P::LPAREN, start);
  case ')':
    ++pos;
    return make(P::RPAREN, start);
  case '[':
    ++pos;
    return make(P::LBRACKET, start);
  case ']':
    ++pos;
    return make(P::RBRACKET, start);
  case ',':
    ++pos;
    return make(P::COMMA, start);
  case ';':
    ++pos;
    return make(P::SEMI, start);
  case '#':
    ++pos;
    return make(P::HASH, start);
  default:
    break;
  }
  if (static_cast<unsigned char>(c) >= 0x80)
    return fail(start, "non-ASCII character outside a string or comment");
  return fail(start,
              llvm::Twine("unexpected character '") + llvm::Twine(c) + "'");
}

bool st::hideTokens(antlr4::BufferedTokenStream &tokens, size_t begin,
                    size_t end) {
  bool hidden = false;
  for (size_t i = begin; i < end && i < tokens.size(); ++i) {
    auto *t = dynamic_cast<antlr4::WritableToken *>(tokens.get(i));
    if (t && t->getType() != antlr4::Token::EOF &&
        t->getChannel() == antlr4::Token::DEFAULT_CHANNEL) {
      t->setChannel(antlr4::Token::HIDDEN_CHANNEL);
      hidden = true;
    }
  }
  return hidden;
}

std::optional<std::string> st::refusedBodyPragma(StringRef pragma) {
  StringRef body = pragma.drop_front().drop_back().trim();
  StringRef word = body.take_while([](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
  });
  for (const char *harmless :
       {"attribute", "warning", "info", "text", "region", "endregion",
        "messageguid", "library", "flag", "bitaccess", "parameterinfo"})
    if (word.equals_insensitive(harmless))
      return std::nullopt;
  for (const char *conditional :
       {"IF", "ELSIF", "ELSE", "END_IF", "define", "undefine"})
    if (word.equals_insensitive(conditional))
      return "conditional compilation '" + pragma.str() +
             "' is not supported (it would choose the statements translated)";
  if (word.equals_insensitive("error"))
    return "pragma '" + pragma.str() +
           "' makes the program's own compiler stop with an error";
  return "pragma '" + pragma.str() +
         "' inside a body is not supported: matiec copies it into the C code "
         "it generates, which cannot be modelled";
}
