//===- main.cpp - the netlift driver --------------------------------------===//
//
// One binary, git-style subcommands. The driver is thin: each subcommand's
// file declares its options and hands the work to the libraries; this file
// parses the command line and dispatches.
//
//===----------------------------------------------------------------------===//
#include "ir/support/Suggest.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/Signals.h"

#include <csignal>

using namespace netlift;
using namespace netlift::driver;

#ifndef NETLIFT_VERSION
#define NETLIFT_VERSION "0.0.0"
#endif
#ifndef NETLIFT_REVISION
#define NETLIFT_REVISION "unknown"
#endif

static const char *const overview =
    "netlift: lift industrial control software into formal models\n\n"
    "  netlift translate IN... [-o OUT] [--from FMT] [--top NAME] "
    "[--timescale 10ms] [--ranges FILE]\n"
    "  netlift opt IN -p PIPELINE [-o OUT] [--verify-each] "
    "[--print-after-all] [--stats]\n"
    "  netlift compose CTRL PLANT... [--connect FILE] [--match names|none] "
    "[--inst NAME:MODULE]... [-o OUT]\n"
    "  netlift emit IN --to net|dot|promela|smv|pnml|nces-xml|pnt [-o OUT]\n"
    "  netlift reach IN [--format aut|dot|json|csv|arc] [-o OUT] [--summary "
    "json] [--find EXPR]\n"
    "  netlift mealy IN.kiss2|IN.dot|MODEL [--to kiss2|dot] [-o OUT] [--info] "
    "[--minimize]\n"
    "  netlift edit-automaton SPEC [--to table|dot|json] [-o OUT]\n"
    "  netlift enforce SPEC TRACE.csv [-o ENFORCED.csv]\n"
    "  netlift check MODEL --ctl FORMULA...\n"
    "  netlift replay MODEL LOG.csv [--trace-html FILE]\n"
    "  netlift sr MODEL --attr NAME[=PRED]... [--report text|json|html] [--ev "
    "F.svg] [--ag FILE.dot]\n\n"
    "Exploring commands (reach, check, sr, mealy, edit-automaton, enforce) "
    "and emit take\n--semantics interleaving|maximal and --timing "
    "weak|strong alike.\n"
    "Run 'netlift <subcommand> --help' for a subcommand's options.\n";

static const struct {
  cl::SubCommand &(*command)();
  int (*run)(DiagEngine &);
} commands[] = {
    {translateCommand, runTranslate},
    {optCommand, runOpt},
    {composeCommand, runCompose},
    {emitCommand, runEmit},
    {reachCommand, runReach},
    {mealyCommand, runMealy},
    {editAutomatonCommand, runEditAutomaton},
    {enforceCommand, runEnforce},
    {srCommand, runSr},
    {checkCommand, runCheck},
    {replayCommand, runReplay},
};

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  // A reader that closes the pipe (`| head`) ends netlift as it ends other
  // Unix tools: quietly, by SIGPIPE (LLVM's default exits 74).
  llvm::sys::SetOneShotPipeSignalFunction([] {
    std::signal(SIGPIPE, SIG_DFL);
    std::raise(SIGPIPE);
  });
  cl::SetVersionPrinter([](llvm::raw_ostream &os) {
    os << "netlift " << NETLIFT_VERSION << " (source revision "
       << NETLIFT_REVISION << ")\n";
  });
  describeEmitFormats();
  cl::HideUnrelatedOptions({&category()});
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const auto &c : commands)
      names.push_back(c.command().getName().str());
    if (!llvm::is_contained(names, argv[1])) {
      diag.error(llvm::SMLoc(), "unknown subcommand '" + llvm::Twine(argv[1]) +
                                    "'" + didYouMean(argv[1], names) +
                                    " (netlift --help lists them)");
      return 1;
    }
  }
  if (!cl::ParseCommandLineOptions(argc, argv, overview, &llvm::errs()))
    return 1;
  for (const auto &c : commands)
    if (c.command())
      return c.run(diag);
  diag.error(llvm::SMLoc(),
             "no subcommand given (translate, opt, compose, emit, reach, "
             "check, sr, mealy, edit-automaton, enforce); see netlift --help");
  return 1;
}
