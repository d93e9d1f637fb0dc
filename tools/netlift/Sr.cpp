//===- Sr.cpp - sr: structural reasoning over a state space ---------------===//
#include "backends/structural/DensityChart.h"
#include "backends/structural/EdwardsVenn.h"
#include "backends/structural/ExploredRegions.h"
#include "backends/structural/HtmlReport.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

using namespace netlift;
using namespace netlift::driver;

static cl::opt<std::string> srInput(cl::Positional, cl::desc("<model>"),
                                    cl::Required, cl::sub(srCommand()));
static cl::list<std::string>
    attrTexts("attr",
              cl::desc("An attribute: a place or Boolean signal NAME, or "
                       "NAME=PREDICATE (repeatable)"),
              cl::value_desc("NAME[=PREDICATE]"), cl::sub(srCommand()),
              cl::cat(category()));
static cl::opt<bool> allRegions("all-regions",
                                cl::desc("Also list regions that never occur"),
                                cl::sub(srCommand()), cl::cat(category()));
enum class Report { Text, Json, Html };
static cl::opt<Report>
    report("report", cl::desc("Report format"), cl::init(Report::Text),
           cl::values(clEnumValN(Report::Text, "text", "text"),
                      clEnumValN(Report::Json, "json", "JSON"),
                      clEnumValN(Report::Html, "html",
                                 "one self-contained HTML file")),
           cl::sub(srCommand()), cl::cat(category()));
static cl::opt<std::string>
    agFile("ag",
           cl::desc("Write the attribute graph as DOT, or as SVG (drawn by "
                    "graphviz's dot) when FILE ends in .svg"),
           cl::value_desc("FILE.dot|FILE.svg"), cl::sub(srCommand()),
           cl::cat(category()));
static cl::opt<std::string>
    evFile("ev",
           cl::desc("Write the Edwards-Venn diagram as SVG (at most 10 "
                    "attributes)"),
           cl::value_desc("FILE.svg"), cl::sub(srCommand()),
           cl::cat(category()));
enum class CurveOrder { Gray, Binary };
static cl::opt<CurveOrder> curveOrder(
    "order", cl::desc("Edwards-Venn curves"), cl::init(CurveOrder::Gray),
    cl::values(clEnumValN(CurveOrder::Gray, "gray",
                          "cos: neighbouring regions differ in one attribute"),
               clEnumValN(CurveOrder::Binary, "binary", "sin")),
    cl::sub(srCommand()), cl::cat(category()));
static cl::opt<std::string> densityFile(
    "density",
    cl::desc("Write the attribute densities and the necklace distribution "
             "as SVG bar charts"),
    cl::value_desc("FILE.svg"), cl::sub(srCommand()), cl::cat(category()));
static cl::opt<bool>
    evNecklaces("ev-necklaces",
                cl::desc("Colour the Edwards-Venn regions by necklace"),
                cl::sub(srCommand()), cl::cat(category()));

static cl::opt<std::string> witnessDir(
    "witnesses",
    cl::desc("Write per region a shortest path into it as an HTML trace "
             "(DIR/region-N.html); the HTML report links them"),
    cl::value_desc("DIR"), cl::sub(srCommand()), cl::cat(category()));

/// `file` as the report at `report` links it: relative to the report's
/// directory when under it, else absolute.
static std::string linkFrom(llvm::StringRef report, llvm::StringRef file) {
  llvm::SmallString<256> target(file), base(report == "-" ? "." : report);
  llvm::sys::fs::make_absolute(target);
  llvm::sys::fs::make_absolute(base);
  llvm::sys::path::remove_dots(target, true);
  llvm::sys::path::remove_dots(base, true);
  if (report != "-")
    llvm::sys::path::remove_filename(base);
  llvm::StringRef t = target;
  if (t.consume_front(base) && t.consume_front("/"))
    return t.str();
  return target.str().str();
}

static bool refuse(DiagEngine &diag, const llvm::Twine &msg) {
  diag.error(llvm::SMLoc(), msg);
  return false;
}

static bool checkOptions(DiagEngine &diag) {
  if (attrTexts.empty() || attrTexts.size() > 20)
    return refuse(diag, "sr needs 1 to 20 attributes (--attr)");
  if (!evFile.empty() && attrTexts.size() > structural::kMaxVennAttributes)
    return refuse(diag, "an Edwards-Venn diagram is drawn for at most " +
                            llvm::Twine(structural::kMaxVennAttributes) +
                            " attributes, not " +
                            llvm::Twine(attrTexts.size()));
  return true;
}

/// Exit 0, 1 on error, 2 when a limit stopped the exploration (docs/sr.md).
int driver::runSr(DiagEngine &diag) {
  net::Design design;
  std::vector<structural::Attribute> attrs;
  if (!checkOptions(diag) ||
      !structural::parseAttributes(attrTexts, design, diag, attrs))
    return 1;
  std::vector<std::string> names;
  for (const structural::Attribute &a : attrs)
    names.push_back(a.name);
  structural::Analysis an(names);
  structural::HtmlReportInputs html;
  html.title = llvm::sys::path::filename(srInput).str();
  llvm::StringRef ext = llvm::sys::path::extension(srInput);
  bool csv =
      inputFormat == "states-csv" || (inputFormat.empty() && ext == ".csv");
  bool stateFile =
      csv || inputFormat == "states" || (inputFormat.empty() && ext == ".json");
  if (!edgesFile.empty() && !csv)
    return !refuse(diag, "--edges goes with a CSV state file");
  if (!witnessDir.empty() && stateFile)
    return !refuse(diag, "--witnesses needs the model (a state file has no "
                         "paths to replay)");
  if (csv && edgesFile.empty())
    diag.warning(llvm::SMLoc(),
                 "a CSV state file has no edges: without --edges FILE (from "
                 "reach --edges) the attribute graph has no edges and regions "
                 "never left are not found");
  structural::ExploredRegions regions;
  if (stateFile) {
    // A state space written by `reach --format json|csv`, streamed.
    if (!structural::classifyStateFile(srInput, edgesFile, csv, attrs,
                                       report == Report::Html, an, regions,
                                       diag))
      return 1;
  } else {
    std::vector<std::string> inputs{srInput};
    engine::ExplorationOptions xo;
    if (!loadModels(inputs, diag, design) || !explorationOptions(xo, diag))
      return 1;
    // The attributes observe what they name (docs/semantics.md).
    xo.observerTexts.assign(attrTexts.begin(), attrTexts.end());
    auto setup = engine::ExplorationSetup::create(design, xo, diag, "sr");
    if (!setup || !structural::classifyExplored(*setup, design, attrs,
                                                report == Report::Html, an,
                                                regions, diag, witnessDir))
      return 1;
  }
  html.examples = std::move(regions.examples);
  for (auto &[r, file] : regions.witnesses)
    html.witnesses[r] = linkFrom(outputFile, file);

  if (!agFile.empty()) {
    std::string svg;
    if (llvm::StringRef(agFile).endswith(".svg")) {
      svg = structural::renderAttributeGraphSvg(an, allRegions);
      if (svg.empty())
        return !refuse(diag, "--ag " + agFile +
                                 ": drawing SVG needs graphviz's `dot` "
                                 "(write .dot instead)");
    }
    if (writeResult(
            agFile,
            [&](llvm::raw_ostream &os) {
              if (svg.empty())
                an.writeDot(os, allRegions);
              else
                os << svg;
            },
            diag))
      return 1;
  }
  if (!densityFile.empty() &&
      writeResult(
          densityFile,
          [&](llvm::raw_ostream &os) { structural::writeDensityChart(an, os); },
          diag))
    return 1;
  structural::VennOptions vo;
  vo.grayOrder = curveOrder == CurveOrder::Gray;
  vo.necklaces = evNecklaces;
  if (!evFile.empty()) {
    if (writeResult(
            evFile,
            [&](llvm::raw_ostream &os) {
              structural::writeEdwardsVenn(an, vo, os);
            },
            diag))
      return 1;
    for (structural::Region r : structural::undrawnRegions(an, vo.grayOrder))
      diag.warning(llvm::SMLoc(),
                   "the binary-order diagram has no area for region " +
                       an.regionName(r) + " (" +
                       llvm::Twine(an.regionCounts().at(r)) +
                       " states); --order gray draws every region");
  }
  if (report == Report::Html) {
    html.venn = vo;
    html.attributeGraphSvg = structural::renderAttributeGraphSvg(an, false);
  }
  if (writeResult(
          outputFile,
          [&](llvm::raw_ostream &os) {
            if (report == Report::Html)
              structural::writeHtmlReport(an, html, os);
            else if (report == Report::Json)
              an.writeJson(os, allRegions);
            else
              an.writeText(os, allRegions);
          },
          diag))
    return 1;
  return regions.complete ? 0 : 2;
}
