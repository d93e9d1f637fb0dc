//===- ReplayLog.cpp - a field log run through the model ------------------===//
#include "backends/statespace/ReplayLog.h"
#include "backends/statespace/StateColumns.h"
#include "engine/ExplorationSetup.h"
#include "engine/ScanStep.h"
#include "ir/support/OutputFile.h"

#include <deque>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::engine;
using namespace netlift::statespace;
using namespace netlift::statespace::listing;

namespace {

/// One column of the log: a free input fixed for the scan, or a value
/// compared after it.
struct LogColumn {
  std::string name;
  enum Kind { Input, Event, Compared } kind = Compared;
  uint32_t leaf = 0; // Input: position in fixInputs' leaves
  const Type *type = nullptr;
  size_t column = 0; // Compared: index into stateColumns
};

/// `TRUE`, `false`, `1`, `-3`: the value, or nullopt.
std::optional<int64_t> parseValue(llvm::StringRef text) {
  if (text.equals_insensitive("true"))
    return 1;
  if (text.equals_insensitive("false"))
    return 0;
  int64_t v;
  if (text.getAsInteger(10, v))
    return std::nullopt;
  return v;
}

llvm::SMLoc at(llvm::StringRef cell) {
  return llvm::SMLoc::getFromPointer(cell.data());
}

} // namespace

bool statespace::showReplayedRun(sem::Semantics &sem,
                                 llvm::ArrayRef<std::string> labels,
                                 llvm::ArrayRef<std::vector<uint64_t>> kept,
                                 const TraceView &view,
                                 const ReplayLogOptions &options,
                                 llvm::StringRef source, llvm::StringRef claim,
                                 DiagEngine &diag, llvm::raw_ostream &os) {
  std::vector<const uint64_t *> states;
  for (const std::vector<uint64_t> &s : kept)
    states.push_back(s.data());
  writeStatePath(sem, labels, states, os, view);
  if (options.htmlFile.empty())
    return true;
  TraceFileHeader h{"replay " + source.str(), true, true, claim.str()};
  return writeOutputFile(
      options.htmlFile,
      [&](llvm::raw_ostream &out) {
        writeHtmlTrace(sem, labels, states, h, view, -1, "", out);
      },
      diag);
}

int statespace::replayLog(sem::Semantics &sem, unsigned bufferID,
                          const TraceView &view,
                          const ReplayLogOptions &options, DiagEngine &diag,
                          llvm::raw_ostream &os) {
  const Module &m = sem.module();
  const sem::StateLayout &L = sem.layout();
  llvm::StringRef text =
      diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  llvm::StringRef file =
      diag.sourceMgr().getMemoryBuffer(bufferID)->getBufferIdentifier();
  file = file.substr(file.find_last_of('/') + 1);

  // Rows: non-empty lines that are not comments; the first is the header.
  std::vector<std::pair<unsigned, llvm::StringRef>> lines;
  unsigned number = 0;
  for (llvm::StringRef rest = text; !rest.empty();) {
    auto [line, tail] = rest.split('\n');
    rest = tail;
    ++number;
    line = line.rtrim("\r");
    if (!line.trim().empty() && !line.trim().startswith("#"))
      lines.push_back({number, line});
  }
  if (lines.empty()) {
    diag.error(at(text), "the log is empty: a header naming the inputs, then "
                         "one row per scan");
    return 1;
  }
  char separator =
      lines[0].second.contains(';') && !lines[0].second.contains(',') ? ';'
                                                                      : ',';
  auto cells = [&](llvm::StringRef line) {
    llvm::SmallVector<llvm::StringRef, 16> out;
    line.split(out, separator);
    for (llvm::StringRef &c : out)
      c = c.trim();
    return out;
  };

  // The header: each name an input, an output or a variable of the model.
  std::vector<StateColumn> state = stateColumns(sem);
  std::vector<LogColumn> columns;
  std::vector<std::string> inputLeaves, eventInputs;
  std::vector<const Type *> leafTypes;
  for (const Port &p : m.ports) {
    if (!p.isInput())
      continue;
    if (p.kind == PortKind::Event) {
      eventInputs.push_back(p.name.str());
      continue;
    }
    inputLeaves.push_back(p.name.str());
    leafTypes.push_back(p.kind == PortKind::Cond ? nullptr : p.type);
  }
  for (llvm::StringRef name : cells(lines[0].second)) {
    LogColumn c;
    c.name = name.str();
    auto input = llvm::find(inputLeaves, c.name);
    auto event = llvm::find(eventInputs, c.name);
    auto compared = llvm::find_if(
        state, [&](const StateColumn &s) { return s.name == c.name; });
    if (input != inputLeaves.end()) {
      c.kind = LogColumn::Input;
      c.leaf = uint32_t(input - inputLeaves.begin());
      c.type = leafTypes[c.leaf];
      if (c.type && !c.type->isScalar()) {
        diag.error(at(name), "input '" + c.name +
                                 "' is not a scalar: a log gives Boolean "
                                 "and integer inputs");
        return 1;
      }
    } else if (event != eventInputs.end()) {
      c.kind = LogColumn::Event;
      c.leaf = uint32_t(event - eventInputs.begin());
    } else if (compared != state.end() &&
               compared->kind != StateColumn::Clock) {
      c.column = size_t(compared - state.begin());
      const Type *t = compared->type;
      if (t && !t->isBool() && !t->isInteger()) {
        diag.error(at(name), "'" + c.name +
                                 "' is neither Boolean nor an integer: a "
                                 "replay compares those values only");
        return 1;
      }
    } else {
      diag.error(at(name), "'" + c.name +
                               "' is neither a free input, an "
                               "output nor a variable of module '" +
                               m.name + "'");
      return 1;
    }
    columns.push_back(std::move(c));
  }
  for (const std::string &in : inputLeaves)
    if (llvm::none_of(columns, [&](const LogColumn &c) {
          return c.kind == LogColumn::Input && c.name == in;
        })) {
      diag.error(at(lines[0].second),
                 "the log has no column for input '" + in +
                     "': a replay fixes every free input at every scan");
      return 1;
    }

  // The run: the initial state, then per row the ticks and the scan.
  const uint32_t words = L.numWords();
  std::deque<std::vector<uint64_t>> kept(1, std::vector<uint64_t>(words));
  std::vector<std::string> labels{""};
  sem::RuntimeError err;
  auto runtimeError = [&] {
    reportRuntimeErrorAt(err, diag);
    return 1;
  };
  if (!sem.initialState(kept.back().data(), err))
    return runtimeError();
  std::vector<int64_t> leaves(inputLeaves.size());
  std::vector<uint8_t> present(eventInputs.size());
  std::vector<bool> given(inputLeaves.size());
  auto printRun = [&] {
    std::vector<std::vector<uint64_t>> run(kept.begin(), kept.end());
    return showReplayedRun(sem, labels, run, view, options, file,
                           "the log's scans run through the model", diag, os);
  };
  uint64_t compared = 0;
  for (size_t r = 1; r < lines.size(); ++r) {
    auto [lineNo, line] = lines[r];
    std::string where = options.rowName
                            ? options.rowName(r)
                            : file.str() + ":" + std::to_string(lineNo);
    auto row = cells(line);
    if (row.size() != columns.size()) {
      diag.error(at(line), "row has " + std::to_string(row.size()) +
                               " values, the header names " +
                               std::to_string(columns.size()));
      return 1;
    }
    // Every cell's value (empty cells none), refused at the first that
    // is not one.
    std::vector<std::optional<int64_t>> values(columns.size());
    for (size_t k = 0; k < columns.size(); ++k) {
      if (row[k].empty())
        continue;
      values[k] = parseValue(row[k]);
      if (!values[k]) {
        diag.error(at(row[k]), "'" + row[k].str() + "' is not a value of '" +
                                   columns[k].name +
                                   "' (0, 1, TRUE, FALSE or an integer)");
        return 1;
      }
    }
    std::fill(present.begin(), present.end(), 0);
    std::string inputsText;
    for (size_t k = 0; k < columns.size(); ++k) {
      const LogColumn &c = columns[k];
      if (c.kind == LogColumn::Compared || row[k].empty())
        continue;
      std::optional<int64_t> v = values[k];
      int64_t lo = c.type ? c.type->lo : 0, hi = c.type ? c.type->hi : 1;
      if (c.kind == LogColumn::Input && (*v < lo || *v > hi)) {
        diag.error(at(row[k]), "value " + std::to_string(*v) + " is outside " +
                                   std::to_string(lo) + ".." +
                                   std::to_string(hi) + " of input '" + c.name +
                                   "'");
        return 1;
      }
      if (c.kind == LogColumn::Event) {
        present[c.leaf] = *v != 0;
      } else {
        leaves[c.leaf] = *v;
        given[c.leaf] = true;
      }
    }
    // An empty input cell keeps the value the last row gave.
    for (size_t i = 0; i < given.size(); ++i)
      if (!given[i]) {
        diag.error(at(line), "no value for input '" + inputLeaves[i] +
                                 "' in this row or any before it");
        return 1;
      }
    // Every input's value, held ones too; the events present.
    for (size_t i = 0; i < leaves.size(); ++i)
      inputsText += (inputsText.empty() ? "" : ", ") + inputLeaves[i] + "=" +
                    std::to_string(leaves[i]);
    for (size_t e = 0; e < present.size(); ++e)
      if (present[e])
        inputsText += (inputsText.empty() ? "" : ", ") + eventInputs[e];
    sem.fixInputs(leaves, present);
    ScanOutcome scan;
    bool ok =
        nextScan(sem, kept.back().data(), options.maxWaitTicks, scan, err);
    sem.fixInputs({}, {});
    if (!ok)
      return runtimeError();
    for (std::vector<uint64_t> &t : scan.ticks) {
      kept.push_back(std::move(t));
      labels.push_back("tick");
    }
    if (scan.kind == ScanOutcome::Nondeterministic) {
      diag.error(at(line), "module '" + m.name +
                               "' is not deterministic "
                               "with these inputs: both " +
                               scan.step + " and " + scan.other +
                               " can happen (replay runs one controller)");
      return 1;
    }
    if (scan.kind != ScanOutcome::Stepped) {
      printRun();
      os << "diverges at " << where << ": the model takes no scan there ("
         << (scan.kind == ScanOutcome::Deadlock
                 ? std::string("a deadlock")
                 : "waited " + std::to_string(options.maxWaitTicks) + " ticks")
         << ")\n";
      return 3;
    }
    kept.push_back(std::move(scan.after));
    labels.push_back(scan.step +
                     (inputsText.empty() ? "" : " [" + inputsText + "]"));
    // What the log recorded after the scan.
    for (size_t k = 0; k < columns.size(); ++k) {
      const LogColumn &c = columns[k];
      if (c.kind != LogColumn::Compared || row[k].empty())
        continue;
      std::optional<int64_t> v = values[k];
      Cell cell = cellOf(sem, state[c.column], kept.back().data());
      ++compared;
      if (cell.v != *v) {
        if (!printRun())
          return 1;
        os << "diverges at " << where << " (scan " << r << ", step "
           << kept.size() - 1 << "): " << c.name << " is " << cell.text
           << " in the model, " << row[k] << " in the " << options.recordName
           << "\n";
        return 3;
      }
    }
  }
  if (!printRun())
    return 1;
  os << "the model agrees with the " << options.recordName << ": "
     << lines.size() - 1 << " scans, " << compared << " recorded values\n";
  return 0;
}
