//===- DensityChart.cpp - densities and necklaces as SVG bar charts -------===//
#include "backends/structural/DensityChart.h"

#include <algorithm>
#include <fmt/format.h>

#include "ir/support/XmlEscape.h"

using namespace netlift;
using namespace netlift::structural;

namespace {
struct Bar {
  std::string label;
  uint64_t count;
  bool highlight;
};

/// One chart at horizontal offset `x0`: bars of count/total, a 0..1 axis.
void chart(llvm::raw_ostream &os, double x0, const std::string &title,
           const std::vector<Bar> &bars, uint64_t total) {
  constexpr double kTop = 40, kHeight = 220, kBar = 34, kGap = 10;
  double width = bars.size() * (kBar + kGap) + kGap;
  os << fmt::format("<g transform=\"translate({},0)\">\n", x0);
  os << fmt::format("<text x=\"0\" y=\"20\" font-size=\"14\" "
                    "font-weight=\"bold\">{}</text>\n",
                    xmlEscape(title));
  for (int t = 0; t <= 4; ++t) {
    double y = kTop + kHeight * (1 - t / 4.0);
    os << fmt::format("<line x1=\"30\" y1=\"{0:.1f}\" x2=\"{1:.1f}\" "
                      "y2=\"{0:.1f}\" stroke=\"#dddddd\"/>"
                      "<text x=\"26\" y=\"{2:.1f}\" font-size=\"10\" "
                      "text-anchor=\"end\">{3:.2f}</text>\n",
                      y, 30 + width, y + 3, t / 4.0);
  }
  for (size_t i = 0; i < bars.size(); ++i) {
    double share = total ? double(bars[i].count) / total : 0;
    double x = 30 + kGap + i * (kBar + kGap), h = kHeight * share;
    os << fmt::format(
        "<g class=\"bar\" data-label=\"{0}\" data-count=\"{1}\">"
        "<title>{0}: {1} of {2} states ({3:.4f})</title>"
        "<rect x=\"{4:.1f}\" y=\"{5:.1f}\" width=\"{6}\" height=\"{7:.1f}\" "
        "fill=\"{8}\"/>"
        "<text x=\"{9:.1f}\" y=\"{10:.1f}\" font-size=\"10\" "
        "text-anchor=\"middle\">{3:.3f}</text>"
        "<text x=\"{9:.1f}\" y=\"{11:.1f}\" font-size=\"11\" "
        "text-anchor=\"end\" transform=\"rotate(-45 {9:.1f} {11:.1f})\">{0}"
        "</text></g>\n",
        xmlEscape(bars[i].label), bars[i].count, total, share, x,
        kTop + kHeight - h, kBar, h, bars[i].highlight ? "#d62728" : "#1f77b4",
        x + kBar / 2, kTop + kHeight - h - 4, kTop + kHeight + 14);
  }
  os << fmt::format("<line x1=\"30\" y1=\"{0}\" x2=\"{1:.1f}\" y2=\"{0}\" "
                    "stroke=\"#000000\"/>\n</g>\n",
                    kTop + kHeight, 30 + width);
}
} // namespace

void netlift::structural::writeDensityChart(const Analysis &a,
                                            llvm::raw_ostream &os) {
  size_t k = a.attributes().size();
  Analysis::KeyAttributes key = a.keyAttributes();
  std::vector<bool> isKey(k, false);
  if (!key.sets.empty())
    for (size_t i : key.sets.front())
      isKey[i] = true;
  std::vector<Bar> densities, necklaces;
  for (size_t i = 0; i < k; ++i)
    densities.push_back({a.attributes()[i], a.attributeCount(i), isKey[i]});
  std::vector<uint64_t> n = a.necklaces();
  for (size_t j = 0; j < n.size(); ++j)
    necklaces.push_back({"j=" + std::to_string(j), n[j], false});
  // Each chart at least as wide as its title.
  double left = std::max(30 + 44.0 * k + 70, 330.0);
  double width = left + std::max(30 + 44.0 * n.size() + 30, 360.0);
  os << fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" "
                    "height=\"330\" viewBox=\"0 0 {0} 330\" "
                    "font-family=\"Helvetica, Arial, sans-serif\" "
                    "class=\"densities\">\n",
                    width);
  chart(os, 0,
        std::string("Attribute densities") +
            (key.sets.empty() ? ""
             : key.exact      ? " (red: key attributes)"
                              : " (red: best partial cover)"),
        densities, a.numStates());
  chart(os, left, "Necklaces (states with exactly j attributes)", necklaces,
        a.numStates());
  os << "</svg>\n";
}
