//===- SemaTypes.cpp - PLC elementary types and standard functions
//----------===//
#include "frontends/plc/SemaChecker.h"

#include <functional>

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

std::string PType::str() const {
  if (!name.empty())
    return name;
  if (isSubrange && base)
    return base->str() + "(" + std::to_string(lo) + ".." + std::to_string(hi) +
           ")";
  switch (kind) {
  case PTypeKind::AnyInt:
    return "ANY_INT";
  case PTypeKind::Array: {
    std::string r = "ARRAY[";
    for (size_t d = 0; d < dims.size(); ++d)
      r += (d ? "," : "") + (anyBounds ? std::string("*")
                                       : std::to_string(dims[d].first) + ".." +
                                             std::to_string(dims[d].second));
    return r + "] OF " + (elem ? elem->str() : "?");
  }
  case PTypeKind::Enum:
    return "enumeration";
  case PTypeKind::Struct:
    return isUnion ? "UNION" : "STRUCT";
  case PTypeKind::Void:
    return "no value";
  case PTypeKind::Reference:
    if (!elem)
      return "NULL";
    if (refKind == RefKind::Interface)
      return elem->str(); // the interface's name
    return std::string(refKind == RefKind::Pointer     ? "POINTER TO "
                       : refKind == RefKind::Reference ? "REFERENCE TO "
                                                       : "REF_TO ") +
           elem->str();
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
    // CODESYS's integers of the size of an address: 64 bits, the x64
    // target the memory layout assumes (SIZEOF).
    {"__XWORD", PTypeKind::Int, 64, false, true},
    {"__UXINT", PTypeKind::Int, 64, false, false},
    {"__XINT", PTypeKind::Int, 64, true, false},
    {"TIME", PTypeKind::Time, 64, true, false},
    {"LTIME", PTypeKind::Time, 64, true, false},
    {"REAL", PTypeKind::Real, 32, true, false},
    {"LREAL", PTypeKind::Real, 64, true, false},
    {"STRING", PTypeKind::String, 8, false, false},
    {"WSTRING", PTypeKind::String, 16, false, false},
    {"CHAR", PTypeKind::String, 8, false, false},
    {"WCHAR", PTypeKind::String, 16, false, false},
    {"DATE", PTypeKind::Date, 32, false, false},
    {"TOD", PTypeKind::Date, 32, false, false},
    {"TIME_OF_DAY", PTypeKind::Date, 32, false, false},
    {"DT", PTypeKind::Date, 32, false, false},
    {"DATE_AND_TIME", PTypeKind::Date, 32, false, false},
    {"LDATE", PTypeKind::Date, 64, false, false},
    {"LTOD", PTypeKind::Date, 64, false, false},
    {"LTIME_OF_DAY", PTypeKind::Date, 64, false, false},
    {"LDT", PTypeKind::Date, 64, false, false},
    {"LDATE_AND_TIME", PTypeKind::Date, 64, false, false},
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
      // STRING and WSTRING without a length hold 80 characters, as in
      // CODESYS and TwinCAT (IEC 61131-3 leaves the default to the
      // implementation).
      if (e.kind == PTypeKind::String && StringRef(e.name).endswith("STRING"))
        ty->strLen = 80;
      if (e.kind == PTypeKind::Date) {
        StringRef n(e.name);
        ty->dateKind =
            n.contains("TOD") || n.contains("TIME_OF_DAY") ? DateKind::TimeOfDay
            : n.contains("DT") || n.contains("AND_TIME") ? DateKind::DateAndTime
                                                         : DateKind::Date;
      }
    }
    return t;
  }();
  return table;
}

} // namespace

namespace netlift::plc::detail {

const PType *anyIntType() {
  static const PType t{PTypeKind::AnyInt};
  return &t;
}
const PType *voidType() {
  static const PType t{PTypeKind::Void};
  return &t;
}
const PType *boolType() { return elementaryType("BOOL"); }

std::vector<std::string> elementaryTypeNames() {
  std::vector<std::string> names;
  for (const Elementary &e : kElementary)
    names.push_back(e.name);
  return names;
}

const PType *baseOf(const PType *t) {
  return t && t->isSubrange && t->base ? t->base : t;
}

} // namespace netlift::plc::detail

const PType *plc::anyRealType() {
  static const PType t = *elementaryType("LREAL");
  return &t;
}

const PType *plc::elementaryType(StringRef name) {
  auto it = elementaryTable().find(name.upper());
  return it == elementaryTable().end() ? nullptr : &it->second;
}

std::optional<MemoryLayout> plc::memoryLayout(const PType *t,
                                              std::string &why) {
  t = baseOf(t);
  auto alignUp = [](int64_t n, int64_t a) { return (n + a - 1) / a * a; };
  switch (t->kind) {
  case PTypeKind::Bool:
    return MemoryLayout{1, 1};
  case PTypeKind::Int:
  case PTypeKind::Real:
  case PTypeKind::Date:
    return MemoryLayout{t->width / 8, t->width / 8};
  case PTypeKind::Reference: // a 64-bit target (TwinCAT x64, CODESYS x64)
    return MemoryLayout{8, 8};
  case PTypeKind::Time: // TIME 32 bits (ms), LTIME 64 (ns)
    return t->name == "LTIME" ? MemoryLayout{8, 8} : MemoryLayout{4, 4};
  case PTypeKind::String: { // the characters and the terminating zero
    int64_t c = t->width / 8;
    return MemoryLayout{c * (int64_t(t->strLen) + 1), c};
  }
  case PTypeKind::Enum: // an INT unless a base type is given
    return t->base ? memoryLayout(t->base, why) : MemoryLayout{2, 2};
  case PTypeKind::Array: {
    if (t->anyBounds) {
      why = "the size of " + t->str() + " is the size of the array given";
      return std::nullopt;
    }
    auto e = memoryLayout(t->elem, why);
    if (!e)
      return e;
    int64_t n = 1;
    for (auto &[lo, hi] : t->dims)
      n *= hi - lo + 1;
    return MemoryLayout{e->size * n, e->align};
  }
  case PTypeKind::Struct: {
    int64_t size = 0, align = 1;
    int64_t pack = std::max<int64_t>(t->pack, 1);
    for (VarDecl *f : t->fields) {
      auto l = memoryLayout(f->type, why);
      if (!l)
        return l;
      l->align = std::min(l->align, pack);
      align = std::max(align, l->align);
      size = t->isUnion ? std::max(size, l->size)
                        : alignUp(size, l->align) + l->size;
    }
    return MemoryLayout{alignUp(size, align), align};
  }
  default:
    why = "a " + t->str() +
          " has no layout netlift knows (the compiler "
          "decides it)";
    return std::nullopt;
  }
}

std::vector<int64_t> plc::fieldOffsets(const PType *t) {
  std::vector<int64_t> offsets;
  int64_t offset = 0, pack = std::max<int64_t>(t->pack, 1);
  std::string why;
  for (VarDecl *f : t->fields) {
    auto l = memoryLayout(f->type, why);
    int64_t align = std::min(l->align, pack);
    offset = (offset + align - 1) / align * align;
    offsets.push_back(offset);
    offset += l->size;
  }
  return offsets;
}

bool plc::memoryLeaves(const PType *t, std::vector<MemoryLeaf> &out,
                       std::string &why) {
  std::function<bool(const PType *, MemoryLeaf)> walk = [&](const PType *pt,
                                                            MemoryLeaf at) {
    const PType *base = baseOf(pt);
    auto layout = memoryLayout(base, why);
    if (!layout)
      return false;
    switch (base->kind) {
    case PTypeKind::Bool:
    case PTypeKind::Int:
    case PTypeKind::Real:
    case PTypeKind::String:
      if (base->kind == PTypeKind::String && base->width != 8) {
        why = "a " + base->str() + "'s bytes are not modelled";
        return false;
      }
      at.size = layout->size;
      at.type = base;
      out.push_back(std::move(at));
      return true;
    case PTypeKind::Array: {
      auto elem = memoryLayout(base->elem, why);
      // Row-major, the last index fastest.
      std::vector<int64_t> index;
      for (auto &[lo, hi] : base->dims)
        index.push_back(lo);
      for (int64_t k = 0;; ++k) {
        MemoryLeaf inner = at;
        inner.path.push_back({"", index});
        inner.offset += k * elem->size;
        if (!walk(base->elem, inner))
          return false;
        size_t d = index.size();
        while (d > 0 && index[d - 1] == base->dims[d - 1].second) {
          index[d - 1] = base->dims[d - 1].first;
          --d;
        }
        if (d == 0)
          return true;
        ++index[d - 1];
      }
    }
    case PTypeKind::Struct: {
      if (base->isUnion) {
        why = "the bytes of a UNION (" + base->str() + ") are not modelled";
        return false;
      }
      std::vector<int64_t> offsets = fieldOffsets(base);
      for (size_t i = 0; i < base->fields.size(); ++i) {
        MemoryLeaf inner = at;
        inner.path.push_back({base->fields[i]->name, {}});
        inner.offset += offsets[i];
        if (!walk(base->fields[i]->type, inner))
          return false;
      }
      return true;
    }
    default:
      why = "the bytes of a " + base->str() + " are not modelled";
      return false;
    }
  };
  return walk(t, MemoryLeaf{});
}

std::string plc::referenceKey(const PType *t) {
  if (!t)
    return "NULL";
  t = baseOf(t);
  switch (t->kind) {
  case PTypeKind::Array: {
    std::string r = "ARRAY[";
    for (size_t d = 0; d < t->dims.size(); ++d)
      r += (d ? "," : "") + std::to_string(t->dims[d].first) + ".." +
           std::to_string(t->dims[d].second);
    return r + "] OF " + referenceKey(t->elem);
  }
  case PTypeKind::Reference:
    return "REF_TO " + referenceKey(t->elem);
  case PTypeKind::String:
    if (t->isString())
      return (t->width == 16 ? "WSTRING[" : "STRING[") +
             std::to_string(t->strLen) + "]";
    return t->str();
  case PTypeKind::FunctionBlock:
    // Every interface's places are one table: an instance is numbered
    // once whatever interface it is seen through, so an interface
    // reference assigned to one its interface extends keeps its number.
    if (t->fb && t->fb->isInterface)
      return "INTERFACE";
    [[fallthrough]];
  default:
    // Named types are one by name; an anonymous structure or enumeration
    // only with itself.
    if (t->name.empty())
      return t->str() + "@" + std::to_string(reinterpret_cast<uintptr_t>(t));
    return llvm::StringRef(t->name).upper();
  }
}

Pou *plc::instanceBlock(const PType *t) {
  while (t && t->kind == PTypeKind::Array)
    t = t->elem;
  return t && t->kind == PTypeKind::FunctionBlock ? t->fb : nullptr;
}

Pou *plc::calledPou(const Expr *c) {
  if (c->callee)
    return c->callee;
  if (c->var && c->var->type && c->var->type->kind == PTypeKind::FunctionBlock)
    return c->var->type->fb;
  if (!c->operands.empty() && c->operands[0]->type &&
      c->operands[0]->type->kind == PTypeKind::FunctionBlock)
    return c->operands[0]->type->fb;
  return nullptr;
}

const PType *plc::nullType() {
  static const PType t{PTypeKind::Reference};
  return &t;
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
                // CODESYS's and TwinCAT's clock since the PLC started;
                // 4diac's monotonic clock and its date and time.
                .Cases("TIME", "LTIME", "NOW_MONOTONIC", "NOW", StdFn::Clock)
                .Cases("LOWER_BOUND", "UPPER_BOUND", StdFn::Bound)
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
    // BCD_TO_INT and BYTE_BCD_TO_USINT read BCD bits; INT_TO_BCD and
    // UINT_TO_BCD_WORD write them (without a bit-string type named: the
    // one as wide as the integer).
    if (from == "BCD" || from.endswith("_BCD")) {
      const PType *bits =
          from == "BCD" ? nullptr : elementaryType(from.drop_back(4));
      const PType *t = elementaryType(to);
      if (t && t->kind == PTypeKind::Int && (from == "BCD" || bits)) {
        info.fn = StdFn::Bcd;
        info.from = bits;
        info.to = t;
      }
      return info;
    }
    if (to == "BCD" || to.startswith("BCD_")) {
      const PType *f = elementaryType(from);
      if (!f || f->kind != PTypeKind::Int)
        return info;
      const char *wide = f->width <= 8    ? "BYTE"
                         : f->width <= 16 ? "WORD"
                         : f->width <= 32 ? "DWORD"
                                          : "LWORD";
      const PType *bits =
          elementaryType(to == "BCD" ? StringRef(wide) : to.drop_front(4));
      if (bits && bits->kind == PTypeKind::Int && bits->isBits) {
        info.fn = StdFn::Bcd;
        info.toBcd = true;
        info.bitsFromContext = to == "BCD";
        info.from = f;
        info.to = bits;
      }
      return info;
    }
    const PType *f = elementaryType(from), *t = elementaryType(to);
    // 4diac's TIME_IN_MS_TO_LINT and the like: the duration in that unit.
    if (from.consume_front("TIME_IN_")) {
      info.unitNs = llvm::StringSwitch<int64_t>(from)
                        .Case("S", 1000000000)
                        .Case("MS", 1000000)
                        .Case("US", 1000)
                        .Case("NS", 1)
                        .Default(0);
      if (info.unitNs && t &&
          (t->kind == PTypeKind::Int || t->kind == PTypeKind::Real))
        f = elementaryType("TIME");
      else
        info.unitNs = 0;
    }
    if (f && t) {
      info.fn = StdFn::Convert;
      info.from = f;
      info.to = t;
    }
  }
  return info;
}
