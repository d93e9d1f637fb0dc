//===- ReduceClocks.cpp - smallest caps for clock variables ---------------===//
//
// `reduce-clocks` lowers the cap of a clock variable to one past the
// largest constant it is compared with or set to, when comparisons with
// constants (`t1 >= 5`, `3 < t1`) and constant assignments (`t1 := 0`) are
// all that is done with it: above that value no comparison tells two
// readings apart, so saturating earlier merges only states nothing can
// distinguish. An initial value above the new cap becomes the cap. A clock
// read in any other way (arithmetic, a data output) keeps its cap.
//
// Place clocks need no pass: the semantics already saturates each at one
// past the largest finite bound of the arcs leaving its place
// (docs/semantics.md).
//
// Preserved: every step and every observation other than the clock's own
// value; the state space shrinks by the clock readings merged.
//
//===----------------------------------------------------------------------===//
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"

using namespace netlift;
using namespace netlift::net;
using llvm::dyn_cast;

namespace {

class ReduceClocksPass : public Pass {
public:
  explicit ReduceClocksPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "reduce-clocks");
    if (!m)
      return false;
    size_t nv = m->vars.size();
    // Largest constant each clock meets; -1 once it is used otherwise.
    std::vector<int64_t> bound(nv, 0);
    std::vector<bool> usable(nv, true);
    std::vector<const Expr *> compared; // Refs seen inside a comparison
    auto isClockRef = [&](const Expr *e) -> int {
      auto *r = dyn_cast<Ref>(e);
      return r && r->sym.kind == SymKind::Var &&
                     m->vars[r->sym.index].type->isClock()
                 ? int(r->sym.index)
                 : -1;
    };
    net::forEachRead(*m, [&](const Expr *root, int) {
      net::walkExpr(root, [&](const Expr *e) {
        auto *b = dyn_cast<BinaryExpr>(e);
        if (!b || b->op < BinaryOp::Eq || b->op > BinaryOp::Ge)
          return;
        int64_t k;
        int c = isClockRef(b->lhs);
        if (c >= 0 && evalConstInt(b->rhs, k)) {
          bound[c] = std::max(bound[c], k);
          compared.push_back(b->lhs);
        }
        c = isClockRef(b->rhs);
        if (c >= 0 && evalConstInt(b->lhs, k)) {
          bound[c] = std::max(bound[c], k);
          compared.push_back(b->rhs);
        }
      });
    });
    // Any other read disqualifies.
    net::forEachRead(*m, [&](const Expr *root, int) {
      net::walkExpr(root, [&](const Expr *e) {
        int c = isClockRef(e);
        if (c >= 0 &&
            std::find(compared.begin(), compared.end(), e) == compared.end())
          usable[c] = false;
      });
    });
    net::forEachAssign(*m, [&](const AssignStmt *a, int) {
      Symbol s = net::targetRoot(a->target);
      if (s.kind != SymKind::Var || !m->vars[s.index].type->isClock())
        return;
      int64_t k;
      if (evalConstInt(a->value, k))
        bound[s.index] = std::max(bound[s.index], k);
      else
        usable[s.index] = false;
    });
    unsigned lowered = 0;
    uint64_t saved = 0;
    Builder b(d);
    b.setModule(m);
    for (uint32_t v = 0; v < nv; ++v) {
      Var &var = m->vars[v];
      if (!var.type->isClock() || !usable[v] || bound[v] + 1 >= var.type->hi)
        continue;
      int64_t cap = bound[v] + 1;
      saved += uint64_t(var.type->hi - cap);
      var.type = d.types.getClock(cap);
      int64_t init;
      if (var.init && evalConstInt(var.init, init) && init > cap)
        var.init = b.intLit(cap, var.init->loc);
      ++lowered;
    }
    stats.add("reduce-clocks", "clocks", lowered,
              "clock variables capped lower");
    stats.add("reduce-clocks", "readings", saved,
              "clock readings merged (sum of cap reductions)");
    return !lowered || reduce::reverify(d, diag, "reduce-clocks");
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createReduceClocksPass(const PassOptions &opts) {
  return std::make_unique<ReduceClocksPass>(opts);
}
} // namespace netlift
