//===- Smv.cpp - flat modules as SMV models for NuSMV/nuXmv ---------------===//
#include "backends/checkers/Smv.h"
#include "backends/checkers/StateUnits.h"
#include "engine/Semantics.h"
#include "ir/net/Printer.h"

#include "llvm/Support/Casting.h"

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;
using llvm::cast;

namespace {

std::string num(int64_t v) { return std::to_string(v); }

/// An SMV expression and whether SMV types it boolean (stored Booleans are
/// integers 0..1, so every use says which it needs).
struct Val {
  std::string text;
  bool isBool = false;
};

std::string boolOf(const Val &v) {
  return v.isBool ? v.text : "(" + v.text + " != 0)";
}
std::string intOf(const Val &v) {
  return v.isBool ? "(" + v.text + " ? 1 : 0)" : v.text;
}

/// What an action has done so far, by symbolic execution: the value each
/// element it wrote holds now and the condition under which it wrote it,
/// keyed by the element's slot.
struct Effect {
  std::map<uint32_t, std::string> value, wrote;
};

/// The first arm whose condition holds, as an SMV case expression.
std::string
firstOf(const std::vector<std::pair<std::string, std::string>> &arms,
        const std::string &otherwise) {
  std::string out = "case ";
  for (const auto &[cond, v] : arms)
    out += cond + " : " + v + "; ";
  return out + "TRUE : " + otherwise + "; esac";
}

std::string joinWith(const std::vector<std::string> &xs, const char *op,
                     const char *empty) {
  if (xs.empty())
    return empty;
  std::string out = "(" + xs[0];
  for (size_t i = 1; i < xs.size(); ++i)
    out += std::string(" ") + op + " " + xs[i];
  return out + ")";
}

class SmvWriter : public StateUnits {
public:
  SmvWriter(const Module &m, const sem::StateLayout &L, DiagEngine &diag,
            llvm::raw_ostream &os)
      : StateUnits(m, L, diag, "the SMV export"), os(os), d(defs) {}

  bool write(llvm::ArrayRef<const CtlFormula *> properties);

private:
  llvm::raw_ostream &os;
  std::string defs;
  llvm::raw_string_ostream d;
  unsigned fresh = 0;
  std::vector<uint32_t> forced, spontaneous;

  // The context of expression translation.
  Effect *env = nullptr; // in an action: reads see its own writes
  std::string pc = "TRUE";
  std::vector<std::string> *errors = nullptr; // an action's runtime errors
  const std::map<uint32_t, int64_t> *inputValue = nullptr; // fixed inputs
  std::set<uint32_t> inputsRead;
  std::map<uint32_t, int64_t> loopValue; // by nesting depth
  uint32_t loopDepth = 0;
  uint64_t unrolled = 0;

  std::string define(const std::string &e) {
    std::string n = "X" + num(fresh++);
    d << "  " << n << " := " << e << ";\n";
    return n;
  }
  uint32_t unitContaining(uint32_t slot) const {
    uint32_t u = 0;
    while (slot < units[u].firstSlot ||
           slot >= units[u].firstSlot + units[u].count)
      ++u;
    return u;
  }
  std::string elementName(uint32_t u, uint32_t k) const {
    return units[u].isArray ? units[u].name + "_" + num(k) : units[u].name;
  }
  std::string readElement(uint32_t u, uint32_t k);
  Val read(const Expr *e);
  Val expr(const Expr *e);
  Val binary(const BinaryExpr *b);
  void exec(Block b, Effect &eff);
  void assign(const AssignStmt *a, Effect &eff);
  void merge(const std::vector<std::string> &conds,
             const std::vector<Effect> &arms, Effect &eff);
  /// Collects in `errs` the runtime errors evaluating it can raise.
  std::string enabling(uint32_t t, std::vector<std::string> &errs);
  std::string joint(const std::function<std::string(uint32_t)> &member);
  std::string ctl(const CtlFormula &f);
};

std::string SmvWriter::readElement(uint32_t u, uint32_t k) {
  uint32_t slot = units[u].firstSlot + k;
  if (env) {
    auto it = env->value.find(slot);
    if (it != env->value.end())
      return it->second;
  }
  if (units[u].isInput) {
    inputsRead.insert(slot);
    if (inputValue)
      if (auto it = inputValue->find(slot); it != inputValue->end())
        return num(it->second);
  }
  return elementName(u, k);
}

Val SmvWriter::read(const Expr *e) {
  std::optional<Access> a = access(e);
  if (!a) {
    refuse(e->loc, "the value '" + exprToString(e) + "'");
    return {"0"};
  }
  const Unit &u = units[a->unit];
  if (!a->index)
    return {readElement(a->unit, 0)};
  int64_t k;
  if (evalConstInt(a->index, k) && k >= u.indexLo &&
      k < u.indexLo + int64_t(u.count))
    return {readElement(a->unit, uint32_t(k - u.indexLo))};
  if (!errors) {
    refuse(e->loc, "indexing with a variable in a property ('" +
                       exprToString(e) + "')");
    return {"0"};
  }
  std::string idx = define(intOf(expr(a->index)));
  errors->push_back("(" + pc + " & !(" + idx + " >= " + num(u.indexLo) + " & " +
                    idx + " <= " + num(u.indexLo + int64_t(u.count) - 1) +
                    "))");
  std::vector<std::pair<std::string, std::string>> arms;
  for (uint32_t i = 1; i < u.count; ++i)
    arms.push_back({idx + " = " + num(u.indexLo + i), readElement(a->unit, i)});
  return {"(" + firstOf(arms, readElement(a->unit, 0)) + ")"};
}

Val SmvWriter::expr(const Expr *e) {
  switch (e->getKind()) {
  case ExprKind::IntLit:
    return {num(cast<IntLit>(e)->value)};
  case ExprKind::BoolLit:
    return {cast<BoolLit>(e)->value ? "TRUE" : "FALSE", true};
  case ExprKind::RealLit:
  case ExprKind::StringLit:
  case ExprKind::Aggregate:
    refuse(e->loc, "the value '" + exprToString(e) + "'");
    return {"0"};
  case ExprKind::Ref: {
    auto *r = cast<Ref>(e);
    switch (r->sym.kind) {
    case SymKind::Place:
      if (r->type && !r->type->isBool()) // a token count (properties)
        return {placeNames[r->sym.index]};
      return {"(" + placeNames[r->sym.index] + " > 0)", true};
    case SymKind::EnumLit:
      return {num(r->sym.index)};
    case SymKind::LoopVar:
      return {num(loopValue[r->sym.index])};
    case SymKind::Port: {
      const Port &p = m.ports[r->sym.index];
      if (p.definition && r->fields.empty())
        return expr(p.definition);
      break;
    }
    default:
      break;
    }
    return read(e);
  }
  case ExprKind::Index:
  case ExprKind::Field:
    return read(e);
  case ExprKind::Unary: {
    auto *u = cast<UnaryExpr>(e);
    Val x = expr(u->operand);
    if (u->op == UnaryOp::Neg)
      return {"(-" + intOf(x) + ")"};
    if (u->op == UnaryOp::BitNot && !(u->type && u->type->isBool())) {
      refuse(e->loc, "the bit operation '" + exprToString(e) + "'");
      return {"0"};
    }
    return {"(!" + boolOf(x) + ")", true};
  }
  case ExprKind::Binary:
    return binary(cast<BinaryExpr>(e));
  case ExprKind::Cond: {
    auto *c = cast<CondExpr>(e);
    std::string cond = boolOf(expr(c->cond)), outer = pc;
    if (errors) {
      cond = define(cond);
      pc = "(" + outer + " & " + cond + ")";
    }
    Val a = expr(c->thenExpr);
    if (errors)
      pc = "(" + outer + " & !" + cond + ")";
    Val b = expr(c->elseExpr);
    pc = outer;
    if (a.isBool && b.isBool)
      return {"(" + cond + " ? " + a.text + " : " + b.text + ")", true};
    return {"(" + cond + " ? " + intOf(a) + " : " + intOf(b) + ")"};
  }
  case ExprKind::Call: {
    auto *c = cast<CallExpr>(e);
    std::string a = define(intOf(expr(c->args[0])));
    if (c->fn == Builtin::Abs)
      return {"(" + a + " < 0 ? -" + a + " : " + a + ")"};
    std::string b = define(intOf(expr(c->args[1])));
    const char *cmp = c->fn == Builtin::Min ? " < " : " > ";
    return {"(" + a + cmp + b + " ? " + a + " : " + b + ")"};
  }
  }
  return {"0"};
}

Val SmvWriter::binary(const BinaryExpr *b) {
  bool boolOperands = b->lhs->type && b->lhs->type->isBool();
  if (b->op == BinaryOp::And || b->op == BinaryOp::Or) {
    // The right operand is evaluated (and can fail) only where the left
    // one does not decide.
    std::string x = boolOf(expr(b->lhs)), outer = pc;
    if (errors) {
      x = define(x);
      pc = "(" + outer + (b->op == BinaryOp::And ? " & " : " & !") + x + ")";
    }
    std::string y = boolOf(expr(b->rhs));
    pc = outer;
    return {"(" + x + (b->op == BinaryOp::And ? " & " : " | ") + y + ")", true};
  }
  Val x = expr(b->lhs), y = expr(b->rhs);
  auto logical = [&](const char *op) {
    return Val{"(" + boolOf(x) + " " + op + " " + boolOf(y) + ")", true};
  };
  auto arith = [&](const char *op) {
    return Val{"(" + intOf(x) + " " + op + " " + intOf(y) + ")"};
  };
  auto compare = [&](const char *op) {
    if (x.isBool && y.isBool)
      return Val{"(" + x.text + " " + op + " " + y.text + ")", true};
    return Val{"(" + intOf(x) + " " + op + " " + intOf(y) + ")", true};
  };
  switch (b->op) {
  case BinaryOp::Or:
  case BinaryOp::And: // above
  case BinaryOp::Xor:
    return logical("xor");
  case BinaryOp::Eq:
  case BinaryOp::Ne:
    if (b->lhs->type && !b->lhs->type->isScalar()) {
      refuse(b->loc, "comparing aggregates ('" + exprToString(b) + "')");
      return {"FALSE", true};
    }
    return compare(b->op == BinaryOp::Eq ? "=" : "!=");
  case BinaryOp::Lt:
    return compare("<");
  case BinaryOp::Le:
    return compare("<=");
  case BinaryOp::Gt:
    return compare(">");
  case BinaryOp::Ge:
    return compare(">=");
  case BinaryOp::BitOr:
  case BinaryOp::BitXor:
  case BinaryOp::BitAnd:
    if (!boolOperands) {
      // `x & (2^n - 1)`, how PLC integers wrap: the remainder modulo 2^n.
      int64_t mask;
      const Expr *other = evalConstInt(b->rhs, mask) ? b->lhs : b->rhs;
      if (b->op == BinaryOp::BitAnd &&
          (other == b->lhs || evalConstInt(b->lhs, mask)) && mask > 0 &&
          mask < (int64_t(1) << 31) && ((mask + 1) & mask) == 0) {
        std::string v = define(intOf(other == b->lhs ? x : y)),
                    n = num(mask + 1);
        return {"(((" + v + " mod " + n + ") + " + n + ") mod " + n + ")"};
      }
      refuse(b->loc, "the bit operation '" + exprToString(b) + "'");
      return {"0"};
    }
    return logical(b->op == BinaryOp::BitOr    ? "|"
                   : b->op == BinaryOp::BitAnd ? "&"
                                               : "xor");
  case BinaryOp::Shl:
  case BinaryOp::Shr: {
    int64_t k;
    if (!evalConstInt(b->rhs, k) || k < 0 || k > 30) {
      refuse(b->loc, "the shift '" + exprToString(b) +
                         "' (only by a "
                         "constant 0..30)");
      return {"0"};
    }
    std::string p = num(int64_t(1) << k), v = define(intOf(x));
    if (b->op == BinaryOp::Shl)
      return {"(" + v + " * " + p + ")"};
    // An arithmetic shift rounds down; SMV's division truncates.
    return {"(" + v + " >= 0 ? " + v + " / " + p + " : -((-" + v + " - 1) / " +
            p + ") - 1)"};
  }
  case BinaryOp::Add:
    return arith("+");
  case BinaryOp::Sub:
    return arith("-");
  case BinaryOp::Mul:
    return arith("*");
  case BinaryOp::Div:
  case BinaryOp::Mod: {
    const char *op = b->op == BinaryOp::Div ? "/" : "mod";
    int64_t k;
    if (evalConstInt(b->rhs, k) && k != 0)
      return arith(op);
    if (!errors) {
      refuse(b->loc, "dividing by a variable in a property ('" +
                         exprToString(b) + "')");
      return {"0"};
    }
    // SMV rejects a division by zero anywhere in the model, reachable or
    // not; netlift's runtime error is the error flag instead.
    std::string v = define(intOf(y));
    errors->push_back("(" + pc + " & " + v + " = 0)");
    return {"(" + intOf(x) + " " + op + " (" + v + " = 0 ? 1 : " + v + "))"};
  }
  }
  return {"0"};
}

void SmvWriter::assign(const AssignStmt *a, Effect &eff) {
  if (!a->target->type->isScalar()) {
    refuse(a->loc, "assigning the aggregate '" + exprToString(a->target) + "'");
    return;
  }
  std::optional<Access> acc = access(a->target);
  if (!acc) {
    refuse(a->loc, "assigning '" + exprToString(a->target) + "'");
    return;
  }
  const Unit &u = units[acc->unit];
  env = &eff;
  Val v = expr(a->value);
  std::string raw = define(intOf(v)), stored = raw;
  uint64_t span = uint64_t(u.hi - u.lo) + 1;
  if (u.wrap)
    stored = define(num(u.lo) + " + (((" + raw + " - " + num(u.lo) + ") mod " +
                    num(int64_t(span)) + ") + " + num(int64_t(span)) +
                    ") mod " + num(int64_t(span)));
  else if (!v.isBool)
    errors->push_back("(" + pc + " & !(" + raw + " >= " + num(u.lo) + " & " +
                      raw + " <= " + num(u.hi) + "))");
  if (!acc->index) {
    eff.value[u.firstSlot] = stored;
    eff.wrote[u.firstSlot] = "TRUE";
    return;
  }
  int64_t k;
  if (evalConstInt(acc->index, k) && k >= u.indexLo &&
      k < u.indexLo + int64_t(u.count)) {
    uint32_t slot = u.firstSlot + uint32_t(k - u.indexLo);
    eff.value[slot] = stored;
    eff.wrote[slot] = "TRUE";
    return;
  }
  std::string idx = define(intOf(expr(acc->index)));
  errors->push_back("(" + pc + " & !(" + idx + " >= " + num(u.indexLo) + " & " +
                    idx + " <= " + num(u.indexLo + int64_t(u.count) - 1) +
                    "))");
  for (uint32_t i = 0; i < u.count; ++i) {
    uint32_t slot = u.firstSlot + i;
    std::string hit = "(" + idx + " = " + num(u.indexLo + i) + ")";
    std::string old = readElement(acc->unit, i);
    auto w = eff.wrote.find(slot);
    std::string oldWrote = w == eff.wrote.end() ? "FALSE" : w->second;
    eff.value[slot] = define("(" + hit + " ? " + stored + " : " + old + ")");
    eff.wrote[slot] = define("(" + hit + " | " + oldWrote + ")");
  }
}

/// Joins the arms of an `if`/`case` (the last one is the else part):
/// each element one of them wrote takes the value of the first arm whose
/// condition holds.
void SmvWriter::merge(const std::vector<std::string> &conds,
                      const std::vector<Effect> &arms, Effect &eff) {
  std::set<uint32_t> slots;
  for (const Effect &a : arms)
    for (const auto &[slot, v] : a.wrote)
      slots.insert(slot);
  for (uint32_t slot : slots) {
    auto valueIn = [&](const Effect &a) {
      auto it = a.value.find(slot);
      if (it != a.value.end())
        return it->second;
      uint32_t u = unitContaining(slot);
      return elementName(u, slot - units[u].firstSlot);
    };
    auto wroteIn = [&](const Effect &a) {
      auto it = a.wrote.find(slot);
      return it == a.wrote.end() ? std::string("FALSE") : it->second;
    };
    std::vector<std::pair<std::string, std::string>> values, wrote;
    for (size_t i = 0; i < conds.size(); ++i) {
      values.push_back({conds[i], valueIn(arms[i])});
      wrote.push_back({conds[i], wroteIn(arms[i])});
    }
    eff.value[slot] = define(firstOf(values, valueIn(arms.back())));
    eff.wrote[slot] = define(firstOf(wrote, wroteIn(arms.back())));
  }
}

void SmvWriter::exec(Block b, Effect &eff) {
  for (const Stmt *s : b) {
    if (failed)
      return;
    switch (s->getKind()) {
    case StmtKind::Assign:
      assign(cast<AssignStmt>(s), eff);
      break;
    case StmtKind::If:
    case StmtKind::Case: {
      env = &eff;
      std::vector<std::string> conds;
      std::vector<Block> bodies;
      if (auto *i = llvm::dyn_cast<IfStmt>(s)) {
        for (const IfArm &arm : i->arms) {
          conds.push_back(define(boolOf(expr(arm.cond))));
          bodies.push_back(arm.body);
        }
        bodies.push_back(i->elseBody);
      } else {
        auto *c = cast<CaseStmt>(s);
        std::string sel = define(intOf(expr(c->selector)));
        for (const CaseArm &arm : c->arms) {
          std::vector<std::string> match;
          for (const CaseLabel &l : arm.labels)
            match.push_back(l.hi ? "(" + sel + " >= " + intOf(expr(l.lo)) +
                                       " & " + sel +
                                       " <= " + intOf(expr(l.hi)) + ")"
                                 : "(" + sel + " = " + intOf(expr(l.lo)) + ")");
          conds.push_back(define(joinWith(match, "|", "FALSE")));
          bodies.push_back(arm.body);
        }
        bodies.push_back(c->elseBody);
      }
      // Each arm runs from the same effect, on the path where it is the
      // first arm whose condition holds.
      std::string outer = pc, earlier = "FALSE";
      std::vector<Effect> arms;
      for (size_t i = 0; i < bodies.size(); ++i) {
        std::string own = i < conds.size() ? conds[i] : "TRUE";
        pc = define("(" + outer + " & !" + earlier + " & " + own + ")");
        if (i < conds.size())
          earlier = define("(" + earlier + " | " + conds[i] + ")");
        arms.push_back(eff);
        exec(bodies[i], arms.back());
      }
      pc = outer;
      merge(conds, arms, eff);
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      int64_t lo, hi;
      if (!evalConstInt(f->lo, lo) || !evalConstInt(f->hi, hi)) {
        refuse(f->loc, "a loop whose bounds are not constant");
        return;
      }
      uint32_t depth = loopDepth++;
      for (int64_t i = lo; i <= hi && !failed; ++i) {
        if (++unrolled > 100000) {
          refuse(f->loc, "a loop unrolled over 100000 times");
          break;
        }
        loopValue[depth] = i;
        exec(f->body, eff);
      }
      --loopDepth;
      break;
    }
    case StmtKind::While: // refused by encodesSemantics
      refuse(s->loc, "a loop without constant bounds");
      return;
    }
  }
}

std::string SmvWriter::enabling(uint32_t ti, std::vector<std::string> &errs) {
  const Transition &t = m.transitions[ti];
  std::vector<std::string> c = tokenAndTimeConditions(ti);
  // Conditions, then the guard, each evaluated (and able to fail) only
  // where everything before it holds, as the engine does.
  std::vector<std::string> *outerErrors = errors;
  std::string outerPc = pc;
  errors = &errs;
  for (const Expr *x : t.conds()) {
    pc = joinWith(c, "&", "TRUE");
    c.push_back(boolOf(expr(x)));
  }
  if (const Expr *g = t.guard()) {
    pc = joinWith(c, "&", "TRUE");
    c.push_back(boolOf(expr(g)));
  }
  errors = outerErrors;
  pc = outerPc;
  return joinWith(c, "&", "TRUE");
}

/// Are the transitions `member` names enabled together (summed token
/// demand and production)? Only places a forced transition touches can
/// make a candidate conflict, so only they are checked.
std::string
SmvWriter::joint(const std::function<std::string(uint32_t)> &member) {
  std::vector<std::string> c;
  for (const auto &[p, effects] : forcedPlaces()) {
    std::vector<std::string> demand, delta;
    int64_t fixedDemand = 0, fixedDelta = 0; // of members that are TRUE
    for (auto &[ti, e] : effects) {
      std::string in = member(ti);
      int64_t dlt = int64_t(e.post) - int64_t(e.pre);
      if (in == "FALSE")
        continue;
      if (in == "TRUE") {
        fixedDemand += e.pre;
        fixedDelta += dlt;
        continue;
      }
      if (e.pre > 0)
        demand.push_back("(" + in + " ? " + num(e.pre) + " : 0)");
      if (dlt != 0)
        delta.push_back("(" + in + " ? " + num(dlt) + " : 0)");
    }
    if (fixedDemand)
      demand.push_back(num(fixedDemand));
    if (fixedDelta)
      delta.push_back(num(fixedDelta));
    if (!demand.empty())
      c.push_back(placeNames[p] + " >= " + joinWith(demand, "+", "0"));
    if (m.places[p].capacity != kInf && !delta.empty())
      c.push_back(placeNames[p] + " + " + joinWith(delta, "+", "0") +
                  " <= " + num(m.places[p].capacity));
  }
  return joinWith(c, "&", "TRUE");
}

std::string SmvWriter::ctl(const CtlFormula &f) {
  auto un = [&](const char *op) { return std::string(op) + " " + ctl(*f.lhs); };
  auto bin = [&](const char *op) {
    return "(" + ctl(*f.lhs) + " " + op + " " + ctl(*f.rhs) + ")";
  };
  switch (f.kind) {
  case CtlFormula::True:
    return "TRUE";
  case CtlFormula::False:
    return "FALSE";
  case CtlFormula::Deadlock:
    return "deadlock";
  case CtlFormula::Atom: // parseCtl refuses free inputs in properties
    return "(" + boolOf(expr(f.atom)) + ")";
  case CtlFormula::Not:
    return "(" + un("!") + ")";
  case CtlFormula::And:
    return bin("&");
  case CtlFormula::Or:
    return bin("|");
  case CtlFormula::Implies:
    return bin("->");
  case CtlFormula::EX:
    return "(" + un("EX") + ")";
  case CtlFormula::AX:
    return "(" + un("AX") + ")";
  case CtlFormula::EF:
    return "(" + un("EF") + ")";
  case CtlFormula::AF:
    return "(" + un("AF") + ")";
  case CtlFormula::EG:
    return "(" + un("EG") + ")";
  case CtlFormula::AG:
    return "(" + un("AG") + ")";
  case CtlFormula::EU:
    return "E [ " + ctl(*f.lhs) + " U " + ctl(*f.rhs) + " ]";
  case CtlFormula::AU:
    return "A [ " + ctl(*f.lhs) + " U " + ctl(*f.rhs) + " ]";
  }
  return "TRUE";
}

bool SmvWriter::write(llvm::ArrayRef<const CtlFormula *> properties) {
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    const Transition &tr = m.transitions[t];
    (tr.isForced() ? forced : spontaneous).push_back(t);
    // A step must then contain one, which depends on the closure's
    // choices: `deadlock` would no longer be a state formula.
    if (tr.isForced() && tr.urgent)
      return refuse(tr.loc,
                    "the urgent forced transition '" + tr.name.str() + "'");
  }
  std::vector<uint64_t> init;
  if (!initialState(init))
    return false;

  // Enabling, urgency and time.
  // Every state evaluates every transition's enabling (under each input
  // valuation): an error there is a runtime error of the state.
  std::vector<std::set<uint32_t>> enablingInputs(m.transitions.size());
  std::vector<std::string> urgent, stateErrors;
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    inputsRead.clear();
    std::string en = enabling(t, stateErrors); // may define helpers first
    d << "  EN" << t << " := " << en << "; -- " << m.transitions[t].name
      << "\n";
    enablingInputs[t] = inputsRead;
    if (m.transitions[t].urgent)
      urgent.push_back("EN" + num(t));
  }
  d << "  URGENT := " << joinWith(urgent, "|", "FALSE") << ";\n";
  // Deadlines: no tick takes an enabled transition past one.
  std::vector<std::string> deadline;
  std::vector<std::pair<uint32_t, std::string>> deadlineArcs; // t, clock >= hi
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    for (const PreArc &a : m.transitions[t].pre())
      if (a.time.deadline) {
        std::string late = clockNames[a.place] + " >= " + num(a.time.hi);
        deadlineArcs.push_back({t, late});
        deadline.push_back("(EN" + num(t) + " & " + late + ")");
      }
  if (!deadline.empty())
    d << "  DEADLINE := " << joinWith(deadline, "|", "FALSE") << ";\n";
  std::vector<std::string> ticks;
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (L.clockSlot(p) >= 0)
      ticks.push_back("(" + placeNames[p] + " > 0 & " + clockNames[p] + " < " +
                      num(L.clockCap(p)) + ")");
  for (uint32_t v = 0; v < m.vars.size(); ++v)
    if (m.vars[v].type->isClock()) {
      const Unit &u = units[unitOfSlot[L.varSlot(v)]];
      ticks.push_back("(" + u.name + " < " + num(u.hi) + ")");
    }
  d << "  TICKS := " << joinWith(ticks, "|", "FALSE") << ";\n";

  // The step: its seed, then the rounds of the closure under forced
  // transitions as the engine makes them. Round r's candidates are the
  // enabled, event-enabled forced transitions that fit with the step one
  // by one; all join when they fit together, otherwise the choice bits C
  // pick a subset that must fit and be maximal. A round with a candidate
  // adds one, so there are at most as many rounds as forced transitions.
  auto member = [&](uint32_t round, uint32_t t) {
    if (!m.transitions[t].isForced())
      return "(trig = S" + num(t) + ")";
    return round == 0 ? std::string("FALSE") : "F" + num(round) + "_" + num(t);
  };
  uint32_t rounds = uint32_t(forced.size());
  std::vector<std::string> roundOk;
  for (uint32_t r = 1; r <= rounds; ++r) {
    for (uint32_t f : forced) {
      const Transition &t = m.transitions[f];
      std::vector<std::string> sources;
      for (const EventSource &s : t.events())
        sources.push_back(s.fromPort ? eventNames[inputEventIndex(s.index)]
                                     : member(r - 1, s.index));
      std::string fits = joint([&](uint32_t x) {
        return x == f ? std::string("TRUE") : member(r - 1, x);
      });
      d << "  CD" << r << "_" << f << " := !" << member(r - 1, f) << " & EN"
        << f << " & "
        << joinWith(sources, t.mode == EventMode::And ? "&" : "|", "FALSE")
        << " & " << fits << ";\n";
    }
    d << "  ALL" << r << " := " << joint([&](uint32_t x) {
      return m.transitions[x].isForced() ? "(" + member(r - 1, x) + " | CD" +
                                               num(r) + "_" + num(x) + ")"
                                         : member(r - 1, x);
    }) << ";\n";
    for (uint32_t f : forced)
      d << "  F" << r << "_" << f << " := " << member(r - 1, f) << " | (CD" << r
        << "_" << f << " & (ALL" << r << " | C" << r << "_" << f << "));\n";
    std::vector<std::string> maximal{
        joint([&](uint32_t x) { return member(r, x); })};
    for (uint32_t f : forced)
      maximal.push_back("((CD" + num(r) + "_" + num(f) + " & !" + member(r, f) +
                        ") -> !" + joint([&](uint32_t x) {
                          return x == f ? std::string("TRUE") : member(r, x);
                        }) +
                        ")");
    d << "  OK" << r << " := ALL" << r << " | "
      << joinWith(maximal, "&", "TRUE") << ";\n";
    roundOk.push_back("OK" + num(r));
  }
  auto inStep = [&](uint32_t t) { return member(rounds, t); };

  // The actions, by symbolic execution.
  std::vector<Effect> effects(m.transitions.size());
  std::vector<std::string> stepErrors;
  std::map<uint32_t, std::vector<uint32_t>> writers; // slot -> transitions
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    std::vector<std::string> errs;
    errors = &errs;
    pc = "TRUE";
    exec(m.transitions[t].action(), effects[t]);
    errors = nullptr;
    env = nullptr;
    if (failed)
      return false;
    for (const auto &[slot, v] : effects[t].wrote)
      writers[slot].push_back(t);
    if (!errs.empty())
      stepErrors.push_back("(" + inStep(t) + " & " +
                           joinWith(errs, "|", "FALSE") + ")");
  }
  for (const auto &[slot, ts] : writers)
    for (size_t i = 0; i < ts.size(); ++i)
      for (size_t j = i + 1; j < ts.size(); ++j)
        stepErrors.push_back(
            "(" + inStep(ts[i]) + " & " + effects[ts[i]].wrote[slot] + " & " +
            inStep(ts[j]) + " & " + effects[ts[j]].wrote[slot] + ")");
  // Token sums past an unbounded place's encoding.
  std::vector<std::string> nextMarking(m.places.size());
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    std::vector<std::string> delta;
    for (uint32_t t = 0; t < m.transitions.size(); ++t)
      for (const PlaceEffect &e : placeEffects(m.transitions[t]))
        if (e.place == p && e.post != e.pre)
          delta.push_back("(" + inStep(t) + " ? " +
                          num(int64_t(e.post) - int64_t(e.pre)) + " : 0)");
    if (delta.empty())
      continue;
    nextMarking[p] = define(placeNames[p] + " + " + joinWith(delta, "+", "0"));
    if (m.places[p].capacity == kInf)
      stepErrors.push_back("(" + nextMarking[p] + " > " +
                           num(L.slotMax(L.markingSlot(p))) + ")");
  }

  std::vector<std::string> events, seeds, inputOnly, anyForced;
  for (const std::string &e : eventNames)
    events.push_back(e);
  for (uint32_t t : spontaneous)
    seeds.push_back("(trig = S" + num(t) + " & EN" + num(t) +
                    (m.transitions[t].urgent ? "" : " & !URGENT") + ")");
  if (!eventNames.empty())
    seeds.push_back("(trig = events & " + joinWith(events, "|", "FALSE") +
                    " & !URGENT)");
  for (uint32_t f : forced)
    anyForced.push_back(inStep(f));
  // Input events alone must start something.
  if (!eventNames.empty())
    roundOk.push_back("(trig != events | " + joinWith(anyForced, "|", "FALSE") +
                      ")");
  d << "  STEP := " << joinWith(seeds, "|", "FALSE") << " & "
    << joinWith(roundOk, "&", "TRUE") << ";\n";
  d << "  STATEERR := " << joinWith(stateErrors, "|", "FALSE") << ";\n";
  d << "  STEPERR := " << joinWith(stepErrors, "|", "FALSE") << ";\n";
  d << "  FIRE := trig != none & trig != tick & STEP & !STEPERR & "
       "!STATEERR;\n";
  d << "  TICK := trig = tick & !URGENT & "
    << (deadline.empty() ? "" : "!DEADLINE & ") << "TICKS & !STATEERR;\n";

  // A deadlock: no step under any valuation of the free inputs, and no
  // tick. A spontaneous seed always makes a step (urgent forced
  // transitions are refused), and input events alone make one when a
  // forced transition they alone trigger is enabled. Each way to go on is
  // a disjunct that exists for some valuation of the inputs its enabling
  // and urgency read: those valuations are enumerated.
  std::set<uint32_t> urgentReads;
  std::vector<uint32_t> urgentOnes;
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    if (m.transitions[t].urgent) {
      urgentOnes.push_back(t);
      urgentReads.insert(enablingInputs[t].begin(), enablingInputs[t].end());
    }
  std::map<uint32_t, int64_t> fixed;
  auto en = [&](uint32_t t) {
    if (!inputValue) // no input read: the definitions serve as they are
      return "EN" + num(t);
    std::vector<std::string> counted; // in STATEERR already
    return enabling(t, counted);
  };
  auto notUrgent = [&]() {
    std::vector<std::string> u;
    for (uint32_t t : urgentOnes)
      u.push_back(en(t));
    return "!" + joinWith(u, "|", "FALSE");
  };
  auto noDeadline = [&]() {
    std::vector<std::string> u;
    for (auto &[t, late] : deadlineArcs)
      u.push_back("(" + en(t) + " & " + late + ")");
    return "!" + joinWith(u, "|", "FALSE");
  };
  std::vector<std::string> live;
  // `body` for every valuation of `reads` and the urgent ones' inputs.
  auto forSomeInputs = [&](int64_t t,
                           const std::function<std::string()> &body) {
    std::set<uint32_t> reads = urgentReads;
    if (t >= 0)
      reads.insert(enablingInputs[t].begin(), enablingInputs[t].end());
    else // a tick: the deadlines' enabling too
      for (auto &[d, late] : deadlineArcs)
        reads.insert(enablingInputs[d].begin(), enablingInputs[d].end());
    std::vector<uint32_t> slots(reads.begin(), reads.end());
    uint64_t valuations = 1;
    for (uint32_t slot : slots) {
      valuations *= uint64_t(L.slots()[slot].hi - L.slots()[slot].lo + 1);
      if (valuations > 4096)
        return refuse(t >= 0 ? m.transitions[t].loc : m.loc,
                      "enabling that reads free inputs with over 4096 "
                      "valuations (the deadlock condition enumerates them)");
    }
    inputValue = slots.empty() ? nullptr : &fixed;
    for (uint64_t v = 0; v < valuations; ++v) {
      uint64_t rest = v;
      for (uint32_t slot : slots) {
        const sem::Slot &s = L.slots()[slot];
        uint64_t span = uint64_t(s.hi - s.lo + 1);
        fixed[slot] = s.lo + int64_t(rest % span);
        rest /= span;
      }
      live.push_back(body());
    }
    inputValue = nullptr;
    return true;
  };
  for (uint32_t t : spontaneous)
    if (!forSomeInputs(t, [&] {
          return m.transitions[t].urgent
                     ? en(t)
                     : "(" + en(t) + " & " + notUrgent() + ")";
        }))
      return false;
  for (uint32_t f : forced) {
    const Transition &t = m.transitions[f];
    bool fromInputs = t.mode == EventMode::And;
    for (const EventSource &s : t.events())
      fromInputs = t.mode == EventMode::And ? fromInputs && s.fromPort
                                            : fromInputs || s.fromPort;
    if (fromInputs && !forSomeInputs(f, [&] {
          return "(" + en(f) + " & " + notUrgent() + ")";
        }))
      return false;
  }
  if (!forSomeInputs(-1, [&] {
        return "(TICKS & " + notUrgent() +
               (deadlineArcs.empty() ? "" : " & " + noDeadline()) + ")";
      }))
    return false;
  d << "  deadlock := !" << joinWith(live, "|", "FALSE") << ";\n";

  // Properties (checked before anything is written).
  // An invariant goes to NuSMV's invariant checker (AG p holds exactly
  // where every reachable state satisfies p, deadlocks included).
  std::vector<std::string> specs;
  for (const CtlFormula *f : properties)
    specs.push_back(f->kind == CtlFormula::AG &&
                            isStateProposition(*f->lhs, true)
                        ? "INVARSPEC " + ctl(*f->lhs)
                        : "CTLSPEC " + ctl(*f));
  if (failed)
    return false;

  os << "-- netlift-smv: encoding=steps deadlocks=self-loops "
        "errors=netlift_error\n"
     << "-- Module '" << m.name
     << "' as SMV (netlift emit --to smv). One SMV transition per netlift\n"
        "-- step or tick (interleaving, weak timing): the input variables "
        "choose\n"
        "-- what starts it (trig), the free inputs and the choices among "
        "conflicting\n"
        "-- forced transitions; TRANS keeps the choices that make a step. "
        "Reachable\n"
        "-- states are netlift's states; see docs/check.md.\n"
        "MODULE main\nVAR\n";
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    os << "  " << placeNames[p] << " : 0.." << L.slotMax(L.markingSlot(p))
       << ";\n";
    if (L.clockSlot(p) >= 0)
      os << "  " << clockNames[p] << " : 0.." << L.clockCap(p) << ";\n";
  }
  for (uint32_t u = 0; u < units.size(); ++u)
    if (!units[u].isInput)
      for (uint32_t k = 0; k < units[u].count; ++k)
        os << "  " << elementName(u, k) << " : " << units[u].lo << ".."
           << units[u].hi << ";\n";
  os << "  netlift_error : boolean;\nIVAR\n  trig : {none, tick";
  for (uint32_t t : spontaneous)
    os << ", S" << t;
  if (!eventNames.empty())
    os << ", events";
  os << "};\n";
  for (uint32_t t : spontaneous)
    os << "  -- S" << t << ": " << m.transitions[t].name << "\n";
  for (uint32_t u = 0; u < units.size(); ++u)
    if (units[u].isInput)
      for (uint32_t k = 0; k < units[u].count; ++k)
        os << "  " << elementName(u, k) << " : " << units[u].lo << ".."
           << units[u].hi << ";\n";
  for (const std::string &e : eventNames)
    os << "  " << e << " : boolean;\n";
  for (uint32_t r = 1; r <= rounds; ++r)
    for (uint32_t f : forced)
      os << "  C" << r << "_" << f << " : boolean;\n";
  os << "DEFINE\n" << d.str();

  os << "ASSIGN\n";
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    const std::string &n = placeNames[p];
    os << "  init(" << n << ") := " << L.get(init.data(), L.markingSlot(p))
       << ";\n";
    // A variable without next() would be free in SMV: one nothing changes
    // keeps its value explicitly.
    if (!nextMarking[p].empty())
      os << "  next(" << n << ") := (FIRE ? " << nextMarking[p] << " : " << n
         << ");\n";
    else
      os << "  next(" << n << ") := " << n << ";\n";
    if (L.clockSlot(p) < 0)
      continue;
    const std::string &k = clockNames[p];
    std::vector<std::string> touched;
    for (uint32_t t = 0; t < m.transitions.size(); ++t)
      for (const PlaceEffect &e : placeEffects(m.transitions[t]))
        if (e.place == p) {
          touched.push_back(inStep(t));
          break;
        }
    os << "  init(" << k
       << ") := " << L.get(init.data(), uint32_t(L.clockSlot(p))) << ";\n"
       << "  next(" << k << ") := case TICK : (" << n << " > 0 & " << k << " < "
       << L.clockCap(p) << " ? " << k << " + 1 : " << k << "); FIRE & "
       << joinWith(touched, "|", "FALSE") << " : 0; TRUE : " << k
       << "; esac;\n";
  }
  for (uint32_t u = 0; u < units.size(); ++u) {
    if (units[u].isInput)
      continue;
    bool clock = false;
    for (uint32_t v = 0; v < m.vars.size(); ++v)
      clock |= m.vars[v].type->isClock() && unitOfSlot[L.varSlot(v)] == int(u);
    for (uint32_t k = 0; k < units[u].count; ++k) {
      std::string n = elementName(u, k);
      uint32_t slot = units[u].firstSlot + k;
      os << "  init(" << n << ") := " << L.get(init.data(), slot) << ";\n";
      std::vector<std::pair<std::string, std::string>> arms;
      if (clock)
        arms.push_back({"TICK", "(" + n + " < " + num(units[u].hi) + " ? " + n +
                                    " + 1 : " + n + ")"});
      if (auto w = writers.find(slot); w != writers.end())
        for (uint32_t t : w->second)
          arms.push_back(
              {"FIRE & " + inStep(t) + " & " + effects[t].wrote[slot],
               effects[t].value[slot]});
      os << "  next(" << n << ") := " << (arms.empty() ? n : firstOf(arms, n))
         << ";\n";
    }
  }
  os << "  init(netlift_error) := FALSE;\n"
        "  next(netlift_error) := netlift_error | STATEERR | (trig != none "
        "& trig != tick & STEP & STEPERR);\n"
        "-- A step, a tick, or staying put in a deadlock or after an error.\n"
        "TRANS\n  case netlift_error | STATEERR : trig = none; trig = none : "
        "deadlock; "
        "trig = tick : TICK; TRUE : STEP; esac\n"
        "INVARSPEC !netlift_error\n";
  for (size_t i = 0; i < properties.size(); ++i)
    os << "-- p" << i + 1 << ": " << ctlToString(*properties[i]) << "\n"
       << specs[i] << "\n";
  return true;
}

} // namespace

bool checkers::writeSmv(const sem::Semantics &semantics, DiagEngine &diag,
                        llvm::raw_ostream &os,
                        llvm::ArrayRef<const CtlFormula *> properties) {
  const Module &m = semantics.module();
  if (!encodesSemantics(m, semantics.options(), "the SMV export", diag))
    return false;
  SmvWriter w(m, semantics.layout(), diag, os);
  return w.buildUnits() && w.write(properties);
}
