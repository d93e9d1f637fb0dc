//===- StConditionals.h - CODESYS conditional compilation -------*- C++ -*-===//
//
// CODESYS's and TwinCAT's conditional compilation pragmas, evaluated like a
// preprocessor before ST is parsed: `{IF defined(NAME)}` ... `{ELSIF ...}`
// ... `{ELSE}` ... `{END_IF}`, with `{define NAME [value]}` and
// `{undefine NAME}`. The names defined are -D's, a .plcproj's compiler
// defines and the file's own {define}s (none by default). The text of the
// branches not taken and the directives themselves are blanked, line ends
// kept, so every location in what is parsed is the file's own.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_ST_STCONDITIONALS_H
#define NETLIFT_FRONTENDS_ST_STCONDITIONALS_H

#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringRef.h"

#include <map>
#include <optional>
#include <string>

namespace netlift::st {

/// Names defined for conditional compilation, upper-case, with their
/// values ("" when defined without one).
using Defines = std::map<std::string, std::string>;

/// `text` with its conditional compilation resolved; `text` itself when it
/// has none (`changed` false). None after reporting an error: an
/// unbalanced directive, or a condition netlift cannot decide
/// (`defined(variable: x)`, `hastype`, `hasattribute`, ... refused by
/// name, never guessed).
std::optional<std::string> resolveConditionals(llvm::StringRef text,
                                               DiagEngine &diag,
                                               Defines defines, bool &changed);

} // namespace netlift::st

#endif
