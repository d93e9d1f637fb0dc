//===- EdwardsVennTest.cpp - every region of the diagram has an area ------===//
#include "backends/structural/EdwardsVenn.h"

#include <gtest/gtest.h>

using namespace netlift::structural;

// Equations (1)-(3) with cos: a complete Venn diagram, every one of the
// 2^k regions (attribute subsets) drawn with an area, up to 10 attributes.
TEST(EdwardsVenn, GrayOrderDrawsEveryRegion) {
  for (unsigned k = 1; k <= kMaxVennAttributes; ++k) {
    std::map<Region, double> areas = vennRegionAreas(k, /*grayOrder=*/true);
    EXPECT_EQ(areas.size(), size_t(1) << k) << k << " attributes";
    for (auto &[r, area] : areas)
      EXPECT_GT(area, 0.5) << "region " << r << " of " << k;
  }
}

// With sin every curve meets the circle at theta = 0: from four
// attributes on, some regions have no area (the diagram lists them).
TEST(EdwardsVenn, BinaryOrderLosesRegionsFromFourAttributes) {
  for (unsigned k = 1; k <= 3; ++k)
    EXPECT_EQ(vennRegionAreas(k, false).size(), size_t(1) << k);
  EXPECT_EQ(vennRegionAreas(4, false).size(), 12u);
}

// The attribute graph's node colours are the diagram's region colours.
TEST(EdwardsVenn, RegionColoursAreStableAndDistinctForNeighbours) {
  EXPECT_EQ(regionColour(0, 4), "#ffffff");
  EXPECT_EQ(regionColour(5, 4), regionColour(5, 4));
  EXPECT_NE(regionColour(1, 4), regionColour(3, 4));
}
