//===- XmlSupport.h - XML inputs read with pugixml --------------*- C++ -*-===//
//
// What every XML frontend (PNML, SpaceEx, later PLCopen and IEC 61499)
// needs from its buffer: parsing it with pugixml, malformed XML reported at
// its offset, and an element's position as an SMLoc so that diagnostics
// read `file:line:col: error:` pointing at the element's '<'.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_XMLSUPPORT_H
#define NETLIFT_FRONTENDS_XMLSUPPORT_H

#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"

#include <algorithm>
#include <pugixml.hpp>

namespace netlift {

class XmlBuffer {
public:
  explicit XmlBuffer(llvm::StringRef buffer) : buffer(buffer) {}

  /// Parses the whole buffer; reports malformed XML and returns false.
  bool parse(pugi::xml_document &doc, DiagEngine &diag) const {
    pugi::xml_parse_result r =
        doc.load_buffer(buffer.data(), buffer.size(), pugi::parse_default);
    if (r)
      return true;
    size_t off = std::min<size_t>(r.offset, buffer.size());
    diag.error(llvm::SMLoc::getFromPointer(buffer.data() + off),
               llvm::Twine("malformed XML: ") + r.description());
    return false;
  }

  /// The position of an element (its '<'), or the buffer's start.
  llvm::SMLoc locOf(const pugi::xml_node &n) const {
    ptrdiff_t off = n.offset_debug();
    if (off < 0 || size_t(off) > buffer.size())
      return llvm::SMLoc::getFromPointer(buffer.data());
    if (off > 0 && buffer[off - 1] == '<')
      --off;
    return llvm::SMLoc::getFromPointer(buffer.data() + off);
  }

  llvm::StringRef text() const { return buffer; }

private:
  llvm::StringRef buffer;
};

} // namespace netlift

#endif
