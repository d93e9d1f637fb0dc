//===- Printer.cpp - canonical NetIR text ---------------------------------===//
#include "ir/net/Printer.h"
#include "ir/net/StringOps.h"

#include "llvm/ADT/STLExtras.h"

#include <optional>

using namespace netlift::net;
using llvm::raw_ostream;
using llvm::StringRef;

namespace {

/// An attribute value or a file name in quotes, with `"`, `\\`, newline
/// and tab escaped (the parser's parseQuotedText reads it back).
void printQuoted(StringRef text, raw_ostream &os) {
  os << '"';
  for (char c : text) {
    if (c == '"' || c == '\\')
      os << '\\' << c;
    else if (c == '\n')
      os << "\\n";
    else if (c == '\t')
      os << "\\t";
    else
      os << c;
  }
  os << '"';
}

/// Precedence of an expression as a whole (see precedence(BinaryOp)):
/// 0 conditional, 1-11 binary, 4 `not`, 12 prefix minus/complement,
/// 13 postfix and primary.
int exprPrecedence(const Expr *e) {
  switch (e->getKind()) {
  case ExprKind::Cond:
    return 0;
  case ExprKind::Binary:
    return precedence(llvm::cast<BinaryExpr>(e)->op);
  case ExprKind::Unary:
    return llvm::cast<UnaryExpr>(e)->op == UnaryOp::Not ? 4 : 12;
  case ExprKind::IntLit:
    // A negative literal (built, not parsed) prints as a prefix minus.
    return llvm::cast<IntLit>(e)->value < 0 ? 12 : 13;
  default:
    return 13;
  }
}

void print(const Expr *e, raw_ostream &os, int ctx);

void printOperand(const Expr *e, raw_ostream &os, int ctx) {
  if (exprPrecedence(e) < ctx) {
    os << '(';
    print(e, os, 0);
    os << ')';
  } else {
    print(e, os, ctx);
  }
}

void print(const Expr *e, raw_ostream &os, int ctx) {
  switch (e->getKind()) {
  case ExprKind::IntLit:
    os << llvm::cast<IntLit>(e)->value;
    return;
  case ExprKind::BoolLit:
    os << (llvm::cast<BoolLit>(e)->value ? "true" : "false");
    return;
  case ExprKind::RealLit:
    os << formatReal(llvm::cast<RealLit>(e)->value);
    return;
  case ExprKind::StringLit:
    os << formatStringLiteral(llvm::cast<StringLit>(e)->chars);
    return;
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    if (r->sym.kind == SymKind::EnumLit && r->type && !r->type->name.empty())
      os << r->type->name << '#' << r->type->enumerators[r->sym.index];
    else
      os << r->name;
    return;
  }
  case ExprKind::Index: {
    auto *x = llvm::cast<IndexExpr>(e);
    printOperand(x->base, os, 13);
    os << '[';
    print(x->index, os, 0);
    os << ']';
    return;
  }
  case ExprKind::Field: {
    auto *f = llvm::cast<FieldExpr>(e);
    printOperand(f->base, os, 13);
    os << '.' << f->field;
    return;
  }
  case ExprKind::Unary: {
    auto *u = llvm::cast<UnaryExpr>(e);
    os << spelling(u->op);
    // `- -x` must not print as `--x`; parenthesise a nested minus.
    int p = u->op == UnaryOp::Not ? 4 : 13;
    printOperand(u->operand, os, p);
    return;
  }
  case ExprKind::Binary: {
    auto *bin = llvm::cast<BinaryExpr>(e);
    int p = precedence(bin->op);
    bool nonAssoc = p == 5; // comparisons do not chain
    printOperand(bin->lhs, os, nonAssoc ? p + 1 : p);
    os << ' ' << spelling(bin->op) << ' ';
    printOperand(bin->rhs, os, p + 1);
    return;
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    printOperand(c->cond, os, 1);
    os << " ? ";
    print(c->thenExpr, os, 0);
    os << " : ";
    print(c->elseExpr, os, 0);
    return;
  }
  case ExprKind::Call: {
    auto *c = llvm::cast<CallExpr>(e);
    os << calleeSpelling(c) << '(';
    llvm::interleave(
        c->args, os, [&](const Expr *a) { print(a, os, 0); }, ", ");
    os << ')';
    return;
  }
  case ExprKind::Aggregate: {
    auto *a = llvm::cast<AggregateLit>(e);
    os << (a->isRecord() ? '{' : '[');
    for (size_t i = 0; i < a->elems.size(); ++i) {
      if (i)
        os << ", ";
      if (a->isRecord())
        os << a->fieldNames[i] << ": ";
      print(a->elems[i], os, 0);
    }
    os << (a->isRecord() ? '}' : ']');
    return;
  }
  }
}

} // namespace

SourceTable::SourceTable(const llvm::SourceMgr &sm) : sm(sm) {}

bool SourceTable::carriesLocations(StringRef bufferName) {
  // NetIR text is the model itself: its own lines are not carried into the
  // text printed from it. netlift's library and generated text are `<...>`.
  return !bufferName.empty() && !bufferName.startswith("<") &&
         !bufferName.endswith(".net");
}

std::string SourceTable::reference(llvm::SMLoc loc) {
  if (!loc.isValid())
    return "";
  unsigned id = sm.FindBufferContainingLoc(loc);
  if (!id)
    return "";
  auto [it, inserted] = numbers.try_emplace(id, 0);
  if (inserted) {
    StringRef name = sm.getMemoryBuffer(id)->getBufferIdentifier();
    // A frontend's working copy of a file (XML text placed at its offsets)
    // is a buffer of the same name and lines: one number for both.
    if (carriesLocations(name)) {
      size_t index =
          std::find(files.begin(), files.end(), name.str()) - files.begin();
      if (index == files.size())
        files.push_back(name.str());
      it->second = index + 1;
    }
  }
  if (!it->second)
    return "";
  auto [line, col] = sm.getLineAndColumn(loc, id);
  return "@" + std::to_string(it->second) + ":" + std::to_string(line) + ":" +
         std::to_string(col);
}

namespace {

class ModulePrinter {
public:
  ModulePrinter(const Module &m, raw_ostream &os, SourceTable *sources)
      : m(m), os(os), sources(sources) {}
  void run();

private:
  void printBlock(Block b, unsigned indent);
  void printStmt(const Stmt *s, unsigned indent);
  void printStmtBody(const Stmt *s, unsigned indent);
  void printTransition(const Transition &t);
  const Module &m;
  raw_ostream &os;
  SourceTable *sources;
};

void ModulePrinter::printBlock(Block b, unsigned indent) {
  os << "{\n";
  for (const Stmt *s : b)
    printStmt(s, indent + 2);
  os.indent(indent) << "}";
}

void ModulePrinter::printStmt(const Stmt *s, unsigned indent) {
  os.indent(indent);
  printStmtBody(s, indent);
  if (sources) {
    std::string ref = sources->reference(s->loc);
    if (!ref.empty())
      os << ' ' << ref;
  }
  os << '\n';
}

void ModulePrinter::printStmtBody(const Stmt *s, unsigned indent) {
  switch (s->getKind()) {
  case StmtKind::Assign: {
    auto *a = llvm::cast<AssignStmt>(s);
    printExpr(a->target, os);
    os << " := ";
    printExpr(a->value, os);
    os << ";";
    return;
  }
  case StmtKind::If: {
    auto *i = llvm::cast<IfStmt>(s);
    bool first = true;
    for (const IfArm &arm : i->arms) {
      os << (first ? "if " : " elif ");
      first = false;
      printExpr(arm.cond, os);
      os << ' ';
      printBlock(arm.body, indent);
    }
    if (i->hasElse) {
      os << " else ";
      printBlock(i->elseBody, indent);
    }
    return;
  }
  case StmtKind::Case: {
    auto *c = llvm::cast<CaseStmt>(s);
    os << "case ";
    printExpr(c->selector, os);
    os << " {\n";
    for (const CaseArm &arm : c->arms) {
      os.indent(indent + 2);
      llvm::interleave(
          arm.labels, os,
          [&](const CaseLabel &l) {
            printOperand(l.lo, os, 6);
            if (l.hi) {
              os << "..";
              printOperand(l.hi, os, 6);
            }
          },
          ", ");
      os << ' ';
      printBlock(arm.body, indent + 2);
      os << '\n';
    }
    if (c->hasElse) {
      os.indent(indent + 2) << "else ";
      printBlock(c->elseBody, indent + 2);
      os << '\n';
    }
    os.indent(indent) << "}";
    return;
  }
  case StmtKind::For: {
    auto *f = llvm::cast<ForStmt>(s);
    os << "for " << f->var << " in ";
    printOperand(f->lo, os, 6);
    os << "..";
    printOperand(f->hi, os, 6);
    os << ' ';
    printBlock(f->body, indent);
    return;
  }
  case StmtKind::While: {
    auto *w = llvm::cast<WhileStmt>(s);
    if (w->testAfter) {
      os << "repeat ";
      printBlock(w->body, indent);
      os << " until ";
      print(w->cond, os, 0);
      os << ";";
      return;
    }
    os << "while ";
    print(w->cond, os, 0);
    os << ' ';
    printBlock(w->body, indent);
    return;
  }
  }
}

void ModulePrinter::printTransition(const Transition &t) {
  os << "  trans " << t.name << " : ";
  if (t.pre().empty())
    os << "()";
  llvm::interleave(
      t.pre(), os,
      [&](const PreArc &a) {
        if (a.weight != 1)
          os << a.weight << '*';
        os << m.places[a.place].name;
        if (!a.time.isTrivial()) {
          os << '[' << a.time.lo << ',';
          if (a.time.hi == kInf)
            os << "inf";
          else
            os << a.time.hi;
          if (a.time.deadline)
            os << " deadline";
          os << ']';
        }
      },
      ", ");
  os << " -> ";
  if (t.post().empty())
    os << "()";
  llvm::interleave(
      t.post(), os,
      [&](const PostArc &a) {
        if (a.weight != 1)
          os << a.weight << '*';
        os << m.places[a.place].name;
      },
      ", ");
  if (!t.conds().empty()) {
    os << " cond ";
    llvm::interleave(
        t.conds(), os, [&](const Expr *e) { printExpr(e, os); }, ", ");
  }
  if (!t.events().empty()) {
    os << " on ";
    llvm::interleave(
        t.events(), os,
        [&](const EventSource &s) {
          os << (s.fromPort ? m.ports[s.index].name
                            : m.transitions[s.index].name);
        },
        t.mode == EventMode::And ? " & " : " | ");
  }
  if (!t.emits().empty()) {
    os << " emit ";
    llvm::interleave(
        t.emits(), os, [&](uint32_t p) { os << m.ports[p].name; }, ", ");
  }
  if (Expr *g = t.guard()) {
    os << " guard ";
    printExpr(g, os);
  }
  if (t.urgent)
    os << " urgent";
  if (t.hasAction()) {
    os << ' ';
    printBlock(t.action(), 2);
    os << '\n';
  } else {
    os << ";\n";
  }
}

void ModulePrinter::run() {
  os << (m.isSystem ? "system " : "module ") << m.name << " {\n";
  for (const Port &p : m.ports) {
    os << "  " << spelling(p.kind) << (p.isInput() ? " input " : " output ")
       << p.name;
    if (p.kind == PortKind::Data) {
      os << " : ";
      p.type->print(os);
    }
    if (p.definition) {
      os << " = ";
      printExpr(p.definition, os);
    } else if (p.init) {
      os << " init ";
      printExpr(p.init, os);
    }
    os << ";\n";
  }
  for (const Var &v : m.vars) {
    if (v.type->isClock()) {
      os << "  clock " << v.name << " : 0.." << v.type->hi;
    } else if (v.type->isReal()) {
      os << "  real " << v.name << " : [" << formatReal(v.type->realLo) << ", "
         << formatReal(v.type->realHi) << "]";
      auto lo = v.initHi ? evalConstReal(v.init) : std::nullopt;
      auto hi = v.initHi ? evalConstReal(v.initHi) : std::nullopt;
      if (lo && hi) {
        os << " in [" << formatReal(*lo) << ", " << formatReal(*hi) << "];\n";
        continue;
      }
    } else {
      os << "  var " << v.name << " : ";
      v.type->print(os);
    }
    if (v.init) {
      os << " = ";
      printExpr(v.init, os);
    }
    os << ";\n";
  }
  for (const Place &p : m.places) {
    os << "  place " << p.name;
    if (p.tokens)
      os << '(' << p.tokens << ')';
    if (p.capacity == kInf)
      os << " cap inf";
    else if (p.capacity != 1)
      os << " cap " << p.capacity;
    os << ";\n";
  }
  for (const Transition &t : m.transitions)
    printTransition(t);
  for (const Flow &f : m.flows) {
    os << "  flow " << m.places[f.place].name << " {";
    for (const Flow::Equation &eq : f.equations) {
      os << ' ' << eq.var << "' ";
      if (eq.rateHi) {
        os << "in [";
        printExpr(eq.rate, os);
        os << ", ";
        printExpr(eq.rateHi, os);
        os << "];";
        continue;
      }
      os << "= ";
      printExpr(eq.rate, os);
      os << ';';
    }
    os << " }\n";
  }
  for (const Invariant &inv : m.invariants) {
    os << "  invariant " << m.places[inv.place].name << " {";
    for (const Expr *c : inv.conditions) {
      os << ' ';
      printExpr(c, os);
      os << ';';
    }
    os << " }\n";
  }
  for (const Instance &i : m.instances)
    os << "  inst " << i.name << " : " << i.moduleName << ";\n";
  auto printEnd = [&](const Endpoint &e) {
    if (!e.instance.empty())
      os << e.instance << '.';
    os << e.port;
  };
  for (const Connection &c : m.connections) {
    os << "  connect ";
    printEnd(c.from);
    os << " -> ";
    printEnd(c.to);
    os << ";\n";
  }
  for (const Attribute &a : m.attributes) {
    os << "  attr ";
    if (!a.target.empty())
      os << a.target << ' ';
    os << a.key << " = ";
    printQuoted(a.value, os);
    os << ";\n";
  }
  os << "}\n";
}

} // namespace

void netlift::net::printExpr(const Expr *e, raw_ostream &os) {
  print(e, os, 0);
}

std::string netlift::net::exprToString(const Expr *e) {
  std::string s;
  llvm::raw_string_ostream os(s);
  printExpr(e, os);
  return os.str();
}

void netlift::net::printModule(const Module &m, raw_ostream &os,
                               SourceTable *sources) {
  ModulePrinter(m, os, sources).run();
}

/// The lines before the modules: timescale, source files, named types.
/// Returns whether it printed anything (a blank line then separates).
static bool printHeader(const Design &d, raw_ostream &os,
                        llvm::ArrayRef<std::string> files) {
  bool needBlank = false;
  if (d.timescale) {
    os << "timescale " << d.timescale->amount << d.timescale->unit << ";\n";
    needBlank = true;
  }
  if (!files.empty()) {
    for (size_t i = 0; i < files.size(); ++i) {
      os << "source " << i + 1 << " = ";
      printQuoted(files[i], os);
      os << ";\n";
    }
    needBlank = true;
  }
  if (!d.types.namedTypes().empty()) {
    if (needBlank)
      os << '\n';
    for (const auto &nt : d.types.namedTypes()) {
      os << "type " << nt.name << " = ";
      if (nt.isAlias)
        nt.type->print(os);
      else
        nt.type->printStructure(os);
      os << ";\n";
    }
    needBlank = true;
  }
  return needBlank;
}

void netlift::net::printDesign(const Design &d, raw_ostream &os,
                               const llvm::SourceMgr *sources) {
  // The modules are printed first so that the source table above them
  // numbers files in the order their statements use them.
  std::optional<SourceTable> table;
  if (sources)
    table.emplace(*sources);
  std::string modules;
  llvm::raw_string_ostream mos(modules);
  for (const auto &m : d.modules) {
    if (&m != &d.modules.front())
      mos << '\n';
    printModule(*m, mos, table ? &*table : nullptr);
  }
  mos.flush();
  bool needBlank = printHeader(
      d, os, table ? table->fileNames() : llvm::ArrayRef<std::string>());
  if (needBlank && !modules.empty())
    os << '\n';
  os << modules;
}
