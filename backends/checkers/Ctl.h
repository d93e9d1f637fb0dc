//===- Ctl.h - CTL properties and their explicit-state checking -*- C++ -*-===//
//
// The property language of `netlift check` (docs/check.md): CTL over atomic
// propositions that are NetIR Boolean expressions of the flat module
// (`p.home`, `c.step == 2`, `not c.valve`), with `!`/`not`, `&`/`and`,
// `|`/`or`, `->`, `true`, `false`, `deadlock`, and the temporal operators
// AX EX AF EF AG EG A[f U g] E[f U g]. Formulas are checked on an explored
// state space by the textbook fixpoints, each linear in the graph: EX and
// E[U] backwards over predecessors, EG as a greatest fixpoint with
// successor counters, the A-forms by duality. Paths end nowhere: a
// deadlocked state is taken to stay where it is forever (a self-loop), as
// most CTL checkers do for finite runs.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_CTL_H
#define NETLIFT_BACKENDS_CHECKERS_CTL_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace netlift::checkers {

struct CtlFormula {
  enum Kind {
    True,
    False,
    Atom,
    Deadlock,
    Not,
    And,
    Or,
    Implies,
    EX,
    AX,
    EF,
    AF,
    EG,
    AG,
    EU,
    AU
  } kind;
  std::unique_ptr<CtlFormula> lhs, rhs; // operands (rhs of binary, U)
  net::Expr *atom = nullptr;
  std::string atomText;
};

/// Parses the formula in buffer `bufferID`; atoms are parsed and checked
/// as NetIR predicates of `top` (errors point into the formula). Null
/// after reporting an error.
std::unique_ptr<CtlFormula> parseCtl(unsigned bufferID, DiagEngine &diag,
                                     net::Design &design, net::Module &top);

/// The formula written back in the canonical syntax.
std::string ctlToString(const CtlFormula &f);

/// A state graph: successors of each state (deadlocks without any), the
/// deadlocked states, and the atoms' truth per state.
struct CtlGraph {
  std::vector<uint32_t> succStart, succ; // CSR
  std::vector<uint8_t> deadlock;
  size_t size() const { return deadlock.size(); }
};

/// The states satisfying `f`; `atomValue(atom, state)` evaluates an atom.
std::vector<uint8_t>
evaluateCtl(const CtlFormula &f, const CtlGraph &g,
            const std::function<bool(const net::Expr *, uint32_t)> &atomValue);

} // namespace netlift::checkers

#endif
