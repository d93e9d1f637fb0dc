//===- ReplayTrace.cpp - a netlift JSON trace run through the model -------===//
//
// `netlift replay MODEL TRACE.json`: a path netlift wrote (`reach
// --trace-json`, `check --trace-dir`; docs/formats.md, "JSON traces"),
// perhaps for another version of the model, is followed step by step: from
// the initial state, each step must be one the model can take with the
// step's label and reach exactly the values the trace records (every column
// of the state listing is recorded, so the state is determined). The run
// is printed as the trace table; the verdict says the model follows the
// trace (and closes its loop, for a lasso) or where it first does not.
//
//===----------------------------------------------------------------------===//
#include "backends/statespace/ReplayLog.h"
#include "backends/statespace/StateColumns.h"
#include "engine/ExplorationSetup.h"
#include "engine/Explorer.h"

#include "llvm/Support/JSON.h"

#include <deque>

using namespace netlift;
using namespace netlift::engine;
using namespace netlift::statespace;
using namespace netlift::statespace::listing;

namespace {

/// The recorded values of one step: name -> value.
using Recorded = std::map<std::string, llvm::json::Value>;

std::string show(const llvm::json::Value &v) {
  std::string s;
  llvm::raw_string_ostream os(s);
  os << v;
  return os.str();
}

} // namespace

int statespace::replayTrace(sem::Semantics &sem, unsigned bufferID,
                            const TraceView &view,
                            const ReplayLogOptions &options, DiagEngine &diag,
                            llvm::raw_ostream &os) {
  const llvm::MemoryBuffer *buf = diag.sourceMgr().getMemoryBuffer(bufferID);
  llvm::SMLoc start = llvm::SMLoc::getFromPointer(buf->getBufferStart());
  llvm::StringRef file = buf->getBufferIdentifier();
  file = file.substr(file.find_last_of('/') + 1);
  auto refuse = [&](const llvm::Twine &msg) {
    diag.error(start, msg);
    return 1;
  };
  llvm::Expected<llvm::json::Value> doc = llvm::json::parse(buf->getBuffer());
  if (!doc)
    return refuse("not a JSON trace: " + llvm::toString(doc.takeError()));
  const llvm::json::Object *top = doc->getAsObject();
  const llvm::json::Array *steps = top ? top->getArray("steps") : nullptr;
  if (!steps || steps->empty())
    return refuse("not a JSON trace: no 'steps' (netlift writes them with "
                  "reach --trace-json and check --trace-dir)");

  std::vector<StateColumn> columns = stateColumns(sem);
  std::map<std::string, size_t> columnOf;
  for (size_t k = 0; k < columns.size(); ++k)
    columnOf[columns[k].name] = k;

  // What each step records, accumulated: step 0's values, then changes.
  std::vector<std::string> labels{""};
  std::vector<Recorded> expected;
  for (size_t i = 0; i < steps->size(); ++i) {
    const llvm::json::Object *step = (*steps)[i].getAsObject();
    const llvm::json::Object *values =
        step ? step->getObject(i == 0 ? "values" : "changes") : nullptr;
    llvm::Optional<llvm::StringRef> label;
    if (step)
      label = step->getString("label");
    if (!values || !label)
      return refuse("step " + llvm::Twine(i) +
                    " of the trace has no 'label' "
                    "or no '" +
                    (i == 0 ? "values" : "changes") + "'");
    Recorded now = i == 0 ? Recorded() : expected.back();
    for (const auto &[name, value] : *values) {
      if (!columnOf.count(name.str()))
        return refuse("step " + llvm::Twine(i) + " of the trace records '" +
                      name.str() +
                      "', which the model does not have (a trace of "
                      "another model?)");
      now.insert_or_assign(name.str(), value);
    }
    expected.push_back(std::move(now));
    if (i > 0) {
      llvm::Optional<llvm::StringRef> inputs = step->getString("inputs");
      labels.push_back(label->str() +
                       (inputs && !inputs->empty() ? " " + inputs->str() : ""));
    }
  }

  // The first recorded value a state does not have.
  auto difference = [&](const uint64_t *state,
                        const Recorded &want) -> std::optional<std::string> {
    for (const auto &[name, value] : want) {
      const StateColumn &c = columns[columnOf[name]];
      llvm::json::Value got = jsonOf(c, cellOf(sem, c, state));
      if (got != value)
        return name + " is " + show(got) + " in the model, " + show(value) +
               " in the trace";
    }
    return std::nullopt;
  };

  const uint32_t words = sem.layout().numWords();
  std::deque<std::vector<uint64_t>> kept(1, std::vector<uint64_t>(words));
  sem::RuntimeError err;
  if (!sem.initialState(kept.back().data(), err)) {
    reportRuntimeErrorAt(err, diag);
    return 1;
  }
  auto printRun = [&](size_t upTo) {
    std::vector<std::vector<uint64_t>> run(kept.begin(), kept.end());
    return showReplayedRun(
        sem, llvm::ArrayRef<std::string>(labels.data(), upTo), run, view,
        options, file, "the trace's steps run through the model", diag, os);
  };
  if (auto d = difference(kept.back().data(), expected[0])) {
    printRun(1);
    os << "diverges at " << file << " step 0 (the initial state): " << *d
       << "\n";
    return 3;
  }
  for (size_t i = 1; i < expected.size(); ++i) {
    llvm::StringRef taken = llvm::StringRef(labels[i]).split(" [").first;
    std::optional<std::vector<uint64_t>> match;
    std::optional<std::string> firstDifference;
    bool ok = sem.successors(
        kept.back().data(),
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          if (match || Explorer::stepText(sem.module(), step) != taken)
            return;
          if (auto d = difference(succ, expected[i])) {
            if (!firstDifference)
              firstDifference = *d;
            return;
          }
          match.emplace(succ, succ + words);
        },
        err);
    if (!ok) {
      reportRuntimeErrorAt(err, diag);
      return 1;
    }
    if (!match) {
      if (!printRun(i))
        return 1;
      os << "diverges at " << file << " step " << i << ": ";
      if (firstDifference)
        os << "after " << taken << ", " << *firstDifference << "\n";
      else
        os << "the model cannot take " << taken << " there\n";
      return 3;
    }
    kept.push_back(std::move(*match));
  }
  if (!printRun(labels.size()))
    return 1;
  os << "the model follows the trace: " << expected.size() - 1 << " steps";
  // A lasso: the last state steps back to states[loop_to].
  llvm::Optional<int64_t> loopTo = top->getInteger("loop_to");
  if (loopTo && *loopTo >= 0 && size_t(*loopTo) < kept.size()) {
    llvm::Optional<llvm::StringRef> loopLabel = top->getString("loop_label");
    std::string back = loopLabel ? loopLabel->split(" [").first.str() : "";
    bool closes = false;
    bool ok = sem.successors(
        kept.back().data(),
        [&](llvm::ArrayRef<uint32_t> step, const uint64_t *succ) {
          closes |= (back.empty() ||
                     Explorer::stepText(sem.module(), step) == back) &&
                    std::equal(succ, succ + words, kept[*loopTo].data());
        },
        err);
    if (!ok) {
      reportRuntimeErrorAt(err, diag);
      return 1;
    }
    if (!closes) {
      os << ", but not its loop: no step " << back << " leads back to step "
         << *loopTo << "\n";
      return 3;
    }
    os << " and its loop back to step " << *loopTo;
  }
  os << "\n";
  return 0;
}
