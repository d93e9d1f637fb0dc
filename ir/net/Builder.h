//===- Builder.h - constructing NetIR ---------------------------*- C++ -*-===//
//
// The API every frontend and pass uses to create NetIR: it allocates names,
// arcs and expression nodes in the Design's arena and keeps the module's
// symbol table up to date. It does not judge what it is given — a name
// declared twice keeps its first meaning and the verifier reports the
// redefinition — so frontends can build first and verify once.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_BUILDER_H
#define NETLIFT_IR_NET_BUILDER_H

#include "ir/net/Module.h"

namespace netlift::net {

class Builder {
public:
  explicit Builder(Design &d) : design(d) {}

  Design &getDesign() { return design; }
  /// Creates a module and makes it current; null if the name is taken.
  Module *createModule(llvm::StringRef name, bool isSystem = false,
                       llvm::SMLoc loc = {});
  void setModule(Module *m) { mod = m; }
  Module *getModule() const { return mod; }

  // Entities (in the current module). Each returns its index.
  uint32_t addPort(llvm::StringRef name, PortKind kind, PortDir dir,
                   const Type *type = nullptr, llvm::SMLoc loc = {});
  uint32_t addPlace(llvm::StringRef name, uint32_t tokens = 0,
                    uint32_t capacity = 1, llvm::SMLoc loc = {});
  uint32_t addTransition(llvm::StringRef name, llvm::ArrayRef<PreArc> pre,
                         llvm::ArrayRef<PostArc> post, llvm::SMLoc loc = {});
  uint32_t addVar(llvm::StringRef name, const Type *type, Expr *init = nullptr,
                  llvm::SMLoc loc = {});
  uint32_t addInstance(llvm::StringRef name, llvm::StringRef moduleName,
                       llvm::SMLoc loc = {});
  void addConnection(Endpoint from, Endpoint to, llvm::SMLoc loc = {});
  /// Attaches `key = value` to `target` (see Attribute; empty: the module).
  void addAttribute(llvm::StringRef target, llvm::StringRef key,
                    llvm::StringRef value, llvm::SMLoc loc = {});
  void addInvariant(uint32_t place, llvm::ArrayRef<Expr *> conditions,
                    llvm::SMLoc loc = {});
  void addFlow(uint32_t place, llvm::ArrayRef<Flow::Equation> eqs,
               llvm::SMLoc loc = {});

  // Transition parts.
  TransitionExtras &extras(uint32_t t);
  void setConds(uint32_t t, llvm::ArrayRef<Expr *> conds);
  void setEvents(uint32_t t, llvm::ArrayRef<EventSource> events,
                 EventMode mode = EventMode::Or);
  void setEmits(uint32_t t, llvm::ArrayRef<uint32_t> ports);
  void setGuard(uint32_t t, Expr *guard);
  void setAction(uint32_t t, llvm::ArrayRef<Stmt *> body);
  void setUrgent(uint32_t t, bool urgent = true);

  // Expressions and statements.
  Expr *intLit(int64_t v, llvm::SMLoc loc = {});
  Expr *boolLit(bool v, llvm::SMLoc loc = {});
  Expr *realLit(double v, llvm::SMLoc loc = {});
  Expr *stringLit(llvm::ArrayRef<char16_t> chars, llvm::SMLoc loc = {});
  Expr *ref(llvm::StringRef name, llvm::SMLoc loc = {});
  Expr *unary(UnaryOp op, Expr *a, llvm::SMLoc loc = {});
  Expr *binary(BinaryOp op, Expr *a, Expr *b, llvm::SMLoc loc = {});
  Expr *cond(Expr *c, Expr *a, Expr *b, llvm::SMLoc loc = {});
  Expr *index(Expr *base, Expr *idx, llvm::SMLoc loc = {});
  Expr *field(Expr *base, llvm::StringRef f, llvm::SMLoc loc = {});
  /// `to`: the target type of Builtin::Convert (else null).
  Expr *call(Builtin fn, llvm::ArrayRef<Expr *> args, llvm::SMLoc loc = {},
             const Type *to = nullptr);
  /// `to(a)`: a conversion to a PLC integer, a float or a string type.
  Expr *convert(const Type *to, Expr *a, llvm::SMLoc loc = {});
  /// An array's (no names) or a record's (one name per field) initial
  /// value.
  Expr *aggregate(llvm::ArrayRef<Expr *> elems,
                  llvm::ArrayRef<llvm::StringRef> fieldNames,
                  llvm::SMLoc loc = {});
  Stmt *assign(Expr *target, Expr *value, llvm::SMLoc loc = {});
  Stmt *ifStmt(llvm::ArrayRef<IfArm> arms, bool hasElse,
               llvm::ArrayRef<Stmt *> elseBody, llvm::SMLoc loc = {});
  Stmt *caseStmt(Expr *sel, llvm::ArrayRef<CaseArm> arms, bool hasElse,
                 llvm::ArrayRef<Stmt *> elseBody, llvm::SMLoc loc = {});
  Stmt *forStmt(llvm::StringRef var, Expr *lo, Expr *hi,
                llvm::ArrayRef<Stmt *> body, llvm::SMLoc loc = {});
  /// `while c { body }`, or with `testAfter` `repeat { body } until c;`.
  Stmt *whileStmt(Expr *c, llvm::ArrayRef<Stmt *> body, bool testAfter,
                  llvm::SMLoc loc = {});

private:
  Design &design;
  Module *mod = nullptr;
};

} // namespace netlift::net

#endif
