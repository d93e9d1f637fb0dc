//===- StAstBuilder.h - ST parse trees into the PLC model -------*- C++ -*-===//
//
// Internal to frontends/st: the AstBuilder that walks an ST parse tree once
// and builds the PLC model (frontends/plc/PlcAst.h), shared by the files
// that implement it by concept — StFrontend.cpp (the compilation unit,
// declarations, types, statements, expressions) and StPous.cpp (POUs and
// what they hold: methods, properties, actions, SFC elements, classes and
// interfaces). StFrontend.h is the API.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_ST_STASTBUILDER_H
#define NETLIFT_FRONTENDS_ST_STASTBUILDER_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

#include "ST.h"

#include <cassert>
#include <map>
#include <optional>
#include <typeinfo>
#include <vector>

namespace netlift::st::detail {

using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;
using P = stgen::ST;

/// `c` as the labelled alternative T (a leaf class of the parse tree), or
/// null. A node of a labelled alternative is of exactly that class, so the
/// addresses of the type_info objects decide; dynamic_cast, whose misses
/// compare type names with strcmp in libstdc++, took a sixth of the
/// frontend's time on long programs.
template <class T> T *alt(antlr4::ParserRuleContext *c) {
  bool is = c && &typeid(*c) == &typeid(T);
  assert(is == (dynamic_cast<T *>(c) != nullptr) &&
         "alt<> is for leaf classes only");
  return is ? static_cast<T *>(c) : nullptr;
}

/// Walks the parse tree once. The first refusal or malformed literal stops
/// the walk (`failed`), so one mistake gives one message.
class AstBuilder {
public:
  AstBuilder(StringRef text, DiagEngine &diag, Unit &unit,
             antlr4::BufferedTokenStream &tokens)
      : text(text), diag(diag), unit(unit), tokens(tokens) {}

  /// Bodies and VAR blocks the parse skipped, as groups of whole statements
  /// or declarations, by the offset of the token closing them.
  const std::map<size_t, std::vector<StringRef>> *skipped = nullptr;
  /// Adds the variables `d` declares in a block of `section`.
  void declare(P::VarDeclContext *d, VarSection section, bool constant,
               bool retain, std::vector<VarDecl *> &out);

  bool build(P::CompilationUnitContext *cu);
  Expr *expr(P::ExpressionContext *ctx);
  void statements(P::StatementListContext *c, StmtList &out);
  /// A POU body: statements and labels (Stmt Label), in order.
  void bodyStatements(P::BodyStatementListContext *c, StmtList &out);
  void varBlock(P::VarBlockContext *c, std::vector<VarDecl *> &out);
  /// Refuses the pragmas in a body that change what the program does.
  void bodyPragmas(P::BodyStatementListContext *c);
  Initializer *initializer(P::InitializerContext *c);
  /// A method of `owner` declared alone (Pou::methodOf set, listed in
  /// owner->methods).
  Pou *methodOf(P::MethodDeclContext *c, Pou *owner) {
    return method(c, owner);
  }
  /// A method of `owner` named `name` whose body (variable blocks and
  /// statements) is `c`, returning `resultType` (none if empty).
  Pou *methodFromBody(P::MethodBodyOnlyContext *c, StringRef name,
                      StringRef resultType, SMLoc at, Pou *owner);

  bool failed = false;

private:
  SMLoc loc(antlr4::Token *t) const {
    return SMLoc::getFromPointer(text.data() + t->getStartIndex());
  }
  SMLoc loc(antlr4::ParserRuleContext *c) const { return loc(c->getStart()); }
  SMLoc loc(antlr4::tree::TerminalNode *n) const { return loc(n->getSymbol()); }
  std::nullptr_t refuse(SMLoc at, const llvm::Twine &what) {
    if (!failed)
      diag.error(at, what);
    failed = true;
    return nullptr;
  }
  // Building a POU, a refusal is kept on it (reported if it is translated)
  // instead of stopping the file.
  template <typename Ctx, typename Build>
  void deferRefusals(PouKind kind, Ctx *c, Build build);
  TypeSyntax *refusedType(SMLoc at, const std::string &what) {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Refused, at);
    ts->refused = what;
    return ts;
  }
  std::vector<Attribute> pragmasBefore(antlr4::Token *t);
  /// The POU's METHODs and PROPERTYs are refused; its SFC elements and
  /// ACTIONs become its chart (an ACTION without steps is a CODESYS
  /// action, refused).
  bool members(const std::vector<P::FbMemberContext *> &ms, StringRef where,
               Pou *pou);
  bool sfcStep(P::SfcStepContext *c, SfcChart &chart);
  bool sfcTransition(P::SfcTransitionContext *c, SfcChart &chart, Pou *pou);

  template <typename Ctx> Pou *pou(PouKind kind, Ctx *c);
  Pou *program(P::ProgramDeclContext *c);
  Pou *functionBlock(P::FunctionBlockDeclContext *c);
  Pou *method(P::MethodDeclContext *c, Pou *owner);
  void refusedElement(P::RefusedElementContext *r);
  Pou *classDecl(P::ClassDeclContext *c);
  Pou *interfaceDecl(P::InterfaceDeclContext *c);
  void actionsBlock(P::ActionsBlockContext *c);
  bool property(P::PropertyDeclContext *c, Pou *owner);
  Pou *function(P::FunctionDeclContext *c);
  void typeDecl(P::TypeDeclContext *c);
  void configuration(P::ConfigurationDeclContext *c);
  /// VAR_ACCESS: read-only access paths noted, read-write ones refused.
  void accessBlock(P::VarBlockContext *c);
  TypeSyntax *typeSpec(P::TypeSpecContext *c);
  TypeSyntax *typeSpec0(P::TypeSpec0Context *c);
  Initializer *
  arrayInitializer(antlr4::ParserRuleContext *at,
                   const std::vector<P::ArrayInitElemContext *> &elems);
  Stmt *statement(P::StatementContext *c);
  Stmt *setReset(P::SetResetStmtContext *c);
  Expr *primary(P::PrimaryContext *c);
  Expr *variable(P::VariableContext *c);
  Expr *literal(P::LiteralContext *c);
  Expr *callOf(Expr *callee, P::VariableContext *written, SMLoc at);
  Expr *chained(Expr *first,
                const std::vector<P::CallSuffixContext *> &suffixes);
  bool callArgs(const std::vector<P::CallArgContext *> &args,
                std::vector<CallArg> &out);

  StringRef text;
  DiagEngine &diag;
  Unit &unit;
  antlr4::BufferedTokenStream &tokens;
};

/// Builds one POU; a construct netlift refuses in it is kept on the POU
/// (`refusal`) and the file goes on, so a library's POUs nobody translates
/// may hold what netlift does not model. Syntax errors are the parser's
/// and stop the file as before.
template <typename Ctx, typename Build>
void AstBuilder::deferRefusals(PouKind kind, Ctx *c, Build build) {
  size_t before = unit.pous.size();
  diag.beginDeferral();
  build();
  std::optional<DiagEngine::Deferred> refusal = diag.endDeferral();
  if (!failed || !refusal)
    return; // built, or a syntax error reported where it is
  failed = false;
  keepRefusedPou(unit, before, kind, c->name->getText(), loc(c->name),
                 refusal->loc, std::move(refusal->message));
}

} // namespace netlift::st::detail

#endif
