//===- TwinCatLib.cpp - models of TwinCAT's libraries
//----------------------===//
//
// What TwinCAT projects call from Beckhoff's libraries and netlift can model
// exactly, written in Structured Text like the standard library (StdLib.cpp)
// and added when a TwinCAT input is read: Tc2_Math's rounding and modulo
// functions on LREAL and Tc2_System's PI. Their behaviour is what Beckhoff
// documents (MODABS(-400.56, 360) = 319.44, LTRUNC(-2.8) = -2, FLOOR and
// CEIL of negative values); twincat-lib.test checks those values.
// Tc2_Standard's timers, triggers and counters are the standard ones.
//
//===----------------------------------------------------------------------===//
#include "frontends/st/StdLib.h"

using namespace netlift;

static const char kTwinCatLibrary[] = R"ST(
VAR_GLOBAL CONSTANT
  PI : LREAL := 3.14159265358979323846;
END_VAR

(* The integer part of a float as an LREAL, whatever its size: from 2^52 up
   every LREAL is whole; below, rounding half away from zero of |x| - 0.5
   truncates exactly. *)
FUNCTION LTRUNC : LREAL
  VAR_INPUT lr_in : LREAL; END_VAR
  IF ABS(lr_in) >= 4503599627370496.0 THEN
    LTRUNC := lr_in;
  ELSIF lr_in >= 0.0 THEN
    LTRUNC := LINT_TO_LREAL(LREAL_TO_LINT(lr_in - 0.5));
  ELSE
    LTRUNC := -LINT_TO_LREAL(LREAL_TO_LINT(-lr_in - 0.5));
  END_IF
END_FUNCTION

FUNCTION FLOOR : LREAL
  VAR_INPUT lr_in : LREAL; END_VAR
  FLOOR := LTRUNC(lr_in);
  IF FLOOR > lr_in THEN
    FLOOR := FLOOR - 1.0;
  END_IF
END_FUNCTION

FUNCTION CEIL : LREAL
  VAR_INPUT lr_in : LREAL; END_VAR
  CEIL := LTRUNC(lr_in);
  IF CEIL < lr_in THEN
    CEIL := CEIL + 1.0;
  END_IF
END_FUNCTION

FUNCTION FRAC : LREAL
  VAR_INPUT lr_in : LREAL; END_VAR
  FRAC := lr_in - LTRUNC(lr_in);
END_FUNCTION

(* The remainder with the sign of the value. *)
FUNCTION LMOD : LREAL
  VAR_INPUT lr_val, lr_mod : LREAL; END_VAR
  LMOD := lr_val - lr_mod * LTRUNC(lr_val / lr_mod);
END_FUNCTION

(* The value within [0, lr_mod). *)
FUNCTION MODABS : LREAL
  VAR_INPUT lr_val, lr_mod : LREAL; END_VAR
  MODABS := lr_val - lr_mod * FLOOR(lr_val / lr_mod);
END_FUNCTION
)ST";

bool st::addTwinCatLibrary(DiagEngine &diag, plc::Unit &unit) {
  return addLibraryText(diag, unit, kTwinCatLibrary,
                        "<netlift TwinCAT library>");
}
