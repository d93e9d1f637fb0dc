//===- StFrontend.cpp - Structured Text parse tree to the PLC model -------===//
//
// Parsing runs in two stages, the usual way to make ANTLR fast: SLL
// prediction with a bailing error strategy first (almost every real file
// parses in this mode), and only if it fails a second parse in full LL mode
// whose syntax errors are reported, one per statement. The parse tree is then
// walked once into the PLC model and dropped.
//
//===----------------------------------------------------------------------===//
#include "frontends/st/StFrontend.h"
#include "frontends/plc/JumpExpansion.h"
#include "frontends/plc/Sema.h"
#include "frontends/plc/SfcExpansion.h"
#include "frontends/st/StAstBuilder.h"
#include "frontends/st/StConditionals.h"
#include "frontends/st/StLexer.h"
#include "frontends/st/StLongParts.h"
#include "ir/support/IecTime.h"

#include "ST.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSwitch.h"

#include <cassert>
#include <cmath>
#include <map>
#include <optional>
#include <type_traits>
#include <typeinfo>

using namespace netlift;
using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;
using P = stgen::ST;
using netlift::st::detail::alt;
using netlift::st::detail::AstBuilder;

//===----------------------------------------------------------------------===//
// Literals
//===----------------------------------------------------------------------===//

bool st::parseIntegerLiteral(StringRef text, int64_t &value,
                             bool *beyondInt64) {
  unsigned base = 10;
  size_t hash = text.find('#');
  StringRef digits = text;
  if (hash != StringRef::npos) {
    if (text.substr(0, hash).getAsInteger(10, base) ||
        (base != 2 && base != 8 && base != 16))
      return false;
    digits = text.substr(hash + 1);
  }
  uint64_t v = 0;
  bool any = false;
  for (char c : digits) {
    if (c == '_')
      continue;
    unsigned d;
    if (c >= '0' && c <= '9')
      d = c - '0';
    else if (c >= 'a' && c <= 'f')
      d = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F')
      d = c - 'A' + 10;
    else
      return false;
    if (d >= base)
      return false;
    if (v > (UINT64_MAX - d) / base)
      return false;
    v = v * base + d;
    any = true;
  }
  if (!any)
    return false;
  // Values past 2^63 - 1 (only a ULINT or LWORD holds them) keep their
  // bits, for a caller that asks; for the others they are out of range.
  if (v > uint64_t(INT64_MAX)) {
    if (!beyondInt64)
      return false;
    *beyondInt64 = true;
  }
  value = static_cast<int64_t>(v);
  return true;
}

bool st::parseDuration(StringRef literal, int64_t &ns, std::string &error) {
  IecTimeKind kind = IecTimeKind::Duration;
  return parseIecTime(literal, kind, ns, error) &&
         (kind == IecTimeKind::Duration ||
          (error = ("'" + literal + "' is not a duration").str(), false));
}

//===----------------------------------------------------------------------===//
// Syntax errors
//===----------------------------------------------------------------------===//

namespace {

/// How a token type reads in an error message.
std::string describeTokenType(const antlr4::dfa::Vocabulary &vocab, size_t type,
                              const std::string &eofName) {
  switch (type) {
  case antlr4::Token::EOF:
    return eofName;
  case P::IDENT:
    return "an identifier";
  case P::INTEGER:
    return "an integer";
  case P::REAL_LIT:
    return "a real number";
  case P::STRING_LIT:
  case P::WSTRING_LIT:
    return "a string";
  case P::DURATION:
    return "a duration";
  case P::DIRECT:
    return "a direct address";
  case P::ASSIGN:
    return "':='";
  case P::OUTPUT_ASSIGN:
    return "'=>'";
  case P::EQ:
    return "'='";
  case P::NE:
    return "'<>'";
  case P::LT:
    return "'<'";
  case P::LE:
    return "'<='";
  case P::GT:
    return "'>'";
  case P::GE:
    return "'>='";
  case P::PLUS:
    return "'+'";
  case P::MINUS:
    return "'-'";
  case P::STAR:
    return "'*'";
  case P::SLASH:
    return "'/'";
  case P::POWER:
    return "'**'";
  case P::AMP:
    return "'&'";
  case P::CARET:
    return "'^'";
  case P::LPAREN:
    return "'('";
  case P::RPAREN:
    return "')'";
  case P::LBRACKET:
    return "'['";
  case P::RBRACKET:
    return "']'";
  case P::COMMA:
    return "','";
  case P::SEMI:
    return "';'";
  case P::COLON:
    return "':'";
  case P::DOT:
    return "'.'";
  case P::DOTDOT:
    return "'..'";
  case P::HASH:
    return "'#'";
  default:
    break;
  }
  std::string name = vocab.getSymbolicName(type);
  if (name == "STRING_KW")
    name = "STRING";
  else if (name == "WSTRING_KW")
    name = "WSTRING";
  return name.empty() ? "a token" : name;
}

/// Records the first syntax error of a parse (the ones after it are
/// ANTLR's recovery talking).
class FirstErrorListener : public antlr4::BaseErrorListener {
public:
  void syntaxError(antlr4::Recognizer *recognizer,
                   antlr4::Token *offendingSymbol, size_t, size_t,
                   const std::string &, std::exception_ptr e) override {
    if (seen)
      return;
    seen = true;
    offset = offendingSymbol ? offendingSymbol->getStartIndex() : 0;
    tokenIndex = offendingSymbol ? offendingSymbol->getTokenIndex() : 0;
    atEof =
        !offendingSymbol || offendingSymbol->getType() == antlr4::Token::EOF;
    std::string found =
        !offendingSymbol || offendingSymbol->getType() == antlr4::Token::EOF
            ? eofName
            : "'" + offendingSymbol->getText() + "'";
    auto *parser = static_cast<antlr4::Parser *>(recognizer);
    antlr4::misc::IntervalSet expected;
    try {
      if (e)
        std::rethrow_exception(e);
      expected = parser->getExpectedTokens();
    } catch (antlr4::RecognitionException &re) {
      expected = re.getExpectedTokens();
    } catch (...) {
    }
    std::vector<std::string> names;
    for (ssize_t t : expected.toList())
      names.push_back(describeTokenType(parser->getVocabulary(),
                                        static_cast<size_t>(t), eofName));
    if (!names.empty() && names.size() <= 4) {
      message = "expected ";
      for (size_t i = 0; i < names.size(); ++i) {
        if (i)
          message += i + 1 == names.size() ? " or " : ", ";
        message += names[i];
      }
      message += ", found " + found;
    } else {
      message = "syntax error: unexpected " + found;
    }
    findUnclosed(parser, expected);
    // Only the first error of a parse is reported (the next parse, with
    // the broken statement hidden, finds the next real one), so the rest
    // of the text need not be parsed: full-LL prediction is what makes a
    // parse with errors slow.
    throw antlr4::ParseCancellationException();
  }
  bool seen = false, atEof = false;
  size_t offset = 0, tokenIndex = 0;
  std::string message;
  std::string eofName = "end of file";
  /// Where the innermost statement the error leaves unclosed opened (an IF
  /// whose END_IF is missing), as a compiler points at an unclosed brace.
  std::optional<size_t> unclosedOffset;
  std::string unclosedWhat;

private:
  void findUnclosed(antlr4::Parser *parser,
                    const antlr4::misc::IntervalSet &expected) {
    static const std::pair<size_t, size_t> pairs[] = {
        {P::IF, P::END_IF},
        {P::CASE, P::END_CASE},
        {P::FOR, P::END_FOR},
        {P::WHILE, P::END_WHILE},
        {P::REPEAT, P::END_REPEAT}};
    for (antlr4::ParserRuleContext *ctx = parser->getContext(); ctx;
         ctx = dynamic_cast<antlr4::ParserRuleContext *>(ctx->parent)) {
      antlr4::Token *start = ctx->getStart();
      if (!start)
        continue;
      for (auto [open, close] : pairs)
        if (start->getType() == open && expected.contains(close)) {
          unclosedOffset = start->getStartIndex();
          unclosedWhat = start->getText();
          return;
        }
    }
  }
};

/// Takes the statement (or declaration) holding token `at` out of the
/// parse by moving its tokens off the parser's channel, so that a new
/// parse goes on to the next real mistake instead of reporting follow-ups
/// of this one. A statement runs from the token after the last `;`,
/// THEN, ELSE, DO, OF, section keyword or END_ keyword before `at` through
/// the first `;` at or after it (an END_ keyword there ends it too, but
/// stays: it closes the enclosing construct; only an END_ keyword that is
/// itself the whole mistake is hidden). False when nothing could be
/// hidden.
bool hideStatement(antlr4::BufferedTokenStream &tokens,
                   const antlr4::dfa::Vocabulary &vocab, size_t at) {
  // getSymbolicName returns a temporary string: test it before it goes.
  auto isEnd = [&](size_t type) {
    return StringRef(vocab.getSymbolicName(type)).startswith("END_");
  };
  auto onChannel = [&](size_t i) {
    return tokens.get(i)->getChannel() == antlr4::Token::DEFAULT_CHANNEL;
  };
  size_t n = tokens.size();
  if (at >= n)
    return false;
  size_t begin = at;
  while (begin > 0) {
    size_t i = begin - 1;
    if (onChannel(i)) {
      size_t type = tokens.get(i)->getType();
      std::string name = vocab.getSymbolicName(type);
      if (type == P::SEMI || type == P::THEN || type == P::ELSE ||
          type == P::DO || type == P::OF || isEnd(type) ||
          StringRef(name).startswith("VAR"))
        break;
    }
    begin = i;
  }
  size_t end = at; // exclusive
  for (; end < n; ++end) {
    size_t type = tokens.get(end)->getType();
    if (!onChannel(end))
      continue;
    if (type == antlr4::Token::EOF || (isEnd(type) && (end > at || begin < at)))
      break;
    if (type == P::SEMI) {
      ++end;
      break;
    }
  }
  return st::hideTokens(tokens, begin, end);
}

//===----------------------------------------------------------------------===//
// Parse tree to PLC model
//===----------------------------------------------------------------------===//

/// Parses the declarations of one group of a long VAR block (see
/// LongParts) into `out`; false after reporting an error.
bool parseDeclarations(StringRef text, DiagEngine &diag, Unit &unit,
                       VarSection section, bool constant, bool retain,
                       std::vector<VarDecl *> &out);

} // namespace

std::vector<Attribute> AstBuilder::pragmasBefore(antlr4::Token *t) {
  std::vector<Attribute> attrs;
  for (antlr4::Token *h :
       tokens.getHiddenTokensToLeft(t->getTokenIndex(), st::kPragmaChannel)) {
    std::string body = h->getText();
    body = StringRef(body).drop_front().drop_back().trim().str();
    attrs.push_back({body, loc(h)});
  }
  return attrs;
}

bool AstBuilder::build(P::CompilationUnitContext *cu) {
  for (auto *el : cu->libraryElement()) {
    if (failed)
      return false;
    if (auto *p = el->programDecl())
      deferRefusals(PouKind::Program, p, [&] { program(p); });
    else if (auto *fb = el->functionBlockDecl())
      deferRefusals(PouKind::FunctionBlock, fb, [&] { functionBlock(fb); });
    else if (auto *f = el->functionDecl())
      deferRefusals(PouKind::Function, f, [&] { function(f); });
    else if (auto *t = el->typeDecl())
      typeDecl(t);
    else if (auto *c = el->configurationDecl())
      configuration(c);
    else if (auto *g = el->globalVarBlock())
      varBlock(g->varBlock(), unit.globals);
    else if (auto *i = el->interfaceDecl())
      deferRefusals(PouKind::FunctionBlock, i, [&] { interfaceDecl(i); });
    else if (auto *k = el->classDecl())
      deferRefusals(PouKind::FunctionBlock, k, [&] { classDecl(k); });
    else if (auto *a = el->actionsBlock())
      actionsBlock(a);
    else if (auto *r = el->refusedElement())
      refusedElement(r);
  }
  return !failed;
}

/// NAMESPACE, and METHOD, PROPERTY or ACTION outside their block: refused
/// where they stand.
void AstBuilder::refusedElement(P::RefusedElementContext *r) {
  std::string kw = StringRef(r->kw->getText()).upper();
  if (kw == "NAMESPACE")
    refuse(loc(r->kw), "NAMESPACE is not supported (a vendor extension)");
  else
    refuse(loc(r->kw), kw +
                           " outside a FUNCTION_BLOCK or PROGRAM: netlift "
                           "reads a " +
                           kw +
                           " inside the block it belongs to (its variables "
                           "are the block's)");
}

void AstBuilder::typeDecl(P::TypeDeclContext *c) {
  // Pragmas before TYPE belong to its first definition (TwinCAT writes one
  // type per TYPE).
  std::vector<Attribute> first = pragmasBefore(c->getStart());
  for (auto *d : c->typeDefinition()) {
    TypeDecl *td = unit.make<TypeDecl>();
    td->name = d->name->getText();
    td->loc = loc(d->name);
    td->attrs = pragmasBefore(d->getStart());
    td->attrs.insert(td->attrs.begin(), first.begin(), first.end());
    first.clear();
    td->type = typeSpec(d->typeSpec());
    if (failed)
      return;
    if (d->ext) {
      if (td->type->kind != TypeSyntaxKind::Struct) {
        refuse(loc(d->ext),
               "EXTENDS in a type declaration is for STRUCTs and UNIONs");
        return;
      }
      td->type->extends = d->ext->getText();
    }
    unit.types.push_back(td);
  }
}

void AstBuilder::configuration(P::ConfigurationDeclContext *c) {
  // Only matiec's family (OpenPLC, Beremiz) writes configurations as text;
  // it converts TIME to and from numbers in seconds.
  unit.inferTimeNumbers(TimeNumbers::Seconds,
                        "seconds, as matiec (OpenPLC, Beremiz) converts: "
                        "the program comes with a textual CONFIGURATION");
  Configuration *cfg = unit.make<Configuration>();
  cfg->name = c->name->getText();
  cfg->loc = loc(c->name);
  auto task = [&](P::TaskDeclContext *t) {
    Task task;
    task.name = t->name->getText();
    task.loc = loc(t->name);
    for (auto *p : t->taskParam()) {
      std::string key = StringRef(p->ident()->getText()).upper();
      Expr *v = expr(p->expression());
      if (key == "INTERVAL")
        task.interval = v;
      else if (key == "SINGLE")
        task.single = v;
      else if (key == "PRIORITY")
        task.priority = v;
      else
        refuse(loc(p), "unknown task parameter '" + p->ident()->getText() +
                           "' (INTERVAL, SINGLE or PRIORITY)");
    }
    cfg->tasks.push_back(task);
  };
  auto prog = [&](P::ProgramConfigContext *p) {
    ProgramInstance pi;
    pi.name = p->inst->getText();
    pi.loc = loc(p->inst);
    if (p->task)
      pi.task = p->task->getText();
    pi.typeName = p->type->getText();
    pi.typeLoc = loc(p->type);
    callArgs(p->callArg(), pi.args);
    cfg->programs.push_back(pi);
  };
  for (auto *item : c->configItem()) {
    if (auto *vb = item->varBlock())
      varBlock(vb, cfg->globals);
    else if (auto *t = item->taskDecl())
      task(t);
    else if (auto *p = item->programConfig())
      prog(p);
    else if (auto *r = item->resourceDecl())
      for (auto *ri : r->resourceItem()) {
        if (auto *vb = ri->varBlock())
          varBlock(vb, cfg->globals);
        else if (auto *t = ri->taskDecl())
          task(t);
        else if (auto *p = ri->programConfig())
          prog(p);
      }
  }
  unit.configs.push_back(cfg);
}

void AstBuilder::varBlock(P::VarBlockContext *c, std::vector<VarDecl *> &out) {
  VarSection section = VarSection::Var;
  switch (c->kind->getType()) {
  case P::VAR_INPUT:
    section = VarSection::Input;
    break;
  case P::VAR_OUTPUT:
    section = VarSection::Output;
    break;
  case P::VAR_IN_OUT:
    section = VarSection::InOut;
    break;
  case P::VAR_EXTERNAL:
    section = VarSection::External;
    break;
  case P::VAR_GLOBAL:
    section = VarSection::Global;
    break;
  case P::VAR_TEMP:
    section = VarSection::Temp;
    break;
  case P::VAR_STAT:
    section = VarSection::Stat; // one variable for every instance and call
    break;
  case P::VAR_INST:
    // CODESYS: a method's variable kept in the instance (AstBuilder::method
    // moves it there); in a POU body it is an ordinary variable.
    section = VarSection::Inst;
    break;
  case P::VAR_ACCESS:
    accessBlock(c);
    return;
  case P::VAR_CONFIG:
    refuse(loc(c->kind), c->kind->getText() + " is not supported");
    return;
  default:
    break;
  }
  bool constant = false, retain = false;
  for (auto *q : c->varQualifier()) {
    if (q->CONSTANT())
      constant = true;
    else if (q->RETAIN() || q->PERSISTENT())
      retain = true;
  }
  for (auto *d : c->varDecl()) {
    declare(d, section, constant, retain, out);
    if (failed)
      return;
  }
  if (skipped)
    if (auto it = skipped->find(c->getStop()->getStartIndex());
        it != skipped->end())
      for (StringRef group : it->second)
        if (!parseDeclarations(group, diag, unit, section, constant, retain,
                               out)) {
          failed = true; // reported where it is
          return;
        }
}

void AstBuilder::accessBlock(P::VarBlockContext *c) {
  // IEC 61131-3 access paths name variables a remote client (a SCADA, an
  // HMI) may read, or also write. Reading changes nothing the program
  // does; a write from outside at any time would make the variable an
  // input of the environment, which netlift does not model yet.
  for (auto *d : c->accessDecl()) {
    std::string direction =
        d->direction ? StringRef(d->direction->getText()).upper() : "";
    std::string target = d->accessTarget()->getText();
    if (direction == "READ_WRITE") {
      refuse(loc(d->direction),
             "VAR_ACCESS '" + d->accessName->getText() +
                 "' lets a remote client write '" + target +
                 "' (READ_WRITE): writes from outside the program are not "
                 "supported");
      return;
    }
    if (!direction.empty() && direction != "READ_ONLY") {
      refuse(loc(d->direction), "expected READ_ONLY or READ_WRITE, found '" +
                                    d->direction->getText() + "'");
      return;
    }
    diag.note(loc(d), "VAR_ACCESS '" + d->accessName->getText() +
                          "' gives remote clients read access to '" + target +
                          "': it does not change what the program does");
  }
}

void AstBuilder::declare(P::VarDeclContext *d, VarSection section,
                         bool constant, bool retain,
                         std::vector<VarDecl *> &out) {
  if (d->accessPath())
    return (void)refuse(loc(d), "access path declarations are not "
                                "supported");
  TypeSyntax *type = typeSpec(d->typeSpec());
  if (failed)
    return;
  std::vector<Attribute> attrs = pragmasBefore(d->getStart());
  char edge = 0;
  if (d->edge) {
    std::string e = StringRef(d->edge->getText()).upper();
    if (e != "R_EDGE" && e != "F_EDGE")
      return (void)refuse(loc(d->edge),
                          "expected ';', found '" + d->edge->getText() + "'");
    edge = e[0];
  }
  std::string location = d->DIRECT() ? d->DIRECT()->getText() : "";
  auto add = [&](std::string name, SMLoc at) {
    VarDecl *v = unit.make<VarDecl>();
    v->name = std::move(name);
    v->loc = at;
    v->section = section;
    v->constant = constant;
    v->retain = retain;
    v->location = location;
    v->typeSyntax = type;
    v->attrs = attrs;
    v->edge = edge;
    out.push_back(v);
  };
  if (d->ident().empty()) // `AT %IX0.0 : BOOL;` names itself by address
    add(location, loc(d->DIRECT()));
  for (auto *id : d->ident())
    add(id->getText(), loc(id));
}

TypeSyntax *AstBuilder::typeSpec(P::TypeSpecContext *c) {
  TypeSyntax *t = typeSpec0(c->elem);
  if (t && c->init)
    t->init = initializer(c->init);
  if (t && c->bare)
    t->init = arrayInitializer(c->bare, c->bare->arrayInitElem());
  return t;
}

TypeSyntax *AstBuilder::typeSpec0(P::TypeSpec0Context *c) {
  if (auto *n = alt<P::NamedTypeContext>(c)) {
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Named, loc(n));
    t->name = n->qualifiedName()->getText();
    return t;
  }
  // The bounds of each dimension (none for ARRAY[*]).
  auto arrayOf = [&](antlr4::ParserRuleContext *at,
                     const std::vector<P::ArrayDimContext *> &dims) {
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Array, loc(at));
    for (auto *d : dims)
      if (auto *s = d->subrange())
        t->dims.push_back({expr(s->lo), expr(s->hi)});
      else
        t->dims.push_back({nullptr, nullptr});
    return t;
  };
  if (auto *a = alt<P::ArrayTypeContext>(c)) {
    TypeSyntax *t = arrayOf(a, a->arrayDim());
    t->elem = typeSpec0(a->elem);
    return t;
  }
  if (auto *a = alt<P::InstanceArrayTypeContext>(c)) {
    TypeSyntax *t = arrayOf(a, a->arrayDim());
    t->elem = unit.make<TypeSyntax>(TypeSyntaxKind::Named, loc(a->base));
    t->elem->name = a->base->getText();
    for (auto *each : a->elementArgs()) {
      std::vector<CallArg> args;
      for (auto *x : each->elementArg()) {
        CallArg arg;
        if (x->name)
          arg.name = x->name->getText();
        arg.value = expr(x->value);
        arg.loc = x->name ? loc(x->name) : arg.value ? arg.value->loc : loc(x);
        args.push_back(arg);
      }
      t->elementArgs.push_back(std::move(args));
    }
    return t;
  }
  auto *st = alt<P::StructTypeContext>(c);
  auto *un = alt<P::UnionTypeContext>(c);
  if (st || un) {
    auto *t =
        unit.make<TypeSyntax>(TypeSyntaxKind::Struct, st ? loc(st) : loc(un));
    t->isUnion = un != nullptr;
    for (auto *f : st ? st->structField() : un->structField()) {
      if (f->DIRECT())
        return refuse(loc(f->DIRECT()), "located structure fields are not "
                                        "supported");
      TypeSyntax *ft = typeSpec(f->typeSpec());
      for (auto *id : f->ident()) {
        VarDecl *v = unit.make<VarDecl>();
        v->name = id->getText();
        v->loc = loc(id);
        v->typeSyntax = ft;
        t->fields.push_back(v);
      }
    }
    return t;
  }
  // Refused where a translated POU uses the type, not where it is written:
  // a library's unused POUs may hold what netlift does not model.
  if (auto *p = alt<P::PointerTypeContext>(c)) {
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Reference, loc(p));
    t->refKind = p->POINTER()     ? RefKind::Pointer
                 : p->REFERENCE() ? RefKind::Reference
                                  : RefKind::RefTo;
    t->elem = typeSpec0(p->typeSpec0());
    return t->elem ? t : nullptr;
  }
  if (auto *e = alt<P::EnumTypeContext>(c)) {
    // `fb : FB_Axis(nId := 1)`: an instance and the arguments of its
    // FB_init (CODESYS), read like an enumeration with a base type that
    // is no elementary type.
    bool allValued = !e->enumValue().empty();
    for (auto *v : e->enumValue())
      allValued &= v->value != nullptr;
    if (e->base && !e->after && allValued &&
        !plc::elementaryType(e->base->getText())) {
      auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Named, loc(e));
      t->name = e->base->getText();
      for (auto *v : e->enumValue()) {
        CallArg a;
        a.name = v->name->getText();
        a.value = expr(v->value);
        a.loc = loc(v->name);
        t->instanceArgs.push_back(a);
      }
      return t;
    }
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Enum, loc(e));
    // CODESYS writes the base type after the values: (a := 1, b := 2) INT.
    if (e->base)
      t->name = e->base->getText();
    else if (e->after)
      t->name = e->after->getText();
    for (auto *v : e->enumValue())
      t->enumerators.push_back({v->name->getText(),
                                v->value ? expr(v->value) : nullptr,
                                loc(v->name)});
    return t;
  }
  if (auto *p = alt<P::InstanceArgsTypeContext>(c)) {
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Named, loc(p));
    t->name = p->base->getText();
    for (auto *x : p->expression()) {
      CallArg a;
      a.value = expr(x);
      a.loc = a.value ? a.value->loc : loc(p);
      t->instanceArgs.push_back(a);
    }
    return t;
  }
  if (auto *s = alt<P::SubrangeTypeContext>(c)) {
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::Subrange, loc(s));
    t->name = s->base->getText();
    t->lo = expr(s->subrange()->lo);
    t->hi = expr(s->subrange()->hi);
    return t;
  }
  if (auto *s = alt<P::StringTypeContext>(c)) {
    auto *t = unit.make<TypeSyntax>(TypeSyntaxKind::String, loc(s));
    t->name = s->WSTRING_KW() ? "WSTRING" : "STRING";
    if (s->length)
      t->length = expr(s->length);
    return t;
  }
  return refuse(loc(c), "unsupported type");
}

Initializer *AstBuilder::initializer(P::InitializerContext *c) {
  if (auto *e = alt<P::ExprInitContext>(c)) {
    auto *i = unit.make<Initializer>(Initializer::Value, loc(e));
    i->value = expr(e->expression());
    return i;
  }
  if (auto *a = alt<P::ArrayInitContext>(c))
    return arrayInitializer(a, a->arrayInitElem());
  auto *s = static_cast<P::StructInitContext *>(c);
  auto *i = unit.make<Initializer>(Initializer::Struct, loc(s));
  for (auto *f : s->fieldInit())
    i->fields.push_back({f->ident()->getText(), initializer(f->initializer())});
  return i;
}

Initializer *AstBuilder::arrayInitializer(
    antlr4::ParserRuleContext *at,
    const std::vector<P::ArrayInitElemContext *> &els) {
  auto *i = unit.make<Initializer>(Initializer::Array, loc(at));
  for (auto *el : els) {
    int64_t count = 1;
    if (el->count && !st::parseIntegerLiteral(el->count->getText(), count))
      return refuse(loc(el->count), "malformed repeat count");
    Initializer *inner =
        el->initializer() ? initializer(el->initializer()) : nullptr;
    i->elems.push_back({count, inner});
  }
  return i;
}

void AstBuilder::bodyPragmas(P::BodyStatementListContext *c) {
  // From the pragmas before the first statement (or before END_ of an empty
  // body) through those after the last.
  size_t lo = c->getStart()->getTokenIndex(), hi = lo;
  auto before = tokens.getHiddenTokensToLeft(lo, st::kPragmaChannel);
  if (!before.empty())
    lo = before.front()->getTokenIndex();
  if (c->getStop() && c->getStop()->getTokenIndex() >= hi) {
    hi = c->getStop()->getTokenIndex();
    auto after = tokens.getHiddenTokensToRight(hi, st::kPragmaChannel);
    if (!after.empty())
      hi = after.back()->getTokenIndex();
  }
  for (antlr4::Token *t : tokens.get(lo, hi)) {
    if (t->getChannel() != st::kPragmaChannel)
      continue;
    if (auto why = st::refusedBodyPragma(t->getText())) {
      refuse(loc(t), *why);
      return;
    }
  }
}

void AstBuilder::bodyStatements(P::BodyStatementListContext *c, StmtList &out) {
  bodyPragmas(c);
  for (auto *child : c->children) {
    if (failed)
      return;
    if (auto *l = dynamic_cast<P::BodyLabelContext *>(child)) {
      Stmt *s = unit.make<Stmt>(StmtKind::Label, loc(l->name));
      s->target = unit.make<Expr>(ExprKind::Name, loc(l->name));
      s->target->name = l->name->getText();
      out.push_back(s);
    } else if (auto *st = dynamic_cast<P::StatementContext *>(child)) {
      if (Stmt *s = statement(st))
        out.push_back(s);
    }
  }
}

void AstBuilder::statements(P::StatementListContext *c, StmtList &out) {
  for (auto *s : c->statement()) {
    if (failed)
      return;
    if (Stmt *st = statement(s))
      out.push_back(st);
  }
}

// `x S= c;` sets x where c holds, `x R= c;` resets it (CODESYS, TwinCAT).
// In a chain `x S= y R= c;` every target takes the one operand at the end,
// evaluated once: IF c THEN y := FALSE; x := TRUE; END_IF.
Stmt *AstBuilder::setReset(P::SetResetStmtContext *c) {
  Stmt *s = unit.make<Stmt>(StmtKind::If, loc(c));
  s->arms.push_back({expr(c->value), {}});
  auto targets = c->setOrReset();
  for (auto it = targets.rbegin(); it != targets.rend(); ++it) {
    Stmt *a = unit.make<Stmt>(StmtKind::Assign, loc((*it)->op));
    a->target = variable((*it)->target);
    a->value = unit.make<Expr>(ExprKind::BoolLit, loc((*it)->op));
    a->value->intValue = (*it)->op->getType() == P::SET_ASSIGN;
    s->arms.back().second.push_back(a);
  }
  return s;
}

Stmt *AstBuilder::statement(P::StatementContext *c) {
  if (alt<P::EmptyStmtContext>(c))
    return nullptr;
  if (auto *a = alt<P::AssignStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::Assign, loc(a->ASSIGN()));
    s->target = variable(a->target);
    s->value = expr(a->value);
    return s;
  }
  if (auto *r = alt<P::RefAssignStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::Assign, loc(r->op));
    s->assignKind = r->op->getType() == P::REF_ASSIGN
                        ? AssignKind::BindReference
                        : AssignKind::Attempt;
    s->target = variable(r->target);
    s->value = expr(r->value);
    return s;
  }
  if (auto *e = alt<P::EmbeddedCStmtContext>(c))
    return refuse(loc(e->EMBEDDED_C()), "embedded C code '{{ ... }}' is not "
                                        "supported (it cannot be modelled)");
  if (auto *sr = alt<P::SetResetStmtContext>(c))
    return setReset(sr);
  if (auto *call = alt<P::CallStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::Call, loc(call));
    Expr *callee = variable(call->callee);
    if (!callee)
      return nullptr;
    Expr *e = callOf(callee, call->callee, loc(call));
    if (!e)
      return nullptr;
    callArgs(call->callArg(), e->args);
    s->value = chained(e, call->callSuffix());
    return s->value ? s : nullptr;
  }
  if (auto *i = alt<P::IfStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::If, loc(i));
    s->arms.push_back({expr(i->cond), {}});
    statements(i->statementList(0), s->arms.back().second);
    for (auto *e : i->elsifPart()) {
      s->arms.push_back({expr(e->cond), {}});
      statements(e->statementList(), s->arms.back().second);
    }
    if (i->elseBody) {
      s->hasElse = true;
      statements(i->elseBody, s->elseBody);
    }
    return s;
  }
  if (auto *cs = alt<P::CaseStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::Case, loc(cs));
    s->value = expr(cs->sel);
    for (auto *arm : cs->caseArm()) {
      CaseArmSyntax a;
      for (auto *l : arm->caseLabel())
        a.labels.push_back({expr(l->lo), l->hi ? expr(l->hi) : nullptr});
      statements(arm->statementList(), a.body);
      s->caseArms.push_back(std::move(a));
    }
    if (cs->elseBody) {
      s->hasElse = true;
      statements(cs->elseBody, s->elseBody);
    }
    return s;
  }
  if (auto *f = alt<P::ForStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::For, loc(f));
    s->target = unit.make<Expr>(ExprKind::Name, loc(f->var));
    s->target->name = f->var->getText();
    s->from = expr(f->from);
    s->to = expr(f->to);
    if (f->by)
      s->by = expr(f->by);
    statements(f->statementList(), s->body);
    return s;
  }
  if (auto *w = alt<P::WhileStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::While, loc(w));
    s->value = expr(w->cond);
    statements(w->statementList(), s->body);
    return s;
  }
  if (auto *r = alt<P::RepeatStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::Repeat, loc(r));
    statements(r->statementList(), s->body);
    s->value = expr(r->cond);
    return s;
  }
  if (alt<P::ExitStmtContext>(c))
    return unit.make<Stmt>(StmtKind::Exit, loc(c));
  if (alt<P::ContinueStmtContext>(c))
    return unit.make<Stmt>(StmtKind::Continue, loc(c));
  if (alt<P::ReturnStmtContext>(c))
    return unit.make<Stmt>(StmtKind::Return, loc(c));
  if (auto *j = alt<P::JumpStmtContext>(c)) {
    Stmt *s = unit.make<Stmt>(StmtKind::Jump, loc(c));
    s->target = unit.make<Expr>(ExprKind::Name, loc(j->IDENT()));
    s->target->name = j->IDENT()->getText();
    return s;
  }
  return refuse(loc(c), "unsupported statement");
}

bool AstBuilder::callArgs(const std::vector<P::CallArgContext *> &args,
                          std::vector<CallArg> &out) {
  for (auto *a : args) {
    CallArg arg;
    arg.loc = loc(a);
    if (auto *n = alt<P::NamedInputContext>(a)) {
      arg.name = n->name->getText();
      arg.value = expr(n->value);
    } else if (auto *o = alt<P::NamedOutputContext>(a)) {
      arg.name = o->name->getText();
      arg.isOutput = true;
      arg.negated = o->NOT() != nullptr;
      arg.value = variable(o->target);
    } else {
      arg.value = expr(static_cast<P::PositionalArgContext *>(a)->value);
    }
    out.push_back(std::move(arg));
  }
  return !failed;
}

static Op binaryOp(size_t tokenType) {
  switch (tokenType) {
  case P::OR:
    return Op::Or;
  case P::OR_ELSE:
    return Op::OrElse;
  case P::XOR:
    return Op::Xor;
  case P::AND:
  case P::AMP:
    return Op::And;
  case P::AND_THEN:
    return Op::AndThen;
  case P::EQ:
    return Op::Eq;
  case P::NE:
    return Op::Ne;
  case P::LT:
    return Op::Lt;
  case P::LE:
    return Op::Le;
  case P::GT:
    return Op::Gt;
  case P::GE:
    return Op::Ge;
  case P::PLUS:
    return Op::Add;
  case P::MINUS:
    return Op::Sub;
  case P::STAR:
    return Op::Mul;
  case P::SLASH:
    return Op::Div;
  case P::MOD:
    return Op::Mod;
  default:
    return Op::Pow;
  }
}

Expr *AstBuilder::expr(P::ExpressionContext *c) {
  if (failed || !c)
    return nullptr;
  if (auto *p = alt<P::PrimaryExprContext>(c))
    return primary(p->primary());
  if (auto *u = alt<P::UnaryExprContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::Unary, loc(u->op));
    e->op = u->op->getType() == P::MINUS  ? Op::Neg
            : u->op->getType() == P::PLUS ? Op::Plus
                                          : Op::Not;
    e->operands.push_back(expr(u->expression()));
    return failed ? nullptr : e;
  }
  // Every other alternative is binary: expression op expression.
  // (The grammar's binary alternatives are `expression op expression`.)
  if (c->children.size() != 3)
    return refuse(loc(c), "unsupported expression");
  auto *lhs = static_cast<P::ExpressionContext *>(c->children[0]);
  auto *rhs = static_cast<P::ExpressionContext *>(c->children[2]);
  auto *opNode = static_cast<antlr4::tree::TerminalNode *>(c->children[1]);
  Expr *e = unit.make<Expr>(ExprKind::Binary, loc(opNode));
  e->op = binaryOp(opNode->getSymbol()->getType());
  e->operands = {expr(lhs), expr(rhs)};
  return failed ? nullptr : e;
}

Expr *AstBuilder::primary(P::PrimaryContext *c) {
  if (auto *l = alt<P::LiteralPrimaryContext>(c))
    return literal(l->literal());
  if (auto *p = alt<P::ParenPrimaryContext>(c))
    return expr(p->expression());
  if (auto *a = alt<P::AddressPrimaryContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::Call, loc(a->AMP()));
    e->name = "REF";
    Expr *of = variable(a->variable());
    if (!of)
      return nullptr;
    e->args.push_back({"", false, false, of, of->loc});
    return e;
  }
  if (auto *v = alt<P::VariablePrimaryContext>(c))
    return variable(v->variable());
  if (auto *o = alt<P::OperatorCallPrimaryContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::Call, loc(o));
    e->name = StringRef(o->op->getText()).upper();
    callArgs(o->callArg(), e->args);
    return failed ? nullptr : e;
  }
  auto *call = static_cast<P::CallPrimaryContext *>(c);
  Expr *callee = variable(call->callee);
  if (!callee)
    return nullptr;
  Expr *e = callOf(callee, call->callee, loc(call));
  if (!e)
    return nullptr;
  callArgs(call->callArg(), e->args);
  return failed ? nullptr : chained(e, call->callSuffix());
}

/// `first` followed by the method calls on what each returns.
Expr *AstBuilder::chained(Expr *first,
                          const std::vector<P::CallSuffixContext *> &suffixes) {
  Expr *e = first;
  for (auto *s : suffixes) {
    Expr *on = e;
    if (s->deref) {
      on = unit.make<Expr>(ExprKind::Deref, loc(s->deref));
      on->operands.push_back(e);
    }
    e = unit.make<Expr>(ExprKind::Call, loc(s->name));
    e->name = s->name->getText();
    e->method = true;
    e->operands.push_back(on);
    callArgs(s->callArg(), e->args);
  }
  return failed ? nullptr : e;
}

/// The call of what `callee` designates: a function or instance by name;
/// `r^(...)`, the instance r designates; `timers[i](...)`, an element of
/// an array of instances; `inst.M(...)`, a METHOD or ACTION of inst;
/// `THIS^.M(...)`, `SUPER^.M(...)` and `SUPER^()` on the running instance.
Expr *AstBuilder::callOf(Expr *callee, P::VariableContext *written, SMLoc at) {
  Expr *e = unit.make<Expr>(ExprKind::Call, at);
  switch (callee->kind) {
  case ExprKind::Name:
    e->name = callee->name;
    e->method = callee->ofThis || callee->ofSuper;
    e->ofSuper = callee->ofSuper;
    return e;
  case ExprKind::Deref:
    if (Expr *r = callee->base();
        r->kind == ExprKind::Name && sameName(r->name, "SUPER")) {
      e->name = "SUPER^";
      e->method = e->ofSuper = true;
      return e;
    }
    [[fallthrough]];
  case ExprKind::Index:
    e->name = written->getText();
    e->operands.push_back(callee);
    return e;
  case ExprKind::Field:
    e->name = callee->name;
    e->method = true;
    e->operands.push_back(callee->base());
    return e;
  default:
    return refuse(at, "calling '" + written->getText() +
                          "' is not supported (calls through this selector "
                          "are refused)");
  }
}

Expr *AstBuilder::variable(P::VariableContext *c) {
  if (failed)
    return nullptr;
  antlr4::Token *head = c->getStart();
  Expr *e = unit.make<Expr>(ExprKind::Name, loc(head));
  e->name = head->getText();
  auto selectors = c->selector();
  // THIS^.x and SUPER^.M: the running instance's member, the base's
  // method.
  bool self = sameName(e->name, "THIS"), super = sameName(e->name, "SUPER");
  if ((self || super) && !selectors.empty() &&
      alt<P::DerefSelContext>(selectors[0])) {
    if (selectors.size() > 1)
      if (auto *f = alt<P::FieldSelContext>(selectors[1])) {
        e = unit.make<Expr>(ExprKind::Name, loc(f->ident()));
        e->name = f->ident()->getText();
        (self ? e->ofThis : e->ofSuper) = true;
        selectors.erase(selectors.begin(), selectors.begin() + 2);
      }
    if (self && !e->ofThis) { // THIS^ itself
      e->name = "THIS^";
      e->selfInstance = true;
      selectors.erase(selectors.begin());
    }
  }
  for (auto *sel : selectors) {
    if (auto *f = alt<P::FieldSelContext>(sel)) {
      Expr *fe = unit.make<Expr>(ExprKind::Field, loc(f->ident()));
      fe->name = f->ident()->getText();
      fe->operands.push_back(e);
      e = fe;
    } else if (auto *b = alt<P::BitSelContext>(sel)) {
      Expr *be = unit.make<Expr>(ExprKind::BitAccess, loc(b->INTEGER()));
      if (!st::parseIntegerLiteral(b->INTEGER()->getText(), be->intValue))
        return refuse(loc(b->INTEGER()), "malformed bit number");
      be->operands.push_back(e);
      e = be;
    } else if (auto *p = alt<P::PartSelContext>(sel)) {
      Expr *pe = unit.make<Expr>(ExprKind::BitAccess, loc(p->DIRECT()));
      std::string text = p->DIRECT()->getText();
      char size = text.size() > 1 ? toupper(text[1]) : 0;
      pe->partWidth = size == 'X'   ? 1
                      : size == 'B' ? 8
                      : size == 'W' ? 16
                      : size == 'D' ? 32
                      : size == 'L' ? 64
                                    : 0;
      if (!pe->partWidth || text.size() < 3 ||
          !st::parseIntegerLiteral(StringRef(text).drop_front(2), pe->intValue))
        return refuse(loc(p->DIRECT()),
                      "'" + text +
                          "' is not a partial access (%Xn, %Bn, "
                          "%Wn, %Dn or %Ln)");
      pe->operands.push_back(e);
      e = pe;
    } else if (auto *ix = alt<P::IndexSelContext>(sel)) {
      Expr *ie = unit.make<Expr>(ExprKind::Index, loc(ix));
      ie->operands.push_back(e);
      for (auto *x : ix->expression())
        ie->operands.push_back(expr(x));
      e = ie;
    } else {
      Expr *de = unit.make<Expr>(ExprKind::Deref, loc(sel));
      de->operands.push_back(e);
      e = de;
    }
  }
  return failed ? nullptr : e;
}

Expr *AstBuilder::literal(P::LiteralContext *c) {
  SMLoc at = loc(c);
  if (auto *i = alt<P::IntLiteralContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::IntLit, at);
    if (!st::parseIntegerLiteral(i->getText(), e->intValue, &e->beyondInt64))
      return refuse(at, "integer literal '" + i->getText() +
                            "' is out of "
                            "range");
    return e;
  }
  if (auto *r = alt<P::RealLiteralContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::RealLit, at);
    std::string t;
    for (char ch : r->getText())
      if (ch != '_')
        t += ch;
    e->realValue = std::strtod(t.c_str(), nullptr);
    return e;
  }
  if (auto *b = alt<P::BoolLiteralContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::BoolLit, at);
    e->intValue = b->TRUE() != nullptr;
    return e;
  }
  if (auto *d = alt<P::DurationLiteralContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::TimeLit, at);
    std::string err;
    if (!st::parseDuration(d->getText(), e->intValue, err))
      return refuse(at, err);
    return e;
  }
  if (alt<P::DateLiteralContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::DateLit, at);
    e->name = c->getText();
    IecTimeKind kind;
    std::string err;
    if (!parseIecTime(e->name, kind, e->intValue, err))
      return refuse(at, err);
    bool wide = std::toupper(static_cast<unsigned char>(e->name[0])) == 'L';
    e->typeName = kind == IecTimeKind::Date        ? "DATE"
                  : kind == IecTimeKind::TimeOfDay ? "TOD"
                                                   : "DT";
    if (wide)
      e->typeName = "L" + e->typeName;
    return e;
  }
  if (auto *s = alt<P::StringLiteralContext>(c)) {
    Expr *e = unit.make<Expr>(ExprKind::StringLit, at);
    e->name = s->getText();
    return e;
  }
  auto *t = static_cast<P::TypedLiteralContext *>(c);
  std::string typeName = t->type->getText();
  std::string value = t->value ? t->value->getText() : t->enumName->getText();
  bool negative = t->sign && t->sign->getType() == P::MINUS;
  switch (t->value ? t->value->getType() : size_t(P::IDENT)) {
  case P::INTEGER: {
    Expr *e = unit.make<Expr>(ExprKind::IntLit, at);
    e->typeName = typeName;
    if (!st::parseIntegerLiteral(value, e->intValue, &e->beyondInt64) ||
        (negative && e->beyondInt64))
      return refuse(at, "integer literal '" + value + "' is out of range");
    if (negative)
      e->intValue = -e->intValue;
    return e;
  }
  case P::REAL_LIT: {
    Expr *e = unit.make<Expr>(ExprKind::RealLit, at);
    e->typeName = typeName;
    e->realValue = std::strtod(value.c_str(), nullptr) * (negative ? -1 : 1);
    return e;
  }
  case P::TRUE:
  case P::FALSE: {
    Expr *e = unit.make<Expr>(ExprKind::BoolLit, at);
    e->typeName = typeName;
    e->intValue = t->value->getType() == P::TRUE;
    return e;
  }
  case P::STRING_LIT:
  case P::WSTRING_LIT: {
    Expr *e = unit.make<Expr>(ExprKind::StringLit, at);
    e->typeName = typeName;
    e->name = value;
    return e;
  }
  default: {
    if (negative)
      return refuse(at, "a sign before an enumerated value");
    Expr *e = unit.make<Expr>(ExprKind::EnumLit, at);
    e->typeName = typeName;
    e->name = value;
    return e;
  }
  }
}

//===----------------------------------------------------------------------===//
// Entry points
//===----------------------------------------------------------------------===//

namespace {

/// Runs `rule` on a parser over `text`, SLL first, full LL on failure,
/// reporting one syntax error per statement. Returns null on error.
template <typename Ctx>
Ctx *parseWith(StringRef text, DiagEngine &diag, st::StLexer &lexer,
               antlr4::CommonTokenStream &tokens, P &parser, Ctx *(P::*rule)(),
               unsigned maxErrors, const char *eofName = "end of file") {
  parser.removeErrorListeners();
  parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(
      antlr4::atn::PredictionMode::SLL);
  parser.setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
  try {
    Ctx *tree = (parser.*rule)();
    if (lexer.hadError())
      return nullptr;
    return tree;
  } catch (antlr4::ParseCancellationException &) {
  }
  if (lexer.hadError())
    return nullptr;
  // Full LL, one syntax error per statement: after each error the broken
  // statement is hidden and the text parsed again (files with syntax
  // errors are rare and small; correct files never come here twice).
  unsigned reported = 0;
  std::optional<size_t> lastUnclosed;
  Ctx *tree = nullptr;
  for (;;) {
    tokens.seek(0);
    parser.reset();
    parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->setPredictionMode(
        antlr4::atn::PredictionMode::LL);
    parser.setErrorHandler(std::make_shared<antlr4::DefaultErrorStrategy>());
    FirstErrorListener listener;
    listener.eofName = eofName;
    parser.addErrorListener(&listener);
    tree = nullptr;
    try {
      tree = (parser.*rule)();
    } catch (antlr4::RecognitionException &) {
    } catch (antlr4::ParseCancellationException &) {
    }
    parser.removeErrorListeners();
    if (lexer.hadError())
      return nullptr;
    if (!listener.seen)
      break;
    // The same statement left open again (the parse after hiding the
    // first error's statement reaches the end): said once.
    if (listener.unclosedOffset && listener.unclosedOffset == lastUnclosed)
      break;
    lastUnclosed = listener.unclosedOffset;
    diag.syntaxError(lexer.locAt(listener.offset), listener.message);
    if (listener.unclosedOffset)
      diag.note(lexer.locAt(*listener.unclosedOffset),
                "the " + listener.unclosedWhat + " opened here is not closed");
    tokens.fill(); // the parse stopped at the error: the rest is unread
    if (++reported >= maxErrors || listener.atEof ||
        !hideStatement(tokens, parser.getVocabulary(), listener.tokenIndex))
      break;
  }
  return reported ? nullptr : tree;
}

bool parseDeclarations(StringRef text, DiagEngine &diag, Unit &unit,
                       VarSection section, bool constant, bool retain,
                       std::vector<VarDecl *> &out) {
  st::StLexer lexer(text, diag);
  antlr4::CommonTokenStream tokens(&lexer);
  P parser(&tokens);
  P::VarDeclsOnlyContext *tree =
      parseWith(text, diag, lexer, tokens, parser, &P::varDeclsOnly,
                st::kMaxSyntaxErrors, "END_VAR");
  if (!tree)
    return false;
  AstBuilder builder(text, diag, unit, tokens);
  for (auto *d : tree->varDecl()) {
    builder.declare(d, section, constant, retain, out);
    if (builder.failed)
      return false;
  }
  return true;
}

} // namespace

bool st::parseStructuredText(StringRef text, DiagEngine &diag, Unit &unit,
                             const ParseOptions &options) {
  // Conditional compilation first: what is parsed is a copy of the buffer
  // with the branches not taken blanked, under the file's name.
  bool changed = false;
  std::optional<std::string> resolved =
      resolveConditionals(text, diag, unit.defines, changed);
  if (!resolved)
    return false;
  if (changed) {
    llvm::SourceMgr &sm = diag.sourceMgr();
    unsigned id =
        sm.FindBufferContainingLoc(SMLoc::getFromPointer(text.data()));
    const llvm::MemoryBuffer *buf = sm.getMemoryBuffer(id);
    size_t offset = text.data() - buf->getBufferStart();
    std::string whole = buf->getBuffer().str();
    whole.replace(offset, text.size(), *resolved);
    unsigned copy = sm.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(whole, buf->getBufferIdentifier()),
        SMLoc());
    text = sm.getMemoryBuffer(copy)->getBuffer().substr(offset, text.size());
  }
  st::LongParts parts = st::findLongParts(text, diag, options);
  StLexer lexer(text, diag);
  st::SkippingSource source(lexer, parts.ranges);
  antlr4::CommonTokenStream tokens(&source);
  P parser(&tokens);
  P::CompilationUnitContext *tree = parseWith(
      text, diag, lexer, tokens, parser, &P::compilationUnit, kMaxSyntaxErrors);
  if (!tree)
    return false;
  AstBuilder builder(text, diag, unit, tokens);
  builder.skipped = &parts.groups;
  return builder.build(tree);
}

/// Parses `text` with the one-rule entry `rule` (an expression, an initial
/// value or a body alone) and hands its tree to `build`; false when the
/// parse or the build failed.
template <typename Ctx, typename Build>
static bool parseAlone(StringRef text, DiagEngine &diag, Unit &unit,
                       Ctx *(P::*rule)(), unsigned maxErrors, const char *end,
                       Build build) {
  st::StLexer lexer(text, diag);
  antlr4::CommonTokenStream tokens(&lexer);
  P parser(&tokens);
  Ctx *tree =
      parseWith(text, diag, lexer, tokens, parser, rule, maxErrors, end);
  if (!tree)
    return false;
  AstBuilder builder(text, diag, unit, tokens);
  build(builder, tree);
  return !builder.failed;
}

Expr *st::parseStExpression(StringRef text, DiagEngine &diag, Unit &unit) {
  Expr *e = nullptr;
  parseAlone(text, diag, unit, &P::expressionOnly, /*maxErrors=*/1,
             "end of the expression",
             [&](AstBuilder &b, P::ExpressionOnlyContext *t) {
               e = b.expr(t->expression());
             });
  return e;
}

Initializer *st::parseStInitializer(StringRef text, DiagEngine &diag,
                                    Unit &unit) {
  Initializer *init = nullptr;
  bool ok = parseAlone(text, diag, unit, &P::initializerOnly, /*maxErrors=*/1,
                       "end of the initial value",
                       [&](AstBuilder &b, P::InitializerOnlyContext *t) {
                         init = b.initializer(t->initializer());
                       });
  return ok ? init : nullptr;
}

bool st::parseAlgorithmBody(StringRef text, DiagEngine &diag, Unit &unit,
                            std::vector<VarDecl *> &temps, StmtList &out) {
  bool ok = parseAlone(text, diag, unit, &P::algorithmBody, kMaxSyntaxErrors,
                       "end of the body",
                       [&](AstBuilder &b, P::AlgorithmBodyContext *t) {
                         for (P::VarBlockContext *vb : t->varBlock())
                           b.varBlock(vb, temps);
                         b.bodyStatements(t->bodyStatementList(), out);
                       });
  for (VarDecl *v : temps)
    if (v->section != VarSection::Temp) {
      diag.error(v->loc, "'" + v->name +
                             "' is declared in an algorithm outside "
                             "VAR_TEMP; an algorithm declares temporaries "
                             "only (VAR_TEMP ... END_VAR)");
      ok = false;
    }
  return ok;
}

Pou *st::parseMethod(StringRef text, DiagEngine &diag, Unit &unit, Pou *owner) {
  Pou *m = nullptr;
  bool ok = parseAlone(text, diag, unit, &P::methodOnly, kMaxSyntaxErrors,
                       "end of the method",
                       [&](AstBuilder &b, P::MethodOnlyContext *t) {
                         m = b.methodOf(t->methodDecl(), owner);
                       });
  return ok ? m : nullptr;
}

Pou *st::parseMethodBody(StringRef text, StringRef name, StringRef resultType,
                         SMLoc at, DiagEngine &diag, Unit &unit, Pou *owner) {
  Pou *m = nullptr;
  bool ok = parseAlone(text, diag, unit, &P::methodBodyOnly, kMaxSyntaxErrors,
                       "end of the method",
                       [&](AstBuilder &b, P::MethodBodyOnlyContext *t) {
                         m = b.methodFromBody(t, name, resultType, at, owner);
                       });
  return ok ? m : nullptr;
}

bool st::parseStatements(StringRef text, DiagEngine &diag, Unit &unit,
                         StmtList &out) {
  return parseAlone(text, diag, unit, &P::statementsOnly, kMaxSyntaxErrors,
                    "end of the body",
                    [&](AstBuilder &b, P::StatementsOnlyContext *t) {
                      b.bodyStatements(t->bodyStatementList(), out);
                    });
}
