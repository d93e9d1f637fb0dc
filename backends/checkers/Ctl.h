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
#include <optional>
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
  /// Where the property starts (set on the whole formula by parseCtl).
  llvm::SMLoc loc;
};

/// Parses the formula in buffer `bufferID`; atoms are parsed and checked
/// as NetIR predicates of `top` (errors point into the formula). Null
/// after reporting an error.
std::unique_ptr<CtlFormula> parseCtl(unsigned bufferID, DiagEngine &diag,
                                     net::Design &design, net::Module &top);

/// The formula written back in the canonical syntax.
std::string ctlToString(const CtlFormula &f);

/// Is `f` a formula of the state alone: no temporal operator, and no
/// `deadlock` unless `deadlockIsState` (an export that can write it as a
/// state predicate)?
bool isStateProposition(const CtlFormula &f, bool deadlockIsState);

/// A state graph: successors of each state (deadlocks without any), the
/// deadlocked states, and the atoms' truth per state.
struct CtlGraph {
  std::vector<uint32_t> succStart, succ; // CSR
  std::vector<uint32_t> succLabel;       // per edge, for traces
  std::vector<uint8_t> deadlock;
  size_t size() const { return deadlock.size(); }
};

/// The states satisfying `f`; `atomValue(atom, state)` evaluates an atom.
std::vector<uint8_t>
evaluateCtl(const CtlFormula &f, const CtlGraph &g,
            const std::function<bool(const net::Expr *, uint32_t)> &atomValue);

/// A path from the initial state (0) that shows a verdict: a witness of a
/// holding existential property, a counterexample to a failing universal
/// one. `loopTo` >= 0: the last state has an edge back to
/// `states[loopTo]` (a lasso, the run goes round forever); a path that ends
/// in a deadlock stays there.
struct CtlTrace {
  bool witness = false; // else a counterexample
  std::string claim;    // what the path shows, in words
  std::vector<uint32_t> states;
  int64_t loopTo = -1;
};

/// The trace of `f`'s verdict at the initial state, where one exists: EX,
/// EF (shortest), EG and E[U] (shortest to the goal) when they hold; AX,
/// AG (shortest), AF and A[U] when they fail. Other verdicts and
/// operators (Boolean combinations at the top) have none.
std::optional<CtlTrace>
ctlTrace(const CtlFormula &f, const CtlGraph &g,
         const std::function<bool(const net::Expr *, uint32_t)> &atomValue);

} // namespace netlift::checkers

#endif
