//===- PlcAst.cpp - the PLC program model ---------------------------------===//
#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/STLExtras.h"

#include "llvm/ADT/StringExtras.h"

#include <set>

using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;

bool netlift::plc::sameName(StringRef a, StringRef b) {
  return a.equals_insensitive(b);
}

StringRef netlift::plc::spelling(Op op) {
  switch (op) {
  case Op::Neg:
    return "-";
  case Op::Plus:
    return "+";
  case Op::Not:
    return "NOT";
  case Op::Or:
    return "OR";
  case Op::OrElse:
    return "OR_ELSE";
  case Op::Xor:
    return "XOR";
  case Op::And:
    return "AND";
  case Op::AndThen:
    return "AND_THEN";
  case Op::Eq:
    return "=";
  case Op::Ne:
    return "<>";
  case Op::Lt:
    return "<";
  case Op::Le:
    return "<=";
  case Op::Gt:
    return ">";
  case Op::Ge:
    return ">=";
  case Op::Add:
    return "+";
  case Op::Sub:
    return "-";
  case Op::Mul:
    return "*";
  case Op::Div:
    return "/";
  case Op::Mod:
    return "MOD";
  case Op::Pow:
    return "**";
  }
  return "?";
}

std::string netlift::plc::noInstanceMessage(StringRef typeName) {
  return "block " + typeName.str() +
         " has no instanceName (a function block is drawn with the "
         "instance it runs)";
}

StringRef netlift::plc::spelling(VarSection s) {
  switch (s) {
  case VarSection::Var:
    return "VAR";
  case VarSection::Input:
    return "VAR_INPUT";
  case VarSection::Output:
    return "VAR_OUTPUT";
  case VarSection::InOut:
    return "VAR_IN_OUT";
  case VarSection::External:
    return "VAR_EXTERNAL";
  case VarSection::Global:
    return "VAR_GLOBAL";
  case VarSection::Temp:
    return "VAR_TEMP";
  case VarSection::Access:
    return "VAR_ACCESS";
  case VarSection::Config:
    return "VAR_CONFIG";
  case VarSection::Stat:
    return "VAR_STAT";
  case VarSection::Inst:
    return "VAR_INST";
  }
  return "VAR";
}

StringRef netlift::plc::spelling(PouKind k) {
  switch (k) {
  case PouKind::Program:
    return "program";
  case PouKind::FunctionBlock:
    return "function block";
  case PouKind::Function:
    return "function";
  }
  return "POU";
}

VarDecl *Pou::find(StringRef n) const {
  if (indexed != vars.size()) {
    for (; indexed < vars.size(); ++indexed)
      index.try_emplace(StringRef(vars[indexed]->name).upper(), vars[indexed]);
  }
  auto it = index.find(n.upper());
  return it == index.end() ? nullptr : it->second;
}

Pou *Unit::findPou(StringRef n) const {
  for (Pou *p : pous)
    if (!p->methodOf && sameName(p->name, n))
      return p;
  return nullptr;
}

/// The first of `block`'s members (its bases' next; for an interface, the
/// interfaces it extends) that `match` accepts.
static Pou *findMember(const Pou *block,
                       llvm::function_ref<bool(const Pou *)> match,
                       unsigned depth = 0) {
  for (const Pou *b = block; b && depth < 64; b = b->base, ++depth) {
    for (Pou *m : b->methods)
      if (match(m))
        return m;
    if (b->isInterface)
      for (Pou *inner : b->extendedInterfaces)
        if (Pou *m = findMember(inner, match, depth + 1))
          return m;
  }
  return nullptr;
}

Pou *netlift::plc::findMethod(const Pou *block, StringRef name) {
  return findMember(block, [&](const Pou *m) {
    return !m->property && sameName(m->name, name);
  });
}

Pou *netlift::plc::findProperty(const Pou *block, StringRef name, bool set) {
  return findMember(block, [&](const Pou *m) {
    return m->property == (set ? 'S' : 'G') && sameName(m->name, name);
  });
}

Pou *netlift::plc::findCallee(const Pou *block, const Expr *call) {
  return call->property ? findProperty(block, call->name, call->property == 'S')
                        : findMethod(block, call->name);
}

void netlift::plc::forEachInitialValue(Initializer *init,
                                       llvm::function_ref<void(Expr *)> fn) {
  if (!init)
    return;
  if (init->value)
    fn(init->value);
  for (auto &[n, e] : init->elems)
    forEachInitialValue(e, fn);
  for (auto &[n, e] : init->fields)
    forEachInitialValue(e, fn);
}

std::vector<const netlift::plc::Task *>
netlift::plc::twinCatTasks(const Unit &unit) {
  std::vector<const Task *> tasks;
  for (const Configuration *c : unit.configs)
    if (c->name == "TwinCAT")
      for (const Task &t : c->tasks)
        tasks.push_back(&t);
  return tasks;
}

bool netlift::plc::derivedFrom(const Pou *block, const Pou *base) {
  for (int depth = 0; block && depth < 64; block = block->base, ++depth)
    if (block == base)
      return true;
  return false;
}

bool netlift::plc::implementsInterface(const Unit &unit, const Pou *block,
                                       const Pou *itf) {
  std::set<const Pou *> seen;
  std::function<bool(const Pou *)> reaches = [&](const Pou *i) {
    if (!i || !seen.insert(i).second)
      return false;
    if (i == itf)
      return true;
    for (const std::string &n : i->implements)
      if (reaches(unit.findPou(n)))
        return true;
    return false;
  };
  for (const Pou *b = block; b; b = b->base)
    for (const std::string &n : b->implements)
      if (reaches(unit.findPou(n)))
        return true;
  return block == itf;
}

void netlift::plc::forEachMethod(const Pou *block,
                                 llvm::function_ref<void(Pou *)> fn) {
  for (const Pou *b = block; b; b = b->base)
    for (Pou *m : b->methods)
      fn(m);
}

void netlift::plc::resolveInheritance(Unit &unit) {
  auto refuse = [](Pou *p, SMLoc at, std::string why) {
    if (p->refusal.empty()) {
      p->refusal = std::move(why);
      p->refusalLoc = at;
    }
  };
  for (Pou *p : unit.pous) {
    for (const std::string &n : p->implements) {
      // An interface the inputs do not declare (a library's) changes
      // nothing the block does: nothing can be assigned to it here.
      Pou *itf = unit.findPou(n);
      if (!itf && !p->isInterface)
        continue;
      // CODESYS's root of queryable interfaces declares nothing: every
      // interface can be queried here (__QUERYINTERFACE, `?=`).
      if (!itf && StringRef(n).equals_insensitive("__SYSTEM.IQueryInterface"))
        continue;
      if (!itf || !itf->isInterface) {
        refuse(p, p->loc,
               "'" + p->name + "' " +
                   (p->isInterface ? "EXTENDS" : "IMPLEMENTS") + " '" + n +
                   "', which is " +
                   (itf ? "not an INTERFACE" : std::string("not declared")));
        continue;
      }
      if (p->isInterface && !llvm::is_contained(p->extendedInterfaces, itf))
        p->extendedInterfaces.push_back(itf);
    }
    if (p->extends.empty() || p->base)
      continue;
    Pou *base = unit.findPou(p->extends);
    if (!base || base->kind != p->kind || base->isInterface) {
      refuse(p, p->extendsLoc,
             "'" + p->name + "' EXTENDS '" + p->extends + "', which is " +
                 (base ? "not a " + spelling(p->kind).str()
                       : std::string("not declared")));
      continue;
    }
    p->base = base;
  }
  // Bases first: a chain is flattened from its root, each block once.
  std::set<Pou *> done;
  std::function<bool(Pou *, std::vector<Pou *> &)> flatten =
      [&](Pou *p, std::vector<Pou *> &path) {
        if (!p->base || done.count(p))
          return true;
        if (llvm::is_contained(path, p)) {
          refuse(p, p->extendsLoc,
                 "'" + p->name + "' extends itself through its bases");
          return false;
        }
        path.push_back(p);
        if (!flatten(p->base, path))
          return false;
        path.pop_back();
        done.insert(p);
        std::vector<VarDecl *> merged;
        for (VarDecl *v : p->base->vars) {
          if (VarDecl *own = p->find(v->name)) {
            refuse(p, own->loc,
                   "'" + own->name + "' is declared again in '" + p->name +
                       "'; its base '" + p->base->name + "' declares it");
            return false;
          }
          merged.push_back(v);
        }
        llvm::append_range(merged, p->vars);
        p->vars = std::move(merged);
        p->varsReordered();
        return true;
      };
  for (Pou *p : unit.pous) {
    std::vector<Pou *> path;
    if (!flatten(p, path))
      for (Pou *q : path) // no cycle left for findMethod to follow
        q->base = nullptr;
  }
  for (Pou *p : unit.pous)
    if (!p->extends.empty() && !p->base)
      refuse(p, p->extendsLoc,
             "'" + p->name + "' EXTENDS '" + p->extends +
                 "', which cannot be resolved (see its base)");
}

TypeDecl *Unit::findType(StringRef n) const {
  for (TypeDecl *t : types)
    if (sameName(t->name, n))
      return t;
  return nullptr;
}

VarDecl *AstMaker::declare(Pou &pou, StringRef name, StringRef type, SMLoc at,
                           VarSection section) {
  VarDecl *v = unit.make<VarDecl>();
  v->name = name.str();
  v->loc = at;
  v->section = section;
  if (type.empty()) {
    v->inferType = true;
  } else {
    v->typeSyntax = unit.make<TypeSyntax>(TypeSyntaxKind::Named, at);
    v->typeSyntax->name = type.str();
  }
  pou.vars.push_back(v);
  return v;
}

void netlift::plc::forEachNestedExpr(Expr *e,
                                     llvm::function_ref<void(Expr *)> fn) {
  if (!e)
    return;
  fn(e);
  for (Expr *o : e->operands)
    forEachNestedExpr(o, fn);
  for (CallArg &a : e->args)
    forEachNestedExpr(a.value, fn);
}

void netlift::plc::forEachStmt(StmtList &l,
                               llvm::function_ref<void(Stmt *)> stmt,
                               llvm::function_ref<void(Expr *)> expr) {
  for (Stmt *s : l) {
    if (stmt)
      stmt(s);
    if (expr)
      for (Expr *e : {s->target, s->value, s->from, s->to, s->by})
        if (e)
          expr(e);
    for (auto &[c, body] : s->arms) {
      if (expr && c)
        expr(c);
      forEachStmt(body, stmt, expr);
    }
    for (CaseArmSyntax &arm : s->caseArms)
      forEachStmt(arm.body, stmt, expr);
    forEachStmt(s->elseBody, stmt, expr);
    forEachStmt(s->body, stmt, expr);
  }
}

void netlift::plc::keepRefusedPou(Unit &unit, size_t pousBefore, PouKind kind,
                                  StringRef name, llvm::SMLoc loc,
                                  llvm::SMLoc refusalLoc, std::string refusal) {
  Pou *pou = unit.pous.size() > pousBefore ? unit.pous.back() : nullptr;
  if (!pou) {
    pou = unit.make<Pou>();
    pou->kind = kind;
    pou->name = name.str();
    pou->loc = loc;
    unit.pous.push_back(pou);
  }
  pou->refusalLoc = refusalLoc;
  pou->refusal = std::move(refusal);
}

std::optional<std::string>
netlift::plc::decodeStringLiteral(StringRef quoted, std::u16string &out) {
  out.clear();
  bool wide = quoted.startswith("\"");
  StringRef body = quoted.drop_front().drop_back();
  for (size_t i = 0; i < body.size(); ++i) {
    unsigned char c = body[i];
    if (c != '$') {
      out += char16_t(c);
      continue;
    }
    char n = i + 1 < body.size() ? body[i + 1] : '\0';
    char16_t escaped = 0;
    switch (llvm::toUpper(n)) {
    case '$':
    case '\'':
    case '"':
      escaped = char16_t(n);
      break;
    case 'L':
    case 'N':
      escaped = '\n';
      break;
    case 'P':
      escaped = '\f';
      break;
    case 'R':
      escaped = '\r';
      break;
    case 'T':
      escaped = '\t';
      break;
    default: {
      size_t digits = wide ? 4 : 2;
      uint64_t code;
      if (i + 1 + digits > body.size() ||
          body.substr(i + 1, digits).getAsInteger(16, code))
        return "malformed escape '$" + body.substr(i + 1, digits).str() +
               "' in a string literal (write $$, $', $L, $N, $P, $R, $T or " +
               (wide ? "four" : "two") + " hex digits)";
      out += char16_t(code);
      i += digits;
      continue;
    }
    }
    out += escaped;
    ++i;
  }
  return std::nullopt;
}
