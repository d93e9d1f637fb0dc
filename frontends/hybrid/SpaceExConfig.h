//===- SpaceExConfig.h - SpaceEx .cfg files -------------------*- C++ -*-===//
//
// A SpaceEx configuration file (`model.cfg` beside `model.xml`) holds the
// analysis settings and the parts of the problem the XML leaves out: the
// component to analyse (`system`), the initial set (`initially`: initial
// locations, values of constants, initial values or intervals of the
// variables) and the unsafe set (`forbidden`). This unit reads the file
// into those parts, each with its position for messages, and splits the
// initial set into the facts the SpaceEx reader applies; everything else
// in the file (scenario, directions, time horizon...) configures SpaceEx's
// own analysis and is not read.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_HYBRID_SPACEEXCONFIG_H
#define NETLIFT_FRONTENDS_HYBRID_SPACEEXCONFIG_H

#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace netlift::spaceex {

/// Does the initial set's `name` designate the flat name `flat`: the same,
/// or its end after a '.' (SpaceEx lets a local of a bound component be
/// named without its instance, `x1` for `f4.x1`)?
bool namedBy(llvm::StringRef flat, llvm::StringRef name);

/// One `key = value` of the file; `text` points into the file's buffer
/// (kept by the source manager), so a part of it has a position.
struct ConfigEntry {
  llvm::StringRef text;
  llvm::SMLoc loc;
};

/// What the initial set says, fact by fact.
struct InitialSet {
  /// `loc(inst) == name`: the instance's initial location (`loc()`: the
  /// system's only instance, empty `instance`).
  struct Location {
    std::string instance, location;
    llvm::SMLoc loc;
  };
  std::vector<Location> locations;
  /// `x == c` (constants and variables) and bounds `x >= a`, `x <= b`,
  /// `a <= x <= b` (strict bounds are taken as closed), by flat name.
  struct Bounds {
    std::optional<double> lo, hi;
    llvm::SMLoc loc;
    bool used = false; // matched a variable or constant of the system
  };
  std::map<std::string, Bounds> bounds;
  /// The value of a name the set fixes (lo == hi).
  std::optional<double> valueOf(const std::string &name) const;
  /// What the set says of a flat name of the system: the entry of the
  /// longest name that designates it (namedBy); its key in `key`. Null
  /// when none.
  Bounds *lookup(llvm::StringRef flat, std::string *key = nullptr);
};

struct Config {
  std::optional<ConfigEntry> system, initially, forbidden;
  /// `output-variables`: the variables the user plots (observes).
  std::optional<ConfigEntry> outputVariables;
  InitialSet initial;
};

/// Reads the file at `path` (added to the diagnostics' source manager) and
/// splits its initial set. False after reporting why.
bool readConfig(llvm::StringRef path, DiagEngine &diag, Config &out);

/// `--param NAME=VALUE` given on the command line: the values override the
/// configuration's. False after reporting a malformed one.
bool addParams(const std::vector<std::string> &params, DiagEngine &diag,
               InitialSet &into);

} // namespace netlift::spaceex

#endif
