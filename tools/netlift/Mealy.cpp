//===- Mealy.cpp - mealy: reading, extracting and comparing machines ------===//
#include "backends/mealy/ExtractMealy.h"
#include "backends/mealy/MealyWriters.h"
#include "frontends/dot/DotMealyReader.h"
#include "frontends/kiss2/Kiss2Reader.h"
#include "ir/automata/Minimize.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/Path.h"

using namespace netlift;
using namespace netlift::driver;

static cl::opt<std::string> mealyInput(cl::Positional, cl::desc("<input>"),
                                       cl::Required, cl::sub(mealyCommand()));
enum class MealyFormat { Kiss2, Dot };
static cl::opt<MealyFormat> mealyTo(
    "to", cl::desc("Output format"), cl::init(MealyFormat::Kiss2),
    cl::values(clEnumValN(MealyFormat::Kiss2, "kiss2", "KISS2"),
               clEnumValN(MealyFormat::Dot, "dot", "Graphviz (AALpy style)")),
    cl::sub(mealyCommand()), cl::cat(category()));
static cl::opt<bool> minimize("minimize",
                              cl::desc("Write the minimal equivalent machine"),
                              cl::sub(mealyCommand()), cl::cat(category()));
static cl::opt<std::string>
    equivTo("equiv",
            cl::desc("Compare with machine B: exit 0 if equivalent, 3 and a "
                     "shortest distinguishing input sequence if not"),
            cl::value_desc("B"), cl::sub(mealyCommand()), cl::cat(category()));
static cl::opt<bool> info("info",
                          cl::desc("Print signals, states and how complete "
                                   "the machine is"),
                          cl::sub(mealyCommand()), cl::cat(category()));

bool driver::readMealySpec(const std::string &path, DiagEngine &diag,
                           automata::MealyMachine &m) {
  llvm::SourceMgr &sm = diag.sourceMgr();
  llvm::StringRef ext = llvm::sys::path::extension(path);
  bool isKiss = inputFormat == "kiss2" ||
                (inputFormat.empty() &&
                 (ext == ".kiss2" || ext == ".kiss" || ext == ".kis"));
  if (isKiss || inputFormat == "dot" ||
      (inputFormat.empty() && ext == ".dot")) {
    unsigned id = addInputFile(sm, path);
    return id &&
           (isKiss ? kiss2::readKiss2(id, diag, m)
                   : dot::readMealyDot(id, diag, m)) &&
           m.checkDeterminism(diag);
  }
  net::Design design;
  std::vector<std::string> inputs{path};
  engine::ExplorationOptions xo;
  if (!loadModels(inputs, diag, design) || !explorationOptions(xo, diag))
    return false;
  auto setup = engine::ExplorationSetup::create(design, xo, diag, "mealy");
  if (!setup)
    return false;
  mealy::MealyExtractOptions opts;
  if (xo.maxStates)
    opts.maxStates = uint32_t(std::min<uint64_t>(xo.maxStates, UINT32_MAX));
  return mealy::extractMealy(setup->semantics(), opts, diag, m);
}

int driver::runMealy(DiagEngine &diag) {
  automata::MealyMachine m;
  if (!readMealySpec(mealyInput, diag, m))
    return 1;
  std::string why;
  if (!equivTo.empty()) {
    automata::MealyMachine other;
    if (!readMealySpec(equivTo, diag, other))
      return 1;
    automata::EquivalenceResult r;
    if (!automata::alignAlphabets(m, other, why) ||
        !automata::checkEquivalence(m, other, r, why)) {
      diag.error(llvm::SMLoc(), why);
      return 1;
    }
    automata::writeEquivalence(m, r, llvm::outs());
    return r.equivalent ? 0 : 3;
  }
  if (minimize) {
    automata::MealyMachine minimal;
    if (!automata::minimize(m, minimal, why)) {
      diag.error(llvm::SMLoc(), why);
      return 1;
    }
    m = std::move(minimal);
  }
  if (info)
    mealy::writeMealyInfo(m, llvm::errs());
  return writeResult(
      outputFile,
      [&](llvm::raw_ostream &os) {
        if (mealyTo == MealyFormat::Kiss2)
          mealy::writeKiss2(m, os);
        else
          mealy::writeMealyDot(m, os);
      },
      diag);
}
