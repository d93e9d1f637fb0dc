//===- TraceHtml.cpp - a path as a timing diagram in one HTML page --------===//
//
// The HTML view of a trace (docs/reach.md, "Traces"): the program's view
// of the path (programTrace: the rows the text table has) turned on its
// side, signals as rows and steps as columns. Booleans are drawn as
// waveforms, other values as a bus with the value written where it
// changes; the pointer on a cell shows the step, its time, the value and
// the source line of the assignment that made it, on a step's header the
// inputs that took it and the lines it ran. Self-contained: no script or
// style is fetched, so the page can be mailed with a bug report.
//
//===----------------------------------------------------------------------===//
#include "backends/statespace/StateColumns.h"
#include "backends/statespace/Writers.h"
#include "ir/support/OutputFile.h"
#include "ir/support/XmlEscape.h"

#include <map>

using namespace netlift;
using namespace netlift::engine;
using namespace netlift::statespace;
using namespace netlift::statespace::listing;

namespace {

const char *kStyle = R"(body{font-family:sans-serif;margin:1.5em;color:#222}
h1{font-size:1.2em}p.claim{color:#555}
table{border-collapse:collapse;font-size:12px}
th{text-align:left;padding:2px 10px 2px 2px;white-space:nowrap;font-weight:normal}
thead td{text-align:center;padding:2px 6px;color:#555;white-space:nowrap}
thead tr.taken td{font-family:monospace;border-bottom:1px solid #ccc}
tbody td{height:22px;min-width:34px;padding:0 4px;font-family:monospace;
 white-space:nowrap}
tr.group th{padding-top:10px;font-weight:bold;color:#555}
td.lo{border-bottom:2px solid #2a7}
td.hi{border-top:2px solid #2a7;background:#e3f6ea}
td.bus{border-top:1px solid #36c;border-bottom:1px solid #36c}
td.chg{border-left:2px solid #2a7}td.bus.chg{border-left:2px solid #36c}
td.in{color:#a50}
#tooltip{position:fixed;display:none;background:#fffbe6;border:1px solid #999;
 padding:4px 8px;font-size:12px;white-space:pre;pointer-events:none})";

const char *kScript = R"(var tip=document.getElementById('tooltip');
document.addEventListener('mouseover',function(e){
 var t=e.target.closest('[data-tip]');
 if(!t){tip.style.display='none';return;}
 tip.textContent=t.getAttribute('data-tip');tip.style.display='block';});
document.addEventListener('mousemove',function(e){
 tip.style.left=(e.clientX+12)+'px';tip.style.top=(e.clientY+12)+'px';});)";

/// `go=1, level=91..100` -> {go: 1, level: 91..100}; several classes
/// (`[a=1] | [b=1]`) are not one valuation: empty.
std::vector<std::pair<std::string, std::string>>
inputValues(llvm::StringRef inputs) {
  std::vector<std::pair<std::string, std::string>> out;
  if (inputs.contains(" | "))
    return out;
  llvm::SmallVector<llvm::StringRef, 8> items;
  inputs.split(items, ", ", -1, false);
  for (llvm::StringRef item : items) {
    auto [name, value] = item.split('=');
    out.push_back({name.str(), value.str()});
  }
  return out;
}

bool isBoolean(const StateColumn &c) {
  return c.kind == StateColumn::Place || (c.type && c.type->isBool());
}

} // namespace

void statespace::writeHtmlTrace(sem::Semantics &sem,
                                llvm::ArrayRef<std::string> labels,
                                llvm::ArrayRef<const uint64_t *> states,
                                const TraceFileHeader &header,
                                const TraceView &view, int64_t loopTo,
                                llvm::StringRef loopLabel,
                                llvm::raw_ostream &os) {
  ProgramTrace trace = programTrace(sem, labels, states, view, true);
  std::string model = sem.module().name.str();
  os << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">\n<title>"
     << xmlEscape("netlift trace: " + header.formula) << "</title>\n<style>"
     << kStyle << "</style></head>\n<body>\n<h1>" << xmlEscape(header.formula)
     << ": " << (header.holds ? "holds" : "fails") << "</h1>\n"
     << "<p class=\"claim\">" << (header.witness ? "witness" : "counterexample")
     << ": " << xmlEscape(header.claim) << " (model " << xmlEscape(model)
     << ")</p>\n<table id=\"timing\">\n<thead>\n<tr class=\"time\"><th>"
     << (trace.timed ? "time" : "ticks") << "</th>";
  for (const TraceRow &r : trace.rows)
    os << "<td>" << xmlEscape(r.time) << "</td>";
  os << "</tr>\n<tr class=\"taken\"><th>step</th>";
  for (const TraceRow &r : trace.rows) {
    std::string tip =
        "step " + std::to_string(r.step) + " at " + r.time + ": " + r.taken;
    if (!r.inputs.empty())
      tip += "\ninputs: " + r.inputs;
    if (!r.ran.empty())
      tip += "\nran " + r.ran;
    os << "<td data-step=\"" << r.step << "\" data-tip=\"" << xmlEscape(tip)
       << "\">" << r.step << "</td>";
  }
  os << "</tr>\n</thead>\n<tbody>\n";

  // The inputs each step read, one row per input in order of appearance.
  std::vector<std::string> inputNames;
  std::vector<std::map<std::string, std::string>> inputsOf;
  for (const TraceRow &r : trace.rows) {
    inputsOf.emplace_back();
    for (auto &[name, value] : inputValues(r.inputs)) {
      if (llvm::find(inputNames, name) == inputNames.end())
        inputNames.push_back(name);
      inputsOf.back()[name] = value;
    }
  }
  auto group = [&](const char *title) {
    os << "<tr class=\"group\"><th colspan=\"" << trace.rows.size() + 1 << "\">"
       << title << "</th></tr>\n";
  };
  if (!inputNames.empty())
    group("inputs");
  for (const std::string &name : inputNames) {
    os << "<tr class=\"signal input\" data-name=\"" << xmlEscape(name)
       << "\"><th>" << xmlEscape(name) << "</th>";
    for (size_t i = 0; i < trace.rows.size(); ++i) {
      auto it = inputsOf[i].find(name);
      std::string value = it == inputsOf[i].end() ? "" : it->second;
      os << "<td class=\"in\" data-tip=\""
         << xmlEscape(name + " = " + (value.empty() ? "not read" : value) +
                      " at step " + std::to_string(trace.rows[i].step))
         << "\">" << xmlEscape(value) << "</td>";
    }
    os << "</tr>\n";
  }

  auto signals = [&](bool outputs) {
    bool titled = false;
    for (size_t k = 0; k < trace.columns.size(); ++k) {
      const StateColumn &c = trace.columns[k];
      if ((c.kind == StateColumn::Output) != outputs)
        continue;
      // A place never marked along the path says nothing.
      if (c.kind == StateColumn::Place &&
          llvm::none_of(trace.rows,
                        [&](const TraceRow &r) { return r.values[k].v; }))
        continue;
      if (!titled)
        group(outputs ? "outputs" : "values");
      titled = true;
      os << "<tr class=\"signal\" data-name=\"" << xmlEscape(c.name)
         << "\"><th>" << xmlEscape(c.name) << "</th>";
      for (const TraceRow &r : trace.rows) {
        const Cell &cell = r.values[k];
        bool changed = r.changed[k];
        std::string cls = isBoolean(c) ? (cell.v ? "hi" : "lo") : "bus";
        if (changed)
          cls += " chg";
        std::string tip = c.name + " = " + cell.text + " after step " +
                          std::to_string(r.step) + " (" + r.time + ")";
        if (!r.at[k].empty())
          tip += ", set at " + r.at[k];
        os << "<td class=\"" << cls << "\" data-tip=\"" << xmlEscape(tip)
           << "\">"
           << (isBoolean(c) || (!changed && r.step != 0) ? ""
                                                         : xmlEscape(cell.text))
           << "</td>";
      }
      os << "</tr>\n";
    }
  };
  signals(true);
  signals(false);
  os << "</tbody>\n</table>\n";
  if (loopTo >= 0)
    os << "<p class=\"loop\">" << xmlEscape(loopLabel.str())
       << " leads back to step " << loopTo << ", and so on forever.</p>\n";
  if (trace.hiddenNames)
    os << "<p class=\"hidden\">" << trace.hiddenNames
       << " internal names hidden (the JSON and VCD traces carry every "
          "name).</p>\n";
  os << "<div id=\"tooltip\"></div>\n<script>" << kScript
     << "</script>\n</body></html>\n";
}
