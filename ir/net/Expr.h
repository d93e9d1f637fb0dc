//===- Expr.h - NetIR guard and action language -----------------*- C++ -*-===//
//
// The small expression and statement language of NetIR guards, condition
// expressions, signal definitions, actions and hybrid flows. Nodes are
// allocated in the owning Design's arena and are trivially destructible;
// children are ArrayRefs into the same arena. References are by name as
// written (qualified names such as `c.step` are single names); the verifier
// resolves every Ref to a Symbol and records the type of every expression,
// so that later stages never look names up again.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_EXPR_H
#define NETLIFT_IR_NET_EXPR_H

#include "ir/net/Types.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Casting.h"
#include "llvm/Support/SMLoc.h"

#include <cstdint>
#include <optional>
#include <string>

namespace netlift::net {

/// What a resolved name denotes inside a module.
enum class SymKind : uint8_t {
  None,
  Place,
  Transition,
  Port,     // index into Module::ports
  Var,      // index into Module::vars (includes clocks and reals)
  Instance, // index into Module::instances
  EnumLit,  // index = enumerator value; Ref::type is the enum
  LoopVar,  // index = nesting depth of the `for`
};

struct Symbol {
  SymKind kind = SymKind::None;
  uint32_t index = 0;
  bool operator==(const Symbol &o) const {
    return kind == o.kind && index == o.index;
  }
};

enum class ExprKind : uint8_t {
  IntLit,
  BoolLit,
  RealLit,
  StringLit,
  Ref,
  Index,
  Field,
  Unary,
  Binary,
  Cond,
  Call,
  Aggregate,
};

enum class UnaryOp : uint8_t { Not, Neg, BitNot };
enum class BinaryOp : uint8_t {
  Or,
  Xor,
  And,
  Eq,
  Ne,
  Lt,
  Le,
  Gt,
  Ge,
  BitOr,
  BitXor,
  BitAnd,
  Shl,
  Shr,
  Add,
  Sub,
  Mul,
  Div,
  Mod,
};
enum class Builtin : uint8_t {
#define NETLIFT_BUILTIN(name, spelling, arity, summary) name,
#include "ir/net/Builtins.def"
};
/// How many operands a built-in takes.
unsigned arity(Builtin b);
/// len, left, ... find: the built-ins with string operands.
bool isStringBuiltin(Builtin b);
/// The built-in spelled `name` (not Convert, which is spelled as a type).
std::optional<Builtin> builtinNamed(llvm::StringRef name);

llvm::StringRef spelling(UnaryOp op);
llvm::StringRef spelling(BinaryOp op);
llvm::StringRef spelling(Builtin b);
/// Binding strength used by the parser and the printer (higher binds
/// tighter).
int precedence(BinaryOp op);
/// `==` `!=` `<` `<=` `>` `>=` (one precedence level).
inline bool isComparison(BinaryOp op) { return precedence(op) == 5; }
/// `+` `-` `*` `/` `%` (the two highest levels).
inline bool isArithmetic(BinaryOp op) { return precedence(op) >= 10; }

class Expr {
public:
  ExprKind getKind() const { return kind; }
  llvm::SMLoc loc;
  /// Filled in by the verifier.
  const Type *type = nullptr;

protected:
  Expr(ExprKind k, llvm::SMLoc l) : loc(l), kind(k) {}

private:
  ExprKind kind;
};

class IntLit : public Expr {
public:
  IntLit(llvm::SMLoc l, int64_t v) : Expr(ExprKind::IntLit, l), value(v) {}
  int64_t value;
  static bool classof(const Expr *e) {
    return e->getKind() == ExprKind::IntLit;
  }
};

class BoolLit : public Expr {
public:
  BoolLit(llvm::SMLoc l, bool v) : Expr(ExprKind::BoolLit, l), value(v) {}
  bool value;
  static bool classof(const Expr *e) {
    return e->getKind() == ExprKind::BoolLit;
  }
};

class RealLit : public Expr {
public:
  RealLit(llvm::SMLoc l, double v) : Expr(ExprKind::RealLit, l), value(v) {}
  double value;
  static bool classof(const Expr *e) {
    return e->getKind() == ExprKind::RealLit;
  }
};

/// `"abc"`: a string constant, of type string[n] (wstring[n] when a
/// character needs more than 8 bits, or when it stands next to a wstring).
class StringLit : public Expr {
public:
  StringLit(llvm::SMLoc l, llvm::ArrayRef<char16_t> c)
      : Expr(ExprKind::StringLit, l), chars(c) {}
  /// The characters (arena-allocated), each a code unit of the string's
  /// character width.
  llvm::ArrayRef<char16_t> chars;
  static bool classof(const Expr *e) {
    return e->getKind() == ExprKind::StringLit;
  }
};

/// A name: a place, port, variable, enumerator (`Color#red` or bare `red`),
/// or loop variable. `c.pos.x` may denote field x of record variable c.pos;
/// the verifier then records the field path in `fields`.
class Ref : public Expr {
public:
  Ref(llvm::SMLoc l, llvm::StringRef n) : Expr(ExprKind::Ref, l), name(n) {}
  llvm::StringRef name;
  Symbol sym;
  /// Field indices applied after the symbol (record access written with
  /// dots inside the name).
  llvm::ArrayRef<uint32_t> fields;
  static bool classof(const Expr *e) { return e->getKind() == ExprKind::Ref; }
};

class IndexExpr : public Expr {
public:
  IndexExpr(llvm::SMLoc l, Expr *b, Expr *i)
      : Expr(ExprKind::Index, l), base(b), index(i) {}
  Expr *base;
  Expr *index;
  static bool classof(const Expr *e) { return e->getKind() == ExprKind::Index; }
};

/// `base.field` where base is not a plain name (e.g. `a[i].x`).
class FieldExpr : public Expr {
public:
  FieldExpr(llvm::SMLoc l, Expr *b, llvm::StringRef f)
      : Expr(ExprKind::Field, l), base(b), field(f) {}
  Expr *base;
  llvm::StringRef field;
  uint32_t fieldIndex = 0;
  static bool classof(const Expr *e) { return e->getKind() == ExprKind::Field; }
};

class UnaryExpr : public Expr {
public:
  UnaryExpr(llvm::SMLoc l, UnaryOp o, Expr *a)
      : Expr(ExprKind::Unary, l), op(o), operand(a) {}
  UnaryOp op;
  Expr *operand;
  static bool classof(const Expr *e) { return e->getKind() == ExprKind::Unary; }
};

class BinaryExpr : public Expr {
public:
  BinaryExpr(llvm::SMLoc l, BinaryOp o, Expr *a, Expr *b)
      : Expr(ExprKind::Binary, l), op(o), lhs(a), rhs(b) {}
  BinaryOp op;
  Expr *lhs, *rhs;
  static bool classof(const Expr *e) {
    return e->getKind() == ExprKind::Binary;
  }
};

/// `c ? a : b`
class CondExpr : public Expr {
public:
  CondExpr(llvm::SMLoc l, Expr *c, Expr *a, Expr *b)
      : Expr(ExprKind::Cond, l), cond(c), thenExpr(a), elseExpr(b) {}
  Expr *cond, *thenExpr, *elseExpr;
  static bool classof(const Expr *e) { return e->getKind() == ExprKind::Cond; }
};

class CallExpr : public Expr {
public:
  CallExpr(llvm::SMLoc l, Builtin f, llvm::ArrayRef<Expr *> a,
           const Type *to = nullptr)
      : Expr(ExprKind::Call, l), fn(f), args(a), to(to) {}
  Builtin fn;
  llvm::ArrayRef<Expr *> args;
  /// Convert: the target type (a PLC integer, a float, a string, or bool
  /// from a string). Converting a float to an integer rounds half away from
  /// zero; a value the target cannot hold is a run-time error, whatever the
  /// target's overflow rule; a string's text is read as IEC 61131-3
  /// writes a literal of the target type (docs/netir.md, "Strings").
  const Type *to;
  static bool classof(const Expr *e) { return e->getKind() == ExprKind::Call; }
};

/// How a call is spelled: the built-in's name, or a conversion's target
/// (`int16`, `real32`: overflow rules play no part in a conversion).
std::string calleeSpelling(const CallExpr *c);

/// The initial value of an array or record variable, and nothing else:
/// `[1, 2, 3]` lists an array's elements from its low index up,
/// `{x: 1, y: [0, 0]}` a record's fields in declaration order (every
/// element and field given, each a constant).
class AggregateLit : public Expr {
public:
  AggregateLit(llvm::SMLoc l, llvm::ArrayRef<Expr *> e,
               llvm::ArrayRef<llvm::StringRef> names)
      : Expr(ExprKind::Aggregate, l), elems(e), fieldNames(names) {}
  llvm::ArrayRef<Expr *> elems;
  /// A record's field names, one per element; empty for an array.
  llvm::ArrayRef<llvm::StringRef> fieldNames;
  bool isRecord() const { return !fieldNames.empty(); }
  static bool classof(const Expr *e) {
    return e->getKind() == ExprKind::Aggregate;
  }
};

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

enum class StmtKind : uint8_t { Assign, If, Case, For, While };

class Stmt {
public:
  StmtKind getKind() const { return kind; }
  llvm::SMLoc loc;

protected:
  Stmt(StmtKind k, llvm::SMLoc l) : loc(l), kind(k) {}

private:
  StmtKind kind;
};

using Block = llvm::ArrayRef<Stmt *>;

/// `target := value;` (target is a Ref, IndexExpr or FieldExpr).
class AssignStmt : public Stmt {
public:
  AssignStmt(llvm::SMLoc l, Expr *t, Expr *v)
      : Stmt(StmtKind::Assign, l), target(t), value(v) {}
  Expr *target;
  Expr *value;
  static bool classof(const Stmt *s) {
    return s->getKind() == StmtKind::Assign;
  }
};

struct IfArm {
  Expr *cond;
  Block body;
};

/// `if c { } elif c { } else { }`
class IfStmt : public Stmt {
public:
  IfStmt(llvm::SMLoc l, llvm::ArrayRef<IfArm> a, bool he, Block e)
      : Stmt(StmtKind::If, l), arms(a), hasElse(he), elseBody(e) {}
  llvm::ArrayRef<IfArm> arms;
  bool hasElse;
  Block elseBody;
  static bool classof(const Stmt *s) { return s->getKind() == StmtKind::If; }
};

/// A case label: a single value (hi == nullptr) or a range lo..hi.
struct CaseLabel {
  Expr *lo;
  Expr *hi;
};
struct CaseArm {
  llvm::ArrayRef<CaseLabel> labels;
  Block body;
};

/// `case e { 1, 2..4 { } else { } }`: the first matching arm runs.
class CaseStmt : public Stmt {
public:
  CaseStmt(llvm::SMLoc l, Expr *s, llvm::ArrayRef<CaseArm> a, bool he, Block e)
      : Stmt(StmtKind::Case, l), selector(s), arms(a), hasElse(he),
        elseBody(e) {}
  Expr *selector;
  llvm::ArrayRef<CaseArm> arms;
  bool hasElse;
  Block elseBody;
  static bool classof(const Stmt *s) { return s->getKind() == StmtKind::Case; }
};

/// `for i in lo..hi { }`: the bounds are evaluated once, before the first
/// iteration; i is read-only in the body.
class ForStmt : public Stmt {
public:
  ForStmt(llvm::SMLoc l, llvm::StringRef v, Expr *a, Expr *b, Block body)
      : Stmt(StmtKind::For, l), var(v), lo(a), hi(b), body(body) {}
  llvm::StringRef var;
  Expr *lo, *hi;
  Block body;
  static bool classof(const Stmt *s) { return s->getKind() == StmtKind::For; }
};

/// `while c { }` (the condition tested before each iteration) or
/// `repeat { } until c;` (after each, so the body runs at least once). Run
/// concretely; every iteration counts against the watchdog of the firing.
class WhileStmt : public Stmt {
public:
  WhileStmt(llvm::SMLoc l, Expr *c, Block body, bool testAfter)
      : Stmt(StmtKind::While, l), cond(c), body(body), testAfter(testAfter) {}
  /// WHILE: keep going while it holds; REPEAT: stop when it holds.
  Expr *cond;
  Block body;
  bool testAfter;
  static bool classof(const Stmt *s) { return s->getKind() == StmtKind::While; }
};

/// Evaluate a constant integer expression (literals, enumerators, + - * /
/// and unary minus) without a state; false if it is not constant.
bool evalConstInt(const Expr *e, int64_t &out);

/// Evaluate a constant real expression (integer and real literals, + - * /
/// and unary minus); nullopt if it is not constant or divides by zero.
std::optional<double> evalConstReal(const Expr *e);

} // namespace netlift::net

#endif
