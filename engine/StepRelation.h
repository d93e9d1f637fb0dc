//===- StepRelation.h - what the one search explores ------------*- C++ -*-===//
//
// The interface between a model and the search (engine/Explorer.h), after
// LTSmin's PINS: a state is a fixed number of 64-bit words; a relation
// gives the initial state and, for a state, each successor with the step
// that reaches it (transition indices, or whatever the relation numbers
// its moves by). The search owns the order, the store, the limits and
// what is recorded; a relation owns only the meaning of a step. Every
// search netlift runs — reach, check, sr, Mealy extraction (a scan per
// input vector), the replay of an abstract counterexample in exact time
// (the exact model paired with the position on the path) and the search
// of the exact model — is this search over one of these relations.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_ENGINE_STEPRELATION_H
#define NETLIFT_ENGINE_STEPRELATION_H

#include "engine/Semantics.h"

#include <string>

namespace netlift::engine {

class StepRelation {
public:
  virtual ~StepRelation() = default;
  /// Words of a packed state.
  virtual uint32_t stateWords() const = 0;
  /// The initial state into `out`; false with `err` if it is invalid.
  virtual bool initialState(uint64_t *out, sem::RuntimeError &err) = 0;
  /// Calls `each` for every successor of `state`; false with `err` after a
  /// runtime error (the successors given before it stand).
  virtual bool successors(const uint64_t *state, sem::Semantics::Callback each,
                          sem::RuntimeError &err) = 0;
  /// The label of a step as traces and graphs show it.
  virtual std::string stepText(llvm::ArrayRef<uint32_t> step) const = 0;
  /// Steps numbered below this are one-move steps the search labels from
  /// a table (0: none).
  virtual uint32_t numMoves() const { return 0; }

  /// What the search also reports when the relation can say it.
  /// Time and memory checked inside one expansion (ir/support/Budget.h).
  virtual void setBudget(Budget *budget) {}
  /// Ticks exist: a state is dead only when no step follows now or after
  /// any number of ticks (the empty step is the tick).
  virtual bool isTimed() const { return false; }
  /// The relation has free inputs, and how many classes of their
  /// valuations the last expansion ran for.
  virtual bool hasFreeInputs() const { return false; }
  virtual uint64_t lastInputClasses() const { return 0; }
  /// The input condition of the successor being given (empty: none).
  virtual llvm::StringRef edgeCondition() const { return {}; }
  /// The layout the token figures of the summary are read from (null:
  /// none).
  virtual const sem::StateLayout *tokenLayout() const { return nullptr; }
  /// The module semantics explored, when the relation is one (writers
  /// show its values); null otherwise.
  virtual sem::Semantics *semantics() { return nullptr; }
};

/// The step relation of a flat module: its semantics (engine/Semantics.h).
class ModuleStepRelation final : public StepRelation {
public:
  explicit ModuleStepRelation(sem::Semantics &semantics) : sem(semantics) {}
  uint32_t stateWords() const override { return sem.layout().numWords(); }
  bool initialState(uint64_t *out, sem::RuntimeError &err) override {
    return sem.initialState(out, err);
  }
  bool successors(const uint64_t *state, sem::Semantics::Callback each,
                  sem::RuntimeError &err) override {
    return sem.successors(state, each, err);
  }
  std::string stepText(llvm::ArrayRef<uint32_t> step) const override;
  uint32_t numMoves() const override {
    return uint32_t(sem.module().transitions.size());
  }
  void setBudget(Budget *budget) override { sem.setBudget(budget); }
  bool isTimed() const override { return sem.isTimed(); }
  bool hasFreeInputs() const override { return sem.hasFreeInputs(); }
  uint64_t lastInputClasses() const override { return sem.lastInputClasses(); }
  llvm::StringRef edgeCondition() const override { return sem.edgeCondition(); }
  const sem::StateLayout *tokenLayout() const override { return &sem.layout(); }
  sem::Semantics *semantics() override { return &sem; }

private:
  sem::Semantics &sem;
};

} // namespace netlift::engine

#endif
