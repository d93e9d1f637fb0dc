//===- Check.cpp - check: CTL properties on a state space -----------------===//
#include "backends/checkers/CheckProperties.h"
#include "tools/netlift/Driver.h"

using namespace netlift;
using namespace netlift::driver;

static cl::opt<std::string> checkInput(cl::Positional, cl::desc("<model>"),
                                       cl::Required, cl::sub(checkCommand()));
static cl::opt<std::string>
    traceDir("trace-dir",
             cl::desc("Also write each property's trace as DIR/p<N>.json and "
                      "DIR/p<N>.aut"),
             cl::value_desc("DIR"), cl::sub(checkCommand()),
             cl::cat(category()));

/// Exit 0 all hold, 3 some fail, 2 the exploration was stopped by a limit,
/// 1 an error (docs/check.md).
int driver::runCheck(DiagEngine &diag) {
  if (properties.empty()) {
    diag.error(llvm::SMLoc(), "check needs a property (--ctl FORMULA)");
    return 1;
  }
  net::Design design;
  std::vector<std::string> inputs{checkInput};
  statespace::ExplorationOptions xo;
  if (!loadModels(inputs, diag, design) || !explorationOptions(xo, diag))
    return 1;
  auto setup = statespace::ExplorationSetup::create(design, xo, diag, "check");
  std::vector<std::unique_ptr<checkers::CtlFormula>> formulas;
  if (!setup || !checkers::parseProperties(properties, design, setup->top(),
                                           diag, formulas))
    return 1;
  return checkers::checkProperties(*setup, formulas, traceDir, llvm::outs(),
                                   diag);
}
