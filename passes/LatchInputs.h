//===- LatchInputs.h - free inputs kept as the PLC's input image -*- C++
//-*-===//
//
// `latch-inputs` (docs/check.md, "Properties over inputs"): a free input
// takes every value at every step and is part of no state, so a property
// cannot name it. A PLC does keep it: the input image holds what the last
// scan read. Latching an input gives the module a variable of that name,
// set to the input's value by the step that reads it (the scan), while the
// environment's value itself becomes the input `NAME.env`. Properties and
// --find may then name it (`AG (overload -> !contactor)`: an input and the
// output the same scan drives). The state space grows by what the image
// tells apart; nothing else changes.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_LATCHINPUTS_H
#define NETLIFT_PASSES_LATCHINPUTS_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <string>
#include <vector>

namespace netlift {

/// Latches the free inputs of the flat, verified module `m` named in
/// `names` (in that order, each once). An input must be read by exactly
/// one transition (a PLC's scan): with several, which read it last in a
/// step would be ambiguous, and the refusal names them. The design is
/// verified again. False after reporting.
bool latchInputs(net::Design &d, net::Module &m,
                 const std::vector<std::string> &names, DiagEngine &diag);

/// The free (cond or data) inputs of `m` that `text` names: identifiers of
/// a property or a --find expression equal to an input's name, in the
/// module's port order.
std::vector<std::string> inputsNamedIn(const net::Module &m,
                                       llvm::StringRef text);

/// The input that carries the environment's value of latched input `name`.
std::string latchedEnvironmentInput(llvm::StringRef name);

} // namespace netlift

#endif
