//===- InputSplitter.h - classes of input valuations, one by one -*- C++
//-*-===//
//
// The free inputs of a step are split on demand (docs/semantics.md, "Free
// inputs"): an execution of the step runs with each input ranging over an
// interval, and wherever the execution needs to know more about an input
// (a branch on it, a comparison, a value stored) it asks for a *decision*:
// the input's current interval is cut into segments on which the needed
// answer is constant, and the execution continues in one of them. A class
// of input valuations is the sequence of choices one execution made — a
// decision prefix — and every class is run by re-executing the step from
// the start with a longer or different prefix, depth first, until every
// choice of every decision has been taken.
//
// The splitter knows nothing of expressions: it records decisions and
// replays them, so any executor — the interpreter today, compiled code
// later — can drive it. An executor calls start() before each execution,
// decide() at each decision point (same points, same order, as long as it
// is deterministic), and advance() after it; advance() returns false when
// the classes are exhausted.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_INPUTSPLITTER_H
#define NETLIFT_ENGINE_INPUTSPLITTER_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/STLFunctionalExtras.h"

#include <cstdint>
#include <vector>

namespace netlift::sem {

class InputSplitter {
public:
  /// One outcome of a decision: the input's interval narrows to [lo, hi]
  /// (in the input's order keys), on which the answer is `value`, or on
  /// which the execution fails (`fails`).
  struct Segment {
    int64_t lo, hi;
    int64_t value;
    bool fails;
  };

  /// Forgets every decision: the next execution is the first class of a
  /// new set.
  void reset() {
    decisions.clear();
    segments.clear();
    cursor = 0;
    runs = 0;
  }
  /// Before each execution.
  void start() { cursor = 0; }

  /// At a decision point about input `input`: the segment the current
  /// class takes. When the point is new, `cut` is called to append the
  /// segments (in order, covering the input's interval) to its argument.
  Segment decide(uint32_t input,
                 llvm::function_ref<void(std::vector<Segment> &)> cut);

  /// After an execution: moves to the next class (the last decision with a
  /// choice left takes its next one, and what followed it is forgotten).
  /// False when every class has run.
  bool advance();

  /// Executions since reset(): the number of classes run.
  uint64_t classesRun() const { return runs; }
  /// The current class's decisions: (input, number of segments).
  template <typename F> void forEachDecision(F f) const {
    for (const Decision &d : decisions)
      f(d.input, d.count);
  }

private:
  struct Decision {
    uint32_t input;
    uint32_t first, count; // its segments in `segments`
    uint32_t choice;
  };
  std::vector<Decision> decisions;
  std::vector<Segment> segments;
  std::vector<Segment> scratch;
  size_t cursor = 0;
  uint64_t runs = 0;
};

} // namespace netlift::sem

#endif
