//===- StateStore.h - the set of visited states -----------------*- C++ -*-===//
//
// Stores packed states contiguously in one flat arena (no per-state heap
// allocation) and finds them through an open-addressing table of
// (hash, index) pairs, so a state costs its packed words plus 8 bytes of
// table (at most 16 at the table's lowest load). States are numbered in
// insertion order; that number is the state's identity in every output.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STATESPACE_STATESTORE_H
#define NETLIFT_BACKENDS_STATESPACE_STATESTORE_H

#include "ir/support/HugePageAllocator.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace netlift::statespace {

class StateStore {
public:
  explicit StateStore(uint32_t wordsPerState) : words(wordsPerState) {}

  /// The index of `state`, and whether it was new.
  std::pair<uint32_t, bool> insert(const uint64_t *state);
  /// The index of `state`, or UINT32_MAX when it is not stored.
  uint32_t find(const uint64_t *state) const;
  const uint64_t *state(uint32_t i) const { return &arena[size_t(i) * words]; }
  uint32_t size() const { return count; }
  uint32_t wordsPerState() const { return words; }
  /// Bytes held (arena and table, by capacity).
  size_t bytes() const {
    return arena.capacity() * sizeof(uint64_t) +
           table.capacity() * sizeof(Bucket);
  }

private:
  struct Bucket {
    uint32_t hash;
    uint32_t index; // kEmpty when free
  };
  static constexpr uint32_t kEmpty = UINT32_MAX;
  static uint32_t hashState(const uint64_t *s, uint32_t n);
  void grow();

  uint32_t words;
  uint32_t count = 0;
  std::vector<uint64_t, HugePageAllocator<uint64_t>> arena;
  std::vector<Bucket, HugePageAllocator<Bucket>> table;
};

} // namespace netlift::statespace

#endif
