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
#include "frontends/plc/SemaChecker.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/ScopeExit.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

const PType *Checker::stringType(uint64_t len, bool wide) {
  uint32_t n = uint32_t(std::min<uint64_t>(len, 65535));
  const PType *&t = stringTypes[{n, wide}];
  if (!t) {
    PType *s = make(PTypeKind::String);
    s->name = (wide ? "WSTRING[" : "STRING[") + std::to_string(n) + "]";
    s->width = wide ? 16 : 8;
    s->strLen = n;
    t = s;
  }
  return t;
}

bool Checker::literalFits(Expr *e, const PType *to, SMLoc at) {
  if (!e || !e->beyondInt64 || !to)
    return true;
  to = baseOf(to);
  if (to->kind == PTypeKind::AnyInt ||
      (to->kind == PTypeKind::Int && to->width == 64 && !to->isSigned) ||
      to->kind == PTypeKind::Real)
    return true;
  error(at, "value " + Twine(uint64_t(e->intValue)) + " is out of range for " +
                to->str());
  return false;
}

bool Checker::constInt(Expr *e, int64_t &v) {
  if (!e)
    return false;
  switch (e->kind) {
  case ExprKind::IntLit:
    v = e->intValue;
    return !e->beyondInt64; // not an int64: every use checks literalFits

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
  case ExprKind::Call: {
    // SIZEOF of a type or a variable (TwinCAT sizes arrays by it:
    // ARRAY[1..SIZEOF(_TaskInfo) / SIZEOF(PlcTaskSystemInfo)]).
    if (!sameName(e->name, "SIZEOF") || e->args.size() != 1 ||
        e->args[0].isOutput)
      return false;
    Expr *arg = e->args[0].value;
    // A global qualified by its list (TwinCAT_SystemInfoVarList._TaskInfo).
    VarDecl *qualified = nullptr;
    if (arg->kind == ExprKind::Field && arg->base() &&
        arg->base()->kind == ExprKind::Name)
      for (VarDecl *g : allGlobals)
        if (sameName(g->globalList, arg->base()->name) &&
            sameName(g->name, arg->name))
          qualified = g;
    if (arg->kind != ExprKind::Name && !qualified)
      return false;
    const PType *t = nullptr;
    if (VarDecl *var = qualified ? qualified : lookupVar(arg->name))
      t = var->type         ? var->type
          : var->typeSyntax ? resolve(var->typeSyntax, "")
                            : nullptr;
    else if (elementaryType(arg->name) || unit.findType(arg->name))
      t = resolveNamed(arg->name, arg->loc);
    std::string why;
    std::optional<MemoryLayout> layout =
        t ? memoryLayout(t, why) : std::nullopt;
    if (!layout)
      return false;
    v = int64_t(layout->size);
    return true;
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

std::optional<unsigned> Checker::packMode(TypeDecl *td) {
  for (const Attribute &a : td->attrs) {
    StringRef text(a.text);
    if (!text.consume_front("attribute"))
      continue;
    text = text.trim();
    if (!text.consume_front("'pack_mode'"))
      continue;
    text = text.trim();
    text.consume_front(":=");
    StringRef value = text.trim().trim("'").trim();
    unsigned n;
    if (value.getAsInteger(10, n) ||
        (n != 0 && n != 1 && n != 2 && n != 4 && n != 8)) {
      error(a.loc, "pack_mode '" + value + "' of '" + td->name +
                       "': CODESYS and TwinCAT pack to 0, 1, 2, 4 or 8 bytes");
      return std::nullopt;
    }
    return n;
  }
  return std::nullopt;
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
      if (auto pack = packMode(td); pack && t->kind == PTypeKind::Struct)
        copy->pack = *pack;
      for (const Attribute &a : td->attrs)
        if (t->kind == PTypeKind::Enum &&
            StringRef(a.text).contains("'to_string'"))
          copy->enumNamesAsText = true;
      t = copy;
    }
    named[key] = t;
    td->resolved = t;
    completeReferences(key, t);
    return t;
  }
  if (Pou *p = unit.findPou(name)) {
    if (p->kind == PouKind::FunctionBlock) {
      PType *t = make(PTypeKind::FunctionBlock);
      t->name = p->name;
      t->fb = p;
      named[key] = t;
      if (p->isInterface) {
        // A variable of an interface type designates an instance of a
        // block that implements it: a reference.
        PType *r = make(PTypeKind::Reference);
        r->refKind = RefKind::Interface;
        r->elem = t;
        named[key] = r;
        return r;
      }
      return t;
    }
    error(at, "'" + name + "' is a " + spelling(p->kind) + ", not a type");
    return nullptr;
  }
  // `Tc2_System.T_MaxString`, `Standard.TON`: a name qualified by the
  // library netlift models it from.
  if (auto [lib, rest] = name.split('.');
      !rest.empty() && libraryNamespace(lib)) {
    TypeDecl *td = unit.findType(rest);
    Pou *p = td ? nullptr : unit.findPou(rest);
    if ((td && !td->isLibrary) || (p && !p->isLibrary)) {
      error(at, "'" + name + "' names " + lib + "'s " + rest +
                    ", but the project declares its own '" + rest +
                    "', which replaces netlift's model of the library's");
      return nullptr;
    }
    if (td || p)
      return resolveNamed(rest, at);
  }
  error(at, "unknown type '" + name + "'" + suggestType(name));
  return nullptr;
}

bool Checker::libraryNamespace(StringRef name) {
  for (const char *lib : {"Standard", "__SYSTEM", "Tc2_Standard", "Tc2_System",
                          "Tc2_Utilities", "Tc2_Math", "Tc2_MC2"})
    if (name.equals_insensitive(lib))
      return !lookupVar(name) && !unit.findType(name) && !unit.findPou(name);
  return false;
}

const PType *Checker::resolve(TypeSyntax *ts, StringRef ownerName) {
  if (!ts)
    return nullptr;
  switch (ts->kind) {
  case TypeSyntaxKind::Named:
    // IEC 61131-3: a variable of a derived type without an initial value of
    // its own starts at the one the type's declaration gives (`TYPE Mode :
    // (IDLE, RUN) := RUN; END_TYPE`), through aliases.
    if (!ts->init) {
      StringRef name = ts->name;
      for (int depth = 0; depth < 64 && !ts->init; ++depth) {
        TypeDecl *td = unit.findType(name);
        if (!td || !td->type)
          break;
        ts->init = td->type->init;
        if (td->type->kind != TypeSyntaxKind::Named)
          break;
        name = td->type->name;
      }
    }
    return resolveNamed(ts->name, ts->loc);
  case TypeSyntaxKind::String: {
    const PType *base = elementaryType(ts->name);
    if (!ts->length)
      return base;
    int64_t n;
    if (!constInt(ts->length, n) || n < 1 || n > 65535) {
      error(ts->length->loc,
            "the length of a " + ts->name + " must be a constant in 1..65535");
      return nullptr;
    }
    return stringType(uint64_t(n), base->width == 16);
  }
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
      if (!loE && !hiE) { // ARRAY[*]
        t->anyBounds = true;
        t->dims.push_back({0, 0});
        continue;
      }
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
    bool valued = true; // every value a constant: the type has numbers
    for (auto &ev : ts->enumerators) {
      for (auto &prev : t->enumerators)
        if (sameName(prev, ev.name)) {
          error(ev.loc, "enumerator '" + ev.name + "' appears twice");
          return nullptr;
        }
      t->enumerators.push_back(ev.name);
      int64_t v = t->enumValues.empty() ? 0 : t->enumValues.back() + 1;
      valued &= !ev.value || constInt(ev.value, v);
      t->enumValues.push_back(v);
    }
    // Without numbers (a value computed by a call), an enumerator is never
    // an integer: conversions are refused where they are written.
    const PType *base = elementaryType(ts->name.empty() ? "INT" : ts->name);
    if (valued && base && base->kind == PTypeKind::Int)
      t->enumBase = base;
    else
      t->enumValues.clear();
    t->hi = int64_t(t->enumerators.size()) - 1;
    // Anonymous enumerations are named after the variable or type that
    // declares them.
    t->name = ownerName.str();
    return t;
  }
  case TypeSyntaxKind::Struct: {
    PType *t = make(PTypeKind::Struct);
    t->isUnion = ts->isUnion;
    if (!ts->extends.empty()) {
      // `TYPE B EXTENDS A : STRUCT ... END_STRUCT`: A's fields, then B's.
      const PType *base = resolveNamed(ts->extends, ts->loc);
      if (!base)
        return nullptr;
      if (base->kind != PTypeKind::Struct || base->isUnion != ts->isUnion) {
        error(ts->loc, "'" + ownerName + "' EXTENDS '" + ts->extends +
                           "', which is not a " +
                           (ts->isUnion ? "UNION" : "STRUCT"));
        return nullptr;
      }
      t->fields = base->fields;
    }
    for (VarDecl *f : ts->fields) {
      f->type = resolve(f->typeSyntax, f->name);
      if (!f->type)
        return nullptr;
      reshapeMember(f->typeSyntax ? f->typeSyntax->init : nullptr, f->type);
      // A structure is a value netlift copies whole; an instance is not.
      if (Pou *fb = instanceBlock(f->type)) {
        error(f->loc, "structure member '" + f->name +
                          "' holds a function block instance (" + fb->name +
                          "): declare the instance as a variable of the "
                          "program or block instead");
        return nullptr;
      }
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
  case TypeSyntaxKind::Reference:
    return resolveReference(ts, ownerName);
  case TypeSyntaxKind::Refused:
    error(ts->loc, ts->refused);
    return nullptr;
  }
  return nullptr;
}

void Checker::checkInitializer(Initializer *init, const PType *t) {
  if (!init || !t)
    return;
  switch (init->kind) {
  case Initializer::Value: {
    if (t->kind == PTypeKind::FunctionBlock || t->kind == PTypeKind::Array ||
        t->kind == PTypeKind::Struct) {
      // `arr : ARRAY[1..3] OF INT := 0`? Not IEC; refuse.
      error(init->loc,
            "a single value cannot initialise a value of type " + t->str());
      return;
    }
    // An enumerator shared by several enumerated types means the one of
    // the value initialised, as on the right of an assignment.
    const PType *outer = expectedEnum;
    expectedEnum = t->kind == PTypeKind::Enum ? t : nullptr;
    expr(init->value);
    expectedEnum = outer;
    assignable(t, init->value, init->loc, "initial value");
    return;
  }
  case Initializer::Array:
    if (t->kind != PTypeKind::Array) {
      error(init->loc, "an array initialiser for a value of type " + t->str());
      return;
    }
    if (t->dims.size() > 1) {
      // Rows: nested lists, or one flat list in row-major order (IEC
      // 61131-3), which is cut into rows here.
      reshapeRowMajor(init, t, 0);
      PType *row = make(PTypeKind::Array);
      row->dims.assign(t->dims.begin() + 1, t->dims.end());
      row->elem = t->elem;
      for (auto &[count, inner] : init->elems)
        if (inner)
          checkInitializer(inner, row);
      return;
    }
    for (auto &[count, inner] : init->elems)
      if (inner)
        checkInitializer(inner, t->elem);
    return;
  case Initializer::Struct: {
    if (t->kind != PTypeKind::Struct && t->kind != PTypeKind::FunctionBlock) {
      error(init->loc,
            "a structure initialiser for a value of type " + t->str());
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

/// A flat list initialising dimensions `dim...` of `t` (every element a
/// value, repeats expanded) becomes one nested list per row.
void Checker::reshapeRowMajor(Initializer *init, const PType *t, size_t dim) {
  if (dim + 1 >= t->dims.size())
    return;
  std::vector<Initializer *> flat;
  for (auto &[count, inner] : init->elems) {
    if (!inner || inner->kind == Initializer::Array)
      return; // nested already (or empty): rows as written
    for (int64_t k = 0; k < count; ++k)
      flat.push_back(inner);
  }
  size_t rowSize = 1;
  for (size_t d = dim + 1; d < t->dims.size(); ++d)
    rowSize *= size_t(t->dims[d].second - t->dims[d].first + 1);
  std::vector<std::pair<int64_t, Initializer *>> rows;
  for (size_t i = 0; i < flat.size(); i += rowSize) {
    Initializer *row = unit.make<Initializer>(Initializer::Array, flat[i]->loc);
    for (size_t k = i; k < std::min(flat.size(), i + rowSize); ++k)
      row->elems.push_back({1, flat[k]});
    reshapeRowMajor(row, t, dim + 1);
    rows.push_back({1, row});
  }
  init->elems = std::move(rows);
}

void Checker::reshapeMember(Initializer *init, const PType *t) {
  if (!init || !t)
    return;
  if (init->kind == Initializer::Array && t->kind == PTypeKind::Array) {
    reshapeRowMajor(init, t, 0);
    for (auto &[count, inner] : init->elems)
      if (inner && inner->kind != Initializer::Value)
        reshapeMember(inner,
                      inner->kind == Initializer::Array && t->dims.size() > 1
                          ? nullptr // a row: reshaped above
                          : t->elem);
  } else if (init->kind == Initializer::Struct &&
             t->kind == PTypeKind::Struct) {
    for (auto &[name, inner] : init->fields)
      for (VarDecl *f : t->fields)
        if (sameName(f->name, name))
          reshapeMember(inner, f->type);
  }
}

std::string Checker::genericTypeName(const TypeSyntax *ts) {
  if (!ts || ts->kind != TypeSyntaxKind::Named || unit.findType(ts->name))
    return "";
  for (const char *g :
       {"ANY", "ANY_DERIVED", "ANY_ELEMENTARY", "ANY_MAGNITUDE", "ANY_NUM",
        "ANY_REAL", "ANY_INT", "ANY_SIGNED", "ANY_UNSIGNED", "ANY_DURATION",
        "ANY_BIT", "ANY_CHARS", "ANY_STRING", "ANY_CHAR", "ANY_DATE"})
    if (StringRef(ts->name).equals_insensitive(g))
      return g;
  return "";
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
    if (std::string generic = genericTypeName(v->typeSyntax);
        !generic.empty()) {
      v->anyGeneric = generic;
      if (!owner || owner->kind != PouKind::Function ||
          v->section != VarSection::Input)
        error(v->loc, "'" + v->name + "' is " + generic +
                          ": a generic type is the type of an input of a "
                          "function or method");
      v->type = resolveNamed("AnyType", v->loc);
      continue;
    }
    // A variable sharing its type syntax with the ones before it (`a, b :
    // INT`) shares the resolved type too.
    if (i > 0 && vars[i - 1]->typeSyntax == v->typeSyntax)
      v->type = vars[i - 1]->type;
    else
      v->type = resolve(v->typeSyntax, v->name);
    if (v->type && v->type->kind == PTypeKind::Array && v->type->anyBounds &&
        (v->section != VarSection::InOut || !owner ||
         owner->kind == PouKind::Program))
      error(v->loc, "'" + v->name + "' is " + v->type->str() +
                        ": an array of any bounds is a VAR_IN_OUT of a "
                        "function, function block or method");
  }
}

VarDecl *Checker::lookupVar(StringRef name, bool ofThis) {
  // A method sees its own variables, then its block's (inherited ones
  // included); `THIS^.x` only the block's.
  // (In a block's own body THIS^.x is the body's x.)
  bool ownOnly = ofThis && current && current->methodOf;
  for (Pou *scope :
       {ownOnly ? nullptr : current, current ? current->methodOf : nullptr}) {
    if (!scope)
      continue;
    if (VarDecl *v = scope->find(name)) {
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

std::string Checker::suggestVar(StringRef name) {
  std::vector<std::string> names;
  if (current)
    for (VarDecl *v : current->vars)
      names.push_back(v->name);
  for (VarDecl *g : allGlobals)
    names.push_back(g->name);
  return didYouMean(name, names);
}

std::string Checker::suggestType(StringRef name) {
  std::vector<std::string> names = elementaryTypeNames();
  for (TypeDecl *td : unit.types)
    names.push_back(td->name);
  for (Pou *p : unit.pous)
    if (p->kind == PouKind::FunctionBlock)
      names.push_back(p->name);
  return didYouMean(name, names);
}

std::string Checker::suggestFunction(StringRef name) {
  std::vector<std::string> names;
  for (Pou *p : unit.pous)
    if (p->kind == PouKind::Function)
      names.push_back(p->name);
  for (const char *f :
       {"ABS", "MIN", "MAX", "LIMIT", "SEL", "MUX", "MOVE", "ADD", "SUB",
        "MUL", "DIV", "MOD", "AND",   "OR",  "XOR", "NOT",  "SHL", "SHR",
        "ROL", "ROR", "GT",  "GE",    "EQ",  "LE",  "LT",   "NE"})
    names.push_back(f);
  return didYouMean(name, names);
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
  std::vector<CallArg> kept;
  auto keep = llvm::make_scope_exit([&] { pi.args = std::move(kept); });
  for (CallArg &a : pi.args) {
    kept.push_back(a);
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
      // `IN := %IX0.0`, `OUT => %QX4.0` (IEC 61131-3 Annex F): the
      // variable is located there, as if declared AT the address.
      StringRef addr(a.value->name);
      char area = addr.size() > 1 ? char(std::toupper(addr[1])) : 0;
      if (a.isOutput ? area != 'Q' && area != 'M' : area != 'I') {
        error(a.value->loc, "binding " +
                                Twine(a.isOutput ? "output '" : "input '") +
                                a.name + "' to " + addr +
                                ": an input is bound to an input address "
                                "(%I...), an output to an output or memory "
                                "address (%Q..., %M...)");
        continue;
      }
      if (!v->location.empty() && !sameName(v->location, addr)) {
        error(a.value->loc, "'" + a.name + "' is located at " + v->location +
                                ", bound here to " + addr);
        continue;
      }
      v->location = addr.str();
      kept.pop_back(); // located: nothing is left to pass
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
  resolveInheritance(unit);
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
    // A type holding what netlift refuses is reported where a checked POU
    // uses it; the others are resolved now (their enumerators are names).
    if (!holdsRefused(td->type))
      resolveNamed(td->name, td->loc);
  }
  // Only what the translation reaches is checked; a POU holding a refused
  // construct is reported if it is reached.
  std::vector<Pou *> checked;
  std::vector<Pou *> reached = reachedPous(unit, options.top);
  std::set<Pou *> isReached(reached.begin(), reached.end());
  for (Pou *p : unit.pous) {
    if (p->refusal.empty()) {
      if (isReached.count(p))
        checked.push_back(p);
    } else if (isReached.count(p)) {
      error(p->refusalLoc, p->refusal);
      p->checkFailed = true;
    } else if (options.warnUnusedRefused) {
      diag.warning(p->refusalLoc, p->refusal + " (in '" + p->name +
                                      "', which the translation does not "
                                      "use)");
    }
  }
  for (size_t i = 0; i < unit.pous.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (sameName(unit.pous[i]->name, unit.pous[j]->name) &&
          !unit.pous[j]->isLibrary &&
          unit.pous[i]->methodOf == unit.pous[j]->methodOf &&
          unit.pous[i]->property == unit.pous[j]->property) {
        error(unit.pous[i]->loc,
              "'" + unit.pous[i]->name + "' is declared twice");
        break;
      }
  current = nullptr;
  declareVars(allGlobals, nullptr);
  for (Configuration *c : unit.configs)
    for (VarDecl *g : c->globals)
      checkInitializer(g->typeSyntax ? g->typeSyntax->init : nullptr, g->type);
  for (Pou *p : checked) {
    current = p;
    unsigned errorsBefore = diag.numErrors();
    declareVars(p->vars, p);
    p->checkFailed |= diag.numErrors() != errorsBefore;
    if (p->kind == PouKind::Function && !p->resultSyntax) {
      p->resultType = voidType();
    } else if (p->kind == PouKind::Function) {
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
  for (Pou *p : checked)
    for (VarDecl *v : p->vars)
      indexEnum(v->type);
  // A structure member's initial value, once every enumerator is known
  // (a member initialised to a bare enumerator of another type).
  // (A member a structure inherits is checked once, with its base.)
  current = nullptr;
  std::set<VarDecl *> membersChecked;
  for (auto &[k, t] : named)
    if (t && t->kind == PTypeKind::Struct)
      for (VarDecl *f : t->fields)
        if (f->typeSyntax && f->typeSyntax->init && !f->owner &&
            membersChecked.insert(f).second)
          checkInitializer(f->typeSyntax->init, f->type);
  for (VarDecl *g : allGlobals)
    hmiVariable(g, nullptr);
  for (Pou *p : checked) {
    unsigned errorsBefore = diag.numErrors();
    checkPou(p);
    p->checkFailed |= diag.numErrors() != errorsBefore;
  }
  // A global instance's FB_init, with the arguments of its declaration,
  // once its block is checked.
  current = nullptr;
  for (VarDecl *g : allGlobals)
    if (Pou *fb = g->type ? instanceBlock(g->type) : nullptr;
        g->typeSyntax && fb && isReached.count(fb))
      initCall(g);
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

void Checker::hmiVariable(VarDecl *v, Pou *owner) {
  TypeSyntax *ts = v->typeSyntax;
  if (!ts || ts->kind != TypeSyntaxKind::Named ||
      !StringRef(ts->name).startswith_insensitive("HMI_"))
    return;
  TypeDecl *td = unit.findType(ts->name);
  if (!td || !td->isLibrary)
    return; // the project's own HMI_ type
  for (const char *node : {"HMI_NODE", "HMI_CLASS", "HMI_LABEL"})
    if (sameName(ts->name, node))
      return;
  if (owner &&
      (owner->kind == PouKind::Function || v->section == VarSection::InOut ||
       v->section == VarSection::Temp)) {
    error(v->loc,
          "'" + v->name + "' of type " + ts->name +
              " may be written by Beremiz's web HMI between scans; "
              "netlift models that for variables that keep their "
              "value between scans, not a " +
              spelling(owner->kind).str() + "'s " +
              (v->section == VarSection::InOut ? "VAR_IN_OUT" : "temporary"));
    return;
  }
  v->sharedOutside = true;
  diag.note(v->loc, "'" + v->name + "' is an " + ts->name +
                        ": Beremiz's web HMI may write it between scans, so "
                        "each scan starts from a value the environment "
                        "chooses (what the program left there included)");
}

void Checker::checkPou(Pou *p) {
  current = p;
  // By index: an initial value's call may add a temporary (anyArgument).
  for (size_t i = 0; i < p->vars.size(); ++i) {
    VarDecl *v = p->vars[i];
    if (v->section == VarSection::External) {
      bool found = false;
      for (VarDecl *g : allGlobals)
        found |= sameName(g->name, v->name);
      if (!found && !v->constant && !options.opaqueRefused && v->type) {
        // Shared with code outside the design (an Arduino sketch, a
        // runtime extension's variable): the environment's, between scans.
        VarDecl *g = unit.make<VarDecl>();
        g->name = v->name;
        g->loc = v->loc;
        g->section = VarSection::Global;
        g->typeSyntax = v->typeSyntax;
        g->type = v->type;
        g->sharedOutside = true;
        unit.globals.push_back(g);
        allGlobals.push_back(g);
        diag.note(v->loc, "no global declares '" + v->name +
                              "': it is taken as shared with code outside "
                              "the design, which may write it between scans "
                              "(declare it VAR_GLOBAL to model it inside)");
        found = true;
      }
      if (!found)
        error(v->loc, "no global variable '" + v->name +
                          "' for this VAR_EXTERNAL declaration");
      continue;
    }
    if (v->typeSyntax)
      checkInitializer(v->typeSyntax->init, v->type);
    hmiVariable(v, p);
    if (v->edge &&
        (p->kind != PouKind::FunctionBlock || v->section != VarSection::Input ||
         (v->type && v->type->kind != PTypeKind::Bool)))
      error(v->loc, Twine(v->edge == 'R' ? "R_EDGE" : "F_EDGE") +
                        " is allowed only on BOOL inputs of function blocks");
    if (v->type && instanceBlock(v->type) == p)
      error(v->loc, "function block '" + p->name + "' contains itself");
    if (v->typeSyntax && v->type)
      initCall(v);
    if (Pou *fb = v->type ? instanceBlock(v->type) : nullptr;
        fb && fb->isAbstract)
      error(v->loc, "'" + fb->name +
                        "' is ABSTRACT: only blocks that EXTEND it have "
                        "instances");
    if (p->kind == PouKind::Function && v->type && instanceBlock(v->type) &&
        v->section != VarSection::InOut)
      error(v->loc, "a function cannot hold a function block instance "
                    "(functions have no memory)");
  }
  if (p->kind == PouKind::FunctionBlock && !p->isInterface)
    checkImplements(p);
  // A block with instances runs every method it has: none may be left
  // ABSTRACT.
  if (p->kind == PouKind::FunctionBlock && !p->isAbstract)
    forEachMethod(p, [&](Pou *m) {
      if (m->isAbstract && findMethod(p, m->name) == m)
        error(p->loc, "'" + p->name +
                          "' does not implement the ABSTRACT "
                          "method '" +
                          m->name + "' of '" + m->methodOf->name + "'");
    });
  loopDepth = 0;
  stmts(p->body);
}

/// Does the type as written hold a construct netlift refuses?
bool Checker::holdsRefused(TypeSyntax *ts) {
  if (!ts)
    return false;
  if (ts->kind == TypeSyntaxKind::Refused)
    return true;
  if (holdsRefused(ts->elem))
    return true;
  for (VarDecl *f : ts->fields)
    if (holdsRefused(f->typeSyntax))
      return true;
  return false;
}

bool plc::checkUnit(Unit &unit, DiagEngine &diag, const CheckOptions &options) {
  Checker c(unit, diag, options);
  return c.run();
}
