//===- StateStore.cpp - the set of visited states -------------------------===//
#include "engine/StateStore.h"

#include <algorithm>

using namespace netlift::engine;

uint32_t StateStore::hashState(const uint64_t *s, uint32_t n) {
  // Words are combined by multiply-xorshift, then the whole is finished by
  // the murmur3 64-bit finaliser, whose every output bit depends on every
  // input bit: packed markings differ in few, clustered bits, and both the
  // bucket (low bits) and the kept 32-bit hash must still spread.
  uint64_t h = 0x9E3779B97F4A7C15ull * (n + 1);
  for (uint32_t i = 0; i < n; ++i) {
    h = (h ^ s[i]) * 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
  }
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ull;
  h ^= h >> 33;
  return uint32_t(h);
}

void StateStore::grow() {
  size_t n = table.empty() ? 1024 : table.size() * 2;
  std::vector<Bucket, HugePageAllocator<Bucket>> fresh(n, Bucket{0, kEmpty});
  size_t mask = n - 1;
  for (const Bucket &b : table) {
    if (b.index == kEmpty)
      continue;
    size_t i = b.hash & mask;
    while (fresh[i].index != kEmpty)
      i = (i + 1) & mask;
    fresh[i] = b;
  }
  table = std::move(fresh);
}

/// Word-wise equality; states are a few words, where a call to memcmp
/// costs more than the comparison.
static inline bool sameState(const uint64_t *a, const uint64_t *b, uint32_t n) {
  for (uint32_t i = 0; i < n; ++i)
    if (a[i] != b[i])
      return false;
  return true;
}

uint32_t StateStore::find(const uint64_t *s, uint32_t h) const {
  if (table.empty())
    return kEmpty;
  size_t mask = table.size() - 1;
  for (size_t i = h & mask;; i = (i + 1) & mask) {
    const Bucket &b = table[i];
    if (b.index == kEmpty)
      return kEmpty;
    if (b.hash == h && sameState(state(b.index), s, words))
      return b.index;
  }
}

std::pair<uint32_t, bool> StateStore::insert(const uint64_t *s, uint32_t h) {
  if ((size_t(count) + 1) * 4 > table.size() * 3)
    grow();
  size_t mask = table.size() - 1;
  size_t i = h & mask;
  for (;; i = (i + 1) & mask) {
    Bucket &b = table[i];
    if (b.index == kEmpty)
      break;
    if (b.hash == h && sameState(state(b.index), s, words))
      return {b.index, false};
  }
  uint32_t idx = count++;
  table[i] = {h, idx};
  if ((idx & blockMask) == 0)
    blocks.emplace_back(blockBytes());
  std::copy(s, s + words, &blocks.back()[size_t(idx & blockMask) * words]);
  return {idx, true};
}
