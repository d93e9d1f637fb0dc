//===- SemanticsImpl.h - the interpreter behind Semantics -------*- C++ -*-===//
//
// Internal to ir/semantics: the state of one Semantics object and the
// interpreter that computes its successors, shared by Semantics.cpp (the
// step rule: enabling, steps, firing, ticks) and InputSplitting.cpp (free
// inputs split into classes on demand, docs/semantics.md). Semantics.h is
// the API.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_SEMANTICSIMPL_H
#define NETLIFT_ENGINE_SEMANTICSIMPL_H

#include "engine/InputSplitter.h"
#include "engine/PtKernel.h"
#include "engine/Semantics.h"
#include "ir/net/FloatOps.h"
#include "ir/net/Printer.h"
#include "ir/net/ScalarOps.h"
#include "ir/net/StringOps.h"
#include "ir/support/Budget.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/SmallVector.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <vector>

namespace netlift::sem {
namespace detail {
using namespace netlift::net;
using llvm::cast;
/// A step: the transitions firing together (a handful: kept inline).
using Step = llvm::SmallVector<uint32_t, 8>;

/// Thrown inside the interpreter; turned into a RuntimeError at the API.
struct EvalError {
  std::string message;
  llvm::SMLoc loc;
  bool limit = false;
  /// The innermost statement running when it happened (set by exec).
  llvm::SMLoc statement;
  /// "time" or "memory": the run's budget was spent (Budget.h).
  const char *budget = nullptr;
};

/// Every maximal subset of `cand` (kept in `cand` order) that `fits`
/// accepts. `fits` must be monotone: a subset of a fitting set fits.
std::vector<std::vector<uint32_t>>
maximalSubsets(const std::vector<uint32_t> &cand,
               const std::function<bool(const std::vector<uint32_t> &)> &fits);
} // namespace detail

using namespace detail;

struct Semantics::Impl {
  Impl(const Module &m, const StateLayout &L, const Options &o)
      : m(m), L(L), opts(o) {}
  const Module &m;
  const StateLayout &L;
  const Options &opts;

  // Static information.
  std::vector<uint32_t> spontaneous, forcedList;
  std::vector<uint32_t> inputSlots;  // cond/data input leaves
  std::vector<uint32_t> eventInputs; // event input port indices
  std::vector<uint32_t> clockVarSlots;
  std::vector<int32_t> eventInputIndex; // port -> position in eventInputs
  // fixInputs(): one valuation instead of all of them.
  bool inputsFixed = false;
  // recordExecution(): the log of the step being fired.
  bool recording = false;
  Semantics::ExecutionLog log;
  llvm::SMLoc assigning; // the assignment store() writes for
  std::vector<int64_t> fixedLeaves;
  std::vector<uint8_t> fixedPresent;
  /// The compiled successor function, when the module is a plain P/T net.
  std::unique_ptr<PtKernel> kernel;
  /// Options::scanResets off: the end-of-scan resets not run.
  llvm::DenseSet<const Stmt *> skipped;
  /// The run's time and memory (setBudget), checked inside one expansion.
  Budget *budget = nullptr;
  void checkBudget() {
    if (!budget)
      return;
    if (const char *what = budget->spent())
      throw EvalError{std::string("the ") + what + " limit was reached",
                      {},
                      true,
                      {},
                      what};
  }

  // Per-state working data.
  std::vector<int64_t> vals; // all slots: packed state, then inputs
  std::vector<char> present; // per event input position
  std::vector<char> en;      // per transition
  std::vector<int64_t> loopVals;

  // --- Free inputs split on demand (InputSplitting.cpp) -------------------
  /// How an input leaf's values are ordered: its keys are int64 in that
  /// order (a float's bits mapped so that keys compare as the numbers do,
  /// NaN above +inf; a uint64's bits with the sign bit flipped).
  enum class KeyKind : uint8_t { Signed, Unsigned64, Float32, Float64 };
  struct InputLeaf {
    KeyKind keys;
    int64_t lo, hi; // the whole domain, as keys
  };
  std::vector<InputLeaf> leaves; // leaf k is held in slot inputSlots[k]
  /// The current class: each leaf's interval of keys.
  std::vector<int64_t> dlo, dhi;
  /// Leaves whose interval holds more than one value (0: nothing to split;
  /// also 0 outside successors() and with --inputs=enumerate).
  uint32_t unsplit = 0;
  /// What an expression reads of the inputs: one leaf (`leaf` >= 0), which
  /// it designates (`identity`) or computes monotonically from with
  /// input-free operands (`chain`: + - * / by constants, negation, numeric
  /// conversions, when they neither fail nor wrap where it is evaluated),
  /// and whether every read of it is in a chain compared with an input-free
  /// value (`cuttable`: those comparisons' values are all the expression
  /// depends on). Expressions that read no input are absent; several
  /// leaves: leaf == -2.
  struct InputUse {
    int32_t leaf = -1;
    bool identity = false;
    bool chain = false;
    bool cuttable = false;
  };
  llvm::DenseMap<const Expr *, InputUse> inputUse;
  InputSplitter splitter;
  /// Classes the last successors() call ran.
  uint64_t classes = 1;
  /// A class as a box: per leaf, then per event input, its interval (keys;
  /// an event 0..1).
  using ClassBox = std::vector<std::pair<int64_t, int64_t>>;
  /// --edge-labels inputs: per emitted record, the classes that took it;
  /// the condition of the edge being reported.
  std::vector<std::vector<ClassBox>> recordClasses;
  std::string edgeCond;
  ClassBox currentClass() const;
  /// The classes of one edge, merged where two differ in one input by
  /// neighbouring intervals, written as a condition on the inputs.
  std::string conditionText(std::vector<ClassBox> boxes) const;
  /// Where each leaf was last decided (for the message when a step has
  /// too many classes).
  std::vector<llvm::SMLoc> decidedAt;
  /// A step ran --max-input-classes classes and has more: the inputs
  /// whose values it tells apart, named.
  [[noreturn]] void tooManyClasses();

  static int64_t keyOf(KeyKind k, int64_t value);
  static int64_t valueOf(KeyKind k, int64_t key);
  void analyseInputUses();
  InputUse analyseUse(const Expr *e);
  /// Before each execution of a class: every leaf at its whole domain
  /// (those the last class narrowed are reset).
  void startClass();
  /// Every leaf at its whole domain, its value where it has one.
  void resetLeaves();
  std::vector<uint32_t> narrowed;
  std::vector<char> isNarrowed;
  uint32_t wholeUnsplit = 0;
  /// Narrows leaf `k` to [lo, hi]; a single value is written where the
  /// interpreter reads it.
  void narrow(uint32_t k, int64_t lo, int64_t hi);
  int64_t splitEval(const Expr *e, const InputUse &u,
                    const std::vector<int64_t> &v);
  /// The input leaf held in `slot`, or -1.
  std::vector<int32_t> leafBySlot;
  int32_t leafOfSlot(uint32_t slot) const {
    return slot < L.numPacked() ? -1 : leafBySlot[slot - L.numPacked()];
  }
  bool splitCase(const CaseStmt *c, const std::vector<int64_t> &v,
                 int32_t &arm);
  /// Slots [first, first + n) are read as values: the input leaves among
  /// them not yet known are decided value by value.
  void readInputs(uint32_t first, uint32_t n, const Expr *at) {
    if (unsplit && first + n > L.numPacked())
      decideValues(first, n, at);
  }
  void decideValues(uint32_t first, uint32_t n, const Expr *at);

  void unpack(const uint64_t *state) {
    for (uint32_t s = 0; s < L.numPacked(); ++s)
      vals[s] = L.get(state, s);
  }
  void pack(const std::vector<int64_t> &v, uint64_t *out) const {
    std::fill(out, out + L.numWords(), 0);
    for (uint32_t s = 0; s < L.numPacked(); ++s)
      L.set(out, s, v[s]);
  }

  // --- Expressions ------------------------------------------------------
  [[noreturn]] void fail(const Expr *e, const std::string &msg) const {
    throw EvalError{msg, e ? e->loc : llvm::SMLoc()};
  }
  /// First slot of the storage an expression designates; -1 when it
  /// designates none (a defined output, a literal...).
  int64_t slotOf(const Expr *e, const std::vector<int64_t> &v) {
    switch (e->getKind()) {
    case ExprKind::Ref:
      return L.refSlot(cast<Ref>(e));
    case ExprKind::Index: {
      auto *x = cast<IndexExpr>(e);
      int64_t base = slotOf(x->base, v);
      if (base < 0)
        fail(e, "cannot index '" + exprToString(x->base) + "'");
      const Type *at = x->base->type;
      int64_t i = eval(x->index, v);
      if (i < at->indexLo || i > at->indexHi)
        fail(x->index, "index " + std::to_string(i) + " is outside " +
                           std::to_string(at->indexLo) + ".." +
                           std::to_string(at->indexHi) + " of '" +
                           exprToString(x->base) + "'");
      return base + (i - at->indexLo) * StateLayout::slotsOf(at->elem);
    }
    case ExprKind::Field: {
      auto *f = cast<FieldExpr>(e);
      int64_t base = slotOf(f->base, v);
      if (base < 0)
        fail(e, "cannot select a field of '" + exprToString(f->base) + "'");
      return base + StateLayout::fieldOffset(f->base->type, f->fieldIndex);
    }
    default:
      return -1;
    }
  }

  int64_t eval(const Expr *e, const std::vector<int64_t> &v) {
    // An expression of one input not yet known in this class: decided
    // (split) here, before its operands are evaluated.
    if (unsplit) {
      auto it = inputUse.find(e);
      if (it != inputUse.end() && it->second.leaf >= 0 &&
          dlo[it->second.leaf] != dhi[it->second.leaf])
        return splitEval(e, it->second, v);
    }
    switch (e->getKind()) {
    case ExprKind::IntLit:
      return cast<IntLit>(e)->value;
    case ExprKind::BoolLit:
      return cast<BoolLit>(e)->value;
    case ExprKind::RealLit:
      if (e->type && e->type->isFloat())
        return floatBits(e->type->width, cast<RealLit>(e)->value);
      fail(e, "real arithmetic is not part of the discrete semantics");
    case ExprKind::Aggregate: // only initial values, flattened there
      fail(e, "an aggregate is not a scalar value");
    case ExprKind::StringLit:
      fail(e, "a string is not a scalar value");
    case ExprKind::Ref: {
      auto *r = cast<Ref>(e);
      switch (r->sym.kind) {
      case SymKind::Place: {
        // A place is "marked", or its token count where a property
        // compares it with numbers (the verifier typed it so).
        int64_t tokens = v[L.markingSlot(r->sym.index)];
        return r->type && !r->type->isBool() ? tokens : tokens > 0;
      }
      case SymKind::EnumLit:
        return r->sym.index;
      case SymKind::LoopVar:
        return loopVals[r->sym.index];
      case SymKind::Port: {
        const Port &p = m.ports[r->sym.index];
        if (p.definition && r->fields.empty())
          return eval(p.definition, v);
        break;
      }
      default:
        break;
      }
      int64_t s = slotOf(e, v);
      if (s < 0)
        fail(e, "'" + r->name.str() + "' has no value here");
      readInputs(uint32_t(s), 1, e);
      return v[s];
    }
    case ExprKind::Index:
    case ExprKind::Field: {
      int64_t s = slotOf(e, v);
      if (s < 0)
        fail(e, "'" + exprToString(e) + "' has no value here");
      readInputs(uint32_t(s), 1, e);
      return v[s];
    }
    case ExprKind::Unary: {
      auto *u = cast<UnaryExpr>(e);
      int64_t a = eval(u->operand, v), r;
      if (e->type && e->type->isFloat())
        return applyFloatNeg(e->type->width, a);
      if (OpError err = applyUnary(u, a, r); err != OpError::None)
        fail(e, opErrorMessage(err, e, 0));
      return r;
    }
    case ExprKind::Binary:
      return evalBinary(cast<BinaryExpr>(e), v);
    case ExprKind::Cond: {
      auto *c = cast<CondExpr>(e);
      return eval(c->cond, v) ? eval(c->thenExpr, v) : eval(c->elseExpr, v);
    }
    case ExprKind::Call:
      return evalCall(cast<CallExpr>(e), v);
    }
    return 0;
  }

  /// The value of a string-typed expression.
  StringValue evalStr(const Expr *e, const std::vector<int64_t> &v) {
    switch (e->getKind()) {
    case ExprKind::StringLit: {
      auto *l = cast<StringLit>(e);
      return StringValue(l->chars.begin(), l->chars.end());
    }
    case ExprKind::Cond: {
      auto *c = cast<CondExpr>(e);
      return eval(c->cond, v) ? evalStr(c->thenExpr, v)
                              : evalStr(c->elseExpr, v);
    }
    case ExprKind::Call: {
      auto *c = cast<CallExpr>(e);
      if (c->fn == Builtin::Convert) {
        const Type *from = c->args[0]->type;
        StringValue text = from->isString()
                               ? evalStr(c->args[0], v)
                               : scalarToString(from, eval(c->args[0], v));
        text.resize(std::min<size_t>(text.size(), c->to->maxLen));
        if (!c->to->isWideString())
          for (char16_t &ch : text)
            ch &= 0xff; // wstring to string keeps the low 8 bits
        return text;
      }
      llvm::SmallVector<StringValue, 2> strs;
      llvm::SmallVector<int64_t, 2> ints;
      for (const Expr *a : c->args) {
        if (a->type->isString())
          strs.push_back(evalStr(a, v));
        else
          ints.push_back(eval(a, v));
      }
      StringValue out;
      if (auto err = applyStringBuiltin(c->fn, strs, ints, out))
        fail(c, "'" + exprToString(c) + "': " + *err);
      // A character written over the terminator of a full string would
      // not fit it: memory past the string.
      if (c->fn == Builtin::WithCode && out.size() > c->args[0]->type->maxLen)
        fail(c, "'" + exprToString(c) + "': writes past the " +
                    std::to_string(c->args[0]->type->maxLen) +
                    " characters of the string");
      return out;
    }
    case ExprKind::Ref:
      if (auto *r = cast<Ref>(e); r->sym.kind == SymKind::Port &&
                                  m.ports[r->sym.index].definition &&
                                  r->fields.empty())
        return evalStr(m.ports[r->sym.index].definition, v);
      [[fallthrough]];
    default: {
      int64_t s = slotOf(e, v);
      if (s < 0)
        fail(e, "'" + exprToString(e) + "' has no value here");
      return StringValue(v.begin() + s + 1, v.begin() + s + 1 + v[s]);
    }
    }
  }

  int64_t evalCall(const CallExpr *c, const std::vector<int64_t> &v) {
    if (c->fn == Builtin::Len)
      return int64_t(evalStr(c->args[0], v).size());
    if (c->fn == Builtin::Find)
      return findString(evalStr(c->args[0], v), evalStr(c->args[1], v));
    if (c->fn == Builtin::Code) {
      int64_t code = 0;
      if (auto err = codeAt(evalStr(c->args[0], v), eval(c->args[1], v), code))
        fail(c, "'" + exprToString(c) + "': " + *err);
      return code;
    }
    if (isStringBuiltin(c->fn) && c->args[0]->type->isString()) {
      // parse_duration, parse_date, parse_tod, parse_dt
      StringValue text = evalStr(c->args[0], v);
      int64_t ns = 0;
      if (auto err = parseTimeText(c->fn, text, ns))
        fail(c, "'" + exprToString(c) + "': " + *err);
      return ns;
    }
    const Type *at = c->args[0]->type;
    if (c->fn == Builtin::Convert && at->isString()) {
      StringValue text = evalStr(c->args[0], v);
      int64_t r = 0;
      ConvertError err = stringToScalar(text, c->to, r);
      if (err != ConvertError::None)
        fail(c, "'" + exprToString(c) +
                    "': " + formatStringLiteral({text.data(), text.size()}) +
                    (err == ConvertError::NotANumber
                         ? " is not a literal of " + calleeSpelling(c)
                         : " is outside the range of " + calleeSpelling(c)));
      return r;
    }
    int64_t a = eval(c->args[0], v), r;
    int64_t b = c->args.size() > 1 ? eval(c->args[1], v) : 0;
    if (c->fn == Builtin::Convert || c->fn == Builtin::Trunc) {
      ConvertError err = c->fn == Builtin::Trunc
                             ? truncToInteger(at->width, a, r)
                             : convertValue(at, c->to, a, r);
      if (err != ConvertError::None)
        fail(c, "'" + exprToString(c) + "': " + formatScalar(at, a) +
                    (err == ConvertError::NotANumber
                         ? " is not a number"
                         : " is outside the range of " +
                               (c->fn == Builtin::Trunc ? std::string("int64")
                                                        : calleeSpelling(c))));
      return r;
    }
    switch (c->fn) {
    case Builtin::Bits: // a float is held as its bits (NaN canonical)
      return a;
    case Builtin::Real32FromBits:
      return floatBits(32, floatValue(32, a & 0xFFFFFFFF));
    case Builtin::Real64FromBits:
      return floatBits(64, floatValue(64, a));
    default:
      break;
    }
    if (c->type && c->type->isFloat())
      return applyFloatBuiltin(c->fn, c->type->width, a, b);
    if (OpError err = applyBuiltin(c, a, b, r); err != OpError::None)
      fail(c, opErrorMessage(err, c, 0));
    return r;
  }

  bool aggregateEqual(const Expr *a, const Expr *b,
                      const std::vector<int64_t> &v) {
    int64_t sa = slotOf(a, v), sb = slotOf(b, v);
    if (sa < 0 || sb < 0)
      fail(a, "comparing these aggregate values is not supported");
    uint32_t n = StateLayout::slotsOf(a->type);
    readInputs(uint32_t(sa), n, a);
    readInputs(uint32_t(sb), n, b);
    for (uint32_t i = 0; i < n; ++i)
      if (v[sa + i] != v[sb + i])
        return false;
    return true;
  }

  int64_t evalBinary(const BinaryExpr *b, const std::vector<int64_t> &v) {
    switch (b->op) {
    case BinaryOp::And:
      return eval(b->lhs, v) && eval(b->rhs, v);
    case BinaryOp::Or:
      return eval(b->lhs, v) || eval(b->rhs, v);
    case BinaryOp::Eq:
    case BinaryOp::Ne:
    case BinaryOp::Lt:
    case BinaryOp::Le:
    case BinaryOp::Gt:
    case BinaryOp::Ge:
      if (b->lhs->type && b->lhs->type->isString())
        return compareStrings(b->op, evalStr(b->lhs, v), evalStr(b->rhs, v));
      if (isComparison(b->op) && b->lhs->type && !b->lhs->type->isScalar()) {
        bool eq = aggregateEqual(b->lhs, b->rhs, v);
        return b->op == BinaryOp::Eq ? eq : !eq;
      }
      break;
    default:
      break;
    }
    int64_t x = eval(b->lhs, v), y = eval(b->rhs, v), r;
    if (b->lhs->type && b->lhs->type->isFloat())
      return applyFloatBinary(b->op, b->lhs->type->width, x, y);
    if (OpError err = applyBinary(b, x, y, r); err != OpError::None)
      fail(b, opErrorMessage(err, b, y));
    return r;
  }

  // --- Actions ------------------------------------------------------------
  /// Loop iterations of the firing being executed, and its transition.
  uint64_t iterations = 0;
  uint32_t firing = 0;
  /// The watchdog: a firing may run at most opts.maxLoopIterations loop
  /// iterations, all loops counted together, as a PLC's watchdog bounds
  /// the time of one scan.
  void countIteration(const Stmt *loop) {
    if ((iterations & 1023) == 1023)
      checkBudget();
    if (++iterations > opts.maxLoopIterations)
      throw EvalError{
          "watchdog: transition '" + m.transitions[firing].name.str() +
              "' ran more than " + std::to_string(opts.maxLoopIterations) +
              " loop iterations in one firing "
              "(--max-loop-iterations)",
          loop->loc};
  }
  void store(const Expr *target, uint32_t slot, int64_t value,
             std::vector<int64_t> &v, std::vector<uint32_t> &written) {
    const Slot &s = L.slots()[slot];
    if (value < s.lo || value > s.hi) {
      if (!s.wrap)
        fail(target, "value " + std::to_string(value) + " is outside " +
                         std::to_string(s.lo) + ".." + std::to_string(s.hi) +
                         " of '" + s.name + "'");
      uint64_t span = uint64_t(s.hi) - uint64_t(s.lo) + 1;
      uint64_t off = uint64_t(value) - uint64_t(s.lo);
      value = span == 0 ? value : int64_t(uint64_t(s.lo) + off % span);
    }
    v[slot] = value;
    written.push_back(slot);
    if (recording)
      log.writes.push_back({slot, assigning});
  }

  /// Writes a string into the slots of a variable of type `t` at `slot`:
  /// its length, then its characters, cut to the variable's length, the
  /// unused characters zero (so equal strings are equal states).
  void storeStr(const Expr *target, uint32_t slot, const Type *t,
                const StringValue &str, std::vector<int64_t> &v,
                std::vector<uint32_t> &written) {
    size_t n = std::min<size_t>(str.size(), t->maxLen);
    store(target, slot, int64_t(n), v, written);
    for (uint32_t i = 0; i < t->maxLen; ++i)
      store(target, slot + 1 + i, i < n ? int64_t(str[i]) : 0, v, written);
  }

  void exec(Block block, std::vector<int64_t> &v,
            std::vector<uint32_t> &written) {
    for (const Stmt *st : block) {
      if (!skipped.empty() && skipped.count(st))
        continue;
      try {
        execStmt(st, v, written);
      } catch (EvalError &e) {
        // Said with the error: an expression read from NetIR text points
        // into the .net, its statement into the program it came from.
        if (!e.statement.isValid())
          e.statement = st->loc;
        throw;
      }
    }
  }

  void execStmt(const Stmt *st, std::vector<int64_t> &v,
                std::vector<uint32_t> &written) {
    if (recording) {
      log.statements.push_back(st->loc);
      assigning = st->loc;
    }
    switch (st->getKind()) {
    case StmtKind::Assign: {
      auto *a = cast<AssignStmt>(st);
      int64_t slot = slotOf(a->target, v);
      if (slot < 0)
        fail(a->target, "'" + exprToString(a->target) + "' has no storage");
      if (a->target->type->isString()) {
        storeStr(a->target, uint32_t(slot), a->target->type,
                 evalStr(a->value, v), v, written);
      } else if (!a->target->type->isScalar()) {
        int64_t src = slotOf(a->value, v);
        if (src < 0)
          fail(a->value, "assigning this aggregate value is not supported");
        uint32_t n = StateLayout::slotsOf(a->target->type);
        readInputs(uint32_t(src), n, a->value);
        std::vector<int64_t> tmp(v.begin() + src, v.begin() + src + n);
        for (uint32_t i = 0; i < n; ++i)
          store(a->target, uint32_t(slot + i), tmp[i], v, written);
      } else {
        store(a->target, uint32_t(slot), eval(a->value, v), v, written);
      }
      break;
    }
    case StmtKind::If: {
      auto *i = cast<IfStmt>(st);
      bool done = false;
      for (const IfArm &arm : i->arms)
        if (eval(arm.cond, v)) {
          exec(arm.body, v, written);
          done = true;
          break;
        }
      if (!done)
        exec(i->elseBody, v, written);
      break;
    }
    case StmtKind::Case: {
      auto *c = cast<CaseStmt>(st);
      if (unsplit) {
        // A selector of one input not yet known: the class splits by
        // the arm taken, not by the selector's value.
        int32_t arm = 0;
        if (splitCase(c, v, arm)) {
          exec(arm < 0 ? c->elseBody : c->arms[arm].body, v, written);
          break;
        }
      }
      int64_t sel = eval(c->selector, v);
      bool done = false;
      for (const CaseArm &arm : c->arms) {
        for (const CaseLabel &l : arm.labels) {
          int64_t lo = eval(l.lo, v);
          int64_t hi = l.hi ? eval(l.hi, v) : lo;
          if (sel >= lo && sel <= hi) {
            done = true;
            break;
          }
        }
        if (done) {
          exec(arm.body, v, written);
          break;
        }
      }
      if (!done)
        exec(c->elseBody, v, written);
      break;
    }
    case StmtKind::For: {
      auto *f = cast<ForStmt>(st);
      int64_t lo = eval(f->lo, v), hi = eval(f->hi, v);
      loopVals.push_back(0);
      for (int64_t i = lo; i <= hi; ++i) {
        countIteration(st);
        loopVals.back() = i;
        exec(f->body, v, written);
        if (i == INT64_MAX)
          break;
      }
      loopVals.pop_back();
      break;
    }
    case StmtKind::While: {
      auto *w = cast<WhileStmt>(st);
      if (w->testAfter) {
        do {
          countIteration(st);
          exec(w->body, v, written);
        } while (!eval(w->cond, v));
      } else {
        while (eval(w->cond, v)) {
          countIteration(st);
          exec(w->body, v, written);
        }
      }
      break;
    }
    }
  }

  // --- Enabling -----------------------------------------------------------
  bool enabled(uint32_t ti) {
    const Transition &t = m.transitions[ti];
    for (const PreArc &a : t.pre()) {
      int64_t tokens = vals[L.markingSlot(a.place)];
      if (tokens < a.weight)
        return false;
      if (!a.time.isTrivial()) {
        int64_t c = vals[L.clockSlot(a.place)];
        if (c < a.time.lo || (a.time.hi != kInf && c > a.time.hi))
          return false;
      }
    }
    for (const PostArc &a : t.post()) {
      uint32_t cap = m.places[a.place].capacity;
      if (cap == kInf)
        continue; // an overflow of the encoding is reported when firing
      int64_t after = vals[L.markingSlot(a.place)] + a.weight;
      for (const PreArc &p : t.pre())
        if (p.place == a.place)
          after -= p.weight;
      if (after > cap)
        return false;
    }
    for (const Expr *c : t.conds())
      if (!eval(c, vals))
        return false;
    if (const Expr *g = t.guard())
      if (!eval(g, vals))
        return false;
    return true;
  }

  /// Are all transitions of `set` enabled together (token demand and
  /// capacities summed)?
  bool jointlyEnabled(llvm::ArrayRef<uint32_t> set) {
    llvm::SmallDenseMap<uint32_t, int64_t, 16> delta, demand;
    for (uint32_t ti : set) {
      const Transition &t = m.transitions[ti];
      for (const PreArc &a : t.pre()) {
        demand[a.place] += a.weight;
        delta[a.place] -= a.weight;
      }
      for (const PostArc &a : t.post())
        delta[a.place] += a.weight;
    }
    for (auto &[p, d] : demand)
      if (vals[L.markingSlot(p)] < d)
        return false;
    for (auto &[p, d] : delta) {
      uint32_t cap = m.places[p].capacity;
      if (cap != kInf && vals[L.markingSlot(p)] + d > cap)
        return false;
    }
    return true;
  }

  bool eventEnabled(uint32_t ti, const std::vector<char> &inStep) {
    const Transition &t = m.transitions[ti];
    bool any = false, all = true;
    for (const EventSource &s : t.events()) {
      bool fires = s.fromPort ? present[eventInputIndex[s.index]] != 0
                              : inStep[s.index] != 0;
      any |= fires;
      all &= fires;
    }
    return t.mode == EventMode::And ? all : any;
  }

  /// Adds every closure of `step` under forced transitions to `out`.
  void closure(Step step, llvm::SmallVectorImpl<Step> &out) {
    if (forcedList.empty()) {
      out.push_back(std::move(step));
      return;
    }
    // inStep is all zero between calls: set for this step, cleared before
    // recursing.
    inStep.resize(m.transitions.size(), 0);
    for (uint32_t t : step)
      inStep[t] = 1;
    std::vector<uint32_t> cand;
    Step with(step);
    for (uint32_t f : forcedList) {
      if (inStep[f] || !en[f] || !eventEnabled(f, inStep))
        continue;
      with.push_back(f);
      if (jointlyEnabled(with))
        cand.push_back(f);
      with.pop_back();
    }
    for (uint32_t t : step)
      inStep[t] = 0;
    if (cand.empty()) {
      out.push_back(std::move(step));
      return;
    }
    // Every maximal subset of the candidates that fits with the step; the
    // common case is that all of them fit together (no conflict).
    with.append(cand.begin(), cand.end());
    if (jointlyEnabled(with)) {
      closure(std::move(with), out);
      return;
    }
    std::vector<std::vector<uint32_t>> maximal =
        maximalSubsets(cand, [&](const std::vector<uint32_t> &chosen) {
          Step w(step);
          w.append(chosen.begin(), chosen.end());
          return jointlyEnabled(w);
        });
    for (auto &mx : maximal) {
      Step next(step);
      next.append(mx.begin(), mx.end());
      closure(std::move(next), out);
    }
  }
  std::vector<char> inStep;

  // --- Firing -------------------------------------------------------------
  /// The packed pre-state of the current successors() call.
  const uint64_t *cur = nullptr;
  std::vector<uint32_t> touchedList;
  std::vector<char> touched;

  /// Fires a step: starts from the packed pre-state and changes only what
  /// the step touches, so the cost is that of its arcs and actions.
  void fire(llvm::ArrayRef<uint32_t> step, uint64_t *out) {
    if (recording) {
      log.statements.clear();
      log.writes.clear();
    }
    std::copy(cur, cur + L.numWords(), out);
    touched.resize(m.places.size(), 0);
    touchedList.clear();
    auto touch = [&](uint32_t p) {
      if (!touched[p]) {
        touched[p] = 1;
        touchedList.push_back(p);
      }
    };
    for (uint32_t ti : step) {
      const Transition &t = m.transitions[ti];
      for (const PreArc &a : t.pre())
        touch(a.place);
      for (const PostArc &a : t.post())
        touch(a.place);
    }
    for (uint32_t p : touchedList) {
      touched[p] = 0;
      uint32_t slot = L.markingSlot(p);
      int64_t tokens = vals[slot];
      for (uint32_t ti : step) {
        const Transition &t = m.transitions[ti];
        for (const PreArc &a : t.pre())
          if (a.place == p)
            tokens -= a.weight;
        for (const PostArc &a : t.post())
          if (a.place == p)
            tokens += a.weight;
      }
      if (tokens > L.slotMax(slot))
        throw EvalError{"place '" + m.places[p].name.str() + "' would hold " +
                            std::to_string(tokens) + " tokens, more than the " +
                            std::to_string(L.slotMax(slot)) +
                            " its encoding allows (unbounded place; raise "
                            "--place-bits)",
                        m.places[p].loc};
      L.set(out, slot, tokens);
      if (L.clockSlot(p) >= 0)
        L.set(out, L.clockSlot(p), 0);
    }
    bool anyAction = false;
    for (uint32_t ti : step)
      anyAction |= m.transitions[ti].hasAction();
    if (!anyAction)
      return;
    // Actions read the pre-state; their writes land together.
    llvm::SmallDenseMap<uint32_t, std::pair<int64_t, uint32_t>, 8> writes;
    for (uint32_t ti : step) {
      const Transition &t = m.transitions[ti];
      if (!t.hasAction())
        continue;
      local = vals;
      written.clear();
      iterations = 0;
      firing = ti;
      exec(t.action(), local, written);
      std::sort(written.begin(), written.end());
      written.erase(std::unique(written.begin(), written.end()), written.end());
      for (uint32_t s : written) {
        auto [it, fresh] = writes.try_emplace(s, local[s], ti);
        if (!fresh)
          throw EvalError{"transitions '" +
                              m.transitions[it->second.second].name.str() +
                              "' and '" + t.name.str() + "' both write '" +
                              L.slots()[s].name + "' in one step",
                          t.loc};
      }
    }
    for (auto &[s, vw] : writes)
      L.set(out, s, vw.first);
  }
  std::vector<int64_t> local;
  std::vector<uint32_t> written;
  std::vector<uint32_t> spontScratch, stepScratch;

  /// The (step, successor) pairs one successors() call has emitted, to
  /// emit each once when several input valuations or closures lead to the
  /// same: flat records and an open-addressing index, both reused across
  /// calls (no allocation per state once warm).
  class EmittedSteps {
  public:
    void clear() {
      for (uint32_t i : used)
        index[i] = 0;
      used.clear();
      records.clear();
      starts.clear();
    }
    /// False when (step, succ) was emitted already.
    bool insert(llvm::ArrayRef<uint32_t> step, llvm::ArrayRef<uint64_t> succ) {
      uint64_t h = 0x9E3779B97F4A7C15ull * (step.size() + 1);
      auto mix = [&](uint64_t x) {
        h = (h ^ x) * 0xBF58476D1CE4E5B9ull;
        h ^= h >> 31;
      };
      for (uint32_t t : step)
        mix(t);
      for (uint64_t w : succ)
        mix(w);
      if ((starts.size() + 1) * 2 > index.size())
        rehash();
      size_t mask = index.size() - 1;
      size_t i = h & mask;
      for (; index[i]; i = (i + 1) & mask)
        if (same(index[i] - 1, step, succ)) {
          last = index[i] - 1;
          return false;
        }
      last = uint32_t(starts.size());
      starts.push_back(records.size());
      records.push_back(step.size());
      records.insert(records.end(), step.begin(), step.end());
      records.insert(records.end(), succ.begin(), succ.end());
      index[i] = starts.size();
      used.push_back(i);
      return true;
    }

    /// The record the last insert() found or added.
    uint32_t lastRecord() const { return last; }
    uint32_t size() const { return uint32_t(starts.size()); }
    /// Record r's step (into `step`) and successor words.
    const uint64_t *record(uint32_t r, llvm::SmallVectorImpl<uint32_t> &step) {
      const uint64_t *p = &records[starts[r]];
      step.assign(p + 1, p + 1 + p[0]);
      return p + 1 + p[0];
    }

  private:
    uint32_t last = 0;
    bool same(uint32_t r, llvm::ArrayRef<uint32_t> step,
              llvm::ArrayRef<uint64_t> succ) const {
      const uint64_t *p = &records[starts[r]];
      if (p[0] != step.size())
        return false;
      for (size_t k = 0; k < step.size(); ++k)
        if (p[1 + k] != step[k])
          return false;
      return std::equal(succ.begin(), succ.end(), p + 1 + step.size());
    }
    void rehash() {
      // Records are few per state: rebuilding by re-inserting is cheap.
      size_t n = std::max<size_t>(64, index.size() * 2);
      std::vector<uint64_t> old;
      old.swap(records);
      std::vector<uint32_t> oldStarts;
      oldStarts.swap(starts);
      index.assign(n, 0);
      used.clear();
      for (size_t r = 0; r < oldStarts.size(); ++r) {
        const uint64_t *p = &old[oldStarts[r]];
        size_t len = p[0];
        size_t end = r + 1 < oldStarts.size() ? oldStarts[r + 1] : old.size();
        llvm::SmallVector<uint32_t, 8> step(p + 1, p + 1 + len);
        insert(step, llvm::ArrayRef<uint64_t>(p + 1 + len, &old[0] + end));
      }
    }
    std::vector<uint64_t> records;     // [len, step..., succ...]...
    std::vector<uint32_t> starts;      // record r begins at starts[r]
    std::vector<uint32_t> index, used; // record + 1, or 0 when free
  };
  EmittedSteps emitted;

  /// The first valuation of the free inputs successors() tries (the only
  /// one when they are fixed).
  void resetInputs() {
    if (opts.splitInputs && !inputsFixed) {
      startClass();
      return;
    }
    for (size_t k = 0; k < inputSlots.size(); ++k)
      vals[inputSlots[k]] =
          inputsFixed ? fixedLeaves[k] : L.slots()[inputSlots[k]].lo;
    for (size_t e = 0; e < present.size(); ++e)
      present[e] = inputsFixed ? fixedPresent[e] : 0;
  }
  std::vector<int64_t> predicateVals;
  std::vector<uint64_t> succScratch;

  bool tick(uint64_t *out) {
    std::vector<int64_t> nv(vals.begin(), vals.begin() + L.numPacked());
    for (uint32_t p = 0; p < m.places.size(); ++p) {
      int32_t c = L.clockSlot(p);
      if (c < 0)
        continue;
      if (nv[L.markingSlot(p)] > 0)
        nv[c] = std::min<int64_t>(nv[c] + 1, L.clockCap(p));
      else
        nv[c] = 0;
    }
    for (uint32_t s : clockVarSlots)
      nv[s] = std::min<int64_t>(nv[s] + 1, L.slotMax(s));
    bool changed = false;
    for (uint32_t s = 0; s < L.numPacked() && !changed; ++s)
      changed = nv[s] != vals[s];
    if (changed)
      pack(nv, out);
    return changed;
  }
};

} // namespace netlift::sem

#endif
