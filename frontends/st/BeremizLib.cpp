//===- BeremizLib.cpp - blocks Beremiz's and OpenPLC's runtimes implement -===//
//
// Beremiz (and OpenPLC, built on it) ships blocks whose bodies are C code
// run by its runtime: LOGGER, which writes the runtime's log
// (NativeLib.xml), RTC, the real-time clock, and the Python extension's
// python_eval, python_poll and python_gear, which run Python code
// (py_ext/pous.xml) and its CSV readers; and OpenPLC's extension blocks, which drive its boards'
// hardware and talk over CAN, TCP and MQTT (its editor's plcopen/*.xml).
// Projects call them without declaring them; SVGHMI's HMI_* types too. netlift declares their interfaces,
// as Beremiz defines them, marked `{netlift environment '...'}`: a call changes
// nothing the program sees but their outputs, which are free inputs of the
// model, said in a note (--opaque=refuse refuses them). LOGGER has no
// outputs: the log is seen outside the program only. A project's own
// definition of a name replaces netlift's (OpenPLC's plc.st writes LOGGER
// with its C body, which is refused where it is called).
//
//===----------------------------------------------------------------------===//
#include "frontends/st/StdLib.h"

using namespace netlift;

static const char kBeremizLibrary[] = R"ST(
TYPE
  LOGLEVEL : (CRITICAL, WARNING, INFO, DEBUG) := INFO;
END_TYPE

(* SVGHMI's types (svghmi/svghmi.py): a variable of HMI_<T> is a <T> the
   web HMI shows and may write between scans (Sema: shared outside); an
   HMI_NODE (older: HMI_CLASS, HMI_LABEL) only names a node of the HMI
   tree. *)
TYPE
  HMI_BOOL : BOOL; HMI_SINT : SINT; HMI_INT : INT; HMI_DINT : DINT;
  HMI_LINT : LINT; HMI_USINT : USINT; HMI_UINT : UINT; HMI_UDINT : UDINT;
  HMI_ULINT : ULINT; HMI_BYTE : BYTE; HMI_WORD : WORD; HMI_DWORD : DWORD;
  HMI_LWORD : LWORD; HMI_REAL : REAL; HMI_LREAL : LREAL;
  HMI_STRING : STRING; HMI_TIME : TIME;
  HMI_NODE : BOOL; HMI_CLASS : BOOL; HMI_LABEL : BOOL;
END_TYPE

{netlift environment 'writes the runtime log'}
FUNCTION_BLOCK LOGGER
  VAR_INPUT TRIG : BOOL; MSG : STRING; LEVEL : LOGLEVEL := INFO; END_VAR
END_FUNCTION_BLOCK

(* matiec's real-time clock (Beremiz's Additional_Function_Blocks): Q
   follows IN, CDT is the clock, set to PDT on IN's rising edge. *)
{netlift environment 'reads and sets the real-time clock'}
FUNCTION_BLOCK RTC
  VAR_INPUT IN : BOOL; PDT : DT; END_VAR
  VAR_OUTPUT Q : BOOL; CDT : DT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'runs Python code in the runtime'}
FUNCTION_BLOCK python_eval
  VAR_INPUT TRIG : BOOL; CODE : STRING; END_VAR
  VAR_OUTPUT ACK : BOOL; RESULT : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'runs Python code in the runtime'}
FUNCTION_BLOCK python_poll
  VAR_INPUT TRIG : BOOL; CODE : STRING; END_VAR
  VAR_OUTPUT ACK : BOOL; RESULT : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'runs Python code in the runtime'}
FUNCTION_BLOCK python_gear
  VAR_INPUT N : UINT; TRIG : BOOL; CODE : STRING; END_VAR
  VAR_OUTPUT ACK : BOOL; RESULT : STRING; END_VAR
END_FUNCTION_BLOCK

(* Beremiz's CSV blocks (py_ext): they read a cell through the Python
   extension, which the runtime runs. *)
{netlift environment 'reads CSV files through the Python extension'}
FUNCTION_BLOCK csv_read_by_string
  VAR_INPUT FILE_NAME : STRING; ROW : STRING; COLUMN : STRING; END_VAR
  VAR_OUTPUT ACK : BOOL; RESULT : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads CSV files through the Python extension'}
FUNCTION_BLOCK csv_read_by_int
  VAR_INPUT FILE_NAME : STRING; ROW : INT; COLUMN : INT; END_VAR
  VAR_OUTPUT ACK : BOOL; RESULT : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reloads CSV files through the Python extension'}
FUNCTION_BLOCK csv_reload
  VAR_INPUT TRIG : BOOL; END_VAR
  VAR_OUTPUT ACK : BOOL; RESULT : STRING; END_VAR
END_FUNCTION_BLOCK

(* OpenPLC's extension blocks (its editor's plcopen/*.xml): I/O boards,
   sensors, CAN, TCP, MQTT. *)
{netlift environment 'reads DS18B20 temperature sensors'}
FUNCTION_BLOCK DS18B20
  VAR_INPUT PIN : SINT; END_VAR
  VAR_OUTPUT OUT : REAL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads DS18B20 temperature sensors'}
FUNCTION_BLOCK DS18B20_2_OUT
  VAR_INPUT PIN : SINT; END_VAR
  VAR_OUTPUT OUT_0, OUT_1 : REAL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads DS18B20 temperature sensors'}
FUNCTION_BLOCK DS18B20_3_OUT
  VAR_INPUT PIN : SINT; END_VAR
  VAR_OUTPUT OUT_0, OUT_1, OUT_2 : REAL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads DS18B20 temperature sensors'}
FUNCTION_BLOCK DS18B20_4_OUT
  VAR_INPUT PIN : SINT; END_VAR
  VAR_OUTPUT OUT_0, OUT_1, OUT_2, OUT_3 : REAL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads DS18B20 temperature sensors'}
FUNCTION_BLOCK DS18B20_5_OUT
  VAR_INPUT PIN : SINT; END_VAR
  VAR_OUTPUT OUT_0, OUT_1, OUT_2, OUT_3, OUT_4 : REAL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks to the Arduino IoT Cloud'}
FUNCTION_BLOCK CLOUD_ADD_BOOL
  VAR_INPUT VAR_NAME : STRING; BOOL_VAR : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks to the Arduino IoT Cloud'}
FUNCTION_BLOCK CLOUD_ADD_DINT
  VAR_INPUT VAR_NAME : STRING; DINT_VAR : DINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks to the Arduino IoT Cloud'}
FUNCTION_BLOCK CLOUD_ADD_REAL
  VAR_INPUT VAR_NAME : STRING; REAL_VAR : REAL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks to the Arduino IoT Cloud'}
FUNCTION_BLOCK CLOUD_BEGIN
  VAR_INPUT THING_ID, SSID, PASS : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives a PWM output of the board'}
FUNCTION_BLOCK PWM_CONTROLLER
  VAR_INPUT CHANNEL : SINT; FREQ, DUTY : REAL; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK ARDUINOCAN_CONF
  VAR_INPUT EN_PIN : WORD; BR : LINT; END_VAR
  VAR_OUTPUT DONE : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK ARDUINOCAN_WRITE
  VAR_INPUT ID : DWORD; D0, D1, D2, D3, D4, D5, D6, D7 : USINT; END_VAR
  VAR_OUTPUT DONE : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK ARDUINOCAN_WRITE_WORD
  VAR_INPUT ID : DWORD; DATA : LWORD; END_VAR
  VAR_OUTPUT DONE : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK ARDUINOCAN_READ
  VAR_OUTPUT DATA : LWORD; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK STM32CAN_CONF
  VAR_INPUT CONF : BOOL; BR : LINT; END_VAR
  VAR_OUTPUT DONE : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK STM32CAN_WRITE
  VAR_INPUT
    EN_PIN : BOOL; CH : USINT; ID : DWORD;
    D0, D1, D2, D3, D4, D5, D6, D7 : BYTE;
  END_VAR
  VAR_OUTPUT DONE : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over CAN'}
FUNCTION_BLOCK STM32CAN_READ
  VAR_INPUT EN_PIN : BOOL; END_VAR
  VAR_OUTPUT
    DONE : BOOL; ID : DWORD; D0, D1, D2, D3, D4, D5, D6, D7 : BYTE;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over TCP'}
FUNCTION_BLOCK TCP_CONNECT
  VAR_INPUT CONNECT : BOOL; IP_ADDRESS : STRING; PORT : INT; END_VAR
  VAR_OUTPUT SOCKET_ID : INT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over TCP'}
FUNCTION_BLOCK TCP_SEND
  VAR_INPUT SEND : BOOL; SOCKET_ID : INT; MSG : STRING; END_VAR
  VAR_OUTPUT BYTES_SENT : INT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over TCP'}
FUNCTION_BLOCK TCP_RECEIVE
  VAR_INPUT RECEIVE : BOOL; SOCKET_ID : INT; END_VAR
  VAR_OUTPUT BYTES_RECEIVED : INT; MSG : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over TCP'}
FUNCTION_BLOCK TCP_CLOSE
  VAR_INPUT CLOSE : BOOL; SOCKET_ID : INT; END_VAR
  VAR_OUTPUT SUCCESS : INT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'configures an ADC of the board'}
FUNCTION_BLOCK ADC_CONFIG
  VAR_INPUT ADC_CH, ADC_TYPE : SINT; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_RECEIVE
  VAR_INPUT RECEIVE : BOOL; TOPIC : STRING; END_VAR
  VAR_OUTPUT RECEIVED : BOOL; MESSAGE : STRING; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_SEND
  VAR_INPUT SEND : BOOL; TOPIC, MESSAGE : STRING; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_CONNECT
  VAR_INPUT CONNECT : BOOL; BROKER : STRING; PORT : UINT; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_CONNECT_AUTH
  VAR_INPUT
    CONNECT : BOOL; BROKER : STRING; PORT : UINT; USER, PASSWORD : STRING;
  END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_SUBSCRIBE
  VAR_INPUT SUBSCRIBE : BOOL; TOPIC : STRING; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_UNSUBSCRIBE
  VAR_INPUT UNSUBSCRIBE : BOOL; TOPIC : STRING; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'talks over MQTT'}
FUNCTION_BLOCK MQTT_DISCONNECT
  VAR_INPUT DISCONNECT : BOOL; END_VAR
  VAR_OUTPUT SUCCESS : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1AM_INIT
  VAR_INPUT INIT : BOOL; END_VAR
  VAR_OUTPUT SUCCESS : SINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1_16CDR
  VAR_INPUT SLOT : SINT; O1, O2, O3, O4, O5, O6, O7, O8 : BOOL; END_VAR
  VAR_OUTPUT I1, I2, I3, I4, I5, I6, I7, I8 : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1_08N
  VAR_INPUT SLOT : SINT; END_VAR
  VAR_OUTPUT I1, I2, I3, I4, I5, I6, I7, I8 : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1_16N
  VAR_INPUT SLOT : SINT; END_VAR
  VAR_OUTPUT
   
    I1, I2, I3, I4, I5, I6, I7, I8, I9, I10, I11, I12, I13, I14, I15, I16 : BOOL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1_08T
  VAR_INPUT SLOT : SINT; O1, O2, O3, O4, O5, O6, O7, O8 : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1_16TR
  VAR_INPUT
    SLOT : SINT;
    O1, O2, O3, O4, O5, O6, O7, O8, O9, O10, O11, O12, O13, O14, O15, O16 : BOOL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives P1AM I/O modules'}
FUNCTION_BLOCK P1_04AD
  VAR_INPUT SLOT : SINT; END_VAR
  VAR_OUTPUT I1, I2, I3, I4 : UINT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'reads a rotary switch of the board'}
FUNCTION_BLOCK ROTARY_SWITCH
  VAR_INPUT READ : BOOL; END_VAR
  VAR_OUTPUT ERROR : BOOL; OUT : INT; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_8RELAY
  VAR_INPUT STACK : SINT; O1, O2, O3, O4, O5, O6, O7, O8 : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_16RELAY
  VAR_INPUT
    STACK : SINT;
    O1, O2, O3, O4, O5, O6, O7, O8, O9, O10, O11, O12, O13, O14, O15, O16 : BOOL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_8DIN
  VAR_INPUT STACK : SINT; END_VAR
  VAR_OUTPUT I1, I2, I3, I4, I5, I6, I7, I8 : BOOL; END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_16DIN
  VAR_INPUT STACK : SINT; END_VAR
  VAR_OUTPUT
   
    I1, I2, I3, I4, I5, I6, I7, I8, I9, I10, I11, I12, I13, I14, I15, I16 : BOOL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_4REL4IN
  VAR_INPUT STACK : SINT; RELAY1, RELAY2, RELAY3, RELAY4 : BOOL; END_VAR
  VAR_OUTPUT
    OPTO1, OPTO2, OPTO3, OPTO4, AC_OPTO1, AC_OPTO2, AC_OPTO3, AC_OPTO4 : BOOL;
    PWM1, PWM2, PWM3, PWM4 : REAL; FREQ1, FREQ2, FREQ3, FREQ4 : UINT;
    BUTTON : BOOL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_INDUSTRIAL
  VAR_INPUT
    STACK : SINT; LED1, LED2, LED3, LED4 : BOOL;
    Q0_10V1, Q0_10V2, Q0_10V3, Q0_10V4, Q4_20MA1, Q4_20MA2, Q4_20MA3, Q4_20MA4, QOD1, QOD2, QOD3, QOD4 : REAL;
  END_VAR
  VAR_OUTPUT
    OPTO1, OPTO2, OPTO3, OPTO4 : BOOL;
    I0_10V1, I0_10V2, I0_10V3, I0_10V4, I4_20MA1, I4_20MA2, I4_20MA3, I4_20MA4, OWB_T1, OWB_T2, OWB_T3, OWB_T4 : REAL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_RTD
  VAR_INPUT STACK : SINT; END_VAR
  VAR_OUTPUT
    TEMP1, TEMP2, TEMP3, TEMP4, TEMP5, TEMP6, TEMP7, TEMP8 : REAL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_BAS
  VAR_INPUT
    STACK : SINT;
    TRIAC1, TRIAC2, TRIAC3, TRIAC4, LED1, LED2, LED3, LED4 : BOOL;
    IN1_T, IN2_T, IN3_T, IN4_T, IN5_T, IN6_T, IN7_T, IN8_T : UINT;
    Q0_10V1, Q0_10V2, Q0_10V3, Q0_10V4 : REAL;
  END_VAR
  VAR_OUTPUT
    UNIV1, UNIV2, UNIV3, UNIV4, UNIV5, UNIV6, UNIV7, UNIV8 : REAL;
    DRY_C1, DRY_C2, DRY_C3, DRY_C4, DRY_C5, DRY_C6, DRY_C7, DRY_C8 : BOOL;
    OWB_T1, OWB_T2, OWB_T3, OWB_T4 : REAL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_HOME
  VAR_INPUT
    STACK : SINT;
    RELAY1, RELAY2, RELAY3, RELAY4, RELAY5, RELAY6, RELAY7, RELAY8 : BOOL;
    Q0_10V1, Q0_10V2, Q0_10V3, Q0_10V4, QOD1, QOD2, QOD3, QOD4 : REAL;
  END_VAR
  VAR_OUTPUT
    OPTO1, OPTO2, OPTO3, OPTO4, OPTO5, OPTO6, OPTO7, OPTO8 : BOOL;
    ADC1, ADC2, ADC3, ADC4, ADC5, ADC6, ADC7, ADC8, OWB_T1, OWB_T2, OWB_T3, OWB_T4 : REAL;
  END_VAR
END_FUNCTION_BLOCK

{netlift environment 'drives Sequent Microsystems I/O cards'}
FUNCTION_BLOCK SM_8MOSFET
  VAR_INPUT
    STACK : SINT; MOS1, MOS2, MOS3, MOS4, MOS5, MOS6, MOS7, MOS8 : BOOL;
  END_VAR
END_FUNCTION_BLOCK
)ST";

bool st::addBeremizLibrary(DiagEngine &diag, plc::Unit &unit) {
  return addLibraryText(diag, unit, kBeremizLibrary,
                        "<netlift Beremiz library>");
}
