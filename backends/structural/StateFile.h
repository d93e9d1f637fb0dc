//===- StateFile.h - state spaces read back from `reach` JSON ---*- C++ -*-===//
//
// Structural reasoning over a state space explored earlier: reads the JSON
// that `netlift reach --format json` writes (docs/formats.md), or its CSV
// (`--format csv` and `--edges`), in one pass
// and without building a document, so that a file of 10^7 states is
// classified with memory for one row, the regions and one region number per
// state (the edges refer to states by number). Attributes are the file's
// columns: a column name alone (`p`, `t1.Q`, `v[2].x`), or a NetIR
// predicate over them, evaluated on each row (a place column stands for
// "marked" where a Boolean is expected, for its token count elsewhere).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STRUCTURAL_STATEFILE_H
#define NETLIFT_BACKENDS_STRUCTURAL_STATEFILE_H

#include "backends/structural/StructuralReasoning.h"
#include "ir/net/Expr.h"
#include "ir/support/Diagnostics.h"

namespace netlift::structural {

/// One selected attribute: its name and its predicate (null: the column of
/// that name).
struct StateFileAttribute {
  std::string name;
  const net::Expr *predicate = nullptr;
};

struct StateFileResult {
  bool complete = true; // the file says the exploration was complete
  std::string model;
  /// If set, the first state of each region as `name=value` text (marked
  /// places only, as the reach writers print states).
  bool collectExamples = false;
  std::map<Region, std::string> examples;
};

/// Classifies every state and edge of the JSON state file in `bufferID`
/// into `analysis` (whose attributes are `attrs`, in order). False after
/// reporting a malformed file, an unknown column or a predicate that
/// cannot be evaluated on a row.
bool analyseStateFile(unsigned bufferID, DiagEngine &diag,
                      const std::vector<StateFileAttribute> &attrs,
                      Analysis &analysis, StateFileResult &result);

/// The same over `reach --format csv` output: the states file (header
/// `id,deadlock,<attribute>...`) and, if `edgesID` is not 0, the edges file
/// (`from,label,to`, written by `reach --edges`). Without edges the
/// attribute graph has no edges.
bool analyseStateCsv(unsigned statesID, unsigned edgesID, DiagEngine &diag,
                     const std::vector<StateFileAttribute> &attrs,
                     Analysis &analysis, StateFileResult &result);

} // namespace netlift::structural

#endif
