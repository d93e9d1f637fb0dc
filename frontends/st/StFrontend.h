//===- StFrontend.h - Structured Text into the PLC model --------*- C++ -*-===//
//
// Parses IEC 61131-3 Structured Text (ST.g4 over the hand-written StLexer)
// and builds the PLC model (frontends/plc/PlcAst.h). The text is a slice of
// a SourceMgr buffer — a whole .st file, or the CDATA of a TwinCAT or
// PLCopen XML file — so every diagnostic points into the file the user
// opened. Syntax errors are reported once, at the first mistake; constructs
// netlift refuses are named where they stand.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_ST_STFRONTEND_H
#define NETLIFT_FRONTENDS_ST_STFRONTEND_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

namespace netlift::st {

/// Syntax errors are reported one per statement; after this many in one
/// file the rest are not worth reading.
inline constexpr unsigned kMaxSyntaxErrors = 20;

/// How long parts of a file are parsed. ANTLR keeps every token and tree
/// node of a parse alive until the parser dies, so POU bodies and VAR
/// blocks of at least `longPartTokens` tokens are parsed in groups of about
/// `groupTokens` tokens, each with a parser of its own (tests set them
/// small to take that path on small inputs).
struct ParseOptions {
  unsigned longPartTokens = 16384;
  unsigned groupTokens = 4096;
};

/// Parses `text` (inside a buffer of diag's SourceMgr) and appends what it
/// declares to `unit`. Returns false after reporting an error.
bool parseStructuredText(llvm::StringRef text, DiagEngine &diag,
                         plc::Unit &unit, const ParseOptions &options = {});

/// Parses a statement list alone (a POU body kept apart from its
/// declarations, as in PLCopen XML) and appends it to `out`.
bool parseStatements(llvm::StringRef text, DiagEngine &diag, plc::Unit &unit,
                     plc::StmtList &out);

/// Parses an algorithm's body that VAR_TEMP blocks may open (IEC 61499
/// algorithms as 4diac writes them): the temporaries into `temps`, the
/// statements into `out`.
bool parseAlgorithmBody(llvm::StringRef text, DiagEngine &diag, plc::Unit &unit,
                        std::vector<plc::VarDecl *> &temps, plc::StmtList &out);

/// Parses one METHOD ... END_METHOD (a method of an IEC 61499 basic FB as
/// 4diac IDE 3 writes it) as a method of `owner`; null after reporting an
/// error.
plc::Pou *parseMethod(llvm::StringRef text, DiagEngine &diag, plc::Unit &unit,
                      plc::Pou *owner);
/// Parses a method's body alone (variable blocks, statements: 4diac IDE 3
/// keeps the name and the result type apart) as method `name` of `owner`
/// returning `resultType` (none if empty); null after reporting an error.
plc::Pou *parseMethodBody(llvm::StringRef text, llvm::StringRef name,
                          llvm::StringRef resultType, llvm::SMLoc at,
                          DiagEngine &diag, plc::Unit &unit, plc::Pou *owner);

/// Parses one ST expression (used for pragma values and --ranges files).
plc::Expr *parseStExpression(llvm::StringRef text, DiagEngine &diag,
                             plc::Unit &unit);

/// Parses one initial value: an expression, `[1, 2, 3(0)]` or
/// `(x := 1, y := 2)` (IEC 61499 InitialValue attributes).
plc::Initializer *parseStInitializer(llvm::StringRef text, DiagEngine &diag,
                                     plc::Unit &unit);

/// The value of a duration literal such as `T#1h2m3.5s` in nanoseconds;
/// false (and `error` set) when it is malformed.
bool parseDuration(llvm::StringRef literal, int64_t &ns, std::string &error);

/// The value of an integer literal (`1_000`, `16#FF`, `2#1010`).
bool parseIntegerLiteral(llvm::StringRef text, int64_t &value,
                         bool *beyondInt64 = nullptr);

} // namespace netlift::st

#endif
