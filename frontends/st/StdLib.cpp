//===- StdLib.cpp - the IEC 61131-3 standard function blocks --------------===//
//
// The standard function blocks, written in Structured Text and translated
// like the user's own code, so their behaviour is exactly what this text
// says. The behaviour is the standard's at scan granularity: an FB computes
// its outputs when it is called, from its inputs and from the time at the
// start of the scan. matiec's library (../shared/corpus/st/matiec/lib) is
// the reference the behavioural tests compare against.
//
// Timers read time through a variable marked `{netlift clock PT}`: it
// becomes a NetIR clock variable counting ticks, saturating at the largest
// value the instance's PT input is ever given (PT must be a constant per
// instance, see LowerToNet.cpp). Assigning 0 restarts it; assigning PT
// parks it saturated, which keeps idle timers from producing states that
// differ only in an elapsed time nobody reads.
//
// Where the reference keeps a PREV_IN flag that can be shown to equal a
// function of STATE whenever it is read (TON, TP), the flag is left out: it
// changes no output and would only multiply states.
//
//===----------------------------------------------------------------------===//
#include "frontends/st/StdLib.h"
#include "frontends/st/StFrontend.h"

using namespace netlift;

static const char kStandardLibrary[] = R"ST(
FUNCTION_BLOCK R_TRIG
  VAR_INPUT CLK : BOOL; END_VAR
  VAR_OUTPUT Q : BOOL; END_VAR
  VAR M : BOOL; END_VAR
  Q := CLK AND NOT M;
  M := CLK;
END_FUNCTION_BLOCK

FUNCTION_BLOCK F_TRIG
  VAR_INPUT CLK : BOOL; END_VAR
  VAR_OUTPUT Q : BOOL; END_VAR
  VAR M : BOOL; END_VAR
  Q := NOT CLK AND NOT M;
  M := NOT CLK;
END_FUNCTION_BLOCK

FUNCTION_BLOCK SR
  VAR_INPUT S1, R : BOOL; END_VAR
  VAR_OUTPUT Q1 : BOOL; END_VAR
  Q1 := S1 OR (NOT R AND Q1);
END_FUNCTION_BLOCK

FUNCTION_BLOCK RS
  VAR_INPUT S, R1 : BOOL; END_VAR
  VAR_OUTPUT Q1 : BOOL; END_VAR
  Q1 := NOT R1 AND (S OR Q1);
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTU
  VAR_INPUT CU : BOOL; R : BOOL; PV : INT; END_VAR
  VAR_OUTPUT Q : BOOL; CV : INT; END_VAR
  VAR CU_T : R_TRIG; END_VAR
  CU_T(CLK := CU);
  IF R THEN
    CV := 0;
  ELSIF CU_T.Q AND CV < 32767 THEN
    CV := CV + 1;
  END_IF;
  Q := CV >= PV;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTD
  VAR_INPUT CD : BOOL; LD : BOOL; PV : INT; END_VAR
  VAR_OUTPUT Q : BOOL; CV : INT; END_VAR
  VAR CD_T : R_TRIG; END_VAR
  CD_T(CLK := CD);
  IF LD THEN
    CV := PV;
  ELSIF CD_T.Q AND CV > -32768 THEN
    CV := CV - 1;
  END_IF;
  Q := CV <= 0;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTUD
  VAR_INPUT CU, CD, R, LD : BOOL; PV : INT; END_VAR
  VAR_OUTPUT QU, QD : BOOL; CV : INT; END_VAR
  VAR CU_T, CD_T : R_TRIG; END_VAR
  CU_T(CLK := CU);
  CD_T(CLK := CD);
  IF R THEN
    CV := 0;
  ELSIF LD THEN
    CV := PV;
  ELSIF NOT (CU_T.Q AND CD_T.Q) THEN
    IF CU_T.Q AND CV < 32767 THEN
      CV := CV + 1;
    ELSIF CD_T.Q AND CV > -32768 THEN
      CV := CV - 1;
    END_IF;
  END_IF;
  QU := CV >= PV;
  QD := CV <= 0;
END_FUNCTION_BLOCK

FUNCTION_BLOCK TON
  VAR_INPUT IN : BOOL; PT : TIME; END_VAR
  VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
  VAR
    STATE : SINT; (* 0 idle, 1 timing, 2 elapsed *)
    {netlift clock PT} CLOCK : TIME;
  END_VAR
  IF NOT IN THEN
    Q := FALSE;
    ET := T#0s;
    STATE := 0;
    CLOCK := PT;
  ELSIF STATE = 0 THEN
    STATE := 1;
    Q := FALSE;
    CLOCK := T#0s;
  ELSIF STATE = 1 THEN
    IF CLOCK >= PT THEN
      STATE := 2;
      Q := TRUE;
      ET := PT;
      CLOCK := PT;
    ELSE
      ET := CLOCK;
    END_IF;
  END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK TOF
  VAR_INPUT IN : BOOL; PT : TIME; END_VAR
  VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
  VAR
    STATE : SINT; (* 0 idle, 1 timing, 2 elapsed *)
    PREV_IN : BOOL;
    {netlift clock PT} CLOCK : TIME;
  END_VAR
  IF IN THEN
    ET := T#0s;
    STATE := 0;
    CLOCK := PT;
  ELSIF STATE = 0 THEN
    IF PREV_IN THEN
      STATE := 1;
      CLOCK := T#0s;
    END_IF;
  ELSIF STATE = 1 THEN
    IF CLOCK >= PT THEN
      STATE := 2;
      ET := PT;
      CLOCK := PT;
    ELSE
      ET := CLOCK;
    END_IF;
  END_IF;
  Q := IN OR STATE = 1;
  PREV_IN := IN;
END_FUNCTION_BLOCK

FUNCTION_BLOCK TP
  VAR_INPUT IN : BOOL; PT : TIME; END_VAR
  VAR_OUTPUT Q : BOOL; ET : TIME; END_VAR
  VAR
    STATE : SINT; (* 0 idle, 1 pulsing, 2 pulse over *)
    {netlift clock PT} CLOCK : TIME;
  END_VAR
  IF STATE = 0 AND IN THEN
    STATE := 1;
    Q := TRUE;
    CLOCK := T#0s;
  ELSIF STATE = 1 THEN
    IF CLOCK >= PT THEN
      STATE := 2;
      Q := FALSE;
      ET := PT;
      CLOCK := PT;
    ELSE
      ET := CLOCK;
    END_IF;
  END_IF;
  IF STATE = 2 AND NOT IN THEN
    ET := T#0s;
    STATE := 0;
  END_IF;
END_FUNCTION_BLOCK
)ST";

bool st::isStandardFunctionBlock(llvm::StringRef name) {
  for (const char *fb : {"R_TRIG", "F_TRIG", "SR", "RS", "CTU", "CTD", "CTUD",
                         "TON", "TOF", "TP"})
    if (name.equals_insensitive(fb))
      return true;
  return false;
}

bool st::addStandardLibrary(DiagEngine &diag, plc::Unit &unit) {
  // Only the blocks the user did not define are kept, so a user's own TON
  // replaces netlift's.
  llvm::SourceMgr &sm = diag.sourceMgr();
  unsigned id =
      sm.AddNewSourceBuffer(llvm::MemoryBuffer::getMemBuffer(
                                kStandardLibrary, "<netlift standard library>"),
                            llvm::SMLoc());
  std::vector<plc::Pou *> before = unit.pous;
  if (!parseStructuredText(sm.getMemoryBuffer(id)->getBuffer(), diag, unit))
    return false;
  std::vector<plc::Pou *> merged = before;
  for (size_t i = before.size(); i < unit.pous.size(); ++i) {
    plc::Pou *p = unit.pous[i];
    p->isLibrary = true;
    bool shadowed = false;
    for (plc::Pou *u : before)
      shadowed |= plc::sameName(u->name, p->name);
    if (!shadowed)
      merged.push_back(p);
  }
  unit.pous = std::move(merged);
  return true;
}
