//===- Suggest.cpp - "did you mean" for misspelt names --------------------===//
#include "ir/support/Suggest.h"

#include <algorithm>

using namespace netlift;

std::string netlift::closestName(llvm::StringRef name,
                                 llvm::ArrayRef<std::string> candidates) {
  std::string lower = name.lower();
  // Two edits (a swapped pair of letters) for any name, more for long
  // ones, but never as many as the name has letters.
  unsigned size = unsigned(name.size());
  unsigned limit = std::min(std::max(2u, (size + 2) / 3), size ? size - 1 : 0);
  unsigned best = limit + 1;
  std::string found;
  for (const std::string &c : candidates) {
    if (c.empty() || llvm::StringRef(c).equals_insensitive(name))
      continue;
    unsigned d = llvm::StringRef(lower).edit_distance(
        llvm::StringRef(c).lower(), /*AllowReplacements=*/true, best);
    if (d < best) {
      best = d;
      found = c;
    }
  }
  return found;
}

std::string netlift::didYouMean(llvm::StringRef name,
                                llvm::ArrayRef<std::string> candidates) {
  std::string c = closestName(name, candidates);
  return c.empty() ? "" : "; did you mean '" + c + "'?";
}
