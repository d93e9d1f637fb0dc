//===- EdwardsVenn.cpp - Edwards-Venn diagrams of regions -----------------===//
#include "backends/structural/EdwardsVenn.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "ir/support/XmlEscape.h"

using namespace netlift;
using namespace netlift::structural;

namespace {

// Picture geometry (SVG pixels): the circle's radius, the half side of the
// square the rectangles fill (the widest curve reaches 1.5 r), the centre.
constexpr double kRadius = 170, kHalf = 280, kCentre = 300;
constexpr double kPi = 3.14159265358979323846;

/// The shapes bounded by a radius around the centre: attribute 0 (the
/// circle) and attributes 3.. (the curves). Attributes 1 and 2 are the
/// upper and right halves, decided by the angle alone.
struct Geometry {
  unsigned k;
  bool gray;

  double radius(unsigned attr, double theta) const {
    if (attr == 0)
      return kRadius;
    double scale = std::ldexp(1.0, int(attr) - 2); // 2^i, i = attr - 2
    double wave = gray ? std::cos(scale * theta) : std::sin(scale * theta);
    return kRadius * wave / scale + kRadius;
  }
  /// Distance from the centre to the square's edge.
  static double edge(double theta) {
    return kHalf /
           std::max(std::fabs(std::cos(theta)), std::fabs(std::sin(theta)));
  }
  Region halves(double theta) const {
    Region r = 0;
    if (k > 1 && std::sin(theta) > 0)
      r |= 2;
    if (k > 2 && std::cos(theta) > 0)
      r |= 4;
    return r;
  }
  std::vector<unsigned> radial() const {
    std::vector<unsigned> out{0};
    for (unsigned a = 3; a < k; ++a)
      out.push_back(a);
    return out;
  }
  unsigned samples() const {
    return std::max(720u, 32u << (k > 3 ? k - 3 : 0));
  }
};

/// A connected run of angle samples over which one region lies between the
/// same two boundaries (a shape's radius, the centre or the square's edge).
struct Piece {
  Region region;
  int lower, upper; // attribute, -1 centre, -2 edge
  unsigned first, last;
  double area = 0;
};

double boundary(const Geometry &g, int b, double theta) {
  if (b == -1)
    return 0;
  if (b == -2)
    return Geometry::edge(theta);
  return g.radius(unsigned(b), theta);
}

std::vector<Piece> sweep(const Geometry &g) {
  unsigned n = g.samples();
  double step = 2 * kPi / n;
  std::vector<unsigned> shapes = g.radial();
  std::vector<Piece> done;
  std::vector<Piece> open;
  std::vector<std::pair<double, int>> sorted;
  for (unsigned j = 0; j < n; ++j) {
    double theta = (j + 0.5) * step;
    sorted.clear();
    sorted.push_back({0, -1});
    for (unsigned a : shapes)
      sorted.push_back({g.radius(a, theta), int(a)});
    std::sort(sorted.begin() + 1, sorted.end());
    sorted.push_back({Geometry::edge(theta), -2});
    std::vector<Piece> next;
    Region inside = 0; // shapes whose radius is above the interval
    for (unsigned a : shapes)
      inside |= Region(1) << a;
    for (size_t q = 1; q < sorted.size(); ++q) {
      Piece p{inside | g.halves(theta), sorted[q - 1].second, sorted[q].second,
              j, j};
      double lo = sorted[q - 1].first, hi = sorted[q].first;
      if (sorted[q].second >= 0)
        inside &= ~(Region(1) << sorted[q].second);
      auto it = std::find_if(open.begin(), open.end(), [&](const Piece &o) {
        return o.region == p.region && o.lower == p.lower &&
               o.upper == p.upper && o.last + 1 == j;
      });
      if (it != open.end()) {
        p = *it;
        p.last = j;
        open.erase(it);
      }
      p.area += (hi * hi - lo * lo) / 2 * step;
      next.push_back(p);
    }
    for (Piece &o : open)
      done.push_back(o);
    open = std::move(next);
  }
  for (Piece &o : open)
    done.push_back(o);
  return done;
}

std::string point(double rho, double theta) {
  // Equations (2) and (3); SVG's y axis points down.
  return fmt::format("{:.1f},{:.1f}", rho * std::cos(theta) + kCentre,
                     kCentre - rho * std::sin(theta));
}

/// Distinct, stable outline colours for the attributes.
const char *const kAttrColours[kMaxVennAttributes] = {
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
    "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};

} // namespace

std::map<Region, double> netlift::structural::vennRegionAreas(unsigned k,
                                                              bool grayOrder) {
  std::map<Region, double> areas;
  for (const Piece &p : sweep(Geometry{k, grayOrder}))
    areas[p.region] += p.area;
  return areas;
}

std::vector<Region> netlift::structural::undrawnRegions(const Analysis &a,
                                                        bool grayOrder) {
  std::map<Region, double> areas =
      vennRegionAreas(a.attributes().size(), grayOrder);
  std::vector<Region> out;
  for (auto &[r, c] : a.regionCounts())
    if (c && !areas.count(r))
      out.push_back(r);
  return out;
}

std::string netlift::structural::regionColour(Region r, unsigned k) {
  if (r == 0)
    return "#ffffff";
  // Hues spread by the golden angle, lightness by the number of
  // attributes (inner necklaces darker), so neighbours differ.
  double hue = std::fmod(r * 137.508, 360.0);
  unsigned j = __builtin_popcount(r);
  double light = 0.85 - 0.35 * double(j) / std::max(1u, k);
  double sat = 0.55, c = (1 - std::fabs(2 * light - 1)) * sat;
  double x = c * (1 - std::fabs(std::fmod(hue / 60, 2) - 1)), m = light - c / 2;
  double rgb[3];
  int sector = int(hue / 60) % 6;
  const double table[6][3] = {{c, x, 0}, {x, c, 0}, {0, c, x},
                              {0, x, c}, {x, 0, c}, {c, 0, x}};
  for (int i = 0; i < 3; ++i)
    rgb[i] = table[sector][i] + m;
  return fmt::format("#{:02x}{:02x}{:02x}", int(std::lround(rgb[0] * 255)),
                     int(std::lround(rgb[1] * 255)),
                     int(std::lround(rgb[2] * 255)));
}

void netlift::structural::writeEdwardsVenn(const Analysis &a,
                                           const VennOptions &opts,
                                           llvm::raw_ostream &os) {
  unsigned k = a.attributes().size();
  Geometry g{k, opts.grayOrder};
  unsigned n = g.samples();
  double step = 2 * kPi / n;
  std::vector<Piece> pieces = sweep(g);
  std::stable_sort(
      pieces.begin(), pieces.end(),
      [](const Piece &x, const Piece &y) { return x.region < y.region; });

  double width = 2 * kCentre + 260, height = 2 * kCentre;
  os << fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" "
                    "width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
                    "font-family=\"Helvetica, Arial, sans-serif\" "
                    "class=\"edwards-venn\">\n",
                    width, height);
  os << fmt::format("<title>Edwards-Venn diagram: {} attributes, {} order, {} "
                    "states</title>\n",
                    k, opts.grayOrder ? "Gray-code" : "binary", a.numStates());

  // Regions: all pieces of one region in one group with its tooltip.
  for (size_t i = 0; i < pieces.size();) {
    Region r = pieces[i].region;
    uint64_t states = a.statesIn(r), deadlocks = a.deadlocksIn(r);
    std::string fill;
    if (opts.necklaces)
      fill = __builtin_popcount(r) % 2 ? "#3a3a3a" : "#f4f4f4";
    else
      fill = states ? regionColour(r, k) : "#f0f0f0";
    std::string name = a.regionName(r);
    std::string tip = fmt::format("{}: {} states", name, states);
    if (a.numStates())
      tip += fmt::format(" ({:.1f}%)", 100.0 * states / a.numStates());
    if (deadlocks)
      tip += fmt::format(", {} deadlocked", deadlocks);
    os << fmt::format("<g class=\"region\" data-id=\"{}\" data-region=\"{}\" "
                      "data-states=\"{}\" data-deadlocks=\"{}\" "
                      "fill=\"{}\" stroke=\"{}\" stroke-width=\"0.6\">"
                      "<title>{}</title>\n",
                      r, xmlEscape(name), states, deadlocks, fill, fill,
                      xmlEscape(tip));
    const Piece *biggest = &pieces[i];
    for (; i < pieces.size() && pieces[i].region == r; ++i) {
      const Piece &p = pieces[i];
      if (p.area > biggest->area)
        biggest = &p;
      // Half a step beyond the first and last sample closes the seams.
      std::string d = "M";
      auto edgeAt = [&](int b, double t) {
        return point(boundary(g, b, t), t);
      };
      double t0 = p.first * step, t1 = (p.last + 1) * step;
      d += edgeAt(p.lower, t0);
      for (unsigned j = p.first; j <= p.last; ++j)
        d += "L" + edgeAt(p.lower, (j + 0.5) * step);
      d += "L" + edgeAt(p.lower, t1) + "L" + edgeAt(p.upper, t1);
      for (unsigned j = p.last + 1; j-- > p.first;)
        d += "L" + edgeAt(p.upper, (j + 0.5) * step);
      d += "L" + edgeAt(p.upper, t0) + "Z";
      os << "<path d=\"" << d << "\"/>\n";
    }
    os << "</g>\n";
    // The count where the region is widest, if a label fits there.
    unsigned mid = (biggest->first + biggest->last) / 2;
    double theta = (mid + 0.5) * step;
    double lo = boundary(g, biggest->lower, theta),
           hi = boundary(g, biggest->upper, theta);
    double room = std::min(hi - lo, (biggest->last - biggest->first + 1) *
                                        step * (lo + hi) / 2);
    if (room >= 9) {
      double size = std::min(14.0, room * 0.8);
      bool dark = opts.necklaces && __builtin_popcount(r) % 2;
      os << fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{:.1f}\" "
                        "text-anchor=\"middle\" dominant-baseline=\"middle\" "
                        "fill=\"{}\" pointer-events=\"none\">{}</text>\n",
                        (lo + hi) / 2 * std::cos(theta) + kCentre,
                        kCentre - (lo + hi) / 2 * std::sin(theta), size,
                        deadlocks ? "#c00000"
                        : dark    ? "#ffffff"
                                  : "#000000",
                        deadlocks ? fmt::format("{}\u2020", states)
                                  : std::to_string(states));
    }
  }

  // Outlines: the rectangles' inner edges, the circle, the curves.
  os << "<g fill=\"none\" stroke-width=\"1.6\" pointer-events=\"none\">\n";
  os << fmt::format("<rect x=\"{0}\" y=\"{0}\" width=\"{1}\" height=\"{1}\" "
                    "stroke=\"#000000\"/>\n",
                    kCentre - kHalf, 2 * kHalf);
  if (k > 1)
    os << fmt::format("<path d=\"M{},{}H{}\" stroke=\"{}\"/>\n",
                      kCentre - kHalf, kCentre, kCentre + kHalf,
                      kAttrColours[1]);
  if (k > 2)
    os << fmt::format("<path d=\"M{},{}V{}\" stroke=\"{}\"/>\n", kCentre,
                      kCentre - kHalf, kCentre + kHalf, kAttrColours[2]);
  for (unsigned attr : g.radial()) {
    std::string d;
    for (unsigned j = 0; j < n; ++j) {
      double t = j * step;
      d += (j ? "L" : "M") + point(g.radius(attr, t), t);
    }
    os << "<path d=\"" << d << "Z\" stroke=\"" << kAttrColours[attr]
       << "\"/>\n";
  }
  os << "</g>\n";

  // Legend: each attribute's shape, colour and density.
  double x = 2 * kCentre + 10, y = 30;
  os << "<g font-size=\"13\">\n";
  static const char *const shapes[3] = {"circle", "upper half", "right half"};
  for (unsigned i = 0; i < k; ++i, y += 22) {
    uint64_t c = a.attributeCount(i);
    std::string shape = i < 3 ? shapes[i] : fmt::format("curve i={}", i - 2);
    os << fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" "
                      "stroke=\"{3}\" stroke-width=\"3\"/>"
                      "<text x=\"{4}\" y=\"{5}\">{6} ({7}): {8:.3f}</text>\n",
                      x, y, x + 22, kAttrColours[i], x + 28, y + 4,
                      xmlEscape(a.attributes()[i]), shape,
                      a.numStates() ? double(c) / a.numStates() : 0.0);
  }
  os << fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\" "
                    "fill=\"#555555\">count in each region; \u2020 deadlocks; "
                    "hover for details</text>\n",
                    x, y + 8);
  // The sin curves of the binary order all meet the circle at the same
  // angles, so some regions have no area: say which occurring ones.
  y += 30;
  for (Region r : undrawnRegions(a, opts.grayOrder)) {
    os << fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\" "
                      "fill=\"#c00000\">not drawable in this order: {} "
                      "({} states)</text>\n",
                      x, y, xmlEscape(a.regionName(r)), a.regionCounts().at(r));
    y += 16;
  }
  os << "</g>\n</svg>\n";
}
