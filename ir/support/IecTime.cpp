//===- IecTime.cpp - IEC 61131-3 durations, dates and times of day --------===//
#include "ir/support/IecTime.h"

#include "llvm/ADT/StringExtras.h"

#include <algorithm>
#include <cmath>

using namespace netlift;
using llvm::StringRef;

// The civil-calendar conversions count 400-year eras of 146097 days from
// 0000-03-01, so that the leap day ends a year (the well-known
// days-from-civil construction).
int64_t netlift::daysFromCivil(int64_t year, unsigned month, unsigned day) {
  year -= month <= 2;
  int64_t era = (year >= 0 ? year : year - 399) / 400;
  int64_t yearOfEra = year - era * 400;
  int64_t dayOfYear =
      (153 * (month > 2 ? month - 3 : month + 9) + 2) / 5 + day - 1;
  int64_t dayOfEra =
      yearOfEra * 365 + yearOfEra / 4 - yearOfEra / 100 + dayOfYear;
  return era * 146097 + dayOfEra - 719468;
}

void netlift::civilFromDays(int64_t days, int64_t &year, unsigned &month,
                            unsigned &day) {
  days += 719468;
  int64_t era = (days >= 0 ? days : days - 146096) / 146097;
  int64_t dayOfEra = days - era * 146097;
  int64_t yearOfEra =
      (dayOfEra - dayOfEra / 1460 + dayOfEra / 36524 - dayOfEra / 146096) / 365;
  int64_t dayOfYear =
      dayOfEra - (365 * yearOfEra + yearOfEra / 4 - yearOfEra / 100);
  int64_t mp = (5 * dayOfYear + 2) / 153;
  day = unsigned(dayOfYear - (153 * mp + 2) / 5 + 1);
  month = unsigned(mp < 10 ? mp + 3 : mp - 9);
  year = yearOfEra + era * 400 + (month <= 2);
}

unsigned netlift::weekdayFromDays(int64_t days) {
  // 1970-01-01 was a Thursday.
  int64_t w = (days + 4) % 7;
  return unsigned(w < 0 ? w + 7 : w);
}

namespace {

bool fail(std::string &error, const llvm::Twine &msg) {
  error = msg.str();
  return false;
}

/// Reads digits and underscores as a number; false when there are none.
bool readNumber(StringRef &text, int64_t &value, unsigned maxDigits = 18) {
  size_t i = 0;
  unsigned digits = 0;
  value = 0;
  while (i < text.size() && (llvm::isDigit(text[i]) || text[i] == '_')) {
    if (text[i] != '_') {
      if (++digits > maxDigits)
        return false;
      value = value * 10 + (text[i] - '0');
    }
    ++i;
  }
  text = text.drop_front(i);
  return digits > 0;
}

/// A fraction of a second after its '.', in nanoseconds (digits past the
/// ninth must be zero).
bool readFraction(StringRef &text, int64_t &ns) {
  ns = 0;
  size_t i = 0;
  int64_t scale = 100000000;
  bool any = false;
  for (; i < text.size() && llvm::isDigit(text[i]); ++i) {
    any = true;
    if (scale == 0) {
      if (text[i] != '0')
        return false;
      continue;
    }
    ns += (text[i] - '0') * scale;
    scale /= 10;
  }
  text = text.drop_front(i);
  return any;
}

bool parseDuration(StringRef literal, StringRef body, int64_t &ns,
                   std::string &error) {
  bool negative = body.consume_front("-");
  body.consume_front("+");
  if (body.empty())
    return fail(error, "empty duration");
  long double total = 0;
  // Matched in this order ("ms" before "m"); each may appear once.
  static const struct {
    const char *name;
    long double ns;
  } units[] = {{"d", 86400e9L}, {"h", 3600e9L}, {"ms", 1e6L}, {"m", 60e9L},
               {"s", 1e9L},     {"us", 1e3L},   {"ns", 1L}};
  int lastUnit = -1;
  while (!body.empty()) {
    size_t i = 0;
    while (i < body.size() &&
           (llvm::isDigit(body[i]) || body[i] == '_' || body[i] == '.'))
      ++i;
    if (i == 0)
      return fail(error, "expected a number in duration '" + literal + "'");
    std::string num;
    for (char c : body.substr(0, i))
      if (c != '_')
        num += c;
    body = body.drop_front(i);
    int unit = -1;
    for (int u = 0; u < 7; ++u) {
      StringRef name = units[u].name;
      if (body.size() >= name.size() &&
          body.substr(0, name.size()).equals_insensitive(name) &&
          // "m" must not swallow the "m" of "ms".
          !(name == "m" && body.size() > 1 &&
            (body[1] == 's' || body[1] == 'S'))) {
        unit = u;
        body = body.drop_front(name.size());
        break;
      }
    }
    if (unit < 0)
      return fail(error, "unknown unit in duration '" + literal +
                             "' (use d, h, m, s, ms, us, ns)");
    // Units must get smaller from left to right (1h2m3s, not 1s2h).
    if (lastUnit >= 0 && units[unit].ns >= units[lastUnit].ns)
      return fail(error, "units out of order in duration '" + literal + "'");
    lastUnit = unit;
    if (num == "." || std::count(num.begin(), num.end(), '.') > 1)
      return fail(error, "expected a number in duration '" + literal + "'");
    total += std::stold(num) * units[unit].ns;
    body.consume_front("_");
  }
  if (total > 9.2e18L)
    return fail(error, "duration '" + literal + "' is too large");
  long double rounded = std::floor(total + 0.5L);
  if (std::fabs(rounded - total) > 1e-6L)
    return fail(error,
                "duration '" + literal + "' is not a whole number of ns");
  ns = static_cast<int64_t>(rounded);
  if (negative)
    ns = -ns;
  return true;
}

bool parseDate(StringRef literal, StringRef &body, int64_t &days,
               std::string &error) {
  int64_t y, m, d;
  if (!readNumber(body, y, 6) || !body.consume_front("-") ||
      !readNumber(body, m, 2) || !body.consume_front("-") ||
      !readNumber(body, d, 2))
    return fail(error, "expected YYYY-MM-DD in '" + literal + "'");
  static const unsigned kDays[] = {31, 29, 31, 30, 31, 30,
                                   31, 31, 30, 31, 30, 31};
  bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  if (m < 1 || m > 12 || d < 1 || d > kDays[m - 1] ||
      (m == 2 && d == 29 && !leap))
    return fail(error, "'" + literal + "' is not a date");
  days = daysFromCivil(y, unsigned(m), unsigned(d));
  return true;
}

bool parseDaytime(StringRef literal, StringRef &body, int64_t &ns,
                  std::string &error) {
  int64_t h, m, s = 0, frac = 0;
  if (!readNumber(body, h, 2) || !body.consume_front(":") ||
      !readNumber(body, m, 2))
    return fail(error, "expected HH:MM:SS in '" + literal + "'");
  if (body.consume_front(":")) {
    if (!readNumber(body, s, 2))
      return fail(error, "expected HH:MM:SS in '" + literal + "'");
    if (body.consume_front(".") && !readFraction(body, frac))
      return fail(error, "expected the fraction of a second in '" + literal +
                             "' (at most nanoseconds)");
  }
  if (h > 23 || m > 59 || s > 59)
    return fail(error, "'" + literal + "' is not a time of day");
  ns = ((h * 60 + m) * 60 + s) * 1000000000LL + frac;
  return true;
}

} // namespace

bool netlift::parseIecTime(StringRef text, IecTimeKind &kind, int64_t &ns,
                           std::string &error, bool prefixOptional) {
  StringRef literal = text.trim();
  StringRef body = literal;
  size_t hash = literal.find('#');
  if (hash != StringRef::npos) {
    std::string prefix = literal.substr(0, hash).upper();
    StringRef p(prefix);
    if (p == "T" || p == "TIME" || p == "LT" || p == "LTIME")
      kind = IecTimeKind::Duration;
    else if (p == "D" || p == "DATE" || p == "LD" || p == "LDATE")
      kind = IecTimeKind::Date;
    else if (p == "TOD" || p == "TIME_OF_DAY" || p == "LTOD" ||
             p == "LTIME_OF_DAY")
      kind = IecTimeKind::TimeOfDay;
    else if (p == "DT" || p == "DATE_AND_TIME" || p == "LDT" ||
             p == "LDATE_AND_TIME")
      kind = IecTimeKind::DateAndTime;
    else
      return fail(error, "'" + literal + "' is not a time literal");
    body = literal.substr(hash + 1);
  } else if (!prefixOptional) {
    return fail(error, "'" + literal + "' is not a time literal");
  }
  switch (kind) {
  case IecTimeKind::Duration:
    return parseDuration(literal, body, ns, error);
  case IecTimeKind::TimeOfDay:
    if (!parseDaytime(literal, body, ns, error))
      return false;
    break;
  case IecTimeKind::Date:
  case IecTimeKind::DateAndTime: {
    int64_t days = 0, daytime = 0;
    if (!parseDate(literal, body, days, error))
      return false;
    if (kind == IecTimeKind::DateAndTime &&
        (!body.consume_front("-") ||
         !parseDaytime(literal, body, daytime, error)))
      return error.empty() ? fail(error, "expected YYYY-MM-DD-HH:MM:SS in '" +
                                             literal + "'")
                           : false;
    // int64 nanoseconds hold 1677-09-21 to 2262-04-11.
    if (__builtin_mul_overflow(days, kNsPerDay, &ns) ||
        __builtin_add_overflow(ns, daytime, &ns))
      return fail(error, "'" + literal +
                             "' is outside the dates netlift holds (1678 to "
                             "2262, in nanoseconds)");
    break;
  }
  }
  if (!body.empty())
    return fail(error, "unexpected '" + body + "' in '" + literal + "'");
  return true;
}

namespace {

/// hh:mm:ss with the fraction of a second when there is one.
void appendDaytime(std::string &out, int64_t ns) {
  char buf[32];
  int64_t secs = ns / 1000000000LL, frac = ns % 1000000000LL;
  snprintf(buf, sizeof buf, "%02lld:%02lld:%02lld",
           static_cast<long long>(secs / 3600),
           static_cast<long long>(secs / 60 % 60),
           static_cast<long long>(secs % 60));
  out += buf;
  if (frac) {
    snprintf(buf, sizeof buf, ".%09lld", static_cast<long long>(frac));
    std::string f = buf;
    while (f.back() == '0')
      f.pop_back();
    out += f;
  }
}

void appendDate(std::string &out, int64_t days) {
  int64_t y;
  unsigned m, d;
  civilFromDays(days, y, m, d);
  char buf[32];
  snprintf(buf, sizeof buf, "%04lld-%02u-%02u", static_cast<long long>(y), m,
           d);
  out += buf;
}

int64_t floorDiv(int64_t a, int64_t b) {
  int64_t q = a / b;
  return (a % b != 0 && (a < 0) != (b < 0)) ? q - 1 : q;
}

} // namespace

std::string netlift::formatIecTime(IecTimeKind kind, int64_t ns,
                                   bool longForm) {
  static const char *const kShort[] = {"T#", "D#", "TOD#", "DT#"};
  static const char *const kLong[] = {"LTIME#", "LDATE#", "LTOD#", "LDT#"};
  return (longForm ? kLong : kShort)[unsigned(kind)] +
         formatIecTimeValue(kind, ns);
}

std::string netlift::formatIecTimeValue(IecTimeKind kind, int64_t ns) {
  std::string out;
  switch (kind) {
  case IecTimeKind::Duration: {
    // The magnitude as unsigned, so that INT64_MIN has one.
    uint64_t left = ns < 0 ? 0 - uint64_t(ns) : uint64_t(ns);
    if (ns < 0)
      out += '-';
    static const struct {
      const char *name;
      uint64_t ns;
    } units[] = {{"d", 86400000000000ULL},
                 {"h", 3600000000000ULL},
                 {"m", 60000000000ULL},
                 {"s", 1000000000ULL},
                 {"ms", 1000000ULL},
                 {"us", 1000ULL},
                 {"ns", 1ULL}};
    bool any = false;
    for (auto &u : units) {
      uint64_t n = left / u.ns;
      left %= u.ns;
      if (n) {
        out += std::to_string(n) + u.name;
        any = true;
      }
    }
    if (!any)
      out += "0ms";
    return out;
  }
  case IecTimeKind::Date:
    appendDate(out, floorDiv(ns, kNsPerDay));
    return out;
  case IecTimeKind::TimeOfDay:
    if (ns < 0 || ns >= kNsPerDay) {
      // Past midnight (TOD arithmetic does not wrap): the hours go on.
      out += ns < 0 ? "-" : "";
      ns = ns < 0 ? -ns : ns;
    }
    appendDaytime(out, ns);
    return out;
  case IecTimeKind::DateAndTime: {
    int64_t days = floorDiv(ns, kNsPerDay);
    appendDate(out, days);
    out += '-';
    appendDaytime(out, ns - days * kNsPerDay);
    return out;
  }
  }
  return out;
}
