//===- StateStore.h - the set of visited states -----------------*- C++ -*-===//
//
// Stores packed states in a flat arena of fixed-size blocks (no per-state
// heap allocation, no copying when it grows, no doubling slack) and finds
// them through an open-addressing table of (hash, index) pairs, so a state
// costs its packed words plus 8 bytes of table (16 at the table's lowest
// load). States are numbered in insertion order; that number is the
// state's identity in every output.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_STATESTORE_H
#define NETLIFT_ENGINE_STATESTORE_H

#include "ir/support/HugePageAllocator.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace netlift::engine {

class StateStore {
public:
  explicit StateStore(uint32_t wordsPerState) : words(wordsPerState) {
    // Blocks of at least one huge page (see blockBytes).
    while ((size_t(1) << blockShift) * words * sizeof(uint64_t) <
           detail::kHugeThreshold)
      ++blockShift;
    blockMask = (uint32_t(1) << blockShift) - 1;
  }
  StateStore(const StateStore &) = delete;
  StateStore &operator=(const StateStore &) = delete;

  /// The index of `state`, and whether it was new.
  std::pair<uint32_t, bool> insert(const uint64_t *state) {
    return insert(state, hash(state));
  }
  /// The same, with `h == hash(state)` computed beforehand.
  std::pair<uint32_t, bool> insert(const uint64_t *state, uint32_t h);
  static constexpr uint32_t kNotFound = UINT32_MAX;
  /// The index of `state`, or kNotFound when it is not stored.
  uint32_t find(const uint64_t *state) const {
    return find(state, hash(state));
  }
  uint32_t find(const uint64_t *state, uint32_t h) const;

  uint32_t hash(const uint64_t *state) const { return hashState(state, words); }
  /// Look-ahead for a batch of lookups: a table far larger than the cache
  /// costs a miss per lookup, so a caller with several states to look up
  /// first calls prefetchBucket for all of them, then prefetchCandidate
  /// (which reads the now-cached bucket and fetches the stored state it
  /// points to), then inserts: the misses overlap instead of adding up.
  void prefetchBucket(uint32_t h) const {
    if (!table.empty())
      __builtin_prefetch(&table[h & (table.size() - 1)]);
  }
  void prefetchCandidate(uint32_t h) const {
    if (table.empty())
      return;
    const Bucket &b = table[h & (table.size() - 1)];
    if (b.index != kEmpty && b.hash == h)
      __builtin_prefetch(state(b.index));
  }
  const uint64_t *state(uint32_t i) const {
    return &blocks[i >> blockShift][size_t(i & blockMask) * words];
  }
  uint32_t size() const { return count; }
  uint32_t wordsPerState() const { return words; }
  /// Bytes the stored states occupy: their words plus the index table.
  size_t storedBytes() const {
    return size_t(count) * words * sizeof(uint64_t) +
           table.capacity() * sizeof(Bucket);
  }
  /// Bytes held (arena blocks and table, by capacity).
  size_t bytes() const {
    return blocks.size() * blockBytes() + table.capacity() * sizeof(Bucket);
  }

private:
  struct Bucket {
    uint32_t hash;
    uint32_t index; // kEmpty when free
  };
  static constexpr uint32_t kEmpty = UINT32_MAX;
  static uint32_t hashState(const uint64_t *s, uint32_t n);
  void grow();

  // 2^blockShift states per block: at least 2^16 and at least one huge
  // page (every lookup reads the arena at random, so its pages must be
  // huge), yet small enough that a small model does not reserve much.
  size_t blockBytes() const {
    return (size_t(1) << blockShift) * words * sizeof(uint64_t);
  }
  /// Uninitialised storage for one block (pages are touched only as
  /// states are written).
  struct Block {
    uint64_t *data;
    size_t bytes;
    explicit Block(size_t n)
        : data(static_cast<uint64_t *>(detail::hugeAllocate(n))), bytes(n) {}
    Block(Block &&o) noexcept : data(o.data), bytes(o.bytes) {
      o.data = nullptr;
    }
    Block(const Block &) = delete;
    ~Block() {
      if (data)
        detail::hugeDeallocate(data, bytes);
    }
    uint64_t &operator[](size_t i) { return data[i]; }
    const uint64_t &operator[](size_t i) const { return data[i]; }
  };

  uint32_t words;
  uint32_t blockShift = 16, blockMask;
  uint32_t count = 0;
  std::vector<Block> blocks;
  std::vector<Bucket, HugePageAllocator<Bucket>> table;
};

} // namespace netlift::engine

#endif
