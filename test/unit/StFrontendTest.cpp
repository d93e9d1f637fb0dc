//===- StFrontendTest.cpp - ST literals and the PLC model
//------------------===//
#include "frontends/st/StFrontend.h"
#include "frontends/plc/Sema.h"
#include "frontends/st/StdLib.h"

#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

using namespace netlift;

namespace {

TEST(StLiterals, Durations) {
  int64_t ns;
  std::string err;
  ASSERT_TRUE(st::parseDuration("T#1h2m3s4ms5us6ns", ns, err)) << err;
  EXPECT_EQ(ns, 3723004005006);
  ASSERT_TRUE(st::parseDuration("TIME#1.5s", ns, err));
  EXPECT_EQ(ns, 1500000000);
  ASSERT_TRUE(st::parseDuration("t#-250ms", ns, err));
  EXPECT_EQ(ns, -250000000);
  ASSERT_TRUE(st::parseDuration("T#1d_2h", ns, err));
  EXPECT_EQ(ns, 93600000000000);
  // `m` is minutes, `ms` milliseconds.
  ASSERT_TRUE(st::parseDuration("T#2m", ns, err));
  EXPECT_EQ(ns, 120000000000);
  EXPECT_FALSE(st::parseDuration("T#5x", ns, err));
  EXPECT_NE(err.find("unknown unit"), std::string::npos);
  EXPECT_FALSE(st::parseDuration("T#1s2h", ns, err));
  EXPECT_NE(err.find("out of order"), std::string::npos);
  EXPECT_FALSE(st::parseDuration("T#0.5ns", ns, err));
}

TEST(StLiterals, Integers) {
  int64_t v;
  EXPECT_TRUE(st::parseIntegerLiteral("1_000", v));
  EXPECT_EQ(v, 1000);
  EXPECT_TRUE(st::parseIntegerLiteral("16#FF", v));
  EXPECT_EQ(v, 255);
  EXPECT_TRUE(st::parseIntegerLiteral("2#1010_1010", v));
  EXPECT_EQ(v, 170);
  EXPECT_TRUE(st::parseIntegerLiteral("8#17", v));
  EXPECT_EQ(v, 15);
  EXPECT_FALSE(st::parseIntegerLiteral("8#9", v));
  EXPECT_FALSE(st::parseIntegerLiteral("3#1", v));
  EXPECT_FALSE(st::parseIntegerLiteral("99999999999999999999", v));
}

/// Parses and checks `text`; returns the number of errors.
unsigned check(const char *text, plc::Unit &unit) {
  llvm::SourceMgr sm;
  sm.setDiagHandler([](const llvm::SMDiagnostic &, void *) {});
  DiagEngine diag(sm);
  unsigned id =
      sm.AddNewSourceBuffer(llvm::MemoryBuffer::getMemBufferCopy(text), {});
  if (!st::parseStructuredText(sm.getMemoryBuffer(id)->getBuffer(), diag, unit))
    return diag.numErrors();
  plc::checkUnit(unit, diag);
  return diag.numErrors();
}

TEST(PlcModel, NamesAreCaseInsensitiveAndTyped) {
  plc::Unit unit;
  ASSERT_EQ(check("PROGRAM p VAR Speed : INT(0..10); END_VAR "
                  "speed := SPEED + 1; END_PROGRAM",
                  unit),
            0u);
  plc::Pou *p = unit.findPou("P");
  ASSERT_NE(p, nullptr);
  plc::VarDecl *v = p->find("SPEED");
  ASSERT_NE(v, nullptr);
  ASSERT_NE(v->type, nullptr);
  EXPECT_TRUE(v->type->isSubrange);
  EXPECT_EQ(v->type->lo, 0);
  EXPECT_EQ(v->type->hi, 10);
  // The assignment's target resolved to the declaration.
  ASSERT_EQ(p->body.size(), 1u);
  EXPECT_EQ(p->body[0]->target->var, v);
}

TEST(PlcModel, OperatorPrecedence) {
  // NOT binds tighter than AND, comparison tighter than AND, * than +.
  plc::Unit unit;
  ASSERT_EQ(check("PROGRAM p VAR a, b : BOOL; i : INT; END_VAR "
                  "a := NOT a AND i + 2 * 3 > 4 OR b; END_PROGRAM",
                  unit),
            0u);
  plc::Expr *e = unit.findPou("p")->body[0]->value;
  ASSERT_EQ(e->kind, plc::ExprKind::Binary);
  EXPECT_EQ(e->op, plc::Op::Or);
  plc::Expr *conj = e->operands[0];
  EXPECT_EQ(conj->op, plc::Op::And);
  EXPECT_EQ(conj->operands[0]->op, plc::Op::Not);
  plc::Expr *cmp = conj->operands[1];
  EXPECT_EQ(cmp->op, plc::Op::Gt);
  EXPECT_EQ(cmp->operands[0]->op, plc::Op::Add);
  EXPECT_EQ(cmp->operands[0]->operands[1]->op, plc::Op::Mul);
}

TEST(StdLib, EveryShippedBlockIsKnownByName) {
  // The IL frontend asks isStandardFunctionBlock before the library joins
  // the unit: the list must name exactly the shipped blocks.
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  plc::Unit unit;
  ASSERT_TRUE(st::addStandardLibrary(diag, unit));
  size_t blocks = 0;
  for (plc::Pou *p : unit.pous) {
    EXPECT_TRUE(p->isLibrary);
    // The rest are the standard functions on dates and times.
    EXPECT_EQ(st::isStandardFunctionBlock(p->name),
              p->kind == plc::PouKind::FunctionBlock)
        << p->name;
    blocks += p->kind == plc::PouKind::FunctionBlock;
  }
  // 10 of IEC's, Annex F's 6 (matiec's additional blocks), 2 SFC steps.
  EXPECT_EQ(blocks, 18u);
  EXPECT_FALSE(st::isStandardFunctionBlock("MyBlock"));
}

} // namespace
