//===- CyclicOrder.cpp - a resource's blocks in one cycle -----------------===//
//
// fb2smv passes a token through the blocks of a network in the order they
// are written (a composite's blocks in its place), and a block holding it
// reacts to every event flag set since its last turn at once, then hands it
// on; events it sends set the flags of their destinations, which react at
// their own turns — later in this cycle or in the next. Under the cyclic
// model the translation gives every basic block event flags `_ev_<E>`,
// latched by its event inputs, and a reaction `recv__run` that samples,
// runs the ECC on the flags and clears them. On the flat module of a
// resource this makes those reactions the turns: `_turn` is the position
// the cycle has reached; the reaction of the first block at or after it
// with a pending flag fires (blocks with nothing pending pass the token
// without a step, as their turn changes nothing), once every block has sent
// what it queued; when no block at or after `_turn` has anything pending
// the cycle ends (`_turn` back to 0). Environment events and timers start a
// chain only when no cycle is due.
//
//===----------------------------------------------------------------------===//
#include "passes/CyclicOrder.h"

#include "passes/ForteOrder.h"
#include "passes/ReduceSupport.h"

#include "ir/net/Builder.h"

using namespace netlift;
using namespace netlift::net;
using llvm::SMLoc;
using llvm::StringRef;

namespace {
/// A block in the cycle: its name prefix in the flat module, its turn (the
/// `_run` reaction), its flags and its queue.
struct CycleBlock {
  std::string prefix;
  uint32_t turn;
  std::vector<std::string> flags;
  bool hasQueue = false;
};
} // namespace

bool iec61499::orderCyclically(Design &design, Module &m, DiagEngine &diag) {
  Builder b(design);
  b.setModule(&m);
  SMLoc at = m.loc;
  std::vector<CycleBlock> blocks;
  for (uint32_t i = 0; i < m.transitions.size(); ++i) {
    auto [prefix, local] = splitBlockName(m.transitions[i].name);
    if (local == "recv__run")
      blocks.push_back({prefix, i, {}, /*hasQueue=*/false});
  }
  if (blocks.empty())
    return true;
  std::map<std::string, size_t> byPrefix;
  for (size_t j = 0; j < blocks.size(); ++j)
    byPrefix[blocks[j].prefix] = j;
  for (const Var &v : m.vars) {
    auto [prefix, local] = splitBlockName(v.name);
    auto it = byPrefix.find(prefix);
    if (it == byPrefix.end())
      continue;
    if (local.startswith("_ev_"))
      blocks[it->second].flags.push_back(v.name.str());
    else if (local == "_queued")
      blocks[it->second].hasQueue = true;
  }

  const int64_t n = int64_t(blocks.size());
  b.addVar("_turn", design.types.getRange(0, n - 1), b.intLit(0, at), at);
  auto ref = [&](StringRef name) { return b.ref(name, at); };
  auto num = [&](int64_t v) { return b.intLit(v, at); };
  auto bin = [&](BinaryOp op, Expr *x, Expr *y) {
    return b.binary(op, x, y, at);
  };
  auto all = [&](std::vector<Expr *> terms) -> Expr * {
    Expr *e = nullptr;
    for (Expr *t : terms)
      e = e ? bin(BinaryOp::And, e, t) : t;
    return e ? e : b.boolLit(true, at);
  };
  auto pending = [&](const CycleBlock &blk) -> Expr * {
    Expr *e = nullptr;
    for (const std::string &f : blk.flags)
      e = e ? bin(BinaryOp::Or, e, ref(f)) : ref(f);
    return e ? e : b.boolLit(false, at);
  };
  // Every block has sent what it queued (the block that just reacted is
  // the only one that can have something queued).
  auto allSent = [&] {
    std::vector<Expr *> terms;
    for (const CycleBlock &blk : blocks)
      if (blk.hasQueue)
        terms.push_back(bin(BinaryOp::Eq, ref(blk.prefix + "_queued"), num(0)));
    return all(terms);
  };
  // Block k is due in this cycle: pending and not yet passed.
  auto due = [&](int64_t k) {
    return bin(BinaryOp::And, bin(BinaryOp::Le, ref("_turn"), num(k)),
               pending(blocks[k]));
  };

  std::set<uint32_t> ordered;
  for (int64_t j = 0; j < n; ++j) {
    CycleBlock &blk = blocks[j];
    std::vector<Expr *> terms = {allSent(), due(j)};
    for (int64_t k = 0; k < j; ++k)
      terms.push_back(b.unary(UnaryOp::Not, due(k), at));
    b.setEvents(blk.turn, {});
    b.setUrgent(blk.turn);
    b.setGuard(blk.turn, all(terms));
    std::vector<Stmt *> body(m.transitions[blk.turn].action().begin(),
                             m.transitions[blk.turn].action().end());
    body.push_back(b.assign(ref("_turn"), num(j + 1 < n ? j + 1 : 0), at));
    b.setAction(blk.turn, body);
    ordered.insert(blk.turn);
  }
  // The end of a cycle: nothing pending from `_turn` on.
  {
    std::vector<Expr *> terms = {bin(BinaryOp::Gt, ref("_turn"), num(0)),
                                 allSent()};
    for (int64_t k = 0; k < n; ++k)
      terms.push_back(b.unary(UnaryOp::Not, due(k), at));
    uint32_t end = b.addTransition("_cycle_end", {}, {}, at);
    b.setGuard(end, all(terms));
    b.setUrgent(end);
    b.setAction(end, {b.assign(ref("_turn"), num(0), at)});
    ordered.insert(end);
  }
  // A block's sends go right after its turn (they are urgent and only its
  // queue is non-empty). What starts a chain from outside — the
  // environment's queue, timers, and the environment's events themselves
  // where they reach a block directly (a basic FB translated alone) — waits
  // until no cycle is due, so the flags a turn clears are never set in the
  // same step.
  auto quiescent = [&] {
    std::vector<Expr *> terms = {bin(BinaryOp::Eq, ref("_turn"), num(0)),
                                 allSent()};
    for (const CycleBlock &blk : blocks)
      terms.push_back(b.unary(UnaryOp::Not, pending(blk), at));
    return all(terms);
  };
  for (uint32_t i = 0; i < m.transitions.size(); ++i) {
    const Transition &t = m.transitions[i];
    auto [prefix, local] = splitBlockName(t.name);
    if (!byPrefix.count(prefix))
      continue;
    if (local.startswith("send_"))
      ordered.insert(i);
    bool fromEnvironment =
        t.isForced() &&
        std::all_of(t.events().begin(), t.events().end(),
                    [](const EventSource &e) { return e.fromPort; });
    if (local.startswith("recv_") && i != blocks[byPrefix[prefix]].turn &&
        fromEnvironment) {
      Expr *g = t.guard();
      b.setGuard(i, g ? bin(BinaryOp::And, g, quiescent()) : quiescent());
    }
  }
  waitForIdle(b, m, ordered, quiescent);

  // The turns' event inputs are gone: nothing outside the cycle gives
  // turns.
  std::vector<bool> keepPort(m.ports.size(), true);
  for (const CycleBlock &blk : blocks) {
    int p = m.findPort(blk.prefix + "_run");
    if (p < 0) {
      diag.error(m.transitions[blk.turn].loc,
                 "internal: the cycle's turn without its event input");
      return false;
    }
    keepPort[p] = false;
  }
  reduce::removePorts(design, m, keepPort);
  m.rebuildSymbols();
  return true;
}
