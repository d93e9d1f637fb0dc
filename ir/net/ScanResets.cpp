//===- ScanResets.cpp - the end-of-scan resets of PLC memory --------------===//
#include "ir/net/ScanResets.h"

#include "ir/net/Walk.h"

#include "ir/net/Names.h"
#include "ir/net/Printer.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"

using namespace netlift;
using namespace netlift::net;

llvm::DenseSet<uint32_t> net::scanResetVars(const Module &m) {
  llvm::DenseSet<uint32_t> out;
  for (const Attribute &a : m.attributes)
    if (a.key == kScanResetAttribute)
      if (Symbol s = m.lookup(a.target); s.kind == SymKind::Var)
        out.insert(s.index);
  return out;
}

/// A value the frontend resets to: nothing it reads can change.
static bool isConstant(const Expr *e) {
  bool constant = true;
  walkExpr(e, [&](const Expr *x) {
    if (auto *r = llvm::dyn_cast<Ref>(x))
      constant &= r->sym.kind != SymKind::Var && r->sym.kind != SymKind::Port;
  });
  return constant;
}

llvm::DenseSet<const Stmt *>
net::scanResetStatements(const Module &m,
                         llvm::function_ref<bool(uint32_t)> resetVar) {
  llvm::DenseSet<const Stmt *> out;
  llvm::DenseSet<uint32_t> marked = scanResetVars(m);
  if (marked.empty())
    return out;
  for (const Transition &t : m.transitions) {
    if (!t.hasAction())
      continue;
    // Backwards: a variable's reset is one run of constant assignments
    // (one per element of an aggregate, each element once) followed by no
    // other write of it; a write before the run, `c.PV := 3` before
    // `c.PV := 0`, is the program's own.
    llvm::DenseSet<uint32_t> writtenLater, closed;
    llvm::DenseMap<uint32_t, llvm::StringSet<>> resetTargets;
    Block action = t.action();
    for (auto it = action.rbegin(); it != action.rend(); ++it) {
      Stmt *const *at = &*it;
      const Stmt *st = *at;
      if (auto *a = llvm::dyn_cast<AssignStmt>(st)) {
        Symbol root = targetRoot(a->target);
        if (root.kind == SymKind::Var && marked.count(root.index) &&
            !writtenLater.count(root.index) && !closed.count(root.index) &&
            isConstant(a->value) &&
            resetTargets[root.index].insert(exprToString(a->target)).second) {
          if (resetVar(root.index))
            out.insert(st);
          continue;
        }
      }
      for (auto &[v, targets] : resetTargets)
        closed.insert(v);
      forEachAssign(Block(at, 1), [&](const AssignStmt *w) {
        Symbol root = targetRoot(w->target);
        if (root.kind == SymKind::Var)
          writtenLater.insert(root.index);
      });
    }
  }
  return out;
}

llvm::DenseSet<const Stmt *> net::scanResetStatements(const Module &m) {
  return scanResetStatements(m, [](uint32_t) { return true; });
}

bool net::isNameInScope(llvm::StringRef name, llvm::StringRef scope) {
  return name == scope ||
         (name.startswith(scope) && name.size() > scope.size() &&
          name[scope.size()] == '.');
}

std::vector<std::string> net::scanResetVarsNamedIn(const Module &m,
                                                   llvm::StringRef text) {
  llvm::DenseSet<uint32_t> marked = scanResetVars(m);
  std::vector<std::string> out;
  if (marked.empty())
    return out;
  std::vector<std::string> words = qualifiedNamesIn(text);
  std::vector<uint32_t> vars(marked.begin(), marked.end());
  llvm::sort(vars);
  for (uint32_t v : vars) {
    llvm::StringRef name = m.vars[v].name;
    for (const std::string &w : words)
      if (isNameInScope(name, w)) {
        out.push_back(name.str());
        break;
      }
  }
  return out;
}
