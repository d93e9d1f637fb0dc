//===- FlattenTest.cpp - the flatten pass ---------------------------------===//
#include "ir/net/Parser.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"
#include "passes/Pass.h"

#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

using namespace netlift;
using namespace netlift::net;

namespace {

TEST(Flatten, NestedHierarchyWithEventMerging) {
  const char *src = R"(
module Src { event output e; place p(1); trans fire : p -> p emit e; }
module Sink { event input e; place q(1); trans take : q -> q on e; }
module Pair {
  event output done;
  inst a : Src; inst b : Src; inst s : Sink;
  connect a.e -> s.e; connect b.e -> s.e; connect a.e -> done;
}
system Top { inst x : Pair; inst y : Sink; connect x.done -> y.e; }
)";
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  unsigned id = sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(src, "t.net"), llvm::SMLoc());
  Design d;
  ASSERT_TRUE(parseNetIR(id, diag, d) && verifyDesign(d, diag));
  PassManager pm;
  ASSERT_TRUE(pm.parsePipeline("flatten", diag));
  ASSERT_TRUE(pm.run(d, diag));
  ASSERT_TRUE(verifyDesign(d, diag));
  ASSERT_EQ(d.modules.size(), 1u);
  const Module &m = *d.modules[0];
  EXPECT_EQ(m.name, "Top");
  auto trans = [&](llvm::StringRef n) -> const Transition & {
    Symbol s = m.lookup(n);
    EXPECT_EQ(s.kind, SymKind::Transition) << n.str();
    return m.transitions[s.index];
  };
  // Two drivers merge into one input: both become event sources.
  const Transition &take = trans("x.s.take");
  ASSERT_EQ(take.events().size(), 2u);
  EXPECT_EQ(m.transitions[take.events()[0].index].name, "x.a.fire");
  EXPECT_EQ(m.transitions[take.events()[1].index].name, "x.b.fire");
  // The pass-through output x.done is emitted by x.a.fire.
  const Transition &ytake = trans("y.take");
  ASSERT_EQ(ytake.events().size(), 1u);
  EXPECT_EQ(m.transitions[ytake.events()[0].index].name, "x.a.fire");
  EXPECT_EQ(pm.stats.empty(), false);
}

} // namespace
