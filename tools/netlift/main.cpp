//===- main.cpp - the netlift driver --------------------------------------===//
//
// One binary, git-style subcommands. The driver is thin: each subcommand's
// file declares its options and hands the work to the libraries; this file
// parses the command line and dispatches.
//
//===----------------------------------------------------------------------===//
#include "backends/statespace/Writers.h"
#include "ir/support/Suggest.h"
#include "tools/netlift/Driver.h"

#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/Signals.h"

#include <csignal>
#include <cstdlib>

using namespace netlift;
using namespace netlift::driver;

#ifndef NETLIFT_VERSION
#define NETLIFT_VERSION "0.0.0"
#endif
#ifndef NETLIFT_REVISION
#define NETLIFT_REVISION "unknown"
#endif

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
  // The suite's self-checks (test/lit.cfg.py): the environment is read
  // here, libraries take options.
  if (const char *verify = std::getenv("NETLIFT_VERIFY_TRACES"))
    statespace::setTraceFileVerification(llvm::StringRef(verify) != "0");
  cl::HideUnrelatedOptions({&category()});
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  if (argc > 1 && argv[1][0] != '-') {
    std::vector<std::string> names;
    for (const Subcommand &c : subcommands())
      names.push_back(c.command().getName().str());
    if (!llvm::is_contained(names, argv[1])) {
      diag.error(llvm::SMLoc(), "unknown subcommand '" + llvm::Twine(argv[1]) +
                                    "'" + didYouMean(argv[1], names) +
                                    " (netlift --help lists them)");
      return 1;
    }
  }
  if (!cl::ParseCommandLineOptions(argc, argv, overview(), &llvm::errs()))
    return 1;
  for (const Subcommand &c : subcommands())
    if (c.command())
      return c.run(diag);
  diag.error(llvm::SMLoc(), "no subcommand given (" + subcommandNames() +
                                "); see netlift --help");
  return 1;
}
