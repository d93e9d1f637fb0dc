//===- StructuralBounds.h - token bounds from place invariants --*- C++ -*-===//
//
// Bounds on the marking of places that hold whatever the step, guard or
// event structure: every P-semiflow y (y >= 0, y^T C = 0 for the incidence
// matrix C) keeps y.m constant, so a place p covered by y never holds more
// than (y.m0) / y_p tokens. Semiflows are computed with the Farkas
// algorithm, abandoned (leaving places unknown) when it would grow beyond
// a fixed number of rows or overflow 64-bit arithmetic. The state encoding
// uses these bounds so unbounded-capacity places (every PNML place) take
// only the bits they can need.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SEMANTICS_STRUCTURALBOUNDS_H
#define NETLIFT_IR_SEMANTICS_STRUCTURALBOUNDS_H

#include "ir/net/Module.h"

#include <cstdint>
#include <vector>

namespace netlift::sem {

constexpr uint64_t kNoBound = UINT64_MAX;

/// P-semiflows of `m` (one weight per place each), or none when the Farkas
/// tableau would grow beyond `maxRows` or overflow.
std::vector<std::vector<int64_t>> placeSemiflows(const net::Module &m,
                                                 size_t maxRows = 4096);

/// For each place, a bound on its tokens from P-semiflows, or kNoBound.
std::vector<uint64_t> structuralBounds(const net::Module &m,
                                       size_t maxRows = 4096);

} // namespace netlift::sem

#endif
