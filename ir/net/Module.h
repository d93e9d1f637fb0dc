//===- Module.h - NetIR modules, nets and designs ---------------*- C++ -*-===//
//
// The NetIR data structures (design §3.1): a Design is what one .net file
// holds (named types, an optional timescale, modules and systems); a Module is
// a Net Condition/Event System with an interface of event/cond/data ports,
// places, transitions with flow, condition and event arcs, data variables,
// guards and actions, hybrid flows, and instances of other modules wired by
// connections. Everything is allocated in the Design: names and expression
// nodes in its arena, so entities are small and a large net costs a few
// times its text. Entities refer to each other by index within their module.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_IR_NET_MODULE_H
#define NETLIFT_IR_NET_MODULE_H

#include "ir/net/Expr.h"
#include "ir/net/Types.h"
#include "ir/support/HugePageAllocator.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Allocator.h"
#include "llvm/Support/SMLoc.h"
#include "llvm/Support/StringSaver.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace netlift::net {

/// Unbounded capacity / upper time bound.
constexpr uint32_t kInf = UINT32_MAX;

enum class PortKind : uint8_t { Event, Cond, Data };
enum class PortDir : uint8_t { In, Out };
enum class EventMode : uint8_t { Or, And };

llvm::StringRef spelling(PortKind k);

struct Port {
  llvm::StringRef name;
  llvm::SMLoc loc;
  PortKind kind;
  PortDir dir;
  /// Data ports: the value type. Cond ports: bool.
  const Type *type = nullptr;
  /// Outputs: the defining expression (`at_home = home;`), or null when the
  /// output is stored state written by actions.
  Expr *definition = nullptr;
  llvm::SMLoc definitionLoc;
  /// Stored outputs: the initial value (null: false / the type's low bound).
  Expr *init = nullptr;

  bool isInput() const { return dir == PortDir::In; }
  bool isOutput() const { return dir == PortDir::Out; }
  /// A cond/data output without a definition holds state.
  bool isStored() const {
    return dir == PortDir::Out && kind != PortKind::Event && !definition;
  }
};

struct Place {
  llvm::StringRef name;
  llvm::SMLoc loc;
  uint32_t tokens = 0;
  uint32_t capacity = 1; // kInf: unbounded
};

/// Time interval on a pre-arc: the arc is time-enabled when the clock of
/// its place lies in [lo, hi]. hi == kInf is unbounded. A deadline (`[lo,hi
/// deadline]`, hi finite) is a strong upper bound of this arc alone: no
/// tick takes its transition, enabled, past hi, whatever --timing says
/// (location invariants of discretised hybrid models).
struct Interval {
  uint32_t lo = 0;
  uint32_t hi = kInf;
  bool deadline = false;
  bool isTrivial() const { return lo == 0 && hi == kInf; }
  bool operator==(const Interval &o) const {
    return lo == o.lo && hi == o.hi && deadline == o.deadline;
  }
};

struct PreArc {
  uint32_t place;
  uint32_t weight = 1;
  Interval time;
};

struct PostArc {
  uint32_t place;
  uint32_t weight = 1;
};

/// Source of an event arc into a transition: another transition of the same
/// module or an event input port.
struct EventSource {
  uint32_t index;
  bool fromPort; // true: index into ports (an event input)
  bool operator==(const EventSource &o) const {
    return index == o.index && fromPort == o.fromPort;
  }
};

/// Rarely used parts of a transition, allocated only when present so that a
/// plain place/transition net stays small.
struct TransitionExtras {
  llvm::ArrayRef<Expr *> conds;       // condition arcs (Boolean signals)
  llvm::ArrayRef<EventSource> events; // incoming event arcs
  llvm::ArrayRef<uint32_t> emits;     // event arcs to event output ports
  Expr *guard = nullptr;              // data guard
  Block action;                       // action block
  bool hasAction = false;             // `{}` written (possibly empty)
  // Where each event source / emitted port was named (parsed input only).
  llvm::ArrayRef<llvm::SMLoc> eventLocs;
  llvm::ArrayRef<llvm::SMLoc> emitLocs;
};

/// A transition. Kept to 64 bytes: large nets have millions of them, so the
/// arcs are counted arrays in the Design's arena and everything a plain
/// place/transition net does not use lives in `extras`.
struct Transition {
  llvm::StringRef name;
  llvm::SMLoc loc;

  llvm::ArrayRef<PreArc> pre() const { return {preArcs, numPre}; }
  llvm::ArrayRef<PostArc> post() const { return {postArcs, numPost}; }
  /// Arcs are set as a whole (the Builder copies them into the arena).
  void setArcs(llvm::ArrayRef<PreArc> p, llvm::ArrayRef<PostArc> q) {
    preArcs = const_cast<PreArc *>(p.data());
    numPre = uint32_t(p.size());
    postArcs = const_cast<PostArc *>(q.data());
    numPost = uint32_t(q.size());
  }
  /// In-place access for passes and the parser's name resolution.
  llvm::MutableArrayRef<PreArc> mutablePre() { return {preArcs, numPre}; }
  llvm::MutableArrayRef<PostArc> mutablePost() { return {postArcs, numPost}; }

  TransitionExtras *extras = nullptr;
  EventMode mode = EventMode::Or;
  bool urgent = false;

  llvm::ArrayRef<Expr *> conds() const {
    return extras ? extras->conds : llvm::ArrayRef<Expr *>();
  }
  llvm::ArrayRef<EventSource> events() const {
    return extras ? extras->events : llvm::ArrayRef<EventSource>();
  }
  llvm::ArrayRef<uint32_t> emits() const {
    return extras ? extras->emits : llvm::ArrayRef<uint32_t>();
  }
  Expr *guard() const { return extras ? extras->guard : nullptr; }
  Block action() const { return extras ? extras->action : Block(); }
  bool hasAction() const { return extras && extras->hasAction; }
  /// Forced transitions have incoming event arcs.
  bool isForced() const { return !events().empty(); }

private:
  PreArc *preArcs = nullptr;
  PostArc *postArcs = nullptr;
  uint32_t numPre = 0, numPost = 0;
};

struct Var {
  llvm::StringRef name;
  llvm::SMLoc loc;
  const Type *type;
  /// Initial value (null: false / low bound / 0 for clocks).
  Expr *init = nullptr;
  /// Hybrid reals only: the initial value is anywhere from `init` to this
  /// (`in [a, b]`, a SpaceEx initial set); null: exactly `init`.
  Expr *initHi = nullptr;
};

/// `flow place { x' = e; y' in [a, b]; }`: while `place` is marked, real
/// variable x evolves with derivative e, and y with a derivative that may
/// be anything between a and b at every instant (a rectangular flow, the
/// differential inclusion a <= y' <= b).
struct Flow {
  llvm::SMLoc loc;
  uint32_t place;
  llvm::StringRef placeName;
  struct Equation {
    llvm::SMLoc loc;
    llvm::StringRef var;
    uint32_t varIndex = 0; // resolved by the verifier
    Expr *rate;
    /// Rectangular flows only: the highest rate (`rate` is the lowest);
    /// null for an equation x' = rate.
    Expr *rateHi = nullptr;
  };
  llvm::ArrayRef<Equation> equations;
};

/// `invariant place { x <= 5; }`: while `place` is marked, each condition
/// (over real and data variables) must hold: the location must be left
/// before one would fail (a hybrid location invariant; discretise makes it
/// deadlines).
struct Invariant {
  llvm::SMLoc loc;
  uint32_t place;
  llvm::StringRef placeName;
  llvm::ArrayRef<Expr *> conditions;
};

class Module;

/// Name -> Symbol for one module. Open addressing with linear probing over
/// 8-byte buckets that keep each name's hash, so growing never re-reads the
/// names and a probe rarely leaves its cache line; a hit is confirmed by
/// comparing the entity's own name. Millions of names stay cheap.
class SymbolTable {
public:
  Symbol lookup(llvm::StringRef name, const Module &m) const;
  /// False (and no change) if the name is taken.
  bool insert(llvm::StringRef name, Symbol s, const Module &m);
  void clear() {
    buckets.clear();
    count = 0;
  }
  /// Makes room for `n` names without growing again.
  void reserve(size_t n, const Module &m);
  size_t size() const { return count; }
  size_t bytes() const { return buckets.capacity() * sizeof(Bucket); }

private:
  struct Bucket {
    uint32_t hash;
    uint32_t packed; // kind << 28 | index; kEmpty when free
  };
  static constexpr uint32_t kEmpty = UINT32_MAX;
  void grow(const Module &m);
  std::vector<Bucket, HugePageAllocator<Bucket>> buckets;
  size_t count = 0;
};

struct Instance {
  llvm::StringRef name;
  llvm::SMLoc loc;
  llvm::StringRef moduleName;
  llvm::SMLoc moduleLoc;
  Module *module = nullptr; // resolved by the verifier
};

/// One end of a connection: `inst.port`, or `port` of the enclosing module.
struct Endpoint {
  llvm::StringRef instance; // empty: the enclosing module's own port
  llvm::StringRef port;
  llvm::SMLoc loc;
};

struct Connection {
  llvm::SMLoc loc;
  Endpoint from, to;
};

/// A named string attached to a module or to one of its entities
/// (`attr step pragma = "attribute 'hide'";`): what a frontend knows about
/// the source that has no meaning in the net, such as a PLC variable's
/// pragmas or the device and resource an IEC 61499 block is mapped to.
/// Analyses ignore attributes. They are kept beside the entities rather
/// than in them because few entities have any; passes keep them with their
/// entity (flatten qualifies the target; an entity a pass removes takes its
/// attributes with it).
/// `attr x needs_range = "x : INT";`: free input `x` (its source name and
/// type in the value) has its source type's
/// full range because the source gave none (a PLC integer input without a
/// `{range}`). Translating needs no range; the commands that enumerate
/// inputs (reach, check, sr, mealy) refuse such an input at its
/// declaration and ask for one.
inline constexpr llvm::StringLiteral kNeedsRangeAttribute = "needs_range";
/// `attr t.CLOCK unbounded_clock = "PT of timer 't'";`: a timer's clock
/// whose preset has no bound but its type's (a PLC timer's PT from an
/// input without a range): translating is exact, but counting to that cap
/// tick by tick cannot be explored; the exploring commands refuse it
/// unless timers are abstracted (--timers=abstract).
inline constexpr llvm::StringLiteral kUnboundedClockAttribute =
    "unbounded_clock";
/// `attr x observed = "output-variables";`: a real the model's user
/// observes though the model does not read it (the variables a SpaceEx
/// configuration plots): `discretise` keeps it instead of dropping it as
/// unobserved.
inline constexpr llvm::StringLiteral kObservedAttribute = "observed";
/// `attr t.STATE internal = "state of TON";`: an entity (or, on a scope,
/// every entity under it) a frontend or pass introduced that the source
/// does not name: a library block's own state, an event queue, a generated
/// block. Traces show the program's own names and hide these unless asked
/// (--trace-internals); analyses treat them like any other entity.
inline constexpr llvm::StringLiteral kInternalAttribute = "internal";

/// `attr t.ET scan_reset = "...";`: the PLC memory `t.ET` (a function-block
/// member the program never reads, or an input every call writes before the
/// block reads it) is reset to its initial value by the statements ending
/// each scan that writes it, so that states do not differ in a value the
/// model never reads. The PLC keeps the value: a command that observes the
/// variable (a property, --find, an sr attribute) keeps it too
/// (passes/KeepValues.h), traces show the value it has before the reset,
/// and the model's meaning for a reader of the text is the one without
/// the resets (docs/semantics.md, "Observers").
inline constexpr llvm::StringLiteral kScanResetAttribute = "scan_reset";

struct Attribute {
  /// An entity or instance of the module, a scope of its qualified names
  /// (`c` of `c.scan`, after flatten), or empty: the module itself.
  llvm::StringRef target;
  llvm::StringRef key;
  llvm::StringRef value;
  llvm::SMLoc loc;
};

/// A NetIR module (or a system: a module with no interface).
class Module {
public:
  Module(llvm::StringRef name, llvm::SMLoc loc, bool isSystem)
      : name(name), loc(loc), isSystem(isSystem) {}

  llvm::StringRef name;
  llvm::SMLoc loc;
  bool isSystem;

  // Entity tables can hold millions of entries; see HugePageAllocator.
  template <typename T> using Table = std::vector<T, HugePageAllocator<T>>;
  Table<Port> ports;
  Table<Place> places;
  Table<Transition> transitions;
  Table<Var> vars;
  std::vector<Flow> flows;
  std::vector<Invariant> invariants;
  std::vector<Instance> instances;
  std::vector<Connection> connections;
  /// In the order they were declared (printed in that order).
  std::vector<Attribute> attributes;

  /// One namespace for ports, places, transitions, variables and instances.
  /// Returns SymKind::None if absent.
  Symbol lookup(llvm::StringRef n) const { return symbols.lookup(n, *this); }
  /// Every name of that namespace (for "did you mean" in messages).
  std::vector<std::string> declaredNames() const;
  /// Registers a name; false if it is taken.
  bool declare(llvm::StringRef n, Symbol s) {
    return symbols.insert(n, s, *this);
  }
  size_t symbolTableBytes() const { return symbols.bytes(); }
  /// Size hint for large modules (the parser's estimate from the text).
  void reserve(size_t numPlaces, size_t numTransitions, size_t numVars) {
    places.reserve(numPlaces);
    transitions.reserve(numTransitions);
    vars.reserve(numVars);
    symbols.reserve(numPlaces + numTransitions + numVars + ports.size(), *this);
  }
  /// Rebuilds the symbol table from the entity vectors (after a pass
  /// removed or renamed entities), and drops the attributes of entities
  /// that are gone.
  void rebuildSymbols();
  /// Whether an attribute may name `target`: the module (empty), an
  /// entity or instance, or a scope of entity names.
  bool isAttributeTarget(llvm::StringRef target) const;
  /// Drops the attributes whose target is gone.
  void pruneAttributes();
  llvm::StringRef symbolName(Symbol s) const;
  int findPort(llvm::StringRef n) const;

private:
  SymbolTable symbols;
};

/// Time unit of one tick (`timescale 10ms;`).
struct Timescale {
  uint64_t amount = 1;
  llvm::StringRef unit; // ns, us, ms, s, min, h
  llvm::SMLoc loc;
  /// The length of one tick in nanoseconds.
  uint64_t nanoseconds() const;
  std::string str() const { return std::to_string(amount) + unit.str(); }
};

/// Everything one .net file holds; owns all memory of its modules.
/// Tokens a transition takes from and puts into one place (its arcs to the
/// place summed per side), places in order of first mention: what the
/// compiled P/T kernel and the P/T exports work with.
struct PlaceEffect {
  uint32_t place;
  uint64_t pre = 0, post = 0;
};
std::vector<PlaceEffect> placeEffects(const Transition &t);

class Design {
public:
  Design();
  ~Design();
  Design(const Design &) = delete;
  Design &operator=(const Design &) = delete;

  TypeTable types;
  std::optional<Timescale> timescale;
  std::vector<std::unique_ptr<Module>> modules;

  Module *lookupModule(llvm::StringRef n) const {
    auto it = moduleIndex.find(n);
    return it == moduleIndex.end() ? nullptr : it->second;
  }
  /// Records the timescale an input file declares. The files of one design
  /// must agree on the length of a tick (however it is spelled): false, and
  /// nothing changed, when `ts` differs from the one already recorded.
  bool mergeTimescale(const Timescale &ts) {
    if (timescale && timescale->nanoseconds() != ts.nanoseconds())
      return false;
    if (!timescale)
      timescale = ts;
    return true;
  }

  /// Creates a module; null if the name is taken.
  Module *createModule(llvm::StringRef name, llvm::SMLoc loc, bool isSystem);
  /// Removes a module (e.g. after flatten replaced the hierarchy).
  void eraseModule(Module *m);
  /// Renames a module; false if the new name is taken.
  bool renameModule(Module *m, llvm::StringRef newName);
  /// The module analyses start from: `name` if given, else the single
  /// system, else the single module no other module instantiates. Sets
  /// `why` and returns null when there is none or it is ambiguous.
  Module *findTop(llvm::StringRef name, std::string &why) const;

  // Arena allocation.
  llvm::StringRef save(llvm::StringRef s) {
    return llvm::StringRef(saveString(s), s.size());
  }
  template <typename T, typename... Args> T *create(Args &&...args) {
    return new (arena.Allocate<T>()) T(std::forward<Args>(args)...);
  }
  template <typename T> llvm::ArrayRef<T> copy(llvm::ArrayRef<T> a) {
    if (a.empty())
      return {};
    T *p = arena.Allocate<T>(a.size());
    std::uninitialized_copy(a.begin(), a.end(), p);
    return llvm::ArrayRef<T>(p, a.size());
  }
  TransitionExtras *createExtras() { return create<TransitionExtras>(); }
  size_t arenaBytes() const { return arena.getTotalMemory(); }

private:
  // 2 MiB slabs on huge pages: a large model allocates hundreds of MB here.
  llvm::BumpPtrAllocatorImpl<HugePageSlabAllocator, size_t(2) << 20> arena;
  char *saveString(llvm::StringRef s);
  llvm::StringMap<Module *> moduleIndex;
};

} // namespace netlift::net

#endif
