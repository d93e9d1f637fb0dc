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

// The subcommands (SubcommandRegistry.def), made on first use so that
// options in any file can name them.
#define NETLIFT_SUBCOMMAND(ID, NAME, USAGE, SUMMARY, READS, EXPLORES, HANDLER) \
  cl::SubCommand &ID##Command();                                               \
  int HANDLER(DiagEngine &);
#include "tools/netlift/SubcommandRegistry.def"

/// A row of the subcommand table.
struct Subcommand {
  cl::SubCommand &(*command)();
  const char *usage;
  bool readsModels, explores;
  int (*run)(DiagEngine &);
};
llvm::ArrayRef<Subcommand> subcommands();
/// The overview `netlift --help` prints, from the table.
std::string overview();
/// Every subcommand's name, comma-separated, in the table's order.
std::string subcommandNames();

/// An option modifier (like cl::sub) attaching the option to every
/// subcommand that reads models, or to every one that explores: such
/// options are declared once, and a subcommand added to the table takes
/// them.
struct OnSubcommands {
  bool exploring;
  template <class Opt> void apply(Opt &option) const {
    for (const Subcommand &c : subcommands())
      if (exploring ? c.explores : c.readsModels)
        option.addSubCommand(c.command());
    option.addCategory(category());
  }
};
inline constexpr OnSubcommands readingCommands{false};
inline constexpr OnSubcommands exploringCommands{true};

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

/// Puts the registry's formats into `emit --to`'s description.
void describeEmitFormats();

} // namespace netlift::driver

#endif
