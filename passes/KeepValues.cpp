//===- KeepValues.cpp - observed PLC memory kept past the scan ------------===//
#include "passes/KeepValues.h"

#include "ir/net/Builder.h"
#include "ir/net/ScanResets.h"
#include "ir/net/Walk.h"
#include "passes/Pass.h"
#include "passes/ReduceSupport.h"

#include "llvm/ADT/StringSet.h"

using namespace netlift;
using namespace netlift::net;

bool netlift::keepValues(Design &d, Module &m,
                         const std::vector<std::string> &names,
                         DiagEngine &diag, bool lenient) {
  if (names.empty())
    return true;
  llvm::StringSet<> kept;
  for (const std::string &n : names) {
    bool any = false;
    for (const Var &v : m.vars)
      if (isNameInScope(v.name, n)) {
        kept.insert(v.name);
        any = true;
      }
    if (!any && !lenient) {
      diag.error(llvm::SMLoc(), "keep-values: '" + n +
                                    "' is no variable of module '" + m.name +
                                    "' (nor a scope of variables)");
      return false;
    }
  }
  llvm::DenseSet<const Stmt *> resets = scanResetStatements(
      m, [&](uint32_t v) { return kept.count(m.vars[v].name) != 0; });
  if (resets.empty())
    return true;
  Builder b(d);
  b.setModule(&m);
  for (uint32_t t = 0; t < m.transitions.size(); ++t)
    if (m.transitions[t].hasAction())
      b.setAction(t, dropAssignments(b, m.transitions[t].action(),
                                     [&](const AssignStmt *a) {
                                       return !resets.count(a);
                                     }));
  llvm::erase_if(m.attributes, [&](const Attribute &a) {
    return a.key == kScanResetAttribute && kept.count(a.target);
  });
  return reduce::reverify(d, diag, "keep-values");
}

namespace {

class KeepValuesPass : public Pass {
public:
  explicit KeepValuesPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "keep-values");
    if (!m)
      return false;
    std::vector<std::string> names = opts.list("names");
    size_t before = scanResetVars(*m).size();
    if (!keepValues(d, *m, names, diag))
      return false;
    stats.add("keep-values", "kept", before - scanResetVars(*m).size(),
              "variables kept past the end of the scan");
    return true;
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createKeepValuesPass(const PassOptions &opts) {
  return std::make_unique<KeepValuesPass>(opts);
}
} // namespace netlift
