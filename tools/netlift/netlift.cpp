//===- netlift.cpp - the netlift driver -----------------------------------===//
//
// One binary, git-style subcommands. The driver is thin: it parses options,
// reads inputs through the frontend registry, and hands the Design to the
// libraries (passes, backends). Outputs are written to a temporary file and
// renamed into place, so an error never leaves a half-written file behind.
//
//===----------------------------------------------------------------------===//
#include "backends/nces/NetDot.h"
#include "frontends/FrontendRegistry.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"
#include "passes/Pass.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

#include <functional>

using namespace netlift;
namespace cl = llvm::cl;

#ifndef NETLIFT_VERSION
#define NETLIFT_VERSION "0.0.0"
#endif

static cl::OptionCategory category("netlift options");

static cl::SubCommand
    translateCmd("translate",
                 "Read models in any supported format, verify them and "
                 "print them as canonical NetIR text");
static cl::SubCommand optCmd("opt",
                             "Run a pipeline of NetIR passes over a model");
static cl::SubCommand emitCmd("emit",
                              "Write a model in another format (net, dot)");

static cl::list<std::string> translateInputs(cl::Positional,
                                             cl::desc("<input files>"),
                                             cl::OneOrMore,
                                             cl::sub(translateCmd));
// Optional so that `opt --list-passes` needs no input; checked in runOpt.
static cl::opt<std::string> optInput(cl::Positional, cl::desc("<input>"),
                                     cl::sub(optCmd));
static cl::opt<std::string> emitInput(cl::Positional, cl::desc("<input>"),
                                      cl::Required, cl::sub(emitCmd));

static cl::opt<std::string> outputFile("o",
                                       cl::desc("Output file ('-' = stdout)"),
                                       cl::value_desc("file"), cl::init("-"),
                                       cl::sub(translateCmd), cl::sub(optCmd),
                                       cl::sub(emitCmd), cl::cat(category));
static cl::opt<std::string>
    inputFormat("from", cl::desc("Input format (default: by file extension)"),
                cl::value_desc("format"), cl::sub(translateCmd),
                cl::sub(optCmd), cl::sub(emitCmd), cl::cat(category));

static cl::opt<std::string> pipelineText("p",
                                         cl::desc("Pass pipeline, e.g. "
                                                  "'flatten,foo{k=v}'"),
                                         cl::value_desc("pipeline"),
                                         cl::sub(optCmd), cl::cat(category));
static cl::alias pipelineAlias("passes", cl::aliasopt(pipelineText));
static cl::opt<bool> listPasses("list-passes",
                                cl::desc("List the registered passes"),
                                cl::sub(optCmd), cl::cat(category));
static cl::opt<bool> listPassesMarkdown(
    "list-passes-markdown",
    cl::desc("List the registered passes as markdown (docs/passes.md)"),
    cl::sub(optCmd), cl::Hidden);
static cl::opt<bool> verifyEach("verify-each",
                                cl::desc("Verify the IR after every pass"),
                                cl::sub(optCmd), cl::cat(category));
static cl::opt<bool> printAfterAll("print-after-all",
                                   cl::desc("Print the IR after every pass "
                                            "(to stderr)"),
                                   cl::sub(optCmd), cl::cat(category));
static cl::opt<bool> showStats("stats",
                               cl::desc("Print the passes' counters to "
                                        "stderr"),
                               cl::sub(optCmd), cl::cat(category));

enum class EmitFormat { Net, Dot };
static cl::opt<EmitFormat>
    emitFormat("to", cl::desc("Output format"), cl::Required,
               cl::values(clEnumValN(EmitFormat::Net, "net", "NetIR text"),
                          clEnumValN(EmitFormat::Dot, "dot",
                                     "Graphviz drawing of the "
                                     "net")),
               cl::sub(emitCmd), cl::cat(category));

/// Writes through `body` to `path` ("-": stdout) via a temporary file that
/// is renamed into place only when everything was written.
static bool writeOutput(llvm::StringRef path,
                        const std::function<void(llvm::raw_ostream &)> &body) {
  if (path == "-") {
    body(llvm::outs());
    llvm::outs().flush();
    return true;
  }
  llvm::SmallString<128> tmp;
  int fd;
  std::string model = (path + ".tmp-%%%%%%").str();
  if (std::error_code ec = llvm::sys::fs::createUniqueFile(model, fd, tmp)) {
    llvm::errs() << "netlift: error: cannot write '" << path
                 << "': " << ec.message() << "\n";
    return false;
  }
  {
    llvm::raw_fd_ostream os(fd, /*shouldClose=*/true);
    body(os);
    os.close();
    if (os.has_error()) {
      llvm::errs() << "netlift: error: cannot write '" << path
                   << "': " << os.error().message() << "\n";
      os.clear_error();
      llvm::sys::fs::remove(tmp);
      return false;
    }
  }
  if (std::error_code ec = llvm::sys::fs::rename(tmp, path)) {
    llvm::errs() << "netlift: error: cannot write '" << path
                 << "': " << ec.message() << "\n";
    llvm::sys::fs::remove(tmp);
    return false;
  }
  return true;
}

/// Writes the design as NetIR text to -o; the exit code of the subcommand.
static int writeDesign(const net::Design &design) {
  return writeOutput(
             outputFile,
             [&](llvm::raw_ostream &os) { net::printDesign(design, os); })
             ? 0
             : 1;
}

static int runTranslate() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  net::Design design;
  if (!loadInputs(translateInputs, inputFormat, diag, design))
    return 1;
  return writeDesign(design);
}

static int runOpt() {
  if (listPasses || listPassesMarkdown) {
    if (!listPassesMarkdown)
      llvm::outs() << "Passes (use with -p 'a,b{key=value}'):\n";
    printPassList(llvm::outs(), listPassesMarkdown);
    return 0;
  }
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  if (optInput.empty()) {
    llvm::errs() << "netlift: error: opt needs an input file ('-' for "
                    "standard input)\n";
    return 1;
  }
  if (pipelineText.getNumOccurrences() == 0) {
    llvm::errs() << "netlift: error: opt needs a pipeline (-p 'pass,...'); "
                    "netlift opt --list-passes lists the passes\n";
    return 1;
  }
  PassManager pm;
  if (!pm.parsePipeline(pipelineText, diag))
    return 1;
  net::Design design;
  std::vector<std::string> inputs{optInput};
  if (!loadInputs(inputs, inputFormat, diag, design))
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
    llvm::errs() << "netlift: error: the pipeline produced invalid IR\n";
    return 1;
  }
  return writeDesign(design);
}

static int runEmit() {
  llvm::SourceMgr sm;
  DiagEngine diag(sm);
  net::Design design;
  std::vector<std::string> inputs{emitInput};
  if (!loadInputs(inputs, inputFormat, diag, design))
    return 1;
  return writeOutput(outputFile,
                     [&](llvm::raw_ostream &os) {
                       switch (emitFormat) {
                       case EmitFormat::Net:
                         net::printDesign(design, os);
                         break;
                       case EmitFormat::Dot:
                         writeDot(design, os);
                         break;
                       }
                     })
             ? 0
             : 1;
}

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  cl::SetVersionPrinter([](llvm::raw_ostream &os) {
    os << "netlift " << NETLIFT_VERSION << "\n";
  });
  cl::HideUnrelatedOptions({&category});
  if (!cl::ParseCommandLineOptions(
          argc, argv,
          "netlift: lift industrial control software into formal models\n\n"
          "  netlift translate IN... [-o OUT] [--from FMT]\n"
          "  netlift opt IN -p PIPELINE [-o OUT] [--verify-each] "
          "[--print-after-all] [--stats]\n"
          "  netlift emit IN --to net|dot [-o OUT]\n\n"
          "Run 'netlift <subcommand> --help' for a subcommand's options.\n",
          &llvm::errs()))
    return 1;
  if (translateCmd)
    return runTranslate();
  if (optCmd)
    return runOpt();
  if (emitCmd)
    return runEmit();
  llvm::errs() << "netlift: error: no subcommand given (translate, opt, "
                  "emit); see netlift --help\n";
  return 1;
}
