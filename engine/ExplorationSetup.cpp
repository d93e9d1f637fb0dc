//===- ExplorationSetup.cpp - one state space for every command -----------===//
#include "engine/ExplorationSetup.h"

#include "ir/net/ExecutedOnly.h"
#include "ir/net/ScanResets.h"
#include "ir/net/Walk.h"

#include <functional>

#include "ir/net/Verifier.h"
#include "passes/Flatten.h"
#include "passes/KeepValues.h"
#include "passes/LatchInputs.h"
#include "passes/Pass.h"

#include "llvm/Support/raw_ostream.h"

using namespace netlift;
using namespace netlift::engine;

bool engine::parseByteSize(llvm::StringRef text, uint64_t &out) {
  uint64_t mult = 1;
  if (text.endswith_insensitive("k"))
    mult = 1ull << 10;
  else if (text.endswith_insensitive("m"))
    mult = 1ull << 20;
  else if (text.endswith_insensitive("g"))
    mult = 1ull << 30;
  if (mult != 1)
    text = text.drop_back();
  if (text.getAsInteger(10, out))
    return false;
  out *= mult;
  return true;
}

/// Per port: is it an input that a transition reads (directly, or through
/// the definitions of the outputs it reads)?
static std::vector<bool> inputsRead(const net::Module &m) {
  std::vector<bool> read(m.ports.size(), false), seen(m.ports.size(), false);
  std::function<void(const net::Expr *)> visit = [&](const net::Expr *root) {
    net::walkExpr(root, [&](const net::Expr *e) {
      auto *r = llvm::dyn_cast<net::Ref>(e);
      if (!r || r->sym.kind != net::SymKind::Port || seen[r->sym.index])
        return;
      seen[r->sym.index] = true;
      const net::Port &p = m.ports[r->sym.index];
      if (p.isInput())
        read[r->sym.index] = true;
      else if (p.definition)
        visit(p.definition);
    });
  };
  net::forEachRead(m, [&](const net::Expr *root, int t) {
    if (t >= 0)
      visit(root);
  });
  return read;
}

net::Module *engine::explorableTop(net::Design &design, llvm::StringRef topName,
                                   DiagEngine &diag, llvm::StringRef command) {
  std::string why;
  net::Module *top = design.findTop(topName, why);
  if (!top) {
    diag.error(llvm::SMLoc(), command + ": " + why);
    return nullptr;
  }
  if (!top->instances.empty()) {
    PassManager pm;
    std::string pipeline = "flatten{top=" + top->name.str() + "}";
    if (!pm.parsePipeline(pipeline, diag) || !pm.run(design, diag) ||
        !net::verifyDesign(design, diag))
      return nullptr;
    top = design.modules[0].get();
  }
  if (net::hasHybridParts(*top)) {
    diag.error(llvm::SMLoc(), command + ": module '" + top->name +
                                  "' has real variables or flows; run the "
                                  "discretise pass first");
    return nullptr;
  }
  return top;
}

ExplorationSetup::ExplorationSetup(net::Module &top,
                                   const ExplorationOptions &options)
    : module(&top), opts(options),
      stateLayout(std::make_unique<sem::StateLayout>(
          top, options.semantics.unboundedBits)),
      sem(std::make_unique<sem::Semantics>(top, *stateLayout,
                                           options.semantics)) {}

std::unique_ptr<ExplorationSetup>
ExplorationSetup::create(net::Design &design, const ExplorationOptions &options,
                         DiagEngine &diag, llvm::StringRef command) {
  net::Module *top = explorableTop(design, options.top, diag, command);
  if (!top)
    return nullptr;
  // Inputs a property names are kept as the PLC's input image, for this
  // run only (passes/LatchInputs.h).
  std::vector<std::string> latch = options.latch;
  for (const std::string &text : options.propertyTexts)
    for (std::string &name : inputsNamedIn(*top, text))
      if (llvm::find(latch, name) == latch.end())
        latch.push_back(std::move(name));
  if (!latchInputs(design, *top, latch, diag))
    return nullptr;
  // PLC memory an observer names keeps its value past the end of the scan
  // (passes/KeepValues.h): the reset of what the model never reads may only
  // drop what no one sees.
  std::vector<std::string> keep = options.keep;
  if (options.keepAll)
    for (uint32_t v : net::scanResetVars(*top))
      keep.push_back(top->vars[v].name.str());
  for (const auto *texts : {&options.propertyTexts, &options.observerTexts})
    for (const std::string &text : *texts)
      for (std::string &name : net::scanResetVarsNamedIn(*top, text))
        keep.push_back(std::move(name));
  llvm::sort(keep);
  keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  if (!keepValues(design, *top, keep, diag, /*lenient=*/options.keep.empty()))
    return nullptr;
  // Enumerating, every value of every input is tried at every step; split
  // on demand, only the values the program tells apart (and strings are
  // still too many).
  bool split = options.semantics.splitInputs;
  auto unenumerable = [&](const net::Type *t) -> const char * {
    const char *what = net::executedOnlyData(t);
    return !split || (what && llvm::StringRef(what) == "a string") ? what
                                                                   : nullptr;
  };
  // Split on demand, an input nothing reads is never decided: what only an
  // unread output shows (an environment block's STATUS) needs no values.
  std::vector<bool> read =
      split ? inputsRead(*top) : std::vector<bool>(top->ports.size(), true);
  if (options.enumeratesInputs)
    for (const net::Port &p : top->ports)
      if (const char *what = p.isInput() && p.type && read[&p - &top->ports[0]]
                                 ? unenumerable(p.type)
                                 : nullptr) {
        diag.error(p.loc, "free input '" + p.name + "' of type " +
                              p.type->str() + ": " + command +
                              " cannot enumerate its values (" + what +
                              ") at every step; connect it to a model of what "
                              "drives it (`netlift compose`), or give it a "
                              "value in the program");
        return nullptr;
      }
  if (options.enumeratesInputs && !split)
    for (const net::Attribute &a : top->attributes) {
      if (a.key != net::kNeedsRangeAttribute)
        continue;
      net::Symbol s = top->lookup(a.target);
      if (s.kind != net::SymKind::Port || !top->ports[s.index].isInput())
        continue; // connected in a closed loop: no longer free
      auto [source, type] = a.value.split(" : ");
      diag.error(a.loc, "input '" + source + "' of type " + type +
                            " has no range: " + command +
                            " would enumerate every value at every step "
                            "(--inputs=enumerate); give its range with a "
                            "pragma {range LO..HI} before the declaration, a "
                            "subrange type, or --ranges FILE");
      return nullptr;
    }
  if (!options.abstractTimers)
    for (const net::Attribute &a : top->attributes)
      if (a.key == net::kUnboundedClockAttribute) {
        diag.error(a.loc, a.value + " has no bound but its type's: " + command +
                              " would count its clock tick by tick up to "
                              "it; give the input it comes from a range "
                              "(--ranges FILE, {range LO..HI}) or explore "
                              "with --timers=abstract");
        return nullptr;
      }
  if (!options.abstractTimers) {
    auto setup =
        std::unique_ptr<ExplorationSetup>(new ExplorationSetup(*top, options));
    setup->tick = design.timescale;
    setup->sources = &diag.sourceMgr();
    setup->latchedInputs = std::move(latch);
    return setup;
  }
  // The exact model stays beside the abstract one, for the replay.
  net::Module *exact = flattenModule(design, top, diag);
  if (!exact || !net::verifyDesign(design, diag))
    return nullptr;
  design.renameModule(exact, top->name.str() + ".exact");
  TimerAbstraction timers;
  if (!abstractTimers(design, *top, options.exactClocks, diag,
                      options.timerNotes, timers))
    return nullptr;
  auto setup =
      std::unique_ptr<ExplorationSetup>(new ExplorationSetup(*top, options));
  setup->tick = design.timescale;
  setup->sources = &diag.sourceMgr();
  setup->latchedInputs = std::move(latch);
  setup->timers = std::move(timers);
  setup->exactTop = exact;
  setup->exactLayout = std::make_unique<sem::StateLayout>(
      *exact, options.semantics.unboundedBits);
  setup->exactSem = std::make_unique<sem::Semantics>(
      *exact, *setup->exactLayout, options.semantics);
  return setup;
}

std::string ExplorationSetup::summaryJsonFields() const {
  std::string out;
  if (opts.abstractTimers)
    out += ",\"timers\":{\"abstracted\":" +
           std::to_string(timers.abstracted.size()) +
           ",\"exact\":" + std::to_string(timers.kept.size()) + "}";
  if (!latchedInputs.empty()) {
    out += ",\"latched\":[";
    for (size_t i = 0; i < latchedInputs.size(); ++i)
      out += (i ? ",\"" : "\"") + latchedInputs[i] + "\"";
    out += "]";
  }
  return out;
}

void ExplorationSetup::noteUnkeptValues(DiagEngine &diag,
                                        llvm::StringRef what) const {
  llvm::DenseSet<uint32_t> vars = net::scanResetVars(*module);
  if (vars.empty())
    return;
  std::vector<uint32_t> sorted(vars.begin(), vars.end());
  llvm::sort(sorted);
  std::string names;
  for (size_t i = 0; i < sorted.size() && i < 10; ++i)
    names += (i ? ", '" : "'") + module->vars[sorted[i]].name.str() + "'";
  if (sorted.size() > 10)
    names += ", ...";
  diag.note(llvm::SMLoc(),
            std::to_string(sorted.size()) +
                " function-block member(s) the program never reads are reset "
                "at the end of each scan " +
                (what == "state file" ? "and left out of the state file ("
                                      : "in this " + what.str() + " (") +
                names +
                "); --keep NAME,... keeps their values, and a property or "
                "--find naming one keeps it");
}

ExploreOptions ExplorationSetup::exploreOptions() const {
  ExploreOptions eo;
  eo.maxStates = opts.maxStates;
  eo.maxMemory = opts.maxMemory;
  eo.timeLimit = opts.timeLimit;
  return eo;
}

void engine::reportRuntimeErrorAt(const sem::RuntimeError &error,
                                  DiagEngine &diag) {
  if (!error.loc.isValid()) {
    diag.error(llvm::SMLoc(), error.message);
    return;
  }
  diag.error(error.loc, (error.limit ? "" : "runtime error: ") + error.message);
  // A model read from NetIR text: the expression is in the .net, the
  // statement it belongs to in the program it was translated from.
  const llvm::SourceMgr &sm = diag.sourceMgr();
  if (error.statement.isValid() &&
      sm.FindBufferContainingLoc(error.statement) !=
          sm.FindBufferContainingLoc(error.loc))
    diag.note(error.statement, "in this statement of the program");
}
