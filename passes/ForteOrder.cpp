//===- ForteOrder.cpp - one FIFO of pending events per resource -----------===//
//
// 4diac FORTE runs a resource's events from one FIFO: a block's reaction
// appends the output events it produces, and the event at the head goes
// next. In the modules the translation builds, every block keeps its own
// queue and any block's head may go next. On the flat module of a
// resource this adds the resource's queue (event codes in `_fifo[0 ..
// _fifo_n-1]`): every reaction of a block takes the event it reacts to off
// the head and appends the events it queued, in order; a block's send is
// enabled only when its event heads the queue; the environment's events
// and the timers (E_DELAY, E_CYCLE, E_RESTART) start a new chain only when
// the queue is empty, as FORTE takes
// external events after the current chain. A chain is then one run, not
// every interleaving of its blocks (docs/iec61499.md).
//
//===----------------------------------------------------------------------===//
#include "passes/ForteOrder.h"

#include "ir/net/Builder.h"

#include "llvm/Support/Casting.h"

#include <map>
#include <set>

using namespace netlift;
using namespace netlift::net;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

/// A block of the flat module: its name prefix (`a.b.` or empty) and the
/// number each of its sends carries in its queue.
struct EventBlock {
  std::string prefix;
  std::vector<std::pair<uint32_t, int64_t>> sends; // transition, number
  std::vector<uint32_t> reactions;
  int64_t base = 0;
};

/// The number in `_queue[0] == N`, the guard the translation gives a send.
int64_t sendNumber(const Transition &t) {
  auto *eq = llvm::dyn_cast_or_null<BinaryExpr>(t.guard());
  if (!eq || eq->op != BinaryOp::Eq)
    return -1;
  auto *n = llvm::dyn_cast<IntLit>(eq->rhs);
  return n ? n->value : -1;
}

} // namespace

bool iec61499::orderLikeForte(Design &design, Module &m, DiagEngine &diag) {
  Builder b(design);
  b.setModule(&m);
  SMLoc at = m.loc;

  // Blocks by their queue variables.
  std::map<std::string, EventBlock> blocks;
  for (const Var &v : m.vars) {
    StringRef name = v.name;
    // The queue of the environment's events is not a block of the chain:
    // its sends start chains, like timers.
    if (name.startswith("_inputs."))
      continue;
    if (name == "_queued" || name.endswith("._queued"))
      blocks[name.drop_back(strlen("_queued")).str()].prefix =
          name.drop_back(strlen("_queued")).str();
  }
  if (blocks.empty())
    return true;
  for (uint32_t i = 0; i < m.transitions.size(); ++i) {
    auto [prefix, local] = splitBlockName(m.transitions[i].name);
    auto it = blocks.find(prefix);
    if (it == blocks.end())
      continue;
    if (local.startswith("send_")) {
      int64_t n = sendNumber(m.transitions[i]);
      if (n < 1) {
        diag.error(m.transitions[i].loc,
                   "internal: send without its queue guard");
        return false;
      }
      it->second.sends.push_back({i, n});
    } else if (local.startswith("recv_")) {
      it->second.reactions.push_back(i);
    }
  }
  int64_t codes = 0;
  for (auto &[prefix, block] : blocks) {
    block.base = codes;
    int64_t most = 0;
    for (auto &[t, n] : block.sends)
      most = std::max(most, n);
    codes += most;
  }
  // Room for every block's queue, within reason; more is a runtime error.
  const int64_t room = std::min<int64_t>(8 * int64_t(blocks.size()), 64);
  b.addVar("_fifo",
           design.types.getArray(design.types.getRange(0, codes), 0, room - 1),
           nullptr, at);
  b.addVar("_fifo_n", design.types.getRange(0, room), b.intLit(0, at), at);
  b.addVar("_fifo_k", design.types.getRange(0, 8), b.intLit(0, at), at);
  b.addVar("_fifo_overflow", design.types.getRange(0, 0), b.intLit(0, at), at);
  for (StringRef v : {"_fifo", "_fifo_n", "_fifo_k", "_fifo_overflow"})
    b.addAttribute(v, net::kInternalAttribute, "the resource's event queue",
                   at);

  auto ref = [&](StringRef n) { return b.ref(n, at); };
  auto num = [&](int64_t v) { return b.intLit(v, at); };
  auto bin = [&](BinaryOp op, Expr *x, Expr *y) {
    return b.binary(op, x, y, at);
  };
  auto conj = [&](Expr *g, Expr *extra) {
    return g ? bin(BinaryOp::And, g, extra) : extra;
  };
  auto idle = [&] { return bin(BinaryOp::Eq, ref("_fifo_n"), num(0)); };
  auto block = [&](std::vector<Stmt *> body) {
    return design.copy(llvm::ArrayRef<Stmt *>(body));
  };
  // Taking the head off: the rest moves up (entries past the count stay 0,
  // so equal queues are equal states).
  auto pop = [&] {
    std::vector<Stmt *> shift = {b.assign(
        b.index(ref("_fifo"), ref("_j"), at),
        b.index(ref("_fifo"), bin(BinaryOp::Add, ref("_j"), num(1)), at), at)};
    std::vector<Stmt *> body = {
        b.forStmt("_j", num(0), num(room - 2), shift, at),
        b.assign(b.index(ref("_fifo"), num(room - 1), at), num(0), at),
        b.assign(ref("_fifo_n"), bin(BinaryOp::Sub, ref("_fifo_n"), num(1)),
                 at)};
    return b.ifStmt(
        {IfArm{bin(BinaryOp::Gt, ref("_fifo_n"), num(0)), block(body)}}, false,
        {}, at);
  };

  // The transitions whose events something listens to, and those a
  // block's reaction listens to (a reaction always fires on its event; a
  // timer's START or STOP may not, so their senders take themselves off).
  std::set<uint32_t> heardByReaction;
  for (auto &[prefix, blk] : blocks)
    for (uint32_t r : blk.reactions)
      for (const EventSource &e : m.transitions[r].events())
        if (!e.fromPort)
          heardByReaction.insert(e.index);
  std::set<uint32_t> touched;

  for (auto &[prefix, blk] : blocks) {
    // A reaction to a sent event takes that event off the ring (one step,
    // one writer), then appends the events it queued, in their order. The
    // ring is empty when a chain starts, so a reaction with a non-empty
    // ring was started by the send of its head.
    for (uint32_t t : blk.reactions) {
      std::string queued = prefix + "_queued", queue = prefix + "_queue";
      std::vector<Stmt *> body;
      body.push_back(b.assign(ref("_fifo_k"), ref(queued), at));
      for (Stmt *s : m.transitions[t].action())
        body.push_back(s);
      body.push_back(pop());
      std::vector<Stmt *> append = {
          // A full ring is a runtime error (1 is outside 0..0).
          b.assign(ref("_fifo_overflow"),
                   bin(BinaryOp::Div, ref("_fifo_n"), num(room)), at),
          b.assign(b.index(ref("_fifo"), ref("_fifo_n"), at),
                   bin(BinaryOp::Add, num(blk.base),
                       b.index(ref(queue), ref("_i"), at)),
                   at),
          b.assign(ref("_fifo_n"), bin(BinaryOp::Add, ref("_fifo_n"), num(1)),
                   at)};
      Expr *fresh =
          bin(BinaryOp::And, bin(BinaryOp::Ge, ref("_i"), ref("_fifo_k")),
              bin(BinaryOp::Lt, ref("_i"), ref(queued)));
      body.push_back(b.forStmt(
          "_i", num(0), num(7),
          {b.ifStmt({IfArm{fresh, block(append)}}, false, {}, at)}, at));
      body.push_back(b.assign(ref("_fifo_k"), num(0), at));
      b.setAction(t, body);
      touched.insert(t);
    }
    // A send goes when its event heads the queue; one no reaction hears
    // takes itself off.
    for (auto &[t, n] : blk.sends) {
      Expr *mine = bin(BinaryOp::And, bin(BinaryOp::Gt, ref("_fifo_n"), num(0)),
                       bin(BinaryOp::Eq, b.index(ref("_fifo"), num(0), at),
                           num(blk.base + n)));
      b.setGuard(t, conj(m.transitions[t].guard(), mine));
      if (!heardByReaction.count(t)) {
        std::vector<Stmt *> body;
        for (Stmt *s : m.transitions[t].action())
          body.push_back(s);
        body.push_back(pop());
        b.setAction(t, body);
      }
      touched.insert(t);
    }
  }
  waitForIdle(b, m, touched, idle);
  return true;
}

std::pair<std::string, StringRef> iec61499::splitBlockName(StringRef name) {
  size_t dot = name.rfind('.');
  if (dot == StringRef::npos)
    return {"", name};
  return {name.take_front(dot + 1).str(), name.drop_front(dot + 1)};
}

void iec61499::waitForIdle(Builder &b, Module &m,
                           const std::set<uint32_t> &ordered,
                           llvm::function_ref<Expr *()> idle) {
  std::set<uint32_t> heard;
  for (const Transition &t : m.transitions)
    for (const EventSource &e : t.events())
      if (!e.fromPort)
        heard.insert(e.index);
  for (uint32_t i = 0; i < m.transitions.size(); ++i) {
    const Transition &t = m.transitions[i];
    if (ordered.count(i) || t.isForced())
      continue;
    if (heard.count(i) || !t.emits().empty()) {
      Expr *g = t.guard();
      b.setGuard(i, g ? b.binary(BinaryOp::And, g, idle(), t.loc) : idle());
    }
  }
}
