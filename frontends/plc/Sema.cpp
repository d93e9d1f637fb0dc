//===- Sema.cpp - names and types of a PLC program ------------------------===//
//
// Implicit conversions follow IEC 61131-3 3rd edition: an integer widens to
// a wider integer of compatible signedness, a literal fits any integer type
// that holds its value, and nothing else converts without a *_TO_*
// function. netlift is lenient in two places real code relies on, both
// written down in docs/st.md: a POU may read and write a global without a
// VAR_EXTERNAL declaration, and a bit string and an integer of the same
// width convert into each other.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Sema.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSwitch.h"

#include <map>
#include <set>

using namespace netlift;
using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;
using llvm::Twine;

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

std::string PType::str() const {
  if (!name.empty())
    return name;
  switch (kind) {
  case PTypeKind::AnyInt:
    return "ANY_INT";
  case PTypeKind::Array: {
    std::string r = "ARRAY[";
    for (size_t d = 0; d < dims.size(); ++d)
      r += (d ? "," : "") + std::to_string(dims[d].first) + ".." +
           std::to_string(dims[d].second);
    return r + "] OF " + (elem ? elem->str() : "?");
  }
  case PTypeKind::Enum:
    return "enumeration";
  case PTypeKind::Struct:
    return "STRUCT";
  case PTypeKind::Void:
    return "no value";
  default:
    return "?";
  }
}

namespace {

struct Elementary {
  const char *name;
  PTypeKind kind;
  unsigned width;
  bool isSigned;
  bool isBits;
};

const Elementary kElementary[] = {
    {"BOOL", PTypeKind::Bool, 1, false, true},
    {"SINT", PTypeKind::Int, 8, true, false},
    {"INT", PTypeKind::Int, 16, true, false},
    {"DINT", PTypeKind::Int, 32, true, false},
    {"LINT", PTypeKind::Int, 64, true, false},
    {"USINT", PTypeKind::Int, 8, false, false},
    {"UINT", PTypeKind::Int, 16, false, false},
    {"UDINT", PTypeKind::Int, 32, false, false},
    {"ULINT", PTypeKind::Int, 64, false, false},
    {"BYTE", PTypeKind::Int, 8, false, true},
    {"WORD", PTypeKind::Int, 16, false, true},
    {"DWORD", PTypeKind::Int, 32, false, true},
    {"LWORD", PTypeKind::Int, 64, false, true},
    {"TIME", PTypeKind::Time, 64, true, false},
    {"LTIME", PTypeKind::Time, 64, true, false},
    {"REAL", PTypeKind::Real, 32, true, false},
    {"LREAL", PTypeKind::Real, 64, true, false},
    {"STRING", PTypeKind::String, 0, false, false},
    {"WSTRING", PTypeKind::String, 0, false, false},
    {"CHAR", PTypeKind::String, 0, false, false},
    {"WCHAR", PTypeKind::String, 0, false, false},
    {"DATE", PTypeKind::Date, 0, false, false},
    {"TOD", PTypeKind::Date, 0, false, false},
    {"TIME_OF_DAY", PTypeKind::Date, 0, false, false},
    {"DT", PTypeKind::Date, 0, false, false},
    {"DATE_AND_TIME", PTypeKind::Date, 0, false, false},
    {"LDATE", PTypeKind::Date, 0, false, false},
    {"LTOD", PTypeKind::Date, 0, false, false},
    {"LDT", PTypeKind::Date, 0, false, false},
};

/// The elementary types, held by value (StringMap entries do not move).
const llvm::StringMap<PType> &elementaryTable() {
  static const llvm::StringMap<PType> table = [] {
    llvm::StringMap<PType> t;
    for (const Elementary &e : kElementary) {
      PType *ty = &t.try_emplace(e.name, PType{e.kind}).first->second;
      ty->name = e.name;
      ty->width = e.width;
      ty->isSigned = e.isSigned;
      ty->isBits = e.isBits && e.kind == PTypeKind::Int;
      if (e.kind == PTypeKind::Int) {
        if (e.width == 64) {
          ty->lo = e.isSigned ? INT64_MIN : 0;
          ty->hi = INT64_MAX;
        } else if (e.isSigned) {
          ty->lo = -(int64_t(1) << (e.width - 1));
          ty->hi = (int64_t(1) << (e.width - 1)) - 1;
        } else {
          ty->lo = 0;
          ty->hi = (int64_t(1) << e.width) - 1;
        }
      }
      if (e.kind == PTypeKind::Bool)
        ty->hi = 1;
    }
    return t;
  }();
  return table;
}

const PType *anyIntType() {
  static const PType t{PTypeKind::AnyInt};
  return &t;
}
const PType *voidType() {
  static const PType t{PTypeKind::Void};
  return &t;
}
const PType *boolType() { return elementaryType("BOOL"); }

/// Strips a subrange to its elementary type.
const PType *baseOf(const PType *t) {
  return t && t->isSubrange && t->base ? t->base : t;
}

} // namespace

const PType *plc::elementaryType(StringRef name) {
  auto it = elementaryTable().find(name.upper());
  return it == elementaryTable().end() ? nullptr : &it->second;
}

StdFnInfo plc::lookupStdFunction(StringRef name) {
  std::string up = name.upper();
  StdFnInfo info;
  info.fn = llvm::StringSwitch<StdFn>(up)
                .Case("ABS", StdFn::Abs)
                .Case("MIN", StdFn::Min)
                .Case("MAX", StdFn::Max)
                .Case("LIMIT", StdFn::Limit)
                .Case("SEL", StdFn::Sel)
                .Case("MUX", StdFn::Mux)
                .Case("MOVE", StdFn::Move)
                .Case("ADD", StdFn::Add)
                .Case("SUB", StdFn::Sub)
                .Case("MUL", StdFn::Mul)
                .Case("DIV", StdFn::Div)
                .Case("MOD", StdFn::Mod)
                .Case("AND", StdFn::And)
                .Case("OR", StdFn::Or)
                .Case("XOR", StdFn::Xor)
                .Case("NOT", StdFn::Not)
                .Case("SHL", StdFn::Shl)
                .Case("SHR", StdFn::Shr)
                .Case("ROL", StdFn::Rol)
                .Case("ROR", StdFn::Ror)
                .Case("GT", StdFn::Gt)
                .Case("GE", StdFn::Ge)
                .Case("EQ", StdFn::Eq)
                .Case("LE", StdFn::Le)
                .Case("LT", StdFn::Lt)
                .Case("NE", StdFn::Ne)
                .Cases("SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN",
                       StdFn::RealMath)
                .Cases("ASIN", "ACOS", "ATAN", "ATAN2", "EXPT", "TRUNC",
                       StdFn::RealMath)
                .Cases("LEN", "LEFT", "RIGHT", "MID", "CONCAT", "INSERT",
                       StdFn::StringOp)
                .Cases("DELETE", "REPLACE", "FIND", StdFn::StringOp)
                .Default(StdFn::None);
  if (info.fn != StdFn::None)
    return info;
  // Conversions: TO_INT, INT_TO_BOOL, TRUNC_INT, BCD_TO_INT, ...
  StringRef u(up);
  if (u.startswith("TO_")) {
    if (const PType *to = elementaryType(u.drop_front(3))) {
      info.fn = StdFn::Convert;
      info.to = to;
    }
    return info;
  }
  size_t pos = u.find("_TO_");
  if (pos != StringRef::npos) {
    StringRef from = u.substr(0, pos), to = u.substr(pos + 4);
    if (from == "BCD" || to == "BCD" || from.endswith("_BCD") ||
        to.startswith("BCD_")) {
      info.fn = StdFn::Refused;
      return info;
    }
    const PType *f = elementaryType(from), *t = elementaryType(to);
    if (f && t) {
      info.fn = StdFn::Convert;
      info.from = f;
      info.to = t;
    }
  }
  return info;
}

//===----------------------------------------------------------------------===//
// The checker
//===----------------------------------------------------------------------===//

namespace {

class Checker {
public:
  Checker(Unit &u, DiagEngine &d) : unit(u), diag(d) {}
  bool run();

private:
  void error(SMLoc at, const Twine &msg) { diag.error(at, msg); }

  // Types.
  const PType *resolve(TypeSyntax *ts, StringRef ownerName);
  const PType *resolveNamed(StringRef name, SMLoc at);
  bool constInt(Expr *e, int64_t &v);
  void checkInitializer(Initializer *init, const PType *t);

  // Declarations.
  void declareVars(std::vector<VarDecl *> &vars, Pou *owner);

  // Bodies.
  void checkPou(Pou *pou);
  void stmts(StmtList &list);
  void stmt(Stmt *s);
  const PType *expr(Expr *e);
  const PType *lvalue(Expr *e);
  const PType *call(Expr *e, bool asStatement);
  void functionArgs(Expr *e, Pou *fn);
  bool drawnAsDeclared(Expr *e, Pou *type);
  bool assignable(const PType *to, Expr *from, SMLoc at, const Twine &what);
  void checkProgramArgs(ProgramInstance &pi, Pou *p);
  const PType *commonNumeric(const PType *a, const PType *b, Expr *e);
  VarDecl *lookupVar(StringRef name);
  int64_t lookupEnumerator(StringRef name, const PType *&type);
  VarDecl *enEno(Pou *p, StringRef name);
  bool orderStdArgs(Expr *e, StdFn fn);
  // The enumerated type an ambiguous enumerator resolves to (assignment
  // target, CASE selector), if any.
  const PType *expectedEnum = nullptr;
  void indexEnum(const PType *t);
  // Enumerators by upper-case name: every enumerated type of the unit.
  llvm::StringMap<std::vector<std::pair<const PType *, int64_t>>> enumsByName;
  std::set<const PType *> indexedEnums;

  Unit &unit;
  DiagEngine &diag;
  std::map<std::string, const PType *> named; // user types, upper-case key
  std::map<std::string, int> resolving;       // cycle detection
  std::vector<VarDecl *> allGlobals;
  Pou *current = nullptr;
  unsigned loopDepth = 0;

  // Types live as long as the unit: the lowering reads them after Sema.
  PType *make(PTypeKind k) { return unit.make<PType>(PType{k}); }
};

} // namespace

bool Checker::constInt(Expr *e, int64_t &v) {
  if (!e)
    return false;
  switch (e->kind) {
  case ExprKind::IntLit:
    v = e->intValue;
    return true;
  case ExprKind::Unary: {
    int64_t a;
    if (e->op == Op::Neg && constInt(e->operands[0], a)) {
      v = -a;
      return true;
    }
    if (e->op == Op::Plus)
      return constInt(e->operands[0], v);
    return false;
  }
  case ExprKind::Binary: {
    int64_t a, b;
    if (!constInt(e->operands[0], a) || !constInt(e->operands[1], b))
      return false;
    switch (e->op) {
    case Op::Add:
      v = a + b;
      return true;
    case Op::Sub:
      v = a - b;
      return true;
    case Op::Mul:
      v = a * b;
      return true;
    case Op::Div:
      if (b == 0)
        return false;
      v = a / b;
      return true;
    case Op::Mod:
      if (b == 0)
        return false;
      v = a % b;
      return true;
    default:
      return false;
    }
  }
  case ExprKind::Name: {
    // A CONSTANT variable with a literal initial value.
    VarDecl *var = lookupVar(e->name);
    if (var && var->constant && var->typeSyntax && var->typeSyntax->init &&
        var->typeSyntax->init->kind == Initializer::Value)
      return constInt(var->typeSyntax->init->value, v);
    return false;
  }
  default:
    return false;
  }
}

const PType *Checker::resolveNamed(StringRef name, SMLoc at) {
  if (const PType *t = elementaryType(name))
    return t;
  std::string key = name.upper();
  auto it = named.find(key);
  if (it != named.end())
    return it->second;
  if (TypeDecl *td = unit.findType(name)) {
    if (resolving[key]++) {
      error(td->loc, "type '" + td->name + "' is defined in terms of itself");
      named[key] = nullptr;
      return nullptr;
    }
    const PType *t = resolve(td->type, td->name);
    resolving[key] = 0;
    if (!t) {
      named[key] = nullptr; // reported once; later uses stay quiet
      return nullptr;
    }
    // Structured and enumerated types take their declared name.
    if (t->name.empty() || t->kind == PTypeKind::Enum ||
        t->kind == PTypeKind::Struct || t->isSubrange) {
      PType *copy = make(t->kind);
      *copy = *t;
      copy->name = td->name;
      t = copy;
    }
    named[key] = t;
    td->resolved = t;
    return t;
  }
  if (Pou *p = unit.findPou(name)) {
    if (p->kind == PouKind::FunctionBlock) {
      PType *t = make(PTypeKind::FunctionBlock);
      t->name = p->name;
      t->fb = p;
      named[key] = t;
      return t;
    }
    error(at, "'" + name + "' is a " + spelling(p->kind) + ", not a type");
    return nullptr;
  }
  error(at, "unknown type '" + name + "'");
  return nullptr;
}

const PType *Checker::resolve(TypeSyntax *ts, StringRef ownerName) {
  if (!ts)
    return nullptr;
  switch (ts->kind) {
  case TypeSyntaxKind::Named:
    return resolveNamed(ts->name, ts->loc);
  case TypeSyntaxKind::String:
    return elementaryType(ts->name);
  case TypeSyntaxKind::Subrange: {
    const PType *base = resolveNamed(ts->name, ts->loc);
    if (!base)
      return nullptr;
    if (base->kind != PTypeKind::Int) {
      error(ts->loc,
            "a subrange needs an integer base type, not '" + base->str() + "'");
      return nullptr;
    }
    int64_t lo, hi;
    if (!constInt(ts->lo, lo) || !constInt(ts->hi, hi)) {
      error(ts->loc, "subrange bounds must be constant integers");
      return nullptr;
    }
    if (lo > hi || lo < base->lo || hi > base->hi) {
      error(ts->loc, "subrange " + Twine(lo) + ".." + Twine(hi) +
                         " is empty or outside " + base->str());
      return nullptr;
    }
    PType *t = make(PTypeKind::Int);
    *t = *base;
    t->name.clear();
    t->isSubrange = true;
    t->base = base;
    t->lo = lo;
    t->hi = hi;
    return t;
  }
  case TypeSyntaxKind::Array: {
    const PType *elem = resolve(ts->elem, ownerName);
    if (!elem)
      return nullptr;
    PType *t = make(PTypeKind::Array);
    t->elem = elem;
    for (auto &[loE, hiE] : ts->dims) {
      int64_t lo, hi;
      if (!constInt(loE, lo) || !constInt(hiE, hi)) {
        error(loE ? loE->loc : ts->loc,
              "array bounds must be constant integers");
        return nullptr;
      }
      if (lo > hi) {
        error(loE->loc,
              "array bounds " + Twine(lo) + ".." + Twine(hi) + " are empty");
        return nullptr;
      }
      t->dims.push_back({lo, hi});
    }
    return t;
  }
  case TypeSyntaxKind::Enum: {
    PType *t = make(PTypeKind::Enum);
    for (auto &ev : ts->enumerators) {
      for (auto &prev : t->enumerators)
        if (sameName(prev, ev.name)) {
          error(ev.loc, "enumerator '" + ev.name + "' appears twice");
          return nullptr;
        }
      t->enumerators.push_back(ev.name);
    }
    t->hi = int64_t(t->enumerators.size()) - 1;
    // Anonymous enumerations are named after the variable or type that
    // declares them.
    t->name = ownerName.str();
    return t;
  }
  case TypeSyntaxKind::Struct: {
    PType *t = make(PTypeKind::Struct);
    for (VarDecl *f : ts->fields) {
      f->type = resolve(f->typeSyntax, f->name);
      if (!f->type)
        return nullptr;
      for (VarDecl *g : t->fields)
        if (sameName(g->name, f->name)) {
          error(f->loc, "field '" + f->name + "' appears twice");
          return nullptr;
        }
      t->fields.push_back(f);
    }
    t->name = ownerName.str();
    return t;
  }
  case TypeSyntaxKind::Refused:
    error(ts->loc, ts->refused + " is not supported");
    return nullptr;
  }
  return nullptr;
}

void Checker::checkInitializer(Initializer *init, const PType *t) {
  if (!init || !t)
    return;
  switch (init->kind) {
  case Initializer::Value:
    if (t->kind == PTypeKind::FunctionBlock || t->kind == PTypeKind::Array ||
        t->kind == PTypeKind::Struct) {
      // `arr : ARRAY[1..3] OF INT := 0`? Not IEC; refuse.
      error(init->loc,
            "a single value cannot initialise a value of type " + t->str());
      return;
    }
    expr(init->value);
    assignable(t, init->value, init->loc, "initial value");
    return;
  case Initializer::Array:
    if (t->kind != PTypeKind::Array) {
      error(init->loc, "an array initialiser for a " + t->str());
      return;
    }
    for (auto &[count, inner] : init->elems)
      if (inner) {
        if (t->dims.size() > 1) {
          error(inner->loc, "initialisers of multi-dimensional arrays are "
                            "not supported");
          return;
        }
        checkInitializer(inner, t->elem);
      }
    return;
  case Initializer::Struct: {
    if (t->kind != PTypeKind::Struct && t->kind != PTypeKind::FunctionBlock) {
      error(init->loc, "a structure initialiser for a " + t->str());
      return;
    }
    for (auto &[name, inner] : init->fields) {
      VarDecl *f = nullptr;
      if (t->kind == PTypeKind::Struct) {
        for (VarDecl *g : t->fields)
          if (sameName(g->name, name))
            f = g;
      } else {
        f = t->fb->find(name);
      }
      if (!f) {
        error(inner ? inner->loc : init->loc,
              "'" + t->str() + "' has no member '" + name + "'");
        continue;
      }
      checkInitializer(inner, f->type);
    }
    return;
  }
  }
}

void Checker::declareVars(std::vector<VarDecl *> &vars, Pou *owner) {
  llvm::StringMap<VarDecl *> seen;
  for (size_t i = 0; i < vars.size(); ++i) {
    VarDecl *v = vars[i];
    v->owner = owner;
    auto [it, fresh] = seen.try_emplace(StringRef(v->name).upper(), v);
    if (!fresh) {
      error(v->loc, "'" + v->name + "' is declared twice");
      diag.note(it->second->loc, "first declared here");
    }
    // A variable sharing its type syntax with the ones before it (`a, b :
    // INT`) shares the resolved type too.
    if (i > 0 && vars[i - 1]->typeSyntax == v->typeSyntax)
      v->type = vars[i - 1]->type;
    else
      v->type = resolve(v->typeSyntax, v->name);
  }
}

VarDecl *Checker::lookupVar(StringRef name) {
  if (current) {
    if (VarDecl *v = current->find(name)) {
      if (v->section != VarSection::External)
        return v;
      for (VarDecl *g : allGlobals)
        if (sameName(g->name, name))
          return g;
      return v; // reported at the declaration
    }
  }
  for (VarDecl *g : allGlobals)
    if (sameName(g->name, name))
      return g;
  return nullptr;
}

void Checker::indexEnum(const PType *t) {
  if (!t || !indexedEnums.insert(t).second)
    return;
  if (t->kind == PTypeKind::Array)
    indexEnum(t->elem);
  if (t->kind == PTypeKind::Struct)
    for (VarDecl *f : t->fields)
      indexEnum(f->type);
  if (t->kind != PTypeKind::Enum)
    return;
  for (size_t i = 0; i < t->enumerators.size(); ++i)
    enumsByName[StringRef(t->enumerators[i]).upper()].push_back(
        {t, int64_t(i)});
}

int64_t Checker::lookupEnumerator(StringRef name, const PType *&type) {
  type = nullptr;
  auto it = enumsByName.find(name.upper());
  if (it == enumsByName.end())
    return -1;
  int64_t value = -1;
  for (auto &[t, v] : it->second) {
    if (type && type->name != t->name)
      return -2; // ambiguous
    type = t;
    value = v;
  }
  return value;
}

/// IEC gives every function and function block the Boolean input EN
/// (TRUE when not given: the body runs) and output ENO. netlift declares
/// them the first time a body, a call or a reader names them.
VarDecl *Checker::enEno(Pou *p, StringRef name) {
  if (!p || p->kind == PouKind::Program)
    return nullptr;
  bool en = name.equals_insensitive("EN"), eno = name.equals_insensitive("ENO");
  if (!en && !eno)
    return nullptr;
  if (VarDecl *v = p->find(name))
    return v;
  VarDecl *v = unit.make<VarDecl>();
  v->name = en ? "EN" : "ENO";
  v->loc = p->loc;
  v->section = en ? VarSection::Input : VarSection::Output;
  v->type = boolType();
  v->owner = p;
  if (en) {
    v->typeSyntax = unit.make<TypeSyntax>(TypeSyntaxKind::Named, p->loc);
    v->typeSyntax->name = "BOOL";
    v->typeSyntax->init = unit.make<Initializer>(Initializer::Value, p->loc);
    v->typeSyntax->init->value = unit.make<Expr>(ExprKind::BoolLit, p->loc);
    v->typeSyntax->init->value->intValue = 1;
    v->typeSyntax->init->value->type = boolType();
  }
  p->vars.push_back(v);
  return v;
}

/// `PROGRAM inst WITH task : Prog(IN := g, OUT => h)`: each argument names
/// an input (`:=`) or output (`=>`) of the program and binds it to a global
/// variable of matching type (IEC 61131-3 2.7.1).
void Checker::checkProgramArgs(ProgramInstance &pi, Pou *p) {
  for (CallArg &a : pi.args) {
    if (a.name.empty()) {
      error(a.loc, "arguments of program instance '" + pi.name +
                       "' must be named ('IN := g' or 'OUT => g')");
      continue;
    }
    VarDecl *v = p->find(a.name);
    VarSection want = a.isOutput ? VarSection::Output : VarSection::Input;
    if (!v || v->section != want) {
      error(a.loc, "program '" + p->name + "' has no " +
                       (a.isOutput ? "output '" : "input '") + a.name + "'");
      continue;
    }
    if (a.negated)
      error(a.loc, "a negated program argument is not supported");
    if (a.value && a.value->kind == ExprKind::Name &&
        StringRef(a.value->name).startswith("%")) {
      error(a.value->loc, "binding '" + a.name + "' to the direct address " +
                              a.value->name +
                              " is not supported: declare the variable AT " +
                              a.value->name + " in the program");
      continue;
    }
    unsigned errorsBefore = diag.numErrors();
    if (!a.value || a.value->kind != ExprKind::Name || !expr(a.value) ||
        !a.value->var || a.value->var->owner) {
      if (diag.numErrors() == errorsBefore) // not already explained
        error(a.value ? a.value->loc : a.loc,
              "the argument of '" + a.name +
                  "' must be a global variable of the configuration");
      continue;
    }
    if (a.value->var->constant && a.isOutput) {
      error(a.value->loc, "output '" + a.name + "' is bound to constant '" +
                              a.value->var->name + "'");
      continue;
    }
    if (v->type && a.value->type && v->type->str() != a.value->type->str())
      error(a.value->loc, "'" + a.name + "' of program '" + p->name + "' is " +
                              v->type->str() + ", global '" +
                              a.value->var->name + "' is " +
                              a.value->type->str());
  }
}

bool Checker::run() {
  for (Configuration *c : unit.configs)
    for (VarDecl *g : c->globals)
      allGlobals.push_back(g);
  for (VarDecl *g : unit.globals)
    allGlobals.push_back(g);
  for (TypeDecl *td : unit.types) {
    for (TypeDecl *other : unit.types) {
      if (other == td)
        break;
      if (sameName(other->name, td->name)) {
        error(td->loc, "type '" + td->name + "' is declared twice");
        break;
      }
    }
    if (elementaryType(td->name))
      error(td->loc, "'" + td->name + "' is an elementary type name");
    resolveNamed(td->name, td->loc);
  }
  for (size_t i = 0; i < unit.pous.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (sameName(unit.pous[i]->name, unit.pous[j]->name) &&
          !unit.pous[j]->isLibrary) {
        error(unit.pous[i]->loc,
              "'" + unit.pous[i]->name + "' is declared twice");
        break;
      }
  current = nullptr;
  declareVars(allGlobals, nullptr);
  for (Configuration *c : unit.configs)
    for (VarDecl *g : c->globals)
      checkInitializer(g->typeSyntax ? g->typeSyntax->init : nullptr, g->type);
  for (Pou *p : unit.pous) {
    current = p;
    declareVars(p->vars, p);
    if (p->kind == PouKind::Function) {
      p->resultType = resolve(p->resultSyntax, p->name);
      VarDecl *rv = unit.make<VarDecl>();
      rv->name = p->name;
      rv->loc = p->loc;
      rv->section = VarSection::Output;
      rv->type = p->resultType;
      rv->owner = p;
      p->resultVar = rv;
    }
  }
  for (auto &[k, t] : named)
    indexEnum(t);
  for (VarDecl *g : allGlobals)
    indexEnum(g->type);
  for (Pou *p : unit.pous)
    for (VarDecl *v : p->vars)
      indexEnum(v->type);
  for (Pou *p : unit.pous)
    checkPou(p);
  for (Configuration *c : unit.configs) {
    current = nullptr;
    for (ProgramInstance &pi : c->programs) {
      Pou *p = unit.findPou(pi.typeName);
      if (!p || p->kind != PouKind::Program) {
        error(pi.typeLoc, "'" + pi.typeName + "' is not a program");
        continue;
      }
      checkProgramArgs(pi, p);
      bool found = pi.task.empty();
      for (Task &t : c->tasks)
        found |= sameName(t.name, pi.task);
      if (!found)
        error(pi.loc, "unknown task '" + pi.task + "'");
    }
    for (Task &t : c->tasks)
      if (t.interval && expr(t.interval) &&
          t.interval->type->kind != PTypeKind::Time)
        error(t.interval->loc, "a task INTERVAL must be a TIME");
  }
  return !diag.hadError();
}

void Checker::checkPou(Pou *p) {
  current = p;
  for (VarDecl *v : p->vars) {
    if (v->section == VarSection::External) {
      bool found = false;
      for (VarDecl *g : allGlobals)
        found |= sameName(g->name, v->name);
      if (!found)
        error(v->loc, "no global variable '" + v->name +
                          "' for this VAR_EXTERNAL declaration");
      continue;
    }
    if (v->typeSyntax)
      checkInitializer(v->typeSyntax->init, v->type);
    if (v->edge &&
        (p->kind != PouKind::FunctionBlock || v->section != VarSection::Input ||
         (v->type && v->type->kind != PTypeKind::Bool)))
      error(v->loc, Twine(v->edge == 'R' ? "R_EDGE" : "F_EDGE") +
                        " is allowed only on BOOL inputs of function blocks");
    if (v->type && v->type->kind == PTypeKind::FunctionBlock &&
        v->type->fb == p)
      error(v->loc, "function block '" + p->name + "' contains itself");
    if (p->kind == PouKind::Function && v->type &&
        v->type->kind == PTypeKind::FunctionBlock)
      error(v->loc, "a function cannot hold a function block instance "
                    "(functions have no memory)");
  }
  loopDepth = 0;
  stmts(p->body);
}

void Checker::stmts(StmtList &list) {
  for (Stmt *s : list)
    stmt(s);
}

void Checker::stmt(Stmt *s) {
  switch (s->kind) {
  case StmtKind::Assign: {
    if (s->target->kind == ExprKind::Name) {
      VarDecl *v = lookupVar(s->target->name);
      if (v && v->inferType && !v->type) {
        const PType *vt = expr(s->value);
        if (!vt)
          return;
        vt = baseOf(vt);
        v->type = vt->kind == PTypeKind::AnyInt ? elementaryType("DINT") : vt;
      }
    }
    const PType *t = lvalue(s->target);
    // An enumerator several types share takes the target's type.
    expectedEnum = t && t->kind == PTypeKind::Enum ? t : nullptr;
    const PType *vt = expr(s->value);
    expectedEnum = nullptr;
    if (vt && t)
      assignable(t, s->value, s->loc, "assignment");
    return;
  }
  case StmtKind::Call:
    call(s->value, true);
    return;
  case StmtKind::If:
    for (auto &[cond, body] : s->arms) {
      if (const PType *t = expr(cond); t && t->kind != PTypeKind::Bool)
        error(cond->loc, "condition must be BOOL, not " + t->str());
      stmts(body);
    }
    stmts(s->elseBody);
    return;
  case StmtKind::Case: {
    const PType *sel = expr(s->value);
    if (sel && !sel->isInteger() && sel->kind != PTypeKind::Enum) {
      error(s->value->loc, "CASE selector must be an integer or an "
                           "enumeration, not " +
                               sel->str());
      sel = nullptr;
    }
    for (auto &arm : s->caseArms) {
      for (auto &l : arm.labels)
        for (Expr *b : {l.lo, l.hi}) {
          if (!b)
            continue;
          expectedEnum = sel && sel->kind == PTypeKind::Enum ? sel : nullptr;
          const PType *lt = expr(b);
          expectedEnum = nullptr;
          int64_t v;
          if (lt && sel && sel->kind == PTypeKind::Enum) {
            if (lt != sel && baseOf(lt) != sel)
              error(b->loc, "CASE label of type " + lt->str() +
                                " for a selector of type " + sel->str());
          } else if (lt && !constInt(b, v)) {
            error(b->loc, "CASE label must be a constant");
          }
        }
      stmts(arm.body);
    }
    stmts(s->elseBody);
    return;
  }
  case StmtKind::For: {
    const PType *t = lvalue(s->target);
    if (t && !t->isInteger())
      error(s->target->loc, "FOR variable must be an integer");
    for (Expr *e : {s->from, s->to, s->by})
      if (e && expr(e) && t)
        assignable(t, e, e->loc, "FOR bound");
    ++loopDepth;
    stmts(s->body);
    --loopDepth;
    return;
  }
  case StmtKind::While:
  case StmtKind::Repeat:
    if (const PType *t = expr(s->value); t && t->kind != PTypeKind::Bool)
      error(s->value->loc, "condition must be BOOL, not " + t->str());
    ++loopDepth;
    stmts(s->body);
    --loopDepth;
    return;
  case StmtKind::Exit:
  case StmtKind::Continue:
    if (!loopDepth)
      error(s->loc, Twine(s->kind == StmtKind::Exit ? "EXIT" : "CONTINUE") +
                        " outside a loop");
    return;
  case StmtKind::Return:
    return;
  }
}

bool Checker::assignable(const PType *to, Expr *from, SMLoc at,
                         const Twine &what) {
  const PType *ft = from ? from->type : nullptr;
  if (!to || !ft)
    return true; // already reported
  const PType *tb = baseOf(to), *fb = baseOf(ft);
  auto mismatch = [&] {
    error(at, "type mismatch in " + what + ": cannot assign " + ft->str() +
                  " to " + to->str());
    return false;
  };
  switch (tb->kind) {
  case PTypeKind::Bool:
    if (fb->kind == PTypeKind::Bool)
      return true;
    // `x := 1` for a BOOL is common IEC practice for BOOL#1.
    if (fb->kind == PTypeKind::AnyInt && from->kind == ExprKind::IntLit &&
        (from->intValue == 0 || from->intValue == 1))
      return true;
    return mismatch();
  case PTypeKind::Int: {
    if (fb->kind == PTypeKind::AnyInt) {
      int64_t v;
      if (constInt(from, v) && (v < to->lo || v > to->hi)) {
        error(at, "value " + Twine(v) + " is out of range for " + to->str());
        return false;
      }
      return true;
    }
    if (fb->kind != PTypeKind::Int)
      return mismatch();
    if (fb == tb || to->isSubrange)
      return true;
    bool widening = fb->width < tb->width && (tb->isSigned || !fb->isSigned);
    bool sameWidth = fb->width == tb->width &&
                     (fb->isSigned == tb->isSigned || fb->isBits || tb->isBits);
    if (widening || sameWidth)
      return true;
    error(at, "type mismatch in " + what + ": " + ft->str() +
                  " does not "
                  "convert implicitly to " +
                  to->str() + " (use " + fb->str() + "_TO_" + tb->str() + ")");
    return false;
  }
  case PTypeKind::Real:
    if (fb->kind == PTypeKind::Real || fb->isInteger())
      return true;
    return mismatch();
  default:
    if (tb->kind == fb->kind &&
        (tb == fb ||
         (tb->kind != PTypeKind::Enum && tb->kind != PTypeKind::Struct &&
          tb->kind != PTypeKind::Array &&
          tb->kind != PTypeKind::FunctionBlock) ||
         (!tb->name.empty() && tb->name == fb->name)))
      return true;
    return mismatch();
  }
}

const PType *Checker::commonNumeric(const PType *a, const PType *b, Expr *e) {
  a = baseOf(a);
  b = baseOf(b);
  if (a->kind == PTypeKind::AnyInt)
    return b;
  if (b->kind == PTypeKind::AnyInt)
    return a;
  if (a == b)
    return a;
  if (a->kind == PTypeKind::Int && b->kind == PTypeKind::Int) {
    const PType *wide = a->width >= b->width ? a : b;
    const PType *narrow = wide == a ? b : a;
    if (wide->width > narrow->width && (wide->isSigned || !narrow->isSigned))
      return wide;
    if (wide->width == narrow->width &&
        (wide->isSigned == narrow->isSigned || wide->isBits || narrow->isBits))
      return wide;
    error(e->loc, "operands of '" + spelling(e->op) +
                      "' have incompatible "
                      "types " +
                      a->str() + " and " + b->str());
    return nullptr;
  }
  if (a->kind == PTypeKind::Real || b->kind == PTypeKind::Real) {
    if ((a->kind == PTypeKind::Real || a->isInteger()) &&
        (b->kind == PTypeKind::Real || b->isInteger()))
      return a->kind == PTypeKind::Real ? a : b;
  }
  error(e->loc, "operands of '" + spelling(e->op) +
                    "' have incompatible "
                    "types " +
                    a->str() + " and " + b->str());
  return nullptr;
}

const PType *Checker::lvalue(Expr *e) {
  const PType *t = expr(e);
  if (!t)
    return nullptr;
  Expr *root = e;
  while (root->kind != ExprKind::Name && root->base())
    root = root->base();
  if (root->kind != ExprKind::Name || !root->var) {
    error(e->loc, "cannot assign to this expression");
    return nullptr;
  }
  VarDecl *v = root->var;
  if (v->constant) {
    error(e->loc, "assignment to constant '" + v->name + "'");
    return nullptr;
  }
  if (v->area() == 'I') {
    error(e->loc, "assignment to input '" + v->name + "' (located at " +
                      v->location + ")");
    return nullptr;
  }
  if (v->section == VarSection::Input && v->owner &&
      v->owner->kind == PouKind::Program && root == e) {
    error(e->loc, "assignment to input '" + v->name + "' of program '" +
                      v->owner->name + "'");
    return nullptr;
  }
  // `fb.Q := x` writes an instance's output from outside.
  if (e->kind == ExprKind::Field && e->base()->type &&
      e->base()->type->kind == PTypeKind::FunctionBlock && e->var &&
      e->var->section == VarSection::Output) {
    error(e->loc,
          "assignment to output '" + e->name + "' of function block instance");
    return nullptr;
  }
  return t;
}

const PType *Checker::expr(Expr *e) {
  if (!e)
    return nullptr;
  const PType *t = nullptr;
  switch (e->kind) {
  case ExprKind::IntLit:
    if (!e->typeName.empty()) {
      t = elementaryType(e->typeName);
      if (!t) {
        // `Color#3`? Not IEC.
        error(e->loc, "unknown type '" + e->typeName + "' in typed literal");
        return nullptr;
      }
      if (t->kind == PTypeKind::Int &&
          (e->intValue < t->lo || e->intValue > t->hi) && !t->isBits) {
        error(e->loc, "value " + Twine(e->intValue) + " is out of range for " +
                          t->str());
        return nullptr;
      }
      if (t->kind == PTypeKind::Bool && e->intValue != 0 && e->intValue != 1) {
        error(e->loc, "BOOL literal must be 0 or 1");
        return nullptr;
      }
    } else {
      t = anyIntType();
    }
    break;
  case ExprKind::RealLit:
    t = elementaryType(e->typeName.empty() ? "LREAL" : e->typeName);
    if (!t || t->kind != PTypeKind::Real) {
      error(e->loc, "a real number cannot be a " + e->typeName);
      return nullptr;
    }
    break;
  case ExprKind::BoolLit:
    t = boolType();
    break;
  case ExprKind::TimeLit:
    t = elementaryType("TIME");
    break;
  case ExprKind::DateLit:
    t = elementaryType("DATE");
    break;
  case ExprKind::StringLit:
    t = elementaryType("STRING");
    break;
  case ExprKind::EnumLit: {
    const PType *et = resolveNamed(e->typeName, e->loc);
    if (!et)
      return nullptr;
    if (et->kind != PTypeKind::Enum) {
      error(e->loc, "'" + e->typeName + "' is not an enumerated type");
      return nullptr;
    }
    for (size_t i = 0; i < et->enumerators.size(); ++i)
      if (sameName(et->enumerators[i], e->name))
        e->enumValue = int64_t(i);
    if (e->enumValue < 0) {
      error(e->loc, "'" + e->typeName + "' has no value '" + e->name + "'");
      return nullptr;
    }
    t = et;
    break;
  }
  case ExprKind::Name: {
    if (e->name[0] == '%') {
      // A direct address used without a declaration: an input, output or
      // memory bit/word of the program.
      for (VarDecl *v : current ? current->vars : std::vector<VarDecl *>{})
        if (sameName(v->location, e->name))
          e->var = v;
      for (VarDecl *g : allGlobals)
        if (!e->var && sameName(g->location, e->name))
          e->var = g;
      if (!e->var && current && current->kind == PouKind::Program) {
        // IEC lets a program use %IX0.1 without declaring it: an implicit
        // variable of the size the address names, located there.
        StringRef addr(e->name);
        char size = addr.size() > 2 ? char(std::toupper(addr[2])) : 'X';
        const char *typeName = size == 'B'   ? "BYTE"
                               : size == 'W' ? "WORD"
                               : size == 'D' ? "DWORD"
                               : size == 'L' ? "LWORD"
                                             : "BOOL";
        VarDecl *v = unit.make<VarDecl>();
        v->name = e->name;
        v->loc = e->loc;
        v->location = e->name;
        v->owner = current;
        v->type = elementaryType(typeName);
        current->vars.push_back(v);
        e->var = v;
      }
      if (!e->var) {
        error(e->loc, "direct address " + e->name +
                          " is not declared (declare it with AT)");
        return nullptr;
      }
      t = e->var->type;
      break;
    }
    if (VarDecl *v = lookupVar(e->name)) {
      e->var = v;
      t = v->type;
      break;
    }
    if (VarDecl *v = enEno(current, e->name)) {
      e->var = v;
      t = v->type;
      break;
    }
    if (current && current->resultVar && sameName(current->name, e->name)) {
      e->var = current->resultVar;
      t = current->resultType;
      break;
    }
    const PType *et = nullptr;
    int64_t ev = lookupEnumerator(e->name, et);
    if (ev == -2 && expectedEnum)
      for (size_t i = 0; i < expectedEnum->enumerators.size(); ++i)
        if (sameName(expectedEnum->enumerators[i], e->name)) {
          ev = int64_t(i);
          et = expectedEnum;
        }
    if (ev == -2) {
      error(e->loc, "'" + e->name +
                        "' names a value of several enumerated "
                        "types; write TYPE#" +
                        e->name);
      return nullptr;
    }
    if (ev >= 0) {
      e->enumValue = ev;
      t = et;
      break;
    }
    error(e->loc, "unknown variable '" + e->name + "'");
    return nullptr;
  }
  case ExprKind::Field: {
    const PType *bt = expr(e->base());
    if (!bt)
      return nullptr;
    if (bt->kind == PTypeKind::Struct) {
      for (VarDecl *f : bt->fields)
        if (sameName(f->name, e->name)) {
          e->var = f;
          t = f->type;
        }
      if (!t) {
        error(e->loc, "'" + bt->str() + "' has no field '" + e->name + "'");
        return nullptr;
      }
      break;
    }
    if (bt->kind == PTypeKind::FunctionBlock) {
      VarDecl *m = bt->fb->find(e->name);
      if (!m)
        m = enEno(bt->fb, e->name);
      if (!m || (m->section != VarSection::Input &&
                 m->section != VarSection::Output &&
                 m->section != VarSection::InOut)) {
        error(e->loc, "'" + e->name + "' is not an input or output of " +
                          "function block " + bt->fb->name);
        return nullptr;
      }
      e->var = m;
      t = m->type;
      break;
    }
    error(e->loc, "'.'" + Twine(" applied to a value of type ") + bt->str());
    return nullptr;
  }
  case ExprKind::BitAccess: {
    const PType *bt = expr(e->base());
    if (!bt)
      return nullptr;
    const PType *b = baseOf(bt);
    if (b->kind != PTypeKind::Int) {
      error(e->loc, "bit access on a value of type " + bt->str());
      return nullptr;
    }
    if (e->intValue < 0 || e->intValue >= int64_t(b->width)) {
      error(e->loc,
            "bit " + Twine(e->intValue) + " does not exist in " + b->str());
      return nullptr;
    }
    t = boolType();
    break;
  }
  case ExprKind::Index: {
    const PType *bt = expr(e->base());
    if (!bt)
      return nullptr;
    if (bt->kind != PTypeKind::Array) {
      error(e->loc, "indexing a value of type " + bt->str());
      return nullptr;
    }
    if (e->operands.size() - 1 != bt->dims.size()) {
      error(e->loc, "array has " + Twine(bt->dims.size()) +
                        " dimension(s), indexed with " +
                        Twine(e->operands.size() - 1));
      return nullptr;
    }
    for (size_t i = 1; i < e->operands.size(); ++i) {
      const PType *it = expr(e->operands[i]);
      if (it && !baseOf(it)->isInteger()) {
        error(e->operands[i]->loc, "array index must be an integer");
        return nullptr;
      }
    }
    t = bt->elem;
    break;
  }
  case ExprKind::Deref:
    error(e->loc, "dereference is not supported");
    return nullptr;
  case ExprKind::Unary: {
    const PType *a = expr(e->operands[0]);
    if (!a)
      return nullptr;
    const PType *b = baseOf(a);
    if (e->op == Op::Not) {
      if (!b->isAnyBit() && !(b->kind == PTypeKind::Int) &&
          b->kind != PTypeKind::AnyInt) {
        error(e->loc, "NOT applied to " + a->str());
        return nullptr;
      }
      t = b;
    } else {
      if (!b->isInteger() && b->kind != PTypeKind::Time &&
          b->kind != PTypeKind::Real) {
        error(e->loc, "'" + spelling(e->op) + "' applied to " + a->str());
        return nullptr;
      }
      if (e->op == Op::Neg && b->kind == PTypeKind::Int && !b->isSigned) {
        error(e->loc, "negation of unsigned " + a->str());
        return nullptr;
      }
      t = b;
    }
    break;
  }
  case ExprKind::Binary: {
    const PType *a = expr(e->operands[0]);
    const PType *b = expr(e->operands[1]);
    if (!a || !b)
      return nullptr;
    const PType *ab = baseOf(a), *bb = baseOf(b);
    switch (e->op) {
    case Op::And:
    case Op::Or:
    case Op::Xor:
    case Op::AndThen:
    case Op::OrElse:
      if (ab->kind == PTypeKind::Bool && bb->kind == PTypeKind::Bool) {
        t = boolType();
        break;
      }
      if (e->op == Op::AndThen || e->op == Op::OrElse) {
        error(e->loc, spelling(e->op) + " needs BOOL operands");
        return nullptr;
      }
      if (ab->isInteger() && bb->isInteger()) {
        t = commonNumeric(a, b, e);
        break;
      }
      error(e->loc, "operands of " + spelling(e->op) +
                        " must both be BOOL "
                        "or both bit strings, "
                        "not " +
                        a->str() + " and " + b->str());
      return nullptr;
    case Op::Eq:
    case Op::Ne:
    case Op::Lt:
    case Op::Le:
    case Op::Gt:
    case Op::Ge: {
      bool ok = false;
      if ((ab->isInteger() || ab->kind == PTypeKind::Real) &&
          (bb->isInteger() || bb->kind == PTypeKind::Real))
        ok = commonNumeric(a, b, e) != nullptr;
      else if (ab->kind == bb->kind &&
               (ab->kind == PTypeKind::Bool || ab->kind == PTypeKind::Time ||
                ab->kind == PTypeKind::String || ab->kind == PTypeKind::Date))
        ok = true;
      else if (ab->kind == PTypeKind::Enum && ab == bb)
        ok = true;
      if (!ok) {
        error(e->loc, "cannot compare " + a->str() + " with " + b->str());
        return nullptr;
      }
      t = boolType();
      break;
    }
    case Op::Add:
    case Op::Sub:
    case Op::Mul:
    case Op::Div:
    case Op::Mod:
      if (ab->kind == PTypeKind::Time || bb->kind == PTypeKind::Time) {
        bool ok = false;
        if (e->op == Op::Add || e->op == Op::Sub)
          ok = ab->kind == PTypeKind::Time && bb->kind == PTypeKind::Time;
        else if (e->op == Op::Mul)
          ok = (ab->kind == PTypeKind::Time && bb->isInteger()) ||
               (bb->kind == PTypeKind::Time && ab->isInteger());
        else if (e->op == Op::Div)
          ok = ab->kind == PTypeKind::Time && bb->isInteger();
        if (!ok) {
          error(e->loc, "'" + spelling(e->op) + "' on " + a->str() + " and " +
                            b->str());
          return nullptr;
        }
        t = elementaryType("TIME");
        break;
      }
      if ((ab->isInteger() || ab->kind == PTypeKind::Real) &&
          (bb->isInteger() || bb->kind == PTypeKind::Real)) {
        if (e->op == Op::Mod &&
            (ab->kind == PTypeKind::Real || bb->kind == PTypeKind::Real)) {
          error(e->loc, "MOD needs integer operands");
          return nullptr;
        }
        t = commonNumeric(a, b, e);
        if (!t)
          return nullptr;
        break;
      }
      error(e->loc,
            "'" + spelling(e->op) + "' on " + a->str() + " and " + b->str());
      return nullptr;
    case Op::Pow:
      if ((ab->isInteger() || ab->kind == PTypeKind::Real) &&
          (bb->isInteger() || bb->kind == PTypeKind::Real)) {
        t = elementaryType("LREAL");
        break;
      }
      error(e->loc, "'**' on " + a->str() + " and " + b->str());
      return nullptr;
    default:
      return nullptr;
    }
    break;
  }
  case ExprKind::Call:
    t = call(e, false);
    if (!t)
      return nullptr;
    break;
  }
  e->type = t;
  return t;
}

void Checker::functionArgs(Expr *e, Pou *fn) {
  std::vector<VarDecl *> params;
  for (VarDecl *v : fn->vars)
    if (v->section == VarSection::Input || v->section == VarSection::InOut ||
        v->section == VarSection::Output)
      params.push_back(v);
  size_t positional = 0;
  for (CallArg &a : e->args) {
    VarDecl *p = nullptr;
    if (a.name.empty()) {
      // Positional arguments bind the inputs (and in-outs) in order.
      while (positional < params.size() &&
             params[positional]->section == VarSection::Output)
        ++positional;
      if (positional >= params.size()) {
        error(a.loc, "too many arguments for '" + fn->name + "'");
        return;
      }
      p = params[positional++];
    } else {
      p = fn->find(a.name);
      if (!p)
        p = enEno(fn, a.name);
      if (!p ||
          (p->section != VarSection::Input && p->section != VarSection::InOut &&
           p->section != VarSection::Output)) {
        // Through an instance, say its type: `PT c` on a CTU named c.
        error(a.loc, (e->var ? "'" + e->name + "' (" + fn->name + ")"
                             : "'" + fn->name + "'") +
                         " has no parameter '" + a.name + "'");
        return;
      }
    }
    if (a.isOutput != (p->section == VarSection::Output)) {
      error(a.loc, a.isOutput
                       ? "'=>' binds outputs; '" + p->name + "' is a " +
                             spelling(p->section)
                       : "output '" + p->name + "' must be bound with '=>'");
      return;
    }
    if (a.isOutput || p->section == VarSection::InOut) {
      const PType *t = lvalue(a.value);
      if (t && p->type &&
          (p->section == VarSection::InOut
               ? baseOf(t) != baseOf(p->type) &&
                     !(t->kind == p->type->kind && t->kind != PTypeKind::Int)
               : false)) {
        error(a.loc, "VAR_IN_OUT '" + p->name + "' of type " + p->type->str() +
                         " bound to a " + t->str());
        return;
      }
      if (a.isOutput && t && p->type) {
        Expr probe(ExprKind::Name, a.loc);
        probe.type = p->type;
        assignable(t, &probe, a.loc, "output '" + p->name + "'");
      }
    } else if (expr(a.value)) {
      assignable(p->type, a.value, a.loc, "argument '" + p->name + "'");
    }
    a.name = p->name; // canonical spelling for the lowering
  }
  for (VarDecl *p : params)
    if (p->section == VarSection::InOut) {
      bool given = false;
      for (CallArg &a : e->args)
        given |= sameName(a.name, p->name);
      if (!given)
        error(e->loc, "VAR_IN_OUT '" + p->name + "' of '" + fn->name +
                          "' must be given");
    }
}

/// Puts the named inputs of a standard function call in parameter order
/// (IEC names: IN; IN1..INn; MN, IN, MX for LIMIT; G, IN0, IN1 for SEL;
/// K, IN0..INn for MUX; IN, N for shifts). All arguments are named or none.
bool Checker::orderStdArgs(Expr *e, StdFn fn) {
  size_t named = 0;
  for (CallArg &a : e->args)
    named += !a.name.empty();
  if (named == 0)
    return true;
  if (named != e->args.size()) {
    error(e->loc, "'" + e->name + "': give all arguments by name or none");
    return false;
  }
  auto position = [&](StringRef n) -> int {
    std::string u = n.upper();
    StringRef up(u);
    unsigned k;
    switch (fn) {
    case StdFn::Limit:
      return up == "MN" ? 0 : up == "IN" ? 1 : up == "MX" ? 2 : -1;
    case StdFn::Sel:
      return up == "G" ? 0 : up == "IN0" ? 1 : up == "IN1" ? 2 : -1;
    case StdFn::Mux:
      if (up == "K")
        return 0;
      return up.consume_front("IN") && !up.getAsInteger(10, k) ? int(k) + 1
                                                               : -1;
    case StdFn::Shl:
    case StdFn::Shr:
    case StdFn::Rol:
    case StdFn::Ror:
      return up == "IN" ? 0 : up == "N" ? 1 : -1;
    default:
      if (up == "IN")
        return 0;
      return up.consume_front("IN") && !up.getAsInteger(10, k) && k >= 1
                 ? int(k) - 1
                 : -1;
    }
  };
  std::vector<CallArg> ordered(e->args.size());
  std::vector<bool> filled(e->args.size(), false);
  for (CallArg &a : e->args) {
    int p = position(a.name);
    if (p < 0 || size_t(p) >= ordered.size() || filled[p]) {
      error(a.loc, "'" + e->name + "' has no parameter '" + a.name + "' here");
      return false;
    }
    ordered[p] = a;
    filled[p] = true;
  }
  e->args = std::move(ordered);
  return true;
}

static const char *withArticle(VarSection s) {
  switch (s) {
  case VarSection::Input:
    return "an input";
  case VarSection::Output:
    return "an output";
  case VarSection::InOut:
    return "an in-out parameter";
  default:
    return "a local variable";
  }
}

/// Holds a graphical block against the type it calls: the type it is drawn
/// as must be the one its instance is declared with, and each pin must be a
/// parameter of that type in the group it is drawn in.
bool Checker::drawnAsDeclared(Expr *e, Pou *type) {
  const DrawnBlock &d = *e->drawn;
  if (!d.instanceName.empty() && !sameName(d.typeName, type->name)) {
    error(e->loc, "block '" + d.instanceName + "' is drawn as " + d.typeName +
                      " but declared " + type->name);
    return false;
  }
  std::string block = d.instanceName.empty() ? "block " + type->name
                                             : "block '" + d.instanceName +
                                                   "' (" + type->name + ")";
  for (const DrawnPin &pin : d.pins) {
    VarDecl *p = type->find(pin.name);
    if (!p)
      p = enEno(type, pin.name);
    // A function's result leaves through the output pin OUT.
    if (!p && type->kind == PouKind::Function && pin.name.size() == 3 &&
        sameName(pin.name, "OUT") && pin.drawnAs == VarSection::Output)
      continue;
    if (!p ||
        (p->section != VarSection::Input && p->section != VarSection::Output &&
         p->section != VarSection::InOut)) {
      error(pin.loc, block + " has no parameter '" + pin.name + "'");
      return false;
    }
    if (p->section != pin.drawnAs) {
      error(pin.loc, block + ": '" + p->name + "' is " +
                         withArticle(p->section) + ", drawn as " +
                         withArticle(pin.drawnAs));
      return false;
    }
  }
  return true;
}

const PType *Checker::call(Expr *e, bool asStatement) {
  // An FB instance call (statement only).
  if (VarDecl *v = lookupVar(e->name)) {
    if (!v->type)
      return nullptr;
    if (v->type->kind != PTypeKind::FunctionBlock) {
      error(e->loc, "'" + e->name + "' is a variable of type " +
                        v->type->str() + ", not a function block instance");
      return nullptr;
    }
    if (!asStatement) {
      error(e->loc, "function block instance '" + e->name +
                        "' cannot be called inside an expression");
      return nullptr;
    }
    e->var = v;
    if (e->drawn && !drawnAsDeclared(e, v->type->fb))
      return nullptr;
    functionArgs(e, v->type->fb);
    return voidType();
  }
  if (e->drawn && !e->drawn->instanceName.empty()) {
    error(e->loc, "block '" + e->drawn->instanceName + "' (" +
                      e->drawn->typeName + "): no variable '" +
                      e->drawn->instanceName + "' is declared");
    return nullptr;
  }
  if (Pou *p = unit.findPou(e->name)) {
    if (p->kind != PouKind::Function) {
      if (e->drawn)
        error(e->loc, noInstanceMessage(e->name));
      else
        error(e->loc, "'" + e->name + "' is a " + spelling(p->kind) +
                          "; only functions and function block instances "
                          "can be called");
      return nullptr;
    }
    if (p == current) {
      error(e->loc, "recursive call of function '" + p->name + "'");
      return nullptr;
    }
    e->callee = p;
    if (e->drawn && !drawnAsDeclared(e, p))
      return nullptr;
    functionArgs(e, p);
    return p->resultType;
  }
  StdFnInfo info = lookupStdFunction(e->name);
  if (info.fn == StdFn::None) {
    error(e->loc, "unknown function '" + e->name + "'");
    return nullptr;
  }
  if (!orderStdArgs(e, info.fn))
    return nullptr;
  std::vector<const PType *> types;
  for (CallArg &a : e->args) {
    if (a.isOutput) {
      error(a.loc, "standard function '" + e->name + "' has no outputs");
      return nullptr;
    }
    const PType *t = expr(a.value);
    if (!t)
      return nullptr;
    types.push_back(t);
  }
  auto arity = [&](size_t lo, size_t hi) {
    if (types.size() < lo || types.size() > hi) {
      error(e->loc, "'" + e->name + "' takes " +
                        (lo == hi ? Twine(lo) : Twine(lo) + " or more") +
                        " argument(s), given " + Twine(types.size()));
      return false;
    }
    return true;
  };
  auto numericOf = [&](size_t from) -> const PType * {
    const PType *t = types[from];
    for (size_t i = from + 1; i < types.size() && t; ++i) {
      Expr probe(ExprKind::Binary, e->loc);
      probe.op = Op::Add;
      if (baseOf(t)->kind == PTypeKind::Time &&
          baseOf(types[i])->kind == PTypeKind::Time)
        continue;
      if (baseOf(t)->kind == PTypeKind::Bool &&
          baseOf(types[i])->kind == PTypeKind::Bool)
        continue;
      if (baseOf(t)->kind == PTypeKind::Enum && baseOf(types[i]) == baseOf(t))
        continue;
      t = commonNumeric(t, types[i], &probe);
    }
    return t ? baseOf(t) : nullptr;
  };
  e->callee = nullptr;
  switch (info.fn) {
  case StdFn::Abs:
  case StdFn::Move:
    if (!arity(1, 1))
      return nullptr;
    return baseOf(types[0]);
  case StdFn::Min:
  case StdFn::Max:
  case StdFn::Add:
  case StdFn::Mul:
    if (!arity(2, 64))
      return nullptr;
    return numericOf(0);
  case StdFn::Sub:
  case StdFn::Div:
  case StdFn::Mod:
    if (!arity(2, 2))
      return nullptr;
    return numericOf(0);
  case StdFn::Limit:
    if (!arity(3, 3))
      return nullptr;
    return numericOf(0);
  case StdFn::Sel:
    if (!arity(3, 3))
      return nullptr;
    if (baseOf(types[0])->kind != PTypeKind::Bool) {
      error(e->args[0].loc, "SEL selector G must be BOOL");
      return nullptr;
    }
    return numericOf(1);
  case StdFn::Mux:
    if (!arity(2, 64))
      return nullptr;
    if (!baseOf(types[0])->isInteger()) {
      error(e->args[0].loc, "MUX selector K must be an integer");
      return nullptr;
    }
    return numericOf(1);
  case StdFn::And:
  case StdFn::Or:
  case StdFn::Xor:
    if (!arity(2, 64))
      return nullptr;
    for (const PType *t : types)
      if (!baseOf(t)->isAnyBit() && !baseOf(t)->isInteger()) {
        error(e->loc, "'" + e->name + "' needs BOOL or bit-string inputs");
        return nullptr;
      }
    return numericOf(0);
  case StdFn::Not:
    if (!arity(1, 1))
      return nullptr;
    return baseOf(types[0]);
  case StdFn::Shl:
  case StdFn::Shr:
  case StdFn::Rol:
  case StdFn::Ror:
    if (!arity(2, 2))
      return nullptr;
    if (baseOf(types[0])->kind != PTypeKind::Int ||
        !baseOf(types[1])->isInteger()) {
      error(e->loc, "'" + e->name + "' shifts a bit string by an integer");
      return nullptr;
    }
    return baseOf(types[0]);
  case StdFn::Gt:
  case StdFn::Ge:
  case StdFn::Eq:
  case StdFn::Le:
  case StdFn::Lt:
    if (!arity(2, 64) || !numericOf(0))
      return nullptr;
    return boolType();
  case StdFn::Ne:
    if (!arity(2, 2) || !numericOf(0))
      return nullptr;
    return boolType();
  case StdFn::Convert: {
    if (!arity(1, 1))
      return nullptr;
    const PType *src = baseOf(types[0]);
    if (info.from && src->kind != PTypeKind::AnyInt && src != info.from &&
        !(src->kind == info.from->kind && src->kind != PTypeKind::Int)) {
      error(e->args[0].loc, "'" + e->name + "' converts from " +
                                info.from->str() + ", given " + src->str());
      return nullptr;
    }
    return info.to;
  }
  case StdFn::RealMath:
    return elementaryType("LREAL");
  case StdFn::StringOp:
    return elementaryType("STRING");
  case StdFn::Refused:
    error(e->loc, "'" + e->name +
                      "' is not supported (BCD conversions are "
                      "refused)");
    return nullptr;
  case StdFn::None:
    break;
  }
  return nullptr;
}

bool plc::checkUnit(Unit &unit, DiagEngine &diag) {
  Checker c(unit, diag);
  return c.run();
}
