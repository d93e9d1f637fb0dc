//===- LatchInputs.cpp - free inputs kept as the PLC's input image --------===//
//
// See LatchInputs.h. For each latched input `x`: the port becomes `x.env`
// (the environment's value, free at every step as before), a variable `x`
// of its type (initially its default, as a PLC's image before the first
// scan) is added, and the one transition that reads the input starts its
// action with `x := x.env`, so that the variable holds what the last
// firing of that transition read. The transition's guard, conditions and
// action still read the input itself: the model's behaviour is unchanged.
//
//===----------------------------------------------------------------------===//
#include "passes/LatchInputs.h"

#include "passes/Pass.h"
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"
#include "ir/net/Names.h"
#include "ir/net/Walk.h"

#include <cctype>
#include <set>

using namespace netlift;
using namespace netlift::net;

std::string netlift::latchedEnvironmentInput(llvm::StringRef name) {
  return name.str() + ".env";
}

std::vector<std::string> netlift::inputsNamedIn(const Module &m,
                                                llvm::StringRef text) {
  std::vector<std::string> named = qualifiedNamesIn(text);
  std::set<std::string> words(named.begin(), named.end());
  std::vector<std::string> out;
  for (const Port &p : m.ports)
    if (p.isInput() && p.kind != PortKind::Event && words.count(p.name.str()))
      out.push_back(p.name.str());
  return out;
}

static bool readsPort(const Expr *e, uint32_t port) {
  bool found = false;
  walkExpr(e, [&](const Expr *x) {
    if (auto *r = llvm::dyn_cast<Ref>(x))
      found |= r->sym.kind == SymKind::Port && r->sym.index == port;
  });
  return found;
}

/// The transitions that read any free input of `m`; when none does, those
/// with an action.
static std::set<int> inputSamplers(const Module &m) {
  std::set<int> out;
  forEachRead(m, [&](const Expr *e, int t) {
    if (t < 0 || out.count(t))
      return;
    walkExpr(e, [&](const Expr *x) {
      if (auto *r = llvm::dyn_cast<Ref>(x);
          r && r->sym.kind == SymKind::Port && m.ports[r->sym.index].isInput())
        out.insert(t);
    });
  });
  if (out.empty())
    for (const Transition &t : m.transitions)
      if (t.hasAction())
        out.insert(int(&t - &m.transitions[0]));
  return out;
}

bool netlift::latchInputs(Design &d, Module &m,
                          const std::vector<std::string> &names,
                          DiagEngine &diag) {
  if (names.empty())
    return true;
  Builder b(d);
  b.setModule(&m);
  for (const std::string &name : names) {
    Symbol s = m.lookup(name);
    const Port *port = s.kind == SymKind::Port ? &m.ports[s.index] : nullptr;
    if (!port || !port->isInput() || port->kind == PortKind::Event) {
      diag.error(llvm::SMLoc(), "latch: '" + name +
                                    "' is not a free cond or "
                                    "data input of module '" +
                                    m.name + "'");
      return false;
    }
    std::string env = latchedEnvironmentInput(name);
    if (m.lookup(env).kind != SymKind::None) {
      diag.error(port->loc, "latch: '" + env + "' is taken; latching input '" +
                                name +
                                "' needs that name for the environment's "
                                "value");
      return false;
    }
    std::set<int> readers;
    forEachRead(m, [&](const Expr *e, int t) {
      if (t >= 0 && readsPort(e, s.index))
        readers.insert(t);
    });
    // An input the program never reads is still in the input image a
    // PLC's scan samples: it is latched by the step that samples the
    // module's other inputs, or, when none does, by its one transition
    // with an action.
    if (readers.empty())
      readers = inputSamplers(m);
    if (readers.size() != 1) {
      std::string which;
      for (int t : readers)
        which +=
            (which.empty() ? "'" : ", '") + m.transitions[t].name.str() + "'";
      diag.error(port->loc,
                 "input '" + name + "' is read by " +
                     (readers.empty() ? std::string("no transition, and no "
                                                    "transition has an action")
                                      : std::to_string(readers.size()) +
                                            " transitions (" + which + ")") +
                     ": a property can name an input through the value "
                     "the step reading it saw (the PLC's input image), "
                     "which needs exactly one transition reading it, as a "
                     "PLC's scan does");
      return false;
    }
    uint32_t reader = *readers.begin();
    llvm::SMLoc at = port->loc;
    const Type *type = port->type;
    // Every reference to the input is re-spelled: names are resolved again
    // below, and `name` becomes the image variable's.
    llvm::StringRef envName = d.save(env);
    forEachRead(m, [&](const Expr *e, int) {
      walkExpr(e, [&](const Expr *x) {
        if (auto *r = llvm::dyn_cast<Ref>(x);
            r && r->sym.kind == SymKind::Port && r->sym.index == s.index)
          const_cast<Ref *>(r)->name = envName;
      });
    });
    for (Attribute &a : m.attributes)
      if (a.target == name)
        a.target = envName;
    m.ports[s.index].name = envName;
    m.rebuildSymbols();
    b.addVar(d.save(name), type, nullptr, at);
    std::vector<Stmt *> body{
        b.assign(b.ref(d.save(name), at), b.ref(envName, at), at)};
    if (m.transitions[reader].hasAction())
      for (Stmt *st : m.transitions[reader].action())
        body.push_back(st);
    b.setAction(reader, body);
    diag.note(at, "input '" + name + "' is latched for this run: '" + name +
                      "' is the value the last firing of '" +
                      m.transitions[reader].name +
                      "' read (the PLC's input image), '" + env +
                      "' the environment's");
  }
  return reduce::reverify(d, diag, "latch-inputs");
}

namespace {

class LatchInputsPass : public Pass {
public:
  explicit LatchInputsPass(const PassOptions &opts) : opts(opts) {}
  bool run(Design &d, DiagEngine &diag, Statistics &stats) override {
    Module *m = reduce::flatTop(d, diag, opts, "latch-inputs");
    if (!m)
      return false;
    std::vector<std::string> names = opts.list("inputs");
    if (!latchInputs(d, *m, names, diag))
      return false;
    stats.add("latch-inputs", "latched", names.size(), "inputs latched");
    return true;
  }

private:
  PassOptions opts;
};

} // namespace

namespace netlift {
std::unique_ptr<Pass> createLatchInputsPass(const PassOptions &opts) {
  return std::make_unique<LatchInputsPass>(opts);
}
} // namespace netlift
