//===- Ctl.cpp - CTL properties and their explicit-state checking ---------===//
#include "backends/checkers/Ctl.h"

#include "ir/net/Parser.h"
#include "ir/net/Verifier.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"

#include <deque>

using namespace netlift;
using namespace netlift::checkers;
using llvm::StringRef;

namespace {

struct Token {
  enum Kind { Word, Number, Punct, End } kind;
  StringRef text;
  size_t offset;
};

std::vector<Token> tokenize(StringRef s, size_t &bad) {
  std::vector<Token> out;
  bad = StringRef::npos;
  size_t i = 0;
  static const char *const two[] = {"->", "==", "!=", "<=", ">=", "<<", ">>"};
  while (i < s.size()) {
    char c = s[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      ++i;
      continue;
    }
    size_t start = i;
    if (llvm::isAlpha(c) || c == '_') {
      // Qualified names (`c.step`) and enumerators (`Mode#AUTO`).
      while (i < s.size() &&
             (llvm::isAlnum(s[i]) || s[i] == '_' || s[i] == '.' || s[i] == '#'))
        ++i;
      out.push_back({Token::Word, s.slice(start, i), start});
      continue;
    }
    if (llvm::isDigit(c)) {
      while (i < s.size() && llvm::isAlnum(s[i]))
        ++i;
      out.push_back({Token::Number, s.slice(start, i), start});
      continue;
    }
    bool matched = false;
    for (const char *t : two)
      if (s.substr(i).startswith(t)) {
        out.push_back({Token::Punct, s.substr(i, 2), start});
        i += 2;
        matched = true;
        break;
      }
    if (matched)
      continue;
    if (StringRef("()[]!&|<>+-*/%~^,?:").contains(c)) {
      out.push_back({Token::Punct, s.substr(i, 1), start});
      ++i;
      continue;
    }
    bad = i;
    return out;
  }
  out.push_back({Token::End, StringRef(), s.size()});
  return out;
}

bool isTemporal(StringRef w) {
  return w == "AG" || w == "AF" || w == "EG" || w == "EF" || w == "AX" ||
         w == "EX";
}

class CtlParser {
public:
  CtlParser(unsigned bufferID, DiagEngine &diag, net::Design &design,
            net::Module &top)
      : id(bufferID), diag(diag), design(design), top(top),
        text(diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer()) {}

  std::unique_ptr<CtlFormula> parse() {
    size_t bad;
    toks = tokenize(text, bad);
    if (bad != StringRef::npos)
      return fail(bad, "unexpected character '" + text.substr(bad, 1) +
                           "' in the property" +
                           (text[bad] == '=' ? "; use == to compare" : ""));
    auto f = implies();
    if (f && peek().kind != Token::End)
      return fail(peek().offset, "expected the end of the property, found '" +
                                     peek().text + "'");
    if (f)
      f->loc = llvm::SMLoc::getFromPointer(text.data());
    return f;
  }

private:
  using F = std::unique_ptr<CtlFormula>;
  const Token &peek() const { return toks[pos]; }
  bool isPunct(StringRef p) const {
    return peek().kind == Token::Punct && peek().text == p;
  }
  bool isWord(StringRef w) const {
    return peek().kind == Token::Word && peek().text == w;
  }
  F fail(size_t offset, const llvm::Twine &msg) {
    if (!failed)
      diag.error(llvm::SMLoc::getFromPointer(text.data() + offset), msg);
    failed = true;
    return nullptr;
  }
  static F make(CtlFormula::Kind k, F a = nullptr, F b = nullptr) {
    auto f = std::make_unique<CtlFormula>();
    f->kind = k;
    f->lhs = std::move(a);
    f->rhs = std::move(b);
    return f;
  }

  F implies() {
    F a = disjunction();
    if (a && isPunct("->")) {
      ++pos;
      F b = implies();
      if (!b)
        return nullptr;
      return make(CtlFormula::Implies, std::move(a), std::move(b));
    }
    return a;
  }
  F disjunction() {
    F a = conjunction();
    while (a && (isPunct("|") || isWord("or"))) {
      ++pos;
      F b = conjunction();
      if (!b)
        return nullptr;
      a = make(CtlFormula::Or, std::move(a), std::move(b));
    }
    return a;
  }
  F conjunction() {
    F a = unary();
    while (a && (isPunct("&") || isWord("and"))) {
      ++pos;
      F b = unary();
      if (!b)
        return nullptr;
      a = make(CtlFormula::And, std::move(a), std::move(b));
    }
    return a;
  }
  F unary() {
    const Token &t = peek();
    if (t.kind == Token::End)
      return fail(t.offset, "expected a formula at the end of the property");
    if (isPunct("!") || isWord("not")) {
      ++pos;
      F a = unary();
      if (!a)
        return nullptr;
      return make(CtlFormula::Not, std::move(a));
    }
    if (t.kind == Token::Word && isTemporal(t.text)) {
      static const std::pair<StringRef, CtlFormula::Kind> ops[] = {
          {"AG", CtlFormula::AG}, {"AF", CtlFormula::AF},
          {"EG", CtlFormula::EG}, {"EF", CtlFormula::EF},
          {"AX", CtlFormula::AX}, {"EX", CtlFormula::EX}};
      CtlFormula::Kind k = CtlFormula::AG;
      for (auto [w, kind] : ops)
        if (t.text == w)
          k = kind;
      ++pos;
      F a = unary();
      if (!a)
        return nullptr;
      return make(k, std::move(a));
    }
    if ((isWord("A") || isWord("E")) && toks[pos + 1].kind == Token::Punct &&
        toks[pos + 1].text == "[") {
      bool all = isWord("A");
      pos += 2;
      F a = implies();
      if (!a)
        return nullptr;
      if (!isWord("U"))
        return fail(peek().offset, "expected 'U' in " +
                                       llvm::Twine(all ? "A" : "E") +
                                       "[f U g]");
      ++pos;
      F b = implies();
      if (!b)
        return nullptr;
      if (!isPunct("]"))
        return fail(peek().offset, "expected ']' to close " +
                                       llvm::Twine(all ? "A" : "E") +
                                       "[f U g]");
      ++pos;
      return make(all ? CtlFormula::AU : CtlFormula::EU, std::move(a),
                  std::move(b));
    }
    if (isWord("true") || isWord("false") || isWord("deadlock")) {
      CtlFormula::Kind k = isWord("true")    ? CtlFormula::True
                           : isWord("false") ? CtlFormula::False
                                             : CtlFormula::Deadlock;
      ++pos;
      return make(k);
    }
    if (isPunct("(")) {
      // A parenthesised formula, unless the parenthesis starts an
      // arithmetic comparison such as `(a + 1) >= b`: look past the
      // matching ')'.
      size_t k = pos, depth = 0;
      for (; toks[k].kind != Token::End; ++k) {
        if (toks[k].kind != Token::Punct)
          continue;
        if (toks[k].text == "(")
          ++depth;
        else if (toks[k].text == ")" && --depth == 0)
          break;
      }
      static const StringRef arith[] = {
          "==", "!=", "<", "<=", ">", ">=", "+", "-", "*", "/", "%"};
      bool comparison = false;
      if (toks[k].kind != Token::End)
        for (StringRef op : arith)
          comparison = comparison || (toks[k + 1].kind == Token::Punct &&
                                      toks[k + 1].text == op);
      if (!comparison) {
        ++pos;
        F a = implies();
        if (!a)
          return nullptr;
        if (!isPunct(")"))
          return fail(peek().offset, "expected ')', found " +
                                         (peek().kind == Token::End
                                              ? std::string("the end")
                                              : "'" + peek().text.str() + "'"));
        ++pos;
        return a;
      }
    }
    return atom();
  }

  /// The longest run of tokens up to a connective of the property
  /// language at bracket depth 0, parsed as a NetIR predicate in place
  /// (the rest of the formula blanked, so locations stay right).
  F atom() {
    size_t first = pos;
    int depth = 0;
    for (;; ++pos) {
      const Token &t = peek();
      if (t.kind == Token::End)
        break;
      if (t.kind == Token::Punct && (t.text == "(" || t.text == "["))
        ++depth;
      if (t.kind == Token::Punct && (t.text == ")" || t.text == "]")) {
        if (depth == 0)
          break;
        --depth;
      }
      if (depth == 0 &&
          ((t.kind == Token::Punct && (t.text == "&" || t.text == "|" ||
                                       t.text == "->" || t.text == "!")) ||
           (t.kind == Token::Word &&
            (t.text == "and" || t.text == "or" || t.text == "U" ||
             t.text == "not" || isTemporal(t.text)))))
        break;
    }
    if (pos == first)
      return fail(peek().offset,
                  "expected a formula, found '" + peek().text + "'");
    size_t begin = toks[first].offset;
    size_t end = toks[pos - 1].offset + toks[pos - 1].text.size();
    std::string blanked(text.size(), ' ');
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n')
        blanked[i] = '\n';
    std::copy(text.begin() + begin, text.begin() + end,
              blanked.begin() + begin);
    std::string name =
        diag.sourceMgr().getMemoryBuffer(id)->getBufferIdentifier().str();
    unsigned atomID = diag.sourceMgr().AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(blanked, name), llvm::SMLoc());
    net::Expr *e = net::parseExpression(atomID, diag, design);
    if (!e || !net::verifyPredicate(design, top, e, diag)) {
      failed = true;
      return nullptr;
    }
    F f = make(CtlFormula::Atom);
    f->atom = e;
    f->atomText = text.slice(begin, end).str();
    return f;
  }

  unsigned id;
  DiagEngine &diag;
  net::Design &design;
  net::Module &top;
  StringRef text;
  std::vector<Token> toks;
  size_t pos = 0;
  bool failed = false;
};

} // namespace

std::unique_ptr<CtlFormula> checkers::parseCtl(unsigned bufferID,
                                               DiagEngine &diag,
                                               net::Design &design,
                                               net::Module &top) {
  return CtlParser(bufferID, diag, design, top).parse();
}

bool checkers::isStateProposition(const CtlFormula &f, bool deadlockIsState) {
  switch (f.kind) {
  case CtlFormula::True:
  case CtlFormula::False:
  case CtlFormula::Atom:
    return true;
  case CtlFormula::Deadlock:
    return deadlockIsState;
  case CtlFormula::Not:
    return isStateProposition(*f.lhs, deadlockIsState);
  case CtlFormula::And:
  case CtlFormula::Or:
  case CtlFormula::Implies:
    return isStateProposition(*f.lhs, deadlockIsState) &&
           isStateProposition(*f.rhs, deadlockIsState);
  default:
    return false;
  }
}

std::string checkers::ctlToString(const CtlFormula &f) {
  auto sub = [](const CtlFormula &g) {
    bool simple = g.kind == CtlFormula::Atom || g.kind == CtlFormula::True ||
                  g.kind == CtlFormula::False || g.kind == CtlFormula::Deadlock;
    return simple ? ctlToString(g) : "(" + ctlToString(g) + ")";
  };
  switch (f.kind) {
  case CtlFormula::True:
    return "true";
  case CtlFormula::False:
    return "false";
  case CtlFormula::Deadlock:
    return "deadlock";
  case CtlFormula::Atom:
    return f.atomText;
  case CtlFormula::Not:
    return "!" + sub(*f.lhs);
  case CtlFormula::And:
    return sub(*f.lhs) + " & " + sub(*f.rhs);
  case CtlFormula::Or:
    return sub(*f.lhs) + " | " + sub(*f.rhs);
  case CtlFormula::Implies:
    return sub(*f.lhs) + " -> " + sub(*f.rhs);
  case CtlFormula::EX:
    return "EX " + sub(*f.lhs);
  case CtlFormula::AX:
    return "AX " + sub(*f.lhs);
  case CtlFormula::EF:
    return "EF " + sub(*f.lhs);
  case CtlFormula::AF:
    return "AF " + sub(*f.lhs);
  case CtlFormula::EG:
    return "EG " + sub(*f.lhs);
  case CtlFormula::AG:
    return "AG " + sub(*f.lhs);
  case CtlFormula::EU:
    return "E[" + ctlToString(*f.lhs) + " U " + ctlToString(*f.rhs) + "]";
  case CtlFormula::AU:
    return "A[" + ctlToString(*f.lhs) + " U " + ctlToString(*f.rhs) + "]";
  }
  return "";
}

namespace {
using Set = std::vector<uint8_t>;

/// Successors with deadlocks looping on themselves; predecessors likewise.
struct Evaluator {
  const CtlGraph &g;
  const std::function<bool(const net::Expr *, uint32_t)> &atomValue;
  std::vector<uint32_t> predStart, pred;

  template <typename Fn> void forSucc(uint32_t s, Fn fn) const {
    if (g.deadlock[s]) {
      fn(s);
      return;
    }
    for (uint32_t k = g.succStart[s]; k < g.succStart[s + 1]; ++k)
      fn(g.succ[k]);
  }
  void buildPredecessors() {
    size_t n = g.size();
    std::vector<uint32_t> count(n + 1, 0);
    for (uint32_t s = 0; s < n; ++s)
      forSucc(s, [&](uint32_t t) { ++count[t + 1]; });
    for (size_t i = 0; i < n; ++i)
      count[i + 1] += count[i];
    predStart = count;
    pred.resize(count[n]);
    for (uint32_t s = 0; s < n; ++s)
      forSucc(s, [&](uint32_t t) { pred[count[t]++] = s; });
  }
  size_t outDegree(uint32_t s) const {
    return g.deadlock[s] ? 1 : g.succStart[s + 1] - g.succStart[s];
  }

  Set negate(Set a) const {
    for (uint8_t &x : a)
      x = !x;
    return a;
  }
  Set ex(const Set &a) const {
    Set r(g.size(), 0);
    for (uint32_t s = 0; s < g.size(); ++s)
      forSucc(s, [&](uint32_t t) { r[s] |= a[t]; });
    return r;
  }
  /// E[a U b]: backwards from b through a.
  Set eu(const Set &a, const Set &b) const {
    Set r = b;
    std::deque<uint32_t> work;
    for (uint32_t s = 0; s < g.size(); ++s)
      if (b[s])
        work.push_back(s);
    while (!work.empty()) {
      uint32_t t = work.front();
      work.pop_front();
      for (uint32_t k = predStart[t]; k < predStart[t + 1]; ++k) {
        uint32_t s = pred[k];
        if (!r[s] && a[s]) {
          r[s] = 1;
          work.push_back(s);
        }
      }
    }
    return r;
  }
  /// EG a: the greatest set inside a where every state keeps a successor
  /// in the set.
  Set eg(const Set &a) const {
    Set r = a;
    std::vector<uint32_t> inside(g.size(), 0);
    std::deque<uint32_t> work;
    for (uint32_t s = 0; s < g.size(); ++s) {
      if (!r[s])
        continue;
      forSucc(s, [&](uint32_t t) { inside[s] += r[t]; });
      if (inside[s] == 0)
        work.push_back(s);
    }
    while (!work.empty()) {
      uint32_t t = work.front();
      work.pop_front();
      if (!r[t])
        continue;
      r[t] = 0;
      for (uint32_t k = predStart[t]; k < predStart[t + 1]; ++k) {
        uint32_t s = pred[k];
        if (r[s] && --inside[s] == 0)
          work.push_back(s);
      }
    }
    return r;
  }

  Set eval(const CtlFormula &f) {
    size_t n = g.size();
    switch (f.kind) {
    case CtlFormula::True:
      return Set(n, 1);
    case CtlFormula::False:
      return Set(n, 0);
    case CtlFormula::Deadlock:
      return g.deadlock;
    case CtlFormula::Atom: {
      Set r(n, 0);
      for (uint32_t s = 0; s < n; ++s)
        r[s] = atomValue(f.atom, s);
      return r;
    }
    case CtlFormula::Not:
      return negate(eval(*f.lhs));
    case CtlFormula::And:
    case CtlFormula::Or:
    case CtlFormula::Implies: {
      Set a = eval(*f.lhs), b = eval(*f.rhs);
      for (size_t s = 0; s < n; ++s)
        a[s] = f.kind == CtlFormula::And  ? (a[s] && b[s])
               : f.kind == CtlFormula::Or ? (a[s] || b[s])
                                          : (!a[s] || b[s]);
      return a;
    }
    case CtlFormula::EX:
      return ex(eval(*f.lhs));
    case CtlFormula::AX:
      return negate(ex(negate(eval(*f.lhs))));
    case CtlFormula::EF:
      return eu(Set(n, 1), eval(*f.lhs));
    case CtlFormula::AF:
      return negate(eg(negate(eval(*f.lhs))));
    case CtlFormula::EG:
      return eg(eval(*f.lhs));
    case CtlFormula::AG:
      return negate(eu(Set(n, 1), negate(eval(*f.lhs))));
    case CtlFormula::EU:
      return eu(eval(*f.lhs), eval(*f.rhs));
    case CtlFormula::AU: {
      // A[a U b] = !(E[!b U (!a & !b)] | EG !b)
      Set a = eval(*f.lhs), b = eval(*f.rhs);
      Set nb = negate(b), both(n, 0);
      for (size_t s = 0; s < n; ++s)
        both[s] = !a[s] && !b[s];
      Set bad = eu(nb, both), stuck = eg(nb);
      Set r(n, 0);
      for (size_t s = 0; s < n; ++s)
        r[s] = !(bad[s] || stuck[s]);
      return r;
    }
    }
    return Set(n, 0);
  }
};
} // namespace

std::vector<uint8_t> checkers::evaluateCtl(
    const CtlFormula &f, const CtlGraph &g,
    const std::function<bool(const net::Expr *, uint32_t)> &atomValue) {
  Evaluator e{g, atomValue, {}, {}};
  e.buildPredecessors();
  return e.eval(f);
}

namespace {
/// Shortest path from state 0 through states in `through` to a state in
/// `goal` (breadth-first, deadlocks looping on themselves).
std::vector<uint32_t> shortestPath(const Evaluator &e, const Set &through,
                                   const Set &goal) {
  size_t n = e.g.size();
  std::vector<uint32_t> parent(n, UINT32_MAX);
  std::deque<uint32_t> work{0};
  parent[0] = 0;
  while (!work.empty()) {
    uint32_t s = work.front();
    work.pop_front();
    if (goal[s]) {
      std::vector<uint32_t> path{s};
      while (path.back() != 0)
        path.push_back(parent[path.back()]);
      return {path.rbegin(), path.rend()};
    }
    if (!through[s])
      continue;
    e.forSucc(s, [&](uint32_t t) {
      if (parent[t] == UINT32_MAX) {
        parent[t] = s;
        work.push_back(t);
      }
    });
  }
  return {};
}

/// A run from state 0 that stays in `inside` (where EG holds, so every
/// state there keeps a successor inside): followed until it comes back to
/// a state of its own (a lasso) or reaches a deadlock.
CtlTrace lasso(const Evaluator &e, const Set &inside) {
  CtlTrace t;
  std::vector<int64_t> index(e.g.size(), -1);
  uint32_t s = 0;
  for (;;) {
    index[s] = int64_t(t.states.size());
    t.states.push_back(s);
    if (e.g.deadlock[s])
      return t;
    uint32_t next = UINT32_MAX;
    e.forSucc(s, [&](uint32_t x) {
      if (next == UINT32_MAX && inside[x])
        next = x;
    });
    if (index[next] >= 0) {
      t.loopTo = index[next];
      return t;
    }
    s = next;
  }
}
} // namespace

std::optional<CtlTrace> checkers::ctlTrace(
    const CtlFormula &f, const CtlGraph &g,
    const std::function<bool(const net::Expr *, uint32_t)> &atomValue) {
  Evaluator e{g, atomValue, {}, {}};
  e.buildPredecessors();
  size_t n = g.size();
  Set all(n, 1);
  auto path = [&](bool witness, std::string claim, std::vector<uint32_t> p) {
    CtlTrace t;
    t.witness = witness;
    t.claim = std::move(claim);
    t.states = std::move(p);
    return std::optional<CtlTrace>(std::move(t));
  };
  auto run = [&](bool witness, std::string claim, const Set &inside) {
    CtlTrace t = lasso(e, inside);
    t.witness = witness;
    t.claim = std::move(claim);
    return std::optional<CtlTrace>(std::move(t));
  };
  bool holds = e.eval(f)[0];
  std::string a = f.lhs ? ctlToString(*f.lhs) : "";
  std::string b = f.rhs ? ctlToString(*f.rhs) : "";
  // EX and EF have a witness when they hold; AX and AG a counterexample
  // when they fail, which reaches where the operand fails.
  auto goalOf = [&](bool exists) {
    Set goal = e.eval(*f.lhs);
    return exists ? goal : e.negate(goal);
  };
  switch (f.kind) {
  case CtlFormula::EX:
  case CtlFormula::AX: {
    bool exists = f.kind == CtlFormula::EX;
    if (holds != exists)
      return std::nullopt;
    Set goal = goalOf(exists);
    uint32_t next = UINT32_MAX;
    e.forSucc(0, [&](uint32_t t) {
      if (next == UINT32_MAX && goal[t])
        next = t;
    });
    return path(
        exists, "a next state where " + a + (exists ? " holds" : " fails"),
        next == 0 ? std::vector<uint32_t>{0} : std::vector<uint32_t>{0, next});
  }
  case CtlFormula::EF:
  case CtlFormula::AG: {
    bool exists = f.kind == CtlFormula::EF;
    if (holds != exists)
      return std::nullopt;
    Set goal = goalOf(exists);
    return path(exists,
                "a shortest path to a state where " + a +
                    (exists ? " holds" : " does not hold"),
                shortestPath(e, all, goal));
  }
  case CtlFormula::EG:
    if (!holds)
      return std::nullopt;
    return run(true, "a run where " + a + " holds forever", e.eval(f));
  case CtlFormula::AF: {
    if (holds)
      return std::nullopt;
    Set never = e.eg(e.negate(e.eval(*f.lhs)));
    return run(false, "a run where " + a + " never holds", never);
  }
  case CtlFormula::EU: {
    if (!holds)
      return std::nullopt;
    return path(true,
                "a shortest path where " + a + " holds until " + b + " does",
                shortestPath(e, e.eval(*f.lhs), e.eval(*f.rhs)));
  }
  case CtlFormula::AU: {
    if (holds)
      return std::nullopt;
    // A[a U b] fails: a path through !b to a state with !a & !b, or a run
    // where b never holds.
    Set sa = e.eval(*f.lhs), sb = e.eval(*f.rhs);
    Set nb = e.negate(sb), both(n, 0);
    for (size_t s = 0; s < n; ++s)
      both[s] = !sa[s] && !sb[s];
    if (e.eu(nb, both)[0])
      return path(false,
                  "a shortest path to a state where neither " + a + " nor " +
                      b + " holds, " + b + " not before",
                  shortestPath(e, nb, both));
    return run(false, "a run where " + b + " never holds", e.eg(nb));
  }
  default:
    return std::nullopt;
  }
}
