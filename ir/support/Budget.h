//===- Budget.h - the time and memory a run may take --------------*- C++
//-*-===//
//
// --time-limit and --max-memory are promises to someone's CI job: a run
// ends within a second of its time limit and near its memory limit, with
// its partial result. The explorer checks its budget between states; one
// state's expansion (millions of input classes, a long scan) checks it too,
// through the same object, so no single step can overrun it.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_BUDGET_H
#define NETLIFT_IR_SUPPORT_BUDGET_H

#include <chrono>
#include <cstdint>

namespace netlift {

/// The resident memory of this process, in bytes (0 where unknown).
uint64_t residentBytes();

class Budget {
public:
  using Clock = std::chrono::steady_clock;
  /// `seconds` from now (0: no limit); `maxBytes` of resident memory (0: no
  /// limit).
  Budget(double seconds, uint64_t maxBytes);
  /// "time" or "memory" once the budget is spent, else null. Cheap enough to
  /// call at every input class: the clock is read each call, the memory
  /// every 256th.
  const char *spent();
  /// The largest resident size seen by spent().
  uint64_t peakBytes() const { return peak; }
  /// The memory now, and whether it is over the limit (read at once).
  bool overMemory(uint64_t &bytes);

private:
  bool timed;
  Clock::time_point deadline;
  uint64_t maxBytes;
  uint64_t peak = 0;
  uint32_t calls = 0;
  const char *what = nullptr;
};

} // namespace netlift

#endif
