//===- Sema.h - names and types of a PLC program ----------------*- C++ -*-===//
//
// The type checker of the PLC model: resolves every type, variable and call
// of a Unit in place (PlcAst.h's "filled in by Sema" fields) and reports
// what IEC 61131-3 forbids with precise errors — unknown names, wrong or
// missing arguments, type mismatches, assignments to inputs and constants,
// EXIT outside a loop. It knows the standard functions and the standard
// function blocks (ST source in frontends/st/StdLib.cpp, added to the unit
// before checking). Whether something can be *modelled* is not its business:
// the lowering (LowerToNet.h) refuses REAL arithmetic, strings and unbounded
// loops.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_SEMA_H
#define NETLIFT_FRONTENDS_PLC_SEMA_H

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

#include <optional>
#include <string>

namespace netlift::plc {

enum class PTypeKind : uint8_t {
  Bool,
  Int,    // SINT..ULINT, BYTE..LWORD (isBits), subranges (isSubrange)
  AnyInt, // an integer literal or constant expression not yet typed
  Time,
  Real,
  String,
  Date, // DATE, TOD, DT and their L forms (see DateKind)
  Enum,
  Array,
  Struct,
  FunctionBlock,
  Reference, // REF_TO, POINTER TO, REFERENCE TO (see RefKind)
  Void,
};

/// Which of the date types a PTypeKind::Date is; all hold nanoseconds
/// (since 1970-01-01 for DATE and DT, since midnight for TOD).
enum class DateKind : uint8_t { None, Date, TimeOfDay, DateAndTime };

struct PType {
  explicit PType(PTypeKind k) : kind(k) {}
  PTypeKind kind;
  std::string name; // IEC spelling or the user type's name
  // Int
  unsigned width = 0;
  bool isSigned = true;
  bool isBits = false;
  bool isSubrange = false;
  int64_t lo = 0, hi = 0;      // Int: the values; Enum: 0..n-1
  const PType *base = nullptr; // Subrange: the elementary type
  // Enum
  std::vector<std::string> enumerators;
  /// Enum: each enumerator's integer value (declared, or one more than the
  /// one before, from 0), and the integer type they are (INT unless the
  /// declaration names one): what CODESYS and TwinCAT read an enumerator
  /// as next to a number.
  std::vector<int64_t> enumValues;
  const PType *enumBase = nullptr;
  /// Enum: `{attribute 'to_string'}` on its declaration: TO_STRING gives
  /// the enumerator's name, not its value.
  bool enumNamesAsText = false;
  // Array: elem and one (lo, hi) per dimension
  const PType *elem = nullptr;
  std::vector<std::pair<int64_t, int64_t>> dims;
  /// Array: ARRAY[*]: a VAR_IN_OUT's, whose bounds are the argument's
  /// (`dims` holds one (0, 0) per dimension).
  bool anyBounds = false;
  // String: the most characters it holds (`width` is then the bits of a
  // character, 8 or 16); 0 for CHAR and WCHAR, single characters.
  uint32_t strLen = 0;
  // Date: which one (`width` is 64 for LDATE, LTOD, LDT, else 32)
  DateKind dateKind = DateKind::None;
  // Struct (a UNION too: its members overlap, LowerUnions.cpp)
  std::vector<VarDecl *> fields;
  bool isUnion = false;
  /// Struct: CODESYS's and TwinCAT's `{attribute 'pack_mode' := 'n'}`:
  /// members aligned to at most n bytes (0 and 1: none); 8, x64's
  /// natural alignment, when not given.
  unsigned pack = 8;
  // FunctionBlock
  Pou *fb = nullptr;
  // Reference: `elem` is the type designated (null for NULL's own type)
  RefKind refKind = RefKind::RefTo;

  bool isInteger() const {
    return kind == PTypeKind::Int || kind == PTypeKind::AnyInt;
  }
  bool isString() const { return kind == PTypeKind::String && strLen > 0; }
  /// CHAR or WCHAR (`width` 8 or 16): one character, held as its code.
  bool isChar() const { return kind == PTypeKind::String && strLen == 0; }
  bool isReference() const { return kind == PTypeKind::Reference; }
  bool isAnyBit() const {
    return kind == PTypeKind::Bool || (kind == PTypeKind::Int && isBits);
  }
  std::string str() const;
};

/// What makes two designated types one for references (REF_TO INT and
/// REF_TO INT(0..9) designate the same storage; ARRAY[1..3] OF INT is the
/// same written anywhere): the lowering numbers storage per key, and Sema
/// lets a reference take another's value only when their keys agree.
std::string referenceKey(const PType *target);

/// The type of NULL: a reference to nothing, assignable to every one.
const PType *nullType();

/// The standard functions of IEC 61131-3 netlift knows by name.
enum class StdFn : uint8_t {
  None,
  Abs,
  Min,
  Max,
  Limit,
  Sel,
  Mux,
  Move,
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  And,
  Or,
  Xor,
  Not,
  Shl,
  Shr,
  Rol,
  Ror,
  Gt,
  Ge,
  Eq,
  Le,
  Lt,
  Ne,
  Convert,  // X_TO_Y and TO_Y between BOOL, integer and bit-string types
  RealMath, // SQRT, SIN, EXPT, TRUNC, ...
  StringOp, // LEN, LEFT, RIGHT, MID, CONCAT, INSERT, DELETE, REPLACE, FIND
  Bcd,      // BCD_TO_INT, WORD_BCD_TO_UINT, INT_TO_BCD, UINT_TO_BCD_WORD
  Clock,    // TIME(), LTIME(): the PLC's clock, chosen by the environment
  Bound,    // LOWER_BOUND, UPPER_BOUND of an array (ARRAY[*]: the argument's)
};

struct StdFnInfo {
  StdFn fn = StdFn::None;
  const PType *to = nullptr;   // Convert: target type
  const PType *from = nullptr; // Convert: declared source (null: any)
  /// Convert: 4diac's TIME_IN_S/MS/US/NS_TO_x count the TIME in this unit
  /// (ns); 0 for the others.
  int64_t unitNs = 0;
  /// Bcd: from an integer to its BCD bits (else from BCD bits); for
  /// INT_TO_BCD, which names no bit string, the context chooses one.
  bool toBcd = false, bitsFromContext = false;
};

StdFnInfo lookupStdFunction(llvm::StringRef name);

/// How CODESYS and TwinCAT lay a value of type `t` out in memory (natural
/// alignment, as C on x86-64: a member sits at a multiple of its
/// alignment, a structure is padded to its largest member's): the bytes
/// and the alignment. None, with `why`, for what has no fixed layout
/// (function block instances).
struct MemoryLayout {
  int64_t size, align;
};
std::optional<MemoryLayout> memoryLayout(const PType *t, std::string &why);
/// Is `place` an element `a[i]` of a one-dimensional array (whose address
/// starts the bytes up to the array's end, for MEMCPY)?
bool arrayElementPlace(Expr *place);
/// Where each field of a structure (not a UNION) with a layout starts.
std::vector<int64_t> fieldOffsets(const PType *t);

/// One scalar of a value in that layout: the fields and indices that reach
/// it, where its bytes start, and its type (BOOL, an integer or bit
/// string, a REAL or a STRING). The bytes no leaf covers are padding.
struct MemoryLeaf {
  struct Step {
    std::string field;          // else an element
    std::vector<int64_t> index; // one per dimension
  };
  std::vector<Step> path;
  int64_t offset = 0, size = 0;
  const PType *type = nullptr;
};
/// The leaves of `t` in offset order; false, with `why`, when a scalar has
/// no byte encoding netlift models (an enumeration, TIME, a date, a
/// reference, an instance, a UNION).
bool memoryLeaves(const PType *t, std::vector<MemoryLeaf> &out,
                  std::string &why);

struct CheckOptions {
  /// The program, program instance or function block translated (--top);
  /// empty: the configuration's programs, else every program.
  std::string top;
  /// Warn about the constructs netlift refuses in POUs nothing translated
  /// uses (-Wunused-refused); they are not errors.
  bool warnUnusedRefused = false;
  /// --opaque=refuse: a VAR_EXTERNAL no global declares is an error rather
  /// than a variable shared with code outside the design.
  bool opaqueRefused = false;
};

/// Checks the POUs the translation reaches from its top (every POU when
/// there is no program and no --top: a library, each of whose POUs that
/// cannot be modelled is reported). Returns false after reporting errors.
bool checkUnit(Unit &unit, DiagEngine &diag, const CheckOptions &options = {});

/// The POUs a translation reaches from its top (see CheckOptions::top), in
/// unit order; every POU when there is no top.
std::vector<Pou *> reachedPous(const Unit &unit, llvm::StringRef top);

/// The block whose instances a variable of type `t` holds: `t`'s own for
/// an instance, the element's for an array of instances (of any depth);
/// null otherwise.
Pou *instanceBlock(const PType *t);

/// The POU a checked call runs: a function, or the type of the instance
/// called by name or through a reference; null for a standard function.
Pou *calledPou(const Expr *call);

/// The PLC type of an elementary type name (BOOL, INT, TIME...), or null.
const PType *elementaryType(llvm::StringRef name);

/// The type of an untyped real literal (`1.5`) and of constant arithmetic on
/// such literals: LREAL, except that next to a REAL it is that REAL (IEC's
/// ANY_REAL literal takes the type its context needs).
const PType *anyRealType();

} // namespace netlift::plc

#endif
