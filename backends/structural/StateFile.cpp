//===- StateFile.cpp - state spaces read back from `reach` JSON -----------===//
#include "backends/structural/StateFile.h"

#include "ir/net/Printer.h"
#include "ir/net/ScalarOps.h"
#include "ir/net/StringOps.h"

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/Support/MemoryBuffer.h"

#include <sys/mman.h>
#include <unistd.h>
#include <unordered_map>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::structural;
using llvm::StringRef;

namespace {

/// A pull reader over JSON text: the caller walks the structure it expects
/// and skips what it does not know. Positions of errors are kept.
class JsonCursor {
public:
  JsonCursor(StringRef buf, DiagEngine &diag) : buf(buf), diag(diag) {}

  bool fail(const llvm::Twine &msg) {
    if (ok)
      diag.error(
          llvm::SMLoc::getFromPointer(buf.data() + std::min(i, buf.size())),
          msg);
    ok = false;
    return false;
  }
  void ws() {
    while (i < buf.size() && (buf[i] == ' ' || buf[i] == '\n' ||
                              buf[i] == '\t' || buf[i] == '\r'))
      ++i;
  }
  bool peek(char c) {
    ws();
    return i < buf.size() && buf[i] == c;
  }
  bool expect(char c) {
    if (!peek(c))
      return fail(llvm::Twine("expected '") + llvm::Twine(c) +
                  "' in the state file");
    ++i;
    return true;
  }
  /// After an element of an array or object: true if another follows.
  bool more(char close) {
    if (peek(',')) {
      ++i;
      return true;
    }
    if (peek(close)) {
      ++i;
      return false;
    }
    fail(llvm::Twine("expected ',' or '") + llvm::Twine(close) + "'");
    return false;
  }
  /// Starts an array or object; false if it is empty (and consumed).
  bool open(char openC, char closeC) {
    if (!expect(openC))
      return false;
    if (peek(closeC)) {
      ++i;
      return false;
    }
    return true;
  }
  bool string(std::string &out) {
    if (!expect('"'))
      return false;
    out.clear();
    while (i < buf.size() && buf[i] != '"') {
      char c = buf[i++];
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i >= buf.size())
        break;
      char e = buf[i++];
      switch (e) {
      case 'n':
        out += '\n';
        break;
      case 't':
        out += '\t';
        break;
      case 'r':
        out += '\r';
        break;
      case 'b':
        out += '\b';
        break;
      case 'f':
        out += '\f';
        break;
      case 'u': {
        unsigned code = 0;
        if (i + 4 > buf.size() || buf.substr(i, 4).getAsInteger(16, code))
          return fail("bad \\u escape");
        i += 4;
        // Names are ASCII in practice; keep others as UTF-8.
        net::appendUtf8(out, code);
        break;
      }
      default:
        out += e;
      }
    }
    if (i >= buf.size())
      return fail("unterminated string");
    ++i;
    return true;
  }
  bool key(std::string &out) { return string(out) && expect(':'); }
  /// The text already read, up to which a mapped file may be dropped.
  size_t position() const { return i; }
  bool integer(int64_t &v) {
    ws();
    size_t start = i;
    if (i < buf.size() && buf[i] == '-')
      ++i;
    while (i < buf.size() && buf[i] >= '0' && buf[i] <= '9')
      ++i;
    if (buf.slice(start, i).getAsInteger(10, v))
      return fail("expected an integer");
    return true;
  }
  bool boolean(bool &v) {
    ws();
    if (buf.substr(i).startswith("true")) {
      v = true;
      i += 4;
      return true;
    }
    if (buf.substr(i).startswith("false")) {
      v = false;
      i += 5;
      return true;
    }
    return fail("expected true or false");
  }
  /// An object, `field(key)` reading each member's value; false after an
  /// error (an empty object is fine).
  bool object(llvm::function_ref<bool(const std::string &)> field) {
    if (!open('{', '}'))
      return ok;
    std::string k;
    do {
      if (!key(k) || !field(k))
        return false;
    } while (more('}'));
    return ok;
  }
  /// An array, `element()` reading each element.
  bool array(llvm::function_ref<bool()> element) {
    if (!open('[', ']'))
      return ok;
    do {
      if (!element())
        return false;
    } while (more(']'));
    return ok;
  }
  bool skipValue() {
    ws();
    if (i >= buf.size())
      return fail("unexpected end of the state file");
    char c = buf[i];
    std::string s;
    if (c == '"')
      return string(s);
    if (c == '{')
      return object([&](const std::string &) { return skipValue(); });
    if (c == '[')
      return array([&] { return skipValue(); });
    while (i < buf.size() && buf[i] != ',' && buf[i] != '}' && buf[i] != ']' &&
           buf[i] != ' ' && buf[i] != '\n')
      ++i;
    return true;
  }
  llvm::SMLoc loc() const {
    return llvm::SMLoc::getFromPointer(buf.data() + std::min(i, buf.size()));
  }

  bool ok = true;

private:
  StringRef buf;
  DiagEngine &diag;
  size_t i = 0;
};

/// Evaluates attribute predicates on a row of column values: every name
/// (`p`, `t1.Q`, `v[2].x`) is resolved to its column once, up front.
class RowEvaluator {
public:
  RowEvaluator(const std::vector<std::string> &columns, DiagEngine &diag)
      : diag(diag) {
    for (size_t c = 0; c < columns.size(); ++c)
      byName.emplace(columns[c], c);
    for (const std::string &c : columns)
      known += (known.empty() ? "" : ", ") + c;
  }

  /// Resolves the names of `e`; false after reporting an unknown one or a
  /// construct a row cannot answer.
  bool resolve(const Expr *e) {
    switch (e->getKind()) {
    case ExprKind::IntLit:
    case ExprKind::BoolLit:
      return true;
    case ExprKind::RealLit:
      diag.error(e->loc, "real numbers are not values of a state file");
      return false;
    case ExprKind::Aggregate:
      diag.error(e->loc, "aggregates are not values of a state file");
      return false;
    case ExprKind::StringLit:
      diag.error(e->loc, "strings are not values of a state file");
      return false;
    case ExprKind::Ref:
    case ExprKind::Field:
    case ExprKind::Index: {
      std::string name = exprToString(e);
      auto it = byName.find(name);
      if (it == byName.end()) {
        diag.error(e->loc, "no column '" + name +
                               "' in the state file (columns: " + known + ")");
        return false;
      }
      column[e] = it->second;
      return true;
    }
    case ExprKind::Unary:
      return resolve(llvm::cast<UnaryExpr>(e)->operand);
    case ExprKind::Binary:
      return resolve(llvm::cast<BinaryExpr>(e)->lhs) &&
             resolve(llvm::cast<BinaryExpr>(e)->rhs);
    case ExprKind::Cond: {
      auto *c = llvm::cast<CondExpr>(e);
      return resolve(c->cond) && resolve(c->thenExpr) && resolve(c->elseExpr);
    }
    case ExprKind::Call:
      for (const Expr *a : llvm::cast<CallExpr>(e)->args)
        if (!resolve(a))
          return false;
      return true;
    }
    return false;
  }

  /// The value of `e` on `row` (NetIR's operators, net/ScalarOps.h);
  /// `error` set and 0 returned where it has none.
  int64_t eval(const Expr *e, const std::vector<int64_t> &row,
               std::string &error) const {
    int64_t r = 0;
    OpError err = OpError::None;
    switch (e->getKind()) {
    case ExprKind::IntLit:
      return llvm::cast<IntLit>(e)->value;
    case ExprKind::BoolLit:
      return llvm::cast<BoolLit>(e)->value;
    case ExprKind::RealLit: // refused by resolve()
    case ExprKind::StringLit:
    case ExprKind::Aggregate:
      return 0;
    case ExprKind::Ref:
    case ExprKind::Field:
    case ExprKind::Index:
      return row[column.at(e)];
    case ExprKind::Cond: {
      auto *c = llvm::cast<CondExpr>(e);
      return eval(c->cond, row, error) ? eval(c->thenExpr, row, error)
                                       : eval(c->elseExpr, row, error);
    }
    case ExprKind::Unary: {
      auto *u = llvm::cast<UnaryExpr>(e);
      err = applyUnary(u, eval(u->operand, row, error), r);
      break;
    }
    case ExprKind::Call: {
      auto *c = llvm::cast<CallExpr>(e);
      int64_t a = eval(c->args[0], row, error);
      int64_t b = c->fn == Builtin::Abs ? 0 : eval(c->args[1], row, error);
      err = applyBuiltin(c, a, b, r);
      break;
    }
    case ExprKind::Binary: {
      auto *b = llvm::cast<BinaryExpr>(e);
      if (b->op == BinaryOp::And)
        return eval(b->lhs, row, error) && eval(b->rhs, row, error);
      if (b->op == BinaryOp::Or)
        return eval(b->lhs, row, error) || eval(b->rhs, row, error);
      int64_t x = eval(b->lhs, row, error), y = eval(b->rhs, row, error);
      err = applyBinary(b, x, y, r);
      if (err != OpError::None && error.empty())
        error = opErrorMessage(err, e, y);
      return err == OpError::None ? r : 0;
    }
    }
    if (err != OpError::None && error.empty())
      error = opErrorMessage(err, e, 0);
    return err == OpError::None ? r : 0;
  }

private:
  DiagEngine &diag;
  std::unordered_map<std::string, size_t> byName;
  std::unordered_map<const Expr *, size_t> column;
  std::string known;
};

constexpr uint32_t kNoState = ~uint32_t(0);

/// What both file formats share: the columns, the attributes resolved
/// against them, the region of every state read so far, and the analysis
/// fed state by state and edge by edge. Errors are returned as text for
/// the reader to place.
class RowClassifier {
public:
  RowClassifier(const std::vector<StateFileAttribute> &attrs, DiagEngine &diag,
                Analysis &analysis, StateFileResult &result)
      : attrs(attrs), diag(diag), analysis(analysis), result(result),
        plainColumn(attrs.size(), -1) {}

  /// The file's columns (and which are places); false after reporting,
  /// at `loc`, an attribute naming no column.
  bool setColumns(std::vector<std::string> names, std::vector<bool> places,
                  llvm::SMLoc loc) {
    columns = std::move(names);
    isPlace = std::move(places);
    eval = std::make_unique<RowEvaluator>(columns, diag);
    for (size_t a = 0; a < attrs.size(); ++a) {
      if (attrs[a].predicate) {
        if (!eval->resolve(attrs[a].predicate))
          return false;
        continue;
      }
      auto it = std::find(columns.begin(), columns.end(), attrs[a].name);
      if (it == columns.end()) {
        std::string known;
        for (const std::string &c : columns)
          known += (known.empty() ? "" : ", ") + c;
        diag.error(loc, "no column '" + attrs[a].name +
                            "' in the state file (columns: " + known + ")");
        return false;
      }
      plainColumn[a] = it - columns.begin();
    }
    return true;
  }
  bool ready() const { return eval != nullptr; }
  size_t numColumns() const { return columns.size(); }

  /// One state; "" or what is wrong with it.
  std::string addState(int64_t id, bool dead, const std::vector<int64_t> &row) {
    if (id < 0 || id >= int64_t(kNoState))
      return "a state without a valid id";
    if (row.size() != columns.size())
      return "state " + std::to_string(id) + " has " +
             std::to_string(row.size()) + " values for " +
             std::to_string(columns.size()) + " attributes";
    Region r = 0;
    for (size_t a = 0; a < attrs.size(); ++a) {
      int64_t v;
      if (plainColumn[a] >= 0) {
        v = row[plainColumn[a]];
      } else {
        std::string err;
        v = eval->eval(attrs[a].predicate, row, err);
        if (!err.empty())
          return "attribute '" + attrs[a].name + "' in state " +
                 std::to_string(id) + ": " + err;
      }
      if (v)
        r |= Region(1) << a;
    }
    if (size_t(id) >= regionOf.size())
      regionOf.resize(size_t(id) + 1, kNoState);
    if (regionOf[id] != kNoState)
      return "state " + std::to_string(id) + " is listed twice";
    regionOf[id] = r;
    analysis.addState(r, dead);
    if (result.collectExamples && !result.examples.count(r)) {
      std::string text;
      for (size_t c = 0; c < columns.size(); ++c)
        if (!isPlace[c] || row[c] != 0)
          text += (text.empty() ? "" : ", ") + columns[c] + "=" +
                  std::to_string(row[c]);
      result.examples[r] = text;
    }
    return "";
  }

  /// One edge; "" or what is wrong with it.
  std::string addEdge(int64_t from, int64_t to) {
    for (int64_t s : {from, to})
      if (s < 0 || size_t(s) >= regionOf.size() || regionOf[s] == kNoState)
        return "an edge refers to state " + std::to_string(s) +
               ", which the file does not list";
    analysis.addEdge(regionOf[from], regionOf[to]);
    return "";
  }

private:
  const std::vector<StateFileAttribute> &attrs;
  DiagEngine &diag;
  Analysis &analysis;
  StateFileResult &result;
  std::vector<std::string> columns;
  std::vector<bool> isPlace;
  std::unique_ptr<RowEvaluator> eval;
  std::vector<int64_t> plainColumn;
  std::vector<uint32_t> regionOf; // by state number
};

/// Gives back the pages of a mapped file already read, so that memory does
/// not grow with the file (they are read again from the file if an error
/// message needs their text).
class PageReleaser {
public:
  explicit PageReleaser(const llvm::MemoryBuffer *mb) : mb(mb) {}
  void readUpTo(size_t offset) {
    if (mb->getBufferKind() != llvm::MemoryBuffer::MemoryBuffer_MMap)
      return;
    constexpr size_t kChunk = size_t(64) << 20;
    size_t page = size_t(sysconf(_SC_PAGESIZE));
    uintptr_t base = uintptr_t(mb->getBufferStart());
    uintptr_t upto = (base + offset) & ~(uintptr_t(page) - 1);
    uintptr_t from = (base + released + page - 1) & ~(uintptr_t(page) - 1);
    if (upto < from + kChunk)
      return;
    madvise(reinterpret_cast<void *>(from), upto - from, MADV_DONTNEED);
    released = upto - base;
  }

private:
  const llvm::MemoryBuffer *mb;
  size_t released = 0;
};

} // namespace

bool netlift::structural::analyseStateFile(
    unsigned bufferID, DiagEngine &diag,
    const std::vector<StateFileAttribute> &attrs, Analysis &analysis,
    StateFileResult &result) {
  const llvm::MemoryBuffer *mb = diag.sourceMgr().getMemoryBuffer(bufferID);
  JsonCursor j(mb->getBuffer(), diag);
  RowClassifier rows(attrs, diag, analysis, result);
  PageReleaser pages(mb);
  bool sawStates = false;
  auto check = [&](const std::string &problem) {
    return problem.empty() || j.fail(problem);
  };
  std::vector<int64_t> row;

  auto attribute = [&](std::vector<std::string> &names,
                       std::vector<bool> &places) {
    std::string name, kind;
    if (!j.object([&](const std::string &key) {
          return key == "name"   ? j.string(name)
                 : key == "kind" ? j.string(kind)
                                 : j.skipValue();
        }))
      return false;
    names.push_back(name);
    places.push_back(kind == "place");
    return true;
  };
  auto state = [&]() {
    int64_t id = -1;
    bool dead = false;
    row.clear();
    if (!j.object([&](const std::string &key) {
          if (key == "id")
            return j.integer(id);
          if (key == "deadlock")
            return j.boolean(dead);
          if (key == "values")
            return j.array([&] {
              int64_t v;
              if (!j.integer(v))
                return false;
              row.push_back(v);
              return true;
            });
          return j.skipValue();
        }))
      return false;
    if (!check(rows.addState(id, dead, row)))
      return false;
    if ((id & 0xffff) == 0)
      pages.readUpTo(j.position());
    return true;
  };
  auto edge = [&]() {
    int64_t from = -1, to = -1;
    if (!j.object([&](const std::string &key) {
          return key == "from" ? j.integer(from)
                 : key == "to" ? j.integer(to)
                               : j.skipValue();
        }))
      return false;
    if (!check(rows.addEdge(from, to)))
      return false;
    if ((from & 0xffff) == 0)
      pages.readUpTo(j.position());
    return true;
  };

  if (!j.peek('{'))
    return j.fail("expected a JSON object (a state file of `netlift reach "
                  "--format json`)");
  bool ok = j.object([&](const std::string &key) {
    if (key == "model")
      return j.string(result.model);
    if (key == "complete")
      return j.boolean(result.complete);
    if (key == "attributes") {
      std::vector<std::string> names;
      std::vector<bool> places;
      llvm::SMLoc at = j.loc();
      return j.array([&] { return attribute(names, places); }) &&
             rows.setColumns(std::move(names), std::move(places), at);
    }
    if (key == "states") {
      if (!rows.ready())
        return j.fail("'attributes' must come before 'states'");
      sawStates = true;
      return j.array(state);
    }
    if (key == "edges") {
      if (!sawStates)
        return j.fail("'states' must come before 'edges'");
      return j.array(edge);
    }
    return j.skipValue();
  });
  if (!ok)
    return false;
  if (!sawStates)
    return j.fail("the file lists no states (is it written by `netlift reach "
                  "--format json`?)");
  return true;
}

/// One CSV line's fields as integers; false (with `why`) if one is not.
static bool csvIntegers(StringRef line, std::vector<int64_t> &out,
                        std::string &why) {
  out.clear();
  llvm::SmallVector<StringRef, 32> fields;
  line.split(fields, ',');
  for (StringRef f : fields) {
    int64_t v;
    if (f.trim().getAsInteger(10, v)) {
      why = "'" + f.str() + "' is not an integer";
      return false;
    }
    out.push_back(v);
  }
  return true;
}

bool netlift::structural::analyseStateCsv(
    unsigned statesID, unsigned edgesID, DiagEngine &diag,
    const std::vector<StateFileAttribute> &attrs, Analysis &analysis,
    StateFileResult &result) {
  RowClassifier rows(attrs, diag, analysis, result);
  auto lines = [&](unsigned id, auto &&onLine) {
    const llvm::MemoryBuffer *mb = diag.sourceMgr().getMemoryBuffer(id);
    PageReleaser pages(mb);
    StringRef rest = mb->getBuffer();
    size_t n = 0;
    while (!rest.empty()) {
      auto [line, next] = rest.split('\n');
      rest = next;
      line = line.rtrim("\r");
      if (line.empty())
        continue;
      if (!onLine(line, n++))
        return false;
      if ((n & 0xffff) == 0)
        pages.readUpTo(size_t(rest.data() - mb->getBufferStart()));
    }
    if (n == 0) {
      diag.error(llvm::SMLoc::getFromPointer(mb->getBufferStart()),
                 "the CSV file is empty (a header is expected)");
      return false;
    }
    return true;
  };
  auto err = [&](StringRef line, const llvm::Twine &msg) {
    diag.error(llvm::SMLoc::getFromPointer(line.data()), msg);
    return false;
  };
  std::vector<int64_t> row, values;
  std::string why;
  // Header `id,deadlock,<attribute>...` (reach --format csv); the kinds of
  // the columns are not in it, so examples list every column.
  bool ok = lines(statesID, [&](StringRef line, size_t n) {
    if (n == 0) {
      llvm::SmallVector<StringRef, 32> fields;
      line.split(fields, ',');
      if (fields.size() < 2 || fields[0] != "id" || fields[1] != "deadlock")
        return err(line, "expected the header 'id,deadlock,...' of `netlift "
                         "reach --format csv`");
      std::vector<std::string> names;
      for (size_t i = 2; i < fields.size(); ++i)
        names.push_back(fields[i].str());
      std::vector<bool> places(names.size(), false);
      return rows.setColumns(std::move(names), std::move(places),
                             llvm::SMLoc::getFromPointer(line.data()));
    }
    if (!csvIntegers(line, values, why))
      return err(line, why);
    if (values.size() != rows.numColumns() + 2)
      return err(line, "expected " + llvm::Twine(rows.numColumns() + 2) +
                           " fields, found " + llvm::Twine(values.size()));
    row.assign(values.begin() + 2, values.end());
    std::string problem = rows.addState(values[0], values[1] != 0, row);
    return problem.empty() || err(line, problem);
  });
  if (!ok || !edgesID)
    return ok;
  // Edges `from,label,to` (reach --edges); labels never contain a line
  // end but may be quoted with commas inside, so from and to are the first
  // and the last field.
  return lines(edgesID, [&](StringRef line, size_t n) {
    if (n == 0) {
      if (line != "from,label,to")
        return err(line, "expected the header 'from,label,to' of `netlift "
                         "reach --edges`");
      return true;
    }
    int64_t from, to;
    if (line.substr(0, line.find(',')).getAsInteger(10, from) ||
        line.substr(line.rfind(',') + 1).getAsInteger(10, to))
      return err(line, "expected 'from,label,to' with state numbers");
    std::string problem = rows.addEdge(from, to);
    return problem.empty() || err(line, problem);
  });
}
