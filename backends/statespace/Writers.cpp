//===- Writers.cpp - state spaces as files --------------------------------===//
#include "backends/statespace/Writers.h"
#include "backends/statespace/ReplayLog.h"
#include "backends/statespace/StateColumns.h"
#include "engine/TraceValues.h"
#include "ir/support/OutputFile.h"

#include "ir/net/Builder.h"
#include "ir/net/FloatOps.h"
#include "ir/net/ScanResets.h"
#include "ir/net/StringOps.h"

#include "llvm/Support/JSON.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

using namespace netlift;
using namespace netlift::engine;
using namespace netlift::statespace;
using namespace netlift::net;
using namespace netlift::statespace::listing;

void netlift::statespace::writeAut(const Explorer &x, llvm::raw_ostream &os) {
  os << "des (0, " << x.edges().size() << ", " << x.store().size() << ")\n";
  for (const Edge &e : x.edges())
    os << '(' << e.from << ",\"" << x.label(e.label) << "\"," << e.to << ")\n";
}

namespace {
std::vector<char> deadlockFlags(const Explorer &x, const ExploreResult &r) {
  std::vector<char> flags(x.store().size(), 0);
  for (uint32_t d : r.deadlocks)
    flags[d] = 1;
  return flags;
}
} // namespace

std::vector<StateColumn> listing::stateColumns(const sem::Semantics &sem,
                                               bool stateFile) {
  const sem::StateLayout &L = sem.layout();
  const Module &m = sem.module();
  std::vector<StateColumn> out;
  llvm::DenseSet<uint32_t> unkept;
  if (stateFile && sem.options().scanResets)
    unkept = net::scanResetVars(m);
  for (uint32_t p = 0; p < m.places.size(); ++p)
    out.push_back({m.places[p].name.str(), StateColumn::Place, L.markingSlot(p),
                   nullptr});
  for (uint32_t p = 0; p < m.places.size(); ++p)
    if (L.clockSlot(p) >= 0)
      out.push_back({L.slots()[L.clockSlot(p)].name, StateColumn::Clock,
                     uint32_t(L.clockSlot(p)), nullptr});
  for (uint32_t v = 0; v < m.vars.size(); ++v) {
    int32_t first = L.varSlot(v);
    if (first < 0 || unkept.count(v))
      continue;
    for (uint32_t i = 0; i < sem::StateLayout::slotsOf(m.vars[v].type); ++i)
      if (const sem::Slot &s = L.slots()[first + i]; s.type)
        out.push_back(
            {s.name, StateColumn::Data, uint32_t(first + i), nullptr, s.type});
  }
  for (uint32_t p = 0; p < m.ports.size(); ++p) {
    const Port &port = m.ports[p];
    if (!port.isOutput() || port.kind == PortKind::Event)
      continue;
    if (port.definition) {
      out.push_back({port.name.str(), StateColumn::Output, 0, port.definition,
                     port.definition->type});
      continue;
    }
    int32_t first = L.portSlot(p);
    for (uint32_t i = 0; i < sem::StateLayout::slotsOf(port.type); ++i)
      if (const sem::Slot &s = L.slots()[first + i]; s.type)
        out.push_back({s.name, StateColumn::Output, uint32_t(first + i),
                       nullptr, s.type});
  }
  return out;
}

Cell listing::cellOf(sem::Semantics &sem, const StateColumn &a,
                     const uint64_t *state) {
  Cell c;
  sem::RuntimeError err;
  if (a.isString()) {
    if (a.def) {
      c.str = sem.evalStringInState(a.def, state, err);
    } else {
      const sem::StateLayout &L = sem.layout();
      int64_t len = L.get(state, a.slot);
      for (int64_t i = 1; i <= len; ++i)
        c.str += char16_t(L.get(state, a.slot + uint32_t(i)));
    }
    c.v = int64_t(c.str.size());
    c.text = formatStringLiteral({c.str.data(), c.str.size()});
    return c;
  }
  c.v = a.def ? sem.evalInState(a.def, state, err)
              : sem.layout().get(state, a.slot);
  c.text = formatScalar(a.type, c.v);
  return c;
}

std::string netlift::statespace::describeState(sem::Semantics &sem,
                                               const uint64_t *state,
                                               llvm::StringRef separator) {
  std::string out;
  for (const StateColumn &a : stateColumns(sem, /*stateFile=*/true)) {
    Cell c = cellOf(sem, a, state);
    if (a.kind == StateColumn::Place && c.v == 0)
      continue; // markings list the marked places only
    out += (out.empty() ? "" : separator.str()) + a.name + "=" + c.text;
  }
  return out;
}

void netlift::statespace::writeDot(const Explorer &x, sem::Semantics &sem,
                                   llvm::raw_ostream &os) {
  os << "digraph statespace {\n  node [shape=box, fontname=Helvetica];\n"
        "  edge [fontname=Helvetica, fontsize=10];\n";
  for (uint32_t s = 0; s < x.store().size(); ++s) {
    // A string's quotes and backslashes are escaped for dot.
    std::string values;
    for (char ch : describeState(sem, x.store().state(s), "\n")) {
      if (ch == '"' || ch == '\\')
        values += '\\';
      values += ch == '\n' ? std::string("\\n") : std::string(1, ch);
    }
    std::string label =
        "s" + std::to_string(s) + (values.empty() ? "" : "\\n" + values);
    os << "  s" << s << " [label=\"" << label << "\""
       << (s == 0 ? ", penwidth=2" : "") << "];\n";
  }
  for (const Edge &e : x.edges())
    os << "  s" << e.from << " -> s" << e.to << " [label=\"" << x.label(e.label)
       << "\"];\n";
  os << "}\n";
}

void netlift::statespace::writeArc(const Explorer &x, sem::Semantics &sem,
                                   llvm::raw_ostream &os) {
  std::vector<StateColumn> attrs = stateColumns(sem, /*stateFile=*/true);
  // Edges grouped by source state, each group in generation order.
  uint32_t n = x.store().size();
  std::vector<uint32_t> first(n + 1, 0);
  for (const Edge &e : x.edges())
    ++first[e.from + 1];
  for (uint32_t s = 0; s < n; ++s)
    first[s + 1] += first[s];
  std::vector<uint32_t> order(x.edges().size()),
      fill(first.begin(), first.end() - 1);
  for (uint32_t i = 0; i < x.edges().size(); ++i)
    order[fill[x.edges()[i].from]++] = i;
  for (uint32_t s = 0; s < n; ++s) {
    os << "state nr. " << s << "\n ";
    bool any = false;
    for (const StateColumn &a : attrs) {
      Cell c = cellOf(sem, a, x.store().state(s));
      if (a.kind == StateColumn::Place && c.v == 0)
        continue; // a marking lists its marked places
      os << " " << a.name << (a.kind == StateColumn::Place ? ":" : "=")
         << c.text;
      any = true;
    }
    if (!any)
      os << " (empty)";
    os << "\n";
    for (uint32_t i = first[s]; i < first[s + 1]; ++i) {
      const Edge &e = x.edges()[order[i]];
      os << "== " << x.label(e.label) << " ==> " << e.to << "\n";
    }
  }
}

void netlift::statespace::writeJson(const Explorer &x, sem::Semantics &sem,
                                    const ExploreResult &r,
                                    llvm::raw_ostream &os) {
  std::vector<StateColumn> attrs = stateColumns(sem, /*stateFile=*/true);
  std::vector<char> isDeadlock = deadlockFlags(x, r);
  llvm::json::OStream j(os, 1);
  j.object([&] {
    j.attribute("model", sem.module().name);
    j.attribute("complete", r.complete);
    j.attributeArray("attributes", [&] {
      for (const StateColumn &a : attrs)
        j.object([&] {
          j.attribute("name", a.name);
          static const char *kinds[] = {"place", "clock", "variable", "output"};
          j.attribute("kind", kinds[a.kind]);
        });
    });
    j.attributeArray("states", [&] {
      for (uint32_t s = 0; s < x.store().size(); ++s)
        j.object([&] {
          j.attribute("id", int64_t(s));
          if (isDeadlock[s])
            j.attribute("deadlock", true);
          j.attributeArray("values", [&] {
            for (const StateColumn &a : attrs) {
              Cell c = cellOf(sem, a, x.store().state(s));
              if (a.isString()) {
                j.value(toUtf8(c.str)); // the characters, not the literal
              } else if (!a.type || !a.type->isFloat()) {
                j.value(c.v);
              } else if (std::isfinite(floatValue(a.type->width, c.v))) {
                // Finite floats as JSON numbers, NaN and infinities as text.
                j.rawValue([&](llvm::raw_ostream &o) { o << c.text; });
              } else {
                j.value(c.text);
              }
            }
          });
        });
    });
    j.attributeArray("edges", [&] {
      for (const Edge &e : x.edges())
        j.object([&] {
          j.attribute("from", int64_t(e.from));
          j.attribute("label", x.label(e.label));
          j.attribute("to", int64_t(e.to));
        });
    });
  });
  os << "\n";
}

static std::string csvField(const std::string &f) {
  if (f.find_first_of(",\"\n") == std::string::npos)
    return f;
  std::string q = "\"";
  for (char c : f)
    q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void netlift::statespace::writeCsvStates(const Explorer &x, sem::Semantics &sem,
                                         const ExploreResult &r,
                                         llvm::raw_ostream &os) {
  std::vector<StateColumn> attrs = stateColumns(sem, /*stateFile=*/true);
  std::vector<char> isDeadlock = deadlockFlags(x, r);
  os << "id,deadlock";
  for (const StateColumn &a : attrs)
    os << ',' << csvField(a.name);
  os << '\n';
  for (uint32_t s = 0; s < x.store().size(); ++s) {
    os << s << ',' << int(isDeadlock[s]);
    for (const StateColumn &a : attrs) {
      Cell c = cellOf(sem, a, x.store().state(s));
      os << ',' << csvField(a.isString() ? toUtf8(c.str) : c.text);
    }
    os << '\n';
  }
}

void netlift::statespace::writeCsvEdges(const Explorer &x,
                                        llvm::raw_ostream &os) {
  os << "from,label,to\n";
  for (const Edge &e : x.edges())
    os << e.from << ',' << csvField(x.label(e.label)) << ',' << e.to << '\n';
}

void netlift::statespace::writeSummaryJson(const Explorer &x,
                                           const ExploreResult &r,
                                           llvm::raw_ostream &os,
                                           llvm::StringRef extraFields) {
  // Written by hand to keep the numbers short and the key order fixed.
  double secs = std::max(r.seconds, 1e-9);
  size_t states = x.store().size();
  os << fmt::format(
      "{{\"states\":{},\"transitions\":{},\"deadlocks\":{},"
      "\"dead_states\":{},\"max_tokens_in_place\":{},"
      "\"max_tokens_per_marking\":{},\"seconds\":{:.6f},"
      "\"states_per_second\":{:.0f},\"peak_bytes\":{},"
      "\"bytes_per_state\":{:.2f},\"state_vector_bytes\":{},"
      "\"complete\":{}",
      states, r.edges, r.deadlocks.size(), r.deadStates, r.maxTokensInPlace,
      r.maxTokensPerMarking, r.seconds, states / secs, r.peakBytes,
      states ? double(x.store().storedBytes()) / states : 0.0,
      x.store().wordsPerState() * 8, r.complete ? "true" : "false");
  if (!r.limitReached.empty())
    os << ",\"limit\":\"" << r.limitReached << "\"";
  // Executions of the step per expanded state: one per class of input
  // valuations (split) or per valuation (enumerate).
  uint64_t expanded = 0, runs = 0;
  for (auto &[classes, n] : r.inputClasses) {
    expanded += n;
    runs += classes * n;
  }
  if (expanded) { // counted only for models with free inputs
    uint64_t median = 0, seen = 0;
    for (auto &[classes, n] : r.inputClasses)
      if ((seen += n) * 2 >= expanded) {
        median = classes;
        break;
      }
    os << fmt::format(
        ",\"inputs\":\"{}\",\"input_classes\":{{\"min\":{},"
        "\"median\":{},\"max\":{},\"mean\":{:.2f}}}",
        x.semantics().options().splitInputs ? "split" : "enumerate",
        r.inputClasses.begin()->first, median, r.inputClasses.rbegin()->first,
        double(runs) / double(expanded));
  }
  os << extraFields << "}\n";
}

void netlift::statespace::writeTrace(const Explorer &x, sem::Semantics &sem,
                                     uint32_t target, llvm::raw_ostream &os,
                                     const TraceView &view) {
  writePath(x, sem, x.pathTo(target), os, view);
}

void netlift::statespace::withInputClasses(
    sem::Semantics &sem, std::vector<std::string> &labels,
    llvm::ArrayRef<const uint64_t *> states) {
  if (!sem.hasFreeInputs())
    return;
  // The same successors, split with their conditions (whatever mode the
  // exploration ran in: splitting gives exactly the enumerated successors).
  sem::Options o = sem.options();
  o.splitInputs = true;
  o.inputConditions = true;
  sem::Semantics replay(sem.module(), sem.layout(), o);
  uint32_t words = sem.layout().numWords();
  for (size_t i = 1; i < states.size() && i < labels.size(); ++i) {
    if (labels[i] == "tick")
      continue;
    std::string classes;
    sem::RuntimeError err;
    replay.successors(
        states[i - 1],
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          if (classes.empty() &&
              Explorer::stepText(sem.module(), step) == labels[i] &&
              std::equal(succ, succ + words, states[i]))
            classes = replay.edgeCondition();
        },
        err);
    if (!classes.empty())
      labels[i] += " " + classes;
  }
}

static PlcPath labelledPath(const Explorer &x, sem::Semantics &sem,
                            llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
                            std::vector<std::string> &labels);

void netlift::statespace::writePath(
    const Explorer &x, sem::Semantics &sem,
    llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path, llvm::raw_ostream &os,
    const TraceView &view, int64_t loopTo, uint32_t loopLabel) {
  // Which inputs took each step (issue 40), unless the labels say it.
  std::vector<std::string> labels;
  PlcPath plc = labelledPath(x, sem, path, labels);
  writeStatePath(plc.in(sem), labels, plc.states, os, view, loopTo,
                 loopLabel == Explorer::kNone ? "" : x.label(loopLabel));
}

llvm::json::Value listing::jsonOf(const StateColumn &a, const Cell &c) {
  if (a.isString())
    return toUtf8(c.str);
  double d;
  if (llvm::to_float(c.text, d) && std::isfinite(d))
    return c.text.find_first_of(".eE") == std::string::npos
               ? llvm::json::Value(int64_t(c.v))
               : llvm::json::Value(d);
  return c.text;
}

void statespace::writeJsonSteps(sem::Semantics &sem,
                                llvm::ArrayRef<std::string> labels,
                                llvm::ArrayRef<const uint64_t *> states,
                                const std::optional<net::Timescale> &tick,
                                llvm::json::OStream &j) {
  std::vector<StateColumn> attrs = stateColumns(sem);
  auto value = [&](const StateColumn &a, const Cell &c) {
    j.value(jsonOf(a, c));
  };
  j.attribute("time_unit", tick
                               ? std::to_string(tick->amount) + tick->unit.str()
                               : std::string("tick"));
  j.attributeArray("steps", [&] {
    std::vector<Cell> prev;
    uint64_t ticks = 0;
    for (size_t i = 0; i < states.size(); ++i) {
      llvm::StringRef label = i == 0 ? "" : llvm::StringRef(labels[i]);
      auto [step, inputs] = label.split(" [");
      if (step == "tick")
        ++ticks;
      std::vector<Cell> cur;
      for (const StateColumn &a : attrs)
        cur.push_back(cellOf(sem, a, states[i]));
      j.object([&] {
        j.attribute("step", int64_t(i));
        j.attribute("label", i == 0 ? "(initial)" : step.str());
        if (inputs.empty())
          j.attribute("inputs", nullptr);
        else
          j.attribute("inputs", "[" + inputs.str());
        j.attribute("time", int64_t(ticks));
        j.attributeObject(i == 0 ? "values" : "changes", [&] {
          for (size_t k = 0; k < attrs.size(); ++k)
            if (i == 0 || cur[k] != prev[k]) {
              j.attributeBegin(attrs[k].name);
              value(attrs[k], cur[k]);
              j.attributeEnd();
            }
        });
      });
      prev = std::move(cur);
    }
  });
}

/// A path's step labels (with the input classes that took each step,
/// unless the labels already say them) and its states, with the values the
/// PLC has (TraceValues.h).
static PlcPath labelledPath(const Explorer &x, sem::Semantics &sem,
                            llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
                            std::vector<std::string> &labels) {
  std::vector<const uint64_t *> states;
  for (const auto &[l, st] : path) {
    labels.push_back(l == Explorer::kNone ? "" : x.label(l));
    states.push_back(x.store().state(st));
  }
  PlcPath plc = plcValues(sem, labels, states);
  if (!x.options().inputLabels)
    withInputClasses(plc.in(sem), labels, plc.states);
  return plc;
}

/// The JSON trace document (docs/formats.md, "JSON traces").
static void writeJsonTrace(const TraceFileHeader &header, const Explorer &x,
                           sem::Semantics &sem,
                           const std::optional<net::Timescale> &tick,
                           llvm::ArrayRef<std::pair<uint32_t, uint32_t>> path,
                           llvm::ArrayRef<std::string> labels,
                           llvm::ArrayRef<const uint64_t *> states,
                           int64_t loopTo, uint32_t loopLabel,
                           llvm::raw_ostream &os) {
  auto label = [&](uint32_t l) {
    return l == Explorer::kNone ? std::string("tau") : x.label(l);
  };
  llvm::json::OStream j(os, 1);
  j.object([&] {
    j.attribute("formula", header.formula);
    j.attribute("holds", header.holds);
    j.attribute("trace", header.witness ? "witness" : "counterexample");
    j.attribute("claim", header.claim);
    j.attributeArray("states", [&] {
      for (const auto &step : path)
        j.value(int64_t(step.second));
    });
    j.attributeArray("labels", [&] {
      for (size_t i = 1; i < path.size(); ++i)
        j.value(label(path[i].first));
    });
    if (loopTo >= 0) {
      j.attribute("loop_to", loopTo);
      j.attribute("loop_label", label(loopLabel));
    } else {
      j.attribute("loop_to", nullptr);
    }
    writeJsonSteps(sem, labels, states, tick, j);
  });
  os << "\n";
}

static bool verifyTraceFiles = false;

void statespace::setTraceFileVerification(bool on) { verifyTraceFiles = on; }

/// A JSON trace just written, read back and replayed (replayTrace) when
/// setTraceFileVerification asks.
static bool verifyJsonTrace(sem::Semantics &sem, llvm::StringRef file,
                            DiagEngine &diag) {
  if (!verifyTraceFiles || file == "-")
    return true;
  unsigned id = addInputFile(diag.sourceMgr(), file);
  if (!id)
    return false;
  llvm::raw_null_ostream quiet;
  if (replayTrace(sem, id, TraceView{}, ReplayLogOptions{}, diag, quiet) == 0)
    return true;
  diag.error(llvm::SMLoc(), "trace verification: the model does not follow "
                            "the JSON trace it wrote to '" +
                                file + "'");
  return false;
}

bool statespace::writeJsonTraceFile(const Explorer &x, sem::Semantics &sem,
                                    uint32_t target,
                                    const TraceFileHeader &header,
                                    const std::optional<net::Timescale> &tick,
                                    llvm::StringRef file, DiagEngine &diag) {
  auto path = x.pathTo(target);
  std::vector<std::string> labels;
  PlcPath plc = labelledPath(x, sem, path, labels);
  return writeOutputFile(
             file,
             [&](llvm::raw_ostream &os) {
               writeJsonTrace(header, x, plc.in(sem), tick, path, labels,
                              plc.states, -1, Explorer::kNone, os);
             },
             diag) &&
         verifyJsonTrace(plc.in(sem), file, diag);
}

void statespace::writeVcd(sem::Semantics &sem,
                          llvm::ArrayRef<std::string> labels,
                          llvm::ArrayRef<const uint64_t *> states,
                          const std::optional<net::Timescale> &tick,
                          llvm::raw_ostream &os) {
  // VCD's time unit is a power of ten of a second: the tick's own unit
  // when it has one, each tick `amount` of them.
  std::string unit = "ns";
  uint64_t perTick = 1;
  if (tick) {
    llvm::StringRef u = tick->unit;
    if (u == "s" || u == "ms" || u == "us" || u == "ns") {
      unit = u.str();
      perTick = tick->amount;
    } else {
      perTick = tick->nanoseconds();
    }
  }
  // Identifiers: printable ASCII from '!', in base 94.
  auto idOf = [](size_t n) {
    std::string id;
    do {
      id += char('!' + n % 94);
      n /= 94;
    } while (n);
    return id;
  };
  // A reference name: no spaces, and brackets are VCD's bit selects.
  auto nameOf = [](std::string n) {
    for (char &c : n)
      c = c == '[' ? '(' : c == ']' ? ')' : c == ' ' ? '_' : c;
    return n;
  };
  std::vector<StateColumn> cols;
  std::vector<std::string> strings;
  for (StateColumn &c : stateColumns(sem)) {
    if (c.kind == StateColumn::Place || c.kind == StateColumn::Clock)
      continue;
    if (c.isString())
      strings.push_back(c.name);
    else
      cols.push_back(c);
  }
  // The free inputs: each time shows the smallest valuation of the class
  // that took its scan (`{scan} [go=1, level=91..100]`), `x` where the
  // step did not depend on an input ([any]) or no class is known.
  struct InputColumn {
    std::string name;
    bool isBool;
  };
  std::vector<InputColumn> inputs;
  for (const Port &port : sem.module().ports)
    if (port.isInput() && port.kind != PortKind::Event &&
        (port.kind == PortKind::Cond ||
         (port.type && (port.type->isInteger() || port.type->isBool()))))
      inputs.push_back({port.name.str(),
                        port.kind == PortKind::Cond || port.type->isBool()});
  auto classOf = [](llvm::StringRef label) {
    std::map<std::string, int64_t> values;
    size_t open = label.find(" [");
    if (open == llvm::StringRef::npos)
      return values;
    llvm::StringRef body = label.drop_front(open + 2);
    body = body.take_until([](char c) { return c == ']'; });
    llvm::SmallVector<llvm::StringRef, 8> items;
    body.split(items, ", ");
    for (llvm::StringRef item : items) {
      auto [name, value] = item.split('=');
      int64_t v;
      if (!value.split("..").first.getAsInteger(10, v))
        values[name.str()] = v;
    }
    return values;
  };
  os << "$version netlift $end\n"
     << "$timescale 1 " << unit << " $end\n"
     << "$scope module " << nameOf(sem.module().name.str()) << " $end\n";
  os << "$var integer 32 " << idOf(0) << " step $end\n";
  for (size_t i = 0; i < cols.size(); ++i) {
    const StateColumn &c = cols[i];
    const char *kind = c.type->isBool()                        ? "wire 1"
                       : c.type->isReal() || c.type->isFloat() ? "real 64"
                                                               : "integer 64";
    os << "$var " << kind << " " << idOf(i + 1) << " " << nameOf(c.name)
       << " $end\n";
  }
  for (size_t i = 0; i < inputs.size(); ++i)
    os << "$var " << (inputs[i].isBool ? "wire 1 " : "integer 64 ")
       << idOf(cols.size() + 1 + i) << " " << nameOf(inputs[i].name)
       << " $end\n";
  os << "$upscope $end\n";
  for (const std::string &n : strings)
    os << "$comment " << nameOf(n)
       << ": a string, which VCD cannot show $end\n";
  os << "$enddefinitions $end\n";
  // Two's complement, leading zeros left out.
  auto vector = [](int64_t v, const std::string &id) {
    std::string bits;
    for (int b = 63; b >= 0; --b)
      bits += (uint64_t(v) >> b) & 1 ? '1' : '0';
    size_t first = bits.find('1');
    return "b" + (first == std::string::npos ? "0" : bits.substr(first)) + " " +
           id;
  };
  auto valueText = [&](const StateColumn &c, const Cell &cell,
                       const std::string &id) -> std::string {
    if (c.type->isBool())
      return (cell.v ? "1" : "0") + id;
    if (c.type->isReal() || c.type->isFloat())
      return "r" + cell.text + " " + id;
    return vector(cell.v, id);
  };
  std::vector<std::string> shown(cols.size() + inputs.size());
  std::string shownStep;
  std::map<std::string, int64_t> chosen; // the inputs of the current time
  uint64_t time = 0;
  bool started = false;
  for (size_t i = 0; i < states.size(); ++i) {
    if (i > 0 && i < labels.size() && labels[i] == "tick") {
      time += perTick;
      chosen.clear();
    } else if (i > 0 && i < labels.size() &&
               labels[i].find(" [") != std::string::npos) {
      chosen = classOf(labels[i]);
    }
    // A time's values are those after its last step.
    bool last = i + 1 == states.size() ||
                (i + 1 < labels.size() && labels[i + 1] == "tick");
    if (!last)
      continue;
    std::string changes;
    std::string step = vector(int64_t(i), idOf(0));
    if (!started || step != shownStep)
      changes += step + "\n";
    shownStep = step;
    for (size_t k = 0; k < cols.size(); ++k) {
      std::string v =
          valueText(cols[k], cellOf(sem, cols[k], states[i]), idOf(k + 1));
      if (!started || v != shown[k])
        changes += v + "\n";
      shown[k] = v;
    }
    for (size_t k = 0; k < inputs.size(); ++k) {
      std::string id = idOf(cols.size() + 1 + k);
      auto it = chosen.find(inputs[k].name);
      std::string v = it == chosen.end()
                          ? (inputs[k].isBool ? "x" + id : "bx " + id)
                      : inputs[k].isBool ? (it->second ? "1" : "0") + id
                                         : vector(it->second, id);
      if (!started || v != shown[cols.size() + k])
        changes += v + "\n";
      shown[cols.size() + k] = v;
    }
    os << "#" << time << "\n";
    if (!started)
      os << "$dumpvars\n" << changes << "$end\n";
    else
      os << changes;
    started = true;
  }
}

bool statespace::writeVcdFile(const Explorer &x, sem::Semantics &sem,
                              uint32_t target,
                              const std::optional<net::Timescale> &tick,
                              llvm::StringRef file, DiagEngine &diag) {
  // The inputs of each step, as the text trace shows them.
  std::vector<std::string> labels;
  PlcPath plc = labelledPath(x, sem, x.pathTo(target), labels);
  return writeOutputFile(
      file.str(),
      [&](llvm::raw_ostream &os) {
        writeVcd(plc.in(sem), labels, plc.states, tick, os);
      },
      diag);
}

bool statespace::writeHtmlTraceFile(const Explorer &x, sem::Semantics &sem,
                                    uint32_t target,
                                    const TraceFileHeader &header,
                                    const TraceView &view, llvm::StringRef file,
                                    DiagEngine &diag) {
  std::vector<std::string> labels;
  PlcPath plc = labelledPath(x, sem, x.pathTo(target), labels);
  return writeOutputFile(
      file.str(),
      [&](llvm::raw_ostream &os) {
        writeHtmlTrace(plc.in(sem), labels, plc.states, header, view, -1, "",
                       os);
      },
      diag);
}

bool statespace::writeTraceFiles(
    const std::string &base, const TraceFileHeader &header, const Explorer &x,
    sem::Semantics &sem, const TraceView &view,
    llvm::ArrayRef<std::pair<uint32_t, uint32_t>> steps, int64_t loopTo,
    uint32_t loopLabel, DiagEngine &diag) {
  auto label = [&](uint32_t l) {
    return l == Explorer::kNone ? std::string("tau") : x.label(l);
  };
  const std::optional<net::Timescale> &tick = view.tick;
  std::vector<std::string> labels;
  PlcPath plc = labelledPath(x, sem, steps, labels);
  sem::Semantics &shown = plc.in(sem);
  const std::vector<const uint64_t *> &states = plc.states;
  bool ok = writeOutputFile(
      base + ".json",
      [&](llvm::raw_ostream &os) {
        writeJsonTrace(header, x, shown, tick, steps, labels, states, loopTo,
                       loopLabel, os);
      },
      diag);
  ok = ok && verifyJsonTrace(shown, base + ".json", diag);
  ok = ok &&
       writeOutputFile(
           base + ".html",
           [&](llvm::raw_ostream &os) {
             writeHtmlTrace(
                 shown, labels, states, header, view, loopTo,
                 loopLabel == Explorer::kNone ? "" : x.label(loopLabel), os);
           },
           diag);
  ok = ok && writeOutputFile(
                 base + ".vcd",
                 [&](llvm::raw_ostream &os) {
                   writeVcd(shown, labels, states, tick, os);
                 },
                 diag);
  // Labels as `reach --format aut` writes them.
  return ok && writeOutputFile(
                   base + ".aut",
                   [&](llvm::raw_ostream &os) {
                     size_t edges = steps.size() - 1 + (loopTo >= 0);
                     os << "des (0, " << edges << ", " << steps.size() << ")\n";
                     for (size_t i = 1; i < steps.size(); ++i)
                       os << "(" << i - 1 << ",\"" << label(steps[i].first)
                          << "\"," << i << ")\n";
                     if (loopTo >= 0)
                       os << "(" << steps.size() - 1 << ",\""
                          << label(loopLabel) << "\"," << loopTo << ")\n";
                   },
                   diag);
}

void statespace::writeSummaryText(const Explorer &x, const ExploreResult &r,
                                  llvm::raw_ostream &os) {
  os << "states: " << x.store().size() << "\n"
     << "transitions: " << r.edges << "\n"
     << "deadlocks: " << r.deadlocks.size() << "\n"
     << "dead states: " << r.deadStates << "\n"
     << "complete: " << (r.complete ? "yes" : "no") << "\n";
}

int statespace::reportSearch(const Explorer &x, sem::Semantics &sem,
                             const ExploreResult &r, llvm::StringRef findText,
                             bool deadlockTrace, int code,
                             llvm::raw_ostream &out, const TraceView &view,
                             llvm::StringRef vcdFile, DiagEngine *diag) {
  auto vcd = [&](uint32_t target) {
    return vcdFile.empty() || !diag ||
           writeVcdFile(x, sem, target, view.tick, vcdFile, *diag);
  };
  if (!findText.empty()) {
    if (r.found) {
      out << "found a state satisfying '" << findText << "' after "
          << x.pathTo(*r.found).size() - 1 << " steps:\n";
      writeTrace(x, sem, *r.found, out, view);
      return vcd(*r.found) ? 0 : 1;
    }
    if (code == 0) {
      out << "no reachable state satisfies '" << findText << "'\n";
      return 3;
    }
  }
  if (deadlockTrace) {
    if (!r.deadlocks.empty()) {
      // Breadth-first numbering: the smallest index is a closest deadlock.
      uint32_t d = *std::min_element(r.deadlocks.begin(), r.deadlocks.end());
      out << "deadlock after " << x.pathTo(d).size() - 1 << " steps:\n";
      writeTrace(x, sem, d, out, view);
      return vcd(d) ? 3 : 1;
    }
    if (code == 0)
      out << "no deadlock\n";
  }
  return code;
}

void statespace::writeStateSpace(GraphFormat format, const Explorer &x,
                                 sem::Semantics &sem, const ExploreResult &r,
                                 llvm::raw_ostream &os) {
  switch (format) {
  case GraphFormat::None:
    break;
  case GraphFormat::Aut:
    writeAut(x, os);
    break;
  case GraphFormat::Dot:
    writeDot(x, sem, os);
    break;
  case GraphFormat::Json:
    writeJson(x, sem, r, os);
    break;
  case GraphFormat::Csv:
    writeCsvStates(x, sem, r, os);
    break;
  case GraphFormat::Arc:
    writeArc(x, sem, os);
    break;
  }
}
