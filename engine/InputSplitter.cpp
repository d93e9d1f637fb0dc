//===- InputSplitter.cpp - classes of input valuations, one by one --------===//
#include "engine/InputSplitter.h"

#include <cassert>

using namespace netlift::sem;

InputSplitter::Segment
InputSplitter::decide(uint32_t input,
                      llvm::function_ref<void(std::vector<Segment> &)> cut) {
  if (cursor < decisions.size()) {
    // Replaying the prefix: a deterministic execution asks the same
    // questions in the same order.
    const Decision &d = decisions[cursor++];
    assert(d.input == input && "the execution is not deterministic");
    (void)input;
    return segments[d.first + d.choice];
  }
  scratch.clear();
  cut(scratch);
  assert(!scratch.empty() && "a decision needs a segment");
  // A single segment is recorded too: replay finds every point of the
  // execution at its position, so a point need not be recomputed to know
  // that it had nothing to decide.
  Decision d{input, uint32_t(segments.size()), uint32_t(scratch.size()), 0};
  segments.insert(segments.end(), scratch.begin(), scratch.end());
  decisions.push_back(d);
  ++cursor;
  return segments[d.first];
}

bool InputSplitter::advance() {
  ++runs;
  // Decisions past the cursor were recorded by an earlier execution that
  // this one did not reach again: impossible when deterministic.
  assert(cursor == decisions.size() && "the execution is not deterministic");
  while (!decisions.empty()) {
    Decision &d = decisions.back();
    if (d.choice + 1 < d.count) {
      ++d.choice;
      return true;
    }
    segments.resize(d.first);
    decisions.pop_back();
  }
  return false;
}
