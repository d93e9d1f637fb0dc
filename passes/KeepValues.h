//===- KeepValues.h - observed PLC memory kept past the scan -----*- C++
//-*-===//
//
// `keep-values` (docs/semantics.md, "Observers"): a PLC frontend resets the
// function-block members the program never reads at the end of each scan
// (`attr NAME scan_reset`), so states do not differ in them. A property,
// a --find expression or an sr attribute that names one observes it: the
// commands that explore keep the named variables' values for that run by
// removing their resets, so a verdict over `t.ET` is the one a PLC gives.
// The state space grows by what the kept values tell apart; nothing else
// changes.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_KEEPVALUES_H
#define NETLIFT_PASSES_KEEPVALUES_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <string>
#include <vector>

namespace netlift {

/// Removes the end-of-scan resets of the `scan_reset` variables of the flat
/// module `m` named in `names` (each a variable or a scope of variables,
/// `t` for every member of `t`), and their marks. A name that is not a
/// variable of `m` is refused unless `lenient` (the names a property
/// mentions, most of which are not reset). False after reporting.
bool keepValues(net::Design &d, net::Module &m,
                const std::vector<std::string> &names, DiagEngine &diag,
                bool lenient = false);

} // namespace netlift

#endif
