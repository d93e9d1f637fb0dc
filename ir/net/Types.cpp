//===- Types.cpp - NetIR data types ---------------------------------------===//
#include "ir/net/Types.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/raw_ostream.h"

#include <cmath>
#include <fmt/format.h>

using namespace netlift::net;
using llvm::StringRef;

uint64_t Type::numSlots() const {
  switch (kind) {
  case TypeKind::Array:
    return uint64_t(indexHi - indexLo + 1) * elem->numSlots();
  case TypeKind::Record: {
    uint64_t n = 0;
    for (const Field &f : fields)
      n += f.type->numSlots();
    return n;
  }
  case TypeKind::String:
    return uint64_t(maxLen) + 1;
  default:
    return 1;
  }
}

int Type::enumIndex(StringRef e) const {
  for (size_t i = 0; i < enumerators.size(); ++i)
    if (enumerators[i] == e)
      return int(i);
  return -1;
}

int Type::fieldIndex(StringRef f) const {
  for (size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name == f)
      return int(i);
  return -1;
}

std::string netlift::net::formatReal(double d) {
  if (std::isinf(d))
    return d < 0 ? "-inf" : "inf";
  // Shortest text that reads back to the same double; keep it recognisable
  // as a real (100 -> 100.0, 1e+20 -> 1.0e+20).
  std::string s = fmt::format("{}", d);
  if (s.find('.') == std::string::npos) {
    size_t e = s.find_first_of("eE");
    s.insert(e == std::string::npos ? s.size() : e, ".0");
  }
  return s;
}

void Type::printStructure(llvm::raw_ostream &os) const {
  switch (kind) {
  case TypeKind::Bool:
    os << "bool";
    return;
  case TypeKind::Range:
    os << lo << ".." << hi;
    return;
  case TypeKind::Clock:
    os << "clock 0.." << hi;
    return;
  case TypeKind::Int:
    os << (isSigned ? "int" : "uint") << width
       << (overflow == Overflow::Wrap ? " wrap" : " error");
    return;
  case TypeKind::Float:
    os << "real" << width;
    return;
  case TypeKind::String:
    os << (width == 16 ? "wstring[" : "string[") << maxLen << "]";
    return;
  case TypeKind::Real:
    os << "real[" << formatReal(realLo) << ", " << formatReal(realHi) << "]";
    return;
  case TypeKind::Array:
    os << "array[" << indexLo << ".." << indexHi << "] of ";
    elem->print(os);
    return;
  case TypeKind::Enum:
    os << "enum { ";
    llvm::interleave(enumerators, os, ", ");
    os << " }";
    return;
  case TypeKind::Record:
    os << "struct { ";
    for (const Field &f : fields) {
      os << f.name << " : ";
      f.type->print(os);
      os << "; ";
    }
    os << "}";
    return;
  }
}

void Type::print(llvm::raw_ostream &os) const {
  if (!name.empty())
    os << name;
  else
    printStructure(os);
}

std::string Type::str() const {
  std::string s;
  llvm::raw_string_ostream os(s);
  print(os);
  return os.str();
}

bool netlift::net::isAssignable(const Type *to, const Type *from) {
  if (to == from)
    return true;
  // A uint64 holds bit patterns: it takes a uint64 or a constant (checked
  // by the verifier), other integers only through a conversion.
  if (to->isUnsigned64() || from->isUnsigned64())
    return to->isUnsigned64() && from->isUnsigned64();
  if (to->isInteger() && from->isInteger())
    return true;
  if (to->isReal() && (from->isReal() || from->isInteger()))
    return true;
  // A constant real expression takes the float type of its context.
  if (to->isFloat() && from->isAnyReal())
    return true;
  if (to->isString() && from->isString())
    return to->width == from->width;
  return false;
}

bool netlift::net::isComparable(const Type *a, const Type *b) {
  return isAssignable(a, b) || isAssignable(b, a);
}

TypeTable::TypeTable() {
  auto b = std::unique_ptr<Type>(new Type(TypeKind::Bool));
  b->lo = 0;
  b->hi = 1;
  boolType = intern(std::move(b));
  auto i = std::unique_ptr<Type>(new Type(TypeKind::Range));
  i->lo = INT64_MIN;
  i->hi = INT64_MAX;
  i->name = "integer";
  integerType = i.get();
  owned.push_back(std::move(i));
  auto r = std::unique_ptr<Type>(new Type(TypeKind::Real));
  r->realLo = -INFINITY;
  r->realHi = INFINITY;
  r->name = "real";
  realType = r.get();
  owned.push_back(std::move(r));
}

const Type *TypeTable::intern(std::unique_ptr<Type> t) {
  std::string key;
  llvm::raw_string_ostream os(key);
  t->printStructure(os);
  os.flush();
  auto it = structural.find(key);
  if (it != structural.end())
    return it->second;
  const Type *p = t.get();
  owned.push_back(std::move(t));
  structural[key] = p;
  return p;
}

const Type *TypeTable::getRange(int64_t lo, int64_t hi) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Range));
  t->lo = lo;
  t->hi = hi;
  return intern(std::move(t));
}

const Type *TypeTable::getClock(int64_t cap) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Clock));
  t->lo = 0;
  t->hi = cap;
  return intern(std::move(t));
}

const Type *TypeTable::getInt(unsigned width, bool isSigned, Overflow ov) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Int));
  t->width = width;
  t->isSigned = isSigned;
  t->overflow = ov;
  if (isSigned) {
    t->lo = width == 64 ? INT64_MIN : -(int64_t(1) << (width - 1));
    t->hi = width == 64 ? INT64_MAX : (int64_t(1) << (width - 1)) - 1;
  } else if (width == 64) {
    t->lo = INT64_MIN; // bit patterns: 2^63.. read as negative int64
    t->hi = INT64_MAX;
  } else {
    t->lo = 0;
    t->hi = (int64_t(1) << width) - 1;
  }
  return intern(std::move(t));
}

const Type *TypeTable::getArray(const Type *elem, int64_t lo, int64_t hi) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Array));
  t->elem = elem;
  t->indexLo = lo;
  t->indexHi = hi;
  return intern(std::move(t));
}

const Type *TypeTable::getReal(double lo, double hi) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Real));
  t->realLo = lo;
  t->realHi = hi;
  return intern(std::move(t));
}

const Type *TypeTable::getFloat(unsigned width) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Float));
  t->width = width;
  t->lo = width == 32 ? 0 : INT64_MIN;
  t->hi = width == 32 ? int64_t(UINT32_MAX) : INT64_MAX;
  return intern(std::move(t));
}

const Type *TypeTable::getString(uint32_t maxLen, bool wide) {
  auto t = std::unique_ptr<Type>(new Type(TypeKind::String));
  t->maxLen = maxLen;
  t->width = wide ? 16 : 8;
  return intern(std::move(t));
}

Type *TypeTable::createEnum(StringRef name, std::vector<StringRef> enums) {
  if (byName.count(name))
    return nullptr;
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Enum));
  t->name = name;
  t->enumerators = std::move(enums);
  t->lo = 0;
  t->hi = int64_t(t->enumerators.size()) - 1;
  Type *p = t.get();
  owned.push_back(std::move(t));
  byName[name] = p;
  named.push_back({name, p, false, {}});
  return p;
}

Type *TypeTable::createRecord(StringRef name, std::vector<Field> fields) {
  if (byName.count(name))
    return nullptr;
  auto t = std::unique_ptr<Type>(new Type(TypeKind::Record));
  t->name = name;
  t->fields = std::move(fields);
  Type *p = t.get();
  owned.push_back(std::move(t));
  byName[name] = p;
  named.push_back({name, p, false, {}});
  return p;
}

bool TypeTable::addAlias(StringRef name, const Type *target) {
  if (byName.count(name))
    return false;
  byName[name] = target;
  named.push_back({name, target, true, {}});
  return true;
}

const Type *TypeTable::lookup(StringRef name) const {
  auto it = byName.find(name);
  return it == byName.end() ? nullptr : it->second;
}
