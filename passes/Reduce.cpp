//===- Reduce.cpp - every reduction to a fixpoint -------------------------===//
//
// `reduce` runs reduce-consts, reduce-dead, reduce-ranges and reduce-clocks
// (and reduce-coi and reduce-chains when `observe=` is given: both keep only
// what is observed) in turn until a round changes
// nothing (at most 10 rounds): folding a constant guard to `false` lets
// reduce-dead remove the transition, whose removal may leave a variable
// unread, and so on. Each pass's counters add up in --stats; `report=`
// writes the module's size before and after.
//
// Preserved: what each pass preserves (docs/passes.md); with `observe=`,
// what reduce-coi and reduce-chains preserve.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Printer.h"

#include "llvm/Support/FormatVariadic.h"

using namespace netlift;
using namespace netlift::net;

namespace {

struct Size {
  size_t places, transitions, vars;
};
Size sizeOf(const Module &m) {
  return {m.places.size(), m.transitions.size(), m.vars.size()};
}

class ReducePass : public Pass {
public:
  explicit ReducePass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce");
    if (!m)
      return false;
    ReportStream report;
    if (!report.open(opts, "reduce", diag))
      return false;
    PassOptions sub;
    if (opts.has("top"))
      sub.set("top", opts.text("top"));
    std::vector<std::unique_ptr<Pass>> passes;
    for (const char *name :
         {"reduce-coi", "reduce-consts", "reduce-dead", "reduce-ranges",
          "reduce-clocks", "reduce-chains"}) {
      PassOptions o = sub;
      if (llvm::StringRef(name) == "reduce-coi" ||
          llvm::StringRef(name) == "reduce-chains") {
        if (!opts.has("observe"))
          continue;
        o.set("observe", opts.text("observe"));
      }
      passes.push_back(lookupPass(name)->create(o));
    }
    Size before = sizeOf(*m);
    std::string last;
    unsigned rounds = 0;
    while (rounds < 10) {
      ++rounds;
      for (auto &p : passes)
        if (!p->run(d, diag, stats))
          return false;
      std::string text;
      llvm::raw_string_ostream os(text);
      printDesign(d, os);
      os.flush();
      if (text == last)
        break;
      last = std::move(text);
    }
    m = reduce::flatTop(d, diag, opts, "reduce");
    Size after = sizeOf(*m);
    stats.add("reduce", "rounds", rounds, "rounds until nothing changed");
    if (auto *os = report.get())
      *os << llvm::formatv("reduce: {0}: places {1} -> {2}, transitions {3} "
                           "-> {4}, variables {5} -> {6} ({7} rounds)\n",
                           m->name, before.places, after.places,
                           before.transitions, after.transitions, before.vars,
                           after.vars, rounds);
    return true;
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReducePass(const PassOptions &opts) {
  return std::make_unique<ReducePass>(opts);
}
} // namespace netlift
