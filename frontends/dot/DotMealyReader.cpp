//===- DotMealyReader.cpp - Mealy machines drawn in Graphviz DOT ----------===//
#include "frontends/dot/DotMealyReader.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"

#include <map>
#include <set>
#include <tuple>

using namespace netlift;
using namespace netlift::dot;
using namespace netlift::automata;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

struct Token {
  enum Kind {
    Id,
    Html,
    Arrow,
    Line,
    LBrace,
    RBrace,
    LBrack,
    RBrack,
    Equal,
    Semi,
    Comma,
    Colon,
    Plus,
    End
  };
  Kind kind = End;
  std::string text; // an ID's value: quotes removed, escapes resolved
  bool quoted = false;
  const char *pos = nullptr;
  SMLoc loc() const { return SMLoc::getFromPointer(pos); }
};

/// DOT's lexical rules: IDs (names, numerals, double-quoted strings, HTML
/// strings), edge operators, punctuation; `//`, `/* */` and `#` line
/// comments.
class DotLexer {
public:
  DotLexer(StringRef buf, DiagEngine &diag) : buf(buf), diag(diag) {}

  bool next(Token &t) {
    skipSpaceAndComments();
    t = Token();
    t.pos = buf.data() + i;
    if (i >= buf.size())
      return true;
    char c = buf[i];
    auto punct = [&](Token::Kind k, size_t len) {
      t.kind = k;
      i += len;
      return true;
    };
    switch (c) {
    case '{':
      return punct(Token::LBrace, 1);
    case '}':
      return punct(Token::RBrace, 1);
    case '[':
      return punct(Token::LBrack, 1);
    case ']':
      return punct(Token::RBrack, 1);
    case '=':
      return punct(Token::Equal, 1);
    case ';':
      return punct(Token::Semi, 1);
    case ',':
      return punct(Token::Comma, 1);
    case ':':
      return punct(Token::Colon, 1);
    case '+':
      return punct(Token::Plus, 1);
    default:
      break;
    }
    if (c == '-' && i + 1 < buf.size() &&
        (buf[i + 1] == '>' || buf[i + 1] == '-'))
      return punct(buf[i + 1] == '>' ? Token::Arrow : Token::Line, 2);
    if (c == '"')
      return quotedString(t);
    if (c == '<')
      return htmlString(t);
    if (isNameStart(c)) {
      size_t start = i;
      while (i < buf.size() && (isNameStart(buf[i]) || llvm::isDigit(buf[i])))
        ++i;
      t.kind = Token::Id;
      t.text = buf.slice(start, i).str();
      return true;
    }
    if (c == '-' || c == '.' || llvm::isDigit(c)) {
      size_t start = i;
      if (c == '-')
        ++i;
      bool digits = false, dot = false;
      while (i < buf.size() &&
             (llvm::isDigit(buf[i]) || (buf[i] == '.' && !dot))) {
        dot |= buf[i] == '.';
        digits |= llvm::isDigit(buf[i]);
        ++i;
      }
      if (digits) {
        t.kind = Token::Id;
        t.text = buf.slice(start, i).str();
        return true;
      }
      i = start;
    }
    diag.error(t.loc(),
               "unexpected character '" + buf.substr(i, 1) + "' in a DOT file");
    return false;
  }

private:
  static bool isNameStart(char c) {
    return llvm::isAlpha(c) || c == '_' || (unsigned char)c >= 0x80;
  }

  void skipSpaceAndComments() {
    while (i < buf.size()) {
      char c = buf[i];
      // `#` lines (C preprocessor output) may be indented.
      size_t lineBegin = buf.rfind('\n', i);
      lineBegin = lineBegin == StringRef::npos ? 0 : lineBegin + 1;
      bool lineStart =
          buf.slice(lineBegin, i).find_first_not_of(" \t") == StringRef::npos;
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f') {
        ++i;
      } else if (c == '/' && i + 1 < buf.size() && buf[i + 1] == '/') {
        skipLine();
      } else if (c == '#' && lineStart) {
        skipLine();
      } else if (c == '/' && i + 1 < buf.size() && buf[i + 1] == '*') {
        size_t end = buf.find("*/", i + 2);
        i = end == StringRef::npos ? buf.size() : end + 2;
      } else {
        return;
      }
    }
  }
  void skipLine() {
    size_t end = buf.find('\n', i);
    i = end == StringRef::npos ? buf.size() : end + 1;
  }

  /// A double-quoted ID: `\"` is a quote, a backslash before a line end
  /// continues the line; other escapes (`\n`, `\l`) are kept as written.
  bool quotedString(Token &t) {
    ++i;
    t.kind = Token::Id;
    t.quoted = true;
    while (i < buf.size() && buf[i] != '"') {
      if (buf[i] == '\\' && i + 1 < buf.size()) {
        char e = buf[i + 1];
        if (e == '"' || e == '\\') {
          t.text += e;
          i += 2;
          continue;
        }
        if (e == '\n' || e == '\r') {
          i += 2;
          if (e == '\r' && i < buf.size() && buf[i] == '\n')
            ++i;
          continue;
        }
      }
      t.text += buf[i++];
    }
    if (i >= buf.size()) {
      diag.error(t.loc(), "unterminated string");
      return false;
    }
    ++i;
    return true;
  }

  bool htmlString(Token &t) {
    int depth = 0;
    size_t start = i;
    for (; i < buf.size(); ++i) {
      depth += buf[i] == '<';
      depth -= buf[i] == '>';
      if (depth == 0)
        break;
    }
    if (i >= buf.size()) {
      diag.error(t.loc(), "unterminated HTML string");
      return false;
    }
    ++i;
    t.kind = Token::Html;
    t.text = buf.slice(start, i).str();
    return true;
  }

  StringRef buf;
  DiagEngine &diag;
  size_t i = 0;
};

struct Attr {
  std::string value;
  SMLoc loc;
  bool html = false;
};
using Attrs = std::map<std::string, Attr>;

struct DotNode {
  std::string id;
  Attrs attrs;
  SMLoc loc;
};

struct DotEdge {
  uint32_t from, to;
  Attrs attrs;
  SMLoc loc;
};

/// The graph as DOT defines it: nodes in order of first mention with their
/// attributes (defaults in force when each was created), edges in order.
struct DotGraph {
  std::vector<DotNode> nodes;
  std::map<std::string, uint32_t> index;
  std::vector<DotEdge> edges;
};

class DotParser {
public:
  DotParser(StringRef buf, DiagEngine &diag, DotGraph &g)
      : lex(buf, diag), diag(diag), g(g) {}

  bool parse() {
    if (!advance())
      return false;
    if (isKeyword("strict") && !advance())
      return false;
    if (isKeyword("graph"))
      return error(tok.loc(), "an undirected graph is not a Mealy machine "
                              "(expected 'digraph')");
    if (!isKeyword("digraph"))
      return error(tok.loc(), "expected 'digraph' at the start of a DOT file");
    if (!advance())
      return false;
    if (tok.kind == Token::Id && !advance())
      return false;
    if (!expect(Token::LBrace, "'{'"))
      return false;
    std::vector<Attrs> nodeDefaults{{}}, edgeDefaults{{}};
    if (!statements(nodeDefaults, edgeDefaults))
      return false;
    if (!expect(Token::RBrace, "'}'"))
      return false;
    if (tok.kind != Token::End)
      return error(tok.loc(), "only one graph per file is read");
    return true;
  }

private:
  bool advance() { return lex.next(tok); }
  bool isKeyword(StringRef k) const {
    return tok.kind == Token::Id && !tok.quoted &&
           StringRef(tok.text).equals_insensitive(k);
  }
  bool error(SMLoc loc, const llvm::Twine &msg) {
    diag.error(loc, msg);
    return false;
  }
  bool expect(Token::Kind k, StringRef what) {
    if (tok.kind != k)
      return error(tok.loc(), "expected " + what + describeFound());
    return advance();
  }
  std::string describeFound() const {
    if (tok.kind == Token::End)
      return " at the end of the file";
    return std::string(", found '") +
           StringRef(tok.pos,
                     tok.kind == Token::Id && !tok.quoted ? tok.text.size() : 1)
               .str() +
           "'";
  }

  /// An ID with `+` concatenations of quoted strings.
  bool id(std::string &out, bool *html = nullptr) {
    if (tok.kind == Token::Html) {
      if (!html)
        return error(tok.loc(), "an HTML string is not a node name");
      *html = true;
      out = tok.text;
      return advance();
    }
    if (tok.kind != Token::Id)
      return error(tok.loc(), "expected a name" + describeFound());
    out = tok.text;
    bool quoted = tok.quoted;
    if (!advance())
      return false;
    while (quoted && tok.kind == Token::Plus) {
      if (!advance())
        return false;
      if (tok.kind != Token::Id || !tok.quoted)
        return error(tok.loc(), "expected a quoted string after '+'");
      out += tok.text;
      if (!advance())
        return false;
    }
    return true;
  }

  bool attrList(Attrs &attrs) {
    while (tok.kind == Token::LBrack) {
      if (!advance())
        return false;
      while (tok.kind != Token::RBrack) {
        std::string key;
        if (!id(key))
          return false;
        Attr a{"true", tok.loc(), false};
        if (tok.kind == Token::Equal) {
          if (!advance())
            return false;
          a.loc = tok.loc();
          if (!id(a.value, &a.html))
            return false;
        }
        attrs[key] = std::move(a);
        if (tok.kind == Token::Semi || tok.kind == Token::Comma)
          if (!advance())
            return false;
      }
      if (!advance())
        return false;
    }
    return true;
  }

  /// A node ID with an optional port (ignored).
  bool nodeId(std::string &name, SMLoc &loc) {
    loc = tok.loc();
    if (!id(name))
      return false;
    for (int k = 0; k < 2 && tok.kind == Token::Colon; ++k) {
      if (!advance())
        return false;
      std::string port;
      if (!id(port))
        return false;
    }
    return true;
  }

  uint32_t node(const std::string &name, SMLoc loc, const Attrs &defaults) {
    auto [it, fresh] = g.index.try_emplace(name, g.nodes.size());
    if (fresh)
      g.nodes.push_back({name, defaults, loc});
    return it->second;
  }

  bool statements(std::vector<Attrs> &nodeDefaults,
                  std::vector<Attrs> &edgeDefaults) {
    while (tok.kind != Token::RBrace && tok.kind != Token::End) {
      if (!statement(nodeDefaults, edgeDefaults))
        return false;
      if (tok.kind == Token::Semi && !advance())
        return false;
    }
    return true;
  }

  bool statement(std::vector<Attrs> &nodeDefaults,
                 std::vector<Attrs> &edgeDefaults) {
    if (isKeyword("node") || isKeyword("edge") || isKeyword("graph")) {
      Attrs *target = isKeyword("node")   ? &nodeDefaults.back()
                      : isKeyword("edge") ? &edgeDefaults.back()
                                          : nullptr;
      Attrs ignored;
      if (!advance())
        return false;
      return attrList(target ? *target : ignored);
    }
    if (isKeyword("subgraph") || tok.kind == Token::LBrace) {
      // Grouping only: its statements join the graph, its defaults stay
      // inside it.
      SMLoc at = tok.loc();
      if (isKeyword("subgraph")) {
        if (!advance())
          return false;
        std::string name;
        if (tok.kind == Token::Id && !id(name))
          return false;
      }
      if (!expect(Token::LBrace, "'{'"))
        return false;
      nodeDefaults.push_back(nodeDefaults.back());
      edgeDefaults.push_back(edgeDefaults.back());
      if (!statements(nodeDefaults, edgeDefaults) ||
          !expect(Token::RBrace, "'}'"))
        return false;
      nodeDefaults.pop_back();
      edgeDefaults.pop_back();
      if (tok.kind == Token::Arrow || tok.kind == Token::Line)
        return error(at, "a subgraph as an edge end is not supported in a "
                         "Mealy machine");
      return true;
    }
    std::string name;
    SMLoc loc;
    if (!nodeId(name, loc))
      return false;
    if (tok.kind == Token::Equal) { // a graph attribute
      if (!advance())
        return false;
      std::string value;
      bool html = false;
      return id(value, &html);
    }
    if (tok.kind != Token::Arrow && tok.kind != Token::Line) {
      Attrs attrs;
      if (!attrList(attrs))
        return false;
      uint32_t n = node(name, loc, nodeDefaults.back());
      for (auto &[k, v] : attrs)
        g.nodes[n].attrs[k] = v;
      return true;
    }
    std::vector<std::pair<uint32_t, SMLoc>> chain{
        {node(name, loc, nodeDefaults.back()), loc}};
    while (tok.kind == Token::Arrow || tok.kind == Token::Line) {
      if (tok.kind == Token::Line)
        return error(tok.loc(), "'--' is an undirected edge; a Mealy machine "
                                "needs '->'");
      if (!advance())
        return false;
      if (isKeyword("subgraph") || tok.kind == Token::LBrace)
        return error(tok.loc(), "a subgraph as an edge end is not supported "
                                "in a Mealy machine");
      if (!nodeId(name, loc))
        return false;
      chain.push_back({node(name, loc, nodeDefaults.back()), loc});
    }
    Attrs attrs = edgeDefaults.back();
    Attrs own;
    if (!attrList(own))
      return false;
    for (auto &[k, v] : own)
      attrs[k] = v;
    for (size_t k = 0; k + 1 < chain.size(); ++k)
      g.edges.push_back(
          {chain[k].first, chain[k + 1].first, attrs, chain[k].second});
    return true;
  }

  DotLexer lex;
  DiagEngine &diag;
  DotGraph &g;
  Token tok;
};

const Attr *attr(const Attrs &attrs, StringRef key) {
  auto it = attrs.find(key.str());
  return it == attrs.end() ? nullptr : &it->second;
}

bool isStartNode(const DotNode &n) {
  if (StringRef(n.id).startswith("__start"))
    return true;
  const Attr *shape = attr(n.attrs, "shape");
  const Attr *label = attr(n.attrs, "label");
  return shape && (shape->value == "none" || shape->value == "point") &&
         label && label->value.empty();
}

/// `text` ends in `:NUMBER` (a probability).
bool hasProbability(StringRef text) {
  size_t colon = text.rfind(':');
  if (colon == StringRef::npos)
    return false;
  double p;
  return !text.drop_front(colon + 1).trim().getAsDouble(p);
}

/// The text of an HTML-like label: tags dropped, `<br/>` as a line end,
/// the five XML entities resolved.
std::string htmlText(StringRef html) {
  html = html.drop_front().drop_back(); // the outer < >
  std::string out;
  for (size_t i = 0; i < html.size();) {
    if (html[i] == '<') {
      size_t end = html.find('>', i);
      StringRef tag = html.slice(i + 1, end).trim();
      if (tag.startswith_insensitive("br"))
        out += '\n';
      i = end == StringRef::npos ? html.size() : end + 1;
      continue;
    }
    if (html[i] == '&') {
      static const std::pair<StringRef, char> entities[] = {{"&amp;", '&'},
                                                            {"&lt;", '<'},
                                                            {"&gt;", '>'},
                                                            {"&quot;", '"'},
                                                            {"&apos;", '\''}};
      bool done = false;
      for (auto [name, c] : entities)
        if (html.substr(i).startswith(name)) {
          out += c;
          i += name.size();
          done = true;
          break;
        }
      if (done)
        continue;
    }
    out += html[i++];
  }
  return out;
}

bool isCube(StringRef s) {
  return !s.empty() && s.find_first_not_of("01-") == StringRef::npos;
}

} // namespace

bool netlift::dot::readMealyDot(unsigned bufferID, DiagEngine &diag,
                                MealyMachine &m) {
  StringRef buf = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  DotGraph g;
  if (!DotParser(buf, diag, g).parse())
    return false;
  auto err = [&](SMLoc loc, const llvm::Twine &msg) {
    diag.error(loc, msg);
    return false;
  };

  // States: every node but the start pseudo-nodes, in order of mention.
  std::vector<int64_t> stateOf(g.nodes.size(), -1);
  std::vector<uint32_t> stateNodes;
  for (uint32_t n = 0; n < g.nodes.size(); ++n) {
    if (isStartNode(g.nodes[n]))
      continue;
    const DotNode &node = g.nodes[n];
    const Attr *shape = attr(node.attrs, "shape");
    const Attr *label = attr(node.attrs, "label");
    if (shape && (shape->value == "record" || shape->value == "Mrecord") &&
        label && label->value.find('|') != std::string::npos)
      return err(label->loc, "state '" + node.id + "' carries an output ('" +
                                 label->value +
                                 "'): a Moore machine; netlift reads Mealy "
                                 "machines (outputs on the edges)");
    stateOf[n] = stateNodes.size();
    stateNodes.push_back(n);
  }
  if (stateNodes.empty())
    return err(SMLoc::getFromPointer(buf.data()), "the graph has no states");
  // State names: the labels when they name the states one to one (AALpy
  // writes `0 [label="s0"]`), else the node IDs; blanks become '_' so
  // that the names survive KISS2.
  auto clean = [](std::string s) {
    for (char &c : s)
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r')
        c = '_';
    return s;
  };
  std::set<std::string> seen;
  bool useLabels = true;
  for (uint32_t n : stateNodes) {
    const Attr *label = attr(g.nodes[n].attrs, "label");
    useLabels = useLabels && label && !label->html && !label->value.empty() &&
                seen.insert(clean(label->value)).second;
  }
  for (uint32_t n : stateNodes) {
    std::string name = clean(useLabels ? attr(g.nodes[n].attrs, "label")->value
                                       : g.nodes[n].id);
    if (std::find(m.states.begin(), m.states.end(), name) != m.states.end())
      return err(g.nodes[n].loc,
                 "state names '" + name + "' collide once blanks become '_'");
    m.states.push_back(name);
  }

  // Edges: the start edge, then `input/output` labels.
  struct Row {
    std::string in, out;
    uint32_t from, to;
    SMLoc loc;
  };
  std::vector<Row> rows;
  std::set<std::tuple<uint32_t, std::string, uint32_t, std::string>> drawn;
  int64_t initial = -1;
  for (const DotEdge &e : g.edges) {
    if (stateOf[e.to] < 0)
      return err(e.loc,
                 "an edge into the start node '" + g.nodes[e.to].id + "'");
    if (stateOf[e.from] < 0) {
      if (initial >= 0 && initial != stateOf[e.to])
        return err(e.loc, "a second start edge (the initial state is '" +
                              m.states[initial] + "')");
      initial = stateOf[e.to];
      continue;
    }
    const Attr *label = attr(e.attrs, "label");
    if (!label || label->value.empty())
      return err(e.loc, "an edge without a label: a Mealy machine's edges "
                        "read 'input/output'");
    std::string text = label->value, in, out;
    if (label->html) {
      // The Automata Wiki's style: <INPUT<br />OUTPUT>.
      std::string plain = htmlText(text);
      size_t br = plain.find('\n');
      if (br == std::string::npos)
        return err(label->loc, "the HTML edge label '" + text +
                                   "' has no <br/> between input and output");
      in = plain.substr(0, br);
      out = plain.substr(br + 1);
      for (char &c : out)
        c = c == '\n' ? ' ' : c;
    } else {
      if (hasProbability(text))
        return err(label->loc, "a probabilistic edge ('" + text +
                                   "'): an MDP or a stochastic machine; "
                                   "netlift reads deterministic Mealy "
                                   "machines");
      // Split at " / " when present (symbols may contain '/'), else at
      // the first '/'.
      size_t slash = text.find(" / ");
      size_t width = 3;
      if (slash == std::string::npos) {
        slash = text.find('/');
        width = 1;
      }
      if (slash == std::string::npos)
        return err(label->loc, "the edge label '" + text +
                                   "' has no output: a DFA or a Moore "
                                   "machine, not a Mealy machine "
                                   "('input/output')");
      in = text.substr(0, slash);
      out = text.substr(slash + width);
    }
    StringRef outText = StringRef(out).trim();
    if (StringRef(in).trim().empty() || outText.empty())
      return err(label->loc, "the edge label '" + text + "' has an empty " +
                                 (outText.empty() ? "output" : "input"));
    // `a | b / x`: one edge for each of the alternatives a and b.
    llvm::SmallVector<StringRef, 4> alternatives;
    StringRef(in).split(alternatives, " | ");
    for (StringRef alt : alternatives) {
      if (alt.trim().empty())
        return err(label->loc, "the edge label '" + text +
                                   "' has an empty input alternative");
      Row row{alt.trim().str(), outText.str(), uint32_t(stateOf[e.from]),
              uint32_t(stateOf[e.to]), label->loc};
      // An edge drawn twice (or an edge chain `a -> a -> a`) is one row.
      if (drawn.insert({row.from, row.in, row.to, row.out}).second)
        rows.push_back(std::move(row));
    }
  }
  if (rows.empty())
    return err(SMLoc::getFromPointer(buf.data()), "the machine has no edges");
  m.initial = initial >= 0 ? uint32_t(initial) : 0;

  // Boolean vectors when every label is a cube of one width on each side
  // (netlift's own DOT), else symbols.
  bool boolean = true;
  for (const Row &r : rows)
    boolean = boolean && isCube(r.in) && isCube(r.out) &&
              r.in.size() == rows[0].in.size() &&
              r.out.size() == rows[0].out.size() && r.in.size() <= 24;
  if (boolean) {
    for (size_t k = 0; k < rows[0].in.size(); ++k)
      m.inputs.push_back("i" + std::to_string(k + 1));
    for (size_t k = 0; k < rows[0].out.size(); ++k)
      m.outputs.push_back("o" + std::to_string(k + 1));
    for (Row &r : rows)
      m.transitions.push_back({r.in, r.from, r.to, r.out, r.loc});
    return true;
  }
  auto code = [](std::vector<std::string> &symbols, const std::string &s) {
    auto it = std::find(symbols.begin(), symbols.end(), s);
    if (it != symbols.end())
      return uint32_t(it - symbols.begin());
    symbols.push_back(s);
    return uint32_t(symbols.size() - 1);
  };
  std::vector<std::pair<uint32_t, uint32_t>> codes;
  for (const Row &r : rows)
    codes.push_back({code(m.inputSymbols, r.in), code(m.outputSymbols, r.out)});
  unsigned inBits = MealyMachine::symbolWidth(m.inputSymbols.size()),
           outBits = MealyMachine::symbolWidth(m.outputSymbols.size());
  constexpr unsigned kMaxSymbolBits = 24;
  if (inBits > kMaxSymbolBits)
    return err(rows[0].loc,
               "more than 2^" + llvm::Twine(kMaxSymbolBits) + " input symbols");
  for (unsigned k = 0; k < inBits; ++k)
    m.inputs.push_back("i" + std::to_string(k + 1));
  for (unsigned k = 0; k < outBits; ++k)
    m.outputs.push_back("o" + std::to_string(k + 1));
  for (size_t k = 0; k < rows.size(); ++k)
    m.transitions.push_back({vectorBits(codes[k].first, inBits), rows[k].from,
                             rows[k].to, vectorBits(codes[k].second, outBits),
                             rows[k].loc});
  return true;
}
