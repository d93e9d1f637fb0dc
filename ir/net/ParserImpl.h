//===- ParserImpl.h - the NetIR parser's state ------------------*- C++ -*-===//
//
// Internal to ir/net: the recursive-descent Parser behind parseNetIR,
// parseExpression and EmbeddedParser, shared by Parser.cpp (files, types,
// modules and their items) and ParseExprs.cpp (expressions and action
// statements). Parser.h is the API.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_PARSERIMPL_H
#define NETLIFT_IR_NET_PARSERIMPL_H

#include "ir/net/Builder.h"
#include "ir/net/Lexer.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringSwitch.h"

#include <map>

namespace netlift::net::detail {

using llvm::SMLoc;
using llvm::StringRef;

/// Expressions and blocks nest at most this deep; deeper input is refused
/// rather than allowed to exhaust the stack.
constexpr unsigned kMaxDepth = 200;

class Parser {
public:
  Parser(StringRef buf, DiagEngine &diag, Design &design)
      : lex(buf), diag(diag), design(design), b(design),
        bufferStart(buf.begin()), bufferEnd(buf.end()) {
    tok = lex.next();
  }

  bool parseFile();
  // Entry points for EmbeddedParser (formats that embed NetIR syntax).
  const Token &current() const { return tok; }
  void advance() { consume(); }
  bool expectToken(Tok k, StringRef what) { return expect(k, what); }
  bool reportHere(const llvm::Twine &msg) { return errorHere(msg); }
  bool report(SMLoc loc, const llvm::Twine &msg) { return error(loc, msg); }
  Expr *expression() { return parseExpr(); }
  bool statements(Block &out) { return parseBlock(out); }
  bool typeDecl(const Type *&t) { return parseType(t, false); }
  bool name(StringRef &n, SMLoc &loc, StringRef what) {
    return parseSimpleName(n, loc, what);
  }
  bool hasFailed() const { return failed; }
  Expr *parseWholeExpression() {
    Expr *e = parseExpr();
    if (e && !tok.is(Tok::Eof)) {
      // `x = 1` is the commonest slip in a property or predicate.
      errorHere("unexpected " + describe() + " after the expression" +
                (tok.is(Tok::Equal) ? "; use == to compare" : ""));
      return nullptr;
    }
    return e;
  }

private:
  // Token handling -------------------------------------------------------
  void consume() { tok = lex.next(); }
  bool error(SMLoc loc, const llvm::Twine &msg) {
    if (!failed)
      diag.error(loc, msg);
    failed = true;
    return false;
  }
  bool errorHere(const llvm::Twine &msg) {
    if (tok.is(Tok::Error)) {
      if (lex.unterminatedComment)
        return error(tok.loc(), "unterminated /* comment");
      if (tok.text == "\"")
        return error(tok.loc(), "unterminated string (a string ends with "
                                "'\"' on the line where it starts)");
      unsigned char c = tok.text.empty() ? 0 : tok.text[0];
      if (c >= 0x20 && c < 0x7f)
        return error(tok.loc(),
                     llvm::Twine("unexpected character '") + tok.text + "'");
      char hex[8];
      snprintf(hex, sizeof hex, "0x%02X", c);
      return error(tok.loc(), llvm::Twine("unexpected byte ") + hex +
                                  " (is this a NetIR text file?)");
    }
    return error(tok.loc(), msg);
  }
  std::string describe() const {
    if (tok.is(Tok::Eof))
      return "end of file";
    return ("'" + tok.text + "'").str();
  }
  bool expect(Tok k, StringRef what) {
    if (tok.is(k)) {
      consume();
      return true;
    }
    return errorHere("expected " + what + ", found " + describe());
  }
  bool expectIdent(StringRef kw) {
    if (tok.isIdent(kw)) {
      consume();
      return true;
    }
    return errorHere("expected '" + kw + "', found " + describe());
  }
  bool parseName(StringRef &name, SMLoc &loc, StringRef what) {
    if (!tok.is(Tok::Ident))
      return errorHere("expected " + what + ", found " + describe());
    if (isReservedWord(tok.text))
      return errorHere("'" + tok.text + "' is a reserved word and cannot be " +
                       "used as " + what);
    name = tok.text;
    loc = tok.loc();
    consume();
    return true;
  }
  bool parseSimpleName(StringRef &name, SMLoc &loc, StringRef what) {
    if (!parseName(name, loc, what))
      return false;
    if (name.contains('.'))
      return error(loc,
                   what + " '" + name + "' must not be qualified (no '.')");
    return true;
  }
  bool parseInt(int64_t &v, StringRef what);
  bool parseUInt32(uint32_t &v, StringRef what, bool allowInf);
  bool parseSignedInt(int64_t &v, StringRef what);
  bool parseRealBound(double &v);
  /// A bound of a rectangular flow's rates: an expression, or `inf` /
  /// `-inf` (a rate SpaceEx leaves unconstrained).
  bool parseRateBound(Expr *&e);

  // Top level ------------------------------------------------------------
  bool parseTimescale();
  bool parseTypeDecl();
  bool parseType(const Type *&type, bool allowReal);
  /// The type a conversion spelled `word(...)` converts to, or null.
  const Type *conversionTarget(StringRef word);
  /// The arguments of a call whose `(` is consumed, checked against the
  /// built-in's arity.
  Expr *parseCallArgs(Builtin fn, StringRef name, SMLoc loc, const Type *to);
  bool parseModule(bool isSystem);
  bool parseModuleItem();
  bool parsePortDecl(PortKind kind);
  bool parsePlaceDecl();
  bool parseTransDecl();
  bool parseArcList(bool pre, llvm::SmallVectorImpl<PreArc> &preArcs,
                    llvm::SmallVectorImpl<PostArc> &postArcs,
                    llvm::SmallVectorImpl<SMLoc> &locs,
                    llvm::SmallVectorImpl<StringRef> &names);
  bool parseVarDecl(bool isClock);
  bool parseRealDecl();
  bool parseInitAndSemi(Expr *&init);
  bool parseFlowDecl();
  bool parseInvariantDecl();
  bool parseInstDecl();
  bool parseConnectDecl();
  bool parseAttrDecl();
  /// The text between a string token's quotes, `\"` `\\` `\n` `\t` read.
  bool parseQuotedText(std::string &out);
  // Source locations (ParseLocations.cpp) ----------------------------------
  bool parseSourceDecl();
  /// `@N:line:col` after a statement: where it was lowered from.
  bool parseStmtLocation(Stmt *s);
  /// Points the statements read with `@` into their files (loaded into the
  /// SourceMgr, or stand-ins when a file is gone or no longer matches).
  void resolveStmtLocations();
  bool parseEndpoint(Endpoint &e);
  bool parseDefinition();
  bool resolveModuleFixups();
  bool parseTransDeclBody();

  // Expressions and statements ---------------------------------------------
  Expr *parseExpr();
  Expr *parseTernary();
  Expr *parseBinary(int minPrec);
  Expr *parseUnary();
  Expr *parsePostfix();
  Expr *parsePrimary();
  bool peekBinaryOp(BinaryOp &op) const;
  bool parseBlock(Block &out);
  Stmt *parseStmt();
  Stmt *parseIf();
  Stmt *parseCase();
  Stmt *parseFor();
  Stmt *parseWhile();

  struct DepthGuard {
    Parser &p;
    bool ok;
    explicit DepthGuard(Parser &p) : p(p), ok(++p.depth <= kMaxDepth) {
      if (!ok)
        p.errorHere("nesting too deep (more than " + llvm::Twine(kMaxDepth) +
                    " levels)");
    }
    ~DepthGuard() { --p.depth; }
  };

  Lexer lex;
  Token tok;
  DiagEngine &diag;
  Design &design;
  Builder b;
  bool failed = false;
  bool sawTimescale = false; // per file: two in one file is an error
  unsigned depth = 0;
  const char *bufferStart, *bufferEnd;
  bool reservedForModule = false;
  static constexpr size_t kLargeModule = 4096;
  void reserveForLargeModule();

  // Names used before their declaration, resolved at the end of a module.
  enum class FixKind : uint8_t {
    PrePlace,
    PostPlace,
    Event,
    Emit,
    FlowPlace,
    InvariantPlace
  };
  struct Fixup {
    FixKind kind;
    uint32_t trans; // or flow index
    uint32_t slot;
    StringRef name;
    SMLoc loc;
  };
  std::vector<Fixup> fixups;
  llvm::SmallVector<Fixup, 8> pendingInTrans;
  /// Points the arc/flow slot of `f` at `s` (the symbol its name denotes),
  /// or reports why it cannot.
  bool applyFixup(const Fixup &f, Symbol s);
  // Output definitions written as `name = expr;`.
  struct Definition {
    StringRef name;
    SMLoc loc;
    Expr *expr;
  };
  std::vector<Definition> definitions;
  // `source N = "file";` and the statements that refer to it.
  struct SourceFile {
    std::string path;
    SMLoc declLoc;
  };
  std::map<int64_t, SourceFile> sourceFiles;
  struct PendingLocation {
    Stmt *stmt;
    int64_t file;
    unsigned line, col;
  };
  std::vector<PendingLocation> pendingLocations;
};

} // namespace netlift::net::detail

#endif
