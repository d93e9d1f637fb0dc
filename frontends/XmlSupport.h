//===- XmlSupport.h - XML inputs read with pugixml --------------*- C++ -*-===//
//
// What every XML frontend (PNML, SpaceEx, PLCopen, IEC 61499) needs from
// its buffer: parsing it with pugixml, malformed XML reported at its
// offset, and an element's position as an SMLoc so that diagnostics read
// `file:line:col: error:` pointing at the element's '<'. Frontends that
// hand text inside the XML (ST bodies, expressions) to another parser use
// XmlSource, which places that text, decoded, at its own offset in a copy
// of the file, so the other parser's errors point into the XML too.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_XMLSUPPORT_H
#define NETLIFT_FRONTENDS_XMLSUPPORT_H

#include "ir/support/Diagnostics.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/STLFunctionalExtras.h"
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

/// The XML file of a SourceMgr buffer and its copy into which text is
/// placed, decoded, for parsing.
class XmlSource : public XmlBuffer {
public:
  XmlSource(unsigned bufferID, DiagEngine &diag);

  llvm::StringRef raw() const { return rawText; }
  /// The text content of `element` (CDATA or character data, directly or in
  /// an xhtml <p>), placed at its offset in the copy; empty if none.
  llvm::StringRef placeText(pugi::xml_node element);
  /// The value of attribute `name` of `element`, placed likewise (for an
  /// element netlift added, in a buffer of its own named
  /// `<netlift generated>/ELEMENT.NAME`, so that a diagnostic in it still
  /// prints); `found` says whether the attribute exists.
  llvm::StringRef placeAttribute(pugi::xml_node element, const char *name,
                                 bool *found = nullptr);
  /// Lets `edit` change text placed in the copy where it stands, keeping
  /// its length (so that positions stay); false for text placed elsewhere.
  bool editPlaced(llvm::StringRef placed,
                  llvm::function_ref<void(llvm::MutableArrayRef<char>)> edit);

private:
  llvm::StringRef place(size_t offset, size_t rawLength,
                        llvm::StringRef decoded);

  llvm::StringRef rawText;
  char *copy = nullptr; // owned by the SourceMgr
  llvm::SourceMgr &sourceMgr;
};

/// An element's name without its namespace prefix.
llvm::StringRef localName(pugi::xml_node n);

/// The first child element called `name` (prefix ignored).
pugi::xml_node child(pugi::xml_node n, llvm::StringRef name);

/// An XML Boolean attribute: "true" or "1".
bool isTrue(pugi::xml_attribute a);

} // namespace netlift

#endif
