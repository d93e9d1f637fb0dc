//===- NetIRTest.cpp - NetIR core unit tests ------------------------------===//
#include "ir/net/Builder.h"
#include "ir/net/Parser.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"

#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

using namespace netlift;
using namespace netlift::net;

namespace {

/// Parses and verifies `text`; returns whether both succeeded.
bool parse(const std::string &text, Design &d, std::string *errs = nullptr) {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  unsigned id = sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, "t.net"), llvm::SMLoc());
  // Capture diagnostics instead of printing them.
  std::string captured;
  sm.setDiagHandler(
      [](const llvm::SMDiagnostic &dg, void *ctx) {
        *static_cast<std::string *>(ctx) += dg.getMessage().str() + "\n";
      },
      &captured);
  bool ok = parseNetIR(id, diag, d) && verifyDesign(d, diag);
  if (errs)
    *errs = captured;
  return ok;
}

std::string print(const Design &d) {
  std::string s;
  llvm::raw_string_ostream os(s);
  printDesign(d, os);
  return os.str();
}

TEST(NetIR, BuilderModuleVerifiesAndPrints) {
  Design d;
  Builder b(d);
  b.createModule("M");
  b.addPort("go", PortKind::Event, PortDir::In);
  uint32_t out = b.addPort("busy", PortKind::Cond, PortDir::Out);
  uint32_t idle = b.addPlace("idle", 1);
  uint32_t busy = b.addPlace("busy_p");
  uint32_t n = b.addVar("n", d.types.getInt(8, false, Overflow::Wrap));
  (void)n;
  uint32_t t =
      b.addTransition("start", {PreArc{idle, 1, {2, 4}}}, {PostArc{busy, 1}});
  b.setEvents(t, {EventSource{0, true}});
  b.setAction(t, {b.assign(b.ref("n"),
                           b.binary(BinaryOp::Add, b.ref("n"), b.intLit(1)))});
  b.getModule()->ports[out].definition = b.ref("busy_p");
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  ASSERT_TRUE(verifyDesign(d, diag));
  EXPECT_EQ(print(d), "module M {\n"
                      "  event input go;\n"
                      "  cond output busy = busy_p;\n"
                      "  var n : uint8 wrap;\n"
                      "  place idle(1);\n"
                      "  place busy_p;\n"
                      "  trans start : idle[2,4] -> busy_p on go {\n"
                      "    n := n + 1;\n"
                      "  }\n"
                      "}\n");
}

TEST(NetIR, PrintParsePrintIsAFixedPoint) {
  const char *src = R"(
timescale 5ms;
type Mode = enum { off, slow, fast };
type Pt = struct { x : 0..3; y : bool; };
module M {
  data input level : 0..10;
  data output mode : Mode init Mode#off;
  var a : array[0..2] of Pt;
  var k : int16 error = -3;
  real pos : [0.0, 100.5] = 0.25;
  place p(2) cap 3, q cap inf;
  trans t : 2*p[1,inf] -> q guard (level + 1) * 2 > 3 and not (k == 1) {
    case mode { off, slow { mode := fast; } else { mode := off; } }
    for i in 0..2 { a[i].x := i; }
    k := level > 5 ? -k : min(k, 3) % 2;
  }
  flow q { pos' = 1.5; }
}
)";
  Design d;
  std::string errs;
  ASSERT_TRUE(parse(src, d, &errs)) << errs;
  std::string once = print(d);
  Design d2;
  ASSERT_TRUE(parse(once, d2, &errs)) << errs << once;
  EXPECT_EQ(once, print(d2));
}

TEST(NetIR, PrecedenceIsPreserved) {
  Design d;
  std::string errs;
  ASSERT_TRUE(parse("module M { var a, b, c : 0..9; place p;\n"
                    "trans t : p -> p guard a - (b - c) == (a - b) - c; }",
                    d, &errs))
      << errs;
  const Transition &t = d.modules[0]->transitions[0];
  EXPECT_EQ(exprToString(t.guard()), "a - (b - c) == a - b - c");
}

TEST(NetIR, VerifierReportsEveryKindOfMistake) {
  struct Case {
    const char *text;
    const char *message;
  } cases[] = {
      {"module M { place p; trans t : p -> p guard x; }",
       "unknown name 'x' in module 'M'"},
      {"module M { place p(2); }",
       "initial marking of place 'p' (2) exceeds its capacity 1"},
      {"module M { var v : 0..3; place p; trans t : p -> p { v := true; } }",
       "cannot assign a value of type 'bool' to 'v' of type '0..3'"},
      {"module M { place p; trans t : p -> p on p; }",
       "event arc source 'p' is a place; an event arc comes from a "
       "transition or an event input"},
      {"module M { place p; trans a : p -> p on b; trans b : p -> p on a; }",
       "event cycle among forced transitions: a -> b -> a"},
      {"module A { inst b : B; } module B { inst a : A; }",
       "recursive instantiation: module 'A' contains itself through 'B.a'"},
      {"module A { cond output o = true; }\n"
       "module B { data input i : 0..1; }\n"
       "system S { inst a : A; inst b : B; connect a.o -> b.i; }",
       "cannot connect cond port 'a.o' to data port 'b.i'"},
  };
  for (const Case &c : cases) {
    Design d;
    std::string errs;
    EXPECT_FALSE(parse(c.text, d, &errs)) << c.text;
    EXPECT_NE(errs.find(c.message), std::string::npos)
        << "expected: " << c.message << "\ngot: " << errs;
  }
}

TEST(NetIR, TopSelection) {
  Design d;
  ASSERT_TRUE(parse("module A {} module B { inst a : A; }", d));
  std::string why;
  Module *top = d.findTop("", why);
  ASSERT_NE(top, nullptr) << why;
  EXPECT_EQ(top->name, "B");
  Design d2;
  ASSERT_TRUE(parse("module A {} module B {}", d2));
  EXPECT_EQ(d2.findTop("", why), nullptr);
  EXPECT_NE(why.find("several top-level modules"), std::string::npos);
}

TEST(NetIR, IntTypesHaveTheirRanges) {
  TypeTable t;
  const Type *i16 = t.getInt(16, true, Overflow::Wrap);
  EXPECT_EQ(i16->lo, -32768);
  EXPECT_EQ(i16->hi, 32767);
  EXPECT_EQ(i16, t.getInt(16, true, Overflow::Wrap));
  EXPECT_NE(i16, t.getInt(16, true, Overflow::Error));
  EXPECT_EQ(t.getInt(8, false, Overflow::Error)->hi, 255);
  EXPECT_EQ(t.getRange(0, 3), t.getRange(0, 3));
}

} // namespace
