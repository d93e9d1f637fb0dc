//===- Enforce.cpp - judging observed I/O traces --------------------------===//
#include "backends/enforce/Enforce.h"

#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/MemoryBuffer.h"

#include <algorithm>

using namespace netlift;
using namespace netlift::enforce;
using namespace netlift::automata;
using llvm::StringRef;

bool netlift::enforce::enforceTrace(
    const EditAutomaton &ea, unsigned bufferID, DiagEngine &diag,
    const std::function<void(const std::string &)> &emit, EnforceResult &r) {
  StringRef buf = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  auto loc = [](StringRef s) { return llvm::SMLoc::getFromPointer(s.data()); };
  StringRef rest = buf;
  std::vector<size_t> column; // signal i is read from CSV column column[i]
  size_t numColumns = 0;
  bool header = true;
  uint32_t state = ea.initial;
  std::string vec(ea.signals.size(), '0');
  // A dense (state, event) -> transition table when it is small enough:
  // the per-vector cost is then an index computation.
  size_t k = ea.signals.size();
  std::vector<int32_t> table;
  if (k <= 20 && (ea.states.size() << k) <= (size_t(1) << 24)) {
    table.assign(ea.states.size() << k, -1);
    for (size_t i = 0; i < ea.transitions.size(); ++i) {
      const EditTransition &t = ea.transitions[i];
      uint32_t code = 0;
      for (char c : t.event)
        code = (code << 1) | uint32_t(c == '1');
      table[(size_t(t.from) << k) | code] = int32_t(i);
    }
  }
  llvm::SmallVector<StringRef, 16> cells;
  while (!rest.empty()) {
    auto [raw, next] = rest.split('\n');
    rest = next;
    StringRef line = raw;
    if (!line.empty() && line.back() == '\r')
      line = line.drop_back();
    if (line.empty() || line.trim().empty())
      continue;
    cells.clear();
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
    uint32_t code = 0;
    for (size_t i = 0; i < column.size(); ++i) {
      StringRef v = cells[column[i]];
      // The common case, a bare digit, without trimming.
      if (v.size() != 1)
        v = v.trim();
      if (v.size() != 1 || (v[0] != '0' && v[0] != '1')) {
        diag.error(loc(cells[column[i]]), "expected 0 or 1 for '" +
                                              ea.signals[i] + "', found '" + v +
                                              "'");
        return false;
      }
      vec[i] = v[0];
      code = (code << 1) | uint32_t(v[0] == '1');
    }
    ++r.vectors;
    if (r.stopped)
      continue; // read on to check the rest of the file is well formed
    const EditTransition *t;
    if (!table.empty()) {
      int32_t ti = table[(size_t(state) << k) | code];
      t = ti < 0 ? nullptr : &ea.transitions[ti];
    } else {
      t = ea.step(state, vec);
    }
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

int netlift::enforce::enforceAndJudge(const EditAutomaton &ea,
                                      unsigned bufferID, DiagEngine &diag,
                                      llvm::raw_ostream &out,
                                      llvm::raw_ostream *csv,
                                      EnforceResult *result) {
  if (csv) {
    for (size_t i = 0; i < ea.signals.size(); ++i)
      *csv << (i ? "," : "") << ea.signals[i];
    *csv << "\n";
  }
  EnforceResult r;
  uint64_t emitted = 0;
  auto vector = [&](const std::string &v) {
    ++emitted;
    out << v << "\n";
    if (csv) {
      for (size_t i = 0; i < v.size(); ++i)
        *csv << (i ? "," : "") << v[i];
      *csv << "\n";
    }
  };
  if (!enforceTrace(ea, bufferID, diag, vector, r))
    return 1;
  if (result)
    *result = r;
  if (r.conform) {
    out << "verdict: conform (" << r.vectors << " vectors read, " << emitted
        << " emitted)\n";
    return 0;
  }
  if (r.stopped) {
    out << "verdict: not conform: stopped at vector " << r.stopIndex << " ("
        << r.stopVector << "); expected one of:";
    for (const std::string &e : r.expected)
      out << ' ' << e;
    out << "\n";
  } else {
    out << "verdict: not conform: the trace ends inside a desynchronised "
           "reading (an intermediate state)\n";
  }
  return 3;
}

void netlift::enforce::writeEditAutomatonDot(const EditAutomaton &ea,
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

void netlift::enforce::writeEditAutomatonTable(const EditAutomaton &ea,
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
