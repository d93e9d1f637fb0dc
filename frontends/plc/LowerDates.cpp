//===- LowerDates.cpp - DATE, TOD, DT and their L forms in NetIR ----------===//
//
// A date type's value is a NetIR int64 (overflow an error) counting
// nanoseconds: since midnight for TOD and LTOD, since 1970-01-01 00:00:00
// for DATE, DT and their L forms (a DATE at midnight). One unit for all
// makes DT - DT, TOD + TIME and DT_TO_TOD plain integer arithmetic and
// keeps LDT's nanoseconds; TIME counts ticks, so a duration is scaled by the
// tick on its way in and rounded up to whole ticks on its way out
// (ARCHITECTURE §3.4, with a note). Conversions to integers give what
// CODESYS and TwinCAT give: seconds for DATE and DT, milliseconds for TOD,
// nanoseconds for the L forms. Text conversions use NetIR's format_* and
// parse_* built-ins (IEC literals, ir/support/IecTime.h).
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

#include "ir/support/IecTime.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

namespace {
bool isDate(const PType *t) { return t && t->kind == PTypeKind::Date; }
bool isTime(const PType *t) { return t && t->kind == PTypeKind::Time; }
} // namespace

NExpr *Lowering::ticksToNs(NExpr *ticks, SMLoc at) {
  return b.binary(net::BinaryOp::Mul, ticks, b.intLit(tickNs, at), at);
}

NExpr *Lowering::nsToTicks(NExpr *ns, SMLoc at) {
  if (tickNs == 1)
    return ns;
  if (!notedTickRounding) {
    notedTickRounding = true;
    diag.note(at, "a duration computed at run time (from dates, times of "
                  "day or numbers) is rounded up to whole ticks of " +
                      formatDuration(tickNs));
  }
  // ns / tick, plus one when a positive remainder is left: no overflow
  // near the ends of int64.
  NExpr *k = b.intLit(tickNs, at);
  NExpr *q = b.binary(net::BinaryOp::Div, ns, k, at);
  NExpr *rest = b.binary(net::BinaryOp::Mod, ns, k, at);
  return b.binary(net::BinaryOp::Add, q,
                  b.cond(b.binary(net::BinaryOp::Gt, rest, b.intLit(0, at), at),
                         b.intLit(1, at), b.intLit(0, at), at),
                  at);
}

NExpr *Lowering::dateArithmetic(Op op, NExpr *l, const PType *lt, NExpr *r,
                                const PType *rt, SMLoc at) {
  lt = baseOf(lt);
  rt = baseOf(rt);
  if (op == Op::Add && isTime(lt))
    std::swap(l, r), std::swap(lt, rt);
  if (isTime(rt)) // TOD +- TIME, DT +- TIME
    return b.binary(op == Op::Add ? net::BinaryOp::Add : net::BinaryOp::Sub, l,
                    ticksToNs(r, at), at);
  // DATE - DATE, TOD - TOD, DT - DT: a duration.
  return nsToTicks(b.binary(net::BinaryOp::Sub, l, r, at), at);
}

NExpr *Lowering::convertDate(NExpr *v, const PType *from, const PType *to,
                             SMLoc at) {
  NExpr *day = b.intLit(kNsPerDay, at);
  // The time of day of a count of nanoseconds since 1970 (a day before
  // 1970 has its time of day too).
  auto daytime = [&](NExpr *ns) {
    NExpr *m = b.binary(net::BinaryOp::Mod, ns, day, at);
    return b.binary(
        net::BinaryOp::Mod,
        b.binary(net::BinaryOp::Add, m, b.intLit(kNsPerDay, at), at), day, at);
  };
  // Nanoseconds per unit of the integer a date type converts to.
  auto unitOf = [](const PType *t) -> int64_t {
    if (t->width == 64)
      return 1;
    return t->dateKind == DateKind::TimeOfDay ? 1000000 : 1000000000;
  };
  if (isDate(from) && isDate(to)) {
    if (to->dateKind == DateKind::TimeOfDay &&
        from->dateKind != DateKind::TimeOfDay)
      return daytime(v); // DT_TO_TOD
    if (to->dateKind == DateKind::Date &&
        from->dateKind == DateKind::DateAndTime)
      return b.binary(net::BinaryOp::Sub, v, daytime(v), at); // DT_TO_DATE
    if (to->dateKind == from->dateKind || to->dateKind == DateKind::DateAndTime)
      return v; // LDT_TO_DT, DATE_TO_DT, TOD_TO_DT (on 1970-01-01)
    refuse(at, "conversion from " + from->str() + " to " + to->str() +
                   " has no meaning");
  }
  if (isDate(from) && isTime(to)) {
    if (from->dateKind != DateKind::TimeOfDay)
      refuse(at, "conversion from " + from->str() + " to " + to->str() +
                     " has no meaning (subtract two dates for a duration)");
    return nsToTicks(v, at); // TOD_TO_TIME: the time since midnight
  }
  if (isTime(from) && isDate(to)) {
    if (to->dateKind != DateKind::TimeOfDay)
      refuse(at, "conversion from " + from->str() + " to " + to->str() +
                     " has no meaning (add a duration to a date and time)");
    return ticksToNs(v, at);
  }
  if (to->kind == PTypeKind::String)
    return dateToString(v, from, to, at);
  if (from->kind == PTypeKind::String)
    return stringToDate(v, from, to, at);
  const PType *lint = elementaryType("LINT");
  if (isDate(from)) {
    // To seconds, milliseconds or nanoseconds (rounded down), then on as
    // a LINT.
    int64_t unit = unitOf(from);
    NExpr *n = v;
    if (unit > 1) {
      NExpr *k = b.intLit(unit, at);
      // Floor division: a time before 1970 counts down.
      NExpr *q = b.binary(net::BinaryOp::Div, v, k, at);
      NExpr *neg =
          b.binary(net::BinaryOp::Lt, b.binary(net::BinaryOp::Mod, v, k, at),
                   b.intLit(0, at), at);
      n = b.binary(net::BinaryOp::Sub, q,
                   b.cond(neg, b.intLit(1, at), b.intLit(0, at), at), at);
    }
    return convert(n, lint, to, at);
  }
  // From a number: that many seconds, milliseconds or nanoseconds.
  NExpr *n = convert(v, from, lint, at);
  int64_t unit = unitOf(to);
  return unit == 1 ? n
                   : b.binary(net::BinaryOp::Mul, n, b.intLit(unit, at), at);
}

NExpr *Lowering::dateToString(NExpr *v, const PType *from, const PType *to,
                              SMLoc at) {
  // The literal CODESYS and TwinCAT write: T#1s500ms, LTIME#1s500ms,
  // D#2024-01-15, TOD#12:30:00, DT#2024-01-15-12:30:00.5, LDT#...
  bool wide = from->width == 64;
  net::Builtin fn;
  const char *prefix;
  if (isTime(from)) {
    fn = net::Builtin::FormatDuration;
    prefix = from->name == "LTIME" ? "LTIME#" : "T#";
    v = ticksToNs(v, at);
  } else if (from->dateKind == DateKind::Date) {
    fn = net::Builtin::FormatDate;
    prefix = wide ? "LDATE#" : "D#";
  } else if (from->dateKind == DateKind::TimeOfDay) {
    fn = net::Builtin::FormatTod;
    prefix = wide ? "LTOD#" : "TOD#";
  } else {
    fn = net::Builtin::FormatDt;
    prefix = wide ? "LDT#" : "DT#";
  }
  std::u16string p(prefix, prefix + strlen(prefix));
  NExpr *text =
      b.call(net::Builtin::Concat,
             {b.stringLit(llvm::ArrayRef<char16_t>(p.data(), p.size()), at),
              b.call(fn, {v}, at)},
             at);
  return b.convert(stringType(to, at, "conversion result"), text, at);
}

NExpr *Lowering::stringToDate(NExpr *v, const PType *, const PType *to,
                              SMLoc at) {
  if (isTime(to))
    return nsToTicks(b.call(net::Builtin::ParseDuration, {v}, at), at);
  net::Builtin fn = to->dateKind == DateKind::Date ? net::Builtin::ParseDate
                    : to->dateKind == DateKind::TimeOfDay
                        ? net::Builtin::ParseTod
                        : net::Builtin::ParseDt;
  return b.call(fn, {v}, at);
}
