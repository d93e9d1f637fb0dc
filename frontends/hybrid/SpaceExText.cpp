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

/// A chained comparison `a <= x <= b` (SpaceEx writes bounds so) as the
/// comparisons it chains, `a <= x` and `x <= b`; anything else as it is.
std::vector<StringRef> spaceex::unchain(StringRef c) {
  std::vector<std::pair<size_t, size_t>> ops; // position, length
  int depth = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    char ch = c[i];
    if (ch == '(')
      ++depth;
    else if (ch == ')')
      --depth;
    else if (depth == 0 &&
             (ch == '<' || ch == '>' ||
              (ch == '=' && i + 1 < c.size() && c[i + 1] == '='))) {
      size_t len = i + 1 < c.size() && c[i + 1] == '=' ? 2 : 1;
      ops.push_back({i, len});
      i += len - 1;
    }
  }
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
