//===- Promela.cpp - flat modules as Promela models for spin --------------===//
#include "backends/checkers/Promela.h"
#include "backends/checkers/PtSubset.h"
#include "backends/checkers/StateUnits.h"
#include "engine/Semantics.h"
#include "ir/net/Printer.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/Support/Casting.h"

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::checkers;
using llvm::cast;

namespace {
const char *typeFor(int64_t lo, int64_t hi) {
  if (lo >= 0 && hi <= 1)
    return "bit";
  if (lo >= 0 && hi <= 255)
    return "byte";
  if (lo >= -32768 && hi <= 32767)
    return "short";
  return "int";
}

std::string num(int64_t v) { return std::to_string(v); }

//===----------------------------------------------------------------------===//
// Place/transition nets: one d_step per transition
//===----------------------------------------------------------------------===//

/// Plain nets keep the direct encoding: spin's transitions are then
/// netlift's edges too, and no intermediate state is stored.
void writePlainNet(const Module &m, const sem::StateLayout &L,
                   llvm::raw_ostream &os) {
  std::vector<std::string> names;
  for (uint32_t p = 0; p < m.places.size(); ++p)
    names.push_back(checkerIdentifier("P", p, m.places[p].name));
  auto hiOf = [&](uint32_t p) { return L.slotMax(L.markingSlot(p)); };

  std::vector<std::string> enabling;
  bool anyUrgent = false;
  for (const Transition &t : m.transitions) {
    std::string cond;
    auto conj = [&](const std::string &c) {
      cond += (cond.empty() ? "" : " && ") + c;
    };
    for (const PlaceEffect &e : placeEffects(t)) {
      const std::string &n = names[e.place];
      if (e.pre > 0)
        conj(n + " >= " + num(e.pre));
      uint32_t cap = m.places[e.place].capacity;
      if (e.post > e.pre && cap != kInf && !L.isStructurallyBounded(e.place))
        conj(n + " + " + num(e.post - e.pre) + " <= " + num(cap));
    }
    enabling.push_back(cond.empty() ? "true" : "(" + cond + ")");
    anyUrgent |= t.urgent;
  }

  os << "/* Module '" << m.name
     << "' as Promela (netlift emit --to promela), encoding: transitions.\n"
        "   One d_step per transition, interleaving: spin's reachable "
        "states are\n"
        "   netlift's, its transitions (stored + matched) netlift's edges + "
        "1.\n"
        "   Check: spin -a FILE && cc -O2 -DBFS -DNOREDUCE -DSAFETY -o pan "
        "pan.c\n"
        "   && ./pan   (deadlocks are valid end states: label `end`). */\n";
  for (uint32_t p = 0; p < m.places.size(); ++p)
    os << typeFor(0, hiOf(p)) << " " << names[p] << " = " << m.places[p].tokens
       << ";\n";
  os << "\nactive proctype net() {\nend:\n  do\n";
  for (uint32_t ti = 0; ti < m.transitions.size(); ++ti) {
    const Transition &t = m.transitions[ti];
    std::string guard = enabling[ti];
    if (anyUrgent && !t.urgent)
      for (uint32_t u = 0; u < m.transitions.size(); ++u)
        if (m.transitions[u].urgent)
          guard += " && !" + enabling[u];
    os << "  :: d_step { " << guard << " ->\n";
    bool any = false;
    for (const PlaceEffect &e : placeEffects(t)) {
      int64_t gain = e.post - e.pre;
      if (gain == 0)
        continue;
      const std::string &n = names[e.place];
      // An unbounded place past its encoding: a runtime error in netlift.
      if (gain > 0 && m.places[e.place].capacity == kInf &&
          !L.isStructurallyBounded(e.place))
        os << "       assert(" << n << " + " << gain << " <= " << hiOf(e.place)
           << ");\n";
      os << "       " << n << " = " << n << (gain > 0 ? " + " : " - ")
         << (gain > 0 ? gain : -gain) << ";\n";
      any = true;
    }
    if (!any)
      os << "       skip;\n";
    os << "     } /* " << t.name << " */\n";
  }
  if (m.transitions.empty())
    os << "  :: false /* no transition: the initial state is a deadlock */\n";
  os << "  od\n}\n";
}

//===----------------------------------------------------------------------===//
// The general encoding: one step per atomic sequence
//===----------------------------------------------------------------------===//

class StepWriter : public StateUnits {
public:
  StepWriter(const Module &m, const sem::StateLayout &L, DiagEngine &diag,
             llvm::raw_ostream &os)
      : StateUnits(m, L, diag, "the Promela export"), os(os) {}

  bool write();
  /// The properties as `ltl` claims (buildUnits() first when write() was
  /// not called).
  bool writeLtl(llvm::ArrayRef<const CtlFormula *> properties);

private:
  llvm::raw_ostream &os;

  std::vector<uint32_t> forced, spontaneous;
  /// Units each action writes, in unit order.
  std::vector<std::vector<uint32_t>> writesOf;
  std::vector<uint32_t> writerCount;
  /// While translating transition `actionOf`'s action, units it writes are
  /// read from its shadow copies.
  int64_t actionOf = -1;
  int loopDepth = 0, maxLoopDepth = 0;
  std::string unitRef(const Access &a, bool shadow);
  std::string expr(const Expr *e);
  void collectWrites(Block b, std::set<uint32_t> &out);
  void stmts(Block b, const std::string &indent);
  void firstTrueArm(llvm::ArrayRef<std::pair<std::string, Block>> arms,
                    Block elseBody, const std::string &indent);
  std::string enabling(uint32_t t);
  std::string eventEnabling(uint32_t t);
  std::string jointEnabling();
  void writeClosure(const std::string &indent);
  /// `after` follows the closing brace (a separator, or nothing).
  void writeFiring(const std::string &indent, const char *after);
  void writeTick(const std::string &indent);
  void writeReset(const std::string &indent);
  std::string shadow(uint32_t t, uint32_t u) const {
    return "A" + std::to_string(t) + "_" + units[u].name;
  }
  std::string written(uint32_t t, uint32_t u) const {
    return "W" + std::to_string(t) + "_" + units[u].name;
  }
};

std::string StepWriter::unitRef(const Access &a, bool useShadow) {
  const Unit &u = units[a.unit];
  std::string name = useShadow ? shadow(uint32_t(actionOf), a.unit) : u.name;
  if (!a.index)
    return name;
  return name + "[(" + expr(a.index) + ") - " + num(u.indexLo) + "]";
}

std::string StepWriter::expr(const Expr *e) {
  switch (e->getKind()) {
  case ExprKind::IntLit:
    return num(cast<IntLit>(e)->value);
  case ExprKind::BoolLit:
    return cast<BoolLit>(e)->value ? "1" : "0";
  case ExprKind::RealLit:
  case ExprKind::StringLit:
  case ExprKind::Aggregate:
    refuse(e->loc, "the value '" + exprToString(e) + "'");
    return "0";
  case ExprKind::Ref: {
    auto *r = cast<Ref>(e);
    switch (r->sym.kind) {
    case SymKind::Place:
      if (r->type && !r->type->isBool()) // a token count (properties)
        return placeNames[r->sym.index];
      return "(" + placeNames[r->sym.index] + " > 0)";
    case SymKind::EnumLit:
      return num(r->sym.index);
    case SymKind::LoopVar:
      return "LV" + num(r->sym.index);
    case SymKind::Port: {
      const Port &p = m.ports[r->sym.index];
      if (p.definition && r->fields.empty())
        return "(" + expr(p.definition) + ")";
      break;
    }
    default:
      break;
    }
    [[fallthrough]];
  }
  case ExprKind::Index:
  case ExprKind::Field: {
    std::optional<Access> a = access(e);
    if (!a) {
      refuse(e->loc, "the value '" + exprToString(e) + "'");
      return "0";
    }
    bool own = actionOf >= 0 && std::count(writesOf[actionOf].begin(),
                                           writesOf[actionOf].end(), a->unit);
    return unitRef(*a, own);
  }
  case ExprKind::Unary: {
    auto *u = cast<UnaryExpr>(e);
    const char *op = u->op == UnaryOp::Not   ? "!"
                     : u->op == UnaryOp::Neg ? "-"
                                             : "~";
    return std::string("(") + op + expr(u->operand) + ")";
  }
  case ExprKind::Binary: {
    auto *b = cast<BinaryExpr>(e);
    if ((b->op == BinaryOp::Eq || b->op == BinaryOp::Ne) && b->lhs->type &&
        !b->lhs->type->isScalar()) {
      refuse(e->loc, "comparing aggregates ('" + exprToString(e) + "')");
      return "0";
    }
    std::string x = expr(b->lhs), y = expr(b->rhs);
    const char *op = nullptr;
    switch (b->op) {
    case BinaryOp::Or:
      op = "||";
      break;
    case BinaryOp::And:
      op = "&&";
      break;
    case BinaryOp::Xor:
      return "((" + x + " != 0) != (" + y + " != 0))";
    case BinaryOp::Eq:
      op = "==";
      break;
    case BinaryOp::Ne:
      op = "!=";
      break;
    case BinaryOp::Lt:
      op = "<";
      break;
    case BinaryOp::Le:
      op = "<=";
      break;
    case BinaryOp::Gt:
      op = ">";
      break;
    case BinaryOp::Ge:
      op = ">=";
      break;
    case BinaryOp::BitOr:
      op = "|";
      break;
    case BinaryOp::BitXor:
      op = "^";
      break;
    case BinaryOp::BitAnd:
      op = "&";
      break;
    case BinaryOp::Shl:
      op = "<<";
      break;
    case BinaryOp::Shr:
      op = ">>";
      break;
    case BinaryOp::Add:
      op = "+";
      break;
    case BinaryOp::Sub:
      op = "-";
      break;
    case BinaryOp::Mul:
      op = "*";
      break;
    case BinaryOp::Div:
      op = "/";
      break;
    case BinaryOp::Mod:
      op = "%";
      break;
    }
    return "(" + x + " " + op + " " + y + ")";
  }
  case ExprKind::Cond: {
    auto *c = cast<CondExpr>(e);
    return "(" + expr(c->cond) + " -> " + expr(c->thenExpr) + " : " +
           expr(c->elseExpr) + ")";
  }
  case ExprKind::Call: {
    auto *c = cast<CallExpr>(e);
    std::string a = expr(c->args[0]);
    if (c->fn == Builtin::Abs)
      return "(" + a + " < 0 -> -" + a + " : " + a + ")";
    std::string b = expr(c->args[1]);
    const char *cmp = c->fn == Builtin::Min ? " < " : " > ";
    return "(" + a + cmp + b + " -> " + a + " : " + b + ")";
  }
  }
  return "0";
}

void StepWriter::collectWrites(Block b, std::set<uint32_t> &out) {
  for (const Stmt *s : b) {
    switch (s->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(s);
      if (!a->target->type->isScalar()) {
        refuse(a->loc,
               "assigning the aggregate '" + exprToString(a->target) + "'");
        return;
      }
      if (std::optional<Access> acc = access(a->target))
        out.insert(acc->unit);
      else
        refuse(a->loc, "assigning '" + exprToString(a->target) + "'");
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      for (const IfArm &arm : i->arms)
        collectWrites(arm.body, out);
      collectWrites(i->elseBody, out);
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      for (const CaseArm &arm : c->arms)
        collectWrites(arm.body, out);
      collectWrites(c->elseBody, out);
      break;
    }
    case StmtKind::For:
      maxLoopDepth = std::max(maxLoopDepth, ++loopDepth);
      collectWrites(cast<ForStmt>(s)->body, out);
      --loopDepth;
      break;
    case StmtKind::While: // refused by encodesSemantics
      refuse(s->loc, "a loop without constant bounds");
      return;
    }
  }
}

/// `if`/`case` of an action: Promela picks among true guards, netlift the
/// first arm that holds, so each guard excludes those before it.
void StepWriter::firstTrueArm(
    llvm::ArrayRef<std::pair<std::string, Block>> arms, Block elseBody,
    const std::string &in) {
  std::string earlier;
  os << in << "if\n";
  for (const auto &[cond, body] : arms) {
    os << in << ":: " << (earlier.empty() ? "" : "!(" + earlier + ") && ")
       << "(" << cond << ") ->\n";
    stmts(body, in + "   ");
    os << in << "   skip\n";
    earlier += (earlier.empty() ? "" : " || ") + ("(" + cond + ")");
  }
  os << in << ":: else ->\n";
  stmts(elseBody, in + "   ");
  os << in << "   skip\n" << in << "fi;\n";
}

/// An action's statements on the shadow copies of what it writes: stores
/// are range-checked (or wrapped) as netlift's are, and flagged written.
void StepWriter::stmts(Block b, const std::string &in) {
  for (const Stmt *s : b) {
    switch (s->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(s);
      std::optional<Access> acc = access(a->target);
      if (!acc)
        return;
      const Unit &u = units[acc->unit];
      std::string elem;
      if (acc->index) {
        os << in << "IX = (" << expr(acc->index) << ") - " << u.indexLo
           << ";\n";
        elem = "[IX]";
      }
      os << in << "TMP = " << expr(a->value) << ";\n";
      uint64_t span = uint64_t(u.hi - u.lo) + 1;
      if (u.wrap && span < (uint64_t(1) << 31))
        os << in << "TMP = " << u.lo << " + ((TMP - " << u.lo << ") % " << span
           << " + " << span << ") % " << span << ";\n";
      else if (!u.wrap)
        os << in << "assert(TMP >= " << u.lo << " && TMP <= " << u.hi << ");\n";
      os << in << shadow(uint32_t(actionOf), acc->unit) << elem << " = TMP;\n";
      os << in << written(uint32_t(actionOf), acc->unit) << elem << " = 1;\n";
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(s);
      std::vector<std::pair<std::string, Block>> arms;
      for (const IfArm &arm : i->arms)
        arms.push_back({expr(arm.cond), arm.body});
      firstTrueArm(arms, i->elseBody, in);
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(s);
      std::string sel = expr(c->selector);
      std::vector<std::pair<std::string, Block>> arms;
      for (const CaseArm &arm : c->arms) {
        std::string match;
        for (const CaseLabel &l : arm.labels)
          match += (match.empty() ? "" : " || ") +
                   (l.hi ? "(" + sel + " >= " + expr(l.lo) + " && " + sel +
                               " <= " + expr(l.hi) + ")"
                         : "(" + sel + " == " + expr(l.lo) + ")");
        arms.push_back({match, arm.body});
      }
      firstTrueArm(arms, c->elseBody, in);
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(s);
      std::string v = "LV" + num(loopDepth);
      ++loopDepth;
      os << in << v << " = " << expr(f->lo) << ";\n"
         << in << "do\n"
         << in << ":: " << v << " <= " << expr(f->hi) << " ->\n";
      stmts(f->body, in + "   ");
      os << in << "   " << v << "++\n"
         << in << ":: else -> break\n"
         << in << "od;\n";
      --loopDepth;
      break;
    }
    case StmtKind::While: // refused by encodesSemantics
      break;
    }
  }
}

std::string StepWriter::enabling(uint32_t ti) {
  const Transition &t = m.transitions[ti];
  std::vector<std::string> c = tokenAndTimeConditions(ti);
  for (const Expr *x : t.conds())
    c.push_back(expr(x));
  if (const Expr *g = t.guard())
    c.push_back(expr(g));
  std::string out;
  for (const std::string &x : c)
    out += (out.empty() ? "" : " && ") + x;
  return out.empty() ? "1" : "(" + out + ")";
}

std::string StepWriter::eventEnabling(uint32_t ti) {
  const Transition &t = m.transitions[ti];
  std::string c;
  const char *join = t.mode == EventMode::And ? " && " : " || ";
  for (const EventSource &s : t.events()) {
    std::string one;
    if (s.fromPort) {
      one = eventNames[inputEventIndex(s.index)];
    } else {
      one = "ST[" + num(s.index) + "]";
    }
    c += (c.empty() ? "" : join) + one;
  }
  return "(" + c + ")";
}

/// Are the transitions marked in SEL enabled together (summed token demand
/// and production)? Only places a forced transition touches can make a
/// candidate conflict, so only they are checked.
std::string StepWriter::jointEnabling() {
  std::string c;
  for (const auto &[p, effects] : forcedPlaces()) {
    std::string demand, delta;
    for (auto &[ti, e] : effects) {
      if (e.pre > 0)
        demand += (demand.empty() ? "" : " + ") +
                  ("SEL[" + num(ti) + "]*" + num(e.pre));
      int64_t d = int64_t(e.post) - int64_t(e.pre);
      if (d != 0)
        delta += " + SEL[" + num(ti) + "]*(" + num(d) + ")";
    }
    if (!demand.empty())
      c += (c.empty() ? "" : " && ") + placeNames[p] + " >= " + demand;
    if (m.places[p].capacity != kInf && !delta.empty())
      c += (c.empty() ? "" : " && ") + placeNames[p] + delta +
           " <= " + num(m.places[p].capacity);
  }
  return c.empty() ? "1" : "(" + c + ")";
}

/// Fires the step in ST (or drops it: empty, or without an urgent
/// transition while one is enabled). Each action runs in a d_step of its
/// own on shadow copies, as actions read the pre-state; the last d_step
/// moves the tokens, restarts the clocks of the places the step touches
/// and lands the writes. spin bounds the jumps in one d_step, so
/// everything but the actions' own control flow is written without
/// branches (conditional expressions).
void StepWriter::writeFiring(const std::string &in, const char *after) {
  std::string any, urgent;
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    any += (any.empty() ? "" : " || ") + ("ST[" + num(t) + "]");
    if (m.transitions[t].urgent)
      urgent += (urgent.empty() ? "" : " || ") + ("ST[" + num(t) + "]");
  }
  os << in << "d_step { DO = (" << (any.empty() ? "0" : any) << ") && (!URGENT"
     << (urgent.empty() ? "" : " || " + urgent) << ") };\n";
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    const Transition &tr = m.transitions[t];
    if (!tr.hasAction() || tr.action().empty())
      continue;
    os << in << "if\n"
       << in << ":: DO && ST[" << t << "] -> d_step { /* " << tr.name
       << " */\n";
    std::string body = in + "     ";
    actionOf = t;
    for (uint32_t u : writesOf[t])
      for (uint32_t k = 0; k < units[u].count; ++k) {
        std::string el = units[u].isArray ? "[" + num(k) + "]" : "";
        os << body << shadow(t, u) << el << " = " << units[u].name << el
           << ";\n";
      }
    stmts(tr.action(), body);
    actionOf = -1;
    os << body << "skip\n"
       << in << "   }\n"
       << in << ":: else -> skip\n"
       << in << "fi;\n";
  }
  os << in << "d_step {\n";
  std::string body = in + "  ";
  // Markings and the clocks of every place the step touches.
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    std::string delta, touched;
    for (uint32_t t = 0; t < m.transitions.size(); ++t)
      for (const PlaceEffect &e : placeEffects(m.transitions[t])) {
        if (e.place != p)
          continue;
        int64_t d = int64_t(e.post) - int64_t(e.pre);
        if (d != 0)
          delta += " + ST[" + num(t) + "]*(" + num(d) + ")";
        touched += (touched.empty() ? "" : " || ") + ("ST[" + num(t) + "]");
      }
    if (touched.empty())
      continue;
    const std::string &n = placeNames[p];
    if (!delta.empty()) {
      if (m.places[p].capacity == kInf)
        os << body << "assert(!DO || " << n << delta
           << " <= " << L.slotMax(L.markingSlot(p)) << ");\n";
      os << body << n << " = (DO -> " << n << delta << " : " << n << ");\n";
    }
    if (L.clockSlot(p) >= 0)
      os << body << clockNames[p] << " = (DO && (" << touched
         << ") -> 0 : " << clockNames[p] << ");\n";
  }
  // The actions' writes land together; two in one slot are an error. A
  // write flag is set only by an action that ran, so only when DO.
  for (uint32_t u = 0; u < units.size(); ++u) {
    if (!writerCount[u])
      continue;
    for (uint32_t k = 0; k < units[u].count; ++k) {
      std::string el = units[u].isArray ? "[" + num(k) + "]" : "";
      std::string v = units[u].name + el;
      bool conflicts = writerCount[u] > 1;
      for (uint32_t t = 0; t < m.transitions.size(); ++t) {
        if (!std::count(writesOf[t].begin(), writesOf[t].end(), u))
          continue;
        std::string w = written(t, u) + el, a = shadow(t, u) + el;
        if (conflicts)
          os << body << "assert(!(" << w << " && CW)); CW = CW || " << w
             << ";\n";
        os << body << v << " = (" << w << " -> " << a << " : " << v << "); "
           << w << " = 0; " << a << " = 0;\n";
      }
      if (conflicts)
        os << body << "CW = 0;\n";
    }
  }
  writeReset(body);
  os << in << "}" << after << "\n";
}

void StepWriter::writeTick(const std::string &in) {
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (L.clockSlot(p) >= 0)
      os << in << clockNames[p] << " = (" << placeNames[p] << " > 0 && "
         << clockNames[p] << " < " << L.clockCap(p) << " -> " << clockNames[p]
         << " + 1 : " << clockNames[p] << ");\n";
  for (uint32_t v = 0; v < m.vars.size(); ++v)
    if (m.vars[v].type->isClock()) {
      const Unit &u = units[unitOfSlot[L.varSlot(v)]];
      os << in << u.name << " = (" << u.name << " < " << u.hi << " -> "
         << u.name << " + 1 : " << u.name << ");\n";
    }
}

/// Back to a state netlift has: scratch zero, inputs at their low values.
void StepWriter::writeReset(const std::string &in) {
  os << in << "DO = 0;\n";
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    os << in << "ST[" << t << "] = 0;\n";
  for (const Unit &u : units)
    if (u.isInput)
      for (uint32_t k = 0; k < u.count; ++k)
        os << in << u.name << (u.isArray ? "[" + num(k) + "]" : "") << " = "
           << u.lo << ";\n";
  for (const std::string &e : eventNames)
    os << in << e << " = 0;\n";
  if (!forced.empty())
    for (uint32_t t = 0; t < m.transitions.size(); ++t)
      os << in << "SEL[" << t << "] = 0;\n";
}

/// The rounds of the closure under forced transitions, then the firing
/// (forced transitions exist).
void StepWriter::writeClosure(const std::string &in2) {
  // Rounds of the closure under forced transitions, as the engine does
  // them: the candidates of a round are the enabled, event-enabled forced
  // transitions that fit with the step one by one; all of them join
  // when they fit together, else each maximal subset is a choice. SEL
  // is the set JOINT judges: the step, plus what is being tried.
  os << in2 << "do\n" << in2 << ":: d_step {\n";
  std::string r = in2 + "     ";
  os << r << "NC = 0;\n";
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    os << r << "SEL[" << t << "] = ST[" << t << "];\n";
  for (uint32_t f : forced)
    os << r << "SEL[" << f << "] = 1; CAND[" << f << "] = !ST[" << f
       << "] && EN" << f << " && EV" << f << " && JOINT; SEL[" << f << "] = ST["
       << f << "]; NC = NC || CAND[" << f << "];\n";
  for (uint32_t f : forced)
    os << r << "SEL[" << f << "] = ST[" << f << "] || CAND[" << f << "];\n";
  os << r << "ALL = JOINT;\n";
  for (uint32_t f : forced)
    os << r << "SEL[" << f << "] = ST[" << f << "];\n";
  os << in2 << "   };\n";
  // The round that finds no candidate fires the step and leaves (a
  // `break` may not lead into a d_step).
  os << in2 << "   if\n" << in2 << "   :: !NC -> ALL = 0;\n";
  writeFiring(in2 + "      ", ";");
  os << in2 << "      break\n";
  os << in2 << "   :: NC && ALL -> d_step {\n";
  for (uint32_t f : forced)
    os << in2 << "        ST[" << f << "] = ST[" << f << "] || CAND[" << f
       << "]; CAND[" << f << "] = 0;\n";
  os << in2 << "        NC = 0; ALL = 0\n" << in2 << "      }\n";
  os << in2 << "   :: NC && !ALL ->\n";
  std::string c = in2 + "      ";
  for (uint32_t f : forced) {
    os << c << "d_step { SEL[" << f << "] = 1; FIT = CAND[" << f
       << "] && JOINT; SEL[" << f << "] = 0 };\n";
    os << c << "if :: FIT -> CHO[" << f << "] = 1; SEL[" << f
       << "] = 1; FIT = 0 :: true -> FIT = 0 fi;\n";
  }
  // A choice that is not maximal is completed in candidate order, so
  // every path ends in a maximal subset and every maximal subset is one.
  os << c << "d_step {\n";
  for (uint32_t f : forced)
    os << c << "  SEL[" << f << "] = 1; CHO[" << f << "] = CHO[" << f
       << "] || (CAND[" << f << "] && JOINT); SEL[" << f << "] = ST[" << f
       << "] || CHO[" << f << "];\n";
  for (uint32_t f : forced)
    os << c << "  ST[" << f << "] = ST[" << f << "] || CHO[" << f << "]; CHO["
       << f << "] = 0; CAND[" << f << "] = 0;\n";
  os << c << "  NC = 0; ALL = 0\n" << c << "}\n";
  os << in2 << "   fi\n" << in2 << "od\n";
}

bool StepWriter::write() {
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    (m.transitions[t].isForced() ? forced : spontaneous).push_back(t);
  writesOf.resize(m.transitions.size());
  writerCount.assign(units.size(), 0);
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    std::set<uint32_t> w;
    collectWrites(m.transitions[t].action(), w);
    writesOf[t].assign(w.begin(), w.end());
    for (uint32_t u : w)
      ++writerCount[u];
  }
  if (failed)
    return false;

  std::vector<uint64_t> init;
  if (!initialState(init))
    return false;
  sem::Semantics semantics(m, L, sem::Options());
  bool hasInputs = !eventNames.empty();
  for (const Unit &u : units)
    hasInputs |= u.isInput;
  bool timed = semantics.isTimed();

  // The macros first: they also find what the export refuses.
  std::string defs;
  llvm::raw_string_ostream d(defs);
  std::string urgentAny;
  for (uint32_t t = 0; t < m.transitions.size(); ++t) {
    d << "#define EN" << t << " " << enabling(t) << " /* "
      << m.transitions[t].name << " */\n";
    if (m.transitions[t].urgent)
      urgentAny += (urgentAny.empty() ? "" : " || ") + ("EN" + num(t));
  }
  for (uint32_t f : forced)
    d << "#define EV" << f << " " << eventEnabling(f) << "\n";
  d << "#define URGENT (" << (urgentAny.empty() ? "0" : urgentAny) << ")\n";
  // Deadlines: no tick takes an enabled transition past one.
  std::string deadlineAny;
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    for (const PreArc &a : m.transitions[t].pre())
      if (a.time.deadline)
        deadlineAny += (deadlineAny.empty() ? "" : " || ") +
                       ("(EN" + num(t) + " && " + clockNames[a.place] +
                        " >= " + num(a.time.hi) + ")");
  if (!deadlineAny.empty())
    d << "#define DEADLINE (" << deadlineAny << ")\n";
  if (!forced.empty())
    d << "#define JOINT " << jointEnabling() << "\n";
  if (timed) {
    std::string ticks;
    for (uint32_t p = 0; p < m.places.size(); ++p)
      if (L.clockSlot(p) >= 0)
        ticks += (ticks.empty() ? "" : " || ") +
                 ("(" + placeNames[p] + " > 0 && " + clockNames[p] + " < " +
                  num(L.clockCap(p)) + ")");
    for (uint32_t v = 0; v < m.vars.size(); ++v)
      if (m.vars[v].type->isClock()) {
        const Unit &u = units[unitOfSlot[L.varSlot(v)]];
        ticks += (ticks.empty() ? "" : " || ") +
                 ("(" + u.name + " < " + num(u.hi) + ")");
      }
    d << "#define TICKS (" << (ticks.empty() ? "0" : ticks) << ")\n";
  }
  if (failed)
    return false;

  // Arrays whose elements start alike are initialised where declared;
  // others in a first d_step, which adds one state before netlift's
  // initial one (the offset the header states).
  auto uniformInit = [&](const Unit &u) {
    if (u.isInput)
      return true;
    for (uint32_t k = 1; k < u.count; ++k)
      if (L.get(init.data(), u.firstSlot + k) !=
          L.get(init.data(), u.firstSlot))
        return false;
    return true;
  };
  bool initStep = false;
  for (const Unit &u : units)
    initStep |= u.isArray && !uniformInit(u);

  // A step is dropped (back to the same state, a stutter netlift does not
  // have) when it is empty or lacks an urgent transition while one is
  // enabled. With no urgent forced transition, a non-urgent seed is not
  // offered while one is enabled; only free inputs then leave drops.
  bool urgentForced = false;
  for (uint32_t f : forced)
    urgentForced |= m.transitions[f].urgent;
  bool drops = hasInputs || urgentForced;
  os << "/* netlift-promela: encoding=steps state-offset=" << (initStep ? 1 : 0)
     << " deadlocks=" << (hasInputs ? "self-loops" : "end-states")
     << " stutter=" << (drops ? "some" : "none") << " */\n";
  os << "/* Module '" << m.name
     << "' as Promela (netlift emit --to promela).\n"
        "   Each netlift step (or tick) is one atomic sequence: the free "
        "inputs,\n"
        "   the transition that starts the step, the choices among "
        "conflicting\n"
        "   forced transitions, the actions, then one d_step that lands "
        "the step.\n"
        "   pan's stored states (depth-first; the states inside atomic "
        "sequences\n"
        "   are not stored) are netlift's states, plus state-offset; see\n"
        "   docs/check.md. Check: spin -a FILE && cc -O2 -fwrapv -DNOREDUCE "
        "-o pan\n"
        "   pan.c && ./pan */\n\n";
  // State.
  for (uint32_t p = 0; p < m.places.size(); ++p) {
    uint32_t s = L.markingSlot(p);
    os << typeFor(0, L.slotMax(s)) << " " << placeNames[p] << " = "
       << L.get(init.data(), s) << ";\n";
    if (L.clockSlot(p) >= 0)
      os << typeFor(0, L.clockCap(p)) << " " << clockNames[p] << " = "
         << L.get(init.data(), uint32_t(L.clockSlot(p))) << ";\n";
  }
  for (const Unit &u : units) {
    int64_t first = u.isInput ? u.lo : L.get(init.data(), u.firstSlot);
    os << typeFor(u.lo, u.hi) << " " << u.name;
    if (u.isArray)
      os << "[" << u.count << "]";
    if (!u.isArray || uniformInit(u))
      os << " = " << first;
    os << ";\n";
  }
  for (const std::string &e : eventNames)
    os << "bit " << e << " = 0;\n";
  // Scratch: the step being built and the actions' shadow copies are part
  // of the states inside an atomic sequence and always 0 outside them;
  // `hidden` temporaries live inside one d_step.
  size_t nt = std::max<size_t>(m.transitions.size(), 1);
  os << "bit ST[" << nt << "];\nbit DO;\n";
  if (timed)
    os << "bit TK;\n";
  if (!forced.empty())
    os << "bit SEL[" << nt << "];\nbit CAND[" << nt << "];\nbit CHO[" << nt
       << "];\nbit NC;\nbit ALL;\nbit FIT;\n";
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    for (uint32_t u : writesOf[t]) {
      const Unit &un = units[u];
      std::string dim = un.isArray ? "[" + num(un.count) + "]" : "";
      os << typeFor(std::min<int64_t>(un.lo, 0), std::max<int64_t>(un.hi, 0))
         << " " << shadow(t, u) << dim << ";\nbit " << written(t, u) << dim
         << ";\n";
    }
  os << "hidden int TMP;\nhidden int IX;\nhidden byte CW;\n";
  for (int i = 0; i < maxLoopDepth; ++i)
    os << "hidden int LV" << i << ";\n";
  os << "\n" << d.str() << "\n";

  os << "active proctype net() {\n";
  if (initStep) {
    os << "  d_step {\n";
    for (const Unit &u : units)
      if (u.isArray && !uniformInit(u))
        for (uint32_t k = 0; k < u.count; ++k)
          os << "    " << u.name << "[" << k
             << "] = " << L.get(init.data(), u.firstSlot + k) << ";\n";
    os << "    skip\n  };\n";
  }
  os << "end:\n  do\n  :: atomic {\n";
  std::string in = "       ";
  // The free inputs of this step.
  for (const std::string &e : eventNames)
    os << in << "if :: " << e << " = 1 :: " << e << " = 0 fi;\n";
  for (const Unit &u : units) {
    if (!u.isInput)
      continue;
    for (uint32_t k = 0; k < u.count; ++k) {
      std::string n = u.name + (u.isArray ? "[" + num(k) + "]" : "");
      if (u.hi - u.lo == 1)
        os << in << "if :: " << n << " = " << u.lo << " :: " << n << " = "
           << u.hi << " fi;\n";
      else
        os << in << "select(" << n << " : " << u.lo << " .. " << u.hi << ");\n";
    }
  }
  // What starts it.
  os << in << "if\n";
  for (uint32_t t : spontaneous)
    os << in << ":: EN" << t
       << (urgentAny.empty() || m.transitions[t].urgent || urgentForced
               ? ""
               : " && !URGENT")
       << " -> ST[" << t << "] = 1 /* " << m.transitions[t].name << " */\n";
  if (!eventNames.empty()) {
    std::string anyEvent;
    for (const std::string &e : eventNames)
      anyEvent += (anyEvent.empty() ? "" : " || ") + e;
    os << in << ":: (" << anyEvent << ") -> skip /* input events alone */\n";
  }
  if (timed)
    os << in << ":: !URGENT" << (deadlineAny.empty() ? "" : " && !DEADLINE")
       << " && TICKS -> TK = 1 /* tick */\n";
  if (hasInputs)
    os << in << ":: else -> skip /* nothing under these inputs */\n";
  if (spontaneous.empty() && eventNames.empty() && !timed && !hasInputs)
    os << in << ":: false\n";
  os << in << "fi;\n";
  std::string in2 = in;
  if (timed) {
    os << in << "if\n" << in << ":: TK ->\n" << in << "   d_step {\n";
    writeTick(in + "     ");
    os << in << "     TK = 0;\n";
    writeReset(in + "     ");
    os << in << "   }\n" << in << ":: else ->\n";
    in2 = in + "   ";
  }
  if (!forced.empty())
    writeClosure(in2);
  else
    writeFiring(in2, "");
  if (timed)
    os << in << "fi\n";
  os << "     }\n  od\n}\n";
  return !failed;
}

/// A state proposition for spin: no temporal operator, no `deadlock`.
static bool isProposition(const CtlFormula &f) {
  return isStateProposition(f, /*deadlockIsState=*/false);
}

/// The LTL of a CTL formula in the fragment where dropping the path
/// quantifiers keeps the meaning; empty outside it.
class LtlWriter {
public:
  explicit LtlWriter(std::function<std::string(const net::Expr *)> atom)
      : atom(std::move(atom)) {}

  std::string top(const CtlFormula &f) {
    switch (f.kind) {
    case CtlFormula::And: {
      std::string a = top(*f.lhs), b = top(*f.rhs);
      return a.empty() || b.empty() ? "" : "(" + a + " && " + b + ")";
    }
    case CtlFormula::AG: {
      std::string b = always(*f.lhs);
      return b.empty() ? "" : "[] " + b;
    }
    case CtlFormula::AF:
      return isProposition(*f.lhs) ? "<> " + prop(*f.lhs) : "";
    case CtlFormula::AU:
      return isProposition(*f.lhs) && isProposition(*f.rhs)
                 ? "(" + prop(*f.lhs) + " U " + prop(*f.rhs) + ")"
                 : "";
    default:
      return isProposition(f) ? prop(f) : "";
    }
  }

private:
  std::function<std::string(const net::Expr *)> atom;

  /// What may stand under AG: propositions, AF p, p -> AF q, and
  /// conjunctions (G distributes over them).
  std::string always(const CtlFormula &f) {
    if (isProposition(f))
      return prop(f);
    if (f.kind == CtlFormula::AF && isProposition(*f.lhs))
      return "(<> " + prop(*f.lhs) + ")";
    if (f.kind == CtlFormula::Implies && isProposition(*f.lhs) &&
        f.rhs->kind == CtlFormula::AF && isProposition(*f.rhs->lhs))
      return "(" + prop(*f.lhs) + " -> <> " + prop(*f.rhs->lhs) + ")";
    if (f.kind == CtlFormula::And) {
      std::string a = always(*f.lhs), b = always(*f.rhs);
      return a.empty() || b.empty() ? "" : "(" + a + " && " + b + ")";
    }
    return "";
  }

  std::string prop(const CtlFormula &f) {
    switch (f.kind) {
    case CtlFormula::True:
      return "true";
    case CtlFormula::False:
      return "false";
    case CtlFormula::Atom:
      return "(" + atom(f.atom) + ")";
    case CtlFormula::Not:
      return "!" + prop(*f.lhs);
    case CtlFormula::And:
      return "(" + prop(*f.lhs) + " && " + prop(*f.rhs) + ")";
    case CtlFormula::Or:
      return "(" + prop(*f.lhs) + " || " + prop(*f.rhs) + ")";
    case CtlFormula::Implies:
      return "(" + prop(*f.lhs) + " -> " + prop(*f.rhs) + ")";
    default:
      return "";
    }
  }
};

bool StepWriter::writeLtl(llvm::ArrayRef<const CtlFormula *> properties) {
  LtlWriter ltl([&](const net::Expr *e) { return expr(e); });
  for (size_t i = 0; i < properties.size(); ++i) {
    std::string text = ltl.top(*properties[i]);
    if (failed)
      return false;
    if (text.empty()) {
      diag.error(properties[i]->loc,
                 "property " + std::to_string(i + 1) + " '" +
                     ctlToString(*properties[i]) +
                     "' is not in the fragment of CTL that netlift writes "
                     "as LTL for spin (AG p, AF p, A[p U q], AG AF p, "
                     "AG (p -> AF q) and conjunctions, over state "
                     "propositions); check it with `netlift check`");
      return false;
    }
    os << "\n/* " << ctlToString(*properties[i]) << " */\nltl p" << i + 1
       << " { " << text << " }\n";
  }
  return true;
}

} // namespace

bool checkers::writePromela(const sem::Semantics &semantics, DiagEngine &diag,
                            llvm::raw_ostream &os,
                            llvm::ArrayRef<const CtlFormula *> properties) {
  const Module &m = semantics.module();
  const sem::StateLayout &L = semantics.layout();
  if (!encodesSemantics(m, semantics.options(), "the Promela export", diag))
    return false;
  StepWriter steps(m, L, diag, os);
  if (!steps.buildUnits())
    return false;
  if (!firstBeyondPt(m))
    writePlainNet(m, L, os);
  else if (!steps.write())
    return false;
  return steps.writeLtl(properties);
}
