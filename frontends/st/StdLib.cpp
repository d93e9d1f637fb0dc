//===- StdLib.cpp - the IEC 61131-3 standard function blocks --------------===//
//
// The standard function blocks, and the standard functions on dates and
// times (IEC 61131-3 3rd edition, Tables 35 and 36: ADD_TOD_TIME ...
// CONCAT_DATE, SPLIT_DT, DAY_OF_WEEK), written in Structured Text and
// translated like the user's own code, so their behaviour is exactly what
// this text says. A date function given a month, day or hour that does not
// exist stops with a runtime error naming the field (a subrange variable). The
// behaviour is the standard's at scan granularity: an FB computes its outputs
// when it is called, from its inputs and from the time at the start of the
// scan. matiec's library (../shared/corpus/st/matiec/lib) is the reference the
// behavioural tests compare against.
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

FUNCTION CONCAT_LDATE : LDATE
  VAR_INPUT YEAR, MONTH, DAY : LINT; END_VAR
  VAR
    checked_month : LINT(1..12);
    checked_day : LINT(1..31);
    days_past_month_end : LINT(-30..0);
    y, era, yoe, doe : LINT;
  END_VAR
  checked_month := MONTH;
  checked_day := DAY;
  IF MONTH = 2 THEN
    IF (YEAR MOD 4 = 0 AND YEAR MOD 100 <> 0) OR YEAR MOD 400 = 0 THEN
      days_past_month_end := DAY - 29;
    ELSE
      days_past_month_end := DAY - 28;
    END_IF;
  ELSIF MONTH = 4 OR MONTH = 6 OR MONTH = 9 OR MONTH = 11 THEN
    days_past_month_end := DAY - 30;
  END_IF;
  (* Days since 1970-01-01 counted in 400-year eras from 0000-03-01. *)
  y := YEAR;
  IF MONTH <= 2 THEN y := y - 1; END_IF;
  IF y >= 0 THEN era := y / 400; ELSE era := (y - 399) / 400; END_IF;
  yoe := y - era * 400;
  IF MONTH > 2 THEN
    doe := (153 * (MONTH - 3) + 2) / 5 + DAY - 1;
  ELSE
    doe := (153 * (MONTH + 9) + 2) / 5 + DAY - 1;
  END_IF;
  doe := yoe * 365 + yoe / 4 - yoe / 100 + doe;
  CONCAT_LDATE := LINT_TO_LDATE((era * 146097 + doe - 719468) * 86400000000000);
END_FUNCTION

FUNCTION CONCAT_LTOD : LTOD
  VAR_INPUT HOUR, MINUTE, SECOND, MILLISECOND : LINT; END_VAR
  VAR
    checked_hour : LINT(0..23);
    checked_minute, checked_second : LINT(0..59);
    checked_millisecond : LINT(0..999);
  END_VAR
  checked_hour := HOUR;
  checked_minute := MINUTE;
  checked_second := SECOND;
  checked_millisecond := MILLISECOND;
  CONCAT_LTOD := LINT_TO_LTOD(((HOUR * 60 + MINUTE) * 60 + SECOND) *
                              1000000000 + MILLISECOND * 1000000);
END_FUNCTION

FUNCTION CONCAT_LDT : LDT
  VAR_INPUT YEAR, MONTH, DAY, HOUR, MINUTE, SECOND, MILLISECOND : LINT;
  END_VAR
  CONCAT_LDT := CONCAT_LDATE_LTOD(CONCAT_LDATE(YEAR, MONTH, DAY),
                  CONCAT_LTOD(HOUR, MINUTE, SECOND, MILLISECOND));
END_FUNCTION

FUNCTION CONCAT_DATE : DATE
  VAR_INPUT YEAR, MONTH, DAY : LINT; END_VAR
  CONCAT_DATE := CONCAT_LDATE(YEAR, MONTH, DAY);
END_FUNCTION

FUNCTION CONCAT_TOD : TOD
  VAR_INPUT HOUR, MINUTE, SECOND, MILLISECOND : LINT; END_VAR
  CONCAT_TOD := CONCAT_LTOD(HOUR, MINUTE, SECOND, MILLISECOND);
END_FUNCTION

FUNCTION CONCAT_DT : DT
  VAR_INPUT YEAR, MONTH, DAY, HOUR, MINUTE, SECOND, MILLISECOND : LINT;
  END_VAR
  CONCAT_DT := CONCAT_LDT(YEAR, MONTH, DAY, HOUR, MINUTE, SECOND, MILLISECOND);
END_FUNCTION

FUNCTION CONCAT_LDATE_LTOD : LDT
  VAR_INPUT IN1 : LDATE; IN2 : LTOD; END_VAR
  CONCAT_LDATE_LTOD := LINT_TO_LDT(LDATE_TO_LINT(IN1) + LTOD_TO_LINT(IN2));
END_FUNCTION

FUNCTION CONCAT_DATE_TOD : DT
  VAR_INPUT IN1 : DATE; IN2 : TOD; END_VAR
  CONCAT_DATE_TOD := CONCAT_LDATE_LTOD(IN1, IN2);
END_FUNCTION

FUNCTION SPLIT_LDATE
  VAR_INPUT IN : LDATE; END_VAR
  VAR_OUTPUT YEAR, MONTH, DAY : INT; END_VAR
  VAR z, era, doe, yoe, doy, mp : LINT; END_VAR
  z := LDATE_TO_LINT(IN);
  IF z >= 0 THEN
    z := z / 86400000000000;
  ELSE
    z := (z + 1) / 86400000000000 - 1;
  END_IF;
  z := z + 719468;
  IF z >= 0 THEN era := z / 146097; ELSE era := (z - 146096) / 146097; END_IF;
  doe := z - era * 146097;
  yoe := (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  doy := doe - (365 * yoe + yoe / 4 - yoe / 100);
  mp := (5 * doy + 2) / 153;
  DAY := LINT_TO_INT(doy - (153 * mp + 2) / 5 + 1);
  IF mp < 10 THEN MONTH := LINT_TO_INT(mp + 3);
  ELSE MONTH := LINT_TO_INT(mp - 9); END_IF;
  IF MONTH <= 2 THEN
    YEAR := LINT_TO_INT(yoe + era * 400 + 1);
  ELSE
    YEAR := LINT_TO_INT(yoe + era * 400);
  END_IF;
END_FUNCTION

FUNCTION SPLIT_LTOD
  VAR_INPUT IN : LTOD; END_VAR
  VAR_OUTPUT HOUR, MINUTE, SECOND, MILLISECOND : INT; END_VAR
  VAR ms : LINT; END_VAR
  ms := LTOD_TO_LINT(IN) / 1000000;
  MILLISECOND := LINT_TO_INT(ms MOD 1000);
  SECOND := LINT_TO_INT(ms / 1000 MOD 60);
  MINUTE := LINT_TO_INT(ms / 60000 MOD 60);
  HOUR := LINT_TO_INT(ms / 3600000);
END_FUNCTION

FUNCTION SPLIT_LDT
  VAR_INPUT IN : LDT; END_VAR
  VAR_OUTPUT YEAR, MONTH, DAY, HOUR, MINUTE, SECOND, MILLISECOND : INT;
  END_VAR
  SPLIT_LDATE(IN := LDT_TO_LDATE(IN), YEAR => YEAR, MONTH => MONTH,
              DAY => DAY);
  SPLIT_LTOD(IN := LDT_TO_LTOD(IN), HOUR => HOUR, MINUTE => MINUTE,
             SECOND => SECOND, MILLISECOND => MILLISECOND);
END_FUNCTION

FUNCTION SPLIT_DATE
  VAR_INPUT IN : DATE; END_VAR
  VAR_OUTPUT YEAR, MONTH, DAY : INT; END_VAR
  SPLIT_LDATE(IN := IN, YEAR => YEAR, MONTH => MONTH, DAY => DAY);
END_FUNCTION

FUNCTION SPLIT_TOD
  VAR_INPUT IN : TOD; END_VAR
  VAR_OUTPUT HOUR, MINUTE, SECOND, MILLISECOND : INT; END_VAR
  SPLIT_LTOD(IN := IN, HOUR => HOUR, MINUTE => MINUTE, SECOND => SECOND,
             MILLISECOND => MILLISECOND);
END_FUNCTION

FUNCTION SPLIT_DT
  VAR_INPUT IN : DT; END_VAR
  VAR_OUTPUT YEAR, MONTH, DAY, HOUR, MINUTE, SECOND, MILLISECOND : INT;
  END_VAR
  SPLIT_LDT(IN := IN, YEAR => YEAR, MONTH => MONTH, DAY => DAY,
            HOUR => HOUR, MINUTE => MINUTE, SECOND => SECOND,
            MILLISECOND => MILLISECOND);
END_FUNCTION

FUNCTION DAY_OF_WEEK : INT
  VAR_INPUT IN : LDATE; END_VAR
  VAR d : LINT; END_VAR
  (* 0 = Sunday; 1970-01-01 was a Thursday. *)
  d := LDATE_TO_LINT(IN);
  IF d >= 0 THEN
    d := d / 86400000000000;
  ELSE
    d := (d + 1) / 86400000000000 - 1;
  END_IF;
  d := (d + 4) MOD 7;
  IF d < 0 THEN d := d + 7; END_IF;
  DAY_OF_WEEK := LINT_TO_INT(d);
END_FUNCTION

FUNCTION ADD_TOD_TIME : TOD
  VAR_INPUT IN1 : TOD; IN2 : TIME; END_VAR
  ADD_TOD_TIME := IN1 + IN2;
END_FUNCTION

FUNCTION ADD_DT_TIME : DT
  VAR_INPUT IN1 : DT; IN2 : TIME; END_VAR
  ADD_DT_TIME := IN1 + IN2;
END_FUNCTION

FUNCTION SUB_TOD_TIME : TOD
  VAR_INPUT IN1 : TOD; IN2 : TIME; END_VAR
  SUB_TOD_TIME := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_DT_TIME : DT
  VAR_INPUT IN1 : DT; IN2 : TIME; END_VAR
  SUB_DT_TIME := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_DATE_DATE : TIME
  VAR_INPUT IN1 : DATE; IN2 : DATE; END_VAR
  SUB_DATE_DATE := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_TOD_TOD : TIME
  VAR_INPUT IN1 : TOD; IN2 : TOD; END_VAR
  SUB_TOD_TOD := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_DT_DT : TIME
  VAR_INPUT IN1 : DT; IN2 : DT; END_VAR
  SUB_DT_DT := IN1 - IN2;
END_FUNCTION

FUNCTION ADD_LTOD_LTIME : LTOD
  VAR_INPUT IN1 : LTOD; IN2 : LTIME; END_VAR
  ADD_LTOD_LTIME := IN1 + IN2;
END_FUNCTION

FUNCTION ADD_LDT_LTIME : LDT
  VAR_INPUT IN1 : LDT; IN2 : LTIME; END_VAR
  ADD_LDT_LTIME := IN1 + IN2;
END_FUNCTION

FUNCTION SUB_LTOD_LTIME : LTOD
  VAR_INPUT IN1 : LTOD; IN2 : LTIME; END_VAR
  SUB_LTOD_LTIME := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_LDT_LTIME : LDT
  VAR_INPUT IN1 : LDT; IN2 : LTIME; END_VAR
  SUB_LDT_LTIME := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_LDATE_LDATE : LTIME
  VAR_INPUT IN1 : LDATE; IN2 : LDATE; END_VAR
  SUB_LDATE_LDATE := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_LTOD_LTOD : LTIME
  VAR_INPUT IN1 : LTOD; IN2 : LTOD; END_VAR
  SUB_LTOD_LTOD := IN1 - IN2;
END_FUNCTION

FUNCTION SUB_LDT_LDT : LTIME
  VAR_INPUT IN1 : LDT; IN2 : LDT; END_VAR
  SUB_LDT_LDT := IN1 - IN2;
END_FUNCTION

FUNCTION ADD_TIME : TIME
  VAR_INPUT IN1 : TIME; IN2 : TIME; END_VAR
  ADD_TIME := IN1 + IN2;
END_FUNCTION

FUNCTION SUB_TIME : TIME
  VAR_INPUT IN1 : TIME; IN2 : TIME; END_VAR
  SUB_TIME := IN1 - IN2;
END_FUNCTION

FUNCTION ADD_LTIME : LTIME
  VAR_INPUT IN1 : LTIME; IN2 : LTIME; END_VAR
  ADD_LTIME := IN1 + IN2;
END_FUNCTION

(* The additional blocks of IEC 61131-3 2nd edition, Annex F, which
   matiec, OpenPLC and Beremiz ship with every program. Their sampling
   period CYCLE counts in seconds, whatever the dialect converts TIME to
   numbers in. *)
FUNCTION_BLOCK HYSTERESIS
  VAR_INPUT XIN1, XIN2, EPS : REAL; END_VAR
  VAR_OUTPUT Q : BOOL := FALSE; END_VAR
  (* Q rises above the band around XIN2 and falls below it. *)
  IF Q AND XIN1 < XIN2 - EPS THEN
    Q := FALSE;
  ELSIF NOT Q AND XIN1 > XIN2 + EPS THEN
    Q := TRUE;
  END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK INTEGRAL
  VAR_INPUT RUN, R1 : BOOL; XIN, X0 : REAL; CYCLE : TIME; END_VAR
  VAR_OUTPUT Q : BOOL; XOUT : REAL; END_VAR
  (* R1 resets to X0 and overrides RUN; RUN integrates XIN over CYCLE,
     otherwise XOUT holds. *)
  Q := NOT R1;
  IF R1 THEN
    XOUT := X0;
  ELSIF RUN THEN
    XOUT := XOUT + XIN * TIME_IN_S_TO_REAL(CYCLE);
  END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK DERIVATIVE
  VAR_INPUT RUN : BOOL; XIN : REAL; CYCLE : TIME; END_VAR
  VAR_OUTPUT XOUT : REAL; END_VAR
  VAR X1, X2, X3 : REAL; END_VAR
  (* A four-point difference over the last three samples; without RUN
     the output is 0 and the samples follow XIN. *)
  IF NOT RUN THEN
    XOUT := 0.0;
    X3 := XIN;
    X2 := XIN;
    X1 := XIN;
  ELSE
    XOUT := (3.0 * (XIN - X3) + X1 - X2) / (10.0 * TIME_IN_S_TO_REAL(CYCLE));
    X3 := X2;
    X2 := X1;
    X1 := XIN;
  END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK PID
  VAR_INPUT AUTO : BOOL; PV, SP, X0, KP, TR, TD : REAL; CYCLE : TIME; END_VAR
  VAR_OUTPUT XOUT : REAL; END_VAR
  VAR ERROR : REAL; ITERM : INTEGRAL; DTERM : DERIVATIVE; END_VAR
  (* Manual (AUTO false) holds the integral at the value that makes XOUT
     follow X0. *)
  ERROR := PV - SP;
  ITERM(RUN := AUTO, R1 := NOT AUTO, XIN := ERROR, X0 := TR * (X0 - ERROR),
        CYCLE := CYCLE);
  DTERM(RUN := AUTO, XIN := ERROR, CYCLE := CYCLE);
  XOUT := KP * (ERROR + ITERM.XOUT / TR + DTERM.XOUT * TD);
END_FUNCTION_BLOCK

FUNCTION_BLOCK RAMP
  VAR_INPUT RUN : BOOL; X0, X1 : REAL; TR, CYCLE : TIME; END_VAR
  VAR_OUTPUT BUSY : BOOL; XOUT : REAL := 0.0; END_VAR
  VAR XI : REAL; T : TIME := T#0s; END_VAR
  (* Without RUN: XOUT tracks X0. With RUN: a straight line from where
     it was to X1 over TR, in steps of CYCLE, then X1. *)
  BUSY := RUN;
  IF NOT RUN THEN
    XOUT := X0;
    XI := X0;
    T := T#0s;
  ELSIF T < TR THEN
    XOUT := XI + (X1 - XI) * TIME_IN_S_TO_REAL(T) / TIME_IN_S_TO_REAL(TR);
    T := T + CYCLE;
  ELSE
    BUSY := FALSE;
    XOUT := X1;
  END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK SEMA
  VAR_INPUT CLAIM, RELEASE : BOOL; END_VAR
  VAR_OUTPUT BUSY : BOOL; END_VAR
  VAR HELD : BOOL; END_VAR
  (* Taken by CLAIM (which wins over RELEASE), given back by RELEASE. *)
  HELD := CLAIM OR (HELD AND NOT RELEASE);
  BUSY := HELD;
END_FUNCTION_BLOCK

(* The steps of a Sequential Function Chart (frontends/plc/SfcExpansion.cpp
   calls them): X is the step flag. ACTIVATED_WHILE_ACTIVE is 1 when a
   transition activates the step while it is active and stays so (an
   unsafe chart) or two transitions activate it at once: the caller's
   write of 1 to this 0..0 input stops the scan with a runtime error at the
   step, naming it. *)
FUNCTION_BLOCK NETLIFT_SFC_STEP
  VAR_INPUT ACTIVE : BOOL; ACTIVATED_WHILE_ACTIVE : INT(0..0); END_VAR
  VAR_OUTPUT X : BOOL; END_VAR
  X := ACTIVE;
END_FUNCTION_BLOCK

(* A step whose elapsed time T is read. Its clock restarts when the step
   is activated (RESTART: deactivated and activated again in one scan),
   T keeps its last value while the step is inactive, and the clock parks
   at CAP meanwhile so that idle steps add no states. *)
FUNCTION_BLOCK NETLIFT_SFC_TIMED_STEP
  VAR_INPUT
    ACTIVE : BOOL; ACTIVATED_WHILE_ACTIVE : INT(0..0); RESTART : BOOL;
    CAP : TIME;
  END_VAR
  VAR_OUTPUT X : BOOL; T : TIME; END_VAR
  VAR
    TIMING : BOOL;
    {netlift clock CAP} CLOCK : TIME;
  END_VAR
  IF ACTIVE AND (RESTART OR NOT TIMING) THEN
    CLOCK := T#0s;
  ELSIF NOT ACTIVE AND TIMING THEN
    CLOCK := CAP;
  END_IF;
  IF ACTIVE THEN
    T := CLOCK;
  END_IF;
  TIMING := ACTIVE;
  X := ACTIVE;
END_FUNCTION_BLOCK

FUNCTION SUB_LTIME : LTIME
  VAR_INPUT IN1 : LTIME; IN2 : LTIME; END_VAR
  SUB_LTIME := IN1 - IN2;
END_FUNCTION

FUNCTION MUL_TIME : TIME
  VAR_INPUT IN1 : TIME; IN2 : LINT; END_VAR
  MUL_TIME := IN1 * IN2;
END_FUNCTION

FUNCTION DIV_TIME : TIME
  VAR_INPUT IN1 : TIME; IN2 : LINT; END_VAR
  DIV_TIME := IN1 / IN2;
END_FUNCTION

FUNCTION MUL_LTIME : LTIME
  VAR_INPUT IN1 : LTIME; IN2 : LINT; END_VAR
  MUL_LTIME := IN1 * IN2;
END_FUNCTION

FUNCTION DIV_LTIME : LTIME
  VAR_INPUT IN1 : LTIME; IN2 : LINT; END_VAR
  DIV_LTIME := IN1 / IN2;
END_FUNCTION

(* CODESYS's and TwinCAT's __SYSTEM types: what an ANY input of a function
   or method holds (the value's address, size in bytes and type class, with
   the class numbers CODESYS documents). *)
TYPE
  TYPE_CLASS : (TYPE_BOOL := 0, TYPE_BIT, TYPE_BYTE, TYPE_WORD, TYPE_DWORD,
    TYPE_LWORD, TYPE_SINT, TYPE_INT, TYPE_DINT, TYPE_LINT, TYPE_USINT,
    TYPE_UINT, TYPE_UDINT, TYPE_ULINT, TYPE_REAL, TYPE_LREAL, TYPE_STRING,
    TYPE_WSTRING, TYPE_TIME, TYPE_DATE, TYPE_DATEANDTIME, TYPE_TIMEOFDAY,
    TYPE_POINTER, TYPE_REFERENCE, TYPE_SUBRANGE, TYPE_ENUM, TYPE_ARRAY,
    TYPE_PARAMS, TYPE_USERDEF, TYPE_NONE, TYPE_ANY, TYPE_ANYBIT,
    TYPE_ANYDATE, TYPE_ANYINT, TYPE_ANYNUM, TYPE_ANYREAL, TYPE_LAZY,
    TYPE_LTIME, TYPE_BITCONST, TYPE_UXINT, TYPE_XWORD, TYPE_XINT,
    TYPE_XSTRING, TYPE_VARLENARRAY, TYPE_ANYSTRING, TYPE_VECTOR, TYPE_LDATE,
    TYPE_LDATEANDTIME, TYPE_LTIMEOFDAY) DINT;
  AnyType : STRUCT
    pValue : POINTER TO BYTE;
    diSize : DINT;
    TypeClass : TYPE_CLASS;
  END_STRUCT;
END_TYPE
)ST";

bool st::isStandardFunctionBlock(llvm::StringRef name) {
  for (const char *fb :
       {"R_TRIG", "F_TRIG", "SR", "RS", "CTU", "CTD", "CTUD", "TON", "TOF",
        "TP", "HYSTERESIS", "INTEGRAL", "DERIVATIVE", "PID", "RAMP", "SEMA",
        "NETLIFT_SFC_STEP", "NETLIFT_SFC_TIMED_STEP"})
    if (name.equals_insensitive(fb))
      return true;
  return false;
}

/// `{netlift runtime 'what it is' free 'A B' first 'C'}` on a library's
/// global: a record the runtime writes before every scan (PlcAst.h).
static void readRuntimeRecord(plc::VarDecl &g) {
  for (const plc::Attribute &a : g.attrs) {
    llvm::StringRef rest(a.text);
    if (!rest.consume_front("netlift runtime"))
      continue;
    // Quoted words after their keys: the description first.
    auto quoted = [&](llvm::StringRef &from) {
      from = from.ltrim();
      if (!from.consume_front("'"))
        return llvm::StringRef();
      auto [inside, after] = from.split('\'');
      from = after;
      return inside;
    };
    g.runtimeRecord = quoted(rest).str();
    while (!(rest = rest.ltrim()).empty()) {
      llvm::StringRef key = rest.take_while([](char c) { return c != ' '; });
      rest = rest.drop_front(key.size());
      llvm::StringRef value = quoted(rest);
      if (key == "first")
        g.runtimeFirst = value.str();
      llvm::SmallVector<llvm::StringRef, 16> fields;
      if (key == "free")
        value.split(fields, ' ', -1, false);
      for (llvm::StringRef f : fields)
        g.runtimeFree.push_back(f.str());
    }
  }
}

bool st::addLibraryText(DiagEngine &diag, plc::Unit &unit, llvm::StringRef text,
                        llvm::StringRef bufferName) {
  // Only the POUs and globals the user did not define are kept, so a
  // user's own TON replaces netlift's.
  llvm::SourceMgr &sm = diag.sourceMgr();
  unsigned id = sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, bufferName), llvm::SMLoc());
  std::vector<plc::Pou *> before = unit.pous;
  std::vector<plc::VarDecl *> globalsBefore = unit.globals;
  std::vector<plc::TypeDecl *> typesBefore = unit.types;
  if (!parseStructuredText(sm.getMemoryBuffer(id)->getBuffer(), diag, unit))
    return false;
  std::vector<plc::TypeDecl *> types = typesBefore;
  for (size_t i = typesBefore.size(); i < unit.types.size(); ++i) {
    bool shadowed = false;
    for (plc::TypeDecl *t : typesBefore)
      shadowed |= plc::sameName(t->name, unit.types[i]->name);
    unit.types[i]->isLibrary = true;
    if (!shadowed)
      types.push_back(unit.types[i]);
  }
  unit.types = std::move(types);
  std::vector<plc::Pou *> merged = before;
  for (size_t i = before.size(); i < unit.pous.size(); ++i) {
    plc::Pou *p = unit.pous[i];
    p->isLibrary = true;
    // `{netlift environment 'what it does'}`: a block with effects.
    for (const plc::Attribute &a : p->attrs) {
      llvm::StringRef text(a.text);
      if (text.consume_front("netlift environment"))
        p->environment = text.trim().trim('\'').str();
      // `{netlift writes 'DESTADDR'}`: an address input the runtime
      // writes through.
      if (text.consume_front("netlift writes"))
        p->writesThrough.push_back(text.trim().trim('\'').str());
    }
    bool shadowed = false;
    for (plc::Pou *u : before)
      shadowed |= !u->methodOf && plc::sameName(u->name, p->name);
    if (!shadowed)
      merged.push_back(p);
  }
  unit.pous = std::move(merged);
  std::vector<plc::VarDecl *> globals = globalsBefore;
  for (size_t i = globalsBefore.size(); i < unit.globals.size(); ++i) {
    unit.globals[i]->isLibrary = true;
    readRuntimeRecord(*unit.globals[i]);
    bool shadowed = false;
    for (plc::VarDecl *g : globalsBefore)
      shadowed |= plc::sameName(g->name, unit.globals[i]->name);
    for (plc::Configuration *c : unit.configs)
      for (plc::VarDecl *g : c->globals)
        shadowed |= plc::sameName(g->name, unit.globals[i]->name);
    if (!shadowed)
      globals.push_back(unit.globals[i]);
  }
  unit.globals = std::move(globals);
  return true;
}

bool st::addStandardLibrary(DiagEngine &diag, plc::Unit &unit) {
  return addLibraryText(diag, unit, kStandardLibrary,
                        "<netlift standard library>");
}
