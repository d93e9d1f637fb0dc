//===- NetDot.h - drawing a net with Graphviz -------------------*- C++ -*-===//
//
// Writes NetIR modules as Graphviz DOT so a user can look at a translated
// model: places as circles (with their tokens), transitions as bars, and the
// three kinds of arc drawn distinctly — flow arcs solid (weight and time
// interval as labels), condition arcs dashed with a dot head, event arcs
// dotted with an open head. Ports and instances appear as their own shapes.
// Output is deterministic: the order of the module's entities.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_NCES_NETDOT_H
#define NETLIFT_BACKENDS_NCES_NETDOT_H

#include "ir/net/Module.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift {

void writeDot(const net::Design &d, llvm::raw_ostream &os);

} // namespace netlift

#endif
