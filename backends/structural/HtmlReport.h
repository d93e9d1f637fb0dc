//===- HtmlReport.h - the structural-reasoning report as one HTML file -*- C++
//-*-===//
//
// One self-contained HTML file (no external scripts, styles or fonts): the
// summary (states, edges, attributes and densities, key attributes), the
// Edwards-Venn diagram, the attribute graph (graphviz's SVG when the
// caller could run `dot`, else its DOT text), the density and necklace
// charts, the deadlock regions and a table of every region with its counts
// and an example state. A small script shows a tooltip over every diagram
// region and graph node listing the region's attributes, states, share,
// deadlocks and example, as the paper's tool does.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STRUCTURAL_HTMLREPORT_H
#define NETLIFT_BACKENDS_STRUCTURAL_HTMLREPORT_H

#include "backends/structural/EdwardsVenn.h"

#include <map>
#include <string>

namespace netlift::structural {

struct HtmlReportInputs {
  std::string title;
  VennOptions venn;
  /// The attribute graph rendered by graphviz (`<svg>...`), or empty.
  std::string attributeGraphSvg;
  /// An example state of each occurring region, as `name=value` text.
  std::map<Region, std::string> examples;
  /// Links to each region's witness page (a shortest path into it).
  std::map<Region, std::string> witnesses;
};

void writeHtmlReport(const Analysis &a, const HtmlReportInputs &in,
                     llvm::raw_ostream &os);

} // namespace netlift::structural

#endif
