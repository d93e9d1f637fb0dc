//===- PlcOpen.h - PLCopen TC6 XML into the PLC model -----------*- C++ -*-===//
//
// PLCopen TC6 XML (tc6_0201, and Beremiz/OpenPLC's tc6_0200) read into the
// same PLC model as Structured Text: data types, POUs with their
// interfaces, configurations with tasks and program instances, and bodies.
// ST and IL bodies go through their own frontends; LD and FBD networks are
// turned into statements by GraphicalBody.cpp following the evaluation
// rules of docs/plcopen.md. Every location is the XML file's own line and
// column: text the frontends parse (bodies, expressions, initial values) is
// placed, decoded, at its own offset in a copy of the file.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_PLCOPEN_PLCOPEN_H
#define NETLIFT_FRONTENDS_PLCOPEN_PLCOPEN_H

#include "frontends/XmlSupport.h"
#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"

#include <pugixml.hpp>

namespace netlift::plcopen {

/// Turns an LD or FBD body element into statements appended to pou->body,
/// declaring the instances and temporaries it needs in `pou`. Returns false
/// after reporting an error.
bool readGraphicalBody(pugi::xml_node body, XmlSource &src, DiagEngine &diag,
                       plc::Unit &unit, plc::Pou *pou);

/// Reads a PLCopen XML file into `unit`.
bool readPlcOpen(unsigned bufferID, DiagEngine &diag, plc::Unit &unit);

} // namespace netlift::plcopen

#endif
