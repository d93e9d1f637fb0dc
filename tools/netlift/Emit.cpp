//===- Emit.cpp - emit: a model in another format -------------------------===//
#include "backends/BackendRegistry.h"
#include "backends/checkers/CheckProperties.h"
#include "backends/nces/NcesXml.h"
#include "tools/netlift/Driver.h"

using namespace netlift;
using namespace netlift::driver;

// Optional so that --list-formats-markdown needs none; checked in runEmit.
static cl::opt<std::string> emitInput(cl::Positional, cl::desc("<input>"),
                                      cl::sub(emitCommand()));
// The description lists the registry (describeEmitFormats).
static cl::opt<std::string> format("to", cl::value_desc("format"),
                                   cl::sub(emitCommand()), cl::cat(category()));
static cl::opt<bool> listFormatsMarkdown(
    "list-formats-markdown",
    cl::desc("List the output formats as markdown (docs/formats.md)"),
    cl::sub(emitCommand()), cl::Hidden);
static cl::opt<bool>
    modular("modular",
            cl::desc("nces-xml: one FBType file per module in the -o "
                     "directory, modules of instances as composite FBTypes "
                     "(FBNetwork)"),
            cl::sub(emitCommand()), cl::cat(category()));

void driver::describeEmitFormats() {
  static std::string text = describeBackends();
  format.setDescription(text);
}

int driver::runEmit(DiagEngine &diag) {
  if (listFormatsMarkdown) {
    printBackendTable(llvm::outs());
    return 0;
  }
  if (emitInput.empty() || format.empty()) {
    diag.error(llvm::SMLoc(), "emit needs an input and --to FORMAT (netlift "
                              "emit --help lists the formats)");
    return 1;
  }
  const BackendInfo *backend = findBackend(format);
  if (!backend) {
    std::string known;
    for (const BackendInfo &b : backends())
      known += (known.empty() ? "" : ", ") + b.id.str();
    diag.error(llvm::SMLoc(),
               "unknown output format '" + format + "' (known: " + known + ")");
    return 1;
  }
  if (!properties.empty() && backend->input != EmitInputKind::Steps) {
    diag.error(llvm::SMLoc(), "--ctl goes with emit --to promela or smv (or "
                              "netlift check)");
    return 1;
  }
  if (modular &&
      (backend->id != "nces-xml" || outputFile.empty() || outputFile == "-")) {
    diag.error(llvm::SMLoc(),
               "--modular goes with --to nces-xml and -o DIRECTORY");
    return 1;
  }
  net::Design design;
  std::vector<std::string> inputs{emitInput};
  bool whole = backend->input == EmitInputKind::Design;
  if ((whole && !topUsable(inputs, "emit", diag)) ||
      !loadModels(inputs, diag, design))
    return 1;
  if (modular)
    return nces::writeNcesModules(design, topName, outputFile, diag) ? 0 : 1;
  EmitInput in;
  in.design = &design;
  in.sourceLocations = !noSourceLocations;
  std::unique_ptr<engine::ExplorationSetup> setup;
  std::vector<std::unique_ptr<checkers::CtlFormula>> formulas;
  std::vector<const checkers::CtlFormula *> claims;
  if (backend->input == EmitInputKind::FlatTop &&
      !(in.top = engine::explorableTop(design, topName, diag, "emit")))
    return 1;
  if (backend->input == EmitInputKind::Steps) {
    engine::ExplorationOptions xo;
    xo.enumeratesInputs = false; // the checkers take the input's type
    // The claims observe what they name; the user's own properties in the
    // checker see only what is kept (docs/semantics.md, "Observers").
    xo.observerTexts.assign(properties.begin(), properties.end());
    if (!explorationOptions(xo, diag) ||
        !(setup = engine::ExplorationSetup::create(design, xo, diag, "emit")) ||
        !checkers::parseProperties(properties, design, setup->top(), diag,
                                   formulas))
      return 1;
    setup->noteUnkeptValues(diag, "export");
    for (const auto &f : formulas)
      claims.push_back(f.get());
    in.top = &setup->top();
    in.setup = setup.get();
    in.properties = claims;
  }
  // Built whole before anything is written.
  std::string text;
  llvm::raw_string_ostream buf(text);
  if (!backend->write(in, diag, buf))
    return 1;
  return writeResult(
      outputFile, [&](llvm::raw_ostream &os) { os << buf.str(); }, diag);
}
