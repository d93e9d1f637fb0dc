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

#include "frontends/plc/PlcAst.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"

#include <pugixml.hpp>

namespace netlift::plcopen {

/// The XML file and its copy into which text is placed, decoded, for
/// parsing.
class XmlSource {
public:
  XmlSource(unsigned bufferID, DiagEngine &diag);

  llvm::StringRef raw() const { return rawText; }
  /// Where an element starts (its '<').
  llvm::SMLoc locOf(pugi::xml_node n) const;
  /// The text content of `element` (CDATA or character data, directly or in
  /// an xhtml <p>), placed at its offset in the copy; empty if none.
  llvm::StringRef placeText(pugi::xml_node element);
  /// The value of attribute `name` of `element`, placed likewise; `found`
  /// says whether the attribute exists.
  llvm::StringRef placeAttribute(pugi::xml_node element, const char *name,
                                 bool *found = nullptr);

private:
  llvm::StringRef place(size_t offset, size_t rawLength,
                        llvm::StringRef decoded);

  llvm::StringRef rawText;
  char *copy = nullptr; // owned by the SourceMgr
};

/// An element's name without its namespace prefix.
llvm::StringRef localName(pugi::xml_node n);

/// The first child element called `name` (prefix ignored).
pugi::xml_node child(pugi::xml_node n, llvm::StringRef name);

/// Turns an LD or FBD body element into statements appended to pou->body,
/// declaring the instances and temporaries it needs in `pou`. Returns false
/// after reporting an error.
bool readGraphicalBody(pugi::xml_node body, XmlSource &src, DiagEngine &diag,
                       plc::Unit &unit, plc::Pou *pou);

/// Reads a PLCopen XML file into `unit`.
bool readPlcOpen(unsigned bufferID, DiagEngine &diag, plc::Unit &unit);

} // namespace netlift::plcopen

#endif
