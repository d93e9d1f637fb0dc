//===- HtmlReport.cpp - the structural-reasoning report as one HTML file --===//
#include "backends/structural/HtmlReport.h"

#include "backends/structural/DensityChart.h"
#include "ir/support/XmlEscape.h"

#include "llvm/Support/JSON.h"

#include <fmt/format.h>

using namespace netlift;
using namespace netlift::structural;

namespace {

/// A link to region r's witness page, or nothing.
std::string witnessLink(const HtmlReportInputs &in, Region r,
                        llvm::StringRef text) {
  auto it = in.witnesses.find(r);
  if (it == in.witnesses.end())
    return "";
  llvm::StringRef lead = text.take_while([](char c) { return c == ' '; });
  return fmt::format("{}<a class=\"witness\" href=\"{}\">{}</a>", lead.str(),
                     xmlEscape(it->second),
                     xmlEscape(text.drop_front(lead.size())));
}

const char *const kStyle = R"(
body { font-family: Helvetica, Arial, sans-serif; margin: 24px; color: #222; }
h1 { font-size: 22px; } h2 { font-size: 17px; margin-top: 28px; }
table { border-collapse: collapse; font-size: 13px; }
td, th { border: 1px solid #ccc; padding: 3px 8px; text-align: left; }
td.num { text-align: right; }
tr.dead td { color: #c00000; }
.figure { overflow-x: auto; }
#tooltip { position: fixed; display: none; pointer-events: none;
  background: #fffff0; border: 1px solid #888; padding: 6px 9px;
  font-size: 13px; max-width: 420px; box-shadow: 2px 2px 6px #aaa; }
.region:hover path, g.node:hover ellipse { stroke: #000; stroke-width: 2; }
)";

// Shows the region of whatever is under the pointer: diagram regions carry
// data-id, graph nodes an id "ag-r<N>" (graphviz keeps node ids).
const char *const kScript = R"(
(function () {
  var regions = JSON.parse(document.getElementById('regions').textContent);
  var tip = document.getElementById('tooltip');
  function regionOf(el) {
    for (; el && el !== document; el = el.parentNode) {
      if (el.getAttribute && el.getAttribute('data-id') !== null)
        return el.getAttribute('data-id');
      if (el.id && el.id.indexOf('ag-r') === 0) return el.id.substring(4);
    }
    return null;
  }
  function text(id) {
    var r = regions[id];
    if (!r) return null;
    var s = r.name + ': ' + r.states + ' states (' + r.share + ')';
    if (r.deadlocks) s += ', ' + r.deadlocks + ' deadlocked';
    if (!r.states) s += ' (never occurs)';
    if (r.example) s += '\nexample: ' + r.example;
    return s;
  }
  document.addEventListener('mouseover', function (e) {
    var t = text(regionOf(e.target));
    if (t === null) { tip.style.display = 'none'; return; }
    tip.textContent = t;
    tip.style.whiteSpace = 'pre-line';
    tip.style.display = 'block';
  });
  document.addEventListener('mousemove', function (e) {
    tip.style.left = (e.clientX + 14) + 'px';
    tip.style.top = (e.clientY + 14) + 'px';
  });
})();
)";

} // namespace

void netlift::structural::writeHtmlReport(const Analysis &a,
                                          const HtmlReportInputs &in,
                                          llvm::raw_ostream &os) {
  a.checkInvariants();
  size_t k = a.attributes().size();
  uint64_t total = a.numStates();
  auto share = [&](uint64_t n) {
    return fmt::format("{:.2f}%", total ? 100.0 * n / total : 0.0);
  };

  os << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">"
     << "\n<title>" << xmlEscape(in.title) << "</title>\n<style>" << kStyle
     << "</style>\n</head>\n<body>\n<div id=\"tooltip\"></div>\n";
  os << "<h1>Structural reasoning: " << xmlEscape(in.title) << "</h1>\n";
  os << fmt::format("<p>{} states, {} edges, {} attributes, {} regions "
                    "occur of {}.</p>\n",
                    total, a.numEdges(), k, a.regionCounts().size(),
                    uint64_t(1) << k);

  os << "<h2>Attributes</h2>\n<table>\n<tr><th>attribute</th><th>states</th>"
        "<th>density</th></tr>\n";
  for (size_t i = 0; i < k; ++i) {
    uint64_t c = a.attributeCount(i);
    os << fmt::format("<tr><td>{}</td><td class=\"num\">{}</td>"
                      "<td class=\"num\">{:.4f}</td></tr>\n",
                      xmlEscape(a.attributes()[i]), c,
                      total ? double(c) / total : 0.0);
  }
  os << "</table>\n";
  Analysis::KeyAttributes key = a.keyAttributes();
  os << "<p id=\"key-attributes\">Key attributes: ";
  if (key.sets.empty()) {
    os << "none";
  } else {
    os << key.kindText()
       << fmt::format(" ({} of {} states have exactly one): ", key.coveredOnce,
                      total);
    for (size_t s = 0; s < key.sets.size(); ++s) {
      os << (s ? ", " : "") << "{";
      for (size_t i = 0; i < key.sets[s].size(); ++i)
        os << (i ? "," : "") << xmlEscape(a.attributes()[key.sets[s][i]]);
      os << "}";
    }
  }
  os << "</p>\n";

  if (k <= kMaxVennAttributes) {
    os << "<h2>Edwards-Venn diagram</h2>\n<div class=\"figure\">\n";
    writeEdwardsVenn(a, in.venn, os);
    os << "</div>\n";
  }
  os << "<h2>Attribute graph</h2>\n<div class=\"figure\" id=\"ag\">\n";
  if (!in.attributeGraphSvg.empty()) {
    // graphviz's SVG without its XML prologue and DOCTYPE.
    llvm::StringRef svg = in.attributeGraphSvg;
    size_t start = svg.find("<svg");
    os << (start == llvm::StringRef::npos ? svg : svg.substr(start));
  } else {
    os << "<p>graphviz's <code>dot</code> was not found; the attribute graph "
          "as DOT:</p>\n<pre>";
    std::string dot;
    llvm::raw_string_ostream ds(dot);
    a.writeDot(ds, false);
    os << xmlEscape(ds.str()) << "</pre>\n";
  }
  os << "</div>\n<h2>Densities and necklaces</h2>\n<div class=\"figure\">\n";
  writeDensityChart(a, os);
  os << "</div>\n";

  os << "<h2>Deadlock regions</h2>\n";
  if (a.deadlockCounts().empty()) {
    os << "<p id=\"deadlocks\">No state is a deadlock.</p>\n";
  } else {
    os << "<ul id=\"deadlocks\">\n";
    for (auto &[r, d] : a.deadlockCounts())
      os << fmt::format("<li>{}: {} of its {} states are deadlocks{}</li>\n",
                        xmlEscape(a.regionName(r)), d, a.statesIn(r),
                        witnessLink(in, r, " (how the region is reached)"));
    os << "</ul>\n";
  }

  if (a.numEdges()) {
    os << "<h2>Regions never left</h2>\n";
    std::vector<Region> trapped = a.regionsNeverLeft();
    if (trapped.empty()) {
      os << "<p id=\"never-left\">Every region can be left.</p>\n";
    } else {
      os << "<ul id=\"never-left\">\n";
      for (Region r : trapped)
        os << fmt::format("<li>{}: {} states; no edge leaves it{}</li>\n",
                          xmlEscape(a.regionName(r)), a.statesIn(r),
                          witnessLink(in, r, " (how it is reached)"));
      os << "</ul>\n";
    }
  }

  bool witnesses = !in.witnesses.empty();
  os << "<h2>Regions</h2>\n<table id=\"region-table\">\n<tr><th>region</th>"
        "<th>states</th><th>share</th><th>deadlocks</th><th>example state"
        "</th>"
     << (witnesses ? "<th>witness</th>" : "") << "</tr>\n";
  llvm::json::Object info;
  for (Region r = 0; r < (Region(1) << k); ++r) {
    uint64_t c = a.statesIn(r), d = a.deadlocksIn(r);
    auto ex = in.examples.find(r);
    std::string example = ex == in.examples.end() ? "" : ex->second;
    if (c)
      os << fmt::format(
          "<tr{}><td>{}</td><td class=\"num\">{}</td>"
          "<td class=\"num\">{}</td><td class=\"num\">{}</td>"
          "<td>{}</td>{}</tr>\n",
          d ? " class=\"dead\"" : "", xmlEscape(a.regionName(r)), c, share(c),
          d, xmlEscape(example),
          witnesses ? "<td>" + witnessLink(in, r, "shortest path") + "</td>"
                    : "");
    info[std::to_string(r)] = llvm::json::Object{{"name", a.regionName(r)},
                                                 {"states", int64_t(c)},
                                                 {"share", share(c)},
                                                 {"deadlocks", int64_t(d)},
                                                 {"example", example}};
  }
  os << "</table>\n";
  // The data the tooltips read; '<' escaped so that no text ends the
  // script element early.
  std::string json;
  llvm::raw_string_ostream js(json);
  js << llvm::json::Value(std::move(info));
  std::string safe;
  for (char c : js.str())
    safe += c == '<' ? std::string("\\u003c") : std::string(1, c);
  os << "<script type=\"application/json\" id=\"regions\">" << safe
     << "</script>\n<script>" << kScript << "</script>\n</body>\n</html>\n";
}
