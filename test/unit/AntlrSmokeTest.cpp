//===- AntlrSmokeTest.cpp - ANTLR 4.7.2 tool + 4.9 runtime ----------------===//
#include "SmokeBaseVisitor.h"
#include "SmokeLexer.h"
#include "SmokeParser.h"

#include "antlr4-runtime.h"

#include <gtest/gtest.h>

namespace {

/// Evaluates the parse tree, so the test checks structure, not just "it
/// parsed".
class Eval : public SmokeBaseVisitor {
public:
  antlrcpp::Any visitSum(SmokeParser::SumContext *ctx) override {
    return fold(ctx->product(), ctx->children);
  }
  antlrcpp::Any visitSumInner(SmokeParser::SumInnerContext *ctx) override {
    return fold(ctx->product(), ctx->children);
  }
  antlrcpp::Any visitProduct(SmokeParser::ProductContext *ctx) override {
    long v = visit(ctx->atom(0)).as<long>();
    for (size_t i = 1; i < ctx->atom().size(); ++i) {
      long r = visit(ctx->atom(i)).as<long>();
      std::string op = ctx->children[2 * i - 1]->getText();
      v = op == "*" ? v * r : v / r;
    }
    return v;
  }
  antlrcpp::Any visitAtom(SmokeParser::AtomContext *ctx) override {
    if (ctx->INT())
      return std::stol(ctx->INT()->getText());
    return visit(ctx->sumInner());
  }

private:
  template <typename P>
  antlrcpp::Any fold(const std::vector<P *> &ps,
                     const std::vector<antlr4::tree::ParseTree *> &kids) {
    long v = visit(ps[0]).template as<long>();
    for (size_t i = 1; i < ps.size(); ++i) {
      long r = visit(ps[i]).template as<long>();
      v = kids[2 * i - 1]->getText() == "+" ? v + r : v - r;
    }
    return v;
  }
};

long evaluate(const std::string &text, size_t &syntaxErrors) {
  antlr4::ANTLRInputStream input(text);
  SmokeLexer lexer(&input);
  antlr4::CommonTokenStream tokens(&lexer);
  SmokeParser parser(&tokens);
  parser.removeErrorListeners();
  auto *tree = parser.sum();
  syntaxErrors = parser.getNumberOfSyntaxErrors();
  if (syntaxErrors)
    return 0;
  Eval e;
  return e.visit(tree).as<long>();
}

TEST(AntlrSmoke, GeneratedParserEvaluatesWithPrecedence) {
  size_t errors;
  EXPECT_EQ(evaluate("1 + 2 * 3", errors), 7);
  EXPECT_EQ(errors, 0u);
  EXPECT_EQ(evaluate("(1 + 2) * 3 - 4 / 2", errors), 7);
  EXPECT_EQ(errors, 0u);
}

TEST(AntlrSmoke, SyntaxErrorsAreCounted) {
  size_t errors;
  evaluate("1 + * 3", errors);
  EXPECT_GT(errors, 0u);
}

} // namespace
