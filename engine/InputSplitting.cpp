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
#include "engine/SemanticsImpl.h"

#include "ir/net/Walk.h"

#include <cmath>

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::sem::detail;

using Segment = InputSplitter::Segment;
using InputUseOf = Semantics::Impl::InputUse;

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
    InputLeaf leaf{KeyKind::Signed, slot.lo, slot.hi};
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
    leafBySlot[inputSlots[k] - L.numPacked()] = int32_t(k);
  decidedAt.assign(leaves.size(), llvm::SMLoc());
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
  case ExprKind::Aggregate:
    for (const Expr *a : cast<AggregateLit>(e)->elems)
      visit(a);
    break;
  default:
    if (inputRoot(m, e)) {
      // An element or member of an input chosen at run time (`in[i]`, a
      // field of one): which leaf is known only there. Its index is
      // analysed for its own reads.
      u.leaf = -2;
      forEachOperand(e, [&](const Expr *x) { analyseUse(x); });
      break;
    }
    forEachOperand(e, visit);
    break;
  }
  if (u.leaf >= 0 && !u.identity) {
    auto none = [](const InputUse &x) { return x.leaf == -1; };
    auto numeric = [](const Type *t) {
      return t && (t->isInteger() || t->isFloat());
    };
    if (auto *un = llvm::dyn_cast<UnaryExpr>(e))
      u.chain = un->op == UnaryOp::Neg && kids[0].chain && numeric(e->type);
    if (auto *b = llvm::dyn_cast<BinaryExpr>(e)) {
      if (b->op == BinaryOp::Add || b->op == BinaryOp::Sub ||
          b->op == BinaryOp::Mul)
        u.chain = numeric(e->type) && ((kids[0].chain && none(kids[1])) ||
                                       (kids[1].chain && none(kids[0])));
      else if (b->op == BinaryOp::Div)
        u.chain = numeric(e->type) && kids[0].chain && none(kids[1]);
      // `(x + 2^(n-1)) & (2^n - 1)`: how a frontend wraps to n bits; the
      // identity where x stays within the mask (checked where evaluated).
      else if (b->op == BinaryOp::BitAnd)
        u.chain = e->type && e->type->isInteger() &&
                  ((kids[0].chain && none(kids[1])) ||
                   (kids[1].chain && none(kids[0])));
      else if (isComparison(b->op))
        u.cuttable = (kids[0].chain && none(kids[1])) ||
                     (kids[1].chain && none(kids[0]));
    }
    if (auto *c = llvm::dyn_cast<CallExpr>(e))
      u.chain = c->fn == Builtin::Convert && kids.size() == 1 &&
                kids[0].chain && numeric(c->args[0]->type) && numeric(e->type);
    if (!u.cuttable && !u.chain) {
      u.cuttable = true;
      for (const InputUse &k : kids)
        if (k.leaf != -1 && !k.cuttable)
          u.cuttable = false;
    }
  }
  if (u.identity)
    u.chain = true;
  inputUse[e] = u;
  return u;
}

// --- Classes
// ------------------------------------------------------------------

void Semantics::Impl::resetLeaves() {
  wholeUnsplit = 0;
  for (size_t k = 0; k < leaves.size(); ++k) {
    dlo[k] = leaves[k].lo;
    dhi[k] = leaves[k].hi;
    vals[inputSlots[k]] = valueOf(leaves[k].keys, leaves[k].lo);
    wholeUnsplit += dlo[k] != dhi[k];
  }
  isNarrowed.assign(leaves.size(), 0);
  narrowed.clear();
}

void Semantics::Impl::startClass() {
  splitter.start();
  // Only the leaves the last class narrowed need their whole domain back.
  for (uint32_t k : narrowed) {
    dlo[k] = leaves[k].lo;
    dhi[k] = leaves[k].hi;
    isNarrowed[k] = 0;
  }
  narrowed.clear();
  unsplit = wholeUnsplit;
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
  if (!isNarrowed[k]) {
    isNarrowed[k] = 1;
    narrowed.push_back(k);
  }
  if (dlo[k] != dhi[k] && lo == hi)
    --unsplit;
  dlo[k] = lo;
  dhi[k] = hi;
  if (lo == hi) {
    uint32_t s = inputSlots[k];
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
  uint32_t s = I.inputSlots[k];
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
  const Slot &s = I.L.slots()[I.inputSlots[k]];
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
    decidedAt[k] = at->loc;
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

static bool collectCuts(Semantics::Impl &I, uint32_t k, const Expr *e,
                        const std::vector<int64_t> &v,
                        std::vector<int64_t> &starts);

/// The order of two values compared as `cmp` compares them: -1, 0, 1, or
/// 2 when unordered (a NaN).
static int compareValues(const BinaryExpr *cmp, int64_t a, int64_t b) {
  const Type *lt = cmp->lhs->type, *rt = cmp->rhs->type;
  if (lt->isFloat() || rt->isFloat()) {
    unsigned w = lt->isFloat() ? lt->width : rt->width;
    double x = floatValue(w, a), y = floatValue(w, b);
    if (std::isnan(x) || std::isnan(y))
      return 2;
    return x < y ? -1 : x > y ? 1 : 0;
  }
  if (lt->isUnsigned64() || rt->isUnsigned64())
    return uint64_t(a) < uint64_t(b) ? -1 : uint64_t(a) > uint64_t(b) ? 1 : 0;
  return a < b ? -1 : a > b ? 1 : 0;
}

/// The value of an integer of type `t` as a number (a uint64's bits
/// unsigned).
static __int128 numberOf(const Type *t, int64_t v) {
  return t->isUnsigned64() ? __int128(uint64_t(v)) : __int128(v);
}

namespace {
/// One step of a chain: node `n` computes from the chain operand `a` and
/// the input-free operand `o` (null for negation and conversions).
struct ChainStep {
  const Expr *n, *a, *o;
  int64_t ov;
};

/// How an integer step's exact result becomes its value: kept within
/// [lo, lo + span) by wrapping (`wraps`), or else out of range is not
/// modelled here (the step is not monotone-checked).
struct StepRange {
  __int128 lo, span;
  bool wraps;
};

StepRange rangeOf(const ChainStep &s) {
  auto *b = llvm::dyn_cast<BinaryExpr>(s.n);
  if (b && b->op == BinaryOp::BitAnd) // x & (2^n - 1) is x mod 2^n
    return {0, __int128(numberOf(s.o->type, s.ov)) + 1, true};
  const Type *t = s.n->type;
  if (t->kind == TypeKind::Int) {
    __int128 lo = numberOf(t, t->lo);
    __int128 hi = t->isUnsigned64() ? __int128(UINT64_MAX) : numberOf(t, t->hi);
    if (t->isUnsigned64())
      lo = 0;
    return {lo, hi - lo + 1, t->overflow == Overflow::Wrap};
  }
  return {INT64_MIN, (__int128(1) << 64), false};
}

/// The exact result of an integer step for chain operand value `av`;
/// false when it has none (a division by zero, a mask that is not 2^n - 1).
bool exactStep(const ChainStep &s, int64_t av, __int128 &r) {
  __int128 x = numberOf(s.a->type, av);
  __int128 c = s.o ? numberOf(s.o->type, s.ov) : 0;
  if (llvm::isa<UnaryExpr>(s.n)) {
    r = -x;
    return true;
  }
  auto *b = llvm::dyn_cast<BinaryExpr>(s.n);
  if (!b) {
    r = x; // a conversion between integers keeps the value
    return true;
  }
  switch (b->op) {
  case BinaryOp::Add:
    r = x + c;
    return true;
  case BinaryOp::Sub:
    r = b->lhs == s.a ? x - c : c - x;
    return true;
  case BinaryOp::Mul:
    r = x * c;
    return true;
  case BinaryOp::Div:
    if (c == 0)
      return false;
    r = x / c; // truncates toward zero, as the PLC does
    return true;
  case BinaryOp::BitAnd:
    if (c < 0 || (c & (c + 1)) != 0)
      return false;
    r = x;
    return true;
  default:
    return false;
  }
}

__int128 floorDiv(__int128 a, __int128 b) {
  __int128 q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/// Is a float step monotone without making a NaN? Rounding is monotone;
/// a non-finite constant or a division by zero could make one (inf - inf,
/// 0 * inf, 0 / 0).
bool floatStepSafe(const ChainStep &s, int64_t aLo, int64_t aHi) {
  if (!s.o)
    return true;
  if (!s.o->type->isFloat())
    return false;
  double c = floatValue(s.o->type->width, s.ov);
  if (!std::isfinite(c))
    return false;
  auto *b = llvm::dyn_cast<BinaryExpr>(s.n);
  if (b && b->op == BinaryOp::Div && c == 0)
    return false;
  if (b && b->op == BinaryOp::Mul && c == 0 && s.a->type->isFloat() &&
      !(std::isfinite(floatValue(s.a->type->width, aLo)) &&
        std::isfinite(floatValue(s.a->type->width, aHi))))
    return false;
  return true;
}

/// Finds the cuts of `f OP c` for a chain `steps` (leaf first) over
/// [lo, hi]: each step is checked monotone there (a wrapping integer step
/// that wraps inside the interval splits it where it wraps, and each piece
/// is checked again), then binary search finds where f reaches c and
/// passes it. False when a step cannot be shown monotone.
class ChainCutter {
public:
  ChainCutter(Semantics::Impl &I, uint32_t k, const BinaryExpr *cmp,
              const Expr *f, int64_t c, const std::vector<int64_t> &v,
              std::vector<int64_t> &starts)
      : I(I), k(k), cmp(cmp), f(f), c(c), v(v), starts(starts) {}

  bool build() {
    for (const Expr *n = f; !I.inputUse.find(n)->second.identity;) {
      ChainStep s{n, nullptr, nullptr, 0};
      if (auto *u = llvm::dyn_cast<UnaryExpr>(n)) {
        s.a = u->operand;
      } else if (auto *b = llvm::dyn_cast<BinaryExpr>(n)) {
        bool left = I.inputUse.count(b->lhs);
        s.a = left ? b->lhs : b->rhs;
        s.o = left ? b->rhs : b->lhs;
      } else {
        s.a = cast<CallExpr>(n)->args[0];
      }
      if (s.o) {
        try {
          s.ov = I.eval(s.o, v);
        } catch (const EvalError &) {
          return false;
        }
      }
      steps.insert(steps.begin(), s);
      n = s.a;
    }
    return true;
  }

  bool cut(int64_t lo, int64_t hi) {
    if (++pieces > kMaxPieces)
      return false;
    for (const ChainStep &s : steps) {
      auto [aLo, f1] = at(s.a, lo);
      auto [aHi, f2] = at(s.a, hi);
      if (f1 || f2)
        return false;
      if (s.n->type->isFloat()) {
        if (!floatStepSafe(s, aLo, aHi))
          return false;
        continue;
      }
      if (!s.n->type->isInteger())
        return false;
      if (s.a->type->isFloat()) {
        // Float to integer: monotone; it must not fail at either end.
        if (at(s.n, lo).second || at(s.n, hi).second)
          return false;
        continue;
      }
      __int128 eLo, eHi;
      if (!exactStep(s, aLo, eLo) || !exactStep(s, aHi, eHi))
        return false;
      StepRange r = rangeOf(s);
      __int128 mLo = floorDiv(eLo - r.lo, r.span);
      __int128 mHi = floorDiv(eHi - r.lo, r.span);
      if (mLo == mHi) {
        if (mLo != 0 && !r.wraps)
          return false;
        continue; // the same wrap everywhere: monotone
      }
      if (!r.wraps)
        return false;
      // Wraps inside: cut where the exact result crosses each multiple of
      // the span, and check each piece again.
      bool up = mLo < mHi;
      std::vector<int64_t> at;
      for (__int128 m = std::min(mLo, mHi) + 1; m <= std::max(mLo, mHi); ++m) {
        __int128 bound = r.lo + m * r.span; // first exact value of wrap m
        int64_t key = firstKey(lo, hi, [&](int64_t key) {
          __int128 e;
          exactStep(s, this->at(s.a, key).first, e);
          return up ? e >= bound : e < bound;
        });
        at.push_back(key);
        if (at.size() > kMaxPieces)
          return false;
      }
      std::sort(at.begin(), at.end());
      int64_t a = lo;
      for (int64_t key : at) {
        starts.push_back(key);
        if (!cut(a, key - 1))
          return false;
        a = key;
      }
      return cut(a, hi);
    }
    // Every step monotone on [lo, hi]: where f reaches c, and passes it.
    auto [fLo, e1] = at(f, lo);
    auto [fHi, e2] = at(f, hi);
    int dir = compareValues(cmp, fLo, fHi);
    if (e1 || e2 || dir == 2)
      return false;
    if (dir == 0)
      return true; // constant here
    auto order = [&](int64_t key) {
      return compareValues(cmp, at(f, key).first, c);
    };
    if (dir < 0) { // increasing
      pushFirst(lo, hi, [&](int64_t key) { return order(key) >= 0; });
      pushFirst(lo, hi, [&](int64_t key) { return order(key) == 1; });
    } else {
      pushFirst(lo, hi, [&](int64_t key) { return order(key) <= 0; });
      pushFirst(lo, hi, [&](int64_t key) { return order(key) == -1; });
    }
    return true;
  }

private:
  static constexpr unsigned kMaxPieces = 256;
  std::pair<int64_t, bool> at(const Expr *x, int64_t key) {
    return atKey(I, k, key, [&] { return I.eval(x, v); });
  }
  /// The first key of [lo, hi] where the monotone `holds` does (hi + 1
  /// reported as none).
  template <typename P> int64_t firstKey(int64_t lo, int64_t hi, P holds) {
    if (!holds(hi))
      return hi; // not reached: callers cut before hi at most
    while (lo < hi) {
      int64_t mid = lo + int64_t((uint64_t(hi) - uint64_t(lo)) / 2);
      if (holds(mid))
        hi = mid;
      else
        lo = mid + 1;
    }
    return lo;
  }
  template <typename P> void pushFirst(int64_t lo, int64_t hi, P holds) {
    if (holds(hi))
      starts.push_back(firstKey(lo, hi, holds));
  }

  Semantics::Impl &I;
  uint32_t k;
  const BinaryExpr *cmp;
  const Expr *f;
  int64_t c;
  const std::vector<int64_t> &v;
  std::vector<int64_t> &starts;
  std::vector<ChainStep> steps;
  unsigned pieces = 0;
};
} // namespace

/// Cuts for `f OP c` where `f` is a chain of leaf `k` (ChainCutter); for a
/// float input, -inf, +inf and NaN are apart and the chain is checked on
/// the finite values between.
static bool monotoneCuts(Semantics::Impl &I, uint32_t k, const BinaryExpr *cmp,
                         const Expr *f, int64_t c,
                         const std::vector<int64_t> &v,
                         std::vector<int64_t> &starts) {
  using K = Semantics::Impl::KeyKind;
  int64_t lo = I.dlo[k], hi = I.dhi[k];
  K kind = I.leaves[k].keys;
  if (kind == K::Float32 || kind == K::Float64) {
    int64_t negInf = I.leaves[k].lo, nan = I.leaves[k].hi, posInf = nan - 1;
    starts.push_back(negInf + 1);
    starts.push_back(posInf);
    starts.push_back(nan);
    lo = std::max(lo, negInf + 1);
    hi = std::min(hi, posInf - 1);
    if (lo > hi)
      return true;
  }
  ChainCutter cutter(I, k, cmp, f, c, v, starts);
  return cutter.build() && cutter.cut(lo, hi);
}

/// Collects the cut keys of every comparison of leaf `k` in `e` (a
/// cuttable expression); false when a chain is not monotone here.
static bool collectCuts(Semantics::Impl &I, uint32_t k, const Expr *e,
                        const std::vector<int64_t> &v,
                        std::vector<int64_t> &starts) {
  auto it = I.inputUse.find(e);
  if (it == I.inputUse.end())
    return true; // reads no input
  auto *b = llvm::dyn_cast<BinaryExpr>(e);
  if (b && isComparison(b->op)) {
    auto use = [&](const Expr *x) {
      auto u = I.inputUse.find(x);
      return u == I.inputUse.end() ? InputUseOf() : u->second;
    };
    auto l = use(b->lhs), r = use(b->rhs);
    const Expr *f = nullptr, *other = nullptr;
    if (l.chain && r.leaf == -1) {
      f = b->lhs;
      other = b->rhs;
    } else if (r.chain && l.leaf == -1) {
      f = b->rhs;
      other = b->lhs;
    }
    if (f) {
      int64_t c;
      try {
        c = I.eval(other, v);
      } catch (const EvalError &) {
        // Fails wherever it is evaluated: no cut depends on it.
        return true;
      }
      if (use(f).identity &&
          keyKindOf(b->lhs->type) == keyKindOf(b->rhs->type) &&
          (!b->lhs->type->isFloat() ||
           b->lhs->type->width == b->rhs->type->width)) {
        cutsAround(I, k, c, starts);
        return true;
      }
      return monotoneCuts(I, k, b, f, c, v, starts);
    }
  }
  bool ok = true;
  auto sub = [&](const Expr *x) { ok = ok && collectCuts(I, k, x, v, starts); };
  if (auto *r = llvm::dyn_cast<Ref>(e);
      r && r->sym.kind == SymKind::Port && I.m.ports[r->sym.index].definition)
    sub(I.m.ports[r->sym.index].definition);
  else
    forEachOperand(e, sub);
  return ok;
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
    if (u.cuttable && collectCuts(*this, k, e, v, starts)) {
      normaliseStarts(starts, lo, hi);
    } else {
      starts.clear();
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
  decidedAt[k] = e->loc;
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
  decidedAt[k] = c->selector->loc;
  arm = int32_t(seg.value);
  return true;
}

void Semantics::Impl::tooManyClasses() {
  // The inputs of the current class's decisions, most segments first.
  std::vector<std::pair<uint64_t, uint32_t>> told; // (segments, leaf)
  std::vector<uint64_t> most(leaves.size(), 0);
  splitter.forEachDecision([&](uint32_t input, uint32_t count) {
    if (input < leaves.size())
      most[input] = std::max<uint64_t>(most[input], count);
  });
  for (uint32_t k = 0; k < leaves.size(); ++k)
    if (most[k] > 1)
      told.push_back({most[k], k});
  std::sort(told.begin(), told.end(),
            [](auto &a, auto &b) { return a.first > b.first; });
  std::string names;
  for (size_t i = 0; i < told.size() && i < 4; ++i)
    names += std::string(i ? ", " : "") + "'" +
             L.slots()[inputSlots[told[i].second]].name + "' (" +
             std::to_string(told[i].first) + " classes)";
  llvm::SMLoc loc = told.empty() ? llvm::SMLoc() : decidedAt[told[0].second];
  throw EvalError{"the free inputs split into more than " +
                      std::to_string(opts.maxInputClasses) +
                      " classes of valuations in one step (more than "
                      "--max-input-classes): the step tells apart the values " +
                      "of " +
                      (names.empty() ? std::string("its inputs") : names) +
                      " (the first decided here); give them narrower ranges "
                      "or connect them",
                  loc, true};
}

Semantics::Impl::ClassBox Semantics::Impl::currentClass() const {
  ClassBox box;
  for (size_t k = 0; k < leaves.size(); ++k)
    box.push_back({dlo[k], dhi[k]});
  for (size_t e = 0; e < eventInputs.size(); ++e)
    box.push_back({present[e], present[e]});
  return box;
}

std::string Semantics::Impl::conditionText(std::vector<ClassBox> boxes) const {
  // Two boxes equal but in one input whose intervals touch are one box
  // (repeated until none merges; only for a readable number of boxes).
  size_t n = leaves.size() + eventInputs.size();
  for (bool merged = boxes.size() <= 256; merged;) {
    merged = false;
    for (size_t a = 0; a < boxes.size() && !merged; ++a)
      for (size_t b = a + 1; b < boxes.size() && !merged; ++b) {
        size_t differ = n, count = 0;
        for (size_t i = 0; i < n && count < 2; ++i)
          if (boxes[a][i] != boxes[b][i]) {
            differ = i;
            ++count;
          }
        if (count != 1)
          continue;
        auto &x = boxes[a][differ], &y = boxes[b][differ];
        if (x.second != INT64_MAX && x.second + 1 == y.first)
          x.second = y.second;
        else if (y.second != INT64_MAX && y.second + 1 == x.first)
          x.first = y.first;
        else
          continue;
        boxes.erase(boxes.begin() + b);
        merged = true;
      }
  }
  std::string out;
  for (const ClassBox &box : boxes) {
    std::string cube;
    auto add = [&](const std::string &s) {
      cube += (cube.empty() ? "[" : ", ") + s;
    };
    for (size_t k = 0; k < leaves.size(); ++k) {
      auto [lo, hi] = box[k];
      if (lo == leaves[k].lo && hi == leaves[k].hi)
        continue; // any value
      const Slot &s = L.slots()[inputSlots[k]];
      auto text = [&](int64_t key) {
        int64_t v = valueOf(leaves[k].keys, key);
        if (s.type && s.type->kind == TypeKind::Enum && v >= 0 &&
            size_t(v) < s.type->enumerators.size())
          return s.type->enumerators[size_t(v)].str();
        return s.type ? formatScalar(s.type, v) : std::to_string(v);
      };
      add(s.name + "=" + text(lo) + (lo == hi ? "" : ".." + text(hi)));
    }
    for (size_t e = 0; e < eventInputs.size(); ++e) {
      auto [lo, hi] = box[leaves.size() + e];
      if (lo == hi)
        add(m.ports[eventInputs[e]].name.str() + "=" + (lo ? "1" : "0"));
    }
    out += (out.empty() ? "" : " | ") + (cube.empty() ? "[any" : cube) + "]";
  }
  return out;
}
