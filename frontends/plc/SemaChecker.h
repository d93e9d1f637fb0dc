//===- SemaChecker.h - the PLC checker's shared state -----------*- C++ -*-===//
//
// Internal to frontends/plc: the Checker that resolves names and types of
// a PLC unit, shared by the files that implement it by construct family —
// Sema.cpp (declarations, POUs, the entry point), SemaStmts.cpp
// (statements, assignability), SemaExprs.cpp (expressions), SemaCalls.cpp
// (calls of functions and function blocks); SemaTypes.cpp has the
// elementary types and standard functions. Sema.h is the API.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_SEMACHECKER_H
#define NETLIFT_FRONTENDS_PLC_SEMACHECKER_H

#include "frontends/plc/Sema.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSwitch.h"

#include <map>
#include <set>

namespace netlift::plc::detail {

using llvm::SMLoc;
using llvm::StringRef;
using llvm::Twine;

// The types every check needs (SemaTypes.cpp).
const PType *anyIntType();
const PType *voidType();
const PType *boolType();
/// Strips a subrange to its elementary type.
const PType *baseOf(const PType *t);
std::vector<std::string> elementaryTypeNames();

class Checker {
public:
  Checker(Unit &u, DiagEngine &d, const CheckOptions &o)
      : unit(u), diag(d), options(o) {}
  bool run();

private:
  void error(SMLoc at, const Twine &msg) { diag.error(at, msg); }

  // Types.
  const PType *resolve(TypeSyntax *ts, StringRef ownerName);
  const PType *resolveNamed(StringRef name, SMLoc at);
  bool constInt(Expr *e, int64_t &v);
  /// Reports a literal past 2^63 - 1 (see Expr::beyondInt64) that meets a
  /// type other than ULINT or LWORD; false when it did.
  bool literalFits(Expr *e, const PType *to, SMLoc at);
  /// STRING[len] or WSTRING[len], one per length.
  const PType *stringType(uint64_t len, bool wide);
  std::map<std::pair<uint32_t, bool>, const PType *> stringTypes;
  void checkInitializer(Initializer *init, const PType *t);
  void reshapeRowMajor(Initializer *init, const PType *t, size_t dim);
  /// The flat lists inside a structure member's initial value cut into
  /// rows (its values are checked where the structure is used).
  void reshapeMember(Initializer *init, const PType *t);

  // References (SemaReferences.cpp).
  const PType *resolveReference(TypeSyntax *ts, StringRef ownerName);
  /// Gives the references waiting for the named type `key` their target.
  void completeReferences(StringRef key, const PType *resolved);
  std::vector<std::pair<PType *, std::string>> pendingTargets;
  /// REF, ADR, __ISVALIDREF (and __NEW, refused): the result's type, null
  /// after an error; nullopt when `e` calls none of them.
  std::optional<const PType *> referenceCall(Expr *e, bool asStatement);
  /// `__QUERYINTERFACE(itf, other)` (CODESYS, TwinCAT): BOOL; sets
  /// `other` to the instance `itf` designates when its block implements
  /// `other`'s interface, to NULL otherwise.
  const PType *queryInterface(Expr *e);
  /// `ANY`, `ANY_NUM`, ... when `ts` names a generic type (and the
  /// program declares no type of that name), else empty.
  std::string genericTypeName(const TypeSyntax *ts);
  /// The argument `a` of the ANY input `p`: checked against the generic,
  /// and made the address of its value (SemaReferences.cpp).
  void anyArgument(CallArg &a, VarDecl *p);
  unsigned anyTemps = 0;
  /// MEMCPY, MEMMOVE, MEMSET, MEMCMP over places of one type, a constant
  /// number of whole elements (stored in `e->intValue`).
  const PType *memoryCall(Expr *e, bool asStatement);
  /// Is `bytes` written as a whole number of elements of `size` bytes (a
  /// constant multiple, or a product with one)?
  bool wholeElements(Expr *bytes, int64_t size);
  /// MEMCPY/MEMMOVE(ADR(x), ADR(y), n) between places of different types:
  /// n bytes of y's layout copied into x's, leaf by leaf (marked "IMAGE",
  /// n in `intValue`). Nullopt when it is no such copy (then memoryCall
  /// goes on); null after an error.
  std::optional<const PType *> imageCopy(Expr *e, Expr *dst, Expr *src,
                                         Expr *count, bool asStatement);
  const PType *derefType(Expr *e);
  /// Is `name` a library netlift models (Standard, Tc2_Standard,
  /// Tc2_System, Tc2_Utilities, Tc2_Math, Tc2_MC2) used as a namespace
  /// (`Tc2_Math.LTRUNC`), not a name the program declares?
  bool libraryNamespace(StringRef name);
  /// A variable of one of SVGHMI's HMI_<T> types, which Beremiz's web HMI
  /// may write between scans: shared outside (a program's or a global),
  /// else refused.
  void hmiVariable(VarDecl *v, Pou *owner);
  /// A structure type's `{attribute 'pack_mode' := 'n'}`, if given (an
  /// invalid one is reported).
  std::optional<unsigned> packMode(TypeDecl *td);
  /// `REF(place)`, unchecked: how REF= and a REFERENCE TO input take
  /// their place.
  Expr *addressCall(Expr *place);
  /// A REFERENCE TO read or written is its target: `e` becomes `e^`.
  const PType *implicitDeref(Expr *e, const PType *t);
  /// The expression whose REFERENCE TO is meant itself (REF='s target,
  /// __ISVALIDREF's argument), not dereferenced.
  Expr *keepReference = nullptr;
  /// `e` checked with keepReference set (as an lvalue when `asTarget`).
  const PType *referenceItself(Expr *e, bool asTarget);
  /// The references implicitDeref put under a `^` (checked again, they
  /// stay references).
  std::set<Expr *> implicitlyDereferenced;
  bool referenceAssignable(const PType *to, Expr *from, SMLoc at,
                           const Twine &what);
  bool comparableReferences(const PType *a, const PType *b, Expr *e);
  /// A pointer met as a number (its address: `dw := ptr`, `ptr < end`):
  /// refused by name, true when reported.
  bool addressAsNumber(const PType *a, const PType *b, SMLoc at);
  /// Is `x` a value of the character type `c` (a CHAR of the same width,
  /// or a literal of one character, which is then typed `c`)?
  bool charValue(const PType *c, Expr *x);
  /// `p + n`, `n + p`, `p - n` on a POINTER TO T, n a whole number of T's
  /// (a multiple of SIZEOF(T)): the pointer's type, or null after an error.
  const PType *pointerArithmetic(Expr *e, const PType *a, const PType *b);
  /// `p < q` (and <=, >, >=) or `p - q` on two POINTER TOs of one element
  /// type (ADR(arr) taken as its first element's): true when they are.
  /// `what` says what is done with them, for the refusal.
  bool pointerPair(Expr *e, StringRef what);
  /// `p[i]` on a POINTER TO T (CODESYS): rewritten to (p + i * SIZEOF(T))^;
  /// T's type, or null after an error.
  const PType *pointerIndex(Expr *e, const PType *pointer);
  /// ADR(arr) where a pointer to arr's elements is wanted: ADR(arr[lo]),
  /// as CODESYS's address of an array is its first element's. False when
  /// `e` is no such ADR.
  bool decayToElement(Expr *e, const PType *elem);
  /// ADR(s) of a STRING where a POINTER TO a one-byte type or to an ARRAY
  /// of one is wanted: the bytes s is held in (CODESYS's address of a
  /// string is its first byte's). Marks the call "BYTES".
  bool viewAsBytes(Expr *e, const PType *elem);
  /// ADR(a) of a one-dimensional array where a POINTER TO an array of the
  /// same element type with other bounds is wanted (OSCAT's `POINTER TO
  /// ARRAY[0..32000] OF REAL` over any array of REAL): the pointer's
  /// element i is a's element number i - lo. Marks the call "ELEMENTS".
  bool viewAsElements(Expr *e, const PType *array);
  /// ADR(x) of an integer, bit string or REAL where a POINTER TO another
  /// of these of the same size is wanted (`pt : POINTER TO DWORD; pt :=
  /// ADR(aReal)`): x's bits read as that type. Marks the call "SCALAR".
  bool viewAsScalar(Expr *e, const PType *elem);
  /// Why viewAsScalar did not see a structure or array as its bytes, said
  /// with the type mismatch that follows.
  std::string bytesUnseen;
  /// Marks ADR(x) as one of the views above (`kind`) through a POINTER TO
  /// `elem`; true.
  bool markView(Expr *e, const char *kind, const PType *elem);
  /// `r REF= x` and `r ?= q`.
  void referenceAssign(Stmt *s);

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
  static bool sameArrayType(const PType *a, const PType *b);
  /// The type of `a op b` when a date type takes part (TOD + TIME, DT - DT
  /// ...), null when IEC gives it none.
  const PType *dateArithmetic(Op op, const PType *a, const PType *b);
  void checkProgramArgs(ProgramInstance &pi, Pou *p);
  const PType *commonNumeric(const PType *a, const PType *b, Expr *e);
  VarDecl *lookupVar(StringRef name, bool ofThis = false);
  /// `Enum.Value` and `GVL.variable`: rewrites the Field `e` into what it
  /// names; false when it is an ordinary field access.
  bool qualifiedName(Expr *e);
  /// `inst.M(...)`, `M(...)` on the running instance, `SUPER^.M(...)`,
  /// `SUPER^()` (SemaObjects.cpp).
  const PType *methodCall(Expr *e, bool asStatement);
  /// Does `block` (or a base) have a PROPERTY `name`?
  static bool hasProperty(const Pou *block, StringRef name);
  /// `e` (P, inst.P) reads a PROPERTY: it becomes the GET call.
  const PType *propertyRead(Expr *e, Expr *instance);
  /// `P := v`, `inst.P := v`: the statement becomes the SET call; false
  /// when its target is no property.
  bool propertyWrite(Stmt *s);
  /// An instance of a block with an FB_init: the call run before the first
  /// scan, with the declaration's arguments (`fb : FB_X(n := 1)`), checked
  /// and kept on the declaration (SemaObjects.cpp).
  void initCall(VarDecl *v);
  /// The FB_init call of an instance of `t` declared as `v` with `args`
  /// (null when its block has none, or the arguments are wrong).
  Expr *initCallWith(VarDecl *v, const PType *t, std::vector<CallArg> &args);
  /// A block that IMPLEMENTS interfaces has every method and property they
  /// declare (SemaObjects.cpp).
  void checkImplements(Pou *block);
  /// `x` of an interface type where its instance is meant (`itf.M()`,
  /// `itf.P`): `x^`; other expressions as they are.
  Expr *throughInterface(Expr *x);
  /// `itf := inst`: an instance (of a block implementing the interface)
  /// where an interface is wanted becomes the reference to it; false when
  /// `from` is no such instance.
  bool instanceAsInterface(const PType *to, Expr *from, SMLoc at);
  /// `REF(d)`/`ADR(d)` (or THIS) of an instance of a block derived from
  /// the block `to` designates: a reference to the base (CODESYS, TwinCAT).
  bool addressAsBase(const PType *to, Expr *from);
  /// A reference or pointer to a block derived from the one `to`
  /// designates, as `to` (IEC 61131-3 3rd edition): `from` becomes the
  /// conversion `__UPCAST(from)`.
  bool referenceAsBase(const PType *to, Expr *from);
  /// The function block or program whose instance runs `current`.
  Pou *runningBlock() const {
    return current && current->methodOf ? current->methodOf : current;
  }
  // "; did you mean 'x'?" for an unknown variable, type or function.
  std::string suggestVar(StringRef name);
  std::string suggestType(StringRef name);
  std::string suggestFunction(StringRef name);
  int64_t lookupEnumerator(StringRef name, const PType *&type);
  VarDecl *enEno(Pou *p, StringRef name);
  bool orderStdArgs(Expr *e, StdFn fn);
  /// LEN, LEFT, ... FIND: operands checked, the result's type.
  const PType *stringCall(Expr *e, llvm::ArrayRef<const PType *> types);
  // The enumerated type an ambiguous enumerator resolves to (assignment
  // target, CASE selector), if any.
  const PType *expectedEnum = nullptr;
  void indexEnum(const PType *t);
  // Enumerators by upper-case name: every enumerated type of the unit.
  llvm::StringMap<std::vector<std::pair<const PType *, int64_t>>> enumsByName;
  std::set<const PType *> indexedEnums;

  Unit &unit;
  DiagEngine &diag;
  const CheckOptions &options;
  static bool holdsRefused(TypeSyntax *ts);
  std::map<std::string, const PType *> named; // user types, upper-case key
  std::map<std::string, int> resolving;       // cycle detection
  std::vector<VarDecl *> allGlobals;
  Pou *current = nullptr;
  unsigned loopDepth = 0;

  // Types live as long as the unit: the lowering reads them after Sema.
  PType *make(PTypeKind k) { return unit.make<PType>(PType{k}); }
};

} // namespace netlift::plc::detail

#endif
