//===- StringOps.cpp - what NetIR's string functions compute --------------===//
#include "ir/net/StringOps.h"

#include "ir/support/IecTime.h"

#include "llvm/ADT/StringExtras.h"

#include <cmath>
#include <cstdlib>

using namespace netlift;
using namespace netlift::net;
using llvm::StringRef;

namespace {

/// Checks a length operand (n >= 0) and a 1-based position operand
/// (1 <= p <= len + 1: one past the end designates the empty rest).
std::optional<std::string> checkSpan(StringRef fn, size_t len, int64_t n,
                                     int64_t p) {
  if (n < 0)
    return fn.str() + "(): length " + std::to_string(n) + " is negative";
  if (p < 1 || uint64_t(p) > len + 1)
    return fn.str() + "(): position " + std::to_string(p) + " is outside 1.." +
           std::to_string(len + 1) + " of a string of length " +
           std::to_string(len);
  return std::nullopt;
}

/// What a time-text built-in reads or writes.
IecTimeKind timeKindOf(Builtin fn) {
  switch (fn) {
  case Builtin::FormatDate:
  case Builtin::ParseDate:
    return IecTimeKind::Date;
  case Builtin::FormatTod:
  case Builtin::ParseTod:
    return IecTimeKind::TimeOfDay;
  case Builtin::FormatDt:
  case Builtin::ParseDt:
    return IecTimeKind::DateAndTime;
  default:
    return IecTimeKind::Duration;
  }
}

/// The characters from position p (1-based, checked) on, at most n.
size_t spanEnd(size_t len, int64_t n, int64_t p) {
  uint64_t end = uint64_t(p - 1) + uint64_t(n);
  return end > len ? len : size_t(end);
}

} // namespace

std::optional<std::string>
net::applyStringBuiltin(Builtin fn, llvm::ArrayRef<StringValue> strs,
                        llvm::ArrayRef<int64_t> ints, StringValue &out) {
  switch (fn) {
  case Builtin::FormatDuration: // the only ones without a string operand
  case Builtin::FormatDate:
  case Builtin::FormatTod:
  case Builtin::FormatDt: {
    std::string text = formatIecTimeValue(timeKindOf(fn), ints[0]);
    out.assign(text.begin(), text.end());
    return std::nullopt;
  }
  default:
    break;
  }
  const StringValue &a = strs[0];
  switch (fn) {
  case Builtin::Left:
  case Builtin::Right: {
    int64_t n = ints[0];
    if (n < 0)
      return spelling(fn).str() + "(): length " + std::to_string(n) +
             " is negative";
    size_t k = uint64_t(n) > a.size() ? a.size() : size_t(n);
    out = fn == Builtin::Left ? a.substr(0, k) : a.substr(a.size() - k);
    return std::nullopt;
  }
  case Builtin::Mid:
  case Builtin::Delete: {
    if (auto err = checkSpan(spelling(fn), a.size(), ints[0], ints[1]))
      return err;
    size_t from = size_t(ints[1] - 1), to = spanEnd(a.size(), ints[0], ints[1]);
    out = fn == Builtin::Mid ? a.substr(from, to - from)
                             : a.substr(0, from) + a.substr(to);
    return std::nullopt;
  }
  case Builtin::Concat:
    out = a + strs[1];
    return std::nullopt;
  case Builtin::Insert: {
    int64_t p = ints[0];
    if (p < 0 || uint64_t(p) > a.size())
      return "insert(): position " + std::to_string(p) + " is outside 0.." +
             std::to_string(a.size()) + " of a string of length " +
             std::to_string(a.size());
    out = a.substr(0, size_t(p)) + strs[1] + a.substr(size_t(p));
    return std::nullopt;
  }
  case Builtin::WithCode: {
    int64_t p = ints[0], c = ints[1];
    if (p < 1)
      return "with_code(): position " + std::to_string(p) + " is below 1";
    if (c < 0 || c > 0xffff)
      return "with_code(): code " + std::to_string(c) + " is outside 0..65535";
    if (c == 0) { // a terminator: the string ends before p
      out = uint64_t(p) <= a.size() ? a.substr(0, size_t(p - 1)) : a;
      return std::nullopt;
    }
    if (uint64_t(p) > a.size() + 1)
      return "with_code(): position " + std::to_string(p) +
             " is beyond the terminator (position " +
             std::to_string(a.size() + 1) + ") of a string of length " +
             std::to_string(a.size());
    out = a;
    if (uint64_t(p) == a.size() + 1)
      out.push_back(char16_t(c));
    else
      out[size_t(p - 1)] = char16_t(c);
    return std::nullopt;
  }
  case Builtin::Replace: {
    if (auto err = checkSpan("replace", a.size(), ints[0], ints[1]))
      return err;
    size_t from = size_t(ints[1] - 1), to = spanEnd(a.size(), ints[0], ints[1]);
    out = a.substr(0, from) + strs[1] + a.substr(to);
    return std::nullopt;
  }
  default:
    return "not a string function";
  }
}

std::optional<std::string> net::parseTimeText(Builtin fn, const StringValue &s,
                                              int64_t &ns) {
  std::string text;
  for (char16_t c : s)
    text += c > 0x7e ? '?' : char(c);
  IecTimeKind want = timeKindOf(fn), kind = want;
  std::string error;
  if (!parseIecTime(text, kind, ns, error, /*prefixOptional=*/true))
    return error;
  if (kind != want)
    return "'" + text + "' is not a " +
           (want == IecTimeKind::Duration    ? "duration"
            : want == IecTimeKind::Date      ? "date"
            : want == IecTimeKind::TimeOfDay ? "time of day"
                                             : "date and time");
  return std::nullopt;
}

std::optional<std::string> net::codeAt(const StringValue &s, int64_t p,
                                       int64_t &code) {
  if (p < 1)
    return "code(): position " + std::to_string(p) + " is below 1";
  code = uint64_t(p) <= s.size() ? int64_t(s[size_t(p - 1)]) : 0;
  return std::nullopt;
}

int64_t net::findString(const StringValue &a, const StringValue &b) {
  if (b.empty())
    return 0;
  size_t at = a.find(b);
  return at == StringValue::npos ? 0 : int64_t(at) + 1;
}

bool net::compareStrings(BinaryOp op, const StringValue &a,
                         const StringValue &b) {
  int c = a.compare(b);
  switch (op) {
  case BinaryOp::Eq:
    return c == 0;
  case BinaryOp::Ne:
    return c != 0;
  case BinaryOp::Lt:
    return c < 0;
  case BinaryOp::Le:
    return c <= 0;
  case BinaryOp::Gt:
    return c > 0;
  case BinaryOp::Ge:
    return c >= 0;
  default:
    return false;
  }
}

StringValue net::scalarToString(const Type *from, int64_t v) {
  std::string text = from->isBool() ? std::string(v ? "TRUE" : "FALSE")
                                    : formatScalar(from, v);
  return StringValue(text.begin(), text.end());
}

ConvertError net::stringToScalar(const StringValue &s, const Type *to,
                                 int64_t &out) {
  // Only ASCII can spell a number; anything else is not one.
  std::string text;
  for (char16_t c : s) {
    if (c > 0x7e)
      return ConvertError::NotANumber;
    text += char(c);
  }
  StringRef t = StringRef(text).trim(" \t");
  if (to->isBool()) {
    if (t.equals_insensitive("TRUE") || t == "1")
      out = 1;
    else if (t.equals_insensitive("FALSE") || t == "0")
      out = 0;
    else
      return ConvertError::NotANumber;
    return ConvertError::None;
  }
  bool neg = t.consume_front("-");
  if (!neg)
    t.consume_front("+");
  unsigned radix = 10;
  if (t.consume_front("2#"))
    radix = 2;
  else if (t.consume_front("8#"))
    radix = 8;
  else if (t.consume_front("16#"))
    radix = 16;
  std::string digits;
  for (size_t i = 0; i < t.size(); ++i) {
    // `_` only between digits, as in an IEC literal.
    if (t[i] == '_' && i > 0 && i + 1 < t.size() && t[i - 1] != '_')
      continue;
    digits += t[i];
  }
  if (digits.empty())
    return ConvertError::NotANumber;
  if (to->isFloat() && radix == 10) {
    for (char c : digits)
      if (!llvm::isDigit(c) && c != '.' && c != 'e' && c != 'E' && c != '+' &&
          c != '-')
        return ConvertError::NotANumber;
    char *end = nullptr;
    double d = std::strtod(digits.c_str(), &end);
    if (*end != '\0' || !llvm::isDigit(digits[0]))
      return ConvertError::NotANumber;
    out = floatBits(to->width, neg ? -d : d);
    return ConvertError::None;
  }
  uint64_t mag = 0;
  if (StringRef(digits).getAsInteger(radix, mag))
    return llvm::all_of(digits,
                        [&](char c) {
                          return llvm::isHexDigit(c) &&
                                 llvm::hexDigitValue(c) < radix;
                        })
               ? ConvertError::OutOfRange
               : ConvertError::NotANumber;
  if (to->isFloat()) {
    double d = double(mag);
    out = floatBits(to->width, neg ? -d : d);
    return ConvertError::None;
  }
  if (to->isUnsigned64()) {
    if (neg && mag != 0)
      return ConvertError::OutOfRange;
    out = int64_t(mag);
    return ConvertError::None;
  }
  if (mag > uint64_t(INT64_MAX) + (neg ? 1 : 0))
    return ConvertError::OutOfRange;
  int64_t v = neg ? int64_t(0 - mag) : int64_t(mag);
  if (v < to->lo || v > to->hi)
    return ConvertError::OutOfRange;
  out = v;
  return ConvertError::None;
}

void net::appendUtf8(std::string &out, uint32_t u) {
  if (u < 0x80) {
    out += char(u);
  } else if (u < 0x800) {
    out += char(0xc0 | (u >> 6));
    out += char(0x80 | (u & 0x3f));
  } else {
    out += char(0xe0 | (u >> 12));
    out += char(0x80 | ((u >> 6) & 0x3f));
    out += char(0x80 | (u & 0x3f));
  }
}

std::string net::toUtf8(const StringValue &s) {
  std::string out;
  for (char16_t c : s)
    appendUtf8(out, c >= 0xd800 && c < 0xe000 ? 0xfffd : c);
  return out;
}

std::string net::formatStringLiteral(llvm::ArrayRef<char16_t> chars) {
  std::string out = "\"";
  for (char16_t c : chars) {
    if (c == '"' || c == '\\')
      out += '\\', out += char(c);
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c >= 0x20 && c < 0x7f)
      out += char(c);
    else if (c < 0x100)
      out += "\\x" + llvm::utohexstr(c, false, 2);
    else
      out += "\\u" + llvm::utohexstr(c, false, 4);
  }
  return out + "\"";
}

std::optional<std::string>
net::parseStringLiteral(StringRef body, StringValue &out, size_t &errorAt) {
  out.clear();
  for (size_t i = 0; i < body.size(); ++i) {
    unsigned char c = body[i];
    if (c != '\\') {
      if (c >= 0x80) {
        errorAt = i;
        return std::string("write a character outside ASCII as \\xHH or "
                           "\\uHHHH");
      }
      out += char16_t(c);
      continue;
    }
    errorAt = i;
    char n = i + 1 < body.size() ? body[i + 1] : '\0';
    if (n == '"' || n == '\\' || n == 'n' || n == 't') {
      out += char16_t(n == 'n' ? '\n' : n == 't' ? '\t' : n);
      ++i;
      continue;
    }
    size_t digits = n == 'x' ? 2 : n == 'u' ? 4 : 0;
    uint64_t code = 0;
    if (!digits || i + 2 + digits > body.size() ||
        body.substr(i + 2, digits).getAsInteger(16, code))
      return std::string("unknown escape; write \\\", \\\\, \\n, \\t, "
                         "\\xHH or \\uHHHH");
    out += char16_t(code);
    i += 1 + digits;
  }
  return std::nullopt;
}
