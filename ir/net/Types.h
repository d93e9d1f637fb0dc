//===- Types.h - NetIR data types -------------------------------*- C++ -*-===//
//
// The data types of NetIR (bool, integer ranges, enumerations, fixed-width
// PLC integers with a declared overflow behaviour, IEEE-754 `real32` and
// `real64`, bounded strings, clocks, arrays and records) and the hybrid
// `real` type that only exists before discretisation. Every scalar type
// other than the hybrid one is held as a 64-bit word in the interval
// [lo, hi] (bool is 0..1, an enumeration 0..n-1, a float its bit pattern),
// which is what the semantics engine and the state encoding work with; a
// string is held as its length followed by one word per character. Types are
// owned by a TypeTable and compared by pointer after uniquing, except named
// types which are nominal.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_TYPES_H
#define NETLIFT_IR_NET_TYPES_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"
#include "llvm/Support/raw_ostream.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace netlift::net {

enum class TypeKind : uint8_t {
  Bool,
  Range,
  Enum,
  Int,
  Clock,
  Array,
  Record,
  Real,   // hybrid: continuous, removed by `discretise`
  Float,  // real32 / real64: the IEEE values a PLC computes
  String, // string[n] / wstring[n]: bounded character strings
};
enum class Overflow : uint8_t { Error, Wrap };

class Type;

struct Field {
  llvm::StringRef name;
  const Type *type;
};

/// One NetIR type. Constructed only through TypeTable.
class Type {
public:
  TypeKind kind;
  /// Scalar finite types: the value interval. Int: derived from the width.
  int64_t lo = 0, hi = 0;
  /// Int: bit width, signedness and what an out-of-range write does.
  /// Float: 32 or 64; lo..hi is then the range of its bit patterns.
  /// Range variables always report out-of-range writes as errors.
  unsigned width = 0;
  bool isSigned = false;
  Overflow overflow = Overflow::Error;
  /// Named types (`type Color = enum {...}`): the name; empty otherwise.
  llvm::StringRef name;
  /// Enum: enumerators in declaration order (value = position).
  std::vector<llvm::StringRef> enumerators;
  /// Array: element type and index range.
  const Type *elem = nullptr;
  int64_t indexLo = 0, indexHi = -1;
  /// Record: fields in declaration order.
  std::vector<Field> fields;
  /// Real: bounds (may be +-infinity).
  double realLo = 0, realHi = 0;
  /// String: the most characters it holds; `width` is then the bits of a
  /// character (8: string, 16: wstring).
  uint32_t maxLen = 0;

  bool isBool() const { return kind == TypeKind::Bool; }
  bool isReal() const { return kind == TypeKind::Real; }
  bool isClock() const { return kind == TypeKind::Clock; }
  bool isFloat() const { return kind == TypeKind::Float; }
  bool isString() const { return kind == TypeKind::String; }
  bool isWideString() const { return isString() && width == 16; }
  /// The type of constant real expressions (`1.5`, `-2.0 * 3.0`): it takes
  /// the float type of its context, or is hybrid.
  bool isAnyReal() const { return kind == TypeKind::Real && name == "real"; }
  /// Integer-valued scalar (range, PLC int or clock).
  bool isInteger() const {
    return kind == TypeKind::Range || kind == TypeKind::Int ||
           kind == TypeKind::Clock;
  }
  bool isScalar() const {
    return kind != TypeKind::Array && kind != TypeKind::Record &&
           kind != TypeKind::String;
  }
  /// `uint64`: held as its bit pattern (lo..hi is all of int64), so its
  /// operators compute in unsigned 64-bit arithmetic (ScalarOps.h).
  bool isUnsigned64() const {
    return kind == TypeKind::Int && width == 64 && !isSigned;
  }
  /// Not hybrid: a value the semantics engine holds in a state.
  bool isFinite() const { return kind != TypeKind::Real; }
  /// Number of scalar slots in the flattened layout.
  uint64_t numSlots() const;
  /// Index of an enumerator, or -1.
  int enumIndex(llvm::StringRef e) const;
  /// Record field index, or -1.
  int fieldIndex(llvm::StringRef f) const;

  /// Canonical spelling: the name for named types, else the structure.
  void print(llvm::raw_ostream &os) const;
  /// The structure even for a named type (used by `type X = ...`).
  void printStructure(llvm::raw_ostream &os) const;
  std::string str() const;

private:
  friend class TypeTable;
  explicit Type(TypeKind k) : kind(k) {}
};

/// Are values of `from` assignable to a variable of type `to` (statically)?
/// Integers assign to integers (the range is checked when the value is
/// written), a constant real (`real`) to a float, a string to a string of
/// the same character width whatever the lengths (a longer value is cut to
/// the target's length when written), everything else needs the same type.
bool isAssignable(const Type *to, const Type *from);
/// Can the two be compared with == / != ?
bool isComparable(const Type *a, const Type *b);

/// Canonical text of a real number (shortest round-trip form, always with
/// a '.', infinities as inf/-inf).
std::string formatReal(double d);

/// Owns and uniques types. Structural types are uniqued by spelling; named
/// types are unique by name.
class TypeTable {
public:
  TypeTable();
  const Type *getBool() const { return boolType; }
  /// The type of integer literals and integer arithmetic before it is
  /// assigned somewhere: all of int64, printed as `integer`.
  const Type *getInteger() const { return integerType; }
  /// The type of real literals and real arithmetic, printed as `real`.
  const Type *getAnyReal() const { return realType; }
  const Type *getRange(int64_t lo, int64_t hi);
  const Type *getClock(int64_t cap);
  /// PLC integer type, e.g. int16 with wrap. `width` in {8,16,32,64}.
  const Type *getInt(unsigned width, bool isSigned, Overflow ov);
  const Type *getArray(const Type *elem, int64_t lo, int64_t hi);
  const Type *getReal(double lo, double hi);
  /// IEEE-754 binary32 (`real32`) or binary64 (`real64`).
  const Type *getFloat(unsigned width);
  /// `string[maxLen]` (8-bit characters) or `wstring[maxLen]` (16-bit).
  const Type *getString(uint32_t maxLen, bool wide);
  /// Named types: created once per name. Returns null if the name exists.
  Type *createEnum(llvm::StringRef name, std::vector<llvm::StringRef> enums);
  Type *createRecord(llvm::StringRef name, std::vector<Field> fields);
  /// A named alias (`type Level = 0..10;`) is its target: aliases are
  /// transparent. The name is remembered for lookup only.
  bool addAlias(llvm::StringRef name, const Type *target);
  const Type *lookup(llvm::StringRef name) const;
  /// Named types in declaration order, for the printer.
  struct NamedType {
    llvm::StringRef name;
    const Type *type;
    bool isAlias;
    llvm::SMLoc loc;
  };
  std::vector<NamedType> &namedTypes() { return named; }
  const std::vector<NamedType> &namedTypes() const { return named; }

private:
  const Type *intern(std::unique_ptr<Type> t);
  std::vector<std::unique_ptr<Type>> owned;
  llvm::StringMap<const Type *> structural;
  llvm::StringMap<const Type *> byName;
  std::vector<NamedType> named;
  const Type *boolType;
  const Type *integerType;
  const Type *realType;
};

} // namespace netlift::net

#endif
