//===- SpaceExText.cpp - splitting SpaceEx conditions ---------------------===//
#include "frontends/hybrid/SpaceExText.h"

#include "llvm/ADT/STLExtras.h"

using namespace netlift;
using llvm::StringRef;

/// Splits a conjunction `a & b & c` at top-level '&' (not inside parens).
std::vector<StringRef> spaceex::conjuncts(StringRef text) {
  std::vector<StringRef> out;
  int depth = 0;
  size_t start = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '(')
      ++depth;
    else if (c == ')')
      --depth;
    else if (c == '&' && depth == 0) {
      out.push_back(text.slice(start, i).trim());
      if (i + 1 < text.size() && text[i + 1] == '&')
        ++i;
      start = i + 1;
    }
  }
  out.push_back(text.substr(start).trim());
  llvm::erase_if(out, [](StringRef s) { return s.empty(); });
  return out;
}

std::vector<std::pair<size_t, size_t>>
spaceex::comparisonOperators(StringRef c, bool singleEquals) {
  std::vector<std::pair<size_t, size_t>> ops;
  int depth = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    char ch = c[i];
    bool eqNext = i + 1 < c.size() && c[i + 1] == '=';
    if (ch == '(')
      ++depth;
    else if (ch == ')')
      --depth;
    else if (depth == 0 && (ch == '<' || ch == '>' ||
                            (ch == '=' && (eqNext || singleEquals)) ||
                            (ch == '!' && eqNext && singleEquals))) {
      size_t len = eqNext ? 2 : 1;
      ops.push_back({i, len});
      i += len - 1;
    }
  }
  return ops;
}

/// A chained comparison `a <= x <= b` (SpaceEx writes bounds so) as the
/// comparisons it chains, `a <= x` and `x <= b`; anything else as it is.
std::vector<StringRef> spaceex::unchain(StringRef c) {
  std::vector<std::pair<size_t, size_t>> ops = comparisonOperators(c, false);
  if (ops.size() < 2)
    return {c};
  std::vector<StringRef> out;
  size_t from = 0;
  for (size_t k = 0; k < ops.size(); ++k) {
    size_t end = k + 1 < ops.size() ? ops[k + 1].first : c.size();
    out.push_back(c.slice(from, end).trim());
    from = ops[k].first + ops[k].second;
  }
  return out;
}
