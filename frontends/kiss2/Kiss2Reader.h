//===- Kiss2Reader.h - KISS2 finite state machines --------------*- C++ -*-===//
//
// Reads KISS2 (the SIS/MCNC/LGSynth91 FSM format) into a MealyMachine:
// `.i .o .p .s .r`, optional `.ilb`/`.ob` signal names (else i1..iN and
// o1..oM), rows `INPUTS CURRENT NEXT OUTPUTS` with 0/1/- cubes kept as
// written, `.e` ending the machine, `#` comments. A missing `.r` makes the
// first row's state initial; a missing `.p` is tolerated, a wrong `.p` or
// `.s` is a warning. Errors point at the offending line and column.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_KISS2_KISS2READER_H
#define NETLIFT_FRONTENDS_KISS2_KISS2READER_H

#include "ir/automata/Mealy.h"
#include "ir/support/Diagnostics.h"

namespace netlift::kiss2 {

bool readKiss2(unsigned bufferID, DiagEngine &diag,
               automata::MealyMachine &machine);

} // namespace netlift::kiss2

#endif
