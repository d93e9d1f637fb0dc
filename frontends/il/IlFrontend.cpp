//===- IlFrontend.cpp - Instruction List into the PLC model ---------------===//
//
// How an instruction list becomes statements:
//  - The current result (CR) is kept as an expression while instructions
//    compute it: `LD a  AND b  ST c` becomes `c := a AND b;`. Before an
//    instruction writes a variable the pending CR reads, CR is first stored
//    into a fresh accumulator temporary (typed by its first value), so CR
//    always means the value at the instruction that computed it.
//  - `OP(` pushes the pending operation; `)` applies it to the inner CR.
//  - Jumps go forward only (a backward jump is a loop netlift cannot
//    bound): a jump sets a flag, and every instruction up to the label runs
//    under `IF NOT flag`. A jump carries CR to its label (stored in a
//    temporary per label, which the fall-through path also writes).
//  - S, R on a BOOL set or reset it when CR is TRUE; the FB input
//    operators (S1, R1, CLK, CU, CD, PV, IN, PT, and S/R on an SR or RS
//    instance) call the instance with that input from CR.
//
//===----------------------------------------------------------------------===//
#include "frontends/il/IlFrontend.h"
#include "frontends/st/StFrontend.h"
#include "frontends/st/StLexer.h"
#include "frontends/st/StdLib.h"

#include "IL.h"
#include "ST.h"

#include "llvm/ADT/StringSwitch.h"
#include "llvm/Support/MemoryBuffer.h"

#include <map>
#include <optional>
#include <set>

using namespace netlift;
using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;
using llvm::Twine;
using IP = ilgen::IL;
using SP = stgen::ST;

namespace {

struct Refusal {};

/// The span of one POU's body in the file.
struct BodySpan {
  size_t begin, end; // byte offsets: [begin, end)
};

/// Finds the instruction-list bodies: after a POU's last END_VAR (or its
/// name and result type) up to its END_ keyword.
std::vector<BodySpan> findBodies(StringRef text) {
  std::vector<BodySpan> spans;
  llvm::SourceMgr scratchSm;
  DiagEngine quiet(scratchSm);
  st::StLexer lexer(text, quiet);
  lexer.setSilent();
  std::vector<std::unique_ptr<antlr4::Token>> toks;
  for (;;) {
    auto t = lexer.nextToken();
    bool eof = t->getType() == antlr4::Token::EOF;
    if (t->getChannel() == 0 || eof)
      toks.push_back(std::move(t));
    if (eof)
      break;
  }
  bool inConfig = false;
  for (size_t i = 0; i < toks.size(); ++i) {
    size_t type = toks[i]->getType();
    if (type == SP::CONFIGURATION)
      inConfig = true;
    if (type == SP::END_CONFIGURATION)
      inConfig = false;
    if (inConfig || (type != SP::PROGRAM && type != SP::FUNCTION_BLOCK &&
                     type != SP::FUNCTION))
      continue;
    size_t endType = type == SP::PROGRAM          ? SP::END_PROGRAM
                     : type == SP::FUNCTION_BLOCK ? SP::END_FUNCTION_BLOCK
                                                  : SP::END_FUNCTION;
    size_t j = i + 1;
    size_t bodyTok = i + 2 < toks.size() ? i + 2 : i + 1; // after the name
    if (type == SP::FUNCTION && bodyTok < toks.size() &&
        toks[bodyTok]->getType() == SP::COLON)
      bodyTok += 2; // `: TYPE`
    for (; j < toks.size() && toks[j]->getType() != endType &&
           toks[j]->getType() != antlr4::Token::EOF;
         ++j)
      if (toks[j]->getType() == SP::END_VAR)
        bodyTok = j + 1;
    if (j >= toks.size() || toks[j]->getType() != endType)
      break; // the ST parser reports the missing END_
    size_t begin =
        bodyTok < j ? toks[bodyTok]->getStartIndex() : toks[j]->getStartIndex();
    spans.push_back({begin, toks[j]->getStartIndex()});
    i = j;
  }
  return spans;
}

class IlLowering {
public:
  IlLowering(StringRef text, DiagEngine &diag, Unit &unit, Pou *pou)
      : text(text), diag(diag), unit(unit), pou(pou) {}

  void lower(IP::IlBodyContext *body);
  /// The current result after the last instruction (null when none set it).
  Expr *result() const { return cr; }

private:
  [[noreturn]] void refuse(SMLoc at, const Twine &msg) {
    diag.error(at, msg);
    throw Refusal{};
  }
  SMLoc loc(antlr4::Token *t) {
    return SMLoc::getFromPointer(text.data() + t->getStartIndex());
  }
  SMLoc loc(antlr4::ParserRuleContext *c) { return loc(c->getStart()); }
  StringRef slice(antlr4::ParserRuleContext *c) {
    size_t a = c->getStart()->getStartIndex();
    size_t b = c->getStop()->getStopIndex() + 1;
    return text.substr(a, b - a);
  }
  Expr *operand(IP::OperandContext *c);
  Expr *need(SMLoc at, StringRef op);
  /// A temporary of the POU (`type` empty: typed by its first value).
  VarDecl *temp(const std::string &name, StringRef type);
  Expr *nameRef(VarDecl *v, SMLoc at);
  Expr *binary(Op op, Expr *a, Expr *b, SMLoc at);
  Expr *notOf(Expr *a, SMLoc at);
  void emit(Stmt *s);
  void materializeIfReads(const std::set<std::string> &written, SMLoc at);
  bool isFbInstance(Expr *e);
  void callArgs(std::vector<IP::CallArgContext *> args,
                std::vector<CallArg> &out);
  void instruction(IP::InstructionContext *c);

  StringRef text;
  DiagEngine &diag;
  Unit &unit;
  Pou *pou;

  Expr *cr = nullptr;
  struct Pending {
    std::string op;
    Expr *saved;
    SMLoc loc;
  };
  std::vector<Pending> parens;
  struct Jump {
    std::string label;
    VarDecl *flag;
  };
  std::vector<Jump> active;
  std::set<std::string> labelsSeen;
  std::map<std::string, VarDecl *> labelCr; // CR carried by jumps
  std::set<std::string> startsFresh; // labels whose code begins with a load
  std::vector<VarDecl *> flags;
  // The guard block statements go into while the active jumps are the same.
  Stmt *guard = nullptr;
  size_t guardJumps = 0;
  unsigned temps = 0;
};

} // namespace

Expr *IlLowering::operand(IP::OperandContext *c) {
  Expr *e = st::parseStExpression(slice(c), diag, unit);
  if (!e)
    throw Refusal{};
  return e;
}

Expr *IlLowering::need(SMLoc at, StringRef op) {
  if (!cr)
    refuse(at, "'" + op + "' needs a current result (load one with LD first)");
  return cr;
}

VarDecl *IlLowering::temp(const std::string &name, StringRef type) {
  return AstMaker(unit).declare(*pou, name, type, pou->loc, VarSection::Temp);
}

Expr *IlLowering::nameRef(VarDecl *v, SMLoc at) {
  Expr *e = unit.make<Expr>(ExprKind::Name, at);
  e->name = v->name;
  return e;
}

Expr *IlLowering::binary(Op op, Expr *a, Expr *b, SMLoc at) {
  Expr *e = unit.make<Expr>(ExprKind::Binary, at);
  e->op = op;
  e->operands = {a, b};
  return e;
}

Expr *IlLowering::notOf(Expr *a, SMLoc at) {
  Expr *e = unit.make<Expr>(ExprKind::Unary, at);
  e->op = Op::Not;
  e->operands = {a};
  return e;
}

static void rootsRead(Expr *e, std::set<std::string> &out) {
  if (!e)
    return;
  if (e->kind == ExprKind::Name)
    out.insert(StringRef(e->name).upper());
  for (Expr *o : e->operands)
    rootsRead(o, out);
  for (CallArg &a : e->args)
    rootsRead(a.value, out);
}

static std::string rootOf(Expr *e) {
  while (e && e->kind != ExprKind::Name)
    e = e->base();
  return e ? StringRef(e->name).upper() : "";
}

void IlLowering::materializeIfReads(const std::set<std::string> &written,
                                    SMLoc at) {
  if (!cr)
    return;
  std::set<std::string> reads;
  rootsRead(cr, reads);
  // Calls read through their callee's memory too: be safe with any call.
  bool hasCall = false;
  std::function<void(Expr *)> scan = [&](Expr *e) {
    if (!e)
      return;
    hasCall |= e->kind == ExprKind::Call;
    for (Expr *o : e->operands)
      scan(o);
  };
  scan(cr);
  bool conflict = hasCall && !written.empty();
  for (const std::string &w : written)
    conflict |= reads.count(w) > 0;
  if (!conflict)
    return;
  VarDecl *t = temp("_CR" + std::to_string(++temps), "");
  Stmt *s = unit.make<Stmt>(StmtKind::Assign, at);
  s->target = nameRef(t, at);
  s->value = cr;
  emit(s);
  cr = nameRef(t, at);
}

void IlLowering::emit(Stmt *s) {
  if (active.empty()) {
    pou->body.push_back(s);
    guard = nullptr;
    return;
  }
  if (!guard || guardJumps != active.size()) {
    // IF NOT (flag1 OR flag2 ...) THEN ... END_IF
    Expr *any = nullptr;
    for (Jump &j : active) {
      Expr *f = nameRef(j.flag, s->loc);
      any = any ? binary(Op::Or, any, f, s->loc) : f;
    }
    guard = unit.make<Stmt>(StmtKind::If, s->loc);
    guard->arms.push_back({notOf(any, s->loc), {}});
    guardJumps = active.size();
    pou->body.push_back(guard);
  }
  guard->arms[0].second.push_back(s);
}

bool IlLowering::isFbInstance(Expr *e) {
  if (!e || e->kind != ExprKind::Name)
    return false;
  VarDecl *v = pou->find(e->name);
  if (!v || !v->typeSyntax || v->typeSyntax->kind != TypeSyntaxKind::Named)
    return false;
  // The standard blocks join the unit only when every file is read.
  Pou *p = unit.findPou(v->typeSyntax->name);
  return p ? p->kind == PouKind::FunctionBlock
           : st::isStandardFunctionBlock(v->typeSyntax->name);
}

void IlLowering::callArgs(std::vector<IP::CallArgContext *> args,
                          std::vector<CallArg> &out) {
  for (auto *a : args) {
    CallArg arg;
    arg.loc = loc(a);
    arg.name = a->name->getText();
    arg.isOutput = a->OUTPUT_ASSIGN() != nullptr;
    arg.negated = a->NOT() != nullptr;
    if (!a->operand())
      refuse(arg.loc, "argument '" + arg.name + "' has no value");
    arg.value = operand(a->operand());
    out.push_back(arg);
  }
}

/// The binary IL operators: the operation and whether the operand is
/// negated (ANDN, &N, ORN, XORN). Null for anything else.
static std::optional<std::pair<Op, bool>> binaryOperator(StringRef up) {
  bool negated = up == "ANDN" || up == "&N" || up == "ORN" || up == "XORN";
  if (negated)
    up = up.drop_back();
  Op op = llvm::StringSwitch<Op>(up)
              .Cases("AND", "&", Op::And)
              .Case("OR", Op::Or)
              .Case("XOR", Op::Xor)
              .Case("ADD", Op::Add)
              .Case("SUB", Op::Sub)
              .Case("MUL", Op::Mul)
              .Case("DIV", Op::Div)
              .Case("MOD", Op::Mod)
              .Case("GT", Op::Gt)
              .Case("GE", Op::Ge)
              .Case("EQ", Op::Eq)
              .Case("NE", Op::Ne)
              .Case("LE", Op::Le)
              .Case("LT", Op::Lt)
              .Default(Op::Pow);
  if (op == Op::Pow)
    return std::nullopt;
  return std::make_pair(op, negated);
}

void IlLowering::instruction(IP::InstructionContext *c) {
  SMLoc at = loc(c);
  if (dynamic_cast<IP::CloseParenContext *>(c)) {
    if (parens.empty())
      refuse(at, "')' without a matching 'OP('");
    Pending p = parens.back();
    parens.pop_back();
    Expr *inner = need(at, ")");
    cr = p.saved;
    // Apply the deferred operation as if its operand were the inner CR.
    auto bop = binaryOperator(p.op);
    if (!bop)
      refuse(p.loc, "'" + p.op + "(' is not an operator that takes '('");
    if (bop->second)
      inner = notOf(inner, at);
    cr = binary(bop->first, need(p.loc, p.op), inner, p.loc);
    return;
  }
  std::string op;
  IP::OpNameContext *opCtx = nullptr;
  if (auto *s = dynamic_cast<IP::SimpleContext *>(c))
    opCtx = s->op;
  else if (auto *d = dynamic_cast<IP::DeferredContext *>(c))
    opCtx = d->op;
  else if (auto *f = dynamic_cast<IP::FormalCallContext *>(c))
    opCtx = f->op;
  else if (auto *w = dynamic_cast<IP::CallWithArgsContext *>(c))
    opCtx = w->op;
  for (antlr4::tree::ParseTree *ch : opCtx->children)
    op += ch->getText();
  std::string up = StringRef(op).upper();

  if (auto *d = dynamic_cast<IP::DeferredContext *>(c)) {
    parens.push_back({up, cr, at});
    cr = d->operand() ? operand(d->operand()) : nullptr;
    return;
  }

  auto call = [&](Expr *callee, std::vector<CallArg> args, Expr *condition) {
    std::set<std::string> written{rootOf(callee)};
    for (CallArg &a : args)
      if (a.isOutput)
        written.insert(rootOf(a.value));
    materializeIfReads(written, at);
    Stmt *s = unit.make<Stmt>(StmtKind::Call, at);
    Expr *e = unit.make<Expr>(ExprKind::Call, at);
    e->name = callee->name;
    e->args = std::move(args);
    s->value = e;
    if (condition) {
      Stmt *i = unit.make<Stmt>(StmtKind::If, at);
      i->arms.push_back({condition, {s}});
      emit(i);
    } else {
      emit(s);
    }
  };

  if (auto *w = dynamic_cast<IP::CallWithArgsContext *>(c)) {
    if (up != "CAL" && up != "CALC" && up != "CALCN")
      refuse(at, "'" + op +
                     "' takes no parenthesised arguments after a "
                     "name");
    Expr *callee = unit.make<Expr>(ExprKind::Name, loc(w->target));
    callee->name = w->target->getText();
    std::vector<CallArg> args;
    callArgs(w->callArg(), args);
    Expr *cond = up == "CALC"    ? need(at, op)
                 : up == "CALCN" ? notOf(need(at, op), at)
                                 : nullptr;
    call(callee, std::move(args), cond);
    return;
  }
  if (auto *f = dynamic_cast<IP::FormalCallContext *>(c)) {
    // A function with formal arguments: CR := F(IN1 := ..., ...).
    Expr *e = unit.make<Expr>(ExprKind::Call, at);
    e->name = op;
    callArgs(f->callArg(), e->args);
    cr = e;
    return;
  }

  auto *s = static_cast<IP::SimpleContext *>(c);
  std::vector<Expr *> ops;
  for (auto *o : s->operand())
    ops.push_back(operand(o));
  auto one = [&]() -> Expr * {
    if (ops.size() != 1)
      refuse(at, "'" + op + "' takes one operand");
    return ops[0];
  };
  auto none = [&] {
    if (!ops.empty())
      refuse(loc(s->operand(0)), "'" + op + "' takes no operand");
  };

  if (up == "LD" || up == "LDN") {
    Expr *v = one();
    cr = up == "LD" ? v : notOf(v, at);
    return;
  }
  if (up == "ST" || up == "STN") {
    Expr *t = one();
    Expr *v = need(at, op);
    materializeIfReads({rootOf(t)}, at);
    v = cr;
    Stmt *st = unit.make<Stmt>(StmtKind::Assign, at);
    st->target = t;
    st->value = up == "ST" ? v : notOf(v, at);
    emit(st);
    return;
  }
  static const char *fbInputs[] = {"S1", "R1", "CLK", "CU", "CD",
                                   "PV", "IN", "PT",  "S",  "R"};
  for (const char *fi : fbInputs)
    if (up == fi && ops.size() == 1 && isFbInstance(ops[0])) {
      CallArg a;
      a.name = fi;
      a.value = need(at, op);
      a.loc = at;
      call(ops[0], {a}, nullptr);
      return;
    }
  if (up == "S" || up == "R") {
    Expr *t = one();
    Expr *cond = need(at, op);
    materializeIfReads({rootOf(t)}, at);
    cond = cr;
    Stmt *st = unit.make<Stmt>(StmtKind::Assign, at);
    st->target = t;
    st->value = unit.make<Expr>(ExprKind::BoolLit, at);
    st->value->intValue = up == "S";
    Stmt *i = unit.make<Stmt>(StmtKind::If, at);
    i->arms.push_back({cond, {st}});
    emit(i);
    return;
  }
  if (up == "NOT") {
    none();
    cr = notOf(need(at, op), at);
    return;
  }
  if (auto bop = binaryOperator(up)) {
    Expr *v = one();
    if (bop->second)
      v = notOf(v, at);
    cr = binary(bop->first, need(at, op), v, at);
    return;
  }
  if (up == "JMP" || up == "JMPC" || up == "JMPCN") {
    if (ops.size() != 1 || ops[0]->kind != ExprKind::Name)
      refuse(at, "'" + op + "' takes a label");
    std::string label = StringRef(ops[0]->name).upper();
    if (labelsSeen.count(label))
      refuse(at, "backward jump to '" + ops[0]->name +
                     "' is a loop netlift cannot bound; it is refused");
    VarDecl *flag = temp("_JMP" + std::to_string(flags.size() + 1), "BOOL");
    flags.push_back(flag);
    Expr *value = up == "JMP"    ? nullptr
                  : up == "JMPC" ? need(at, op)
                                 : notOf(need(at, op), at);
    if (!value) {
      value = unit.make<Expr>(ExprKind::BoolLit, at);
      value->intValue = 1;
    }
    // The jump carries CR to its label (when the label's code reads it).
    if (cr && !startsFresh.count(label)) {
      VarDecl *&carry = labelCr[label];
      if (!carry)
        carry = temp("_CR_" + ops[0]->name, "");
      Stmt *keep = unit.make<Stmt>(StmtKind::Assign, at);
      keep->target = nameRef(carry, at);
      keep->value = cr;
      emit(keep);
    }
    Stmt *st = unit.make<Stmt>(StmtKind::Assign, at);
    st->target = nameRef(flag, at);
    st->value = value;
    emit(st);
    active.push_back({label, flag});
    if (up == "JMP")
      cr = nullptr; // what follows is reached only through a label
    return;
  }
  if (up == "RET" || up == "RETC" || up == "RETCN") {
    none();
    Stmt *r = unit.make<Stmt>(StmtKind::Return, at);
    if (up == "RET") {
      emit(r);
    } else {
      Stmt *i = unit.make<Stmt>(StmtKind::If, at);
      Expr *cond = up == "RETC" ? need(at, op) : notOf(need(at, op), at);
      i->arms.push_back({cond, {r}});
      emit(i);
    }
    return;
  }
  if (up == "CAL" || up == "CALC" || up == "CALCN") {
    Expr *callee = one();
    if (callee->kind != ExprKind::Name)
      refuse(at, "CAL needs a function block instance name");
    Expr *cond = up == "CALC"    ? need(at, op)
                 : up == "CALCN" ? notOf(need(at, op), at)
                                 : nullptr;
    call(callee, {}, cond);
    return;
  }
  // Anything else names a function: CR := F(CR, operands...).
  Expr *e = unit.make<Expr>(ExprKind::Call, at);
  e->name = op;
  CallArg first;
  first.value = need(at, op);
  first.loc = at;
  e->args.push_back(first);
  for (Expr *o : ops) {
    CallArg a;
    a.value = o;
    a.loc = o->loc;
    e->args.push_back(a);
  }
  cr = e;
}

void IlLowering::lower(IP::IlBodyContext *body) {
  // Labels followed by LD/LDN need no CR from their jumps (and jumps may
  // then carry CRs of different types there).
  for (auto *line : body->ilLine()) {
    auto *label = line->labelDef();
    auto *s = line->instruction()
                  ? dynamic_cast<IP::SimpleContext *>(line->instruction())
                  : nullptr;
    if (label && s) {
      std::string op = StringRef(s->op->getText()).upper();
      if (op == "LD" || op == "LDN")
        startsFresh.insert(StringRef(label->name->getText()).upper());
    }
  }
  for (auto *line : body->ilLine()) {
    if (auto *label = line->labelDef()) {
      std::string name = StringRef(label->name->getText()).upper();
      if (!labelsSeen.insert(name).second)
        refuse(loc(label),
               "label '" + label->name->getText() + "' is defined twice");
      // CR at a label: what the jumps carried, or what falls through.
      auto carried = labelCr.find(name);
      if (carried != labelCr.end() && cr && !startsFresh.count(name)) {
        Stmt *keep = unit.make<Stmt>(StmtKind::Assign, loc(label));
        keep->target = nameRef(carried->second, loc(label));
        keep->value = cr;
        emit(keep); // still under the guards of the jumps to this label
      }
      // Jumps to this label end here.
      size_t before = active.size();
      active.erase(
          std::remove_if(active.begin(), active.end(),
                         [&](const Jump &j) { return j.label == name; }),
          active.end());
      if (active.size() != before)
        guard = nullptr;
      if (!parens.empty())
        refuse(loc(label), "label inside a parenthesised operation");
      cr = carried != labelCr.end() ? nameRef(carried->second, loc(label))
                                    : nullptr;
    }
    if (line->instruction())
      instruction(line->instruction());
  }
  if (!parens.empty())
    refuse(parens.back().loc, "'(' is never closed");
  if (!active.empty())
    refuse(pou->loc, "jump to undefined label '" + active.front().label + "'");
  // Flags start FALSE at every execution of the body (an FB may run twice
  // in a scan).
  std::vector<Stmt *> init;
  for (VarDecl *f : flags) {
    Stmt *s = unit.make<Stmt>(StmtKind::Assign, pou->loc);
    s->target = nameRef(f, pou->loc);
    s->value = unit.make<Expr>(ExprKind::BoolLit, pou->loc);
    init.push_back(s);
  }
  pou->body.insert(pou->body.begin(), init.begin(), init.end());
}

/// Moves the tokens of the line holding token `at` (not its line end) off
/// the parser's channel; false when there were none.
static bool hideLine(antlr4::BufferedTokenStream &tokens, size_t at) {
  auto isLineEnd = [&](size_t i) {
    size_t type = tokens.get(i)->getType();
    return type == SP::EOL || type == antlr4::Token::EOF;
  };
  size_t n = tokens.size();
  if (at >= n)
    return false;
  size_t begin = at;
  while (begin > 0 && !isLineEnd(begin - 1))
    --begin;
  size_t end = at;
  while (end < n && !isLineEnd(end))
    ++end;
  return st::hideTokens(tokens, begin, end);
}

bool il::parseInstructionList(unsigned bufferID, DiagEngine &diag, Unit &unit) {
  llvm::SourceMgr &sm = diag.sourceMgr();
  const llvm::MemoryBuffer *buf = sm.getMemoryBuffer(bufferID);
  StringRef text = buf->getBuffer();
  std::vector<BodySpan> spans = findBodies(text);

  // The declarations, with the bodies blanked out (line ends kept, so every
  // location is the same), parsed as Structured Text.
  std::string blanked = text.str();
  for (const BodySpan &s : spans)
    for (size_t i = s.begin; i < s.end; ++i)
      if (blanked[i] != '\n')
        blanked[i] = ' ';
  unsigned declID = sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(blanked, buf->getBufferIdentifier()),
      SMLoc());
  size_t firstPou = unit.pous.size();
  if (!st::parseStructuredText(sm.getMemoryBuffer(declID)->getBuffer(), diag,
                               unit))
    return false;
  if (unit.pous.size() - firstPou != spans.size()) {
    diag.error(SMLoc::getFromPointer(text.data()),
               "could not find the instruction list of every POU");
    return false;
  }
  for (size_t k = 0; k < spans.size(); ++k) {
    Pou *pou = unit.pous[firstPou + k];
    StringRef body = text.substr(spans[k].begin, spans[k].end - spans[k].begin);
    if (!il::parseInstructionListBody(body, diag, unit, pou))
      return false;
  }
  return true;
}

bool il::parseInstructionListBody(StringRef body, DiagEngine &diag, Unit &unit,
                                  Pou *pou, Expr **result) {
  st::StLexer lexer(body, diag, /*lineEnds=*/true);
  antlr4::CommonTokenStream tokens(&lexer);
  IP parser(&tokens);
  parser.removeErrorListeners();
  // One error per instruction: after an error its line is taken out of
  // the parse (off the parser's channel) and the body parsed again, so
  // that the next report is the next mistake, not ANTLR's recovery.
  struct Listener : antlr4::BaseErrorListener {
    void syntaxError(antlr4::Recognizer *, antlr4::Token *t, size_t, size_t,
                     const std::string &msg, std::exception_ptr) override {
      if (seen)
        return;
      seen = true;
      offset = t ? t->getStartIndex() : 0;
      tokenIndex = t ? t->getTokenIndex() : 0;
      text = t && t->getType() != antlr4::Token::EOF
                 ? "syntax error in instruction list at '" + t->getText() + "'"
                 : "syntax error in instruction list: " + msg;
      if (t && t->getType() == SP::EOL)
        text = "syntax error in instruction list: unexpected end of line";
    }
    bool seen = false;
    size_t offset = 0, tokenIndex = 0;
    std::string text;
  } listener;
  IP::IlBodyContext *tree = nullptr;
  unsigned reported = 0;
  for (;;) {
    listener = Listener();
    parser.addErrorListener(&listener);
    tree = parser.ilBody();
    parser.removeErrorListeners();
    if (lexer.hadError())
      return false;
    if (!listener.seen)
      break;
    diag.syntaxError(lexer.locAt(listener.offset), listener.text);
    if (++reported >= st::kMaxSyntaxErrors ||
        !hideLine(tokens, listener.tokenIndex))
      break;
    tokens.seek(0);
    parser.reset();
  }
  if (reported)
    return false;
  // A pragma among the instructions that changes what the POU does (C code
  // for matiec, conditional compilation) is the POU's refusal, reported if
  // it is translated, as in ST.
  for (antlr4::Token *t : tokens.getTokens()) {
    if (!pou || !pou->refusal.empty())
      break;
    if (t->getChannel() != st::kPragmaChannel)
      continue;
    if (auto why = st::refusedBodyPragma(t->getText())) {
      pou->refusal = *why;
      pou->refusalLoc = lexer.locAt(t->getStartIndex());
    }
  }
  try {
    IlLowering lowering(body, diag, unit, pou);
    lowering.lower(tree);
    if (result)
      *result = lowering.result();
  } catch (Refusal &) {
    return false;
  }
  return true;
}
