//===- PlcAst.h - the PLC program model shared by ST, IL and LD -*- C++ -*-===//
//
// What a PLC program says, independent of the language it was written in:
// POUs (programs, function blocks, functions), their variables, user types,
// configurations with tasks, and bodies as statements and expressions. The
// ST frontend builds it from the parse tree, the IL frontend lowers its
// accumulator code into the same statements, and the PLCopen reader
// builds LD and FBD networks into it. Sema (Sema.h) resolves names and types in
// place; LowerToNet.h turns a checked program into a NetIR controller module.
//
// Nodes are owned by the Unit that created them; locations are SMLocs into
// buffers of the DiagEngine's SourceMgr, so every later error points into
// the source the user wrote.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLC_PLCAST_H
#define NETLIFT_FRONTENDS_PLC_PLCAST_H

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace netlift {
class DiagEngine;
}

namespace netlift::plc {

struct PType;
struct VarDecl;
struct Pou;

/// A pragma `{...}` attached to the declaration that follows it; `text` is
/// what stands between the braces.
struct Attribute {
  std::string text;
  llvm::SMLoc loc;
};

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

enum class ExprKind : uint8_t {
  IntLit,    // 42, 16#FF, INT#5 (typeName holds INT)
  RealLit,   // 1.5
  BoolLit,   // TRUE
  TimeLit,   // T#1s: value in nanoseconds
  DateLit,   // D#, TOD#, DT# and L forms: intValue ns, typeName the type
  StringLit, // 'abc'
  EnumLit,   // Color#red (typeName, name)
  Name,      // a variable, enumerator, constant or direct address
  Field,     // base.name
  BitAccess, // base.3, base.%X3; base.%B1 (partWidth 8), .%W1, .%D1
  Index,     // base[i, j]
  Deref,     // base^: what a reference designates
  Unary,
  Binary,
  Call, // name(args): function call (or FB call as a statement)
};

enum class Op : uint8_t {
  Neg,
  Plus,
  Not, // unary
  Or,
  OrElse,
  Xor,
  And,
  AndThen,
  Eq,
  Ne,
  Lt,
  Le,
  Gt,
  Ge,
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  Pow
};

llvm::StringRef spelling(Op op);

struct Expr;
struct DrawnBlock;

/// One argument of a call: `x`, `IN := x`, `Q => y`, `NOT Q => y`.
struct CallArg {
  std::string name; // empty: positional
  bool isOutput = false;
  bool negated = false;
  Expr *value = nullptr; // the input expression or the output target
  llvm::SMLoc loc;
  /// Set by Sema for an argument of an ANY input (an __SYSTEM.AnyType):
  /// `value` is then the address of what was passed, `anyClass` its type
  /// class and `anySize` its size in bytes; a value that is no variable
  /// (`anyValue`) is first stored into the caller's temporary `anyTemp`,
  /// whose address `value` takes.
  Expr *anyClass = nullptr, *anySize = nullptr;
  Expr *anyValue = nullptr, *anyTemp = nullptr;
};

struct Expr {
  ExprKind kind;
  llvm::SMLoc loc;
  std::string name;     // Name, Field, Call, EnumLit (enumerator)
  std::string typeName; // typed literals: INT#5, Color#red
  int64_t intValue = 0; // IntLit, BoolLit, TimeLit (ns), BitAccess (part)
  /// BitAccess: the width of the part, 1 for a bit; the part covers bits
  /// [intValue * partWidth, (intValue + 1) * partWidth) of the base.
  unsigned partWidth = 1;
  /// IntLit: the value is in [2^63, 2^64), only a ULINT or LWORD holds it,
  /// and intValue holds its bits.
  bool beyondInt64 = false;
  double realValue = 0;
  Op op = Op::Neg;
  std::vector<Expr *> operands; // Unary: 1, Binary: 2, Field/BitAccess/
                                // Deref: base, Index: base then indices
  std::vector<CallArg> args;    // Call
  DrawnBlock *drawn = nullptr;  // Call: the graphical block it was drawn as
  /// Call of a standard function: its EN argument and ENO target, if given.
  Expr *enable = nullptr, *enableOut = nullptr;
  /// Call of a METHOD or ACTION (`inst.M(...)`): operands[0] is the
  /// instance; without operands the call runs on the running instance
  /// (`M(...)`, `THIS^.M(...)`, `SUPER^.M(...)`).
  bool method = false;
  /// Name written `THIS^.x` (the instance's x, not a method's own) or
  /// `SUPER^.M` (the base's M); Call `SUPER^()` (the base's body).
  bool ofThis = false, ofSuper = false;
  /// A method call that reads ('G') or assigns ('S') a PROPERTY.
  char property = 0;
  /// Name `THIS^`: the running instance itself (Sema sets `callee` to the
  /// block whose code it is in).
  bool selfInstance = false;

  // Filled in by Sema.
  const PType *type = nullptr;
  VarDecl *var = nullptr; // Name: the variable it denotes
  Pou *callee = nullptr;  // Call: a user or library function
  int64_t enumValue = -1; // EnumLit or Name denoting an enumerator

  Expr(ExprKind k, llvm::SMLoc l) : kind(k), loc(l) {}
  Expr *base() const { return operands.empty() ? nullptr : operands[0]; }
};

//===----------------------------------------------------------------------===//
// Types as written
//===----------------------------------------------------------------------===//

enum class TypeSyntaxKind : uint8_t {
  Named,     // INT, TON, MyStruct
  Subrange,  // INT(0..10)
  Array,     // ARRAY[1..3, 0..1] OF T
  Enum,      // (a, b := 2, c)
  Struct,    // STRUCT ... END_STRUCT
  String,    // STRING[20]
  Reference, // REF_TO T, POINTER TO T, REFERENCE TO T (elem: T)
  Refused,   // a construct netlift refuses: `refused` is the message
};

/// Which of the three spellings of a reference a type was written with.
/// They designate storage alike (docs/st.md, "References and pointers");
/// they differ in what the program may write: a REFERENCE TO is
/// dereferenced implicitly and bound with `REF=`, a POINTER TO takes
/// ADR and compares with 0.
enum class RefKind : uint8_t { RefTo, Pointer, Reference, Interface };

struct Initializer;

struct EnumValueSyntax {
  std::string name;
  Expr *value = nullptr;
  llvm::SMLoc loc;
};

struct TypeSyntax {
  TypeSyntaxKind kind;
  llvm::SMLoc loc;
  std::string name;                            // Named; Subrange: base
  std::string refused;                         // Refused: the construct
  Expr *lo = nullptr, *hi = nullptr;           // Subrange
  Expr *length = nullptr;                      // String: STRING[20]
  std::vector<std::pair<Expr *, Expr *>> dims; // Array
  TypeSyntax *elem = nullptr;                  // Array, Reference
  RefKind refKind = RefKind::RefTo;            // Reference
  std::vector<EnumValueSyntax> enumerators;    // Enum
  std::vector<VarDecl *> fields;               // Struct
  std::string extends; // Struct: `TYPE B EXTENDS A : STRUCT`, A's name
  /// Named: `fb : FB_Axis(nId := 1)`, the arguments of the instance's
  /// FB_init.
  std::vector<CallArg> instanceArgs;
  /// Array: `ARRAY[1..2] OF FB_Axis[(nId := 1), (nId := 2)]`, each
  /// element's FB_init arguments in row-major order.
  std::vector<std::vector<CallArg>> elementArgs;
  bool isUnion = false;        // Struct: UNION ... END_UNION (members overlap)
  Initializer *init = nullptr; // `:= init` after the type
  TypeSyntax(TypeSyntaxKind k, llvm::SMLoc l) : kind(k), loc(l) {}
};

/// An initial value: an expression, `[1, 2, 3(0)]` or `(x := 1, y := 2)`.
struct Initializer {
  enum Kind : uint8_t { Value, Array, Struct } kind;
  llvm::SMLoc loc;
  Expr *value = nullptr;
  std::vector<std::pair<int64_t, Initializer *>> elems; // (repeat, init)
  std::vector<std::pair<std::string, Initializer *>> fields;
  Initializer(Kind k, llvm::SMLoc l) : kind(k), loc(l) {}
};

//===----------------------------------------------------------------------===//
// Variables
//===----------------------------------------------------------------------===//

enum class VarSection : uint8_t {
  Var,
  Input,
  Output,
  InOut,
  External,
  Global,
  Temp,
  // Sections netlift refuses (named in the error):
  Access,
  Config,
  Stat,
  Inst,
};

llvm::StringRef spelling(VarSection s);

/// A pin of a block drawn in a graphical body (LD, FBD): its formal
/// parameter and the pin group it sits in (inputVariables: Input,
/// inOutVariables: InOut, outputVariables: Output).
struct DrawnPin {
  std::string name;
  VarSection drawnAs;
  llvm::SMLoc loc;
};

/// What a graphical body drew for a call: the block's typeName and every
/// pin. A graphical block names its type and its instance separately, so
/// the two can disagree; Sema checks the drawing against the declaration
/// (a TOF drawn on an instance declared TON is an error, never a TON).
/// The error for a graphical block of a function block type drawn without
/// an instanceName (LD/FBD readers and Sema say it alike).
std::string noInstanceMessage(llvm::StringRef typeName);

struct DrawnBlock {
  std::string typeName;
  std::string instanceName; // empty for a function
  std::vector<DrawnPin> pins;
};

struct VarDecl {
  std::string name;
  llvm::SMLoc loc;
  bool isLibrary = false; // a global of netlift's own (st::addLibraryText)
  /// Declared by a frontend for an element, not by the user (a graphical
  /// body's temporaries, enable flags and edge detectors): internal.
  bool generated = false;
  /// A global no input declares, made for a VAR_EXTERNAL: the variable is
  /// shared with code outside the design (an Arduino sketch, a runtime
  /// extension), which may write it between scans (Sema, LowerEnvironment).
  bool sharedOutside = false;
  VarSection section = VarSection::Var;
  bool constant = false;
  bool retain = false;
  std::string location; // "%IX0.0" for `AT %IX0.0`, empty otherwise
  TypeSyntax *typeSyntax = nullptr;
  std::vector<Attribute> attrs;
  /// A temporary made by a frontend (the IL accumulator) whose type is that
  /// of the first value assigned to it.
  bool inferType = false;
  /// `x : BOOL R_EDGE` ('R') or `F_EDGE` ('F'): inside the function block
  /// the input is TRUE only at an edge of what the caller passes.
  char edge = 0;

  // Filled in by Sema.
  const PType *type = nullptr;
  Pou *owner = nullptr;
  /// A program input (or `AT %I` variable) the program writes: the written
  /// value stands until the next scan samples the input again, as matiec
  /// and CODESYS run it.
  bool writtenInput = false;

  /// An instance whose block has an FB_init: its call before the first
  /// scan, with the declaration's arguments (Sema builds and checks it).
  Expr *initCall = nullptr;
  /// An array of such instances declared with each element's arguments:
  /// their calls, in row-major order.
  std::vector<Expr *> elementInitCalls;
  /// An input of a function or method of a generic type (`ANY`,
  /// `ANY_NUM`, ...; CODESYS, TwinCAT): the generic's name; the input is
  /// an __SYSTEM.AnyType describing what each call passes.
  std::string anyGeneric;
  /// A global of a TwinCAT global variable list: the list's name, by
  /// which the program may qualify it (`GVL_IO.bStart`).
  std::string globalList;
  /// A record the runtime writes before every scan (TwinCAT's `_TaskInfo`
  /// and `_AppInfo`), declared by a library with `{netlift runtime 'what
  /// it is' free 'fields' first 'field'}`: what it is; the fields whose
  /// values the model does not know (free inputs, read where read); the
  /// field that is TRUE in the first scan only. The program may only read
  /// it (Sema; LowerEnvironment.cpp).
  std::string runtimeRecord;
  std::vector<std::string> runtimeFree;
  std::string runtimeFirst;

  /// `AT %I...` / `%Q...` / `%M...`: 'I', 'Q', 'M' or 0.
  char area() const { return location.size() > 1 ? location[1] : 0; }
};

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

enum class StmtKind : uint8_t {
  Assign,
  Call, // an FB instance call or a function call used as a statement
  If,
  Case,
  For,
  While,
  Repeat,
  Exit,
  Continue,
  Return,
  // CODESYS's jumps in ST (`JMP l;`, `l:`; target: the label's Name):
  // expandJumps turns them into the statements above before Sema.
  Jump,
  Label,
};

struct Stmt;
using StmtList = std::vector<Stmt *>;

struct CaseLabel {
  Expr *lo;
  Expr *hi; // null: a single value
};

struct CaseArmSyntax {
  std::vector<CaseLabel> labels;
  StmtList body;
};

/// How an Assign stores: `:=`, `REF=` (binds a REFERENCE TO, or sets any
/// reference, to the target's address) or `?=` (an assignment attempt:
/// NULL when the value does not designate a target of the type).
enum class AssignKind : uint8_t { Value, BindReference, Attempt };

struct Stmt {
  StmtKind kind;
  llvm::SMLoc loc;
  AssignKind assignKind = AssignKind::Value; // Assign
  Expr *target = nullptr; // Assign; For: the loop variable (a Name)
  Expr *value = nullptr;  // Assign; Call (a Call expression); Case selector;
                          // While/Repeat condition
  std::vector<std::pair<Expr *, StmtList>> arms; // If (cond, body)
  std::vector<CaseArmSyntax> caseArms;           // Case
  bool hasElse = false;
  StmtList elseBody;                   // If, Case
  Expr *from = nullptr, *to = nullptr; // For
  Expr *by = nullptr;
  StmtList body; // For, While, Repeat
  Stmt(StmtKind k, llvm::SMLoc l) : kind(k), loc(l) {}
};

//===----------------------------------------------------------------------===//
// Program organisation units and configurations
//===----------------------------------------------------------------------===//

enum class PouKind : uint8_t { Program, FunctionBlock, Function };

/// A Sequential Function Chart (IEC 61131-3 3rd edition, 6.7), as textual
/// SFC and PLCopen's graphical SFC give it; expandSfc (SfcExpansion.cpp)
/// turns it into the statements a scan runs.
struct SfcAssociation {
  std::string action; // an ACTION of the POU or a BOOL variable
  std::string qualifier = "N";
  Expr *time = nullptr; // L, D, SD, DS, SL
  std::vector<std::string> indicators;
  llvm::SMLoc loc;
};

struct SfcStep {
  std::string name;
  llvm::SMLoc loc;
  bool initial = false;
  std::vector<SfcAssociation> actions;
};

struct SfcTransition {
  std::string name; // may be empty
  llvm::SMLoc loc;
  int64_t priority = -1; // PRIORITY := n, -1 when not given
  std::vector<std::string> from, to;
  std::vector<llvm::SMLoc> fromLocs, toLocs;
  Expr *condition = nullptr;
  /// The condition as written (or what names it), for drawings.
  std::string conditionText;
};

struct SfcAction {
  std::string name;
  llvm::SMLoc loc;
  StmtList body;
};

struct SfcChart {
  /// What a graphical chart computes before its transitions are cleared:
  /// the networks drawn beside it (wired conditions) and the bodies of the
  /// POU transitions it names (each sets a BOOL named like it).
  StmtList networks;
  std::vector<SfcStep *> steps;
  std::vector<SfcTransition *> transitions;
  std::vector<SfcAction *> actions;
};

llvm::StringRef spelling(PouKind k);

struct Pou {
  PouKind kind;
  std::string name;
  llvm::SMLoc loc;
  TypeSyntax *resultSyntax = nullptr; // functions
  std::vector<VarDecl *> vars;
  StmtList body;
  /// The body's chart when it is written in SFC (then `body` is what
  /// expandSfc made of it).
  SfcChart *sfc = nullptr;
  std::vector<Attribute> attrs;
  /// Part of netlift's standard library (TON, CTU, ...), not the user's.
  bool isLibrary = false;
  /// Object orientation (docs/st.md, "TwinCAT and CODESYS"). A METHOD or
  /// ACTION is a Function whose `methodOf` is the function block or
  /// program it belongs to (an ACTION has no variables of its own); the
  /// block lists it in `methods`. `extends` names the base block, `base`
  /// is that block once resolved (resolveInheritance), whose variables the
  /// block's `vars` then start with.
  Pou *methodOf = nullptr;
  std::vector<Pou *> methods;
  bool isAction = false;
  /// A library block the runtime implements with effects netlift does not
  /// model (ADS, files): what it does, for the note and the refusal; its
  /// outputs are free inputs of the model (--opaque=environment), its
  /// inputs are not stored. Empty for a block modelled by its body.
  std::string environment;
  /// An environment block's address inputs through which the runtime
  /// writes the program's memory (ADSREAD's DESTADDR), from `{netlift
  /// writes 'DESTADDR'}`: what `ADR(x)` given there designates takes free
  /// values at every call (LowerCalls.cpp, environmentCall).
  std::vector<std::string> writesThrough;
  /// A PROPERTY's accessor: 'G' (GET: a method whose result is the
  /// property's value) or 'S' (SET: a method whose input named like the
  /// property is the value assigned); 0 otherwise.
  char property = 0;
  std::string extends;
  llvm::SMLoc extendsLoc;
  Pou *base = nullptr;
  std::vector<std::string> implements;
  /// PUBLIC (empty), PRIVATE, PROTECTED or INTERNAL; ABSTRACT, FINAL.
  std::string access;
  bool isAbstract = false;
  /// An INTERFACE (kind FunctionBlock, no variables, abstract methods);
  /// `implements` then lists the interfaces it EXTENDS.
  bool isInterface = false;
  std::vector<Pou *> extendedInterfaces; // resolved `implements` of one
  /// The first construct netlift refuses in this POU (its message and
  /// place); reported only if the POU is translated, so a library's unused
  /// POUs may hold what netlift does not model.
  std::string refusal;
  llvm::SMLoc refusalLoc;

  // Filled in by Sema.
  /// Sema reported an error in this POU (or its refusal): a library's
  /// blocks that reach it are not lowered.
  bool checkFailed = false;
  const PType *resultType = nullptr;
  VarDecl *resultVar = nullptr; // functions: the variable named like it
  /// The variable declared with this name (case-insensitive), or null.
  VarDecl *find(llvm::StringRef name) const;
  /// After `vars` changed other than by appending.
  void varsReordered() {
    index.clear();
    indexed = 0;
  }

private:
  // Upper-case name -> first declaration; rebuilt when vars grows.
  mutable llvm::StringMap<VarDecl *> index;
  mutable size_t indexed = 0;
};

struct TypeDecl {
  std::string name;
  llvm::SMLoc loc;
  TypeSyntax *type = nullptr;
  const PType *resolved = nullptr; // Sema
  bool isLibrary = false;          // netlift's own (st::addLibraryText)
  /// Pragmas written before it (`{attribute 'pack_mode' := '1'}`).
  std::vector<Attribute> attrs;
};

struct Task {
  std::string name;
  llvm::SMLoc loc;
  Expr *interval = nullptr; // INTERVAL := T#20ms
  Expr *single = nullptr;   // SINGLE := trigger (refused)
  Expr *priority = nullptr;
};

struct ProgramInstance {
  std::string name;
  llvm::SMLoc loc;
  std::string task;
  std::string typeName;
  llvm::SMLoc typeLoc;
  std::vector<CallArg> args;
};

struct Configuration {
  std::string name;
  llvm::SMLoc loc;
  std::vector<VarDecl *> globals;
  std::vector<Task> tasks;
  std::vector<ProgramInstance> programs;
};

/// Everything read from the inputs of one translation: the owner of all
/// nodes.
/// Whose order an SFC scan follows (docs/sfc.md, "One scan").
enum class SfcDialect : uint8_t {
  Iec,     // evolve, then run the actions of the new activity
  Codesys, // run the actions of the current activity, then evolve
};

/// What TIME_TO_INT, TIME_TO_REAL, INT_TO_TIME and REAL_TO_TIME count in,
/// which IEC 61131-3 leaves to the implementation: seconds in matiec
/// (OpenPLC, Beremiz), milliseconds in CODESYS and TwinCAT.
enum class TimeNumbers : uint8_t { Milliseconds, Seconds };

class Unit {
public:
  /// --sfc-dialect, read by expandSfc.
  SfcDialect sfcDialect = SfcDialect::Iec;
  /// --time-unit, or what the inputs show (a textual CONFIGURATION, a
  /// PLCopen file written by Beremiz or OpenPLC: seconds); `timeNumbersWhy`
  /// says why, for the note the lowering gives where it converts.
  TimeNumbers timeNumbers = TimeNumbers::Milliseconds;
  std::string timeNumbersWhy;
  /// What an input shows of the unit: the option, else the first input
  /// that shows one, decides.
  void inferTimeNumbers(TimeNumbers t, std::string why) {
    if (!timeNumbersWhy.empty())
      return;
    timeNumbers = t;
    timeNumbersWhy = std::move(why);
  }
  /// The Instruction List reader (il::parseInstructionListBody), for an SFC
  /// transition condition written in IL inside ST; set by the frontend
  /// that owns both languages (the ST library cannot depend on IL's).
  std::function<bool(llvm::StringRef, DiagEngine &, Unit &, Pou *, Expr **)>
      instructionListReader;
  /// A TwinCAT file was read: the models of its libraries are added.
  bool twinCat = false;
  /// Names defined for conditional compilation (-D, a project's compiler
  /// defines), upper-case, with their values (st/StConditionals.h).
  std::map<std::string, std::string> defines;
  /// The PLC project read (FrontendOptions::projectName), or empty.
  std::string projectName;
  std::vector<Pou *> pous;
  std::vector<TypeDecl *> types;
  std::vector<Configuration *> configs;
  std::vector<VarDecl *> globals; // top-level VAR_GLOBAL (TwinCAT GVLs)

  template <typename T, typename... Args> T *make(Args &&...args) {
    auto node = std::make_unique<Holder<T>>(std::forward<Args>(args)...);
    T *raw = &node->value;
    owned.push_back(std::move(node));
    return raw;
  }

  Pou *findPou(llvm::StringRef name) const;
  TypeDecl *findType(llvm::StringRef name) const;

private:
  struct HolderBase {
    virtual ~HolderBase() = default;
  };
  template <typename T> struct Holder : HolderBase {
    template <typename... Args>
    explicit Holder(Args &&...args) : value(std::forward<Args>(args)...) {}
    T value;
  };
  std::vector<std::unique_ptr<HolderBase>> owned;
};

/// IEC identifiers are case-insensitive.
bool sameName(llvm::StringRef a, llvm::StringRef b);

/// The METHOD or ACTION `name` an instance of `block` runs: its own, else
/// its base's (an override hides the base's); null when none.
Pou *findMethod(const Pou *block, llvm::StringRef name);

/// The GET (`set` false) or SET accessor of the PROPERTY `name` an
/// instance of `block` runs; null when none.
Pou *findProperty(const Pou *block, llvm::StringRef name, bool set);

/// What a method call (Expr::method) runs on an instance of `block`: the
/// method, action or property accessor it names.
Pou *findCallee(const Pou *block, const Expr *call);

/// Is `block` `base`, or derived from it through EXTENDS?
bool derivedFrom(const Pou *block, const Pou *base);
/// The tasks of a TwinCAT project (its .TcTTO files, the configuration
/// the loader names "TwinCAT"), in the order read: what sizes `_TaskInfo`
/// and what GETCURTASKINDEXEX() ranges over.
std::vector<const Task *> twinCatTasks(const Unit &unit);

/// Does `block` (or a base) IMPLEMENT `itf`, or an interface that EXTENDS
/// it?
bool implementsInterface(const Unit &unit, const Pou *block, const Pou *itf);

/// Every method of `block` and of its bases (overridden ones included).
void forEachMethod(const Pou *block, llvm::function_ref<void(Pou *)> fn);

/// Resolves EXTENDS between function blocks: each derived block's `base`
/// is set and its `vars` begin with its base's (the same declarations, so
/// a base method's name designates the member whatever the instance's
/// type); an interface's `extendedInterfaces`. An unknown base or
/// interface, a base of the wrong kind, a cycle and a member declared
/// again become the block's refusal (reported if the translation reaches
/// it: a library block a project does not use may extend what it lacks).
void resolveInheritance(Unit &unit);

/// Builds the AST of code a frontend generates rather than parses (the
/// networks of graphical bodies, SFC charts). A maker that must watch how
/// much it builds overrides make().
class AstMaker {
public:
  explicit AstMaker(Unit &unit) : unit(unit) {}
  virtual ~AstMaker() = default;
  virtual Expr *make(ExprKind k, llvm::SMLoc at) {
    return unit.make<Expr>(k, at);
  }
  Expr *boolLit(bool v, llvm::SMLoc at) {
    Expr *e = make(ExprKind::BoolLit, at);
    e->intValue = v;
    return e;
  }
  Expr *intLit(int64_t v, llvm::SMLoc at) {
    Expr *e = make(ExprKind::IntLit, at);
    e->intValue = v;
    return e;
  }
  Expr *nameRef(llvm::StringRef name, llvm::SMLoc at) {
    Expr *e = make(ExprKind::Name, at);
    e->name = name.str();
    return e;
  }
  Expr *field(Expr *base, llvm::StringRef name, llvm::SMLoc at) {
    Expr *e = make(ExprKind::Field, at);
    e->name = name.str();
    e->operands.push_back(base);
    return e;
  }
  Expr *unary(Op op, Expr *a, llvm::SMLoc at) {
    Expr *e = make(ExprKind::Unary, at);
    e->op = op;
    e->operands.push_back(a);
    return e;
  }
  Expr *binary(Op op, Expr *a, Expr *b, llvm::SMLoc at) {
    Expr *e = make(ExprKind::Binary, at);
    e->op = op;
    e->operands = {a, b};
    return e;
  }
  Stmt *assign(Expr *target, Expr *value, llvm::SMLoc at) {
    Stmt *s = unit.make<Stmt>(StmtKind::Assign, at);
    s->target = target;
    s->value = value;
    return s;
  }
  Stmt *when(Expr *cond, StmtList body, llvm::SMLoc at) {
    Stmt *s = unit.make<Stmt>(StmtKind::If, at);
    s->arms.push_back({cond, std::move(body)});
    return s;
  }
  /// A variable of `pou` of the named `type` (empty: typed by the first
  /// value assigned to it, VarDecl::inferType).
  VarDecl *declare(Pou &pou, llvm::StringRef name, llvm::StringRef type,
                   llvm::SMLoc at, VarSection section = VarSection::Var);

protected:
  Unit &unit;
};

/// The characters of an IEC string literal written with its quotes: 'abc'
/// (STRING; `$hh` escapes a byte) or "abc" (WSTRING; `$hhhh`), with `$$`,
/// `$'` / `$"`, `$L` and `$N` (line feed), `$P` (form feed), `$R`, `$T`.
/// Returns the message of a malformed escape, or nullopt.
std::optional<std::string> decodeStringLiteral(llvm::StringRef quoted,
                                               std::u16string &out);

/// After reading a POU stopped at a construct netlift refuses: the POU
/// read so far (added to `unit` after its first `pousBefore` POUs) or, if
/// none was added, a stub of that kind and name keeps the refusal, to be
/// reported if the translation reaches it (Sema).
void keepRefusedPou(Unit &unit, size_t pousBefore, PouKind kind,
                    llvm::StringRef name, llvm::SMLoc loc,
                    llvm::SMLoc refusalLoc, std::string refusal);

/// Visits every statement of `l`, nested ones included: `stmt` on the
/// statement, then `expr` on each expression it holds directly (target,
/// value, FOR bounds, IF conditions; not their sub-expressions), then the
/// statements nested in it.
void forEachStmt(StmtList &l, llvm::function_ref<void(Stmt *)> stmt,
                 llvm::function_ref<void(Expr *)> expr = nullptr);

/// Visits the value of every element of an initial value (`[1, 2]`,
/// `(x := 1)`, nested), in order; not their sub-expressions.
void forEachInitialValue(Initializer *init,
                         llvm::function_ref<void(Expr *)> fn);

/// Visits `e` and every expression nested in it (operands, call
/// arguments), outermost first.
void forEachNestedExpr(Expr *e, llvm::function_ref<void(Expr *)> fn);

} // namespace netlift::plc

#endif
