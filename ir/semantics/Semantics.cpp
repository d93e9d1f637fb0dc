//===- Semantics.cpp - the step semantics of NetIR ------------------------===//
//
// A direct implementation of docs/semantics.md over unpacked valuations:
// clarity first, with the structure (precomputed arc lists, one valuation
// buffer reused across states, no allocation per enabled check) that the
// fast paths of later work keep.
//
//===----------------------------------------------------------------------===//
#include "ir/semantics/Semantics.h"

#include "ir/net/FloatOps.h"
#include "ir/net/ScalarOps.h"
#include "ir/net/StringOps.h"
#include "ir/semantics/PtKernel.h"

#include "ir/net/Printer.h"

#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/Hashing.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <set>

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::net;
using llvm::cast;

namespace {
/// A step: the transitions firing together (a handful: kept inline).
using Step = llvm::SmallVector<uint32_t, 8>;

/// Thrown inside the interpreter; turned into a RuntimeError at the API.
struct EvalError {
  std::string message;
  llvm::SMLoc loc;
};

/// Every maximal subset of `cand` (kept in `cand` order) that `fits`
/// accepts. `fits` must be monotone: a subset of a fitting set fits.
std::vector<std::vector<uint32_t>>
maximalSubsets(const std::vector<uint32_t> &cand,
               const std::function<bool(const std::vector<uint32_t> &)> &fits) {
  std::vector<std::vector<uint32_t>> maximal;
  std::vector<uint32_t> chosen;
  std::function<void(size_t)> choose = [&](size_t i) {
    if (i == cand.size()) {
      for (auto &mx : maximal)
        if (std::includes(mx.begin(), mx.end(), chosen.begin(), chosen.end()))
          return;
      // Drop earlier choices this one contains.
      maximal.erase(std::remove_if(maximal.begin(), maximal.end(),
                                   [&](const std::vector<uint32_t> &mx) {
                                     return std::includes(chosen.begin(),
                                                          chosen.end(),
                                                          mx.begin(), mx.end());
                                   }),
                    maximal.end());
      maximal.push_back(chosen);
      return;
    }
    chosen.push_back(cand[i]);
    if (fits(chosen))
      choose(i + 1);
    chosen.pop_back();
    choose(i + 1);
  };
  choose(0);
  return maximal;
}
} // namespace

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
  std::vector<int64_t> fixedLeaves;
  std::vector<uint8_t> fixedPresent;
  /// The compiled successor function, when the module is a plain P/T net.
  std::unique_ptr<PtKernel> kernel;

  // Per-state working data.
  std::vector<int64_t> vals; // all slots: packed state, then inputs
  std::vector<char> present; // per event input position
  std::vector<char> en;      // per transition
  std::vector<int64_t> loopVals;

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
      return v[s];
    }
    case ExprKind::Index:
    case ExprKind::Field: {
      int64_t s = slotOf(e, v);
      if (s < 0)
        fail(e, "'" + exprToString(e) + "' has no value here");
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
        if (same(index[i] - 1, step, succ))
          return false;
      starts.push_back(records.size());
      records.push_back(step.size());
      records.insert(records.end(), step.begin(), step.end());
      records.insert(records.end(), succ.begin(), succ.end());
      index[i] = starts.size();
      used.push_back(i);
      return true;
    }

  private:
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

Semantics::Semantics(const Module &mod, const StateLayout &layout, Options o)
    : m(mod), L(layout), opts(o), impl(std::make_shared<Impl>(m, L, opts)) {
  Impl &I = *impl;
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    (m.transitions[t].isForced() ? I.forcedList : I.spontaneous).push_back(t);
  I.eventInputIndex.assign(m.ports.size(), -1);
  for (uint32_t p = 0; p < m.ports.size(); ++p) {
    const Port &port = m.ports[p];
    if (!port.isInput())
      continue;
    if (port.kind == PortKind::Event) {
      I.eventInputIndex[p] = I.eventInputs.size();
      I.eventInputs.push_back(p);
    } else {
      uint32_t first = L.portSlot(p);
      for (uint32_t i = 0; i < StateLayout::slotsOf(port.type); ++i)
        I.inputSlots.push_back(first + i);
    }
  }
  for (uint32_t v = 0; v < m.vars.size(); ++v)
    if (m.vars[v].type->isClock()) {
      I.clockVarSlots.push_back(L.varSlot(v));
      timed = true;
    }
  for (uint32_t p = 0; p < m.places.size(); ++p)
    timed |= L.clockSlot(p) >= 0;
  I.kernel = PtKernel::compile(m, L, opts);
  I.vals.assign(L.numSlots(), 0);
  I.present.assign(I.eventInputs.size(), 0);
  I.en.assign(m.transitions.size(), 0);
}

bool Semantics::initialState(uint64_t *out, RuntimeError &err) const {
  Impl &I = *impl;
  std::vector<int64_t> v(L.numSlots(), 0);
  for (uint32_t s = 0; s < L.numSlots(); ++s)
    v[s] = L.slots()[s].initial; // false / 0 for PLC integers / low bound
  try {
    for (uint32_t p = 0; p < m.places.size(); ++p) {
      uint32_t s = L.markingSlot(p);
      if (m.places[p].tokens > L.slotMax(s))
        throw EvalError{"initial marking of '" + m.places[p].name.str() +
                            "' does not fit the encoding of an unbounded "
                            "place; raise --place-bits",
                        m.places[p].loc};
      v[s] = m.places[p].tokens;
    }
    std::vector<uint32_t> written;
    std::function<void(int32_t, const Type *, const Expr *)> init =
        [&](int32_t first, const Type *t, const Expr *e) {
          if (!e || first < 0)
            return;
          if (auto *agg = llvm::dyn_cast<AggregateLit>(e)) {
            // Elements and fields lie one after another in the layout.
            // (The verifier admits only aggregates for arrays and records.)
            for (size_t i = 0; i < agg->elems.size(); ++i) {
              const Type *et =
                  t->kind == TypeKind::Array ? t->elem : t->fields[i].type;
              init(first, et, agg->elems[i]);
              first += int32_t(StateLayout::slotsOf(et));
            }
            return;
          }
          if (t->isString())
            I.storeStr(e, uint32_t(first), t, I.evalStr(e, v), v, written);
          else
            I.store(e, uint32_t(first), I.eval(e, v), v, written);
        };
    for (uint32_t x = 0; x < m.vars.size(); ++x)
      init(L.varSlot(x), m.vars[x].type, m.vars[x].init);
    for (uint32_t p = 0; p < m.ports.size(); ++p)
      if (m.ports[p].isStored())
        init(L.portSlot(p), m.ports[p].type, m.ports[p].init);
  } catch (const EvalError &e) {
    err = {e.message, e.loc};
    return false;
  }
  I.pack(v, out);
  return true;
}

bool Semantics::successors(const uint64_t *state, Callback cb,
                           RuntimeError &err) {
  Impl &I = *impl;
  if (I.kernel) {
    I.succScratch.resize(L.numWords());
    if (I.kernel->successors(state, I.succScratch.data(),
                             [&](uint32_t t, const uint64_t *succ) {
                               cb(llvm::ArrayRef<uint32_t>(t), succ);
                             }))
      return true;
    // An overflow: the interpreter below reports it.
  }
  I.unpack(state);
  I.cur = state;
  uint64_t combos = uint64_t(1) << std::min<size_t>(I.eventInputs.size(), 63);
  if (I.inputsFixed)
    combos = 1;
  else
    for (uint32_t s : I.inputSlots) {
      uint64_t span = uint64_t(L.slots()[s].hi - L.slots()[s].lo) + 1;
      if (span == 0 || combos > opts.maxInputValuations / span) {
        err = {"the free inputs have more than " +
                   std::to_string(opts.maxInputValuations) +
                   " valuations per step; connect them or narrow their types",
               {}};
        return false;
      }
      combos *= span;
    }
  bool manyValuations = combos > 1;
  bool dedupe = manyValuations || !I.forcedList.empty() ||
                opts.policy == StepPolicy::Maximal;
  // The successor buffer is reused across states (no allocation per state).
  std::vector<uint64_t> &succ = I.succScratch;
  succ.resize(L.numWords());
  if (dedupe)
    I.emitted.clear();
  auto emit = [&](llvm::ArrayRef<uint32_t> step) {
    if (dedupe && !I.emitted.insert(step, succ))
      return;
    cb(step, succ.data());
  };
  I.resetInputs();
  bool tickAllowed = false;
  try {
    for (uint64_t n = 0; n < combos; ++n) {
      if (n > 0) {
        // Next valuation: an odometer over event inputs, then data inputs.
        bool carry = true;
        for (size_t e = 0; e < I.present.size() && carry; ++e) {
          I.present[e] ^= 1;
          carry = I.present[e] == 0;
        }
        for (size_t k = 0; k < I.inputSlots.size() && carry; ++k) {
          uint32_t s = I.inputSlots[k];
          if (I.vals[s] < L.slots()[s].hi) {
            ++I.vals[s];
            carry = false;
          } else {
            I.vals[s] = L.slots()[s].lo;
          }
        }
      }
      bool anyUrgent = false, strongBlocks = false;
      for (uint32_t t = 0; t < m.transitions.size(); ++t) {
        I.en[t] = I.enabled(t);
        if (!I.en[t])
          continue;
        const Transition &tr = m.transitions[t];
        anyUrgent |= tr.urgent;
        if (opts.timing == Timing::Strong)
          for (const PreArc &a : tr.pre())
            if (!a.time.isTrivial() && a.time.hi != kInf &&
                I.vals[L.clockSlot(a.place)] >= int64_t(a.time.hi))
              strongBlocks = true;
      }
      if (!anyUrgent && !strongBlocks)
        tickAllowed = true;

      // Seeds: spontaneous transitions by policy; present input events
      // may also start a step on their own.
      std::vector<uint32_t> &spont = I.spontScratch;
      spont.clear();
      for (uint32_t t : I.spontaneous)
        if (I.en[t])
          spont.push_back(t);
      // The common case (interleaving, no forced transitions): every
      // enabled transition is a step of its own; no closure to compute.
      if (opts.policy == StepPolicy::Interleaving && I.forcedList.empty()) {
        std::vector<uint32_t> &step = I.stepScratch;
        for (uint32_t t : spont) {
          if (anyUrgent && !m.transitions[t].urgent)
            continue;
          step.assign(1, t);
          I.fire(step, succ.data());
          emit(step);
        }
        continue;
      }
      llvm::SmallVector<Step, 8> seeds;
      if (opts.policy == StepPolicy::Interleaving) {
        for (uint32_t t : spont)
          seeds.push_back(Step{t});
      } else if (!spont.empty()) {
        if (I.jointlyEnabled(spont)) {
          seeds.push_back(Step(spont.begin(), spont.end()));
        } else {
          for (auto &mx :
               maximalSubsets(spont, [&](const std::vector<uint32_t> &cur) {
                 return I.jointlyEnabled(cur);
               }))
            seeds.push_back(Step(mx.begin(), mx.end()));
        }
      }
      if (std::find(I.present.begin(), I.present.end(), 1) != I.present.end())
        seeds.push_back({});
      for (auto &seed : seeds) {
        llvm::SmallVector<Step, 4> steps;
        I.closure(std::move(seed), steps);
        for (auto &step : steps) {
          if (step.empty())
            continue;
          std::sort(step.begin(), step.end());
          if (anyUrgent) {
            bool hasUrgent = false;
            for (uint32_t t : step)
              hasUrgent |= m.transitions[t].urgent;
            if (!hasUrgent)
              continue;
          }
          I.fire(step, succ.data());
          emit(step);
        }
      }
    }
    if (tickAllowed && I.tick(succ.data()))
      emit({});
  } catch (const EvalError &e) {
    err = {e.message, e.loc};
    return false;
  }
  return true;
}

void Semantics::fixInputs(llvm::ArrayRef<int64_t> leafValues,
                          llvm::ArrayRef<uint8_t> eventsPresent) {
  Impl &I = *impl;
  I.inputsFixed = !leafValues.empty() || !eventsPresent.empty();
  if (!I.inputsFixed)
    return;
  assert(leafValues.size() == I.inputSlots.size() &&
         eventsPresent.size() == I.eventInputs.size() &&
         "one value per input leaf and event input");
  I.fixedLeaves.assign(leafValues.begin(), leafValues.end());
  I.fixedPresent.assign(eventsPresent.begin(), eventsPresent.end());
}

bool Semantics::evalPredicate(const Expr *e, const uint64_t *state,
                              RuntimeError &err) {
  return evalInState(e, state, err) != 0;
}

std::vector<int64_t> &Semantics::predicateValuation(const uint64_t *state) {
  // A buffer of its own: predicates are evaluated while successors() is
  // still enumerating from its working valuation.
  Impl &I = *impl;
  std::vector<int64_t> &v = I.predicateVals;
  v.assign(L.numSlots(), 0);
  for (uint32_t s = 0; s < L.numPacked(); ++s)
    v[s] = L.get(state, s);
  for (size_t k = 0; k < I.inputSlots.size(); ++k)
    v[I.inputSlots[k]] =
        I.inputsFixed ? I.fixedLeaves[k] : L.slots()[I.inputSlots[k]].lo;
  return v;
}

/// `f()`, or `fallback` with `err` set if it fails with an EvalError.
template <typename F, typename T>
static T orReport(F f, T fallback, RuntimeError &err) {
  try {
    return f();
  } catch (const EvalError &x) {
    err = {x.message, x.loc};
    return fallback;
  }
}

int64_t Semantics::evalInState(const Expr *e, const uint64_t *state,
                               RuntimeError &err) {
  std::vector<int64_t> &v = predicateValuation(state);
  return orReport([&] { return impl->eval(e, v); }, int64_t(0), err);
}

net::StringValue Semantics::evalStringInState(const Expr *e,
                                              const uint64_t *state,
                                              RuntimeError &err) {
  std::vector<int64_t> &v = predicateValuation(state);
  return orReport([&] { return impl->evalStr(e, v); }, net::StringValue(), err);
}
