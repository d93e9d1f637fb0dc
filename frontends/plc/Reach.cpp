//===- Reach.cpp - the POUs a PLC translation reaches ---------------------===//
//
// Only what the translated programs use is checked and lowered: a library
// file may hold POUs netlift cannot model (pointers, methods) next to the
// function block a user translates with --top. The walk is by name over
// declarations and bodies (variable types, type declarations they name,
// calls); a name that turns out to be a variable rather than a POU only
// adds nothing.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Sema.h"

#include <set>

using namespace netlift;
using namespace netlift::plc;
using llvm::StringRef;

namespace {

class ReachWalk {
public:
  explicit ReachWalk(const Unit &unit) : unit(unit) {}

  void pou(Pou *p) {
    if (!p || !reached.insert(p).second)
      return;
    todo.push_back(p);
  }

  void run() {
    while (!todo.empty()) {
      Pou *p = todo.back();
      todo.pop_back();
      for (VarDecl *v : p->vars)
        type(v->typeSyntax);
      type(p->resultSyntax);
      stmts(p->body);
      // A block's methods and actions (any may be called on an instance),
      // a method's block, and the blocks extended.
      pou(p->methodOf);
      pou(p->base);
      forEachMethod(p, [&](Pou *m) { pou(m); });
    }
  }

  void globals(const std::vector<VarDecl *> &vars) {
    for (VarDecl *v : vars)
      type(v->typeSyntax);
  }

  std::set<Pou *> reached;

private:
  void name(StringRef n) {
    if (Pou *p = unit.findPou(n))
      pou(p);
    else if (TypeDecl *td = unit.findType(n)) {
      if (typesSeen.insert(td).second)
        type(td->type);
    } else if (n.contains('.')) {
      name(n.split('.').second); // `Tc2_Standard.TON`: the library's
    }
  }
  void type(TypeSyntax *ts) {
    if (!ts)
      return;
    if (!ts->name.empty())
      name(ts->name);
    type(ts->elem);
    for (VarDecl *f : ts->fields)
      type(f->typeSyntax);
  }
  void expr(Expr *e) {
    if (!e)
      return;
    if (e->kind == ExprKind::Call)
      name(e->name);
    for (Expr *o : e->operands)
      expr(o);
    for (CallArg &a : e->args)
      expr(a.value);
  }
  void stmts(StmtList &list) {
    forEachStmt(list, nullptr, [&](Expr *e) { expr(e); });
  }

  const Unit &unit;
  std::vector<Pou *> todo;
  std::set<TypeDecl *> typesSeen;
};

} // namespace

std::vector<Pou *> plc::reachedPous(const Unit &unit, StringRef top) {
  ReachWalk walk(unit);
  bool fromConfig = false;
  for (Configuration *c : unit.configs)
    for (ProgramInstance &pi : c->programs)
      if (top.empty() || sameName(pi.name, top) || sameName(pi.typeName, top)) {
        walk.pou(unit.findPou(pi.typeName));
        fromConfig = true;
      }
  if (!top.empty() && walk.reached.empty())
    walk.pou(unit.findPou(top));
  if (top.empty() && walk.reached.empty())
    for (Pou *p : unit.pous)
      if (p->kind == PouKind::Program)
        walk.pou(p);
  if (walk.reached.empty())
    return unit.pous; // a library: every POU
  if (fromConfig)
    for (Configuration *c : unit.configs)
      walk.globals(c->globals);
  walk.globals(unit.globals);
  walk.run();
  std::vector<Pou *> out;
  for (Pou *p : unit.pous)
    if (walk.reached.count(p))
      out.push_back(p);
  return out;
}
