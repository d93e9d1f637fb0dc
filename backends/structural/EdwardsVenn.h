//===- EdwardsVenn.h - Edwards-Venn diagrams of regions ---------*- C++ -*-===//
//
// Draws the Edwards-Venn diagram of up to 10 attributes as SVG, following
// equations (1)-(3) of Lobov and Lastra: the first attribute is a circle of
// radius r, the second the upper and the third the right half of the
// picture (the two rectangles), and attribute j >= 4 the closed curve
// rho = r * cos(2^i * theta) / 2^i + r with i = j - 3 (sin instead of cos
// for the binary order), in polar coordinates around the circle's centre.
// Every one of the 2^k regions is computed (not only drawn as outlines):
// a sweep over the angle sorts the curves' radii, so each radial interval
// is one region; the pieces of a region are filled together, coloured,
// labelled with its state count where there is room, and carry a tooltip
// (`<title>`) and `data-` attributes naming its attributes, states and
// deadlocks (the HTML report uses them). With cos (the Gray-code order)
// all 2^k regions have an area for k <= 10; with sin (the binary order)
// the curves meet the circle at common angles (all at theta = 0), so from
// four attributes on some regions have none: those that hold states are
// listed in the picture instead.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_STRUCTURAL_EDWARDSVENN_H
#define NETLIFT_BACKENDS_STRUCTURAL_EDWARDSVENN_H

#include "backends/structural/StructuralReasoning.h"

#include <map>

namespace netlift::structural {

constexpr unsigned kMaxVennAttributes = 10;

struct VennOptions {
  /// Gray-code neighbourhood (cos) or binary-counting order (sin).
  bool grayOrder = true;
  /// Colour the regions by necklace (number of attributes), alternating
  /// dark and light as in the paper's Figure 5, instead of one colour each.
  bool necklaces = false;
};

/// The drawn area of every region of k attributes (in square pixels of
/// the SVG): a region missing here would not be visible. For tests.
std::map<Region, double> vennRegionAreas(unsigned k, bool grayOrder);

/// The occurring regions of `a` that the diagram cannot show (binary order).
std::vector<Region> undrawnRegions(const Analysis &a, bool grayOrder);

/// The fill colour of a region, shared by the diagram and the attribute
/// graph so that a node and its region look alike.
std::string regionColour(Region r, unsigned k);

/// Writes the diagram (1 to kMaxVennAttributes attributes).
void writeEdwardsVenn(const Analysis &a, const VennOptions &opts,
                      llvm::raw_ostream &os);

} // namespace netlift::structural

#endif
