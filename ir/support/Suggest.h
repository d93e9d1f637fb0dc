//===- Suggest.h - "did you mean" for misspelt names -------------*- C++
//-*-===//
//
// Every message about a name netlift does not know (a subcommand, a pass,
// a module, a variable, a type, a name in a ranges file) offers the
// closest known one, so that a typo leads somewhere.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_SUGGEST_H
#define NETLIFT_IR_SUPPORT_SUGGEST_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"

#include <string>

namespace netlift {

/// The candidate closest to `name` (case-insensitive edit distance of at
/// most two, or a third of a long name, and less than its length), or ""
/// when none is that close. Ties go to the first candidate.
std::string closestName(llvm::StringRef name,
                        llvm::ArrayRef<std::string> candidates);

/// "; did you mean 'x'?" for the closest candidate, or "".
std::string didYouMean(llvm::StringRef name,
                       llvm::ArrayRef<std::string> candidates);

} // namespace netlift

#endif
