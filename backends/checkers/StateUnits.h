//===- StateUnits.h - a flat module's state as a checker names it -*- C++
//-*-===//
//
// The exports to model checkers (Promela, SMV) name the same things: each
// place's marking and clock, each scalar or array of scalars a variable or
// stored port holds (records split into their fields), the free inputs and
// the input events. This unit builds those names and storage units once
// from the state layout, finds which unit an expression designates, and
// refuses, by name and place, what neither export can carry (arrays of
// aggregates, values beyond 32 bits).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_CHECKERS_STATEUNITS_H
#define NETLIFT_BACKENDS_CHECKERS_STATEUNITS_H

#include "engine/Semantics.h"
#include "engine/StateLayout.h"
#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include <optional>
#include <string>
#include <vector>

namespace netlift::checkers {

/// The Promela and SMV exports encode netlift's default steps: one
/// spontaneous transition a step (`--semantics interleaving`) and weak
/// timing. A semantics whose state space on `m` differs from those is
/// refused, naming the option, rather than silently encoded as the default
/// (maximal steps are the same on a module of one spontaneous transition,
/// strong timing where every transition with a finite deadline is urgent).
bool encodesSemantics(const net::Module &m, const sem::Options &semantics,
                      const char *format, DiagEngine &diag);

/// A checker identifier: a prefix and index keep names unique, the NetIR
/// name (non-identifier characters replaced) keeps them readable.
std::string checkerIdentifier(const char *prefix, uint32_t i,
                              llvm::StringRef name);

/// Each transition's effect on one place, by transition.
using EffectsOnPlace = std::vector<std::pair<uint32_t, net::PlaceEffect>>;

/// Storage of the state or of the inputs as a checker sees it: a scalar
/// slot, or an array of scalar slots.
struct Unit {
  std::string name;
  uint32_t firstSlot = 0;
  uint32_t count = 1; // > 1 or `isArray`: an array
  bool isArray = false;
  int64_t indexLo = 0;
  int64_t lo = 0, hi = 0; // of each element
  bool wrap = false;
  bool isInput = false;
};

/// Where an expression's storage is: a unit and either a static element or
/// an index expression (arrays).
struct Access {
  uint32_t unit = 0;
  const net::Expr *index = nullptr;
};

class StateUnits {
public:
  /// `format` names the export in refusals ("the Promela export").
  StateUnits(const net::Module &m, const sem::StateLayout &L, DiagEngine &diag,
             const char *format)
      : m(m), L(L), diag(diag), format(format) {}

  /// Builds the units, names and input events; false after a refusal.
  bool buildUnits();
  /// The unit `e` designates; nullopt if it designates none statically (a
  /// refusal is reported for indexing a non-array and for aggregates).
  std::optional<Access> access(const net::Expr *e);
  /// Reports the first refusal only; always false.
  bool refuse(llvm::SMLoc loc, const std::string &what);
  /// The position of input event port `port` among the input events.
  uint32_t inputEventIndex(uint32_t port) const;
  /// The initial state, or false after reporting why there is none.
  bool initialState(std::vector<uint64_t> &state);
  /// Transition t's token, capacity and time conditions as comparisons
  /// both languages read alike (`P0_a >= 1`, `K2_b <= 3`).
  std::vector<std::string> tokenAndTimeConditions(uint32_t t) const;
  /// For every place a forced transition touches (only those can make
  /// closure candidates conflict), every transition's effect on it.
  std::vector<std::pair<uint32_t, EffectsOnPlace>> forcedPlaces() const;

protected:
  const net::Module &m;
  const sem::StateLayout &L;
  DiagEngine &diag;
  const char *format;

  std::vector<Unit> units;
  std::vector<int32_t> unitOfSlot; // first slot of a unit -> unit
  std::vector<std::string> placeNames, clockNames, eventNames;
  bool failed = false;

private:
  bool addUnits(const std::string &name, const net::Type *t, uint32_t &slot,
                bool isInput, llvm::SMLoc loc);
};

} // namespace netlift::checkers

#endif
