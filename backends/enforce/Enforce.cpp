//===- Enforce.cpp - judging observed I/O traces --------------------------===//
#include "backends/enforce/Enforce.h"

#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/MemoryBuffer.h"

#include <algorithm>

using namespace netlift;
using namespace netlift::automata;
using llvm::StringRef;

bool netlift::enforceTrace(const EditAutomaton &ea, unsigned bufferID,
                           DiagEngine &diag,
                           const std::function<void(const std::string &)> &emit,
                           EnforceResult &r) {
  StringRef buf = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  auto loc = [](StringRef s) { return llvm::SMLoc::getFromPointer(s.data()); };
  StringRef rest = buf;
  std::vector<size_t> column; // signal i is read from CSV column column[i]
  size_t numColumns = 0;
  bool header = true;
  uint32_t state = ea.initial;
  std::string vec(ea.signals.size(), '0');
  while (!rest.empty()) {
    auto [raw, next] = rest.split('\n');
    rest = next;
    StringRef line = raw.rtrim("\r");
    if (line.trim().empty())
      continue;
    llvm::SmallVector<StringRef, 16> cells;
    line.split(cells, ',');
    if (header) {
      header = false;
      numColumns = cells.size();
      column.assign(ea.signals.size(), SIZE_MAX);
      for (size_t c = 0; c < cells.size(); ++c) {
        StringRef name = cells[c].trim();
        auto it = std::find(ea.signals.begin(), ea.signals.end(), name.str());
        if (it == ea.signals.end()) {
          diag.error(loc(cells[c]), "the trace has a signal '" + name +
                                        "' the specification does not have");
          return false;
        }
        size_t i = size_t(it - ea.signals.begin());
        if (column[i] != SIZE_MAX) {
          diag.error(loc(cells[c]), "signal '" + name + "' appears twice");
          return false;
        }
        column[i] = c;
      }
      for (size_t i = 0; i < column.size(); ++i)
        if (column[i] == SIZE_MAX) {
          diag.error(loc(line),
                     "the trace lacks the signal '" + ea.signals[i] + "'");
          return false;
        }
      continue;
    }
    if (cells.size() != numColumns) {
      diag.error(loc(line), "row has " + llvm::Twine(cells.size()) +
                                " values, the header names " +
                                llvm::Twine(numColumns));
      return false;
    }
    for (size_t i = 0; i < column.size(); ++i) {
      StringRef v = cells[column[i]].trim();
      if (v != "0" && v != "1") {
        diag.error(loc(cells[column[i]]), "expected 0 or 1 for '" +
                                              ea.signals[i] + "', found '" + v +
                                              "'");
        return false;
      }
      vec[i] = v[0];
    }
    ++r.vectors;
    if (r.stopped)
      continue; // read on to check the rest of the file is well formed
    const EditTransition *t = ea.step(state, vec);
    if (!t) {
      r.stopped = true;
      r.stopIndex = r.vectors;
      r.stopVector = vec;
      r.expected = ea.expected(state);
      continue;
    }
    if (t->kind == EditKind::Validate)
      emit(vec);
    state = t->to;
  }
  if (header) {
    diag.error(loc(buf), "the trace is empty (a header naming the signals "
                         "is expected)");
    return false;
  }
  r.endedIntermediate = !r.stopped && !ea.states[state].specified;
  r.conform = !r.stopped && !r.endedIntermediate;
  return true;
}

void netlift::writeEditAutomatonDot(const EditAutomaton &ea,
                                    llvm::raw_ostream &os) {
  os << "digraph edit_automaton {\n";
  for (size_t s = 0; s < ea.states.size(); ++s)
    os << "  q" << s << " [shape=circle, label=\"" << ea.states[s].name << "\""
       << (ea.states[s].specified ? "" : ", style=filled, fillcolor=gray85")
       << "];\n";
  os << "  __start0 [label=\"\", shape=none];\n  __start0 -> q" << ea.initial
     << ";\n";
  for (const EditTransition &t : ea.transitions)
    os << "  q" << t.from << " -> q" << t.to << " [label=\"" << t.event << "\""
       << (t.kind == EditKind::Suppress ? ", style=dashed, fontcolor=gray50"
                                        : "")
       << "];\n";
  os << "}\n";
}

void netlift::writeEditAutomatonTable(const EditAutomaton &ea,
                                      llvm::raw_ostream &os) {
  os << "signals:";
  for (const std::string &s : ea.signals)
    os << ' ' << s;
  os << "\ninitial: " << ea.states[ea.initial].name << "\n";
  for (const EditTransition &t : ea.transitions)
    os << ea.states[t.from].name
       << (ea.states[t.from].specified ? "" : " (intermediate)") << "  "
       << t.event << "  "
       << (t.kind == EditKind::Validate ? "validate" : "suppress") << "  "
       << ea.states[t.to].name
       << (ea.states[t.to].specified ? "" : " (intermediate)") << "\n";
}
