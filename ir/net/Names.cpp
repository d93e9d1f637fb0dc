//===- Names.cpp - NetIR identifiers --------------------------------------===//
#include "ir/net/Names.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSwitch.h"

using namespace netlift;
using llvm::StringRef;

bool netlift::net::isReservedWord(StringRef n) {
  return llvm::StringSwitch<bool>(n)
      .Cases("and", "or", "xor", "not", "true", "false", "inf", true)
      .Cases("if", "elif", "else", "case", "for", "in", true)
      .Cases("while", "repeat", "until", "string", "wstring", true)
      .Default(false);
}

bool netlift::net::isIdentifier(StringRef n) { return toIdentifier(n) == n; }

std::string netlift::net::toIdentifier(StringRef name, bool keepDots) {
  std::string out;
  for (char c : name)
    out += (isalnum((unsigned char)c) || c == '_' || (keepDots && c == '.'))
               ? c
               : '_';
  if (out.empty() || isdigit((unsigned char)out[0]))
    out = "_" + out;
  if (isReservedWord(out))
    out += "_";
  return out;
}

bool netlift::net::hasGeneratedComponent(StringRef name) {
  return name.startswith("_") || name.contains("._");
}

std::vector<std::string> net::qualifiedNamesIn(llvm::StringRef text) {
  std::vector<std::string> words;
  std::string word;
  auto flush = [&] {
    while (!word.empty() && word.back() == '.')
      word.pop_back();
    if (!word.empty())
      words.push_back(word);
    word.clear();
  };
  for (char c : text) {
    if (llvm::isAlnum(c) || c == '_' || c == '.')
      word += c;
    else
      flush();
  }
  flush();
  return words;
}
