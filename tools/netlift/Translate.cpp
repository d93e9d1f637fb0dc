//===- Translate.cpp - translate, compose and opt -------------------------===//
#include "ir/net/Verifier.h"
#include "passes/Compose.h"
#include "passes/Pass.h"
#include "tools/netlift/Driver.h"

using namespace netlift;
using namespace netlift::driver;

static cl::list<std::string> translateInputs(cl::Positional,
                                             cl::desc("<input files>"),
                                             cl::OneOrMore,
                                             cl::sub(translateCommand()));

static cl::list<std::string> composeInputs(cl::Positional,
                                           cl::desc("<controller> <plant>..."),
                                           cl::OneOrMore,
                                           cl::sub(composeCommand()));
static cl::opt<std::string> connectFile(
    "connect", cl::desc("Connections 'a.out -> b.in', one per line"),
    cl::value_desc("FILE"), cl::sub(composeCommand()), cl::cat(category()));
enum class Match { Default, Names, None };
static cl::opt<Match> matchNames(
    "match", cl::desc("Wire inputs still undriven to outputs of the same name"),
    cl::init(Match::Default),
    cl::values(clEnumValN(Match::Names, "names",
                          "yes (the default without --connect)"),
               clEnumValN(Match::None, "none", "no")),
    cl::sub(composeCommand()), cl::cat(category()));
static cl::list<std::string>
    components("inst",
               cl::desc("A component NAME:MODULE (repeatable; default: every "
                        "module no other instantiates, named in lower case)"),
               cl::value_desc("NAME:MODULE"), cl::sub(composeCommand()),
               cl::cat(category()));
static cl::opt<std::string>
    systemName("name", cl::desc("Name of the system (default Closed)"),
               cl::value_desc("NAME"), cl::init("Closed"),
               cl::sub(composeCommand()), cl::cat(category()));
static cl::opt<bool> quiet("q",
                           cl::desc("Do not list the wiring, free inputs and "
                                    "unused outputs on stderr"),
                           cl::sub(composeCommand()), cl::cat(category()));

// Optional so that `opt --list-passes` needs no input; checked in runOpt.
static cl::opt<std::string> optInput(cl::Positional, cl::desc("<input>"),
                                     cl::sub(optCommand()));
static cl::opt<std::string> pipeline("p",
                                     cl::desc("Pass pipeline, e.g. "
                                              "'flatten,foo{k=v}'"),
                                     cl::value_desc("pipeline"),
                                     cl::sub(optCommand()),
                                     cl::cat(category()));
static cl::alias pipelineAlias("passes", cl::aliasopt(pipeline));
static cl::opt<bool> listPasses("list-passes",
                                cl::desc("List the registered passes"),
                                cl::sub(optCommand()), cl::cat(category()));
static cl::opt<bool> listPassesMarkdown(
    "list-passes-markdown",
    cl::desc("List the registered passes as markdown (docs/passes.md)"),
    cl::sub(optCommand()), cl::Hidden);
static cl::opt<bool> verifyEach("verify-each",
                                cl::desc("Verify the IR after every pass"),
                                cl::sub(optCommand()), cl::cat(category()));
static cl::opt<bool> printAfterAll("print-after-all",
                                   cl::desc("Print the IR after every pass "
                                            "(to stderr)"),
                                   cl::sub(optCommand()), cl::cat(category()));
static cl::opt<bool> showStats("stats",
                               cl::desc("Print the passes' counters to "
                                        "stderr"),
                               cl::sub(optCommand()), cl::cat(category()));

int driver::runTranslate(DiagEngine &diag) {
  net::Design design;
  if (!topUsable(translateInputs, "translate", diag) ||
      !loadModels(translateInputs, diag, design))
    return 1;
  return writeDesign(design, diag);
}

int driver::runCompose(DiagEngine &diag) {
  ComposeOptions co;
  co.instances = components;
  co.connectFile = connectFile;
  co.systemName = systemName;
  if (matchNames != Match::Default)
    co.matchNames = matchNames == Match::Names;
  net::Design design;
  Statistics stats;
  if (!loadModels(composeInputs, diag, design) ||
      !composeSystem(design, diag, co, quiet ? nullptr : &llvm::errs(), stats))
    return 1;
  return writeDesign(design, diag);
}

int driver::runOpt(DiagEngine &diag) {
  if (listPasses || listPassesMarkdown) {
    if (!listPassesMarkdown)
      llvm::outs() << "Passes (use with -p 'a,b{key=value}'):\n";
    printPassList(llvm::outs(), listPassesMarkdown);
    return 0;
  }
  if (optInput.empty()) {
    diag.error(llvm::SMLoc(),
               "opt needs an input file ('-' for standard input)");
    return 1;
  }
  if (pipeline.getNumOccurrences() == 0) {
    diag.error(llvm::SMLoc(), "opt needs a pipeline (-p 'pass,...'); netlift "
                              "opt --list-passes lists the passes");
    return 1;
  }
  PassManager pm;
  if (!pm.parsePipeline(pipeline, diag))
    return 1;
  net::Design design;
  std::vector<std::string> inputs{optInput};
  if (!topUsable(inputs, "opt", diag) || !loadModels(inputs, diag, design))
    return 1;
  pm.verifyEach = verifyEach;
  if (printAfterAll)
    pm.printAfterAll = &llvm::errs();
  bool ok = pm.run(design, diag);
  if (showStats)
    pm.stats.print(llvm::errs());
  if (!ok)
    return 1;
  // The result of a pipeline is always checked before it is written.
  if (!verifyEach && !net::verifyDesign(design, diag)) {
    diag.error(llvm::SMLoc(), "the pipeline produced invalid IR");
    return 1;
  }
  return writeDesign(design, diag);
}
