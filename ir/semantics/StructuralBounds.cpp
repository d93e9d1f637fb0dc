//===- StructuralBounds.cpp - token bounds from place invariants ----------===//
#include "ir/semantics/StructuralBounds.h"

#include <algorithm>
#include <numeric>
#include <set>

using namespace netlift;
using namespace netlift::sem;
using namespace netlift::net;

namespace {
/// One row of the Farkas tableau: the remaining incidence columns and the
/// combination of places it stands for.
struct Row {
  std::vector<int64_t> c; // per transition
  std::vector<int64_t> y; // per place
  bool operator<(const Row &o) const { return y < o.y; }
};

bool combine(const Row &a, int64_t fa, const Row &b, int64_t fb, Row &out) {
  out.c.resize(a.c.size());
  out.y.resize(a.y.size());
  int64_t g = 0;
  for (size_t i = 0; i < a.c.size(); ++i) {
    int64_t x, y2, s;
    if (__builtin_mul_overflow(a.c[i], fa, &x) ||
        __builtin_mul_overflow(b.c[i], fb, &y2) ||
        __builtin_add_overflow(x, y2, &s))
      return false;
    out.c[i] = s;
    g = std::gcd(g, s < 0 ? -s : s);
  }
  for (size_t i = 0; i < a.y.size(); ++i) {
    int64_t x, y2, s;
    if (__builtin_mul_overflow(a.y[i], fa, &x) ||
        __builtin_mul_overflow(b.y[i], fb, &y2) ||
        __builtin_add_overflow(x, y2, &s))
      return false;
    out.y[i] = s;
    g = std::gcd(g, s);
  }
  if (g > 1) {
    for (int64_t &v : out.c)
      v /= g;
    for (int64_t &v : out.y)
      v /= g;
  }
  return true;
}
} // namespace

std::vector<std::vector<int64_t>> netlift::sem::placeSemiflows(const Module &m,
                                                               size_t maxRows) {
  size_t P = m.places.size(), T = m.transitions.size();
  std::vector<Row> rows(P);
  for (size_t p = 0; p < P; ++p) {
    rows[p].c.assign(T, 0);
    rows[p].y.assign(P, 0);
    rows[p].y[p] = 1;
  }
  for (size_t t = 0; t < T; ++t) {
    for (const PreArc &a : m.transitions[t].pre())
      rows[a.place].c[t] -= a.weight;
    for (const PostArc &a : m.transitions[t].post())
      rows[a.place].c[t] += a.weight;
  }
  for (size_t t = 0; t < T; ++t) {
    std::vector<Row> zero, pos, neg;
    for (Row &r : rows)
      (r.c[t] == 0 ? zero : r.c[t] > 0 ? pos : neg).push_back(std::move(r));
    if (pos.empty() || neg.empty()) {
      rows = std::move(zero); // rows that move this column cannot be fixed
      continue;
    }
    if (zero.size() + pos.size() * neg.size() > maxRows)
      return {}; // too expensive: no semiflows
    for (const Row &a : pos)
      for (const Row &b : neg) {
        Row r;
        if (!combine(a, -b.c[t], b, a.c[t], r))
          return {};
        zero.push_back(std::move(r));
      }
    // Drop duplicates to keep the tableau small.
    std::sort(zero.begin(), zero.end());
    zero.erase(
        std::unique(zero.begin(), zero.end(),
                    [](const Row &a, const Row &b) { return a.y == b.y; }),
        zero.end());
    rows = std::move(zero);
  }
  std::vector<std::vector<int64_t>> flows;
  for (Row &r : rows)
    flows.push_back(std::move(r.y));
  return flows;
}

std::vector<uint64_t> netlift::sem::structuralBounds(const Module &m,
                                                     size_t maxRows) {
  size_t P = m.places.size();
  std::vector<uint64_t> bounds(P, kNoBound);
  for (const std::vector<int64_t> &y : placeSemiflows(m, maxRows)) {
    uint64_t weighted = 0;
    bool overflow = false;
    for (size_t p = 0; p < P && !overflow; ++p) {
      uint64_t term;
      overflow |= __builtin_mul_overflow(uint64_t(y[p]),
                                         uint64_t(m.places[p].tokens), &term) ||
                  __builtin_add_overflow(weighted, term, &weighted);
    }
    if (overflow)
      continue;
    for (size_t p = 0; p < P; ++p)
      if (y[p] > 0)
        bounds[p] = std::min(bounds[p], weighted / uint64_t(y[p]));
  }
  return bounds;
}
