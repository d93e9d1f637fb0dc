//===- Lowering.h - the PLC lowering's shared state -------------*- C++ -*-===//
//
// Internal to frontends/plc: the Lowering class that turns a checked PLC
// unit into NetIR, shared by the files that implement it by concept —
// LowerToNet.cpp (time, modules, the entry points), LowerDecls.cpp (types
// and declarations), LowerExprs.cpp (expressions and standard functions),
// LowerCalls.cpp (function and function block calls),
// LowerInstanceArrays.cpp (arrays of instances), LowerStmts.cpp
// (statements and loops), LowerReals.cpp, LowerStrings.cpp and
// LowerDates.cpp and LowerUnions.cpp (the data types that need more than
// integers), LowerEnvironment.cpp (what the environment of the translated
// POU chooses: its aggregate inputs, its VAR_IN_OUTs, the clock). LowerToNet.h
// is the API.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_LOWERING_H
#define NETLIFT_FRONTENDS_PLC_LOWERING_H

#include "frontends/plc/LowerToNet.h"
#include "frontends/plc/Sema.h"

#include "ir/net/Builder.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/SmallPtrSet.h"
#include "llvm/ADT/StringSet.h"

#include <map>
#include <numeric>
#include <optional>
#include <set>

namespace netlift::plc::detail {

/// A subrange's elementary type (SemaTypes.cpp).
const PType *baseOf(const PType *t);

/// Calls `fn` with every index of an array's dimensions, in row-major
/// order (LowerInstanceArrays.cpp).
void forEachIndex(const PType *array,
                  llvm::function_ref<void(llvm::ArrayRef<int64_t>)> fn);

using llvm::SMLoc;
using llvm::StringRef;
using llvm::Twine;
using NExpr = net::Expr;
using NStmt = net::Stmt;
using Sink = std::vector<NStmt *>;
/// A place or value made afresh at each use.
using FreshPlace = std::function<NExpr *()>;

/// Thrown to abandon the translation after the first refusal; caught in
/// lowerToNet. (One refusal per run: later ones would mostly be echoes.)
struct Refusal {};

/// ULINT and LWORD: NetIR's uint64, which integer literals past INT64_MAX
/// and mixed arithmetic need handled apart.
inline bool isUnsigned64(const PType *t) {
  return t && t->kind == PTypeKind::Int && t->width == 64 && !t->isSigned;
}

/// The mask of a partial access `x.%B1` of `width` bits (all ones for 64).
inline int64_t partMask(unsigned width) {
  return width >= 64 ? int64_t(-1) : int64_t((uint64_t(1) << width) - 1);
}

struct Range {
  int64_t lo, hi;
  bool exact; // false: unknown (treat as unbounded)
};

/// The lowering of one POU body invocation: whose names, under which
/// prefix, with which VAR_IN_OUT aliases, and the control flags in force.
struct Frame {
  Pou *pou = nullptr;
  std::string prefix; // "" for the top program, "t1." for an instance
  std::map<VarDecl *, NExpr *> aliases; // VAR_IN_OUT -> caller's lvalue
  /// VAR_IN_OUT -> the argument and the caller's frame it is lowered in
  /// (REF of the parameter is REF of the argument).
  std::map<VarDecl *, std::pair<Expr *, Frame *>> aliasSources;
  /// VAR_IN_OUT of a function block type -> the caller's instance prefix.
  std::map<VarDecl *, std::string> instanceAliases;
  std::string returnFlag; // set when the body has RETURN
  bool external = false;  // program frame: reads of FB members count as
                          // reads from outside the instance
  /// A method's or action's frame: the type of the instance it runs on
  /// and that instance's prefix, under which the block's variables are
  /// (the method's own are under `prefix`, its call site's).
  Pou *self = nullptr;
  std::string selfPrefix;
  /// The prefix `v` is named under in this frame.
  const std::string &prefixOf(const VarDecl *v) const {
    return self && v->owner != pou ? selfPrefix : prefix;
  }
  /// The instance code in this frame runs on (its type and prefix): a
  /// method's, else the block or program whose body this is.
  std::pair<Pou *, std::string> running() const {
    return self ? std::pair(self, selfPrefix) : std::pair(pou, prefix);
  }
};

struct LoopCtx {
  std::string exitFlag, continueFlag;
};

struct InstanceUse {
  unsigned calls = 0;
  std::map<std::string, unsigned> given; // input member -> calls giving it
};

/// A step from a variable to a place a reference designates: an instance's
/// member, a structure's field, or an array's elements (all of them: a
/// family holds every element, numbered in row-major order).
struct RefStep {
  enum Kind : uint8_t { Member, Field, Index } kind = Field;
  std::string name;                              // Member, Field
  std::vector<std::pair<int64_t, int64_t>> dims; // Index
  /// An index into an array of function block instances, whose elements
  /// are instances of their own (flattened under their element paths).
  bool ofInstances = false;
};

/// How a family's places are seen: as themselves, or (the address of a
/// STRING taken as a POINTER TO BYTE or TO ARRAY[lo..] OF BYTE) as the
/// `bytes` bytes the string is held in, terminator included.
struct RefView {
  /// Plain: the place itself. Bytes, ByteArray: a STRING's bytes seen as
  /// BYTEs or as an ARRAY OF BYTE. Elements: an array seen as an array of
  /// the same element type with other bounds.
  /// Scalar: a scalar seen as another scalar of the same size (a REAL's
  /// bits as a DWORD), or as an ARRAY OF BYTE (its bytes, `bytes` of them),
  /// or (`byteSteps`) as BYTEs a POINTER TO BYTE steps through.
  enum Kind : uint8_t {
    Plain,
    Bytes,
    ByteArray,
    Elements,
    Scalar
  } kind = Plain;
  int64_t bytes = 0;   // Bytes, ByteArray: the string's; Elements: elements
  int64_t lo = 0;      // ByteArray, Elements: the viewing array's first index
  int64_t placeLo = 0; // Elements: the first index of the array seen
  const PType *seen = nullptr; // Scalar: the type of the place seen
  bool byteSteps = false;
  /// Places numbered byte by byte (`bytes` per element of the family).
  bool numbersBytes() const { return kind == Bytes || byteSteps; }
  std::string suffix() const {
    return kind == Plain      ? ""
           : kind == Elements ? "#elements"
           : byteSteps        ? "#scalarbytes"
           : kind == Scalar   ? "#scalar"
                              : "#bytes";
  }
};

/// Places of one type a reference may designate, numbered offset ..
/// offset + size - 1: `base` (a NetIR variable) and the steps from it.
struct RefFamily {
  RefView view;
  std::string key; // base and steps, as familyKey spells them
  std::string base;
  /// Set for a function's variable: `base` is its name in the call running
  /// where the reference is dereferenced (Lowering::activeCalls).
  Pou *function = nullptr;
  std::vector<RefStep> steps;
  int64_t offset = 1, size = 1;
  /// A pointer stepped through the family may stand outside its elements
  /// without being dereferenced (C's one past the end, every PLC's loop
  /// `pt := pt + 1` after the last element, `pt - 1` before the first,
  /// `ADR(s) + pos - 1` with pos 0): a family of one contiguous block whose
  /// type a program steps through has four more numbers, none designating
  /// anything: one before its first element and its end (one past the
  /// last), exact, and beyond them one for every address further below
  /// and one for every address further above (see farBelow, farAbove).
  bool hasOutside = false;
  int64_t farBelow() const { return offset - 2; }
  int64_t before() const { return offset - 1; }
  int64_t end() const { return offset + size; }
  int64_t farAbove() const { return offset + size + 1; }
  /// The numbers of its elements and (`withOutside`) of the addresses
  /// outside them.
  int64_t first(bool withOutside = true) const {
    return withOutside && hasOutside ? farBelow() : offset;
  }
  int64_t last(bool withOutside = true) const {
    return withOutside && hasOutside ? farAbove() : offset + size - 1;
  }
  /// Is `k` one of its elements, or (`withOutside`) outside them?
  bool holds(int64_t k, bool withOutside = false) const {
    return k >= first(withOutside) && k <= last(withOutside);
  }
};

/// The places of one designated type (by referenceKey) in one module.
struct RefTable {
  std::vector<RefFamily> families;
  std::map<std::string, size_t> byKey; // base and steps -> family
  int64_t count = 0;
};

struct ClockUse {
  std::string var;    // the clock variable
  std::string member; // the FB input bounding it (PT)
  std::string path;   // the instance path
  int64_t cap = 0;
  bool unbounded = false; // capped by its type only (kUnboundedClockAttribute)
  std::vector<std::string> timeMembers; // TIME members retyped 0..cap
};

class Lowering {
public:
  Lowering(Unit &u, const LowerOptions &o, DiagEngine &d, net::Design &des)
      : unit(u), opts(o), diag(d), design(des), b(des) {}
  bool run();
  bool runEventDriven(std::vector<EventDrivenBlock> &blocks);

private:
  [[noreturn]] void refuse(SMLoc at, const Twine &msg) {
    diag.error(at, msg);
    throw Refusal{};
  }

public:
  // Time: the durations a POU and what it calls write.
  static void collectTimes(Pou *p, std::set<Pou *> &seen,
                           std::vector<int64_t> &ns);
  static void collectTimesExpr(Expr *e, std::set<Pou *> &seen,
                               std::vector<int64_t> &ns);
  static void collectTimesStmts(StmtList &l, std::set<Pou *> &seen,
                                std::vector<int64_t> &ns);

private:
  int64_t ticks(int64_t ns, SMLoc at);

  // Types and declarations.
  const net::Type *netType(const PType *t, SMLoc at, StringRef what);
  /// `v`'s initial value (`init`, else its type's); inside an aggregate
  /// (`at` given) every element is spelt out, defaults included.
  NExpr *initialValue(VarDecl *v, Initializer *init, const PType *t,
                      std::optional<SMLoc> at = std::nullopt);
  /// An array (from dimension `dim` on) or structure initial value.
  NExpr *aggregateValue(VarDecl *v, Initializer *init, const PType *t,
                        size_t dim, SMLoc at);
  NExpr *defaultValue(const PType *t, SMLoc at);
  std::string unique(std::string name);

public:
  static std::string sanitize(StringRef name);

private:
  void declareProgramVar(VarDecl *v);
  // The translated POU's environment (LowerEnvironment.cpp).
  /// An input of an array or structure type, or a VAR_IN_OUT, of the POU
  /// run as a program: the environment chooses each of its scalars at the
  /// start of every scan (`environmentSamples`).
  void declareEnvironmentValue(VarDecl *v, const std::string &name);
  /// One free input port per scalar of a value of type `t` held in the
  /// variable `name` (named `portStem` and the scalar's suffix: `s_a`,
  /// `buf_0`): what copies them in (`samplesOf()`, fresh statements each
  /// time) and sets them back to their defaults (`defaultsOf()`). `what` names
  /// the value in refusals.
  struct ChosenScalars {
    struct Scalar {
      std::string port;
      std::vector<std::pair<std::string, int64_t>> path; // field, else index
      const PType *type = nullptr;
    };
    std::string name;
    SMLoc at;
    std::vector<Scalar> scalars;
  };
  std::vector<NStmt *> samplesOf(const ChosenScalars &c);
  /// The scalar `c` of the chosen value.
  NExpr *scalarOf(const ChosenScalars &chosen, const ChosenScalars::Scalar &c);
  std::vector<NStmt *> defaultsOf(const ChosenScalars &c);
  /// `onlyFields`, when given, keeps the scalars under those fields of a
  /// structure (at any depth) and chooses no other; with `portsWhenRead`
  /// a port is declared where it is first read (freeInputRead).
  ChosenScalars
  chooseScalars(const std::string &name, const std::string &portStem,
                const PType *t, const std::string &what,
                const std::string &shown, SMLoc at,
                const std::vector<std::string> *onlyFields = nullptr,
                bool portsWhenRead = false);
  /// Ports chooseScalars named but declares only when first read: their
  /// types and what messages call them.
  std::map<std::string, std::pair<const PType *, std::string>>
      portsDeclaredWhenRead;
  /// A read of free input `port`, declared here if it is not yet.
  NExpr *freeInputRead(const std::string &port, SMLoc at);
  /// A record the runtime writes before every scan (VarDecl::runtimeRecord,
  /// TwinCAT's `_TaskInfo`): a variable of the scan holding what the
  /// project states, its other fields environment values read where read,
  /// its first-cycle flag set at the start of each scan.
  void declareRuntimeRecord(VarDecl *v, const std::string &name);
  /// GETCURTASKINDEXEX(): 0 in FB_init, else the task's index (1 with one
  /// task; with several, a free input over them).
  NExpr *taskIndex(Expr *call);
  /// Set while FB_init calls are lowered (they run outside any task).
  bool loweringInitCalls = false;
  /// A free input port for a value of type `t` (`shown` names it in
  /// messages and in the range an exploration asks for).
  void addFreeInputPort(const std::string &port, const PType *t,
                        const std::string &shown, SMLoc at);
  std::map<VarDecl *, std::vector<NStmt *>> environmentSamples;
  /// The type of the caller's object a reference input of the POU run as a
  /// program may designate (null when none is modelled: an instance, an
  /// interface, more scalars than the environment chooses). A
  /// one-dimensional array too large to choose whole is modelled by its
  /// first --caller-elements elements: that shorter array's type, which
  /// the reference sees as an array with other bounds (RefView::Elements).
  const PType *callerTarget(VarDecl *v);
  std::map<const PType *, const PType *> callerPrefixes;
  /// That object, `<name>_target`: an output port chosen by the
  /// environment at each scan, as a VAR_IN_OUT of the translated POU is.
  void declareCallerTarget(VarDecl *v, const std::string &name,
                           const PType *elem);
  /// TIME() or LTIME(): the clock, a free input chosen at every scan.
  NExpr *clockReading(Expr *call);
  /// LOWER_BOUND / UPPER_BOUND: a constant, the bounds of the array an
  /// ARRAY[*] is given at this call (LowerInstanceArrays.cpp).
  NExpr *arrayBound(Expr *call, Frame &f);
  /// Their scalars back to defaults at the end of the scan, so that what
  /// the environment chose last is not state.
  std::map<VarDecl *, std::vector<NStmt *>> environmentResets;
  /// Is `v` chosen by the environment scalar by scalar (then it is a
  /// variable of the scan itself, written without a copy)?
  bool isEnvironmentValue(VarDecl *v) const;
  void declareInstance(const std::string &path, Pou *fb, Initializer *init);
  void declareEnvironment(const std::string &path, Pou *fb);
  /// The call of an instance of an environment block: its arguments
  /// evaluated, its outputs read (LowerCalls.cpp).
  void environmentCall(Expr *call, Pou *fb, const std::string &path, Frame &f,
                       Sink &out);
  std::set<std::string> notedEnvironment;
  /// An argument of an environment block or function is not stored, but
  /// the calls computing it run.
  void runArgumentCalls(Expr *value, Frame &f, Sink &out);
  /// `a` gives an address an environment block writes the program's memory
  /// through (Pou::writesThrough): the variable it designates takes free
  /// values (appended to `out`).
  void writeThrough(CallArg &a, Pou *fb, const std::string &path, Frame &f,
                    Sink &out);
  /// A call of a function marked `{netlift environment '...'}`: its result
  /// a free input (LowerEnvironment.cpp).
  NExpr *environmentFunction(Expr *call, Frame &f, Sink &pre);
  std::string staticVar(VarDecl *v, SMLoc at);
  /// A variable of the scan, back at `initial` (the type's initial value
  /// when null) at the end of every scan; an array or structure only with
  /// `local` (a VAR_TEMP or a function's local: the environment's
  /// structures are reset scalar by scalar where they are chosen).
  uint32_t declareTemp(const std::string &name, const PType *t, SMLoc at,
                       NExpr *initial = nullptr, bool local = false);
  std::optional<std::pair<int64_t, int64_t>> inputRange(VarDecl *v);

  /// Picks the tick from the durations `ns` (and the options, or a model
  /// read before) and sets the design's timescale.
  void chooseTick(std::vector<int64_t> ns);

  // References and pointers (LowerReferences.cpp).
  struct ProgramRun;
  struct ReferencePlan {
    std::map<std::string, RefTable> tables; // by referenceKey
  };
  /// The places each reference type can designate in a module of `runs`.
  ReferencePlan planReferences(llvm::ArrayRef<ProgramRun> runs);
  /// The NetIR variables `v` is in each instance of its owner.
  std::vector<std::string>
  placeBases(VarDecl *v,
             const std::map<Pou *, std::vector<std::string>> &instances,
             llvm::ArrayRef<ProgramRun> runs);
  /// The scan-local copy a written program input is read through (also
  /// one of a function block translated as the top, run as a program is).
  std::optional<std::string> inputImageName(const std::string &prefix,
                                            VarDecl *v);
  /// The POUs run as programs in the module being lowered.
  std::set<Pou *> runPous;
  bool runAsProgram(Pou *p) const {
    return p && (p->kind == PouKind::Program || runPous.count(p));
  }
  /// Numbers outside each family a pointer steps through
  /// (RefFamily::hasOutside), renumbering those tables.
  void giveOutsideNumbers(ReferencePlan &plan);
  /// Is the number `k` of a pointer to a type of `table` one of the
  /// numbers for every address beyond a block (RefFamily::farBelow,
  /// farAbove)? Null when the table has none.
  NExpr *farFromBlock(const RefTable &table, NExpr *k, SMLoc at);
  void adoptReferencePlan(ReferencePlan plan);
  /// Variables whose address is taken count as written everywhere.
  void markAddressTaken();
  /// The number of places a reference to `target` may designate in any
  /// module (its NetIR type is 0..that).
  int64_t referenceCount(const PType *target);
  std::string scanVariable(const std::string &stem, const net::Type *type,
                           int64_t init, SMLoc at);
  NExpr *checkedRange(NExpr *v, int64_t lo, int64_t hi, const std::string &what,
                      Sink &pre, SMLoc at);
  NExpr *addressOf(Expr *call, Frame &f, Sink &pre);
  /// REF(r^.f[i]): in the family r designates, the same selection.
  NExpr *addressThroughReference(Expr *call, Frame &f, Sink &pre);
  /// The row-major offset of the element the index selectors choose (a
  /// constant part, and the rest or null), each index checked.
  std::pair<int64_t, NExpr *>
  elementOffset(llvm::ArrayRef<std::pair<Expr *, Frame *>> selectors,
                const std::string &what, Sink &pre, SMLoc at);
  struct DerefTargets {
    Expr *deref = nullptr;
    const RefTable *table = nullptr;
    std::string number; // the reference, checked to be 1..n
    /// A reference known at translation.
    std::optional<int64_t> constant;
    /// The families it may designate here (a function's variables only
    /// while a call of it runs).
    std::vector<const RefFamily *> live;
  };
  /// The family key of a function's variable (one for all its calls).
  static std::string functionPlace(VarDecl *v);
  /// The prefixes of the calls of each function being lowered, innermost
  /// last.
  std::map<Pou *, std::vector<std::string>> activeCalls;
  NExpr *numberOf(const DerefTargets &t, SMLoc at);
  bool throughReference(Expr *e);
  DerefTargets derefTargets(Expr *e, Frame &f, Sink &pre);
  /// A run-time error named `stem` when any of `tests` holds.
  void failWhenAny(llvm::ArrayRef<NExpr *> tests, const std::string &stem,
                   Sink &pre, SMLoc at);
  NExpr *familyPlace(const RefFamily &fam, const DerefTargets &t, Expr *e,
                     Frame &f, Sink &pre);
  NExpr *familyTest(const RefFamily &fam, const DerefTargets &t);
  /// The variable and steps of a family's place (`name` while no step has
  /// made an expression of it; then the expression).
  NExpr *familyRoot(const RefFamily &fam, const DerefTargets &t,
                    std::string &name);
  /// The position `first + i - lo` that the index `i` of an array view
  /// (a STRING's bytes, an array with other bounds) designates, checked at
  /// run time to lie in what is viewed (the error names `what`).
  NExpr *viewedPosition(const RefFamily &fam, const DerefTargets &t,
                        Expr *indexExpr, int64_t first, llvm::StringRef what,
                        Frame &f, Sink &pre);
  /// For a scalar's bytes seen as an array, the bit offset of the byte
  /// `e` (pt^[i]) designates, checked; null for a whole scalar view.
  NExpr *scalarByteShift(const RefFamily &fam, const DerefTargets &t, Expr *e,
                         Frame &f, Sink &pre);
  /// Is the family a structure or an array seen as its bytes
  /// (LowerRecordBytes.cpp)?
  static bool seesRecordBytes(const RefView &view);
  /// The byte a scalar or record view designates, counted from 0, checked
  /// to lie in it; null for a whole scalar view.
  NExpr *scalarBytePosition(const RefFamily &fam, const DerefTargets &t,
                            Expr *e, Frame &f, Sink &pre);
  /// `v`, known to lie in lo..hi, for use several times: itself when a
  /// literal, else a variable of the scan it is copied into first.
  FreshPlace positionValue(NExpr *v, int64_t lo, int64_t hi, Sink &pre,
                           SMLoc at);
  /// Byte `pos` (from 0) of the value of type `t` at `place`, in SIZEOF's
  /// layout: of the scalar holding it, little-endian; padding reads 0.
  NExpr *recordByte(const PType *t, const FreshPlace &place,
                    const FreshPlace &pos, SMLoc at);
  /// Writes `byte` as byte `pos` of the value at `place`, the scalar
  /// holding it keeping its other bytes (padding keeps nothing).
  void storeRecordByte(const PType *t, const FreshPlace &place,
                       const FreshPlace &pos, const FreshPlace &byte, Sink &out,
                       SMLoc at);
  NExpr *bytePosition(const RefFamily &fam, const DerefTargets &t, Expr *e,
                      Frame &f, Sink &pre);
  /// What `e` reads in a family's place (a byte of a string: code()).
  NExpr *familyValue(const RefFamily &fam, const DerefTargets &t, Expr *e,
                     Frame &f, Sink &pre);
  /// `target := value` in a family's place (a byte: with_code()); the
  /// index computations go to `pre`, the store to `out`.
  void familyStore(const RefFamily &fam, const DerefTargets &t, Expr *target,
                   NExpr *value, Expr *valueExpr, Frame &f, Sink &pre,
                   Sink &out, SMLoc at);
  NExpr *readThroughReference(Expr *e, Frame &f, Sink &pre);
  /// `e` as an lvalue when the reference has one possible family; `use`
  /// says where, for the refusal otherwise.
  NExpr *placeThroughReference(Expr *e, Frame &f, Sink &pre, StringRef use);
  void writeThroughReference(Expr *target, NExpr *value, Expr *valueExpr,
                             Frame &f, Sink &out, SMLoc at);
  /// `p + n * SIZEOF(T)` and `p - ...`: the element n further in the array
  /// p points into, or outside it (RefFamily::hasOutside); coming back from
  /// far outside, where its distance is not kept, is a run-time error.
  NExpr *pointerStep(Expr *e, Frame &f, Sink &pre);
  /// How many elements the steps `e` (`p + a - b`, nested) move from the
  /// pointer they start from (`start`, the first that is not a step).
  NExpr *stepElements(Expr *e, Frame &f, Sink &pre, Expr *&start);
  /// `bytes` (Sema checked: a whole number of elements of `size` bytes) as
  /// a number of elements.
  NExpr *elementsIn(Expr *bytes, int64_t size, Frame &f, Sink &pre);
  /// `p < q` (<=, >, >=) and `p - q` (their distance in bytes) on two
  /// pointers into one array, string or variable: numbers compared, as
  /// they follow the addresses there; into different ones (or NULL) a
  /// run-time error, since their order is the linker's.
  NExpr *pointerPairValue(Expr *e, Frame &f, Sink &pre);
  /// MEMCPY, MEMMOVE, MEMSET (statements around nothing) and MEMCMP.
  NExpr *memoryCall(Expr *call, Frame &f, Sink &pre);
  /// MEMCPY, MEMMOVE, MEMSET and MEMCMP of a number of elements known at
  /// run time: a loop over as many as the longest block of the type holds.
  NExpr *memoryLoop(Expr *call, Frame &f, Sink &pre);
  /// An element MEMCMP compares, read through its reference once.
  FreshPlace comparedValue(Expr *element, Frame &f, Sink &pre);
  /// Byte `byte` of the value of type `t`, in memory order.
  NExpr *valueByte(const PType *t, const FreshPlace &value, int64_t byte,
                   SMLoc at);
  /// `(p + offset)^` of type `t` (`p^` without an offset), as Sema types it.
  Expr *elementAt(Expr *p, Expr *offset, const PType *t, SMLoc at);
  /// MEMCPY/MEMMOVE between places of different types (Sema's "IMAGE"):
  /// each target scalar the bytes reach is rebuilt from the source's bytes
  /// in the x64 layout (memoryLeaves), little-endian.
  NExpr *imageCopy(Expr *call, Frame &f, Sink &pre);
  /// The same with a count known only at run time, or from or into
  /// `ADR(a[i])` of a one-dimensional array (the bytes from element i on: a
  /// structure serialised into a buffer at an offset); both sides must
  /// hold the bytes, a run-time error otherwise.
  NExpr *imageCopySpans(Expr *call, Frame &f, Sink &pre);
  /// The place MEMCPY between types reads or writes (`what`), made afresh
  /// at each use; one reached through a reference is refused.
  NExpr *directPlace(Expr *place, StringRef what, Frame &f, Sink &pre);
  /// MEMSET's fill: the low byte of its value.
  NExpr *fillByte(Expr *fill, Frame &f, Sink &pre);
  /// MEMSET of one element (through its reference) with `fill`.
  void fillElement(Expr *element, NExpr *fill, Frame &f, Sink &out);
  /// Each leaf written from its bits, all computed before any is written.
  void storeLeavesTogether(
      llvm::ArrayRef<std::pair<const MemoryLeaf *, NExpr *>> leaves,
      llvm::function_ref<NExpr *(const MemoryLeaf &)> placeOf, Sink &pre,
      SMLoc at);
  /// A field of a structure that may hold byte `pos`: its place, the
  /// position within it, and the test that it holds the byte.
  struct FieldBytes {
    VarDecl *field;
    FreshPlace member, inside, holds;
  };
  std::vector<FieldBytes> fieldsHolding(const PType *t, const FreshPlace &place,
                                        const FreshPlace &pos, SMLoc at);
  /// The place `l` reaches from `root`.
  NExpr *leafPlace(NExpr *root, const MemoryLeaf &l, SMLoc at);
  /// MEMSET(..., 0, ...) of one array or structure: each scalar of the
  /// place `place` designates (a dereference, perhaps selected) set to 0.
  /// MEMSET of a place: every scalar's bytes set to `byte` (0 when null).
  void fillThroughReference(Expr *place, NExpr *byte, Frame &f, Sink &pre,
                            SMLoc at);
  /// A BOOL, integer or REAL of at most 32 bits whose every byte is `byte`.
  NExpr *filledScalar(const PType *t, NExpr *byte, SMLoc at);
  ReferencePlan refPlan;
  /// The prefix of the instance whose variables are being declared (a
  /// reference's initial value REF(x) is numbered in it).
  std::string declaringPrefix;
  /// Where the variable being declared is (an instance's notes point
  /// there).
  SMLoc declaringLoc;
  std::map<std::string, int64_t> refDomain; // by referenceKey, all modules

  // Bodies.
  /// One program of a module: the prefix of its own names ("" when the
  /// module is the program's alone), the scan it runs in, and what its
  /// lowering produces.
  struct ProgramRun {
    Pou *pou = nullptr;
    std::string prefix;
    std::string scan, cycle; // the scan transition and its place
    int64_t period = 1;
    Sink action;
    std::vector<std::pair<std::string, NExpr *>> resets; // end of its scan
    size_t membersBegin = 0, membersEnd = 0;             // its FB members
  };
  /// The globals `program` reads or writes (its body, the FBs and
  /// functions it calls, its instance's arguments), in declaration order.
  std::vector<VarDecl *> globalsUsedBy(Pou *program);
  std::vector<VarDecl *> inDeclarationOrder(const std::set<VarDecl *> &globals);
  /// While one program's declarations or body are lowered: its names'
  /// prefix is in force and end-of-scan resets go to it.
  struct InProgram {
    Lowering &L;
    ProgramRun &run;
    InProgram(Lowering &l, ProgramRun &r) : L(l), run(r) {
      L.currentProgram = r.pou;
      L.programPrefix = r.prefix;
      std::swap(L.resets, r.resets);
    }
    ~InProgram() { std::swap(L.resets, run.resets); }
  };
  void startModule(const std::string &name, SMLoc loc);
  void declareProgram(ProgramRun &run);
  void lowerProgramBody(ProgramRun &run);
  void runInitCalls(ProgramRun &run, Frame &top, Sink &action);
  void initCallsOf(VarDecl *v, const PType *type, const std::string &path,
                   Frame &in, Sink &calls, Expr *given = nullptr);
  /// FB_init of the global instances the programs use: one IF under a flag,
  /// put at the start of every task's scan.
  Sink globalInitCalls(std::vector<ProgramRun> &runs);
  void deadValueResets(ProgramRun &run);
  /// One module holding `runs`; runs with the same scan share it, in
  /// order.
  void lowerPrograms(const std::string &name, SMLoc loc,
                     std::vector<ProgramRun> &runs);
  void capClocks();
  /// Pragmas become `pragma` attributes of what they annotate (see
  /// attachPragmas).
  void keepPragmas(const std::string &target,
                   const std::vector<Attribute> &attrs) {
    for (const Attribute &a : attrs)
      pendingPragmas.push_back({target, &a});
  }
  void attachPragmas();
  std::vector<std::pair<std::string, const Attribute *>> pendingPragmas;
  void lowerEventBlock(EventDrivenBlock &block);
  void body(StmtList &list, Frame &f, Sink &out,
            const std::vector<LoopCtx> &loops);
  void stmt(Stmt *s, Frame &f, Sink &out, const std::vector<LoopCtx> &loops);
  NExpr *expr(Expr *e, Frame &f, Sink &pre);
  NExpr *lvalue(Expr *e, Frame &f, Sink &pre);
  NExpr *varRef(VarDecl *v, Frame &f, SMLoc at);
  /// Each instance's path as the program names it (`MAIN.suites[2].log`),
  /// by its NetIR prefix.
  std::map<std::string, std::string> sourcePaths;
  /// The initial value of `v` when it is a STRING marked
  /// `{attribute 'instance-path'}` (CODESYS, TwinCAT): the path of the
  /// instance it belongs to, `source` under the project; else null.
  NExpr *instancePathValue(VarDecl *v, const std::string &source);
  std::set<VarDecl *> instancePathsNoted;
  // Arrays of function block instances (LowerInstanceArrays.cpp).
  /// The prefix of the element `index` of the instances at `path`.
  static std::string elementPath(const std::string &path,
                                 llvm::ArrayRef<int64_t> index);
  /// The instances a family's place may be when its steps index an array
  /// of instances (LowerReferences.cpp); empty when they do not.
  std::vector<std::string> instanceElementBases(const std::string &base,
                                                llvm::ArrayRef<RefStep> steps,
                                                std::vector<RefStep> &rest);
  /// The instance, or every element of the array of instances, at `path`.
  void declareInstances(const std::string &path, const PType *t,
                        Initializer *init);
  /// Every instance prefix a variable of type `t` at `path` holds.
  static std::vector<std::string> instancePaths(const std::string &path,
                                                const PType *t);
  /// An instance the program may designate: its prefix, and when it is
  /// one of several (chosen at run time), the condition that chooses it.
  struct InstanceChoice {
    NExpr *test;
    std::string path;
  };
  std::vector<InstanceChoice> instanceChoices(Expr *e, Frame &f, Sink &pre);
  /// Does an index in `instance` (an element of an array of instances)
  /// become known only at run time?
  bool chosenAtRunTime(Expr *instance, Frame &f);
  /// The prefix of an instance known at translation.
  std::string instancePath(Expr *e, Frame &f);
  /// One of `bodies`, chosen by `tests` (one per body; the last body is
  /// the else: the choice was checked to be one of them), into `out`; a
  /// single body goes in inline.
  void emitChoice(llvm::ArrayRef<NExpr *> tests, std::vector<Sink> &bodies,
                  Sink &out, SMLoc at);
  /// `value` once into a temporary of `type` (named after `stem`) when it
  /// is more than a literal or a name: stored in several places after.
  NExpr *valueOnce(NExpr *value, const PType *type, const std::string &stem,
                   Sink &out, SMLoc at);
  /// The call of whichever of `choices` is chosen.
  void callChosenInstance(Expr *call, Pou *fb,
                          llvm::ArrayRef<InstanceChoice> choices, Frame &f,
                          Sink &out);
  /// `timers[i](...)`.
  void elementCall(Expr *call, Frame &f, Sink &out);
  /// `timers[i].Q`, an index known only at run time.
  bool memberOfChosenInstance(Expr *e, Frame &f);
  NExpr *chosenMemberRead(Expr *e, Frame &f, Sink &pre);
  void chosenMemberWrite(Stmt *s, NExpr *value, Frame &f, Sink &out);
  void fbCall(Expr *call, Frame &f, Sink &out);
  /// The call `call` of the instance of `fb` at `path`.
  void instanceCall(Expr *call, Pou *fb, const std::string &path, Frame &f,
                    Sink &out);
  /// Reference inputs known to hold a constant while the body of the
  /// call that gave it is lowered (innermost last).
  std::vector<std::pair<std::string, int64_t>> knownConstants;
  /// The variables (and instance members) a reference may designate.
  std::set<std::string> addressTaken;
  /// The place chosen for a VAR_IN_OUT argument that is a dereference of
  /// several possible places, while the call for that place is lowered.
  std::map<Expr *, NExpr *> inOutPlaces;
  /// The same for an instance passed in-out that is chosen at run time.
  std::map<Expr *, std::string> inOutInstances;
  /// `source` (an interface's number) when the instance it designates is
  /// of a block that implements `wanted` (an interface type), else NULL
  /// (`?=` and __QUERYINTERFACE between interfaces).
  NExpr *interfaceQuery(NExpr *source, const PType *wanted, Sink &pre,
                        SMLoc at);
  /// `__UPCAST(r)`: a reference to a derived block renumbered among its
  /// base's places (LowerReferences.cpp).
  NExpr *referenceUpcast(Expr *call, Frame &f, Sink &pre);
  NExpr *queryInterfaceCall(Expr *call, Frame &f, Sink &pre);
  /// The prefix of the instance an in-out argument designates.
  std::string boundInstance(Expr *argument, Frame &f);
  /// A call of `callee` one of whose VAR_IN_OUT arguments may be bound to
  /// one of several places (an element of an array of instances chosen at
  /// run time, a dereference designating several places): `lowerOnce`
  /// lowers the call into the sink given, with that argument bound
  /// (inOutInstances, inOutPlaces), once per place, chosen at run time;
  /// its value (a function's result, null for a block) goes through one
  /// temporary, returned in `value`. False, with nothing lowered, when no
  /// argument needs a choice.
  bool callPerBinding(Expr *call, Pou *callee, Frame &f, Sink &out,
                      llvm::function_ref<NExpr *(Sink &)> lowerOnce,
                      NExpr *&value);
  /// The instances whose bodies are being lowered, outermost first.
  std::vector<std::string> instancesLowering;
  /// `r^(...)`: the call of the instance r designates.
  void callThroughReference(Expr *call, Frame &f, Sink &out);
  void enabledBody(Pou *callee, const std::string &prefix, Expr *call,
                   Frame &nf, Sink &out);
  void noteClockBound(const std::string &member, Expr *value, Frame &f,
                      SMLoc at);
  NExpr *functionCall(Expr *call, Frame &f, Sink &pre);
  /// A method's or action's call: the implementation the instance's type
  /// runs, and the instances it may run on (LowerCalls.cpp).
  struct MethodTarget {
    Pou *impl = nullptr;
    Pou *selfType = nullptr;
    std::vector<NExpr *> tests;        // one per prefix when chosen
    std::vector<std::string> prefixes; // each instance's, with its dot
    /// Through a reference or interface: each instance's type and the
    /// implementation it runs; `mixed` when they differ.
    std::vector<Pou *> selfTypes, impls;
    bool mixed = false;
  };
  MethodTarget methodTarget(Expr *call, Frame &f, Sink &pre);
  /// `call` of `fn` inlined at this call site: a function's, or a method's
  /// on the instances of `target`.
  NExpr *inlineCall(Expr *call, Pou *fn, const MethodTarget &target, Frame &f,
                    Sink &pre);
  /// The ANY input `v` of a call, in the call site's variable `name`: the
  /// address, size and type class of what `a` passes.
  void anyInput(const std::string &name, VarDecl *v, CallArg &a, Frame &f,
                Sink &pre);
  /// `SUPER^()`: the base's body on the running instance.
  void baseBody(Expr *call, Frame &f, Sink &out);
  void atCallSite(llvm::ArrayRef<NStmt *> lowered, SMLoc at);
  NExpr *stdCall(Expr *call, Frame &f, Sink &pre);
  /// A standard function's result, EN aside.
  NExpr *stdValue(Expr *call, Frame &f, Sink &pre);
  /// BCD_TO_x and x_TO_BCD: digits checked (a nibble above 9, a value
  /// beyond the digits, is a run-time error).
  NExpr *bcdConversion(Expr *call, const StdFnInfo &info, NExpr *v, Sink &pre,
                       SMLoc at);
  NExpr *convert(NExpr *v, const PType *from, const PType *to, SMLoc at);
  // REAL and LREAL (LowerReals.cpp).
  const net::Type *floatType(const PType *t);
  /// `v` of PLC type `from` where IEC converts it implicitly to `to`: a
  /// NetIR conversion when a float is involved, else `v`.
  NExpr *coerce(NExpr *v, const PType *from, const PType *to, SMLoc at);
  /// An enumerator's integer value (CODESYS, TwinCAT: an enumeration next
  /// to a number), and back: an integer stored in an enumeration is the
  /// enumerator of that value, another value a run-time error
  /// (LowerExprs.cpp).
  NExpr *enumToInteger(NExpr *v, const PType *t, SMLoc at);
  NExpr *integerToEnum(NExpr *v, const PType *t, Sink &pre, SMLoc at);
  /// The REAL type operands are computed in (the widest typed REAL among
  /// them; anyRealType() for literals only), or null when none is REAL.
  const PType *commonReal(llvm::ArrayRef<Expr *> operands);
  NExpr *realMath(Expr *call, llvm::ArrayRef<NExpr *> args, SMLoc at);
  NExpr *convertReal(NExpr *v, const PType *from, const PType *to, SMLoc at);
  /// An integer of PLC type `from` as a NetIR uint64 (a negative value
  /// wraps modulo 2^64).
  NExpr *asUnsigned64(NExpr *v, const PType *from, SMLoc at);
  /// A TIME (in ticks) counted in `unitNs` units as the integer or REAL
  /// type `to` (4diac's TIME_IN_MS_TO_LINT...).
  NExpr *timeInUnit(NExpr *v, int64_t unitNs, const PType *to, SMLoc at);
  /// The nanoseconds a number converted to or from TIME counts (the
  /// unit's TimeNumbers), noted once per translation.
  int64_t timeNumberNs(SMLoc at);
  bool notedTimeNumbers = false;
  /// A ULINT/LWORD constant past 2^63 - 1, where NetIR's literals stop:
  /// uint64(v - 2^63) + (2^63 - 1) + 1, computed in uint64.
  NExpr *unsigned64Literal(uint64_t v, SMLoc at);
  /// What unsigned64Literal built: already a uint64, whatever Sema's
  /// untyped-literal type says.
  llvm::SmallPtrSet<NExpr *, 4> unsigned64Literals;
  /// A NetIR uint64 as the integer type `to` (its low bits, two's
  /// complement).
  NExpr *fromUnsigned64(NExpr *v, const PType *to, SMLoc at);
  /// Operands computed together (`a + b`, MAX(a, b, c)): when one is a
  /// ULINT or LWORD, the other integers become uint64.
  void unifyUnsigned64(std::vector<NExpr *> &values,
                       llvm::ArrayRef<Expr *> sources, SMLoc at);
  // STRING and WSTRING (LowerStrings.cpp).
  const net::Type *stringType(const PType *t, SMLoc at, StringRef what);
  NExpr *stringLiteral(Expr *literal);
  /// A one-character literal where a CHAR or WCHAR is meant: its code.
  NExpr *charLiteral(Expr *literal);
  /// `s[i]` on a STRING or WSTRING (CODESYS, TwinCAT): the code of its
  /// (i+1)-th character, read and assigned as code() and with_code().
  static bool isStringIndex(const Expr *e);
  NExpr *stringByteRead(Expr *e, Frame &f, Sink &pre);
  void stringByteWrite(Expr *target, NExpr *value, Frame &f, Sink &out,
                       SMLoc at);
  /// LEN, LEFT, ... FIND on lowered operands.
  NExpr *stringFunction(Expr *call, llvm::ArrayRef<NExpr *> args, SMLoc at);
  /// A conversion to or from a string.
  NExpr *convertString(NExpr *v, const PType *from, const PType *to, SMLoc at);
  // DATE, TOD, DT and their L forms (LowerDates.cpp).
  NExpr *ticksToNs(NExpr *ticks, SMLoc at);
  /// Nanoseconds as ticks, rounded up (noted once per translation).
  NExpr *nsToTicks(NExpr *ns, SMLoc at);
  bool notedTickRounding = false;
  /// `l op r` where a date type takes part (Sema's dateArithmetic).
  NExpr *dateArithmetic(Op op, NExpr *l, const PType *lt, NExpr *r,
                        const PType *rt, SMLoc at);
  /// A conversion to or from a date type, or between TIME and a string.
  NExpr *convertDate(NExpr *v, const PType *from, const PType *to, SMLoc at);
  NExpr *dateToString(NExpr *v, const PType *from, const PType *to, SMLoc at);
  NExpr *stringToDate(NExpr *v, const PType *from, const PType *to, SMLoc at);
  // UNION (LowerUnions.cpp): held as its bytes in one int64.
  struct UnionLayout {
    int64_t size, align;
  };
  UnionLayout unionLayout(const PType *t, SMLoc at);
  const net::Type *unionType(const PType *t, SMLoc at);
  /// What `e` designates inside a UNION (u.m, u.a[i], u.s.f): the UNION
  /// expression, the bit offset, the type there; none when `e` is not in
  /// one.
  struct UnionPart {
    Expr *unionExpr;
    NExpr *bitOffset;
    const PType *type;
  };
  std::optional<UnionPart> unionPart(Expr *e, Frame &f, Sink &pre);
  const PType *scalarUnionMember(const UnionPart &p, SMLoc at);
  NExpr *unionRead(const UnionPart &p, Frame &f, Sink &pre, SMLoc at);
  /// A member's value as the bits it leaves in the UNION.
  NExpr *unionBits(const PType *t, NExpr *value, SMLoc at);
  /// `whole` with its `bits` bits at `offset` replaced by `field`'s low bits.
  NExpr *insertBits(NExpr *whole, NExpr *field, int64_t bits, NExpr *offset,
                    SMLoc at);
  /// The value of scalar type `t` whose `bits` low bits `raw` holds.
  NExpr *fromBits(const PType *t, NExpr *raw, int64_t bits, SMLoc at);
  NStmt *unionWrite(const UnionPart &p, NExpr *value, const PType *valueType,
                    Frame &f, Sink &pre, SMLoc at);
  NExpr *unionInitialValue(VarDecl *v, Initializer *init, const PType *t,
                           SMLoc at);
  NExpr *wrapTo(NExpr *v, const PType *t, Range r, SMLoc at);
  /// `x.3`, `x.%B1`: reading and writing a part of an integer's bits
  /// (LowerStmts.cpp).
  NExpr *partRead(Expr *e, Frame &f, Sink &pre);
  void partWrite(Expr *target, NExpr *value, Frame &f, Sink &out, SMLoc at);
  NExpr *maskTo(NExpr *v, const PType *t, SMLoc at);
  Range rangeOf(Expr *e);
  std::optional<int64_t> constValue(Expr *e, Frame &f);
  bool mayJump(const StmtList &l, bool loopLevel);
  std::optional<int64_t> loopBound(Stmt *loop, Stmt *before, Frame &f);
  void runtimeFor(Stmt *s, Frame &f, Sink &out,
                  const std::vector<LoopCtx> &loops);
  /// A fresh BOOL temporary `_<what>N` (EXIT, CONTINUE flags).
  std::string newFlag(const char *what, SMLoc at);
  Stmt *previous = nullptr; // the statement before the one being lowered
  void assign(NExpr *target, NExpr *value, const PType *targetType,
              Expr *valueExpr, Sink &out, SMLoc at);
  /// `target := value`, an aggregate value split into one assignment per
  /// element or field of `t` (from dimension `dim` of an array).
  void assignParts(NExpr *target, NExpr *value, const PType *t, size_t dim,
                   Sink &out, SMLoc at);
  /// `name := init` for each end-of-scan reset of `list`.
  void appendResets(const std::vector<std::pair<std::string, NExpr *>> &list,
                    Sink &out);

  Unit &unit;
  const LowerOptions &opts;
  DiagEngine &diag;
  net::Design &design;
  net::Builder b;
  int64_t tickNs = 0;

  // Per module.
  net::Module *mod = nullptr;
  std::map<const PType *, const net::Type *> typeCache;
  std::vector<std::pair<std::string, NExpr *>> resets; // end-of-scan
  std::set<std::string> resetNames;
  std::vector<std::string> instanceMembers; // FB member variables
  std::set<std::string> externallyRead;     // `inst.member` read by caller
  std::map<std::string, InstanceUse> instanceUses;
  std::map<std::string, ClockUse> clocks;          // by clock variable name
  std::map<std::string, std::string> clockOfBound; // `t.PT` -> clock var
  std::map<std::string, Pou *> instanceTypes;
  std::map<std::string, const PType *> varTypes; // NetIR var -> PLC type
  std::set<VarDecl *> written;
  /// The values each variable is assigned directly (`v := e`), and the
  /// variables also written otherwise (an output binding, a field).
  std::map<VarDecl *, std::vector<Expr *>> assignedValues;
  std::set<VarDecl *> writtenOtherwise;
  /// The FOR loops each variable is the control variable of.
  std::map<VarDecl *, std::vector<Stmt *>> forLoopsOf;
  void collectAssignments(StmtList &l);
  /// The largest value `e` can take, if netlift can bound it: a constant,
  /// an exact interval, or a variable only ever assigned such values.
  /// `visiting` holds the variables on the current path (cycles give no
  /// bound).
  std::optional<int64_t> upperBound(Expr *e, Frame &f,
                                    std::set<VarDecl *> &visiting);
  /// The same for a variable, from the values it is ever given.
  std::optional<int64_t> variableBound(Expr *e, Frame &f,
                                       std::set<VarDecl *> &visiting);
  std::map<VarDecl *, std::pair<int64_t, int64_t>> inputRanges;
  unsigned callSites = 0, flags = 0, loopVars = 0;
  /// The configuration's instance of each translated program.
  std::map<Pou *, std::pair<ProgramInstance *, Configuration *>> instanceOf;
  /// The instance whose arguments bind a program's inputs and outputs.
  std::map<Pou *, ProgramInstance *> argumentsOf;
  /// Inputs of the program being lowered that an argument feeds.
  std::set<VarDecl *> boundInputs;
  Pou *currentProgram = nullptr;
  /// The prefix of the current program's own names (see ProgramRun).
  std::string programPrefix;
  /// What the web HMI writes into instances' HMI_<T> members before a
  /// scan of the program whose prefix is the key ("": an instance among
  /// the globals, before every program's scan).
  std::map<std::string, std::vector<ChosenScalars>> scanSamples;
  /// An environment block's structured outputs: each scalar's free input
  /// by its place (`Axis1.NcToPlc.ActPos`), and the outputs themselves.
  std::map<std::string, std::string> environmentScalarPorts;
  std::vector<ChosenScalars> environmentValues;
  /// Each one's block, as notes name it.
  std::map<std::string, std::string> environmentOwners;
  /// What a runtime record's first read notes (emptied once said).
  std::map<std::string, std::string> runtimeRecordNotes;
  /// Registers `chosen` as an environment value (its scalars read where
  /// read); `owner` names it in refusals.
  void addEnvironmentValue(const ChosenScalars &chosen,
                           const std::string &owner);
  /// `place` read: a scalar of an environment block's structured output
  /// is its free input; a part of one read whole is chosen first (into
  /// `pre`). Null when `place` is none of these.
  NExpr *environmentRead(NExpr *place, Sink &pre);
  NExpr *environmentValueOr(NExpr *place, Sink &pre) {
    NExpr *x = environmentRead(place, pre);
    return x ? x : place;
  }
  /// Lowering an event-driven block: inputs take their full types.
  bool eventDriven = false;
  /// --ranges entries some input took, and every name an input could have
  /// taken one by (for the error about the others).
  std::set<std::string> rangesUsed;
  std::vector<std::string> rangeCandidates;
  void checkRangesUsed();
};

/// The variables a statement list assigns (through fields and indices),
/// nested statements included.
void collectWritten(StmtList &l, std::set<VarDecl *> &w);
/// The variables a statement list binds to VAR_IN_OUT parameters (the
/// callee may write them).
void collectInOutWritten(StmtList &l, std::set<VarDecl *> &w);
/// The name a reference's run-time checks are named after: its root
/// variable's (`pointer` when it has none).
std::string stemOf(Expr *reference);
/// The elements of a family that lie next to each other in memory: those
/// of its last index step (a string's or scalar's bytes when the family
/// numbers bytes; 1 when it ends in a field or is one place).
int64_t contiguousBlock(const RefFamily &fam);

} // namespace netlift::plc::detail

#endif
