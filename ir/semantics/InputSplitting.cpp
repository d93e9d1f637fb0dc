//===- InputSplitting.cpp - free inputs split into classes on demand ------===//
//
// The interpreter's side of input splitting (docs/semantics.md, "Free
// inputs"): which expressions read which input, where an execution must
// decide something about an input, and into which segments the input's
// interval is cut there. InputSplitter.h records and replays the
// decisions.
//
// Where a decision cuts:
//  - an expression that designates the input (a value stored, an index,
//    arithmetic not under a comparison): one segment per value, up to
//    --max-input-values;
//  - an expression whose every read of the input is an operand of a
//    comparison with an input-free expression (`x > 5`, `x >= lo AND x <
//    hi`, a Boolean input tested): at the compared values only;
//  - a CASE on the input: at the labels' bounds, one segment per arm run;
//  - any other expression of one input: evaluated at every value of its
//    interval (up to --max-input-values), runs of equal value merged.
//
//===----------------------------------------------------------------------===//
#include "ir/semantics/SemanticsImpl.h"

#include "ir/net/Walk.h"

#include <cmath>

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::sem::detail;

using Segment = InputSplitter::Segment;

// --- Order keys -------------------------------------------------------------

static const uint64_t kSign64 = uint64_t(1) << 63;

/// The key of a float's bits: non-negative floats above negative ones,
/// each in the order of their magnitudes; the canonical NaN above +inf.
static int64_t floatKey(unsigned width, int64_t bits) {
  if (width == 32) {
    uint32_t b = uint32_t(bits);
    if (std::isnan(floatValue(32, bits)))
      return int64_t(0x7F800000u | 0x80000000u) + 1;
    return int64_t((b & 0x80000000u) ? ~b : (b | 0x80000000u));
  }
  uint64_t b = uint64_t(bits);
  if (std::isnan(floatValue(64, bits)))
    return int64_t((uint64_t(0x7FF0000000000000) | kSign64) ^ kSign64) + 1;
  uint64_t u = (b & kSign64) ? ~b : (b | kSign64);
  return int64_t(u ^ kSign64);
}

int64_t Semantics::Impl::keyOf(KeyKind k, int64_t value) {
  switch (k) {
  case KeyKind::Signed:
    return value;
  case KeyKind::Unsigned64:
    return int64_t(uint64_t(value) ^ kSign64);
  case KeyKind::Float32:
    return floatKey(32, value);
  case KeyKind::Float64:
    return floatKey(64, value);
  }
  return value;
}

int64_t Semantics::Impl::valueOf(KeyKind k, int64_t key) {
  switch (k) {
  case KeyKind::Signed:
    return key;
  case KeyKind::Unsigned64:
    return int64_t(uint64_t(key) ^ kSign64);
  case KeyKind::Float32: {
    if (key > floatKey(32, 0x7F800000))
      return floatBits(32, NAN);
    uint32_t u = uint32_t(key);
    return int64_t(uint32_t((u & 0x80000000u) ? (u & 0x7FFFFFFFu) : ~u));
  }
  case KeyKind::Float64: {
    if (key > floatKey(64, 0x7FF0000000000000))
      return floatBits(64, NAN);
    uint64_t u = uint64_t(key) ^ kSign64;
    return int64_t((u & kSign64) ? (u & ~kSign64) : ~u);
  }
  }
  return key;
}

static Semantics::Impl::KeyKind keyKindOf(const Type *t) {
  using K = Semantics::Impl::KeyKind;
  if (t->isFloat())
    return t->width == 32 ? K::Float32 : K::Float64;
  return t->isUnsigned64() ? K::Unsigned64 : K::Signed;
}

/// Number of keys in [lo, hi] minus one (no overflow for a full range).
static uint64_t spanOf(int64_t lo, int64_t hi) {
  return uint64_t(hi) - uint64_t(lo);
}

// --- What expressions read of the inputs ------------------------------------

/// The input port an lvalue-like expression's storage belongs to, if any.
static const Port *inputRoot(const Module &m, const Expr *e) {
  while (true) {
    if (auto *x = llvm::dyn_cast<IndexExpr>(e))
      e = x->base;
    else if (auto *f = llvm::dyn_cast<FieldExpr>(e))
      e = f->base;
    else
      break;
  }
  auto *r = llvm::dyn_cast<Ref>(e);
  if (!r || r->sym.kind != SymKind::Port)
    return nullptr;
  const Port &p = m.ports[r->sym.index];
  return p.isInput() && p.kind != PortKind::Event && !p.definition ? &p
                                                                   : nullptr;
}

void Semantics::Impl::analyseInputUses() {
  leaves.clear();
  for (uint32_t s : inputSlots) {
    const Slot &slot = L.slots()[s];
    InputLeaf leaf{s, KeyKind::Signed, slot.lo, slot.hi};
    if (slot.type)
      leaf.keys = keyKindOf(slot.type);
    switch (leaf.keys) {
    case KeyKind::Signed:
      break;
    case KeyKind::Unsigned64:
      leaf.lo = INT64_MIN;
      leaf.hi = INT64_MAX;
      break;
    case KeyKind::Float32:
      leaf.lo = floatKey(32, int64_t(0xFF800000u)); // -inf
      leaf.hi = floatKey(32, floatBits(32, NAN));
      break;
    case KeyKind::Float64:
      leaf.lo = floatKey(64, int64_t(0xFFF0000000000000ull));
      leaf.hi = floatKey(64, floatBits(64, NAN));
      break;
    }
    leaves.push_back(leaf);
  }
  leafBySlot.assign(L.numSlots() - L.numPacked(), -1);
  for (size_t k = 0; k < leaves.size(); ++k)
    leafBySlot[leaves[k].slot - L.numPacked()] = int32_t(k);
  dlo.assign(leaves.size(), 0);
  dhi.assign(leaves.size(), 0);
  if (leaves.empty())
    return;
  forEachRead(m, [&](const Expr *e, int) { analyseUse(e); });
  // Only expressions that read an input stay: a miss means "none".
  llvm::SmallVector<const Expr *, 64> none;
  for (auto &[e, u] : inputUse)
    if (u.leaf == -1)
      none.push_back(e);
  for (const Expr *e : none)
    inputUse.erase(e);
}

Semantics::Impl::InputUse Semantics::Impl::analyseUse(const Expr *e) {
  if (auto it = inputUse.find(e); it != inputUse.end())
    return it->second;
  InputUse u;
  llvm::SmallVector<InputUse, 4> kids;
  auto visit = [&](const Expr *c) {
    InputUse cu = analyseUse(c);
    kids.push_back(cu);
    if (cu.leaf == -1)
      return;
    u.leaf = u.leaf == -1 || u.leaf == cu.leaf ? cu.leaf : -2;
  };
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = cast<Ref>(e);
    if (r->sym.kind != SymKind::Port)
      break;
    const Port &p = m.ports[r->sym.index];
    if (p.definition && r->fields.empty()) {
      visit(p.definition);
      break;
    }
    if (!inputRoot(m, e))
      break;
    int64_t s = L.refSlot(r);
    if (s >= int64_t(L.numPacked()) && e->type && e->type->isScalar()) {
      u.leaf = leafOfSlot(uint32_t(s));
      u.identity = u.leaf >= 0;
    } else {
      u.leaf = -2; // a whole record or array of inputs
    }
    break;
  }
  case ExprKind::Index: {
    auto *x = cast<IndexExpr>(e);
    if (inputRoot(m, e)) {
      u.leaf = -2; // which input depends on the index
      analyseUse(x->index);
      break;
    }
    visit(x->base);
    visit(x->index);
    break;
  }
  case ExprKind::Field: {
    auto *f = cast<FieldExpr>(e);
    if (inputRoot(m, e)) {
      u.leaf = -2;
      analyseUse(f->base);
      break;
    }
    visit(f->base);
    break;
  }
  case ExprKind::Unary:
    visit(cast<UnaryExpr>(e)->operand);
    break;
  case ExprKind::Binary:
    visit(cast<BinaryExpr>(e)->lhs);
    visit(cast<BinaryExpr>(e)->rhs);
    break;
  case ExprKind::Cond: {
    auto *c = cast<CondExpr>(e);
    visit(c->cond);
    visit(c->thenExpr);
    visit(c->elseExpr);
    break;
  }
  case ExprKind::Call:
    for (const Expr *a : cast<CallExpr>(e)->args)
      visit(a);
    break;
  case ExprKind::Aggregate:
    for (const Expr *a : cast<AggregateLit>(e)->elems)
      visit(a);
    break;
  default:
    break;
  }
  if (u.leaf >= 0 && !u.identity) {
    // Thresholds: a comparison of the input itself with an input-free
    // value of the same order, or only such comparisons below.
    auto *b = llvm::dyn_cast<BinaryExpr>(e);
    if (b && isComparison(b->op) && kids.size() == 2 &&
        (kids[0].identity ? kids[1].leaf == -1 : kids[0].leaf == -1) &&
        b->lhs->type && b->rhs->type && b->lhs->type->isScalar() &&
        keyKindOf(b->lhs->type) == keyKindOf(b->rhs->type) &&
        (!b->lhs->type->isFloat() ||
         b->lhs->type->width == b->rhs->type->width)) {
      u.thresholds = true;
    } else {
      u.thresholds = true;
      for (const InputUse &k : kids)
        if (k.leaf != -1 && !k.thresholds)
          u.thresholds = false;
    }
  }
  inputUse[e] = u;
  return u;
}

// --- Classes
// ------------------------------------------------------------------

void Semantics::Impl::startClass() {
  splitter.start();
  unsplit = 0;
  for (size_t k = 0; k < leaves.size(); ++k) {
    dlo[k] = leaves[k].lo;
    dhi[k] = leaves[k].hi;
    vals[leaves[k].slot] = valueOf(leaves[k].keys, leaves[k].lo);
    unsplit += dlo[k] != dhi[k];
  }
  // Event inputs are few: decided up front, present or not (the first
  // one innermost, so that classes come in the enumeration's order).
  for (size_t e = present.size(); e-- > 0;)
    present[e] = char(splitter
                          .decide(uint32_t(leaves.size() + e),
                                  [](std::vector<Segment> &out) {
                                    out.push_back({0, 0, 0, false});
                                    out.push_back({1, 1, 1, false});
                                  })
                          .value);
}

void Semantics::Impl::narrow(uint32_t k, int64_t lo, int64_t hi) {
  if (dlo[k] != dhi[k] && lo == hi)
    --unsplit;
  dlo[k] = lo;
  dhi[k] = hi;
  if (lo == hi) {
    uint32_t s = leaves[k].slot;
    int64_t value = valueOf(leaves[k].keys, lo);
    vals[s] = value;
    if (local.size() > s)
      local[s] = value;
  }
}

namespace {
/// Runs `f` with input leaf `k` held at one key, as if its class had
/// narrowed to it; restores the class after.
template <typename F>
std::pair<int64_t, bool> atKey(Semantics::Impl &I, uint32_t k, int64_t key,
                               F f) {
  uint32_t s = I.leaves[k].slot;
  int64_t lo = I.dlo[k], hi = I.dhi[k], saved = I.vals[s];
  bool hasLocal = I.local.size() > s;
  int64_t savedLocal = hasLocal ? I.local[s] : 0;
  I.dlo[k] = I.dhi[k] = key;
  int64_t value = Semantics::Impl::valueOf(I.leaves[k].keys, key);
  I.vals[s] = value;
  if (hasLocal)
    I.local[s] = value;
  std::pair<int64_t, bool> r{0, false};
  try {
    r.first = f();
  } catch (const EvalError &) {
    r.second = true;
  }
  I.dlo[k] = lo;
  I.dhi[k] = hi;
  I.vals[s] = saved;
  if (hasLocal)
    I.local[s] = savedLocal;
  return r;
}

/// Appends the segments of [lo, hi] that start at `starts` (sorted keys
/// inside (lo, hi]), each valued by `f` at its first key, merging
/// neighbours of equal value.
template <typename F>
void segmentsFrom(Semantics::Impl &I, uint32_t k, int64_t lo, int64_t hi,
                  llvm::ArrayRef<int64_t> starts, F f,
                  std::vector<Segment> &out) {
  int64_t a = lo;
  for (size_t i = 0; i <= starts.size(); ++i) {
    int64_t b = i < starts.size() ? starts[i] - 1 : hi;
    auto [value, fails] = atKey(I, k, a, f);
    if (!out.empty() && out.back().fails == fails &&
        (fails || out.back().value == value))
      out.back().hi = b;
    else
      out.push_back({a, b, value, fails});
    if (i < starts.size())
      a = starts[i];
  }
}
} // namespace

[[noreturn]] static void tooManyValues(const Semantics::Impl &I, uint32_t k,
                                       const Expr *at, uint64_t span) {
  const Slot &s = I.L.slots()[I.leaves[k].slot];
  std::string count =
      span == UINT64_MAX ? std::string("2^64") : std::to_string(span + 1);
  throw EvalError{"the free input '" + s.name + "' takes " + count +
                      " values here and '" + exprToString(at) +
                      "' needs each of them (more than --max-input-values=" +
                      std::to_string(I.opts.maxInputValues) +
                      "); give the input a narrower range ({range LO..HI}, "
                      "a subrange type) or connect it",
                  at->loc, true};
}

/// One segment per value of leaf `k`'s interval.
static void eachValue(Semantics::Impl &I, uint32_t k, const Expr *at,
                      std::vector<Segment> &out) {
  int64_t lo = I.dlo[k], hi = I.dhi[k];
  uint64_t span = spanOf(lo, hi);
  if (span >= I.opts.maxInputValues)
    tooManyValues(I, k, at, span);
  for (int64_t key = lo;; ++key) {
    out.push_back(
        {key, key, Semantics::Impl::valueOf(I.leaves[k].keys, key), false});
    if (key == hi)
      break;
  }
}

void Semantics::Impl::decideValues(uint32_t first, uint32_t n, const Expr *at) {
  for (uint32_t s = std::max(first, L.numPacked()); s < first + n; ++s) {
    int32_t k = leafOfSlot(s);
    if (k < 0 || dlo[k] == dhi[k])
      continue;
    Segment seg = splitter.decide(uint32_t(k), [&](std::vector<Segment> &out) {
      eachValue(*this, uint32_t(k), at, out);
    });
    narrow(uint32_t(k), seg.lo, seg.hi);
  }
}

/// The keys where a comparison of leaf `k` with `value` may change its
/// answer: segment starts at the value and just after it (for a float,
/// also at its negation, so that -0 and +0 stay together, and at NaN).
static void cutsAround(const Semantics::Impl &I, uint32_t k, int64_t value,
                       std::vector<int64_t> &starts) {
  using K = Semantics::Impl::KeyKind;
  auto add = [&](int64_t key) {
    starts.push_back(key);
    if (key != INT64_MAX)
      starts.push_back(key + 1);
  };
  K kind = I.leaves[k].keys;
  add(Semantics::Impl::keyOf(kind, value));
  if (kind == K::Float32 || kind == K::Float64) {
    int64_t sign = kind == K::Float32 ? int64_t(0x80000000u) : INT64_MIN;
    add(Semantics::Impl::keyOf(kind, value ^ sign));
    starts.push_back(I.leaves[k].hi); // NaN, compared false
  }
}

/// Collects the cut keys of every comparison of leaf `k` in `e` (an
/// expression in threshold form).
static void collectCuts(Semantics::Impl &I, uint32_t k, const Expr *e,
                        const std::vector<int64_t> &v,
                        std::vector<int64_t> &starts) {
  auto it = I.inputUse.find(e);
  if (it == I.inputUse.end())
    return; // reads no input
  auto *b = llvm::dyn_cast<BinaryExpr>(e);
  if (b && isComparison(b->op)) {
    auto isLeaf = [&](const Expr *x) {
      auto u = I.inputUse.find(x);
      return u != I.inputUse.end() && u->second.identity;
    };
    const Expr *other = isLeaf(b->lhs)   ? b->rhs
                        : isLeaf(b->rhs) ? b->lhs
                                         : nullptr;
    if (other && !I.inputUse.count(other)) {
      try {
        cutsAround(I, k, I.eval(other, v), starts);
      } catch (const EvalError &) {
        // Its value fails wherever it is evaluated: no cut depends on it.
      }
      return;
    }
  }
  switch (e->getKind()) {
  case ExprKind::Unary:
    collectCuts(I, k, cast<UnaryExpr>(e)->operand, v, starts);
    return;
  case ExprKind::Binary:
    collectCuts(I, k, cast<BinaryExpr>(e)->lhs, v, starts);
    collectCuts(I, k, cast<BinaryExpr>(e)->rhs, v, starts);
    return;
  case ExprKind::Cond:
    collectCuts(I, k, cast<CondExpr>(e)->cond, v, starts);
    collectCuts(I, k, cast<CondExpr>(e)->thenExpr, v, starts);
    collectCuts(I, k, cast<CondExpr>(e)->elseExpr, v, starts);
    return;
  case ExprKind::Call:
    for (const Expr *a : cast<CallExpr>(e)->args)
      collectCuts(I, k, a, v, starts);
    return;
  case ExprKind::Ref:
    if (auto *r = cast<Ref>(e);
        r->sym.kind == SymKind::Port && I.m.ports[r->sym.index].definition)
      collectCuts(I, k, I.m.ports[r->sym.index].definition, v, starts);
    return;
  default:
    return;
  }
}

/// Sorted, unique, inside (lo, hi].
static void normaliseStarts(std::vector<int64_t> &starts, int64_t lo,
                            int64_t hi) {
  starts.erase(std::remove_if(starts.begin(), starts.end(),
                              [&](int64_t s) { return s <= lo || s > hi; }),
               starts.end());
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
}

int64_t Semantics::Impl::splitEval(const Expr *e, const InputUse &u,
                                   const std::vector<int64_t> &v) {
  uint32_t k = uint32_t(u.leaf);
  Segment seg = splitter.decide(k, [&](std::vector<Segment> &out) {
    int64_t lo = dlo[k], hi = dhi[k];
    if (u.identity)
      return eachValue(*this, k, e, out);
    std::vector<int64_t> starts;
    if (u.thresholds) {
      collectCuts(*this, k, e, v, starts);
      normaliseStarts(starts, lo, hi);
    } else {
      uint64_t span = spanOf(lo, hi);
      if (span >= opts.maxInputValues)
        tooManyValues(*this, k, e, span);
      for (int64_t key = lo; key != hi;)
        starts.push_back(++key);
    }
    segmentsFrom(
        *this, k, lo, hi, starts, [&] { return eval(e, v); }, out);
  });
  narrow(k, seg.lo, seg.hi);
  if (seg.fails) {
    // The failure itself, with its message: at the segment's first value.
    narrow(k, seg.lo, seg.lo);
    eval(e, v);
    fail(e, "'" + exprToString(e) + "' fails for some values of an input");
  }
  return seg.value;
}

bool Semantics::Impl::splitCase(const CaseStmt *c,
                                const std::vector<int64_t> &v, int32_t &arm) {
  auto it = inputUse.find(c->selector);
  if (it == inputUse.end() || !it->second.identity)
    return false;
  uint32_t k = uint32_t(it->second.leaf);
  if (dlo[k] == dhi[k] || leaves[k].keys != KeyKind::Signed)
    return false;
  for (const CaseArm &a : c->arms)
    for (const CaseLabel &l : a.labels)
      if (inputUse.count(l.lo) || (l.hi && inputUse.count(l.hi)))
        return false;
  Segment seg = splitter.decide(k, [&](std::vector<Segment> &out) {
    // Labels in the order exec tries them.
    llvm::SmallVector<std::tuple<int64_t, int64_t, int32_t>, 16> ranges;
    std::vector<int64_t> starts;
    for (size_t ai = 0; ai < c->arms.size(); ++ai)
      for (const CaseLabel &l : c->arms[ai].labels) {
        int64_t lo = eval(l.lo, v);
        int64_t hi = l.hi ? eval(l.hi, v) : lo;
        ranges.push_back({lo, hi, int32_t(ai)});
        starts.push_back(lo);
        if (hi != INT64_MAX)
          starts.push_back(hi + 1);
      }
    normaliseStarts(starts, dlo[k], dhi[k]);
    int64_t a = dlo[k];
    for (size_t i = 0; i <= starts.size(); ++i) {
      int64_t b = i < starts.size() ? starts[i] - 1 : dhi[k];
      int32_t chosen = -1;
      for (auto &[lo, hi, ai] : ranges)
        if (a >= lo && a <= hi) {
          chosen = ai;
          break;
        }
      if (!out.empty() && out.back().value == chosen)
        out.back().hi = b;
      else
        out.push_back({a, b, chosen, false});
      if (i < starts.size())
        a = starts[i];
    }
  });
  narrow(k, seg.lo, seg.hi);
  arm = int32_t(seg.value);
  return true;
}
