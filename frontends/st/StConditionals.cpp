//===- StConditionals.cpp - CODESYS conditional compilation ---------------===//
#include "frontends/st/StConditionals.h"
#include "frontends/st/StLexer.h"

#include "llvm/ADT/StringExtras.h"

#include <cctype>
#include <vector>

using namespace netlift;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

/// A condition's words: names, strings, and the punctuation ( ) , :.
struct Cursor {
  StringRef rest;
  void skipSpace() { rest = rest.ltrim(); }
  bool eat(char c) {
    skipSpace();
    if (!rest.empty() && rest.front() == c) {
      rest = rest.drop_front();
      return true;
    }
    return false;
  }
  StringRef word() {
    skipSpace();
    StringRef w = rest.take_while([](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' ||
             c == '.';
    });
    rest = rest.drop_front(w.size());
    return w;
  }
  bool eatWord(StringRef keyword) {
    skipSpace();
    StringRef save = rest;
    if (word().equals_insensitive(keyword))
      return true;
    rest = save;
    return false;
  }
  std::optional<std::string> quoted() {
    skipSpace();
    if (rest.empty() || (rest.front() != '\'' && rest.front() != '"'))
      return std::nullopt;
    char q = rest.front();
    size_t end = rest.find(q, 1);
    if (end == StringRef::npos)
      return std::nullopt;
    std::string s = rest.substr(1, end - 1).str();
    rest = rest.drop_front(end + 1);
    return s;
  }
};

/// Evaluates a condition: OR of ANDs of [NOT] defined(NAME), hasvalue(NAME,
/// 'v') or a parenthesised condition. `error` is set when it cannot.
class Condition {
public:
  Condition(StringRef text, const st::Defines &defines)
      : c{text}, defines(defines) {}
  bool evaluate() {
    bool v = disjunction();
    c.skipSpace();
    if (error.empty() && !c.rest.empty())
      error = "unexpected '" + c.rest.str() + "'";
    return v;
  }
  std::string error;

private:
  bool disjunction() {
    bool v = conjunction();
    while (error.empty() && c.eatWord("OR"))
      v = conjunction() || v;
    return v;
  }
  bool conjunction() {
    bool v = factor();
    while (error.empty() && c.eatWord("AND"))
      v = factor() && v;
    return v;
  }
  bool factor() {
    if (c.eatWord("NOT"))
      return !factor();
    if (c.eat('(')) {
      bool v = disjunction();
      if (!c.eat(')'))
        fail("expected ')'");
      return v;
    }
    StringRef fn = c.word();
    if (fn.empty()) {
      fail("expected defined(NAME) or hasvalue(NAME, 'value')");
      return false;
    }
    if (!c.eat('(')) {
      fail("expected '(' after '" + fn.str() + "'");
      return false;
    }
    std::string call = fn.lower();
    if (call == "defined") {
      StringRef name = c.word();
      if (c.eat(':')) {
        // defined(variable: x), defined(type: T), defined(pou: P): about the
        // program's own declarations, which the preprocessor does not see.
        fail("'defined(" + name.str() +
             ": ...)' is not evaluated (netlift decides only names given with "
             "-D, a project's compiler defines or {define})");
        return false;
      }
      if (name.empty() || !c.eat(')')) {
        fail("expected defined(NAME)");
        return false;
      }
      return defines.count(name.upper());
    }
    if (call == "hasvalue") {
      StringRef name = c.word();
      std::optional<std::string> value;
      if (!c.eat(',') || !(value = c.quoted()) || !c.eat(')')) {
        fail("expected hasvalue(NAME, 'value')");
        return false;
      }
      auto it = defines.find(name.upper());
      return it != defines.end() && it->second == *value;
    }
    fail("condition '" + fn.str() +
         "(...)' is not evaluated (it asks about the program's own types, "
         "attributes or constants; netlift decides defined(NAME) and "
         "hasvalue(NAME, 'value'))");
    return false;
  }
  void fail(std::string why) {
    if (error.empty())
      error = std::move(why);
  }
  Cursor c;
  const st::Defines &defines;
};

struct Branch {
  bool outerActive; // the text around the IF is translated
  bool taken;       // a branch of this IF was taken
  bool active;      // the current branch is translated
  SMLoc at;
};

} // namespace

std::optional<std::string> st::resolveConditionals(StringRef text,
                                                   DiagEngine &diag,
                                                   Defines defines,
                                                   bool &changed) {
  changed = false;
  // Most files have no directive: a scan for `{IF`, `{define`... (any
  // case, spaces allowed) spares them a second lexing.
  bool maybe = false;
  for (size_t at = text.find('{'); at != StringRef::npos && !maybe;
       at = text.find('{', at + 1)) {
    StringRef word = text.substr(at + 1).ltrim().take_while([](char ch) {
      return std::isalpha(static_cast<unsigned char>(ch)) || ch == '_';
    });
    for (const char *d :
         {"IF", "ELSIF", "ELSE", "END_IF", "define", "undefine"})
      maybe |= word.equals_insensitive(d);
  }
  if (!maybe)
    return text.str();
  // The directives: pragma tokens found by the lexer (not in comments or
  // strings).
  struct Directive {
    size_t begin, end;
    std::string word;
    StringRef rest;
  };
  std::vector<Directive> directives;
  {
    llvm::SourceMgr scratch;
    DiagEngine quiet(scratch);
    StLexer lexer(text, quiet);
    lexer.setSilent();
    for (;;) {
      auto t = lexer.nextToken();
      if (t->getType() == antlr4::Token::EOF)
        break;
      if (t->getChannel() != kPragmaChannel)
        continue;
      size_t begin = t->getStartIndex(), end = t->getStopIndex() + 1;
      StringRef body = text.substr(begin, end - begin);
      body = body.drop_front().drop_back().trim();
      StringRef word = body.take_while([](char ch) {
        return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
      });
      std::string w = word.upper();
      if (w == "IF" || w == "ELSIF" || w == "ELSE" || w == "END_IF" ||
          w == "DEFINE" || w == "UNDEFINE")
        directives.push_back({begin, end, w, body.drop_front(word.size())});
    }
  }
  if (directives.empty())
    return text.str();
  changed = true;
  std::string out = text.str();
  auto blank = [&](size_t from, size_t to) {
    for (size_t i = from; i < to; ++i)
      if (out[i] != '\n' && out[i] != '\r')
        out[i] = ' ';
  };
  std::vector<Branch> open;
  auto active = [&] { return open.empty() || open.back().active; };
  size_t cursor = 0;
  for (const Directive &d : directives) {
    SMLoc at = SMLoc::getFromPointer(text.data() + d.begin);
    if (!active())
      blank(cursor, d.begin);
    blank(d.begin, d.end);
    cursor = d.end;
    auto decide = [&](bool &value) {
      Condition cond(d.rest, defines);
      value = cond.evaluate();
      if (!cond.error.empty()) {
        diag.error(at,
                   "conditional compilation '{" +
                       text.substr(d.begin + 1, d.end - d.begin - 2).trim() +
                       "}': " + cond.error);
        return false;
      }
      return true;
    };
    if (d.word == "IF") {
      bool outer = active(), v = false;
      if (outer && !decide(v))
        return std::nullopt;
      open.push_back({outer, outer && v, outer && v, at});
    } else if (d.word == "ELSIF" || d.word == "ELSE") {
      if (open.empty()) {
        diag.error(at, "{" + d.word + "} without {IF}");
        return std::nullopt;
      }
      Branch &b = open.back();
      bool v = d.word == "ELSE";
      if (b.outerActive && !b.taken && !v && !decide(v))
        return std::nullopt;
      b.active = b.outerActive && !b.taken && v;
      b.taken |= b.active;
    } else if (d.word == "END_IF") {
      if (open.empty()) {
        diag.error(at, "{END_IF} without {IF}");
        return std::nullopt;
      }
      open.pop_back();
    } else if (active()) { // {define NAME [value]}, {undefine NAME}
      Cursor c{d.rest};
      StringRef name = c.word();
      if (name.empty()) {
        diag.error(at,
                   "{" + llvm::StringRef(d.word).lower() + "} needs a name");
        return std::nullopt;
      }
      if (d.word == "DEFINE")
        defines[name.upper()] = c.rest.trim().str();
      else
        defines.erase(name.upper());
    }
  }
  if (!open.empty()) {
    diag.error(open.back().at, "{IF} without {END_IF}");
    return std::nullopt;
  }
  return out;
}
