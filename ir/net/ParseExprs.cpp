//===- ParseExprs.cpp - NetIR text parser: expressions, statements --------===//
#include "ir/net/ParserImpl.h"
#include "ir/net/StringOps.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::net::detail;

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

Expr *Parser::parseExpr() {
  DepthGuard g(*this);
  if (!g.ok)
    return nullptr;
  return parseTernary();
}

Expr *Parser::parseTernary() {
  Expr *c = parseBinary(1);
  if (!c || !tok.is(Tok::Question))
    return c;
  SMLoc loc = tok.loc();
  consume();
  Expr *a = parseExpr();
  if (!a || !expect(Tok::Colon, "':' in a conditional expression"))
    return nullptr;
  Expr *e = parseExpr();
  if (!e)
    return nullptr;
  return b.cond(c, a, e, loc);
}

bool Parser::peekBinaryOp(BinaryOp &op) const {
  switch (tok.kind) {
  case Tok::Ident:
    if (tok.text == "or")
      op = BinaryOp::Or;
    else if (tok.text == "xor")
      op = BinaryOp::Xor;
    else if (tok.text == "and")
      op = BinaryOp::And;
    else
      return false;
    return true;
  case Tok::EqEq:
    op = BinaryOp::Eq;
    return true;
  case Tok::Ne:
    op = BinaryOp::Ne;
    return true;
  case Tok::Lt:
    op = BinaryOp::Lt;
    return true;
  case Tok::Le:
    op = BinaryOp::Le;
    return true;
  case Tok::Gt:
    op = BinaryOp::Gt;
    return true;
  case Tok::Ge:
    op = BinaryOp::Ge;
    return true;
  case Tok::Pipe:
    op = BinaryOp::BitOr;
    return true;
  case Tok::Caret:
    op = BinaryOp::BitXor;
    return true;
  case Tok::Amp:
    op = BinaryOp::BitAnd;
    return true;
  case Tok::Shl:
    op = BinaryOp::Shl;
    return true;
  case Tok::Shr:
    op = BinaryOp::Shr;
    return true;
  case Tok::Plus:
    op = BinaryOp::Add;
    return true;
  case Tok::Minus:
    op = BinaryOp::Sub;
    return true;
  case Tok::Star:
    op = BinaryOp::Mul;
    return true;
  case Tok::Slash:
    op = BinaryOp::Div;
    return true;
  case Tok::Percent:
    op = BinaryOp::Mod;
    return true;
  default:
    return false;
  }
}

Expr *Parser::parseBinary(int minPrec) {
  Expr *lhs;
  if (tok.isIdent("not")) {
    // `not` binds looser than comparisons: `not a == b` is `not (a == b)`.
    SMLoc loc = tok.loc();
    consume();
    DepthGuard g(*this);
    if (!g.ok)
      return nullptr;
    Expr *operand = parseBinary(4);
    if (!operand)
      return nullptr;
    lhs = b.unary(UnaryOp::Not, operand, loc);
  } else {
    lhs = parseUnary();
  }
  if (!lhs)
    return nullptr;
  BinaryOp op;
  while (peekBinaryOp(op) && precedence(op) >= minPrec) {
    SMLoc loc = tok.loc();
    consume();
    int p = precedence(op);
    Expr *rhs = parseBinary(p + 1);
    if (!rhs)
      return nullptr;
    lhs = b.binary(op, lhs, rhs, loc);
    BinaryOp next;
    if (isComparison(op) && peekBinaryOp(next) && isComparison(next)) {
      errorHere("comparisons do not chain; use parentheses or 'and'");
      return nullptr;
    }
  }
  return lhs;
}

Expr *Parser::parseUnary() {
  if (tok.is(Tok::Minus) || tok.is(Tok::Tilde)) {
    UnaryOp op = tok.is(Tok::Minus) ? UnaryOp::Neg : UnaryOp::BitNot;
    SMLoc loc = tok.loc();
    consume();
    DepthGuard g(*this);
    if (!g.ok)
      return nullptr;
    Expr *a = parseUnary();
    return a ? b.unary(op, a, loc) : nullptr;
  }
  return parsePostfix();
}

Expr *Parser::parsePostfix() {
  Expr *e = parsePrimary();
  while (e) {
    if (tok.is(Tok::LBrack)) {
      SMLoc loc = tok.loc();
      consume();
      Expr *i = parseExpr();
      if (!i || !expect(Tok::RBrack, "']'"))
        return nullptr;
      e = b.index(e, i, loc);
    } else if (tok.is(Tok::Dot)) {
      SMLoc loc = tok.loc();
      consume();
      StringRef f;
      SMLoc floc;
      if (!parseName(f, floc, "a field name"))
        return nullptr;
      // `a[i].x.y` arrives as one name "x.y": split into fields.
      llvm::SmallVector<StringRef, 4> parts;
      f.split(parts, '.');
      for (StringRef part : parts)
        e = b.field(e, part, loc);
    } else {
      break;
    }
  }
  return e;
}

Expr *Parser::parsePrimary() {
  SMLoc loc = tok.loc();
  switch (tok.kind) {
  case Tok::Int: {
    int64_t v;
    if (tok.text.getAsInteger(10, v)) {
      errorHere("integer literal '" + tok.text + "' is too large");
      return nullptr;
    }
    consume();
    return b.intLit(v, loc);
  }
  case Tok::Real: {
    double v = strtod(tok.text.str().c_str(), nullptr);
    consume();
    return b.realLit(v, loc);
  }
  case Tok::String: {
    StringValue chars;
    size_t at = 0;
    StringRef body = tok.text.drop_front().drop_back();
    if (auto err = parseStringLiteral(body, chars, at)) {
      error(SMLoc::getFromPointer(body.data() + at), *err);
      return nullptr;
    }
    consume();
    return b.stringLit(llvm::ArrayRef<char16_t>(chars.data(), chars.size()),
                       loc);
  }
  case Tok::LParen: {
    consume();
    Expr *e = parseExpr();
    if (!e || !expect(Tok::RParen, "')'"))
      return nullptr;
    return e;
  }
  case Tok::LBrack:
  case Tok::LBrace: {
    // An aggregate initial value: `[e, ...]` or `{field: e, ...}`.
    bool record = tok.is(Tok::LBrace);
    consume();
    llvm::SmallVector<Expr *, 8> elems;
    llvm::SmallVector<StringRef, 8> names;
    Tok close = record ? Tok::RBrace : Tok::RBrack;
    if (!tok.is(close)) {
      do {
        if (record) {
          if (!tok.is(Tok::Ident)) {
            errorHere("expected a field name, found " + describe());
            return nullptr;
          }
          names.push_back(tok.text);
          consume();
          if (!expect(Tok::Colon, "':'"))
            return nullptr;
        }
        Expr *e = parseExpr();
        if (!e)
          return nullptr;
        elems.push_back(e);
      } while (tok.is(Tok::Comma) && (consume(), true));
    }
    if (!expect(close, record ? "'}'" : "']'"))
      return nullptr;
    return b.aggregate(elems, names, loc);
  }
  case Tok::Ident: {
    StringRef n = tok.text;
    if (n == "true" || n == "false") {
      consume();
      return b.boolLit(n == "true", loc);
    }
    if (n == "inf") { // a reserved name: the real infinity
      consume();
      return b.realLit(INFINITY, loc);
    }
    if (n == "string" || n == "wstring") {
      // A conversion to a string type: `string[20](x)`.
      const Type *to;
      if (!parseType(to, false) || !expect(Tok::LParen, "'(' after the type"))
        return nullptr;
      return parseCallArgs(Builtin::Convert, to->str(), loc, to);
    }
    if (Lexer peek = lex; peek.next().is(Tok::LParen)) {
      std::optional<Builtin> fn = builtinNamed(n);
      const Type *to = fn ? nullptr : conversionTarget(n);
      if (to)
        fn = Builtin::Convert;
      if (fn) {
        consume();
        consume();
        return parseCallArgs(*fn, n, loc, to);
      }
    }
    if (isReservedWord(n)) {
      errorHere("expected an expression, found '" + n + "'");
      return nullptr;
    }
    consume();
    if (tok.is(Tok::Hash)) {
      // Typed enumerator: Color#red.
      consume();
      if (!tok.is(Tok::Ident)) {
        errorHere("expected an enumerator after '#', found " + describe());
        return nullptr;
      }
      StringRef full(n.data(), tok.text.end() - n.data());
      consume();
      return b.ref(full, loc);
    }
    return b.ref(n, loc);
  }
  default:
    errorHere("expected an expression, found " + describe());
    return nullptr;
  }
}

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

bool Parser::parseBlock(Block &out) {
  DepthGuard g(*this);
  if (!g.ok)
    return false;
  if (!expect(Tok::LBrace, "'{'"))
    return false;
  llvm::SmallVector<Stmt *, 8> stmts;
  while (!tok.is(Tok::RBrace)) {
    if (tok.is(Tok::Eof))
      return errorHere("expected '}' to end the block");
    Stmt *s = parseStmt();
    if (!s || (tok.is(Tok::At) && !parseStmtLocation(s)))
      return false;
    stmts.push_back(s);
  }
  consume();
  out = design.copy(llvm::ArrayRef<Stmt *>(stmts));
  return true;
}

Stmt *Parser::parseStmt() {
  if (tok.isIdent("if"))
    return parseIf();
  if (tok.isIdent("while") || tok.isIdent("repeat"))
    return parseWhile();
  if (tok.isIdent("case"))
    return parseCase();
  if (tok.isIdent("for"))
    return parseFor();
  SMLoc loc = tok.loc();
  Expr *target = parsePostfix();
  if (!target)
    return nullptr;
  if (!expect(Tok::Assign, "':=' in an assignment"))
    return nullptr;
  Expr *value = parseExpr();
  if (!value || !expect(Tok::Semi, "';'"))
    return nullptr;
  return b.assign(target, value, loc);
}

Stmt *Parser::parseIf() {
  SMLoc loc = tok.loc();
  consume();
  llvm::SmallVector<IfArm, 2> arms;
  Expr *c = parseExpr();
  Block body;
  if (!c || !parseBlock(body))
    return nullptr;
  arms.push_back({c, body});
  while (tok.isIdent("elif")) {
    consume();
    c = parseExpr();
    if (!c || !parseBlock(body))
      return nullptr;
    arms.push_back({c, body});
  }
  Block elseBody;
  bool hasElse = false;
  if (tok.isIdent("else")) {
    consume();
    hasElse = true;
    if (!parseBlock(elseBody))
      return nullptr;
  }
  return b.ifStmt(arms, hasElse, elseBody, loc);
}

Stmt *Parser::parseCase() {
  SMLoc loc = tok.loc();
  consume();
  Expr *sel = parseExpr();
  if (!sel || !expect(Tok::LBrace, "'{'"))
    return nullptr;
  std::vector<CaseArm> arms;
  Block elseBody;
  bool hasElse = false;
  while (!tok.is(Tok::RBrace)) {
    if (tok.isIdent("else")) {
      if (hasElse) {
        errorHere("'else' given twice in a case");
        return nullptr;
      }
      consume();
      hasElse = true;
      if (!parseBlock(elseBody))
        return nullptr;
      continue;
    }
    if (hasElse) {
      errorHere("the 'else' arm must come last in a case");
      return nullptr;
    }
    llvm::SmallVector<CaseLabel, 4> labels;
    do {
      Expr *lo = parseBinary(6);
      if (!lo)
        return nullptr;
      Expr *hi = nullptr;
      if (tok.is(Tok::DotDot)) {
        consume();
        if (!(hi = parseBinary(6)))
          return nullptr;
      }
      labels.push_back({lo, hi});
    } while (tok.is(Tok::Comma) && (consume(), true));
    Block body;
    if (!parseBlock(body))
      return nullptr;
    arms.push_back({design.copy(llvm::ArrayRef<CaseLabel>(labels)), body});
  }
  consume();
  return b.caseStmt(sel, arms, hasElse, elseBody, loc);
}

Stmt *Parser::parseFor() {
  SMLoc loc = tok.loc();
  consume();
  StringRef var;
  SMLoc vloc;
  if (!parseSimpleName(var, vloc, "a loop variable") || !expectIdent("in"))
    return nullptr;
  Expr *lo = parseBinary(6);
  if (!lo || !expect(Tok::DotDot, "'..'"))
    return nullptr;
  Expr *hi = parseBinary(6);
  Block body;
  if (!hi || !parseBlock(body))
    return nullptr;
  return b.forStmt(var, lo, hi, body, loc);
}

Stmt *Parser::parseWhile() {
  SMLoc loc = tok.loc();
  bool testAfter = tok.isIdent("repeat");
  consume();
  Expr *c = nullptr;
  Block body;
  if (!testAfter && !(c = parseExpr()))
    return nullptr;
  if (!parseBlock(body))
    return nullptr;
  if (testAfter && (!expectIdent("until") || !(c = parseExpr()) ||
                    !expect(Tok::Semi, "';'")))
    return nullptr;
  return b.whileStmt(c, body, testAfter, loc);
}

Expr *Parser::parseCallArgs(Builtin fn, StringRef name, SMLoc loc,
                            const Type *to) {
  llvm::SmallVector<Expr *, 4> args;
  if (!tok.is(Tok::RParen)) {
    do {
      Expr *a = parseExpr();
      if (!a)
        return nullptr;
      args.push_back(a);
    } while (tok.is(Tok::Comma) && (consume(), true));
  }
  if (!expect(Tok::RParen, "')'"))
    return nullptr;
  unsigned want = arity(fn);
  if (args.size() != want) {
    error(loc, name + "() takes " + llvm::Twine(want) + " argument" +
                   (want == 1 ? "" : "s"));
    return nullptr;
  }
  return b.call(fn, args, loc, to);
}

const Type *Parser::conversionTarget(StringRef word) {
  if (word == "bool")
    return design.types.getBool();
  if (word == "real32" || word == "real64")
    return design.types.getFloat(word == "real32" ? 32 : 64);
  bool isSigned = word.startswith("int");
  unsigned width;
  if ((isSigned || word.startswith("uint")) &&
      !word.drop_front(isSigned ? 3 : 4).getAsInteger(10, width) &&
      (width == 8 || width == 16 || width == 32 || width == 64))
    return design.types.getInt(width, isSigned, Overflow::Error);
  return nullptr;
}
