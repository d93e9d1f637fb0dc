//===- DiscretiseTransfers.cpp - resets reading other reals ---------------===//
//
// A reset may read other reals: a sample-and-hold copies one real into
// another (`x2 := x1`), a clock synchronisation takes a mean (`x := (c1 +
// c2)/2`). After discretise a real is only its position token, so such a
// reset `x := a*x + sum(b_j * y_j) + c` moves x's token, per combination
// of positions of the y_j (condition arcs: their values before the step,
// SpaceEx's simultaneous assignment), to every position the image of the
// values those positions stand for meets — the affine reset's rule with
// the y_j's interval added. A y_j's positions must be known first, so the
// reals are coded in an order that puts the reals read before the reals
// reset from them; resets reading each other in a cycle are refused.
//
//===----------------------------------------------------------------------===//
#include "passes/Discretiser.h"

using namespace netlift;
using namespace netlift::net;
using namespace netlift::discretise;

std::pair<double, double> Discretiser::hullOf(const Real &r, Value v) const {
  double lo = v.atPoint ? r.grid[v.k] : r.grid[v.k - 1];
  double hi = r.grid[v.k];
  if (v.atPoint && v.k + 1 == r.grid.size() && r.openTop)
    hi = INFINITY;
  if (v.atPoint && v.k == 0 && r.openBottom)
    lo = -INFINITY;
  return {lo, hi};
}

namespace {
/// b * [lo, hi].
std::pair<double, double> scaled(double b, std::pair<double, double> iv) {
  double l = b * iv.first, h = b * iv.second;
  return l <= h ? std::make_pair(l, h) : std::make_pair(h, l);
}
} // namespace

std::pair<bool, bool> Discretiser::endsIncluded(Form f) {
  switch (f.kind) {
  case FormKind::At:
  case FormKind::Rest:
    return {true, true};
  case FormKind::Up:
    return {true, false};
  case FormKind::Down:
    return {false, true};
  default:
    return {false, false};
  }
}

Discretiser::Added Discretiser::transferHull(const TransferReset &tx) const {
  Added out;
  for (auto [rj, bj] : tx.terms) {
    const Real &y = reals[rj];
    double l = y.grid.front(), h = y.grid.back();
    if (y.openTop)
      h = INFINITY;
    if (y.openBottom)
      l = -INFINITY;
    auto [sl, sh] = scaled(bj, {l, h});
    out.lo += sl;
    out.hi += sh;
  }
  return out;
}

std::vector<std::pair<std::vector<uint32_t>, Discretiser::Added>>
Discretiser::transferCombinations(const TransferReset &tx,
                                  const Expr *guard) const {
  std::vector<std::pair<std::vector<uint32_t>, Added>> out;
  std::vector<uint32_t> places;
  std::function<void(size_t, Added)> walk = [&](size_t j, Added sum) {
    if (j == tx.terms.size()) {
      out.push_back({places, sum});
      return;
    }
    auto [rj, bj] = tx.terms[j];
    const Real &y = reals[rj];
    for (auto &[f, p] : y.places) {
      // Positions where the transition cannot fire need no transfer.
      auto never = [&](bool clockZero) {
        std::optional<bool> t = truthAt(guard, y, valueOf(y, f, clockZero));
        return t && !*t;
      };
      if (never(false) && (!f.moving() || never(true)))
        continue;
      auto [l, h] = scaled(bj, hullOf(y, valueOf(y, f, false)));
      auto [inLo, inHi] = endsIncluded(f);
      if (bj < 0)
        std::swap(inLo, inHi);
      Added next = sum;
      next.lo += l;
      next.hi += h;
      next.closedLo &= inLo;
      next.closedHi &= inHi;
      places.push_back(p);
      walk(j + 1, next);
      places.pop_back();
    }
  };
  walk(0, Added{});
  return out;
}

bool Discretiser::codingOrder(std::vector<size_t> &order) {
  // reads[x]: the reals x's transfers read.
  std::vector<std::set<size_t>> reads(reals.size());
  std::map<std::pair<size_t, size_t>, uint32_t> via; // for the message
  for (auto &[key, tx] : transferResets)
    for (auto [rj, bj] : tx.terms) {
      reads[key.second].insert(rj);
      via.try_emplace({key.second, rj}, key.first);
    }
  enum { Fresh, Open, Done };
  std::vector<int> state(reals.size(), Fresh);
  bool reported = false; // the cycle is said once, where it closes
  std::function<bool(size_t)> visit = [&](size_t x) {
    if (state[x] == Done)
      return true;
    if (state[x] == Open)
      return false;
    state[x] = Open;
    for (size_t y : reads[x])
      if (!visit(y)) {
        if (!reported) {
          reported = true;
          const Transition &t = m.transitions[via[{x, y}]];
          return error(t.loc, "transition '" + t.name + "' resets '" +
                                  reals[x].name + "' from '" + reals[y].name +
                                  "', whose resets read '" + reals[x].name +
                                  "' in turn; discretise codes a reset "
                                  "reading other reals only where those "
                                  "resets do not form a cycle");
        }
        return false;
      }
    state[x] = Done;
    order.push_back(x);
    return true;
  };
  for (size_t x = 0; x < reals.size(); ++x)
    if (!visit(x))
      return false;
  return true;
}

bool Discretiser::widenForTransfers() {
  // x's range must hold every value a transfer gives it, which depends on
  // the ranges of the reals read (and on x's own, for x := a*x + ...):
  // widen the inferred ranges until nothing changes.
  for (unsigned round = 0; round < 64; ++round) {
    bool changed = false;
    for (auto &[key, tx] : transferResets) {
      Real &x = reals[key.second];
      const Type *type = m.vars[x.var].type;
      auto [l, h] = scaled(tx.a, {x.lo, x.hi});
      if (tx.a == 0)
        l = h = 0;
      l += tx.c;
      h += tx.c;
      for (auto [rj, bj] : tx.terms) {
        const Real &y = reals[rj];
        auto [sl, sh] = scaled(
            bj, {y.openBottom ? -INFINITY : y.lo, y.openTop ? INFINITY : y.hi});
        l += sl;
        h += sh;
      }
      const Transition &t = m.transitions[key.first];
      bool lowInferred = !std::isfinite(type->realLo) && !x.openBottom;
      bool highInferred = !std::isfinite(type->realHi) && !x.openTop;
      if ((lowInferred && !std::isfinite(l)) ||
          (highInferred && !std::isfinite(h)))
        return error(t.loc, "transition '" + t.name + "' resets '" + x.name +
                                "' from reals with no bound on one side; "
                                "discretise needs its range bounded (give "
                                "a range)");
      if (lowInferred && l < x.lo) {
        x.lo = l;
        changed = true;
      }
      if (highInferred && h > x.hi) {
        x.hi = h;
        changed = true;
      }
    }
    if (!changed)
      return true;
  }
  auto &[key, tx] = *transferResets.begin();
  const Transition &t = m.transitions[key.first];
  return error(t.loc, "the resets reading other reals (transition '" + t.name +
                          "' resets '" + reals[key.second].name +
                          "') widen their ranges without end; discretise "
                          "needs bounded ranges (give a range)");
}
