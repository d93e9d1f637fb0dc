//===- Enforce.cpp - edit-automaton and enforce ---------------------------===//
#include "backends/enforce/Enforce.h"
#include "backends/enforce/EditAutomatonJson.h"
#include "backends/statespace/Exploring.h"
#include "backends/statespace/ReplayLog.h"
#include "engine/ExplorationSetup.h"
#include "ir/automata/EditAutomaton.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

using namespace netlift;
using namespace netlift::driver;

static cl::opt<std::string> eaInput(cl::Positional, cl::desc("<spec>"),
                                    cl::Required,
                                    cl::sub(editAutomatonCommand()));
enum class EaFormat { Table, Dot, Json };
static cl::opt<EaFormat> eaTo(
    "to", cl::desc("Output format"), cl::init(EaFormat::Table),
    cl::values(clEnumValN(EaFormat::Table, "table", "one transition a line"),
               clEnumValN(EaFormat::Dot, "dot",
                          "Graphviz (suppressions dashed, intermediate "
                          "states shaded)"),
               clEnumValN(EaFormat::Json, "json",
                          "JSON, read back by enforce and edit-automaton")),
    cl::sub(editAutomatonCommand()), cl::cat(category()));
static cl::opt<bool> delayedOutputs(
    "delayed-outputs",
    cl::desc("Also tolerate outputs that appear one observation after the "
             "inputs that caused them (docs/enforce.md)"),
    cl::sub(editAutomatonCommand()), cl::sub(enforceCommand()),
    cl::cat(category()));
static cl::opt<bool> synchronisedInputs(
    "synchronised-inputs",
    cl::desc("Also tolerate two changes of different inputs read in one scan "
             "(docs/enforce.md)"),
    cl::sub(editAutomatonCommand()), cl::sub(enforceCommand()),
    cl::cat(category()));
static cl::list<std::string> enforceInputs(cl::Positional,
                                           cl::desc("<spec> <trace.csv>"),
                                           cl::OneOrMore,
                                           cl::sub(enforceCommand()));

/// An edit automaton written as JSON, or the one built from a Mealy
/// specification.
static bool specAutomaton(const std::string &path, DiagEngine &diag,
                          automata::EditAutomaton &ea) {
  if (inputFormat == "json" ||
      (inputFormat.empty() && llvm::sys::path::extension(path) == ".json")) {
    if (delayedOutputs || synchronisedInputs) {
      diag.error(llvm::SMLoc(), path + " is a built edit automaton: the "
                                       "phenomena it tolerates were chosen "
                                       "when it was built");
      return false;
    }
    unsigned id = addInputFile(diag.sourceMgr(), path);
    return id && enforce::readEditAutomatonJson(id, diag, ea);
  }
  automata::MealyMachine m;
  if (!readMealySpec(path, diag, m))
    return false;
  if (m.isSymbolic()) {
    diag.error(llvm::SMLoc(), path + " reads input symbols, not Boolean "
                                     "signals: the PLC's desynchronised "
                                     "reading is defined per input signal");
    return false;
  }
  automata::EditAutomatonOptions opts;
  opts.delayedOutputs = delayedOutputs;
  opts.synchronisedInputs = synchronisedInputs;
  std::string why;
  if (!automata::buildEditAutomaton(m, ea, why, opts)) {
    diag.error(llvm::SMLoc(), why);
    return false;
  }
  return true;
}

int driver::runEditAutomaton(DiagEngine &diag) {
  automata::EditAutomaton ea;
  if (!specAutomaton(eaInput, diag, ea))
    return 1;
  return writeResult(
      outputFile,
      [&](llvm::raw_ostream &os) {
        if (eaTo == EaFormat::Dot)
          enforce::writeEditAutomatonDot(ea, os);
        else if (eaTo == EaFormat::Json)
          enforce::writeEditAutomatonJson(ea, os);
        else
          enforce::writeEditAutomatonTable(ea, os);
      },
      diag);
}

/// Is the specification a program (whose Mealy machine is extracted), not
/// an automaton file?
static bool isProgramSpec(const std::string &path) {
  if (!inputFormat.empty())
    return inputFormat != "json" && inputFormat != "kiss2" &&
           inputFormat != "dot";
  llvm::StringRef ext = llvm::sys::path::extension(path);
  return ext != ".json" && ext != ".kiss2" && ext != ".kiss" && ext != ".kis" &&
         ext != ".dot";
}

/// A program specification explains a stop in its own terms: the program
/// runs on the vectors the automaton emitted, then on the stopped one
/// (replay's scan table, with the source lines of every change), up to the
/// output the trace does not show. Returns 1 on an error, else 3 (the
/// verdict stands).
static int explainStop(const automata::EditAutomaton &ea, unsigned traceID,
                       const enforce::EnforceResult &stop,
                       const std::string &program, DiagEngine &diag) {
  auto row = [](const std::string &vector) {
    std::string r;
    for (char c : vector)
      r.append(r.empty() ? "" : ",").push_back(c);
    return r + "\n";
  };
  std::string csv;
  for (const std::string &signal : ea.signals)
    csv.append(csv.empty() ? "" : ",").append(signal);
  csv += "\n";
  size_t emitted = 0;
  enforce::EnforceResult again;
  if (!enforce::enforceTrace(
          ea, traceID, diag,
          [&](const std::string &v) {
            csv += row(v);
            ++emitted;
          },
          again))
    return 1;
  csv += row(stop.stopVector);
  std::string trace =
      llvm::sys::path::filename(
          diag.sourceMgr().getMemoryBuffer(traceID)->getBufferIdentifier())
          .str();
  unsigned id = diag.sourceMgr().AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(csv, "<the vectors enforced on " +
                                                    trace + ">"),
      llvm::SMLoc());
  engine::ExplorationOptions xo;
  net::Design design;
  std::vector<std::string> inputs{program};
  if (!explorationOptions(xo, diag) || !loadModels(inputs, diag, design))
    return 1;
  auto setup = engine::ExplorationSetup::create(design, xo, diag, "enforce");
  if (!setup)
    return 1;
  statespace::ReplayLogOptions options;
  options.rowName = [&](size_t r) {
    return r <= emitted ? "enforced vector " + std::to_string(r)
                        : trace + " vector " + std::to_string(stop.stopIndex);
  };
  options.recordName = "trace";
  llvm::outs() << "the program on the enforced vectors, then on vector "
               << stop.stopIndex << ":\n";
  int code = statespace::replayLog(setup->semantics(), id,
                                   statespace::traceViewOf(*setup), options,
                                   diag, llvm::outs());
  return code == 1 ? 1 : 3;
}

/// Exit 0 conform, 3 not conform, 1 error.
int driver::runEnforce(DiagEngine &diag) {
  if (enforceInputs.size() != 2) {
    diag.error(llvm::SMLoc(), "enforce needs a specification and a trace: "
                              "netlift enforce SPEC.kiss2 TRACE.csv");
    return 1;
  }
  automata::EditAutomaton ea;
  if (!specAutomaton(enforceInputs[0], diag, ea))
    return 1;
  unsigned id = addInputFile(diag.sourceMgr(), enforceInputs[1]);
  if (!id)
    return 1;
  // Streamed: each enforced vector is printed as it is emitted, and written
  // to -o (a temporary renamed into place at the end).
  enforce::EnforceResult result;
  int code = 1;
  if (outputFile == "-") {
    code =
        enforce::enforceAndJudge(ea, id, diag, llvm::outs(), nullptr, &result);
  } else {
    if (writeResult(
            outputFile,
            [&](llvm::raw_ostream &os) {
              code = enforce::enforceAndJudge(ea, id, diag, llvm::outs(), &os,
                                              &result);
            },
            diag))
      return 1;
    if (code == 1)
      llvm::sys::fs::remove(outputFile);
  }
  if (code == 3 && result.stopped && isProgramSpec(enforceInputs[0]))
    return explainStop(ea, id, result, enforceInputs[0], diag);
  return code;
}
