//===- XmlSupport.cpp - placing XML text for the frontends' parsers ------===//
//
// See XmlSupport.h.
//
//===----------------------------------------------------------------------===//
#include "frontends/XmlSupport.h"

#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"

#include <cstring>

using namespace netlift;
using llvm::SMLoc;
using llvm::StringRef;

bool netlift::isTrue(pugi::xml_attribute a) {
  StringRef v = a.value();
  return v == "true" || v == "1";
}

XmlSource::XmlSource(unsigned bufferID, DiagEngine &diag)
    : XmlBuffer(diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer()),
      rawText(text()), sourceMgr(diag.sourceMgr()) {
  llvm::SourceMgr &sm = diag.sourceMgr();
  const llvm::MemoryBuffer *buf = sm.getMemoryBuffer(bufferID);
  auto buffer = llvm::WritableMemoryBuffer::getNewUninitMemBuffer(
      rawText.size(), buf->getBufferIdentifier());
  // A copy of the file (so that a diagnostic shows the XML line) in which
  // each piece of text handed to a parser is replaced by its decoded form.
  copy = buffer->getBufferStart();
  std::memcpy(copy, rawText.data(), rawText.size());
  sm.AddNewSourceBuffer(std::move(buffer), SMLoc());
}

/// Decoding entities only shortens text, so the decoded text fits where the
/// raw text stood; each line is put at its raw line's start so that line
/// numbers stay exact (columns after an entity shift by what it saved).
StringRef XmlSource::place(size_t offset, size_t rawLength, StringRef decoded) {
  rawLength = std::min(rawLength, rawText.size() - offset);
  StringRef rawSpan = rawText.substr(offset, rawLength);
  if (decoded.size() > rawLength)
    decoded = decoded.take_front(rawLength);
  for (size_t i = offset; i < offset + rawLength; ++i)
    if (copy[i] != '\n')
      copy[i] = ' ';
  llvm::SmallVector<StringRef, 16> rawLines, lines;
  rawSpan.split(rawLines, '\n');
  decoded.split(lines, '\n');
  if (rawLines.size() == lines.size()) {
    for (size_t i = 0; i < lines.size(); ++i) {
      size_t at = rawLines[i].data() - rawText.data();
      std::memcpy(copy + at, lines[i].data(), lines[i].size());
    }
  } else {
    std::memcpy(copy + offset, decoded.data(), decoded.size());
  }
  return StringRef(copy + offset, rawLength);
}

bool XmlSource::editPlaced(
    StringRef placed,
    llvm::function_ref<void(llvm::MutableArrayRef<char>)> edit) {
  if (!copy || placed.data() < copy ||
      placed.data() + placed.size() > copy + rawText.size())
    return false;
  edit(llvm::MutableArrayRef<char>(copy + (placed.data() - copy),
                                   placed.size()));
  return true;
}

StringRef netlift::localName(pugi::xml_node n) {
  StringRef name = n.name();
  size_t colon = name.find(':');
  return colon == StringRef::npos ? name : name.drop_front(colon + 1);
}

pugi::xml_node netlift::child(pugi::xml_node n, StringRef name) {
  for (pugi::xml_node c : n.children())
    if (c.type() == pugi::node_element && localName(c) == name)
      return c;
  return {};
}

StringRef XmlSource::placeText(pugi::xml_node element) {
  for (pugi::xml_node c : element.children()) {
    if (c.type() == pugi::node_cdata) {
      // Verbatim but for line ends (pugixml turns CR LF into LF).
      size_t off = c.offset_debug();
      size_t end = rawText.find("]]>", off);
      if (end == StringRef::npos)
        end = rawText.size();
      return place(off, end - off, c.value());
    }
    if (c.type() == pugi::node_pcdata) {
      size_t off = c.offset_debug();
      size_t end = rawText.find('<', off);
      if (end == StringRef::npos)
        end = rawText.size();
      return place(off, end - off, c.value());
    }
    if (c.type() == pugi::node_element && localName(c) == "p")
      return placeText(c);
  }
  return {};
}

StringRef XmlSource::placeAttribute(pugi::xml_node element, const char *name,
                                    bool *found) {
  pugi::xml_attribute a = element.attribute(name);
  if (found)
    *found = bool(a);
  if (!a)
    return {};
  // An element netlift added itself (a simple FB's ECC, a model of a
  // function FB) has no place in the text.
  if (element.offset_debug() < 0) {
    unsigned id = sourceMgr.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(
            a.value(),
            "<netlift generated>/" + std::string(element.name()) + "." + name),
        llvm::SMLoc());
    return sourceMgr.getMemoryBuffer(id)->getBuffer();
  }
  // pugixml keeps no offsets of attributes: find it in the start tag.
  size_t from = locOf(element).getPointer() - rawText.data();
  size_t tagEnd = rawText.find('>', from);
  StringRef tag = rawText.substr(from, tagEnd - from);
  size_t pos = 0;
  while ((pos = tag.find(name, pos)) != StringRef::npos) {
    bool wordStart = pos > 0 && isspace((unsigned char)tag[pos - 1]);
    size_t p = pos + strlen(name);
    while (p < tag.size() && isspace((unsigned char)tag[p]))
      ++p;
    if (wordStart && p < tag.size() && tag[p] == '=') {
      ++p;
      while (p < tag.size() && isspace((unsigned char)tag[p]))
        ++p;
      if (p < tag.size() && (tag[p] == '"' || tag[p] == '\'')) {
        size_t close = tag.find(tag[p], p + 1);
        size_t off = from + p + 1;
        return place(off, close - p - 1, a.value());
      }
    }
    pos = p;
  }
  return {};
}
