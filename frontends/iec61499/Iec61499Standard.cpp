//===- Iec61499Standard.cpp - 4diac's standard library, known by name -----===//
//
// A 4diac IDE 3 project does not copy the standard library into its folder
// (the IDE keeps it as a library outside the project), so a system's
// F_ADD, F_INT_TO_REAL, IX, PUBLISH_1 or FB_CTU is often in no file the
// user can give with -I. netlift knows these types by name: where a type is
// neither in the inputs, nor in the -I directories, nor one of
// lib/iec61499's blocks, a name of the standard library's families gets
// the interface the standard gives it (IEC 61131-3's function signatures
// and function blocks as 4diac wraps them: REQ with the inputs, CNF with
// the outputs; 4diac's service interfaces for communication and I/O). The
// type is then what its name means elsewhere in the frontend: a generic
// function or conversion gets its body (Iec61499Functions.cpp), a service
// FB is modelled as environment (Iec61499Environment.cpp), the IEC 61131-3
// bistables, edge detectors and counters get the ST body written here. A
// note at the first use says which type was taken by name.
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

#include "llvm/ADT/StringSwitch.h"

using namespace netlift;
using namespace netlift::iec61499::detail;

namespace {

/// An interface (and, for the IEC 61131-3 function blocks, the ST run on
/// REQ over internal variables) from which the type's XML is written.
struct TypeSpec : InterfaceSpec {
  std::vector<PortSpec> internals;
  std::string requestBody; // a SimpleFB's REQ algorithm, or none

  /// REQ with every input, CNF with every output: IEC 61131-3's call of a
  /// function or function block as 4diac wraps it.
  /// `body` runs on REQ over `internals` (a function block's memory).
  static TypeSpec request(std::vector<PortSpec> in, std::vector<PortSpec> out,
                          std::string body = "",
                          std::vector<PortSpec> internals = {}) {
    TypeSpec t;
    t.internals = std::move(internals);
    t.inputs = std::move(in);
    t.outputs = std::move(out);
    EventSpec req{"REQ", {}}, cnf{"CNF", {}};
    for (const PortSpec &p : t.inputs)
      req.with.push_back(p.name);
    for (const PortSpec &p : t.outputs)
      cnf.with.push_back(p.name);
    t.eventInputs.push_back(req);
    t.eventOutputs.push_back(cnf);
    t.requestBody = std::move(body);
    return t;
  }
};

/// The generic functions genericFunctionBody gives a body: their
/// parameters and generic types (IEC 61131-3 tables 22-30).
std::optional<TypeSpec> genericFunction(StringRef name) {
  auto binary = [](const char *in, const char *out) {
    return TypeSpec::request({{"IN1", in}, {"IN2", in}}, {{"OUT", out}});
  };
  auto ternary = [](const char *type) {
    return TypeSpec::request({{"IN1", type}, {"IN2", type}, {"IN3", type}},
                             {{"OUT", type}});
  };
  auto unary = [](const char *in, const char *out) {
    return TypeSpec::request({{"IN", in}}, {{"OUT", out}});
  };
  auto shift = [] {
    return TypeSpec::request({{"IN", "ANY_BIT"}, {"N", "ANY_INT"}},
                             {{"OUT", "ANY_BIT"}});
  };
  std::string n = name.upper();
  if (n == "F_ADD" || n == "F_SUB")
    return binary("ANY_MAGNITUDE", "ANY_MAGNITUDE");
  if (n == "F_ADD_3")
    return ternary("ANY_MAGNITUDE");
  if (n == "F_MUL" || n == "F_DIV")
    return binary("ANY_NUM", "ANY_NUM");
  if (n == "F_MOD")
    return binary("ANY_INT", "ANY_INT");
  if (n == "F_AND" || n == "F_OR" || n == "F_XOR")
    return binary("ANY_BIT", "ANY_BIT");
  if (n == "F_AND_3" || n == "F_OR_3" || n == "F_XOR_3")
    return ternary("ANY_BIT");
  if (n == "F_EQ" || n == "F_NE" || n == "F_GT" || n == "F_GE" || n == "F_LT" ||
      n == "F_LE")
    return binary("ANY_ELEMENTARY", "BOOL");
  if (n == "F_MAX" || n == "F_MIN")
    return binary("ANY_ELEMENTARY", "ANY_ELEMENTARY");
  // Configured with a structure (StructuredType), they get a port per
  // member (Iec61499Functions.cpp); unconfigured, environment.
  if (n == "STRUCT_MUX")
    return TypeSpec::request({}, {{"OUT", "ANY_STRUCT"}});
  if (n == "STRUCT_DEMUX")
    return TypeSpec::request({{"IN", "ANY_STRUCT"}}, {});
  if (n == "F_MOVE")
    return unary("ANY", "ANY");
  if (n == "F_ABS")
    return unary("ANY_NUM", "ANY_NUM");
  if (n == "F_NOT")
    return unary("ANY_BIT", "ANY_BIT");
  if (n == "F_SHL" || n == "F_SHR" || n == "F_ROL" || n == "F_ROR")
    return shift();
  if (n == "F_LIMIT")
    return TypeSpec::request({{"MN", "ANY_ELEMENTARY"},
                              {"IN", "ANY_ELEMENTARY"},
                              {"MX", "ANY_ELEMENTARY"}},
                             {{"OUT", "ANY_ELEMENTARY"}});
  if (n == "F_SEL")
    return TypeSpec::request({{"G", "BOOL"}, {"IN0", "ANY"}, {"IN1", "ANY"}},
                             {{"OUT", "ANY"}});
  if (n == "F_MUX_2")
    return TypeSpec::request({{"K", "ANY_INT"}, {"IN1", "ANY"}, {"IN2", "ANY"}},
                             {{"OUT", "ANY"}});
  static const char *const kRealFunctions[] = {
      "F_SQRT", "F_LN",  "F_LOG",  "F_EXP",  "F_SIN",
      "F_COS",  "F_TAN", "F_ASIN", "F_ACOS", "F_ATAN"};
  if (llvm::is_contained(kRealFunctions, StringRef(n)))
    return unary("ANY_REAL", "ANY_REAL");
  if (n == "F_EXPT")
    return binary("ANY_REAL", "ANY_REAL");
  if (n == "F_TRUNC")
    return unary("ANY_REAL", "ANY_INT");
  if (n == "F_MULTIME" || n == "F_DIVTIME")
    return TypeSpec::request({{"IN1", "TIME"}, {"IN2", "ANY_NUM"}},
                             {{"OUT", "TIME"}});
  // The character string functions (IEC 61131-3 table 29).
  auto strings = [](std::vector<PortSpec> in, const char *out) {
    return TypeSpec::request(std::move(in), {{"OUT", out}});
  };
  const char *S = "ANY_STRING", *I = "ANY_INT";
  if (n == "F_LEN")
    return strings({{"IN", S}}, I);
  if (n == "F_LEFT" || n == "F_RIGHT")
    return strings({{"IN", S}, {"L", I}}, S);
  if (n == "F_MID" || n == "F_DELETE")
    return strings({{"IN", S}, {"L", I}, {"P", I}}, S);
  if (n == "F_CONCAT")
    return strings({{"IN1", S}, {"IN2", S}}, S);
  if (n == "F_INSERT")
    return strings({{"IN1", S}, {"IN2", S}, {"P", I}}, S);
  if (n == "F_REPLACE")
    return strings({{"IN1", S}, {"IN2", S}, {"L", I}, {"P", I}}, S);
  if (n == "F_FIND")
    return strings({{"IN1", S}, {"IN2", S}}, I);
  return std::nullopt;
}

/// The elementary types a conversion F_<A>_TO_<B> or <A>2<A> may name.
bool isElementary(StringRef type) {
  return llvm::StringSwitch<bool>(type.upper())
      .Cases("BOOL", "BYTE", "WORD", "DWORD", "LWORD", true)
      .Cases("SINT", "INT", "DINT", "LINT", true)
      .Cases("USINT", "UINT", "UDINT", "ULINT", true)
      .Cases("REAL", "LREAL", "TIME", "LTIME", true)
      .Cases("DATE", "TIME_OF_DAY", "TOD", "DATE_AND_TIME", "DT", true)
      .Cases("STRING", "WSTRING", "CHAR", "WCHAR", true)
      .Default(false);
}

std::optional<TypeSpec> conversion(StringRef name) {
  std::string n = name.upper();
  StringRef s = n;
  if (s.consume_front("F_")) {
    size_t to = s.find("_TO_");
    if (to == StringRef::npos)
      return std::nullopt;
    StringRef from = s.take_front(to), target = s.drop_front(to + 4);
    if (!isElementary(from) || !isElementary(target))
      return std::nullopt;
    // The ports spell out what the name abbreviates, as 4diac's do.
    auto spelled = [](StringRef type) {
      return llvm::StringSwitch<std::string>(type)
          .Case("DT", "DATE_AND_TIME")
          .Case("TOD", "TIME_OF_DAY")
          .Default(type.str());
    };
    return TypeSpec::request({{"IN", spelled(from)}},
                             {{"OUT", spelled(target)}});
  }
  // 4diac's convert/ blocks: INT2INT, STRING2STRING (a copy).
  size_t two = s.find('2');
  if (two == StringRef::npos || s.take_front(two) != s.drop_front(two + 1) ||
      !isElementary(s.take_front(two)))
    return std::nullopt;
  std::string type = s.take_front(two).str();
  return TypeSpec::request({{"IN", type}}, {{"OUT", type}});
}

/// The typed functions (typedFunction): their interface; the body comes
/// from modelFunctionFb, as for a 4diac file declaring them without one.
std::optional<TypeSpec> typedFunctionBlock(StringRef name) {
  std::optional<TypedFunction> f = typedFunction(name);
  if (!f)
    return std::nullopt;
  return TypeSpec::request(f->inputs, {f->output});
}

/// A count written after a prefix (`PUBLISH_3`), or nullopt.
std::optional<unsigned> countAfter(StringRef s, StringRef prefix) {
  unsigned n;
  if (!s.consume_front(prefix) || s.empty() || s.getAsInteger(10, n) || n > 99)
    return std::nullopt;
  return n;
}

void numbered(std::vector<PortSpec> &to, std::vector<std::string> &with,
              const char *prefix, unsigned count) {
  for (unsigned i = 1; i <= count; ++i) {
    std::string p = prefix + std::to_string(i);
    to.push_back({p, "ANY"});
    with.push_back(p);
  }
}

/// The part 4diac's service FBs share: INIT with QI and their parameter
/// (`ID`, `PARAMS`), answered by INITO with QO and STATUS (a string of the
/// parameter's type).
TypeSpec initialised(const char *parameter, const char *stringType) {
  TypeSpec t;
  t.inputs = {{"QI", "BOOL"}, {parameter, stringType}};
  t.outputs = {{"QO", "BOOL"}, {"STATUS", stringType}};
  t.eventInputs.push_back({"INIT", {"QI", parameter}});
  t.eventOutputs.push_back({"INITO", {"QO", "STATUS"}});
  return t;
}

/// PUBLISH_n / SUBSCRIBE_n, CLIENT_m_n / SERVER_m_n (m data sent, n
/// received; CLIENT_n is CLIENT_n_n): 4diac's communication service FBs.
std::optional<TypeSpec> communication(StringRef name) {
  std::string n = name.upper();
  StringRef s = n;
  unsigned sent = 0, received = 0;
  bool requester; // REQ/CNF (publisher, client) or RSP/IND
  if (auto c = countAfter(s, "PUBLISH_")) {
    sent = *c;
    requester = true;
  } else if (auto c = countAfter(s, "SUBSCRIBE_")) {
    received = *c;
    requester = false;
  } else {
    StringRef rest = s;
    if (rest.consume_front("CLIENT_"))
      requester = true;
    else if (rest.consume_front("SERVER_"))
      requester = false;
    else
      return std::nullopt;
    auto [m, k] = rest.split('_');
    if (m.getAsInteger(10, sent) || sent > 99)
      return std::nullopt;
    received = sent;
    if (!k.empty() && (k.getAsInteger(10, received) || received > 99))
      return std::nullopt;
  }
  TypeSpec t = initialised("ID", "WSTRING");
  EventSpec send{requester ? "REQ" : "RSP", {"QI"}};
  EventSpec back{requester ? "CNF" : "IND", {"QO", "STATUS"}};
  numbered(t.inputs, send.with, "SD_", sent);
  numbered(t.outputs, back.with, "RD_", received);
  t.eventInputs.push_back(send);
  t.eventOutputs.push_back(back);
  return t;
}

/// 4diac's process image blocks: IX/IB/IW/ID/IL read an input, QX...QL
/// write an output, of BOOL, BYTE, WORD, DWORD, LWORD.
std::optional<TypeSpec> processImage(StringRef name) {
  std::string n = name.upper();
  if (n.size() != 2 || (n[0] != 'I' && n[0] != 'Q'))
    return std::nullopt;
  const char *type = llvm::StringSwitch<const char *>(n.substr(1))
                         .Case("X", "BOOL")
                         .Case("B", "BYTE")
                         .Case("W", "WORD")
                         .Case("D", "DWORD")
                         .Case("L", "LWORD")
                         .Default(nullptr);
  if (!type)
    return std::nullopt;
  TypeSpec t = initialised("PARAMS", "STRING");
  if (n[0] == 'I') {
    t.outputs.push_back({"IN", type});
    t.eventInputs.push_back({"REQ", {"QI"}});
    t.eventOutputs.push_back({"CNF", {"QO", "STATUS", "IN"}});
    if (n == "IX") // a change of the input, reported on its own
      t.eventOutputs.push_back({"IND", {"QO", "STATUS", "IN"}});
  } else {
    t.inputs.push_back({"OUT", type});
    t.eventInputs.push_back({"REQ", {"QI", "OUT"}});
    t.eventOutputs.push_back({"CNF", {"QO", "STATUS"}});
  }
  return t;
}

/// IEC 61131-3's bistables, edge detectors and counters (table 43-45) as
/// 4diac wraps them: each REQ is one call of the block.
std::optional<TypeSpec> standardBlock(StringRef name) {
  std::string n = name.upper();
  if (n == "FB_R_TRIG" || n == "FB_F_TRIG") {
    return TypeSpec::request({{"CLK", "BOOL"}}, {{"Q", "BOOL"}},
                             n == "FB_R_TRIG"
                                 ? "Q := CLK AND NOT M; M := CLK;"
                                 : "Q := NOT CLK AND NOT M; M := NOT CLK;",
                             {{"M", "BOOL"}});
  }
  if (n == "FB_SR")
    return TypeSpec::request({{"S1", "BOOL"}, {"R", "BOOL"}}, {{"Q1", "BOOL"}},
                             "Q1 := S1 OR (NOT R AND Q1);");
  if (n == "FB_RS")
    return TypeSpec::request({{"S", "BOOL"}, {"R1", "BOOL"}}, {{"Q1", "BOOL"}},
                             "Q1 := NOT R1 AND (S OR Q1);");
  // FB_CTU, FB_CTU_DINT, ...: the count's type after the name, INT without.
  StringRef s = n;
  std::string kind;
  for (const char *k : {"FB_CTUD", "FB_CTU", "FB_CTD"})
    if (s.startswith(k)) {
      kind = k;
      break;
    }
  if (kind.empty())
    return std::nullopt;
  StringRef suffix = s.drop_front(kind.size());
  std::string count = "INT";
  if (!suffix.empty()) {
    if (!suffix.consume_front("_") || (suffix != "DINT" && suffix != "LINT" &&
                                       suffix != "UDINT" && suffix != "ULINT"))
      return std::nullopt;
    count = suffix.str();
  }
  // The range of the count: a count stops at its type's ends (PVmax and
  // PVmin of the standard), and a rising edge counts (the block keeps the
  // last CU and CD it saw).
  std::string max = llvm::StringSwitch<std::string>(count)
                        .Case("INT", "32767")
                        .Case("DINT", "2147483647")
                        .Case("LINT", "9223372036854775807")
                        .Case("UDINT", "4294967295")
                        .Default("18446744073709551615");
  std::string min = llvm::StringSwitch<std::string>(count)
                        .Case("INT", "-32768")
                        .Case("DINT", "-2147483648")
                        .Case("LINT", "(-9223372036854775807 - 1)")
                        .Default("0");
  std::string up = "CU AND NOT CU_M AND CV < " + max;
  std::string down = "CD AND NOT CD_M AND CV > " + min;
  if (kind == "FB_CTU") {
    return TypeSpec::request(
        {{"CU", "BOOL"}, {"R", "BOOL"}, {"PV", count}},
        {{"Q", "BOOL"}, {"CV", count}},
        "IF R THEN CV := 0; ELSIF " + up +
            " THEN CV := CV + 1; END_IF; CU_M := CU; Q := CV >= PV;",
        {{"CU_M", "BOOL"}});
  }
  if (kind == "FB_CTD") {
    return TypeSpec::request(
        {{"CD", "BOOL"}, {"LD", "BOOL"}, {"PV", count}},
        {{"Q", "BOOL"}, {"CV", count}},
        "IF LD THEN CV := PV; ELSIF " + down +
            " THEN CV := CV - 1; END_IF; CD_M := CD; Q := CV <= 0;",
        {{"CD_M", "BOOL"}});
  }
  // Both edges at once count neither way.
  return TypeSpec::request(
      {{"CU", "BOOL"},
       {"CD", "BOOL"},
       {"R", "BOOL"},
       {"LD", "BOOL"},
       {"PV", count}},
      {{"QU", "BOOL"}, {"QD", "BOOL"}, {"CV", count}},
      "IF R THEN CV := 0; ELSIF LD THEN CV := PV; ELSIF NOT (CU AND NOT "
      "CU_M AND CD AND NOT CD_M) THEN IF " +
          up + " THEN CV := CV + 1; ELSIF " + down +
          " THEN CV := CV - 1; END_IF; END_IF; CU_M := CU; CD_M := CD; "
          "QU := CV >= PV; QD := CV <= 0;",
      {{"CU_M", "BOOL"}, {"CD_M", "BOOL"}});
}

/// OUT_ANY_CONSOLE, FB_TON/TOF/TP and the test utilities: service FBs of
/// 4diac's library whose behaviour is the runtime's (a console, the
/// runtime's clock, a test harness).
std::optional<TypeSpec> serviceBlock(StringRef name) {
  std::string n = name.upper();
  if (n == "OUT_ANY_CONSOLE") {
    TypeSpec t;
    t.inputs = {{"QI", "BOOL"}, {"LABEL", "STRING"}, {"IN", "ANY"}};
    t.outputs = {{"QO", "BOOL"}};
    t.eventInputs.push_back({"REQ", {"QI", "LABEL", "IN"}});
    t.eventOutputs.push_back({"CNF", {"QO"}});
    return t;
  }
  // 4diac's test utilities: TEST_CONDITION reports its `check` (the
  // expectation a user proves with `check`, docs/iec61499.md), STEST_END
  // ends a test run; APPEND_STRING_n formats values for a log.
  if (n == "TEST_CONDITION")
    return TypeSpec::request({{"check", "BOOL"}}, {});
  if (n == "STEST_END") {
    TypeSpec t;
    t.eventInputs.push_back({"REQ", {}});
    return t;
  }
  if (auto count = countAfter(n, "APPEND_STRING_"); count && *count >= 2) {
    TypeSpec t = TypeSpec::request({}, {{"OUT", "STRING"}});
    numbered(t.inputs, t.eventInputs[0].with, "IN_", *count);
    return t;
  }
  // CSV_WRITER_n writes SD_1..SD_n as a line of file FILE_NAME.
  if (auto count = countAfter(n, "CSV_WRITER_"); count && *count >= 1) {
    TypeSpec t = initialised("FILE_NAME", "STRING");
    t.eventInputs.push_back({"REQ", {"QI"}});
    numbered(t.inputs, t.eventInputs[1].with, "SD_", *count);
    t.eventOutputs.push_back({"CNF", {"QO", "STATUS"}});
    return t;
  }
  if (n == "FB_TON" || n == "FB_TOF" || n == "FB_TP")
    return TypeSpec::request({{"IN", "BOOL"}, {"PT", "TIME"}},
                             {{"Q", "BOOL"}, {"ET", "TIME"}});
  return std::nullopt;
}

std::string xmlOf(StringRef name, const TypeSpec &t) {
  std::string x = "<FBType Name=\"" + name.str() +
                  "\" Comment=\"netlift: 4diac standard library type known "
                  "by name\">\n<InterfaceList>\n" +
                  interfaceListContents(t) + "</InterfaceList>\n";
  if (!t.requestBody.empty()) {
    x += "<SimpleFB>";
    if (!t.internals.empty())
      x += varListXml("InternalVars", t.internals);
    x += "<Algorithm Name=\"REQ\"><ST Text=\"" + xmlEscape(t.requestBody) +
         "\"/></Algorithm></SimpleFB>\n";
  }
  return x + "</FBType>\n";
}

} // namespace

std::optional<TypedFunction>
netlift::iec61499::detail::typedFunction(StringRef name) {
  std::string n = name.upper();
  StringRef s = n;
  if (!s.consume_front("F_"))
    return std::nullopt;
  // IEC 61131-3 table 30: the date and time arithmetic 4diac has.
  static const char *const kDateAndTime[][4] = {
      {"ADD_DT_TIME", "DATE_AND_TIME", "TIME", "DATE_AND_TIME"},
      {"ADD_TOD_TIME", "TIME_OF_DAY", "TIME", "TIME_OF_DAY"},
      {"SUB_DATE_DATE", "DATE", "DATE", "TIME"},
      {"SUB_DT_DT", "DATE_AND_TIME", "DATE_AND_TIME", "TIME"},
      {"SUB_DT_TIME", "DATE_AND_TIME", "TIME", "DATE_AND_TIME"},
      {"SUB_TOD_TIME", "TIME_OF_DAY", "TIME", "TIME_OF_DAY"},
      {"SUB_TOD_TOD", "TIME_OF_DAY", "TIME_OF_DAY", "TIME"},
      {"CONCAT_DATE_TOD", "DATE", "TIME_OF_DAY", "DATE_AND_TIME"}};
  for (const auto &f : kDateAndTime)
    if (s == f[0])
      return TypedFunction{{{"IN1", f[1]}, {"IN2", f[2]}}, {"OUT", f[3]}};
  // BCD digits in a bit string, and back (table 23); not 64-bit ones,
  // which the ST frontend refuses (4diac's files keep them environment).
  static const char *const kBcd[][2] = {
      {"BYTE", "USINT"}, {"WORD", "UINT"}, {"DWORD", "UDINT"}};
  for (const auto &[bits, number] : kBcd) {
    if (s == (Twine(bits) + "_BCD_TO_" + number).str())
      return TypedFunction{{{"IN", bits}}, {"OUT", number}};
    if (s == (Twine(number) + "_TO_BCD_" + bits).str())
      return TypedFunction{{{"IN", number}}, {"OUT", bits}};
  }
  // A duration as a count of a unit (4diac's F_TIME_IN_MS_TO_LINT...).
  if (s.consume_front("TIME_IN_")) {
    auto [unit, type] = s.split("_TO_");
    if (llvm::is_contained(
            std::initializer_list<StringRef>{"NS", "US", "MS", "S"}, unit) &&
        llvm::is_contained(
            std::initializer_list<StringRef>{"LINT", "ULINT", "LREAL"}, type))
      return TypedFunction{{{"IN", "TIME"}}, {"OUT", type.str()}};
  }
  return std::nullopt;
}

std::optional<std::string>
netlift::iec61499::detail::standardTypeXml(StringRef name) {
  for (auto family : {genericFunction, conversion, typedFunctionBlock,
                      communication, processImage, standardBlock, serviceBlock})
    if (std::optional<TypeSpec> t = family(name))
      return xmlOf(name, *t);
  return std::nullopt;
}
