//===- TwinCatLib.cpp - models of TwinCAT's libraries
//----------------------===//
//
// What TwinCAT projects call from Beckhoff's libraries and netlift can model
// exactly, written in Structured Text like the standard library (StdLib.cpp)
// and added when a TwinCAT input is read: Tc2_Math's rounding and modulo
// functions on LREAL and Tc2_System's PI. Tc2_System's and Tc2_Utilities'
// blocks and functions with effects outside the program (ADS, files, the
// runtime, the clock) or results netlift does not reproduce exactly (text
// formatting) are declared with their interface only and marked
// `{netlift environment '...'}`: an instance's outputs, a call's result,
// are free inputs of the model, said in a note (--opaque=refuse refuses
// them; LowerDecls.cpp, declareEnvironment; LowerEnvironment.cpp). Their
// behaviour is what Beckhoff documents (MODABS(-400.56, 360) = 319.44,
// LTRUNC(-2.8) = -2, FLOOR and CEIL of negative values); twincat-lib.test
// checks those values. Tc2_Standard's timers, triggers and counters are the
// standard ones. Tc2_MC2's axis (AXIS_REF) and motion blocks are
// environment too: the NC task, not the program, moves the axis.
// Tc2_Utilities' FB_FormatString is environment; its T_Arg arguments (F_INT,
// F_STRING, ...) carry their type and size, their address 0 in the model.
// PVOID, XWORD, UXINT and XINT are the 64-bit integers of an x64 target.
//
//===----------------------------------------------------------------------===//
#include "frontends/st/StdLib.h"

using namespace netlift;

static const char kTwinCatLibrary[] = R"ST(
VAR_GLOBAL CONSTANT
  PI : LREAL := 3.14159265358979323846;
  MAX_STRING_LENGTH : UDINT := 255;
END_VAR

TYPE
  (* Every TwinCAT library holds a global of this type (its Global_Version
     list, stLibVersion_<library>); Tc2_System declares it. *)
  ST_LibVersion : STRUCT
    iMajor : UINT;
    iMinor : UINT;
    iBuild : UINT;
    iRevision : UINT;
    nFlags : DWORD;
    sVersion : STRING(23);
  END_STRUCT;
  T_AmsNetId : STRING(23);
  T_AmsPort : UINT;
  T_MaxString : STRING(255);
  E_OpenPath : (PATH_GENERIC := 1, PATH_BOOTPRJ, PATH_BOOTDATA, PATH_BOOTPATH,
                PATH_USERPATH1 := 11, PATH_USERPATH2, PATH_USERPATH3,
                PATH_USERPATH4, PATH_USERPATH5, PATH_USERPATH6,
                PATH_USERPATH7, PATH_USERPATH8, PATH_USERPATH9);
END_TYPE

VAR_GLOBAL CONSTANT
  DEFAULT_ADS_TIMEOUT : TIME := T#5S;
END_VAR

(* Blocks with effects outside the PLC program (Tc2_System): environment.
   Their inputs are the runtime's (an address input is declared DWORD: it
   is never read); their outputs are free. *)
{netlift environment 'communicates over ADS'}
FUNCTION_BLOCK ADSWRITE
  VAR_INPUT
    NETID : T_AmsNetId; PORT : T_AmsPort; IDXGRP, IDXOFFS, LEN : UDINT;
    SRCADDR : DWORD; WRITE : BOOL; TMOUT : TIME;
  END_VAR
  VAR_OUTPUT BUSY, ERR : BOOL; ERRID : UDINT; END_VAR
END_FUNCTION_BLOCK

(* Reads write the program's memory: what ADR(x) given as the destination
   designates takes any value at every call. *)
{netlift environment 'communicates over ADS'}
{netlift writes 'DESTADDR'}
FUNCTION_BLOCK ADSREAD
  VAR_INPUT
    NETID : T_AmsNetId; PORT : T_AmsPort; IDXGRP, IDXOFFS, LEN : UDINT;
    DESTADDR : DWORD; READ : BOOL; TMOUT : TIME;
  END_VAR
  VAR_OUTPUT BUSY, ERR : BOOL; ERRID : UDINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'communicates over ADS'}
{netlift writes 'DESTADDR'}
FUNCTION_BLOCK ADSRDWRT
  VAR_INPUT
    NETID : T_AmsNetId; PORT : T_AmsPort; IDXGRP, IDXOFFS, WRITELEN,
    READLEN : UDINT; SRCADDR, DESTADDR : DWORD; WRTRD : BOOL; TMOUT : TIME;
  END_VAR
  VAR_OUTPUT BUSY, ERR : BOOL; ERRID : UDINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'communicates over ADS'}
FUNCTION_BLOCK ADSRDSTATE
  VAR_INPUT NETID : T_AmsNetId; PORT : T_AmsPort; RDSTATE : BOOL; TMOUT : TIME; END_VAR
  VAR_OUTPUT BUSY, ERR : BOOL; ERRID : UDINT; ADSSTATE, DEVSTATE : UINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'communicates over ADS'}
FUNCTION_BLOCK ADSWRTCTL
  VAR_INPUT
    NETID : T_AmsNetId; PORT : T_AmsPort; ADSSTATE, DEVSTATE : UINT;
    LEN : UDINT; SRCADDR : DWORD; WRITE : BOOL; TMOUT : TIME;
  END_VAR
  VAR_OUTPUT BUSY, ERR : BOOL; ERRID : UDINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
FUNCTION_BLOCK FB_FileOpen
  VAR_INPUT
    sNetId : T_AmsNetId; sPathName : T_MaxString; nMode : DWORD;
    ePath : E_OpenPath; bExecute : BOOL; tTimeout : TIME;
  END_VAR
  VAR_OUTPUT bBusy, bError : BOOL; nErrId : UDINT; hFile : UINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
FUNCTION_BLOCK FB_FileClose
  VAR_INPUT sNetId : T_AmsNetId; hFile : UINT; bExecute : BOOL; tTimeout : TIME; END_VAR
  VAR_OUTPUT bBusy, bError : BOOL; nErrId : UDINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
FUNCTION_BLOCK FB_FileWrite
  VAR_INPUT
    sNetId : T_AmsNetId; hFile : UINT; pWriteBuff : DWORD; cbWriteLen : UDINT;
    bExecute : BOOL; tTimeout : TIME;
  END_VAR
  VAR_OUTPUT bBusy, bError : BOOL; nErrId, cbWrite : UDINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
{netlift writes 'pReadBuff'}
FUNCTION_BLOCK FB_FileRead
  VAR_INPUT
    sNetId : T_AmsNetId; hFile : UINT; pReadBuff : DWORD; cbReadLen : UDINT;
    bExecute : BOOL; tTimeout : TIME;
  END_VAR
  VAR_OUTPUT bBusy, bError : BOOL; nErrId, cbRead : UDINT; bEOF : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
FUNCTION_BLOCK FB_FilePuts
  VAR_INPUT
    sNetId : T_AmsNetId; hFile : UINT; sLine : T_MaxString;
    bExecute : BOOL; tTimeout : TIME;
  END_VAR
  VAR_OUTPUT bBusy, bError : BOOL; nErrId : UDINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
FUNCTION_BLOCK FB_FileGets
  VAR_INPUT
    sNetId : T_AmsNetId; hFile : UINT; bExecute : BOOL; tTimeout : TIME;
  END_VAR
  VAR_OUTPUT
    bBusy, bError : BOOL; nErrId : UDINT; sLine : T_MaxString; bEOF : BOOL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'accesses the file system'}
FUNCTION_BLOCK FB_FileDelete
  VAR_INPUT
    sNetId : T_AmsNetId; sPathName : T_MaxString; ePath : E_OpenPath;
    bExecute : BOOL; tTimeout : TIME;
  END_VAR
  VAR_OUTPUT bBusy, bError : BOOL; nErrId : UDINT; END_VAR
END_FUNCTION_BLOCK

(* The index of the task that runs the caller (1..n in a cyclic task, 0
   in FB_init); lowered as the project's tasks give it
   (LowerEnvironment.cpp, taskIndex). *)
{netlift environment 'asks the runtime which task runs'}
FUNCTION GETCURTASKINDEXEX : DINT
END_FUNCTION

FUNCTION_BLOCK GETCURTASKINDEX
  VAR_OUTPUT index : BYTE; END_VAR
  index := DINT_TO_BYTE(GETCURTASKINDEXEX());
END_FUNCTION_BLOCK

(* Tc2_System: messages to the event log (and a message box); the result
   is the call's error code, 0 on success. *)
VAR_GLOBAL CONSTANT
  ADSLOG_MSGTYPE_HINT : DWORD := 16#01;
  ADSLOG_MSGTYPE_WARN : DWORD := 16#02;
  ADSLOG_MSGTYPE_ERROR : DWORD := 16#04;
  ADSLOG_MSGTYPE_LOG : DWORD := 16#10;
  ADSLOG_MSGTYPE_MSGBOX : DWORD := 16#20;
  ADSLOG_MSGTYPE_RESOURCE : DWORD := 16#40;
  ADSLOG_MSGTYPE_STRING : DWORD := 16#80;
END_VAR

{netlift environment 'writes the TwinCAT event log'}
FUNCTION ADSLOGSTR : DINT
  VAR_INPUT msgCtrlMask : DWORD; msgFmtStr, strArg : T_MaxString; END_VAR
END_FUNCTION

{netlift environment 'writes the TwinCAT event log'}
FUNCTION ADSLOGDINT : DINT
  VAR_INPUT msgCtrlMask : DWORD; msgFmtStr : T_MaxString; dintArg : DINT; END_VAR
END_FUNCTION

{netlift environment 'writes the TwinCAT event log'}
FUNCTION ADSLOGLREAL : DINT
  VAR_INPUT msgCtrlMask : DWORD; msgFmtStr : T_MaxString; lrealArg : LREAL; END_VAR
END_FUNCTION

(* TwinCAT 3's names of the address-sized integers (64 bits on x64); a
   PVOID holds an address, which netlift does not model as a number: an
   ADR assigned to one is refused by name where it happens. *)
TYPE
  XWORD : __XWORD;
  UXINT : __UXINT;
  XINT : __XINT;
  PVOID : __UXINT;
END_TYPE

(* Tc2_System: the system time, in 100 ns since 1601-01-01. *)
{netlift environment 'reads the system clock'}
FUNCTION F_GetSystemTime : ULINT
END_FUNCTION

(* Tc2_Utilities: Windows' local time, and text formatting netlift does not
   reproduce digit for digit. *)
TYPE TIMESTRUCT : STRUCT
  wYear, wMonth, wDayOfWeek, wDay, wHour, wMinute, wSecond,
  wMilliseconds : WORD;
END_STRUCT END_TYPE

{netlift environment 'reads the system clock over ADS'}
FUNCTION_BLOCK NT_GetTime
  VAR_INPUT NETID : T_AmsNetId; START : BOOL; TMOUT : TIME := DEFAULT_ADS_TIMEOUT; END_VAR
  VAR_OUTPUT BUSY, ERR : BOOL; ERRID : UDINT; TIMESTR : TIMESTRUCT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'formats a number as text'}
FUNCTION LREAL_TO_FMTSTR : STRING(510)
  VAR_INPUT in : LREAL; iPrecision : INT; bRound : BOOL; END_VAR
END_FUNCTION

(* FB_FormatString's arguments: each names its type and size; pData, the
   argument's address, is 0 in the model (only the formatting, which is
   environment, would read it). *)
TYPE
  E_ArgType : (ARGTYPE_UNKNOWN := 0, ARGTYPE_BYTE, ARGTYPE_WORD, ARGTYPE_DWORD,
               ARGTYPE_REAL, ARGTYPE_LREAL, ARGTYPE_SINT, ARGTYPE_INT,
               ARGTYPE_DINT, ARGTYPE_USINT, ARGTYPE_UINT, ARGTYPE_UDINT,
               ARGTYPE_STRING, ARGTYPE_BOOL, ARGTYPE_BIGTYPE, ARGTYPE_ULARGE,
               ARGTYPE_UHUGE, ARGTYPE_LARGE, ARGTYPE_HUGE, ARGTYPE_LWORD);
  T_Arg : STRUCT
    eType : E_ArgType := ARGTYPE_UNKNOWN;
    cbLen : UDINT := 0;
    pData : PVOID := 0;
  END_STRUCT;
END_TYPE

FUNCTION F_BYTE : T_Arg
  VAR_INPUT in : BYTE; END_VAR
  F_BYTE.eType := ARGTYPE_BYTE; F_BYTE.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_WORD : T_Arg
  VAR_INPUT in : WORD; END_VAR
  F_WORD.eType := ARGTYPE_WORD; F_WORD.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_DWORD : T_Arg
  VAR_INPUT in : DWORD; END_VAR
  F_DWORD.eType := ARGTYPE_DWORD; F_DWORD.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_LWORD : T_Arg
  VAR_INPUT in : LWORD; END_VAR
  F_LWORD.eType := ARGTYPE_LWORD; F_LWORD.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_REAL : T_Arg
  VAR_INPUT in : REAL; END_VAR
  F_REAL.eType := ARGTYPE_REAL; F_REAL.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_LREAL : T_Arg
  VAR_INPUT in : LREAL; END_VAR
  F_LREAL.eType := ARGTYPE_LREAL; F_LREAL.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_SINT : T_Arg
  VAR_INPUT in : SINT; END_VAR
  F_SINT.eType := ARGTYPE_SINT; F_SINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_INT : T_Arg
  VAR_INPUT in : INT; END_VAR
  F_INT.eType := ARGTYPE_INT; F_INT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_DINT : T_Arg
  VAR_INPUT in : DINT; END_VAR
  F_DINT.eType := ARGTYPE_DINT; F_DINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_USINT : T_Arg
  VAR_INPUT in : USINT; END_VAR
  F_USINT.eType := ARGTYPE_USINT; F_USINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_UINT : T_Arg
  VAR_INPUT in : UINT; END_VAR
  F_UINT.eType := ARGTYPE_UINT; F_UINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_UDINT : T_Arg
  VAR_INPUT in : UDINT; END_VAR
  F_UDINT.eType := ARGTYPE_UDINT; F_UDINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_BOOL : T_Arg
  VAR_INPUT in : BOOL; END_VAR
  F_BOOL.eType := ARGTYPE_BOOL; F_BOOL.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_LINT : T_Arg
  VAR_INPUT in : LINT; END_VAR
  F_LINT.eType := ARGTYPE_LARGE; F_LINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_ULINT : T_Arg
  VAR_INPUT in : ULINT; END_VAR
  F_ULINT.eType := ARGTYPE_ULARGE; F_ULINT.cbLen := SIZEOF(in);
END_FUNCTION
FUNCTION F_STRING : T_Arg
  VAR_INPUT in : T_MaxString; END_VAR
  F_STRING.eType := ARGTYPE_STRING; F_STRING.cbLen := INT_TO_UDINT(LEN(in)) + 1;
END_FUNCTION

{netlift environment 'formats text'}
FUNCTION_BLOCK FB_FormatString
  VAR_INPUT
    sFormat : T_MaxString;
    arg1, arg2, arg3, arg4, arg5, arg6, arg7, arg8, arg9, arg10 : T_Arg;
  END_VAR
  VAR_OUTPUT bError : BOOL; nErrId : UDINT; sOut : T_MaxString; END_VAR
END_FUNCTION_BLOCK

(* A string's first character code, and the string of one code. *)
FUNCTION F_ToASC : BYTE
  VAR_INPUT str : T_MaxString; END_VAR
  IF LEN(str) > 0 THEN F_ToASC := str[0]; END_IF
END_FUNCTION

FUNCTION F_ToCHR : T_MaxString
  VAR_INPUT c : BYTE; END_VAR
  IF c <> 0 THEN F_ToCHR := ' '; F_ToCHR[0] := c; END_IF
END_FUNCTION

{netlift environment 'reads the system clock'}
FUNCTION_BLOCK GETSYSTEMTIME
  VAR_OUTPUT timeLoDW, timeHiDW : UDINT; END_VAR
END_FUNCTION_BLOCK

TYPE E_TimeZoneID : (eTimeZoneID_Invalid := -1, eTimeZoneID_Unknown := 0,
                     eTimeZoneID_Standard := 1, eTimeZoneID_Daylight := 2) DINT;
END_TYPE

{netlift environment 'reads the local time of the system'}
FUNCTION_BLOCK FB_LocalSystemTime
  VAR_INPUT
    sNetID : T_AmsNetId; bEnable : BOOL; dwCycle : DWORD := 5;
    dwOpt : DWORD := 1; tTimeout : TIME := DEFAULT_ADS_TIMEOUT;
  END_VAR
  VAR_OUTPUT bValid : BOOL; systemTime : TIMESTRUCT; tzID : E_TimeZoneID; END_VAR
END_FUNCTION_BLOCK

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

(* Tc2_MC2, PLCopen motion control on the NC: an axis (AXIS_REF) and the
   blocks that command it. The NC task moves the axis; netlift has no model
   of it, so an AXIS_REF's cyclic data (NcToPlc) and status are the
   environment's, chosen at every scan, and an MC block's outputs are free
   inputs: every answer the interface allows, in any order (a Done without
   a Busy before it included). Interfaces as Beckhoff documents them; the
   members a program may read are those listed here. *)
TYPE
  MC_AxisStates : (MC_AXISSTATE_UNDEFINED, MC_AXISSTATE_DISABLED,
    MC_AXISSTATE_STANDSTILL, MC_AXISSTATE_ERRORSTOP, MC_AXISSTATE_STOPPING,
    MC_AXISSTATE_HOMING, MC_AXISSTATE_DISCRETEMOTION,
    MC_AXISSTATE_CONTINOUSMOTION, MC_AXISSTATE_SYNCHRONIZEDMOTION);
  MC_BufferMode : (MC_Aborting, MC_Buffered, MC_BlendingLow,
    MC_BlendingPrevious, MC_BlendingNext, MC_BlendingHigh);
  MC_Direction : (MC_Positive_Direction := 1, MC_Shortest_Way,
    MC_Negative_Direction, MC_Current_Direction);
  MC_HomingMode : (MC_DefaultHoming, MC_ForceCalibration,
    MC_ResetCalibration);
  E_JogMode : (MC_JOGMODE_STANDARD_SLOW, MC_JOGMODE_STANDARD_FAST,
    MC_JOGMODE_CONTINOUS, MC_JOGMODE_INCHING, MC_JOGMODE_INCHING_MODULO);
  NCTOPLC_AXIS_REF : STRUCT
    StateDWord : DWORD; ErrorCode : UDINT; AxisState : UDINT;
    AxisModeConfirmation : UDINT; HomingState : UDINT; CoupleState : UDINT;
    SvbEntries : UDINT; SafEntries : UDINT; AxisId : UDINT;
    OpModeDWord : DWORD; ActPos : LREAL; ModuloActPos : LREAL;
    ModuloActTurns : DINT; ActVelo : LREAL; PosDiff : LREAL; SetPos : LREAL;
    SetVelo : LREAL; SetAcc : LREAL; TargetPos : LREAL;
    ModuloSetPos : LREAL; ModuloSetTurns : DINT; CmdNo : UINT;
    CmdState : UINT; SetJerk : LREAL; SetTorque : LREAL; ActTorque : LREAL;
  END_STRUCT;
  PLCTONC_AXIS_REF : STRUCT
    ControlDWord : DWORD; Override : UDINT; AxisModeRequest : UDINT;
    AxisModeDWord : UDINT; AxisModeLReal : LREAL; PositionCorrection : LREAL;
    ExtSetPos : LREAL; ExtSetVelo : LREAL; ExtSetAcc : LREAL;
    ExtSetDirection : DINT; ExtControllerOutput : LREAL;
    GearRatio1 : LREAL; GearRatio2 : LREAL; GearRatio3 : LREAL;
    GearRatio4 : LREAL;
  END_STRUCT;
  ST_AxisStatus : STRUCT
    UpdateTaskIndex : BYTE; UpdateCycleTime : LREAL; CycleCounter : UDINT;
    NcCycleCounter : UDINT; MotionState : MC_AxisStates; Error : BOOL;
    ErrorId : UDINT; ErrorStop : BOOL; Disabled : BOOL; Stopping : BOOL;
    StandStill : BOOL; DiscreteMotion : BOOL; ContinuousMotion : BOOL;
    SynchronizedMotion : BOOL; Homing : BOOL; ConstantVelocity : BOOL;
    Accelerating : BOOL; Decelerating : BOOL; Operational : BOOL;
    ControlLoopClosed : BOOL; HasJob : BOOL; HasBeenStopped : BOOL;
    NewTargetPosition : BOOL; InPositionArea : BOOL;
    InTargetPosition : BOOL; ProtectedMode : BOOL; Homed : BOOL;
    HomingBusy : BOOL; MotionCommandsLocked : BOOL;
    SoftLimitMinExceeded : BOOL; SoftLimitMaxExceeded : BOOL; Moving : BOOL;
    PositiveDirection : BOOL; NegativeDirection : BOOL; NotMoving : BOOL;
    Compensating : BOOL; ExtSetPointGenEnabled : BOOL; PhasingActive : BOOL;
    ExternalLatchValid : BOOL; CamDataQueued : BOOL; CamTableQueued : BOOL;
    CamScalingPending : BOOL; CmdBuffered : BOOL; PTPmode : BOOL;
    DriveDeviceError : BOOL; IoDataInvalid : BOOL;
    ErrorPropagationDelayed : BOOL;
  END_STRUCT;
END_TYPE

{netlift environment 'is an axis the NC task moves'}
FUNCTION_BLOCK AXIS_REF
  VAR_INPUT PlcToNc : PLCTONC_AXIS_REF; END_VAR
  VAR_OUTPUT NcToPlc : NCTOPLC_AXIS_REF; Status : ST_AxisStatus; END_VAR
ACTION ReadStatus:
END_ACTION
END_FUNCTION_BLOCK

{netlift environment 'enables an axis on the NC'}
FUNCTION_BLOCK MC_Power
  VAR_INPUT
    Enable, Enable_Positive, Enable_Negative : BOOL; Override : LREAL := 100.0;
    BufferMode : MC_BufferMode;
  END_VAR
  VAR_OUTPUT Status, Busy, Active, Error : BOOL; ErrorID : UDINT; END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'resets an axis on the NC'}
FUNCTION_BLOCK MC_Reset
  VAR_INPUT Execute : BOOL; END_VAR
  VAR_OUTPUT Done, Busy, Error : BOOL; ErrorID : UDINT; END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'stops an axis on the NC'}
FUNCTION_BLOCK MC_Stop
  VAR_INPUT Execute : BOOL; Deceleration, Jerk : LREAL; END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'halts an axis on the NC'}
FUNCTION_BLOCK MC_Halt
  VAR_INPUT
    Execute : BOOL; Deceleration, Jerk : LREAL; BufferMode : MC_BufferMode;
  END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'homes an axis on the NC'}
FUNCTION_BLOCK MC_Home
  VAR_INPUT
    Execute : BOOL; Position : LREAL := 1E308; HomingMode : MC_HomingMode;
    BufferMode : MC_BufferMode; bCalibrationCam : BOOL;
  END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'moves an axis on the NC'}
FUNCTION_BLOCK MC_MoveAbsolute
  VAR_INPUT
    Execute : BOOL; Position, Velocity, Acceleration, Deceleration,
    Jerk : LREAL; BufferMode : MC_BufferMode;
  END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'moves an axis on the NC'}
FUNCTION_BLOCK MC_MoveRelative
  VAR_INPUT
    Execute : BOOL; Distance, Velocity, Acceleration, Deceleration,
    Jerk : LREAL; BufferMode : MC_BufferMode;
  END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'moves an axis on the NC'}
FUNCTION_BLOCK MC_MoveModulo
  VAR_INPUT
    Execute : BOOL; Position, Velocity, Acceleration, Deceleration,
    Jerk : LREAL; Direction : MC_Direction; BufferMode : MC_BufferMode;
  END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'moves an axis on the NC'}
FUNCTION_BLOCK MC_MoveVelocity
  VAR_INPUT
    Execute : BOOL; Velocity, Acceleration, Deceleration, Jerk : LREAL;
    Direction : MC_Direction := MC_Positive_Direction;
    BufferMode : MC_BufferMode;
  END_VAR
  VAR_OUTPUT
    InVelocity, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'jogs an axis on the NC'}
FUNCTION_BLOCK MC_Jog
  VAR_INPUT
    JogForward, JogBackwards : BOOL; Mode : E_JogMode; Position, Velocity,
    Acceleration, Deceleration, Jerk : LREAL;
  END_VAR
  VAR_OUTPUT
    Done, Busy, Active, CommandAborted, Error : BOOL; ErrorID : UDINT;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'sets the position of an axis on the NC'}
FUNCTION_BLOCK MC_SetPosition
  VAR_INPUT Execute : BOOL; Position : LREAL; Mode : BOOL; END_VAR
  VAR_OUTPUT Done, Busy, Error : BOOL; ErrorID : UDINT; END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads an axis on the NC'}
FUNCTION_BLOCK MC_ReadActualPosition
  VAR_INPUT Enable : BOOL; END_VAR
  VAR_OUTPUT Valid, Busy, Error : BOOL; ErrorID : UDINT; Position : LREAL; END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads an axis on the NC'}
FUNCTION_BLOCK MC_ReadActualVelocity
  VAR_INPUT Enable : BOOL; END_VAR
  VAR_OUTPUT
    Valid, Busy, Error : BOOL; ErrorID : UDINT; ActualVelocity : LREAL;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads an axis on the NC'}
FUNCTION_BLOCK MC_ReadAxisError
  VAR_INPUT Enable : BOOL; END_VAR
  VAR_OUTPUT Valid, Busy, Error : BOOL; ErrorID, AxisErrorID : UDINT; END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads an axis on the NC'}
FUNCTION_BLOCK MC_ReadStatus
  VAR_INPUT Enable : BOOL; END_VAR
  VAR_OUTPUT
    Valid, Busy, Error : BOOL; ErrorID : UDINT;
    ErrorStop, Disabled, Stopping, StandStill, DiscreteMotion,
    ContinuousMotion, SynchronizedMotion, Homing, ConstantVelocity,
    Accelerating, Decelerating : BOOL; Status : ST_AxisStatus;
  END_VAR
  VAR_IN_OUT Axis : AXIS_REF; END_VAR
END_FUNCTION_BLOCK
)ST";

/// A string literal of Structured Text.
static std::string stLiteral(llvm::StringRef text) {
  std::string out = "'";
  for (char c : text)
    out += c == '\''  ? std::string("$'")
           : c == '$' ? std::string("$$")
                      : std::string(1, c);
  return out + "'";
}

/// TwinCAT_SystemInfoVarList, the records the runtime writes before every
/// scan: `_TaskInfo`, one PlcTaskSystemInfo per task of the project, and
/// `_AppInfo`. What the project states is known: with one task, its name,
/// cycle time (in 100 ns) and priority from its .TcTTO, and FirstCycle,
/// TRUE in the first scan only; the project's name; the number of tasks.
/// The rest (object ids, ports, counters, the runtime's timings and flags)
/// is free: the `{netlift runtime}` pragma lists it. With several tasks
/// the model does not know which index the runtime gives the task that
/// runs the program, so each is free whole.
static std::string systemInfoText(const plc::Unit &unit) {
  std::vector<const plc::Task *> tasks = plc::twinCatTasks(unit);
  size_t n = std::max<size_t>(tasks.size(), 1);
  std::string out = R"ST(
TYPE
  OTCID : UDINT;
  PlcTaskSystemInfo : STRUCT
    ObjId : OTCID;
    CycleTime : UDINT;
    Priority : UINT;
    AdsPort : UINT;
    CycleCount : UDINT;
    DcTaskTime : LINT;
    LastExecTime : UDINT;
    FirstCycle : BOOL;
    CycleTimeExceeded : BOOL;
    InCallAfterOutputUpdate : BOOL;
    RTViolation : BOOL;
    TaskName : STRING(63);
  END_STRUCT;
  PlcAppSystemInfo : STRUCT
    ObjId : OTCID;
    TaskCnt : UDINT;
    OnlineChangeCnt : UDINT;
    Flags : DWORD;
    AdsPort : UINT;
    BootDataLoaded : BOOL;
    OldBootData : BOOL;
    AppTimestamp : DT;
    KeepOutputsOnBP : BOOL;
    ShutdownInProgress : BOOL;
    LicensesPending : BOOL;
    BSODOccured : BOOL;
    TComSrvPtr : PVOID;
    AppName : STRING(63);
    ProjectName : STRING(63);
  END_STRUCT;
END_TYPE
)ST";
  std::string taskFree = "ObjId AdsPort CycleCount DcTaskTime LastExecTime "
                         "CycleTimeExceeded InCallAfterOutputUpdate "
                         "RTViolation";
  std::string taskInit, first;
  const plc::Task *task = tasks.size() == 1 ? tasks.front() : nullptr;
  if (tasks.size() > 1) {
    taskFree += " CycleTime Priority TaskName FirstCycle";
  } else {
    first = " first 'FirstCycle'";
    std::vector<std::string> known;
    if (task && task->interval)
      known.push_back("CycleTime := " +
                      std::to_string(task->interval->intValue / 100));
    else
      taskFree += " CycleTime";
    if (task && task->priority)
      known.push_back("Priority := " +
                      std::to_string(task->priority->intValue));
    else
      taskFree += " Priority";
    if (task)
      known.push_back("TaskName := " + stLiteral(task->name));
    else
      taskFree += " TaskName";
    for (size_t i = 0; i < known.size(); ++i)
      taskInit += (i ? ", " : " := [(") + known[i];
    if (!known.empty())
      taskInit += ")]";
  }
  std::string appFree = "ObjId OnlineChangeCnt Flags AdsPort BootDataLoaded "
                        "OldBootData AppTimestamp KeepOutputsOnBP "
                        "ShutdownInProgress LicensesPending BSODOccured "
                        "TComSrvPtr AppName";
  std::vector<std::string> appKnown;
  if (tasks.empty())
    appFree += " TaskCnt";
  else
    appKnown.push_back("TaskCnt := " + std::to_string(n));
  if (unit.projectName.empty())
    appFree += " ProjectName";
  else
    appKnown.push_back("ProjectName := " + stLiteral(unit.projectName));
  std::string appInit;
  for (size_t i = 0; i < appKnown.size(); ++i)
    appInit += (i ? ", " : " := (") + appKnown[i];
  if (!appKnown.empty())
    appInit += ")";
  out += "VAR_GLOBAL\n"
         "  {netlift runtime 'is the record TwinCAT keeps of its tasks' "
         "free '" +
         taskFree + "'" + first + "}\n  _TaskInfo : ARRAY[1.." +
         std::to_string(n) + "] OF PlcTaskSystemInfo" + taskInit +
         ";\n"
         "  {netlift runtime 'is the record TwinCAT keeps of the "
         "application' free '" +
         appFree + "'}\n  _AppInfo : PlcAppSystemInfo" + appInit +
         ";\nEND_VAR\n"
         "FUNCTION F_GetTaskInfo : PlcTaskSystemInfo\n"
         "  F_GetTaskInfo := _TaskInfo[GETCURTASKINDEXEX()];\n"
         "END_FUNCTION\n";
  return out;
}

bool st::addTwinCatLibrary(DiagEngine &diag, plc::Unit &unit) {
  size_t globalsBefore = unit.globals.size();
  if (!addLibraryText(diag, unit, kTwinCatLibrary + systemInfoText(unit),
                      "<netlift TwinCAT library>"))
    return false;
  for (size_t i = globalsBefore; i < unit.globals.size(); ++i)
    if (!unit.globals[i]->runtimeRecord.empty())
      unit.globals[i]->globalList = "TwinCAT_SystemInfoVarList";
  return true;
}
