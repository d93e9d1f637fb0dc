//===- StringOps.h - what NetIR's string functions compute ------*- C++ -*-===//
//
// The values of NetIR's string built-ins (len, left, right, mid, concat,
// insert, delete, replace, find, code, with_code), of comparisons between
// strings, and of conversions between strings and numbers, on values held as
// sequences of 16-bit code units (a `string[n]` uses only 0..255). The rules
// are IEC 61131-3's (positions count from 1; docs/netir.md, "Strings" writes
// down where the standard leaves a choice); a position or length outside
// them is an error the caller reports with its location. Also the text of a
// string literal in NetIR, read and written. One definition for every
// evaluator, as FloatOps.h is for floats.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_STRINGOPS_H
#define NETLIFT_IR_NET_STRINGOPS_H

#include "ir/net/Expr.h"
#include "ir/net/FloatOps.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"

#include <optional>
#include <string>

namespace netlift::net {

using StringValue = std::u16string;

/// A string built-in applied to its operands: `strs` are the string
/// operands in order, `ints` the integer ones (left/right: n; mid, delete:
/// n, p; insert: p; replace: n, p). Returns the message of the rule a
/// position or length breaks, or nullopt with the result in `out`.
std::optional<std::string> applyStringBuiltin(Builtin fn,
                                              llvm::ArrayRef<StringValue> strs,
                                              llvm::ArrayRef<int64_t> ints,
                                              StringValue &out);
/// parse_duration(s), parse_date(s), parse_tod(s), parse_dt(s): the
/// nanoseconds the text spells, or the message saying why it spells none.
std::optional<std::string> parseTimeText(Builtin fn, const StringValue &s,
                                         int64_t &ns);
/// find(a, b) and len(s), which give integers.
int64_t findString(const StringValue &a, const StringValue &b);
/// code(s, p): the p-th code unit of s, 0 past its end; an error for p < 1.
std::optional<std::string> codeAt(const StringValue &s, int64_t p,
                                  int64_t &code);
/// `a op b` for a comparison: code unit by code unit, a proper prefix
/// before the longer string.
bool compareStrings(BinaryOp op, const StringValue &a, const StringValue &b);

/// The text `string[n](v)` gives for a value of a scalar type: integers in
/// decimal, floats in shortest round-trip form, bools as TRUE / FALSE.
StringValue scalarToString(const Type *from, int64_t v);
/// `to(s)` for a number, bool or float target: the text read as a literal
/// of that type (blanks around it ignored; integers may be 2#, 8#, 16#
/// based and use `_` between digits). NotANumber when it is not one.
ConvertError stringToScalar(const StringValue &s, const Type *to, int64_t &out);

/// The characters as UTF-8 (a lone surrogate code unit as U+FFFD), for
/// JSON and CSV.
std::string toUtf8(const StringValue &s);
/// Appends the UTF-8 encoding of a code point of the Basic Multilingual
/// Plane (below U+10000).
void appendUtf8(std::string &out, uint32_t code);
/// NetIR text of a string literal, quotes included: `\"`, `\\`, `\n`, `\t`
/// escaped, other code units outside printable ASCII as `\xHH` or `\uHHHH`.
std::string formatStringLiteral(llvm::ArrayRef<char16_t> chars);
/// Reads the text between the quotes of a NetIR string literal. On error,
/// returns the message and sets `errorAt` to the offset of the bad escape.
std::optional<std::string>
parseStringLiteral(llvm::StringRef body, StringValue &out, size_t &errorAt);

} // namespace netlift::net

#endif
