//===- Driver.h - what the netlift subcommands share ------------*- C++ -*-===//
//
// The driver is option parsing and dispatch: a file per subcommand family
// declares its options and hands the work to the libraries. Here: the
// subcommands, the options several take (Options.cpp), each entry point.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_TOOLS_NETLIFT_DRIVER_H
#define NETLIFT_TOOLS_NETLIFT_DRIVER_H

#include "engine/ExplorationSetup.h"
#include "frontends/FrontendRegistry.h"
#include "ir/automata/Mealy.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/CommandLine.h"

namespace netlift::driver {

namespace cl = llvm::cl;

cl::OptionCategory &category();

// The subcommands, made on first use so that options in any file can name
// them.
cl::SubCommand &translateCommand(), &optCommand(), &composeCommand();
cl::SubCommand &emitCommand(), &reachCommand(), &checkCommand();
cl::SubCommand &srCommand(), &mealyCommand(), &editAutomatonCommand();
cl::SubCommand &enforceCommand(), &replayCommand();

// Options several subcommands take.
extern cl::opt<std::string> outputFile;  // -o
extern cl::opt<std::string> inputFormat; // --from
extern cl::opt<std::string> topName;     // --top
extern cl::list<std::string> properties; // --ctl (check, emit)
extern cl::opt<std::string> edgesFile;   // --edges (reach, sr)
extern cl::opt<bool> noSourceLocations;  // --no-locations (NetIR output)

/// The frontends' options (--top, --timescale, --scan-period, --ranges, -I,
/// --fb-semantics); false after reporting a malformed one.
bool frontendOptions(FrontendOptions &out, DiagEngine &diag);

/// Reads the inputs with the frontends' options.
bool loadModels(llvm::ArrayRef<std::string> paths, DiagEngine &diag,
                net::Design &design);

/// The exploration options (--top, --semantics, --timing, --place-bits,
/// --interpreter, limits); false after reporting.
bool explorationOptions(engine::ExplorationOptions &out, DiagEngine &diag);

/// translate, opt and emit of a whole design: --top only chooses what a
/// PLC frontend translates, so with NetIR input alone it is refused.
bool topUsable(llvm::ArrayRef<std::string> inputs, llvm::StringRef command,
               DiagEngine &diag);

/// Writes `path` whole ("-": stdout); 0, or 1 after reporting.
int writeResult(llvm::StringRef path,
                llvm::function_ref<void(llvm::raw_ostream &)> body,
                DiagEngine &diag);
int writeDesign(const net::Design &design, DiagEngine &diag);

/// The specification of mealy, edit-automaton and enforce: a deterministic
/// KISS2 or DOT machine, or any model whose controller's Mealy machine is
/// extracted (docs/enforce.md). False after reporting.
bool readMealySpec(const std::string &path, DiagEngine &diag,
                   automata::MealyMachine &m);

// The subcommands: the exit code.
int runTranslate(DiagEngine &), runOpt(DiagEngine &), runCompose(DiagEngine &);
int runEmit(DiagEngine &), runReach(DiagEngine &), runCheck(DiagEngine &);
int runSr(DiagEngine &), runMealy(DiagEngine &), runEnforce(DiagEngine &);
int runEditAutomaton(DiagEngine &), runReplay(DiagEngine &);
/// Puts the registry's formats into `emit --to`'s description.
void describeEmitFormats();

} // namespace netlift::driver

#endif
