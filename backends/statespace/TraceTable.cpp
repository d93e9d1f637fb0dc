//===- TraceTable.cpp - a path as a table of steps ------------------------===//
//
// The text view of a trace (docs/reach.md, "Traces"). By default it is the
// program's view: one row per step that is not a tick, time folded into a
// column in the design's unit, the inputs that took the step, then the
// outputs and the other values it changed, with clocks and what frontends
// generated (kInternalAttribute) hidden. --trace-internals gives the net's
// view instead: every step and every name.
//
//===----------------------------------------------------------------------===//
#include "backends/statespace/StateColumns.h"
#include "backends/statespace/Writers.h"

#include "llvm/ADT/StringSet.h"

#include <fmt/format.h>

#include <algorithm>

using namespace netlift;
using namespace netlift::engine;
using namespace netlift::statespace;
using namespace netlift::statespace::listing;

namespace {

/// The targets of the module's `internal` attributes: entities and scopes.
llvm::StringSet<> internalTargets(const net::Module &m) {
  llvm::StringSet<> out;
  for (const net::Attribute &a : m.attributes)
    if (a.key == net::kInternalAttribute && !a.target.empty())
      out.insert(a.target);
  return out;
}

/// Is the column (a variable's leaf `q`, `buf[2]`, `r.f`, or a place) one
/// of the internal entities, or under an internal scope?
bool isInternal(llvm::StringRef name, const llvm::StringSet<> &targets) {
  if (targets.empty())
    return false;
  while (!name.empty()) {
    if (targets.count(name))
      return true;
    size_t cut = name.find_last_of(".[");
    if (cut == llvm::StringRef::npos)
      return false;
    name = name.take_front(cut);
  }
  return false;
}

/// Whether the program's view leaves the column out: clocks (time has its
/// own column) and internal names.
bool hiddenColumn(const StateColumn &c, const llvm::StringSet<> &targets) {
  if (c.kind == StateColumn::Clock || (c.type && c.type->isClock()))
    return true;
  return isInternal(c.name, targets);
}

/// `{scan} [go=1]` -> (`{scan}`, `go=1`): the transitions and the inputs
/// that took them (withInputClasses); a class that any input takes shows
/// no inputs.
std::pair<std::string, std::string> splitLabel(llvm::StringRef label) {
  size_t at = label.find(" [");
  if (at == llvm::StringRef::npos)
    return {label.str(), ""};
  llvm::StringRef taken = label.take_front(at);
  llvm::StringRef inputs = label.drop_front(at + 1);
  llvm::SmallVector<llvm::StringRef, 4> classes;
  inputs.split(classes, " | ");
  if (llvm::all_of(classes, [](llvm::StringRef c) { return c == "[any]"; }))
    return {taken.str(), ""};
  if (classes.size() == 1 && inputs.startswith("[") && inputs.endswith("]"))
    inputs = inputs.drop_front().drop_back();
  return {taken.str(), inputs.str()};
}

/// `{a,_gen.b}` without the transitions of internal scopes (unless every
/// one is).
std::string withoutInternal(const std::string &taken,
                            const llvm::StringSet<> &targets) {
  llvm::StringRef t(taken);
  if (!t.consume_front("{") || !t.consume_back("}"))
    return taken;
  llvm::SmallVector<llvm::StringRef, 4> names;
  t.split(names, ',');
  std::string kept;
  for (llvm::StringRef n : names)
    if (!isInternal(n, targets))
      kept += (kept.empty() ? "" : ",") + n.str();
  return kept.empty() ? taken : "{" + kept + "}";
}

std::string timeText(uint64_t ticks,
                     const std::optional<net::Timescale> &tick) {
  if (!tick)
    return std::to_string(ticks);
  return std::to_string(ticks * tick->amount) + " " + tick->unit.str();
}

void append(std::string &list, const std::string &item) {
  list += (list.empty() ? "" : ", ") + item;
}

/// What each step of the path executed: the step run again from the state
/// before it (split, recording), the log of the run that leads to the
/// state after it. Empty for ticks and steps without actions.
std::vector<sem::Semantics::ExecutionLog>
executedSteps(sem::Semantics &sem, llvm::ArrayRef<std::string> labels,
              llvm::ArrayRef<const uint64_t *> states) {
  std::vector<sem::Semantics::ExecutionLog> out(states.size());
  sem::Options o = sem.options();
  o.splitInputs = true;
  o.inputConditions = false;
  sem::Semantics replay(sem.module(), sem.layout(), o);
  replay.recordExecution(true);
  uint32_t words = sem.layout().numWords();
  for (size_t i = 1; i < states.size() && i < labels.size(); ++i) {
    if (labels[i] == "tick")
      continue;
    std::string taken = splitLabel(labels[i]).first;
    bool found = false;
    sem::RuntimeError err;
    replay.successors(
        states[i - 1],
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          if (!found && Explorer::stepText(sem.module(), step) == taken &&
              std::equal(succ, succ + words, states[i])) {
            out[i] = replay.lastExecution();
            found = true;
          }
        },
        err);
  }
  return out;
}

/// `delay.st:7` for a location in a file the user gave; empty for
/// netlift's own library and generated text (buffers named `<...>`), and
/// unless `netir`, for NetIR files (`.net`: the model itself, not the
/// program it was translated from).
std::string sourceLine(const llvm::SourceMgr &sm, llvm::SMLoc loc,
                       bool netir = true) {
  if (!loc.isValid())
    return "";
  unsigned id = sm.FindBufferContainingLoc(loc);
  if (!id)
    return "";
  llvm::StringRef name = sm.getMemoryBuffer(id)->getBufferIdentifier();
  if (name.startswith("<") || (!netir && name.endswith(".net")))
    return "";
  size_t slash = name.find_last_of('/');
  if (slash != llvm::StringRef::npos)
    name = name.drop_front(slash + 1);
  return name.str() + ":" + std::to_string(sm.getLineAndColumn(loc, id).first);
}

/// The value of attribute `name` in a start tag's attribute text.
llvm::StringRef xmlAttribute(llvm::StringRef attrs, llvm::StringRef name) {
  for (size_t at = attrs.find(name); at != llvm::StringRef::npos;
       at = attrs.find(name, at + 1)) {
    llvm::StringRef after = attrs.drop_front(at + name.size());
    if (at > 0 && isspace((unsigned char)attrs[at - 1]) &&
        after.consume_front("=\""))
      return after.take_until([](char c) { return c == '"'; });
  }
  return "";
}

/// ` coil 111` where a location is a PLCopen graphical element (its XML
/// start tag with a localId: a contact, coil or block of a rung), the name
/// by which an LD or FBD editor finds it; ` block 32 PT` for a block's
/// formal parameter; empty elsewhere.
std::string graphicalElement(const llvm::SourceMgr &sm, llvm::SMLoc loc) {
  const llvm::MemoryBuffer *buf =
      sm.getMemoryBuffer(sm.FindBufferContainingLoc(loc));
  llvm::StringRef rest(loc.getPointer(),
                       buf->getBufferEnd() - loc.getPointer());
  if (!rest.consume_front("<"))
    return "";
  llvm::StringRef tag = rest.take_while(
      [](char c) { return isalnum((unsigned char)c) || c == '_'; });
  llvm::StringRef attrs = rest.take_until([](char c) { return c == '>'; });
  if (tag.empty())
    return "";
  if (llvm::StringRef id = xmlAttribute(attrs, "localId"); !id.empty())
    return " " + tag.str() + " " + id.str();
  // A formal parameter is inside its block's start and end tags: the
  // nearest block opened before it.
  llvm::StringRef param = xmlAttribute(attrs, "formalParameter");
  if (tag != "variable" || param.empty())
    return "";
  llvm::StringRef before(buf->getBufferStart(),
                         loc.getPointer() - buf->getBufferStart());
  size_t open = before.rfind("<block ");
  if (open == llvm::StringRef::npos)
    return "";
  llvm::StringRef blockAttrs =
      before.drop_front(open).take_until([](char c) { return c == '>'; });
  llvm::StringRef id = xmlAttribute(blockAttrs, "localId");
  return id.empty() ? "" : " block " + id.str() + " " + param.str();
}

/// `ran delay.st:6,7, rungs.xml:40`: the lines a step executed, in order,
/// a line repeated at once (a statement and the branch on its line) once.
std::string ranLines(const llvm::SourceMgr &sm,
                     const sem::Semantics::ExecutionLog &log) {
  std::string out, file, last;
  for (llvm::SMLoc loc : log.statements) {
    std::string where = sourceLine(sm, loc);
    if (where.empty() || where == last)
      continue;
    last = where;
    auto [f, line] = llvm::StringRef(where).rsplit(':');
    if (f == file) {
      out += "," + line.str();
      continue;
    }
    file = f.str();
    out += (out.empty() ? "" : ", ") + where;
  }
  return out;
}

/// The source line of the assignment that wrote `slot` last in the step
/// (NetIR lines with --trace-source only).
std::string writtenAt(const llvm::SourceMgr *sm,
                      const sem::Semantics::ExecutionLog &log, uint32_t slot,
                      bool netir) {
  if (!sm)
    return "";
  for (auto it = log.writes.rbegin(); it != log.writes.rend(); ++it)
    if (it->first == slot) {
      std::string line = sourceLine(*sm, it->second, netir);
      return line.empty() ? line : line + graphicalElement(*sm, it->second);
    }
  return "";
}

/// The net's view: every step and every name.
void writeInternalsTable(sem::Semantics &sem,
                         llvm::ArrayRef<std::string> labels,
                         llvm::ArrayRef<const uint64_t *> states,
                         llvm::raw_ostream &os, const TraceView &view,
                         int64_t loopTo, llvm::StringRef loopLabel) {
  std::vector<sem::Semantics::ExecutionLog> logs;
  if (view.source && view.sources)
    logs = executedSteps(sem, labels, states);
  std::vector<StateColumn> attrs = stateColumns(sem);
  std::vector<Cell> prev;
  size_t width = 9; // "(initial)"
  for (const std::string &l : labels)
    width = std::max(width, l.size());
  os << fmt::format("{:>4}  {:<{}}  {}\n", "step", "label", width,
                    "values (initial) / changes");
  for (size_t i = 0; i < states.size(); ++i) {
    std::vector<Cell> cur;
    for (const StateColumn &a : attrs)
      cur.push_back(cellOf(sem, a, states[i]));
    std::string changes;
    for (size_t k = 0; k < attrs.size(); ++k) {
      if (i == 0) {
        if (attrs[k].kind == StateColumn::Place && cur[k].v == 0)
          continue;
        append(changes, attrs[k].name + "=" + cur[k].text);
      } else if (cur[k] != prev[k]) {
        append(changes,
               attrs[k].name + ": " + prev[k].text + " -> " + cur[k].text);
      }
    }
    os << fmt::format("{:>4}  {:<{}}  {}\n", i,
                      i == 0 ? std::string("(initial)") : labels[i], width,
                      changes);
    if (!logs.empty())
      if (std::string ran = ranLines(*view.sources, logs[i]); !ran.empty())
        os << fmt::format("{:>4}  {:<{}}  ran {}\n", "", "", width, ran);
    prev = std::move(cur);
  }
  if (loopTo >= 0)
    os << fmt::format("{:>4}  {:<{}}  back to step {}, and so on forever\n", "",
                      loopLabel.str(), width, loopTo);
}

} // namespace

ProgramTrace listing::programTrace(sem::Semantics &sem,
                                   llvm::ArrayRef<std::string> labels,
                                   llvm::ArrayRef<const uint64_t *> states,
                                   const TraceView &view, bool withRan) {
  ProgramTrace out;
  out.timed = view.tick.has_value();
  std::vector<StateColumn> attrs = stateColumns(sem);
  llvm::StringSet<> targets = internalTargets(sem.module());
  for (StateColumn &a : attrs) {
    if (!hiddenColumn(a, targets))
      out.columns.push_back(std::move(a));
    else
      out.hiddenNames += a.kind != StateColumn::Clock;
  }
  std::vector<sem::Semantics::ExecutionLog> logs;
  if (view.sources)
    logs = executedSteps(sem, labels, states);
  std::vector<Cell> prev;
  uint64_t ticks = 0;
  for (size_t i = 0; i < states.size(); ++i) {
    TraceRow row;
    row.step = i;
    bool isTick = i > 0 && labels[i] == "tick";
    ticks += isTick;
    row.time = timeText(ticks, view.tick);
    bool any = false;
    for (const StateColumn &c : out.columns) {
      row.values.push_back(cellOf(sem, c, states[i]));
      bool changed = i > 0 && row.values.back() != prev[row.values.size() - 1];
      row.changed.push_back(changed);
      any |= changed;
      std::string at;
      if (changed && !logs.empty() && !c.def)
        at = writtenAt(view.sources, logs[i], c.slot, view.source);
      row.at.push_back(std::move(at));
    }
    prev = row.values;
    // A tick only moves clocks: it shows as the time of the next row,
    // unless it changed something shown or ends the path.
    if (isTick && !any && i + 1 < states.size())
      continue;
    if (i == 0) {
      row.taken = "(initial)";
    } else {
      std::tie(row.taken, row.inputs) = splitLabel(labels[i]);
      row.taken = withoutInternal(row.taken, targets);
      if (withRan && !logs.empty())
        row.ran = ranLines(*view.sources, logs[i]);
    }
    out.rows.push_back(std::move(row));
  }
  return out;
}

void statespace::writeStatePath(sem::Semantics &sem,
                                llvm::ArrayRef<std::string> labels,
                                llvm::ArrayRef<const uint64_t *> states,
                                llvm::raw_ostream &os, const TraceView &view,
                                int64_t loopTo, llvm::StringRef loopLabel) {
  if (view.internals) {
    writeInternalsTable(sem, labels, states, os, view, loopTo, loopLabel);
    return;
  }
  ProgramTrace trace = programTrace(sem, labels, states, view, view.source);
  // The text of each row: outputs, then the other values it changed (the
  // initial row: every value shown, marked places only).
  struct Text {
    std::string outputs, changed;
  };
  std::vector<Text> texts;
  std::string initialValues;
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const TraceRow &r = trace.rows[i];
    Text t;
    for (size_t k = 0; k < trace.columns.size(); ++k) {
      const StateColumn &c = trace.columns[k];
      std::string item;
      if (r.step == 0) {
        if (c.kind == StateColumn::Place && r.values[k].v == 0)
          continue;
        item = c.name + "=" + r.values[k].text;
      } else if (r.changed[k]) {
        // The value before: the last row's (a tick left out changed
        // nothing shown).
        item = c.name + ": " + trace.rows[i - 1].values[k].text + " -> " +
               r.values[k].text;
        if (!r.at[k].empty())
          item += " (" + r.at[k] + ")";
      } else {
        continue;
      }
      append(c.kind == StateColumn::Output ? t.outputs : t.changed, item);
    }
    if (r.step == 0) {
      // The initial values span the columns: they set no widths.
      initialValues = t.outputs;
      append(initialValues, t.changed);
      t = Text();
    }
    texts.push_back(std::move(t));
  }

  std::string timeHead = trace.timed ? "time" : "ticks";
  size_t wTime = timeHead.size(), wTaken = 10, wInputs = 6, wOutputs = 7;
  bool anyInputs = false, anyOutputs = false;
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const TraceRow &r = trace.rows[i];
    wTime = std::max(wTime, r.time.size());
    wTaken = std::max(wTaken, r.taken.size());
    wInputs = std::max(wInputs, r.inputs.size());
    wOutputs = std::max(wOutputs, texts[i].outputs.size());
    anyInputs |= !r.inputs.empty();
    anyOutputs |= !texts[i].outputs.empty();
  }
  auto line = [&](const std::string &step, const std::string &time,
                  const std::string &taken, const std::string &inputs,
                  const std::string &outputs, const std::string &changed) {
    std::string text =
        fmt::format("{:>4}  {:>{}}  {:<{}}", step, time, wTime, taken, wTaken);
    if (anyInputs)
      text += fmt::format("  {:<{}}", inputs, wInputs);
    if (anyOutputs)
      text += fmt::format("  {:<{}}", outputs, wOutputs);
    text += "  " + changed;
    os << llvm::StringRef(text).rtrim() << "\n";
  };
  line("step", timeHead, "step taken", "inputs", "outputs", "changed");
  for (size_t i = 0; i < trace.rows.size(); ++i) {
    const TraceRow &r = trace.rows[i];
    if (r.step == 0) {
      os << llvm::StringRef(fmt::format("{:>4}  {:>{}}  {:<{}}  {}", 0, r.time,
                                        wTime, r.taken, wTaken, initialValues))
                .rtrim()
         << "\n";
      continue;
    }
    line(std::to_string(r.step), r.time, r.taken, r.inputs, texts[i].outputs,
         texts[i].changed);
    if (!r.ran.empty())
      os << fmt::format("{:>4}  {:>{}}  ran {}\n", "", "", wTime, r.ran);
  }
  if (loopTo >= 0)
    os << fmt::format("{:>4}  {:>{}}  {} back to step {}, and so on forever\n",
                      "", "", wTime, loopLabel.str(), loopTo);
  if (trace.hiddenNames)
    os << fmt::format("({} internal name{} hidden: --trace-internals shows "
                      "them and every tick)\n",
                      trace.hiddenNames, trace.hiddenNames == 1 ? "" : "s");
}
