//===- XmlEscape.h - text inside XML, SVG and HTML --------------*- C++ -*-===//
//
// Escapes the five characters XML gives meaning to, for text and attribute
// values written into SVG and HTML.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_XMLESCAPE_H
#define NETLIFT_IR_SUPPORT_XMLESCAPE_H

#include "llvm/ADT/StringRef.h"

#include <string>

namespace netlift {

inline std::string xmlEscape(llvm::StringRef s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s)
    switch (c) {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    case '\'':
      out += "&#39;";
      break;
    default:
      out += c;
    }
  return out;
}

} // namespace netlift

#endif
