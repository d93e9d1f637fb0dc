//===- Iec61499Resources.cpp - IEC 61499 resources as one flat module -----===//
//
// `iec61499-resources`: the last step of translating IEC 61499 under the
// forte and cyclic execution models (docs/iec61499.md). Each module named
// by `modules=` (a translated type or an application: one resource) is
// flattened into one module of the same name, whose events are then put in
// FORTE's order (one FIFO per resource, ForteOrder.h) or fb2smv's (blocks
// taking turns, CyclicOrder.h); the modules named by `built=` (the blocks
// the frontend built them from) are removed. The IEC 61499 frontend asks
// for this pass (FrontendContext::pipelines); it runs after every input is
// read, so the frontend itself builds modules only.
//
//===----------------------------------------------------------------------===//
#include "passes/CyclicOrder.h"
#include "passes/Flatten.h"
#include "passes/ForteOrder.h"
#include "passes/Pass.h"

#include "ir/net/Verifier.h"

#include <algorithm>

using namespace netlift;

namespace {

class Iec61499ResourcesPass : public Pass {
public:
  explicit Iec61499ResourcesPass(const PassOptions &opts) : opts(opts) {}
  bool run(net::Design &d, DiagEngine &diag, Statistics &stats) override {
    std::string model = opts.text("model", "forte");
    // flatten reads resolved names: verify first.
    if (!net::verifyDesign(d, diag))
      return false;
    std::vector<net::Module *> flats;
    for (const std::string &r : opts.list("modules")) {
      net::Module *top = d.lookupModule(r);
      if (!top)
        continue;
      net::Module *flat = flattenModule(d, top, diag);
      if (!flat)
        return false;
      flats.push_back(flat);
    }
    for (const std::string &name : opts.list("built"))
      if (net::Module *m = d.lookupModule(name))
        if (std::find(flats.begin(), flats.end(), m) == flats.end())
          d.eraseModule(m);
    for (net::Module *flat : flats) {
      llvm::StringRef name = llvm::StringRef(flat->name)
                                 .drop_back(llvm::StringRef(".flat").size());
      d.renameModule(flat, d.save(name));
      if (model == "forte" ? !iec61499::orderLikeForte(d, *flat, diag)
                           : !iec61499::orderCyclically(d, *flat, diag))
        return false;
    }
    stats.add("iec61499-resources", "resources", flats.size(),
              "resources made one flat module");
    return true;
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createIec61499ResourcesPass(const PassOptions &opts) {
  return std::make_unique<Iec61499ResourcesPass>(opts);
}
} // namespace netlift
