//===- ExploredRegions.h - sr over an explored state space ------*- C++ -*-===//
//
// What `netlift sr` does with a model (rather than a state file): parse the
// attributes (`NAME` — a place or Boolean signal — or `NAME=PREDICATE`, in
// NetIR), explore the model through its exploration set-up, and put every
// state into the region of the attributes it satisfies and every edge
// between regions into the Analysis. Also draws the attribute graph as SVG
// with graphviz's `dot` for the reports.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STRUCTURAL_EXPLOREDREGIONS_H
#define NETLIFT_BACKENDS_STRUCTURAL_EXPLOREDREGIONS_H

#include "backends/structural/StructuralReasoning.h"
#include "engine/ExplorationSetup.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <map>
#include <string>
#include <vector>

namespace netlift::structural {

struct Attribute {
  std::string name;
  net::Expr *predicate = nullptr; // the name itself when `plain`
  bool plain = true;              // given as NAME alone
};

/// Parses each `NAME[=PREDICATE]`; false after reporting (errors point
/// into the attribute's text).
bool parseAttributes(llvm::ArrayRef<std::string> texts, net::Design &design,
                     DiagEngine &diag, std::vector<Attribute> &out);

struct ExploredRegions {
  bool complete = false;
  /// The first state (in discovery order) of each region, described.
  std::map<Region, std::string> examples;
  /// The witness page of each region (`DIR/region-N.html`), when asked.
  std::map<Region, std::string> witnesses;
};

/// Explores the set-up's state space and classifies it into `an` (states
/// by region, deadlocks, edges between regions); examples when asked.
/// With `witnessDir`, also writes there, per region, a shortest path to its
/// first state as an HTML trace (`region-N.html`, N the region's number).
/// False after reporting (an attribute that is not a state property, or a
/// runtime error of the model with its trace).
bool classifyExplored(engine::ExplorationSetup &setup, net::Design &design,
                      llvm::ArrayRef<Attribute> attrs, bool collectExamples,
                      Analysis &an, ExploredRegions &out, DiagEngine &diag,
                      llvm::StringRef witnessDir = "");

/// The same over a state space `reach` wrote: `path` as JSON, or as CSV
/// when `csv` (with the edges file `edgesPath` unless it is empty).
bool classifyStateFile(llvm::StringRef path, llvm::StringRef edgesPath,
                       bool csv, llvm::ArrayRef<Attribute> attrs,
                       bool collectExamples, Analysis &an, ExploredRegions &out,
                       DiagEngine &diag);

/// The attribute graph as SVG drawn by graphviz's `dot`, or "" when it is
/// not installed or fails (the HTML report then shows the DOT text).
std::string renderAttributeGraphSvg(const Analysis &an, bool allRegions);

} // namespace netlift::structural

#endif
