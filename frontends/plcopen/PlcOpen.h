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

#include <functional>
#include <map>
#include <pugixml.hpp>

namespace netlift::plcopen {

/// Turns an LD or FBD body element into statements appended to pou->body,
/// declaring the instances and temporaries it needs in `pou`. Returns false
/// after reporting an error.
/// An LD or FBD body into `pou->body`. In an SFC body (`sfcConditions`
/// set), the networks drawn beside the chart: the SFC elements are left to
/// SfcBody.cpp, and each wired transition condition (transition localId ->
/// BOOL variable) is assigned like an output.
bool readGraphicalBody(
    pugi::xml_node body, XmlSource &src, DiagEngine &diag, plc::Unit &unit,
    plc::Pou *pou, const std::map<int, std::string> *sfcConditions = nullptr);

/// Reads a PLCopen XML file into `unit`.
/// Reads a POU's <body> (any language) into a statement list.
using SfcBodyReader =
    std::function<bool(pugi::xml_node body, plc::StmtList &out)>;

/// An <SFC> body: the chart (SfcBody.cpp), expanded into scan code. The
/// POU's <actions> and <transitions> are read with `readBody`.
bool readSfcBody(pugi::xml_node sfc, pugi::xml_node pouNode, XmlSource &src,
                 DiagEngine &diag, plc::Unit &unit, plc::Pou *pou,
                 const SfcBodyReader &readBody);

bool readPlcOpen(unsigned bufferID, DiagEngine &diag, plc::Unit &unit);

} // namespace netlift::plcopen

#endif
