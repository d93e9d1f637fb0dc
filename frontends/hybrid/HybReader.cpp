//===- HybReader.cpp - Stateflow-like hybrid charts (.hyb) to NetIR -------===//
//
// A `.hyb` file holds charts (docs/hybrid.md): inputs, outputs (sensors
// defined as thresholds), parameters, real variables with ranges, discrete
// variables, states with entry/during/exit actions and flow equations,
// parallel regions, and transitions `A -> B : event [guard] {action} emit
// e;`. Each chart becomes one NetIR module with `real` variables and
// `flow` blocks, ready for the `discretise` pass:
//   - a state is a place (the initial state of each region is marked);
//   - a transition is a NetIR transition from its source to its target
//     place, `on` its event (an event input), with its guard, `urgent` when
//     it has no event (a chart takes a transition as soon as it can), and
//     the action exit(source); action; entry(target);
//   - a state's flow equations become `flow state { x' = e; }`;
//   - a during action runs once per tick: `state[1,1] -> state urgent`;
//   - parameters are replaced by their values wherever they are used.
// Expressions, types and statements are NetIR's (ir/net/Parser.h's
// EmbeddedParser), so positions in errors point into the .hyb file.
//
//===----------------------------------------------------------------------===//
#include "frontends/FrontendRegistry.h"

#include "ir/net/Builder.h"
#include "ir/net/Parser.h"

#include "llvm/ADT/StringMap.h"

#include <cmath>
#include <optional>

using namespace netlift;
using namespace netlift::net;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

struct HybState {
  StringRef name;
  SMLoc loc;
  unsigned region = 0;
  Block entry, during, exit;
  SMLoc entryLoc;
  std::vector<Flow::Equation> flows;
  SMLoc flowLoc;
  std::vector<Expr *> invariant; // `invariant x <= D;`, conjoined
  SMLoc invariantLoc;
};

struct HybTransition {
  StringRef from, to;
  SMLoc loc, fromLoc, toLoc;
  StringRef event;
  SMLoc eventLoc;
  Expr *guard = nullptr;
  Block action;
  bool hasAction = false;
  std::vector<std::pair<StringRef, SMLoc>> emits;
};

class ChartReader {
public:
  ChartReader(EmbeddedParser &p, Design &d, DiagEngine &diag)
      : p(p), d(d), b(d), diag(diag) {}
  bool parseFile();

private:
  const Token &tok() const { return p.token(); }
  bool isKw(StringRef k) const { return tok().isIdent(k); }
  bool expectKw(StringRef k) {
    if (isKw(k)) {
      p.consume();
      return true;
    }
    return p.errorHere("expected '" + k + "', found '" + tok().text + "'");
  }
  bool parseChart();
  bool parseItem(unsigned region);
  bool parsePorts(PortDir dir);
  bool parseParam();
  bool parseReal();
  bool parseVar();
  bool parseState(unsigned region);
  bool parseTransition(unsigned region);
  bool build();
  /// Replaces parameter names by their values (in place).
  Expr *substitute(Expr *e);
  /// Substitutes in place, in every statement of `blk`.
  void substituteIn(Block blk);

  EmbeddedParser &p;
  Design &d;
  Builder b;
  DiagEngine &diag;

  // The chart being read.
  StringRef chartName;
  SMLoc chartLoc;
  llvm::StringMap<Expr *> params;
  std::vector<HybState> states;
  llvm::StringMap<unsigned> stateIndex;
  std::vector<HybTransition> transitions;
  std::vector<std::pair<StringRef, SMLoc>> initials; // per region
  std::vector<StringRef> regionNames;
  struct PendingReal {
    StringRef name;
    SMLoc loc;
    Expr *lo, *hi, *init;
  };
  std::vector<PendingReal> pendingReals;
  bool declareReal(const PendingReal &r);
  Module *mod = nullptr;
};

} // namespace

bool ChartReader::parseFile() {
  if (isKw("timescale")) {
    SMLoc loc = tok().loc();
    p.consume();
    if (!tok().is(Tok::Int))
      return p.errorHere("expected a number after 'timescale'");
    uint64_t amount;
    if (tok().text.getAsInteger(10, amount) || amount == 0)
      return p.errorHere("the timescale must be a positive whole number");
    p.consume();
    StringRef unit = tok().text;
    if (!tok().is(Tok::Ident) ||
        !(unit == "ns" || unit == "us" || unit == "ms" || unit == "s" ||
          unit == "min" || unit == "h"))
      return p.errorHere("expected a time unit (ns us ms s min h)");
    p.consume();
    if (!p.expect(Tok::Semi, "';'"))
      return false;
    Timescale ts{amount, d.save(unit), loc};
    if (!d.mergeTimescale(ts)) {
      p.error(loc, "timescale " + ts.str() + " differs from the timescale " +
                       d.timescale->str() +
                       " of an earlier file; the models of one design "
                       "must agree on the length of a tick");
      return false;
    }
  }
  bool any = false;
  while (!tok().is(Tok::Eof)) {
    if (!isKw("chart"))
      return p.errorHere("expected 'chart', found '" + tok().text + "'");
    if (!parseChart())
      return false;
    any = true;
  }
  if (!any)
    return p.errorHere("no chart in this file");
  return true;
}

bool ChartReader::parseChart() {
  p.consume();
  params.clear();
  states.clear();
  stateIndex.clear();
  transitions.clear();
  pendingReals.clear();
  initials.assign(1, {StringRef(), SMLoc()});
  regionNames.assign(1, StringRef());
  if (!p.name(chartName, chartLoc, "a chart name"))
    return false;
  mod = b.createModule(chartName, false, chartLoc);
  if (!mod)
    return p.error(chartLoc, "a module named '" + chartName + "' exists");
  if (!p.expect(Tok::LBrace, "'{'"))
    return false;
  while (!tok().is(Tok::RBrace)) {
    if (tok().is(Tok::Eof))
      return p.errorHere("expected '}' to end the chart");
    if (isKw("region")) {
      p.consume();
      StringRef rn;
      SMLoc rl;
      if (!p.name(rn, rl, "a region name") || !p.expect(Tok::LBrace, "'{'"))
        return false;
      unsigned r = regionNames.size();
      regionNames.push_back(rn);
      initials.push_back({StringRef(), SMLoc()});
      while (!tok().is(Tok::RBrace)) {
        if (tok().is(Tok::Eof))
          return p.errorHere("expected '}' to end the region");
        if (!(isKw("state") || isKw("initial") || tok().is(Tok::Ident)))
          return p.errorHere("expected a state, 'initial' or a transition "
                             "in a region");
        if (!parseItem(r))
          return false;
      }
      p.consume();
      continue;
    }
    if (!parseItem(0))
      return false;
  }
  p.consume();
  return build();
}

bool ChartReader::parseItem(unsigned region) {
  if (isKw("input") || isKw("output")) {
    PortDir dir = isKw("input") ? PortDir::In : PortDir::Out;
    p.consume();
    return parsePorts(dir);
  }
  if (isKw("param"))
    return parseParam();
  if (isKw("real"))
    return parseReal();
  if (isKw("var"))
    return parseVar();
  if (isKw("state"))
    return parseState(region);
  if (isKw("initial")) {
    p.consume();
    auto &ini = initials[region];
    if (ini.second.isValid())
      return p.errorHere("a second 'initial' in the same region");
    StringRef n;
    SMLoc l;
    if (!p.name(n, l, "a state name"))
      return false;
    ini = {n, l};
    return p.expect(Tok::Semi, "';'");
  }
  if (isKw("nested") || isKw("junction") || isKw("history"))
    return p.errorHere("'" + tok().text +
                       "' is not supported in .hyb charts "
                       "(flatten the hierarchy into states and regions)");
  if (tok().is(Tok::Ident))
    return parseTransition(region);
  return p.errorHere("expected a chart item, found '" + tok().text + "'");
}

bool ChartReader::parsePorts(PortDir dir) {
  PortKind kind;
  if (isKw("event"))
    kind = PortKind::Event;
  else if (isKw("cond"))
    kind = PortKind::Cond;
  else if (isKw("data"))
    kind = PortKind::Data;
  else
    return p.errorHere("expected 'event', 'cond' or 'data'");
  p.consume();
  for (;;) {
    StringRef n;
    SMLoc l;
    if (!p.name(n, l, "a port name"))
      return false;
    const Type *type = kind == PortKind::Cond ? d.types.getBool() : nullptr;
    if (kind == PortKind::Data) {
      if (!p.expect(Tok::Colon, "':' and a type") || !p.type(type))
        return false;
    }
    uint32_t pi = b.addPort(n, kind, dir, type, l);
    if (tok().is(Tok::Equal)) {
      if (dir == PortDir::In || kind == PortKind::Event)
        return p.errorHere("only cond and data outputs can be defined");
      SMLoc dl = tok().loc();
      p.consume();
      Expr *e = p.expr();
      if (!e)
        return false;
      mod->ports[pi].definition = e; // parameters replaced in build()
      mod->ports[pi].definitionLoc = dl;
    }
    if (tok().is(Tok::Comma)) {
      p.consume();
      continue;
    }
    return p.expect(Tok::Semi, "';'");
  }
}

bool ChartReader::parseParam() {
  p.consume();
  for (;;) {
    StringRef n;
    SMLoc l;
    if (!p.name(n, l, "a parameter name") || !p.expect(Tok::Equal, "'='"))
      return false;
    Expr *e = p.expr();
    if (!e)
      return false;
    e = substitute(e);
    if (!evalConstReal(e))
      return p.error(e->loc,
                     "the value of parameter '" + n + "' is not a constant");
    if (!params.insert({n, e}).second)
      return p.error(l, "parameter '" + n + "' is defined twice");
    if (tok().is(Tok::Comma)) {
      p.consume();
      continue;
    }
    return p.expect(Tok::Semi, "';'");
  }
}

bool ChartReader::parseReal() {
  p.consume();
  StringRef n;
  SMLoc l;
  if (!p.name(n, l, "a variable name") || !p.expect(Tok::Colon, "':'") ||
      !p.expect(Tok::LBrack, "'['"))
    return false;
  Expr *lo = p.expr();
  if (!lo || !p.expect(Tok::Comma, "','"))
    return false;
  Expr *hi = p.expr();
  if (!hi || !p.expect(Tok::RBrack, "']'"))
    return false;
  Expr *init = nullptr;
  if (tok().is(Tok::Equal)) {
    p.consume();
    init = p.expr();
    if (!init)
      return false;
  }
  pendingReals.push_back({n, l, lo, hi, init});
  return p.expect(Tok::Semi, "';'");
}

bool ChartReader::declareReal(const PendingReal &r) {
  auto lv = evalConstReal(substitute(r.lo)),
       hv = evalConstReal(substitute(r.hi));
  if (!lv)
    return p.error(r.lo->loc, "a range bound must be a constant");
  if (!hv)
    return p.error(r.hi->loc, "a range bound must be a constant");
  if (*lv > *hv)
    return p.error(r.loc, "empty range for real '" + r.name + "'");
  Expr *init = nullptr;
  if (r.init) {
    auto iv = evalConstReal(substitute(r.init));
    if (!iv)
      return p.error(r.init->loc, "the initial value must be a constant");
    init = b.realLit(*iv, r.init->loc);
  }
  b.addVar(r.name, d.types.getReal(*lv, *hv), init, r.loc);
  return true;
}

bool ChartReader::parseVar() {
  p.consume();
  StringRef n;
  SMLoc l;
  const Type *t;
  if (!p.name(n, l, "a variable name") || !p.expect(Tok::Colon, "':'") ||
      !p.type(t))
    return false;
  Expr *init = nullptr;
  if (tok().is(Tok::Equal)) {
    p.consume();
    init = p.expr();
    if (!init)
      return false;
    init = substitute(init);
  }
  b.addVar(n, t, init, l);
  return p.expect(Tok::Semi, "';'");
}

bool ChartReader::parseState(unsigned region) {
  p.consume();
  HybState s;
  s.region = region;
  if (!p.name(s.name, s.loc, "a state name"))
    return false;
  if (stateIndex.count(s.name))
    return p.error(s.loc, "state '" + s.name + "' is declared twice");
  if (tok().is(Tok::Semi)) {
    p.consume();
  } else {
    if (!p.expect(Tok::LBrace, "'{' or ';'"))
      return false;
    while (!tok().is(Tok::RBrace)) {
      if (isKw("entry") || isKw("during") || isKw("exit")) {
        StringRef which = tok().text;
        SMLoc wl = tok().loc();
        p.consume();
        Block blk;
        if (!p.block(blk))
          return false;
        substituteIn(blk);
        if (which == "entry") {
          s.entry = blk;
          s.entryLoc = wl;
        } else if (which == "during") {
          s.during = blk;
        } else {
          s.exit = blk;
        }
        continue;
      }
      if (isKw("invariant")) {
        // `invariant x <= D;`: the state must be left before it fails.
        if (s.invariant.empty())
          s.invariantLoc = tok().loc();
        p.consume();
        Expr *c = p.expr();
        if (!c || !p.expect(Tok::Semi, "';'"))
          return false;
        s.invariant.push_back(substitute(c));
        continue;
      }
      if (tok().is(Tok::Ident)) {
        // A flow equation `x' = rate;`, or a rectangular flow
        // `x' in [lo, hi];`.
        Flow::Equation eq;
        if (!p.name(eq.var, eq.loc, "a real variable"))
          return false;
        if (!p.expect(Tok::Prime, "\"'\" (a flow x' = rate)"))
          return false;
        if (isKw("in")) {
          p.consume();
          if (!p.expect(Tok::LBrack, "'['") || !(eq.rate = p.expr()) ||
              !p.expect(Tok::Comma, "','") || !(eq.rateHi = p.expr()) ||
              !p.expect(Tok::RBrack, "']'"))
            return false;
          eq.rateHi = substitute(eq.rateHi);
        } else if (!p.expect(Tok::Equal, "'=' or 'in'") ||
                   !(eq.rate = p.expr())) {
          return false;
        }
        eq.rate = substitute(eq.rate);
        if (s.flows.empty())
          s.flowLoc = eq.loc;
        s.flows.push_back(eq);
        if (!p.expect(Tok::Semi, "';'"))
          return false;
        continue;
      }
      return p.errorHere("expected 'entry', 'during', 'exit', 'invariant' or "
                         "a flow x' = rate in a state, found '" +
                         tok().text + "'");
    }
    p.consume();
  }
  stateIndex[s.name] = states.size();
  states.push_back(s);
  return true;
}

bool ChartReader::parseTransition(unsigned region) {
  (void)region;
  HybTransition t;
  t.loc = tok().loc();
  if (!p.name(t.from, t.fromLoc, "a state name") ||
      !p.expect(Tok::Arrow, "'->'") || !p.name(t.to, t.toLoc, "a state name"))
    return false;
  if (tok().is(Tok::Colon)) {
    p.consume();
    if (tok().is(Tok::Ident) && !isKw("emit")) {
      t.event = tok().text;
      t.eventLoc = tok().loc();
      p.consume();
    }
    if (tok().is(Tok::LBrack)) {
      p.consume();
      t.guard = p.expr();
      if (!t.guard || !p.expect(Tok::RBrack, "']'"))
        return false;
      t.guard = substitute(t.guard);
    }
    if (tok().is(Tok::LBrace)) {
      if (!p.block(t.action))
        return false;
      substituteIn(t.action);
      t.hasAction = true;
    }
    if (isKw("emit")) {
      p.consume();
      for (;;) {
        StringRef n;
        SMLoc l;
        if (!p.name(n, l, "an event output"))
          return false;
        t.emits.push_back({n, l});
        if (!tok().is(Tok::Comma))
          break;
        p.consume();
      }
    }
  }
  if (!p.expect(Tok::Semi, "';'"))
    return false;
  transitions.push_back(t);
  return true;
}

Expr *ChartReader::substitute(Expr *e) {
  if (!e)
    return e;
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto it = params.find(llvm::cast<Ref>(e)->name);
    if (it == params.end())
      return e;
    Expr *v = it->second;
    if (auto *i = llvm::dyn_cast<IntLit>(v))
      return b.intLit(i->value, e->loc);
    auto c = evalConstReal(v);
    return b.realLit(*c, e->loc);
  }
  case ExprKind::Unary: {
    auto *u = llvm::cast<UnaryExpr>(e);
    u->operand = substitute(u->operand);
    return e;
  }
  case ExprKind::Binary: {
    auto *bin = llvm::cast<BinaryExpr>(e);
    bin->lhs = substitute(bin->lhs);
    bin->rhs = substitute(bin->rhs);
    return e;
  }
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    c->cond = substitute(c->cond);
    c->thenExpr = substitute(c->thenExpr);
    c->elseExpr = substitute(c->elseExpr);
    return e;
  }
  case ExprKind::Call: {
    auto *c = llvm::cast<CallExpr>(e);
    std::vector<Expr *> args(c->args.begin(), c->args.end());
    for (Expr *&a : args)
      a = substitute(a);
    c->args = d.copy(llvm::ArrayRef<Expr *>(args));
    return e;
  }
  case ExprKind::Index: {
    auto *x = llvm::cast<IndexExpr>(e);
    x->base = substitute(x->base);
    x->index = substitute(x->index);
    return e;
  }
  default:
    return e;
  }
}

void ChartReader::substituteIn(Block blk) {
  for (Stmt *s : blk) {
    if (auto *a = llvm::dyn_cast<AssignStmt>(s)) {
      a->value = substitute(a->value);
    } else if (auto *i = llvm::dyn_cast<IfStmt>(s)) {
      std::vector<IfArm> arms(i->arms.begin(), i->arms.end());
      for (IfArm &arm : arms) {
        arm.cond = substitute(arm.cond);
        substituteIn(arm.body);
      }
      i->arms = d.copy(llvm::ArrayRef<IfArm>(arms));
      substituteIn(i->elseBody);
    } else if (auto *c = llvm::dyn_cast<CaseStmt>(s)) {
      c->selector = substitute(c->selector);
      for (const CaseArm &arm : c->arms)
        substituteIn(arm.body);
      substituteIn(c->elseBody);
    } else if (auto *f = llvm::dyn_cast<ForStmt>(s)) {
      f->lo = substitute(f->lo);
      f->hi = substitute(f->hi);
      substituteIn(f->body);
    } else if (auto *w = llvm::dyn_cast<WhileStmt>(s)) {
      w->cond = substitute(w->cond);
      substituteIn(w->body);
    }
  }
}

bool ChartReader::build() {
  if (states.empty())
    return p.error(chartLoc, "chart '" + chartName + "' has no state");
  // Parameters may be declared after their use: replaced here.
  for (const PendingReal &r : pendingReals)
    if (!declareReal(r))
      return false;
  for (Port &port : mod->ports)
    if (port.definition)
      port.definition = substitute(port.definition);
  for (Var &v : mod->vars)
    if (v.init)
      v.init = substitute(v.init);
  for (HybState &st : states) {
    substituteIn(st.entry);
    substituteIn(st.during);
    substituteIn(st.exit);
    for (Flow::Equation &eq : st.flows) {
      eq.rate = substitute(eq.rate);
      if (eq.rateHi)
        eq.rateHi = substitute(eq.rateHi);
    }
  }
  for (HybTransition &t : transitions) {
    t.guard = substitute(t.guard);
    substituteIn(t.action);
  }
  // Initial states: the declared one, else the first state of the region.
  std::vector<int> initialOf(regionNames.size(), -1);
  for (unsigned r = 0; r < regionNames.size(); ++r) {
    auto &[n, l] = initials[r];
    if (l.isValid()) {
      auto it = stateIndex.find(n);
      if (it == stateIndex.end())
        return p.error(l, "no state '" + n + "' in this chart");
      if (states[it->second].region != r)
        return p.error(l, "state '" + n + "' is not in this region");
      initialOf[r] = it->second;
      continue;
    }
    for (unsigned s = 0; s < states.size(); ++s)
      if (states[s].region == r) {
        initialOf[r] = s;
        break;
      }
    if (initialOf[r] < 0 && r > 0)
      return p.error(chartLoc, "region '" + regionNames[r] + "' has no state");
  }
  for (unsigned r = 0; r < regionNames.size(); ++r)
    if (initialOf[r] >= 0 && !states[initialOf[r]].entry.empty())
      return p.error(states[initialOf[r]].entryLoc,
                     "the entry action of initial state '" +
                         states[initialOf[r]].name +
                         "' would run before time 0; give the initial "
                         "values in the declarations instead");
  for (unsigned s = 0; s < states.size(); ++s) {
    bool initial = false;
    for (int i : initialOf)
      initial |= i == int(s);
    b.addPlace(states[s].name, initial ? 1 : 0, 1, states[s].loc);
  }
  for (HybTransition &t : transitions) {
    auto fi = stateIndex.find(t.from), ti = stateIndex.find(t.to);
    if (fi == stateIndex.end())
      return p.error(t.fromLoc, "no state '" + t.from + "' in this chart");
    if (ti == stateIndex.end())
      return p.error(t.toLoc, "no state '" + t.to + "' in this chart");
    HybState &from = states[fi->second], &to = states[ti->second];
    if (from.region != to.region)
      return p.error(t.loc, "a transition from '" + t.from + "' to '" + t.to +
                                "' crosses parallel regions");
    std::string name = (t.from + "_to_" + t.to).str();
    for (unsigned k = 2; mod->lookup(name).kind != SymKind::None; ++k)
      name = (t.from + "_to_" + t.to + "_" + llvm::Twine(k)).str();
    uint32_t tr = b.addTransition(d.save(name), {PreArc{fi->second, 1, {}}},
                                  {PostArc{ti->second}}, t.loc);
    if (!t.event.empty()) {
      int port = mod->findPort(t.event);
      if (port < 0 || mod->ports[port].kind != PortKind::Event ||
          !mod->ports[port].isInput())
        return p.error(t.eventLoc,
                       "'" + t.event + "' is not an event input of the chart");
      b.setEvents(tr, {EventSource{uint32_t(port), true}});
    } else {
      b.setUrgent(tr);
    }
    if (t.guard)
      b.setGuard(tr, t.guard);
    std::vector<uint32_t> emits;
    for (auto &[n, l] : t.emits) {
      int port = mod->findPort(n);
      if (port < 0 || mod->ports[port].kind != PortKind::Event ||
          mod->ports[port].isInput())
        return p.error(l, "'" + n + "' is not an event output of the chart");
      emits.push_back(port);
    }
    if (!emits.empty())
      b.setEmits(tr, emits);
    // exit(source); action; entry(target) — a self-transition leaves and
    // re-enters its state.
    std::vector<Stmt *> body(from.exit.begin(), from.exit.end());
    body.insert(body.end(), t.action.begin(), t.action.end());
    body.insert(body.end(), to.entry.begin(), to.entry.end());
    if (!body.empty() || t.hasAction)
      b.setAction(tr, body);
  }
  for (unsigned s = 0; s < states.size(); ++s) {
    HybState &st = states[s];
    if (!st.flows.empty())
      b.addFlow(s, st.flows, st.flowLoc);
    if (!st.invariant.empty())
      b.addInvariant(s, st.invariant, st.invariantLoc);
    if (!st.during.empty()) {
      uint32_t tr =
          b.addTransition(d.save((st.name + "_during").str()),
                          {PreArc{s, 1, Interval{1, 1}}}, {PostArc{s}}, st.loc);
      b.setUrgent(tr);
      b.setAction(tr, st.during);
    }
  }
  return true;
}

bool netlift::loadHybridChart(FrontendContext &ctx, unsigned bufferID,
                              DiagEngine &diag, Design &design) {
  const llvm::MemoryBuffer *buf = diag.sourceMgr().getMemoryBuffer(bufferID);
  // A chart's reals carry their ranges (`real x : [lo, hi]`); a range given
  // beside it would be ignored, so it is refused.
  if (!ctx.options.rangesFile.empty() || !ctx.options.rangeOptions.empty()) {
    diag.error(llvm::SMLoc::getFromPointer(buf->getBufferStart()),
               "a .hyb chart declares the range of each real (`real x : "
               "[lo, hi]`); --range and --ranges are for SpaceEx models "
               "and PLC inputs");
    return false;
  }
  EmbeddedParser p(buf->getBuffer(), diag, design);
  ChartReader r(p, design, diag);
  return r.parseFile() && !p.failed();
}
