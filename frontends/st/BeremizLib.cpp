//===- BeremizLib.cpp - the blocks Beremiz's runtime implements -----------===//
//
// Beremiz (and OpenPLC, built on it) ships blocks whose bodies are C code
// run by its runtime: LOGGER, which writes the runtime's log
// (NativeLib.xml), and the Python extension's python_eval, python_poll and
// python_gear, which run Python code (py_ext/pous.xml). Projects call them
// without declaring them. netlift declares their interfaces, as Beremiz
// defines them, marked `{netlift environment '...'}`: a call changes
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

{netlift environment 'writes the runtime log'}
FUNCTION_BLOCK LOGGER
  VAR_INPUT TRIG : BOOL; MSG : STRING; LEVEL : LOGLEVEL := INFO; END_VAR
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
)ST";

bool st::addBeremizLibrary(DiagEngine &diag, plc::Unit &unit) {
  return addLibraryText(diag, unit, kBeremizLibrary,
                        "<netlift Beremiz library>");
}
