//===- StLongParts.cpp - long ST bodies parsed in groups ------------------===//
#include "frontends/st/StLongParts.h"

#include "ST.h"

#include <optional>

using namespace netlift;
using namespace netlift::st;
using llvm::StringRef;
using P = stgen::ST;

namespace {

struct ScanToken {
  size_t type, start, stop;
};

/// Cuts tokens [begin, end) into groups (see LongParts); false when they do
/// not nest properly or hold something else (`plain` decides), in which
/// case the part stays in the file's parse.
template <typename Depth>
bool cutIntoGroups(StringRef text, const std::vector<ScanToken> &toks,
                   size_t begin, size_t end, Depth depthChange,
                   const st::ParseOptions &options, LongParts &out) {
  if (end - begin < options.longPartTokens || toks[end - 1].type != P::SEMI)
    return false;
  std::vector<StringRef> groups;
  int depth = 0;
  size_t from = toks[begin - 1].stop + 1, count = 0;
  for (size_t k = begin; k < end; ++k, ++count) {
    std::optional<int> change = depthChange(toks[k].type);
    if (!change || (depth += *change) < 0)
      return false;
    if (toks[k].type == P::SEMI && depth == 0 &&
        (count >= options.groupTokens || k + 1 == end)) {
      size_t to = k + 1 == end ? toks[end].start : toks[k].stop + 1;
      groups.push_back(text.slice(from, to));
      from = to;
      count = 0;
    }
  }
  if (depth != 0)
    return false;
  out.ranges.push_back({toks[begin - 1].stop + 1, toks[end].start});
  out.groups[toks[end].start] = std::move(groups);
  return true;
}

} // namespace

LongParts st::findLongParts(StringRef text, DiagEngine &diag,
                            const ParseOptions &options) {
  // A part of N tokens takes N bytes at least: short files need no scan.
  if (text.size() < options.longPartTokens)
    return {};
  std::vector<ScanToken> toks;
  {
    st::StLexer lexer(text, diag);
    lexer.setSilent();
    for (;;) {
      std::unique_ptr<antlr4::Token> t = lexer.nextToken();
      if (t->getType() == antlr4::Token::EOF)
        break;
      if (t->getChannel() == antlr4::Token::DEFAULT_CHANNEL)
        toks.push_back({t->getType(), t->getStartIndex(), t->getStopIndex()});
    }
    if (lexer.hadError())
      return {};
  }
  auto statementDepth = [](size_t type) -> std::optional<int> {
    switch (type) {
    case P::IF:
    case P::CASE:
    case P::FOR:
    case P::WHILE:
    case P::REPEAT:
      return 1;
    case P::END_IF:
    case P::END_CASE:
    case P::END_FOR:
    case P::END_WHILE:
    case P::END_REPEAT:
      return -1;
    case P::METHOD:
    case P::ACTION:
    case P::PROPERTY:
    case P::STEP:
    case P::INITIAL_STEP:
    case P::TRANSITION:
    case P::VAR:
    case P::END_VAR:
      return std::nullopt; // not a plain statement list
    default:
      return 0;
    }
  };
  auto declarationDepth = [](size_t type) -> std::optional<int> {
    return type == P::STRUCT ? 1 : type == P::END_STRUCT ? -1 : 0;
  };
  LongParts out;
  size_t bodyStart = 0; // the token after the POU's last END_VAR (0: none)
  for (size_t i = 0; i < toks.size(); ++i) {
    switch (toks[i].type) {
    case P::PROGRAM:
    case P::FUNCTION_BLOCK:
    case P::FUNCTION:
      bodyStart = 0;
      break;
    case P::VAR:
    case P::VAR_INPUT:
    case P::VAR_OUTPUT:
    case P::VAR_IN_OUT:
    case P::VAR_EXTERNAL:
    case P::VAR_GLOBAL:
    case P::VAR_TEMP: {
      size_t first = i + 1;
      while (first < toks.size() && (toks[first].type == P::CONSTANT ||
                                     toks[first].type == P::RETAIN ||
                                     toks[first].type == P::NON_RETAIN ||
                                     toks[first].type == P::PERSISTENT))
        ++first;
      size_t e = first;
      while (e < toks.size() && toks[e].type != P::END_VAR)
        ++e;
      if (e == toks.size())
        return out; // unterminated: the parse reports it
      cutIntoGroups(text, toks, first, e, declarationDepth, options, out);
      i = e;
      bodyStart = e + 1;
      break;
    }
    case P::END_PROGRAM:
    case P::END_FUNCTION_BLOCK:
    case P::END_FUNCTION:
      if (bodyStart)
        cutIntoGroups(text, toks, bodyStart, i, statementDepth, options, out);
      bodyStart = 0;
      break;
    default:
      break;
    }
  }
  return out;
}
