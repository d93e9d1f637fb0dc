//===- OutputFile.h - writing an output whole or not at all -----*- C++ -*-===//
//
// Every file netlift writes goes through writeOutputFile: the text is
// written to a temporary next to the target and renamed into place only
// when all of it was written, so an error never leaves a half-written
// output behind. "-" is standard output; a device or pipe (/dev/null, a
// FIFO) is written in place.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_OUTPUTFILE_H
#define NETLIFT_IR_SUPPORT_OUTPUTFILE_H

#include "ir/support/Diagnostics.h"

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/raw_ostream.h"

namespace netlift {

/// Writes what `body` prints to `path`; false after reporting through
/// `diag` (nothing is left at `path` then).
bool writeOutputFile(llvm::StringRef path,
                     llvm::function_ref<void(llvm::raw_ostream &)> body,
                     DiagEngine &diag);

} // namespace netlift

#endif
