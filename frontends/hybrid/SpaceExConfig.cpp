//===- SpaceExConfig.cpp - SpaceEx .cfg files -----------------------------===//
//
// The file is `key = value` lines, `#` comments; a value in double quotes
// may span lines. The initial set is a conjunction; each conjunct is a
// location (`loc(inst) == name`) or a bound of one name by a constant
// expression, which may use names the set fixes elsewhere (`-d <= x <= d &
// d == 0.001`): conjuncts are taken in rounds until none can be.
//
//===----------------------------------------------------------------------===//
#include "frontends/hybrid/SpaceExConfig.h"
#include "frontends/hybrid/SpaceExText.h"

#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"

#include <cctype>
#include <cmath>
#include <functional>

using namespace netlift;
using namespace netlift::spaceex;
using llvm::SMLoc;
using llvm::StringRef;

std::optional<double> InitialSet::valueOf(const std::string &name) const {
  auto it = bounds.find(name);
  if (it == bounds.end() || !it->second.lo || !it->second.hi ||
      *it->second.lo != *it->second.hi)
    return std::nullopt;
  return it->second.lo;
}

bool spaceex::namedBy(StringRef flat, StringRef name) {
  return flat == name || (flat.endswith(name) && flat.size() > name.size() &&
                          flat[flat.size() - name.size() - 1] == '.');
}

InitialSet::Bounds *InitialSet::lookup(StringRef flat, std::string *key) {
  Bounds *best = nullptr;
  size_t bestLen = 0;
  for (auto &[name, bd] : bounds)
    if (namedBy(flat, name) && name.size() > bestLen) {
      best = &bd;
      bestLen = name.size();
      if (key)
        *key = name;
    }
  return best;
}

namespace {

bool isNameStart(char c) { return std::isalpha((unsigned char)c) || c == '_'; }
bool isNameChar(char c) {
  return std::isalnum((unsigned char)c) || c == '_' || c == '.';
}

bool isName(StringRef s) {
  if (s.empty() || !isNameStart(s[0]))
    return false;
  return llvm::all_of(s, isNameChar);
}

/// A constant expression (+ - * / ^, parentheses, numbers, names the set
/// has fixed); nullopt when it is not one.
class ConstEval {
public:
  ConstEval(StringRef s, const InitialSet &known) : s(s), known(known) {}
  std::optional<double> run() {
    auto v = sum();
    skip();
    if (!v || pos != s.size())
      return std::nullopt;
    return v;
  }

private:
  void skip() {
    while (pos < s.size() && std::isspace((unsigned char)s[pos]))
      ++pos;
  }
  bool eat(char c) {
    skip();
    if (pos < s.size() && s[pos] == c) {
      ++pos;
      return true;
    }
    return false;
  }
  std::optional<double> sum() {
    auto v = product();
    while (v) {
      if (eat('+')) {
        auto r = product();
        v = r ? std::optional<double>(*v + *r) : std::nullopt;
      } else if (eat('-')) {
        auto r = product();
        v = r ? std::optional<double>(*v - *r) : std::nullopt;
      } else {
        break;
      }
    }
    return v;
  }
  std::optional<double> product() {
    auto v = power();
    while (v) {
      if (eat('*')) {
        auto r = power();
        v = r ? std::optional<double>(*v * *r) : std::nullopt;
      } else if (eat('/')) {
        auto r = power();
        v = r ? std::optional<double>(*v / *r) : std::nullopt;
      } else {
        break;
      }
    }
    return v;
  }
  std::optional<double> power() {
    auto v = unary();
    if (v && eat('^')) {
      auto e = unary();
      return e ? std::optional<double>(std::pow(*v, *e)) : std::nullopt;
    }
    return v;
  }
  std::optional<double> unary() {
    if (eat('-')) {
      auto v = unary();
      return v ? std::optional<double>(-*v) : std::nullopt;
    }
    if (eat('+'))
      return unary();
    return primary();
  }
  std::optional<double> primary() {
    skip();
    if (eat('(')) {
      auto v = sum();
      return v && eat(')') ? v : std::nullopt;
    }
    size_t start = pos;
    if (pos < s.size() &&
        (std::isdigit((unsigned char)s[pos]) || s[pos] == '.')) {
      while (pos < s.size() &&
             (std::isdigit((unsigned char)s[pos]) || s[pos] == '.' ||
              s[pos] == 'e' || s[pos] == 'E' ||
              ((s[pos] == '-' || s[pos] == '+') &&
               (s[pos - 1] == 'e' || s[pos - 1] == 'E'))))
        ++pos;
      double v;
      if (s.slice(start, pos).getAsDouble(v))
        return std::nullopt;
      return v;
    }
    if (pos < s.size() && isNameStart(s[pos])) {
      while (pos < s.size() && isNameChar(s[pos]))
        ++pos;
      return known.valueOf(s.slice(start, pos).str());
    }
    return std::nullopt;
  }

  StringRef s;
  const InitialSet &known;
  size_t pos = 0;
};

/// Does `c` hold `ch` outside parentheses?
bool hasTopLevel(StringRef c, char ch) {
  int depth = 0;
  for (char x : c) {
    depth += x == '(' ? 1 : x == ')' ? -1 : 0;
    if (depth == 0 && x == ch)
      return true;
  }
  return false;
}

/// `(a <= x)` as `a <= x`: parentheses around the whole, removed.
StringRef unparenthesize(StringRef c) {
  while (c.startswith("(") && c.endswith(")")) {
    int depth = 0;
    bool whole = true;
    for (size_t i = 0; i + 1 < c.size() && whole; ++i) {
      depth += c[i] == '(' ? 1 : c[i] == ')' ? -1 : 0;
      whole = depth > 0;
    }
    if (!whole)
      break;
    c = c.drop_front().drop_back().trim();
  }
  return c;
}

/// `x op c` with the operator at the top level: (lhs, op, rhs); op empty
/// when there is none.
std::tuple<StringRef, StringRef, StringRef> splitComparison(StringRef c) {
  auto ops = comparisonOperators(c, /*singleEquals=*/true);
  if (ops.empty())
    return {c, "", ""};
  auto [at, len] = ops.front();
  return {c.take_front(at).trim(), c.substr(at, len),
          c.substr(at + len).trim()};
}

StringRef flip(StringRef op) {
  if (op == "<=")
    return ">=";
  if (op == ">=")
    return "<=";
  if (op == "<")
    return ">";
  if (op == ">")
    return "<";
  return op;
}

bool splitInitialSet(const ConfigEntry &e, DiagEngine &diag, InitialSet &out) {
  struct Pending {
    StringRef text;
  };
  std::vector<Pending> pending;
  // The conjuncts, through parentheses around conjunctions.
  std::vector<StringRef> flat;
  std::function<void(StringRef)> flatten = [&](StringRef text) {
    for (StringRef c : conjuncts(text)) {
      StringRef inner = unparenthesize(c);
      if (inner.size() != c.size() && hasTopLevel(inner, '&'))
        flatten(inner);
      else
        flat.push_back(inner);
    }
  };
  flatten(e.text);
  for (StringRef chained : flat) {
    if (hasTopLevel(chained, '|')) {
      diag.error(SMLoc::getFromPointer(chained.data()),
                 "initial condition '" + chained +
                     "' is a disjunction; netlift takes an initial set that "
                     "is a conjunction of bounds (one start interval per "
                     "variable)");
      return false;
    }
    for (StringRef one : unchain(chained)) {
      if (one == "true")
        continue;
      if (one.startswith("loc(") || one.startswith("loc (")) {
        size_t open = one.find('('), close = one.find(')');
        auto [lhs, op, rhs] = splitComparison(one.substr(close + 1));
        if (close == StringRef::npos || !lhs.empty() ||
            (op != "==" && op != "=") || !isName(rhs)) {
          diag.error(SMLoc::getFromPointer(one.data()),
                     "initial location '" + one +
                         "' is not loc(instance) == location");
          return false;
        }
        out.locations.push_back({one.slice(open + 1, close).trim().str(),
                                 rhs.str(), SMLoc::getFromPointer(one.data())});
        continue;
      }
      pending.push_back({one});
    }
  }
  // Rounds: a bound whose constant side can be evaluated with the names
  // fixed so far.
  for (bool progress = true; progress && !pending.empty();) {
    progress = false;
    for (size_t i = 0; i < pending.size();) {
      StringRef c = pending[i].text;
      auto [lhs, op, rhs] = splitComparison(c);
      StringRef name;
      std::optional<double> v;
      if (!op.empty() && op != "!=") {
        if (isName(lhs) && (v = ConstEval(rhs, out).run())) {
          name = lhs;
        } else if (isName(rhs) && (v = ConstEval(lhs, out).run())) {
          name = rhs;
          op = flip(op);
        }
      }
      if (name.empty()) {
        ++i;
        continue;
      }
      InitialSet::Bounds &bd = out.bounds[name.str()];
      if (!bd.loc.isValid())
        bd.loc = SMLoc::getFromPointer(c.data());
      if (op != "<=" && op != "<")
        bd.lo = bd.lo ? std::max(*bd.lo, *v) : *v;
      if (op != ">=" && op != ">")
        bd.hi = bd.hi ? std::min(*bd.hi, *v) : *v;
      if (bd.lo && bd.hi && *bd.lo > *bd.hi) {
        diag.error(SMLoc::getFromPointer(c.data()),
                   "the initial set gives '" + name + "' no value ('" + c +
                       "' contradicts an earlier bound)");
        return false;
      }
      pending.erase(pending.begin() + i);
      progress = true;
    }
  }
  if (!pending.empty()) {
    StringRef c = pending.front().text;
    diag.error(SMLoc::getFromPointer(c.data()),
               "initial condition '" + c +
                   "' is not a bound of one variable by a constant (x == c, "
                   "x <= c, a <= x <= b) or loc(instance) == location");
    return false;
  }
  return true;
}

} // namespace

bool spaceex::readConfig(StringRef path, DiagEngine &diag, Config &out) {
  auto buf = llvm::MemoryBuffer::getFile(path);
  if (!buf) {
    diag.error(SMLoc(), "cannot read the SpaceEx configuration '" + path +
                            "': " + buf.getError().message());
    return false;
  }
  llvm::SourceMgr &sm = diag.sourceMgr();
  unsigned id = sm.AddNewSourceBuffer(std::move(*buf), SMLoc());
  StringRef text = sm.getMemoryBuffer(id)->getBuffer();
  size_t pos = 0;
  while (pos < text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == StringRef::npos)
      eol = text.size();
    StringRef line = text.slice(pos, eol);
    StringRef trimmed = line.ltrim();
    if (trimmed.empty() || trimmed.startswith("#") ||
        trimmed.startswith("//")) {
      pos = eol + 1;
      continue;
    }
    size_t eq = trimmed.find('=');
    if (eq == StringRef::npos) {
      diag.error(SMLoc::getFromPointer(trimmed.data()),
                 "expected 'key = value' in a SpaceEx configuration");
      return false;
    }
    StringRef key = trimmed.take_front(eq).trim();
    const char *valueStart = trimmed.data() + eq + 1;
    size_t vpos = valueStart - text.data();
    while (vpos < eol && (text[vpos] == ' ' || text[vpos] == '\t'))
      ++vpos;
    StringRef value;
    if (vpos < text.size() && text[vpos] == '"') {
      size_t close = text.find('"', vpos + 1);
      if (close == StringRef::npos) {
        diag.error(SMLoc::getFromPointer(text.data() + vpos),
                   "the quoted value of '" + key + "' is not closed");
        return false;
      }
      value = text.slice(vpos + 1, close);
      eol = text.find('\n', close);
      if (eol == StringRef::npos)
        eol = text.size();
    } else {
      value = text.slice(vpos, eol).trim();
    }
    ConfigEntry entry{value, SMLoc::getFromPointer(value.data())};
    if (key == "system")
      out.system = entry;
    else if (key == "initially")
      out.initially = entry;
    else if (key == "forbidden")
      out.forbidden = entry;
    else if (key == "output-variables")
      out.outputVariables = entry;
    pos = eol + 1;
  }
  return !out.initially || splitInitialSet(*out.initially, diag, out.initial);
}

bool spaceex::addParams(const std::vector<std::string> &params,
                        DiagEngine &diag, InitialSet &into) {
  for (const std::string &p : params) {
    auto [name, text] = StringRef(p).split('=');
    double v;
    if (!isName(name.trim()) || text.trim().getAsDouble(v)) {
      diag.error(SMLoc(), "--param " + p + ": expected NAME=NUMBER");
      return false;
    }
    InitialSet::Bounds &bd = into.bounds[name.trim().str()];
    bd.lo = bd.hi = v;
  }
  return true;
}
