//===- Subcommands.cpp - the subcommand table -----------------------------===//
//
// Everything that lists subcommands, made from SubcommandRegistry.def.
//
//===----------------------------------------------------------------------===//
#include "tools/netlift/Driver.h"

using namespace netlift;
using namespace netlift::driver;

#define NETLIFT_SUBCOMMAND(ID, NAME, USAGE, SUMMARY, READS, EXPLORES, HANDLER) \
  cl::SubCommand &driver::ID##Command() {                                      \
    static cl::SubCommand c(NAME, SUMMARY);                                    \
    return c;                                                                  \
  }
#include "tools/netlift/SubcommandRegistry.def"

llvm::ArrayRef<Subcommand> driver::subcommands() {
  static const Subcommand table[] = {
#define NETLIFT_SUBCOMMAND(ID, NAME, USAGE, SUMMARY, READS, EXPLORES, HANDLER) \
  {ID##Command, USAGE, READS, EXPLORES, HANDLER},
#include "tools/netlift/SubcommandRegistry.def"
  };
  return table;
}

std::string driver::subcommandNames() {
  std::string names;
  for (const Subcommand &c : subcommands())
    names += (names.empty() ? "" : ", ") + c.command().getName().str();
  return names;
}

std::string driver::overview() {
  std::string text =
      "netlift: lift industrial control software into formal models\n\n";
  std::string exploring;
  for (const Subcommand &c : subcommands()) {
    llvm::StringRef name = c.command().getName();
    text += "  netlift " + name.str() + " " + c.usage + "\n";
    if (c.explores)
      exploring += (exploring.empty() ? "" : ", ") + name.str();
  }
  return text + "\nExploring commands (" + exploring +
         ") and emit take\n--semantics interleaving|maximal and --timing "
         "weak|strong alike.\nRun 'netlift <subcommand> --help' for a "
         "subcommand's options.\n";
}
