//===- SpaceExText.h - splitting SpaceEx conditions -----------*- C++ -*-===//
//
// SpaceEx writes guards, invariants, flows and initial sets as
// conjunctions in one text, with chained comparisons for bounds
// (`0 <= x <= 5 & y == 1`). These split such a text into its parts without
// copying, so that each part keeps its position in the file; shared by the
// model reader and the configuration reader.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_HYBRID_SPACEEXTEXT_H
#define NETLIFT_FRONTENDS_HYBRID_SPACEEXTEXT_H

#include "llvm/ADT/StringRef.h"

#include <vector>

namespace netlift::spaceex {

/// The conjuncts of `a & b && c`, split at the top-level '&' (not inside
/// parentheses), trimmed, empty ones left out.
std::vector<llvm::StringRef> conjuncts(llvm::StringRef text);

/// The comparison operators of `text` outside parentheses, in order, as
/// (position, length): `<`, `<=`, `>`, `>=`, `==`; with `singleEquals`
/// also `=` (SpaceEx's configurations write it for `==`) and `!=`.
std::vector<std::pair<size_t, size_t>> comparisonOperators(llvm::StringRef text,
                                                           bool singleEquals);

/// A chained comparison `a <= x <= b` as the comparisons it chains, `a <= x`
/// and `x <= b`; anything else as it is.
std::vector<llvm::StringRef> unchain(llvm::StringRef comparison);

} // namespace netlift::spaceex

#endif
