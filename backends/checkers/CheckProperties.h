//===- CheckProperties.h - CTL properties on an explored model --*- C++ -*-===//
//
// `netlift check`: parses the properties over the set-up's flat top,
// explores its state space, turns the explored graph into the CSR form the
// CTL evaluator reads, and prints each property's verdict with its
// witness or counterexample (and writes them as trace files when asked).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_CHECKPROPERTIES_H
#define NETLIFT_BACKENDS_CHECKERS_CHECKPROPERTIES_H

#include "backends/checkers/Ctl.h"
#include "engine/ExplorationSetup.h"

#include "llvm/Support/raw_ostream.h"

#include <memory>
#include <string>
#include <vector>

namespace netlift::checkers {

/// Parses each property text over `top` (each its own buffer `<ctl N>`, so
/// errors point into it); false after reporting.
bool parseProperties(llvm::ArrayRef<std::string> texts, net::Design &design,
                     net::Module &top, DiagEngine &diag,
                     std::vector<std::unique_ptr<CtlFormula>> &out);

/// Explores and checks; verdicts and traces go to `out`, and with a
/// non-empty `traceDir` each property's trace to `traceDir/p<N>.json|.aut`.
/// Exit code: 0 all hold, 3 some fail, 2 a limit stopped the exploration
/// (undecided), 1 an error (reported). With abstract timers, each
/// counterexample is replayed in exact time; the clocks involved in the
/// spurious ones are added to `spuriousClocks` (exit code 3 then means
/// "refine").
int checkProperties(engine::ExplorationSetup &setup,
                    llvm::ArrayRef<std::unique_ptr<CtlFormula>> formulas,
                    const std::string &traceDir, llvm::raw_ostream &out,
                    DiagEngine &diag,
                    std::vector<std::string> *spuriousClocks = nullptr);

/// `AG p` with p free of temporal operators: what --timers=abstract
/// decides.
bool isInvariant(const CtlFormula &f);

} // namespace netlift::checkers

#endif
