//===- Parser.h - NetIR text parser -----------------------------*- C++ -*-===//
//
// Reads the NetIR text form (docs/netir.md) into a Design. Hand-written
// recursive descent in the LLVM style: the first syntax error is reported as
// `file:line:col: error:` with the line and a caret, and parsing stops, so a
// mistake never produces a cascade. Names used in arcs are resolved at the
// end of each module (declaration order is free); names in expressions are
// resolved by the verifier.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_PARSER_H
#define NETLIFT_IR_NET_PARSER_H

#include "ir/net/Lexer.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <memory>

namespace netlift::net {

/// Parses buffer `bufferID` of the diagnostic engine's SourceMgr into
/// `design`. Returns false (after reporting) on a syntax error.
bool parseNetIR(unsigned bufferID, DiagEngine &diag, Design &design);

/// Parses buffer `bufferID` as one expression (e.g. a predicate given on
/// the command line). Null after reporting an error.
Expr *parseExpression(unsigned bufferID, DiagEngine &diag, Design &design);

namespace detail {
class Parser;
}

/// NetIR's expression, type and statement syntax for other text formats
/// that embed it (the .hyb charts): the host reader walks the shared token
/// stream and asks for one construct at the current token. Locations stay
/// in the host buffer, and the first error stops everything as in NetIR.
class EmbeddedParser {
public:
  EmbeddedParser(llvm::StringRef buffer, DiagEngine &diag, Design &design);
  ~EmbeddedParser();
  const Token &token() const;
  void consume();
  bool expect(Tok k, llvm::StringRef what);
  bool errorHere(const llvm::Twine &msg);
  bool error(llvm::SMLoc loc, const llvm::Twine &msg);
  Expr *expr();
  /// `{ statement* }`
  bool block(Block &out);
  /// A finite NetIR type (`bool`, `0..9`, `int16`, ...).
  bool type(const Type *&t);
  /// An unqualified, non-reserved name.
  bool name(llvm::StringRef &n, llvm::SMLoc &loc, llvm::StringRef what);
  bool failed() const;

private:
  std::unique_ptr<detail::Parser> impl;
};

} // namespace netlift::net

#endif
