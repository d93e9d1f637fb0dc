//===- IecTimeTest.cpp - the calendar and the text of IEC time literals ---===//
#include "ir/support/IecTime.h"

#include <gtest/gtest.h>

#include <ctime>

using namespace netlift;

namespace {

TEST(IecTime, CalendarAgreesWithTheCLibrary) {
  // Every day from 1900 to 2200 against timegm's proleptic Gregorian count.
  for (int64_t days = -25567; days <= 84006; ++days) {
    int64_t y;
    unsigned m, d;
    civilFromDays(days, y, m, d);
    ASSERT_EQ(daysFromCivil(y, m, d), days);
    std::tm tm{};
    tm.tm_year = int(y - 1900);
    tm.tm_mon = int(m - 1);
    tm.tm_mday = int(d);
    ASSERT_EQ(int64_t(timegm(&tm)), days * 86400) << y << "-" << m << "-" << d;
    ASSERT_EQ(int(weekdayFromDays(days)), tm.tm_wday);
  }
}

TEST(IecTime, LiteralsReadBackAsWritten) {
  struct Case {
    const char *in;
    IecTimeKind kind;
    const char *out;
  } cases[] = {
      {"T#1h2m3s4ms", IecTimeKind::Duration, "T#1h2m3s4ms"},
      {"TIME#-1.5s", IecTimeKind::Duration, "T#-1s500ms"},
      {"t#0s", IecTimeKind::Duration, "T#0ms"},
      {"D#2000-02-29", IecTimeKind::Date, "D#2000-02-29"},
      {"LDATE#1969-12-31", IecTimeKind::Date, "D#1969-12-31"},
      {"TOD#7:05:09.25", IecTimeKind::TimeOfDay, "TOD#07:05:09.25"},
      {"TIME_OF_DAY#23:59", IecTimeKind::TimeOfDay, "TOD#23:59:00"},
      {"DT#2262-04-11-23:47:16.854775807", IecTimeKind::DateAndTime,
       "DT#2262-04-11-23:47:16.854775807"},
  };
  for (const Case &c : cases) {
    IecTimeKind kind;
    int64_t ns = 0;
    std::string error;
    ASSERT_TRUE(parseIecTime(c.in, kind, ns, error)) << c.in << ": " << error;
    EXPECT_EQ(kind, c.kind) << c.in;
    EXPECT_EQ(formatIecTime(kind, ns), c.out) << c.in;
  }
}

TEST(IecTime, MalformedLiteralsSayWhy) {
  struct Case {
    const char *in;
    const char *error;
  } cases[] = {
      {"D#2023-02-29", "'D#2023-02-29' is not a date"},
      {"TOD#24:00:00", "'TOD#24:00:00' is not a time of day"},
      {"DT#2024-01-01", "expected YYYY-MM-DD-HH:MM:SS in 'DT#2024-01-01'"},
      {"DT#2263-01-01-00:00:00",
       "'DT#2263-01-01-00:00:00' is outside the dates netlift holds (1678 to "
       "2262, in nanoseconds)"},
      {"T#1s2h", "units out of order in duration 'T#1s2h'"},
      {"X#1", "'X#1' is not a time literal"},
  };
  for (const Case &c : cases) {
    IecTimeKind kind;
    int64_t ns;
    std::string error;
    EXPECT_FALSE(parseIecTime(c.in, kind, ns, error)) << c.in;
    EXPECT_EQ(error, c.error);
  }
  // Bare text reads in the kind asked for (STRING_TO_DATE('2024-01-15')).
  IecTimeKind kind = IecTimeKind::Date;
  int64_t ns;
  std::string error;
  ASSERT_TRUE(parseIecTime("2024-01-15", kind, ns, error, true)) << error;
  EXPECT_EQ(ns, daysFromCivil(2024, 1, 15) * kNsPerDay);
}

} // namespace
