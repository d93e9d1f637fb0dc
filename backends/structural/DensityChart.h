//===- DensityChart.h - densities and necklaces as SVG bar charts -*- C++
//-*-===//
//
// The two distributions of the structural-reasoning paper drawn as SVG bar
// charts side by side: the density |A_i|/|S| of each attribute (the key
// attributes of the exact or best cover drawn in another colour, since
// their densities sum to 1 exactly when they cover the state space), and
// the necklace distribution, the fraction of states holding exactly j of
// the k attributes (the paper's Figure 10). Every bar has a tooltip with
// its count.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STRUCTURAL_DENSITYCHART_H
#define NETLIFT_BACKENDS_STRUCTURAL_DENSITYCHART_H

#include "backends/structural/StructuralReasoning.h"

namespace netlift::structural {

void writeDensityChart(const Analysis &a, llvm::raw_ostream &os);

} // namespace netlift::structural

#endif
