//===- IecTime.h - IEC 61131-3 durations, dates and times of day -*- C++
//-*-===//
//
// The text of IEC 61131-3 time literals and the calendar behind it, shared by
// the PLC frontends (which read `T#1s500ms`, `D#2024-01-15`, `TOD#12:30:00`,
// `DT#2024-01-15-12:30:00` in programs) and NetIR's string conversions (which
// write and read the same text at run time, TIME_TO_STRING and
// STRING_TO_DT). Every value is a count of nanoseconds: a duration's length,
// a time of day's distance from midnight, a date's or a date and time's from
// 1970-01-01 00:00:00 (proleptic Gregorian calendar, no leap seconds).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_SUPPORT_IECTIME_H
#define NETLIFT_IR_SUPPORT_IECTIME_H

#include "llvm/ADT/StringRef.h"

#include <cstdint>
#include <string>

namespace netlift {

/// What a time text denotes.
enum class IecTimeKind : uint8_t { Duration, Date, TimeOfDay, DateAndTime };

constexpr int64_t kNsPerDay = 86400LL * 1000000000LL;

/// Days since 1970-01-01 of a proleptic Gregorian date (month 1..12).
int64_t daysFromCivil(int64_t year, unsigned month, unsigned day);
/// The date `days` after 1970-01-01.
void civilFromDays(int64_t days, int64_t &year, unsigned &month, unsigned &day);
/// The day of the week of a day count, 0 = Sunday .. 6 = Saturday.
unsigned weekdayFromDays(int64_t days);

/// Reads a literal's value: with its prefix (`T#1s`, `LTOD#1:2:3`,
/// `DATE#2024-01-15`; `kind` is then set from the prefix) or, when
/// `prefixOptional`, the bare value in the given `kind`. False with `error`
/// set when the text is not such a literal or its value does not fit.
bool parseIecTime(llvm::StringRef text, IecTimeKind &kind, int64_t &ns,
                  std::string &error, bool prefixOptional = false);

/// The literal of a value in the form CODESYS and TwinCAT write:
/// `T#1h2m3s4ms` (zero components left out, `T#0ms` for zero),
/// `D#2024-01-15`, `TOD#12:30:00.5`, `DT#2024-01-15-12:30:00`; `longForm`
/// gives the LTIME/LDATE/LTOD/LDT prefixes (`LTIME#`, `LDATE#`, `LTOD#`,
/// `LDT#`).
std::string formatIecTime(IecTimeKind kind, int64_t ns, bool longForm = false);
/// The same text without its prefix and '#' (`1h2m3s4ms`, `2024-01-15`).
std::string formatIecTimeValue(IecTimeKind kind, int64_t ns);

} // namespace netlift

#endif
