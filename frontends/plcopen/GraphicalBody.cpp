//===- GraphicalBody.cpp - LD and FBD networks into statements ------------===//
//
// A Ladder Diagram or Function Block Diagram body is a graph of elements
// joined by wires (connectionPointIn/connection refLocalId). Elements with
// an effect — coils, output variables, blocks, jumps, returns, labels, and
// edge-sensing contacts (they keep an R_TRIG/F_TRIG) — become statements;
// the rest (rails, contacts, input variables, connectors) become the
// expressions those statements read: series is AND, a point joining several
// wires is OR. Statements run in executionOrderId order when every one of
// them has one, otherwise in data-flow order with ties broken top to bottom
// then left to right (docs/plcopen.md gives the rules and their sources).
//
//===----------------------------------------------------------------------===//
#include "frontends/plcopen/PlcOpen.h"

#include "frontends/st/StFrontend.h"
#include "frontends/st/StdLib.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringMap.h"

#include <map>
#include <queue>
#include <set>

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plcopen;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

struct Wire {
  int ref;
  std::string formal; // the block output it leaves from, or empty
};

struct Element {
  pugi::xml_node node;
  std::string kind;
  int id = 0;
  int order = 0; // executionOrderId, 0 when absent
  long x = 0, y = 0;
  bool statement = false;
};

/// Expressions are trees: a value read by several statements is built once
/// per reader. Past this many nodes a network is refused rather than
/// expanded further.
constexpr size_t kMaxExprNodes = 2'000'000;

class Network : public AstMaker {
public:
  Network(XmlSource &src, DiagEngine &diag, Unit &unit, Pou *pou,
          const std::map<int, std::string> *sfcConditions)
      : AstMaker(unit), src(src), diag(diag), pou(pou),
        sfcConditions(sfcConditions) {}

  bool read(pugi::xml_node body);

private:
  struct Failure {};
  [[noreturn]] void fail(pugi::xml_node at, const llvm::Twine &msg) {
    diag.error(src.locOf(at), msg);
    throw Failure();
  }
  std::string describe(const Element &e) const {
    return "<" + e.kind + "> localId " + std::to_string(e.id);
  }

  bool collect(pugi::xml_node body);
  std::vector<Wire> wiresOf(pugi::xml_node connectionPointIn) const;
  std::vector<Wire> inputWires(const Element &e) const;
  const Element &target(const Element &from, const Wire &w);
  void producers(const Element &e, std::set<int> &hard, std::set<int> &soft,
                 std::set<int> &visiting);
  std::vector<const Element *> order();

  // Expressions.
  Expr *make(ExprKind k, SMLoc at) override {
    if (++made > kMaxExprNodes) {
      diag.error(at, "network too large once expanded into expressions "
                     "(more than 2000000 nodes)");
      throw Failure();
    }
    return unit.make<Expr>(k, at);
  }
  Expr *textExpr(pugi::xml_node holder, const Element &e, const char *what);
  Expr *power(const Element &e);
  Expr *joined(const Element &e, const std::vector<Wire> &wires,
               pugi::xml_node at);
  Expr *value(const Element &from, const Wire &w);
  Expr *blockOutput(const Element &b, StringRef formal, SMLoc at);
  pugi::xml_node enInput(const Element &b) const;
  bool hasEn(const Element &b);

  // Statements.
  VarDecl *declare(const std::string &name, StringRef type, VarSection s,
                   pugi::xml_node at);
  void emit(Stmt *s);
  std::string trigger(const Element &e, StringRef suffix, bool rising,
                      Expr *clk);
  void coil(const Element &e);
  void contactTrigger(const Element &e);
  void block(const Element &e);
  DrawnBlock *drawing(const Element &b);
  void jump(const Element &e);
  void label(const Element &e);

  XmlSource &src;
  DiagEngine &diag;
  Pou *pou;
  std::map<int, Element> elements;
  /// In an SFC body: the transitions whose condition is wired from the
  /// networks drawn there, and the variable each condition goes to.
  const std::map<int, std::string> *sfcConditions;
  std::vector<int> document;             // localIds in document order
  std::map<std::string, int> connectors; // upper-case name -> localId
  size_t made = 0;
  // Forward jumps not yet at their label: (label, flag variable).
  std::vector<std::pair<std::string, std::string>> pending;
  std::set<std::string> labelsSeen;
};

} // namespace

static const char *const statementKinds[] = {"coil", "outVariable", "block",
                                             "jump", "return",      "label"};
static const char *const sfcKinds[] = {"step",
                                       "transition",
                                       "selectionDivergence",
                                       "selectionConvergence",
                                       "jumpStep",
                                       "actionBlock",
                                       "simultaneousDivergence",
                                       "simultaneousConvergence",
                                       "macroStep"};
static const char *const expressionKinds[] = {
    "leftPowerRail", "rightPowerRail", "contact",     "inVariable",
    "inOutVariable", "connector",      "continuation"};

bool Network::collect(pugi::xml_node body) {
  for (pugi::xml_node n : body.children()) {
    if (n.type() != pugi::node_element)
      continue;
    StringRef kind = localName(n);
    if (kind == "comment" || kind == "documentation" || kind == "addData")
      continue;
    if (sfcConditions && llvm::is_contained(sfcKinds, kind)) {
      // The chart is SfcBody.cpp's; a wired condition is an output here.
      int id = n.attribute("localId").as_int(-1);
      if (kind == "transition" && sfcConditions->count(id)) {
        Element e;
        e.node = child(n, "condition");
        e.kind = "sfcCondition";
        e.id = id;
        e.order = n.attribute("executionOrderId").as_int(0);
        pugi::xml_node pos = child(n, "position");
        e.x = pos.attribute("x").as_int(0);
        e.y = pos.attribute("y").as_int(0);
        e.statement = true;
        document.push_back(e.id);
        elements.emplace(e.id, e);
      }
      continue;
    }
    bool known = llvm::is_contained(statementKinds, kind) ||
                 llvm::is_contained(expressionKinds, kind);
    if (!known)
      fail(n, "<" + kind.str() + "> (localId " +
                  n.attribute("localId").value() + ") in a " +
                  localName(body).str() + " body is not supported");
    Element e;
    e.node = n;
    e.kind = kind.str();
    if (!n.attribute("localId") ||
        StringRef(n.attribute("localId").value()).getAsInteger(10, e.id))
      fail(n, "<" + kind.str() + "> without a numeric localId");
    e.order = n.attribute("executionOrderId").as_int(0);
    pugi::xml_node pos = child(n, "position");
    e.x = pos.attribute("x").as_int(0);
    e.y = pos.attribute("y").as_int(0);
    e.statement = llvm::is_contained(statementKinds, kind) ||
                  (kind == "contact" &&
                   (StringRef(n.attribute("edge").value()) == "rising" ||
                    StringRef(n.attribute("edge").value()) == "falling")) ||
                  (kind == "inOutVariable" &&
                   !wiresOf(child(n, "connectionPointIn")).empty());
    if (elements.count(e.id))
      fail(n, "localId " + std::to_string(e.id) + " is used twice");
    if (kind == "connector") {
      std::string name = StringRef(n.attribute("name").value()).upper();
      if (!connectors.emplace(name, e.id).second)
        fail(n, "connector '" + std::string(n.attribute("name").value()) +
                    "' is defined twice");
    }
    document.push_back(e.id);
    elements.emplace(e.id, e);
  }
  return true;
}

std::vector<Wire> Network::wiresOf(pugi::xml_node cpi) const {
  std::vector<Wire> wires;
  for (pugi::xml_node c : cpi.children())
    if (localName(c) == "connection")
      wires.push_back({c.attribute("refLocalId").as_int(-1),
                       c.attribute("formalParameter").value()});
  return wires;
}

/// Every wire entering an element (a block: all its inputs).
std::vector<Wire> Network::inputWires(const Element &e) const {
  std::vector<Wire> all;
  if (e.kind == "block") {
    for (const char *group : {"inputVariables", "inOutVariables"})
      for (pugi::xml_node v : child(e.node, group).children())
        for (const Wire &w : wiresOf(child(v, "connectionPointIn")))
          all.push_back(w);
    return all;
  }
  for (pugi::xml_node c : e.node.children())
    if (localName(c) == "connectionPointIn")
      for (const Wire &w : wiresOf(c))
        all.push_back(w);
  return all;
}

const Element &Network::target(const Element &from, const Wire &w) {
  auto it = elements.find(w.ref);
  if (it == elements.end())
    fail(from.node, describe(from) + " is wired to localId " +
                        std::to_string(w.ref) + ", which does not exist");
  const Element &t = it->second;
  if (t.kind == "continuation")
    return t;
  if (t.kind == "rightPowerRail" || t.kind == "outVariable" ||
      t.kind == "jump" || t.kind == "return" || t.kind == "label" ||
      t.kind == "connector")
    fail(from.node, describe(from) + " is wired to the output of " +
                        describe(t) + ", which has none");
  return t;
}

/// The statements whose results element `e` reads through its wires; those
/// read from an in-out variable or a function block instance are `soft`:
/// the variable (or the instance's stored output) may break a loop, the
/// reader then sees the value of the previous evaluation.
void Network::producers(const Element &e, std::set<int> &hard,
                        std::set<int> &soft, std::set<int> &visiting) {
  if (!visiting.insert(e.id).second)
    fail(e.node, "feedback loop through " + describe(e) +
                     " with no variable to break it");
  for (const Wire &w : inputWires(e)) {
    const Element *t = &target(e, w);
    if (t->kind == "continuation") {
      auto c =
          connectors.find(StringRef(t->node.attribute("name").value()).upper());
      if (c == connectors.end())
        fail(t->node, "continuation '" +
                          std::string(t->node.attribute("name").value()) +
                          "' has no connector of that name");
      t = &elements.at(c->second);
    }
    if (t->statement)
      (t->kind == "inOutVariable" ||
               (t->kind == "block" &&
                !StringRef(t->node.attribute("instanceName").value()).empty())
           ? soft
           : hard)
          .insert(t->id);
    else
      producers(*t, hard, soft, visiting);
  }
  visiting.erase(e.id);
}

std::vector<const Element *> Network::order() {
  std::vector<const Element *> stmts;
  for (int id : document)
    if (elements.at(id).statement)
      stmts.push_back(&elements.at(id));
  bool explicitOrder =
      !stmts.empty() &&
      llvm::all_of(stmts, [](const Element *e) { return e->order > 0; });
  // Dependencies are computed in both cases: they report wires that lead to
  // unknown elements and loops of pure expressions.
  std::map<int, std::set<int>> hard, soft;
  for (const Element *s : stmts) {
    std::set<int> visiting;
    producers(*s, hard[s->id], soft[s->id], visiting);
    hard[s->id].erase(s->id);
    soft[s->id].erase(s->id);
    for (int h : hard[s->id])
      soft[s->id].erase(h);
  }
  if (explicitOrder) {
    std::stable_sort(
        stmts.begin(), stmts.end(),
        [](const Element *a, const Element *b) { return a->order < b->order; });
    return stmts;
  }
  // Data-flow order, ties broken top to bottom then left to right. When
  // only loops remain, the first statement (in that order) whose other
  // inputs are ready runs, reading the previous values of the in-out
  // variables and instance outputs on the loop.
  auto key = [](const Element *e) {
    return std::make_tuple(e->y, e->x, e->id);
  };
  auto before = [&](const Element *a, const Element *b) {
    return key(a) < key(b);
  };
  std::map<int, size_t> waitHard, waitSoft;
  std::map<int, std::vector<std::pair<const Element *, bool>>> readers;
  std::set<const Element *, decltype(before)> ready(before), left(before);
  for (const Element *s : stmts) {
    waitHard[s->id] = hard[s->id].size();
    waitSoft[s->id] = soft[s->id].size();
    for (int d : hard[s->id])
      readers[d].push_back({s, true});
    for (int d : soft[s->id])
      readers[d].push_back({s, false});
    left.insert(s);
  }
  for (const Element *s : stmts)
    if (!waitHard[s->id] && !waitSoft[s->id])
      ready.insert(s);
  std::vector<const Element *> sorted;
  while (!left.empty()) {
    if (ready.empty()) {
      // Break a loop at its first statement (not at one that merely waits
      // for a loop's result).
      auto onLoop = [&](const Element *s) {
        std::set<int> seen;
        std::vector<int> todo(soft[s->id].begin(), soft[s->id].end());
        while (!todo.empty()) {
          int d = todo.back();
          todo.pop_back();
          if (d == s->id)
            return true;
          if (!left.count(&elements.at(d)) || !seen.insert(d).second)
            continue;
          todo.insert(todo.end(), hard[d].begin(), hard[d].end());
          todo.insert(todo.end(), soft[d].begin(), soft[d].end());
        }
        return false;
      };
      for (const Element *s : left)
        if (!waitHard[s->id] && onLoop(s)) {
          ready.insert(s);
          break;
        }
      if (ready.empty())
        fail((*left.begin())->node,
             "feedback loop through " + describe(**left.begin()) +
                 " with no variable or function block instance to break it "
                 "(put an in-out variable on the loop, or give every "
                 "element an executionOrderId)");
    }
    const Element *s = *ready.begin();
    ready.erase(ready.begin());
    left.erase(s);
    sorted.push_back(s);
    for (auto [r, isHard] : readers[s->id]) {
      if (!left.count(r))
        continue;
      size_t &w = isHard ? waitHard[r->id] : waitSoft[r->id];
      if (w && --w == 0 && !waitHard[r->id] && !waitSoft[r->id])
        ready.insert(r);
    }
  }
  return sorted;
}

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

/// A variable or expression written as the text of `holder`.
Expr *Network::textExpr(pugi::xml_node holder, const Element &e,
                        const char *what) {
  StringRef text = holder ? src.placeText(holder) : StringRef();
  if (text.trim().empty())
    fail(e.node, describe(e) + " names no " + what);
  Expr *x = st::parseStExpression(text, diag, unit);
  if (!x)
    throw Failure();
  return x;
}

Expr *Network::joined(const Element &e, const std::vector<Wire> &wires,
                      pugi::xml_node at) {
  if (wires.empty())
    fail(at ? at : e.node, describe(e) + " has an unconnected input");
  Expr *v = value(e, wires[0]);
  for (size_t i = 1; i < wires.size(); ++i)
    v = binary(Op::Or, v, value(e, wires[i]), src.locOf(e.node));
  return v;
}

/// The power flow or value entering a single-input element.
Expr *Network::power(const Element &e) {
  pugi::xml_node cpi = child(e.node, "connectionPointIn");
  return joined(e, wiresOf(cpi), cpi);
}

Expr *Network::value(const Element &from, const Wire &w) {
  const Element &t = target(from, w);
  SMLoc at = src.locOf(t.node);
  const std::string &k = t.kind;
  if (k == "leftPowerRail")
    return boolLit(true, at);
  if (k == "continuation") {
    auto c =
        connectors.find(StringRef(t.node.attribute("name").value()).upper());
    if (c == connectors.end())
      fail(t.node, "continuation '" +
                       std::string(t.node.attribute("name").value()) +
                       "' has no connector of that name");
    return power(elements.at(c->second));
  }
  if (k == "contact") {
    Expr *in = power(t);
    StringRef edge = t.node.attribute("edge").value();
    Expr *sensed;
    if (edge == "rising" || edge == "falling")
      sensed = field(nameRef("_TRIG" + std::to_string(t.id), at), "Q", at);
    else
      sensed = textExpr(child(t.node, "variable"), t, "variable");
    if (isTrue(t.node.attribute("negated")))
      sensed = unary(Op::Not, sensed, at);
    if (in->kind == ExprKind::BoolLit && in->intValue)
      return sensed; // straight from the left rail
    return binary(Op::And, in, sensed, at);
  }
  if (k == "coil")
    return power(t); // a coil passes its left link on
  if (k == "inVariable" || k == "inOutVariable") {
    Expr *v = textExpr(child(t.node, "expression"), t, "expression");
    return isTrue(t.node.attribute("negated")) ? unary(Op::Not, v, at) : v;
  }
  if (k == "block")
    return blockOutput(t, w.formal, at);
  fail(from.node,
       describe(from) + " reads " + describe(t) + ", which gives no value");
}

static std::string upper(StringRef s) { return s.upper(); }

/// The output `formal` of a block; empty names its only output.
Expr *Network::blockOutput(const Element &b, StringRef formal, SMLoc at) {
  pugi::xml_node outs = child(b.node, "outputVariables");
  pugi::xml_node out;
  std::vector<pugi::xml_node> all;
  for (pugi::xml_node v : outs.children())
    if (localName(v) == "variable") {
      all.push_back(v);
      if (upper(v.attribute("formalParameter").value()) == upper(formal))
        out = v;
    }
  if (!out && formal.empty()) {
    std::vector<pugi::xml_node> real;
    for (pugi::xml_node v : all)
      if (upper(v.attribute("formalParameter").value()) != "ENO")
        real.push_back(v);
    if (real.size() == 1)
      out = real[0];
  }
  if (!out)
    fail(b.node, describe(b) + " (" + b.node.attribute("typeName").value() +
                     ") has no output '" + formal.str() + "'");
  std::string name = upper(out.attribute("formalParameter").value());
  std::string id = std::to_string(b.id);
  Expr *v;
  StringRef instance = b.node.attribute("instanceName").value();
  if (name == "ENO")
    v = hasEn(b) ? nameRef("_EN" + id, at) : boolLit(true, at);
  else if (!instance.empty())
    v = field(nameRef(instance, at), out.attribute("formalParameter").value(),
              at);
  else
    v = nameRef("_TMP_" + upper(b.node.attribute("typeName").value()) + id +
                    "_" + name,
                at);
  return isTrue(out.attribute("negated")) ? unary(Op::Not, v, at) : v;
}

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

pugi::xml_node Network::enInput(const Element &b) const {
  for (pugi::xml_node v : child(b.node, "inputVariables").children())
    if (localName(v) == "variable" &&
        upper(v.attribute("formalParameter").value()) == "EN")
      return v;
  return {};
}

/// EN decides whether a block runs; absent, unconnected or wired straight
/// to the left rail it is TRUE and the block runs unconditionally.
bool Network::hasEn(const Element &b) {
  pugi::xml_node en = enInput(b);
  if (!en)
    return false;
  std::vector<Wire> wires = wiresOf(child(en, "connectionPointIn"));
  if (wires.empty())
    return false;
  auto it = elements.find(wires[0].ref);
  return !(wires.size() == 1 && it != elements.end() &&
           it->second.kind == "leftPowerRail");
}

VarDecl *Network::declare(const std::string &name, StringRef type,
                          VarSection section, pugi::xml_node at) {
  if (VarDecl *old = pou->find(name)) {
    if (old->loc == src.locOf(at))
      return old; // the same element asked twice
    fail(at, "netlift names a variable '" + name +
                 "' for this element, but POU '" + pou->name +
                 "' already declares one");
  }
  VarDecl *v = AstMaker::declare(*pou, name, type, src.locOf(at), section);
  v->generated = true;
  return v;
}

/// Statements between a taken forward jump and its label do not run.
void Network::emit(Stmt *s) {
  if (!pending.empty()) {
    Expr *skip = nullptr;
    for (auto &[label, flag] : pending) {
      Expr *f = nameRef(flag, s->loc);
      skip = skip ? binary(Op::Or, skip, f, s->loc) : f;
    }
    s = when(unary(Op::Not, skip, s->loc), {s}, s->loc);
  }
  pou->body.push_back(s);
}

/// Calls the edge detector kept for element `e` on `clk` and names it.
std::string Network::trigger(const Element &e, StringRef suffix, bool rising,
                             Expr *clk) {
  SMLoc at = src.locOf(e.node);
  std::string name = "_TRIG" + std::to_string(e.id) + suffix.str();
  declare(name, rising ? "R_TRIG" : "F_TRIG", VarSection::Var, e.node);
  Expr *call = make(ExprKind::Call, at);
  call->name = name;
  CallArg arg;
  arg.name = "CLK";
  arg.value = clk;
  arg.loc = at;
  call->args.push_back(arg);
  Stmt *s = unit.make<Stmt>(StmtKind::Call, at);
  s->value = call;
  emit(s);
  return name;
}

static bool isEdge(StringRef edge, bool &rising) {
  rising = edge == "rising";
  return edge == "rising" || edge == "falling";
}

void Network::coil(const Element &e) {
  SMLoc at = src.locOf(e.node);
  Expr *in = power(e);
  Expr *target = textExpr(child(e.node, "variable"), e, "variable");
  StringRef storage = e.node.attribute("storage").value();
  bool negated = isTrue(e.node.attribute("negated"));
  bool stores = storage == "set" || storage == "reset";
  bool rising;
  if (isEdge(e.node.attribute("edge").value(), rising)) {
    // A negated edge coil has no agreed meaning (pulse on every scan but
    // one?), so it is refused rather than guessed.
    if (negated)
      fail(e.node, describe(e) + ": an edge coil that is also negated is "
                                 "not supported");
    std::string t = trigger(e, "", rising, in);
    in = field(nameRef(t, at), "Q", at);
  }
  if (stores) {
    if (negated)
      in = unary(Op::Not, in, at);
    emit(when(in, {assign(target, boolLit(storage == "set", at), at)}, at));
    return;
  }
  emit(assign(target, negated ? unary(Op::Not, in, at) : in, at));
}

void Network::block(const Element &e) {
  SMLoc at = src.locOf(e.node);
  std::string type = e.node.attribute("typeName").value();
  std::string instance = e.node.attribute("instanceName").value();
  std::string id = std::to_string(e.id);
  if (type.empty())
    fail(e.node, describe(e) + " has no typeName");
  if (instance.empty()) {
    Pou *fb = unit.findPou(type);
    if (st::isStandardFunctionBlock(type) ||
        (fb && fb->kind != PouKind::Function))
      fail(e.node, noInstanceMessage(type));
  }
  Expr *call = make(ExprKind::Call, at);
  call->name = instance.empty() ? type : instance;
  call->drawn = drawing(e);
  for (const char *group : {"inputVariables", "inOutVariables"})
    for (pugi::xml_node v : child(e.node, group).children()) {
      if (localName(v) != "variable")
        continue;
      std::string formal = v.attribute("formalParameter").value();
      if (upper(formal) == "EN")
        continue;
      pugi::xml_node cpi = child(v, "connectionPointIn");
      std::vector<Wire> wires = wiresOf(cpi);
      if (wires.empty()) {
        if (StringRef(group) == "inOutVariables")
          fail(v, describe(e) + ": in-out parameter '" + formal +
                      "' is not connected");
        continue; // the parameter keeps its default
      }
      Expr *val = joined(e, wires, v);
      if (isTrue(v.attribute("negated")))
        val = unary(Op::Not, val, at);
      bool rising;
      if (isEdge(v.attribute("edge").value(), rising))
        val =
            field(nameRef(trigger(e, "_" + formal, rising, val), at), "Q", at);
      CallArg arg;
      arg.name = formal;
      arg.value = val;
      arg.loc = src.locOf(v);
      call->args.push_back(arg);
    }
  Stmt *s;
  bool en = hasEn(e);
  if (!instance.empty()) {
    s = unit.make<Stmt>(StmtKind::Call, at);
    s->value = call;
  } else {
    // A function's result and other outputs land in temporaries (VAR_TEMP:
    // back to their initial value at every scan). A call that EN skips
    // leaves them there, so what reads them gets 0 / FALSE, as in runtimes
    // built with matiec (IEC 61131-3 leaves the value open).
    VarSection keep = VarSection::Temp;
    for (pugi::xml_node v : child(e.node, "outputVariables").children()) {
      std::string formal = upper(v.attribute("formalParameter").value());
      if (localName(v) != "variable" || formal == "ENO" || formal == "OUT")
        continue;
      Pou *fn = unit.findPou(type);
      VarDecl *param = fn ? fn->find(formal) : nullptr;
      if (!param || param->section != VarSection::Output)
        fail(v, describe(e) + ": output '" + formal + "' of '" + type +
                    "' is not an output of a function netlift knows");
      std::string tmp = "_TMP_" + upper(type) + id + "_" + formal;
      VarDecl *d = declare(tmp, "", keep, v);
      d->inferType = false;
      d->typeSyntax = param->typeSyntax;
      CallArg arg;
      arg.name = formal;
      arg.isOutput = true;
      arg.value = nameRef(tmp, at);
      arg.loc = src.locOf(v);
      call->args.push_back(arg);
    }
    std::string result = "_TMP_" + upper(type) + id + "_OUT";
    declare(result, "", keep, e.node);
    s = assign(nameRef(result, at), call, at);
  }
  if (!en) {
    emit(s);
    return;
  }
  std::string flag = "_EN" + id;
  declare(flag, "BOOL", VarSection::Temp, e.node);
  pugi::xml_node env = enInput(e);
  emit(assign(nameRef(flag, at),
              joined(e, wiresOf(child(env, "connectionPointIn")), env), at));
  emit(when(nameRef(flag, at), {s}, at));
}

/// The block as drawn, for Sema to hold against the declared type: its
/// typeName and every pin with the group it sits in.
DrawnBlock *Network::drawing(const Element &b) {
  DrawnBlock *d = unit.make<DrawnBlock>();
  d->typeName = b.node.attribute("typeName").value();
  d->instanceName = b.node.attribute("instanceName").value();
  static const std::pair<const char *, VarSection> groups[] = {
      {"inputVariables", VarSection::Input},
      {"inOutVariables", VarSection::InOut},
      {"outputVariables", VarSection::Output}};
  for (auto [group, section] : groups)
    for (pugi::xml_node v : child(b.node, group).children())
      if (localName(v) == "variable")
        d->pins.push_back(
            {v.attribute("formalParameter").value(), section, src.locOf(v)});
  return d;
}

void Network::jump(const Element &e) {
  std::string label = upper(e.node.attribute("label").value());
  if (labelsSeen.count(label))
    fail(e.node, describe(e) + ": backward jump to label '" +
                     e.node.attribute("label").value() +
                     "' (loops are refused)");
  std::string flag = "_JMP" + std::to_string(e.id);
  declare(flag, "BOOL", VarSection::Temp, e.node);
  SMLoc at = src.locOf(e.node);
  emit(assign(nameRef(flag, at), power(e), at));
  pending.push_back({label, flag});
}

void Network::label(const Element &e) {
  std::string label = upper(e.node.attribute("label").value());
  if (!labelsSeen.insert(label).second)
    fail(e.node, "label '" + std::string(e.node.attribute("label").value()) +
                     "' is defined twice");
  llvm::erase_if(pending, [&](auto &p) { return p.first == label; });
}

bool Network::read(pugi::xml_node body) {
  try {
    collect(body);
    for (const Element *e : order()) {
      SMLoc at = src.locOf(e->node);
      const std::string &k = e->kind;
      if (k == "coil") {
        coil(*e);
      } else if (k == "contact") {
        bool rising;
        isEdge(e->node.attribute("edge").value(), rising);
        trigger(*e, "", rising,
                textExpr(child(e->node, "variable"), *e, "variable"));
      } else if (k == "outVariable" || k == "inOutVariable") {
        Expr *v = power(*e);
        if (k == "outVariable" && isTrue(e->node.attribute("negated")))
          v = unary(Op::Not, v, at);
        emit(assign(textExpr(child(e->node, "expression"), *e, "expression"), v,
                    at));
      } else if (k == "block") {
        block(*e);
      } else if (k == "sfcCondition") {
        emit(assign(nameRef(sfcConditions->at(e->id), at), power(*e), at));
      } else if (k == "jump") {
        jump(*e);
      } else if (k == "label") {
        label(*e);
      } else if (k == "return") {
        emit(when(power(*e), {unit.make<Stmt>(StmtKind::Return, at)}, at));
      }
    }
    if (!pending.empty())
      for (int id : document) {
        const Element &e = elements.at(id);
        if (e.kind == "jump" &&
            upper(e.node.attribute("label").value()) == pending[0].first)
          fail(e.node, describe(e) + ": no label '" +
                           e.node.attribute("label").value() +
                           "' after this jump in POU '" + pou->name + "'");
      }
  } catch (Failure &) {
    return false;
  }
  return true;
}

bool plcopen::readGraphicalBody(
    pugi::xml_node body, XmlSource &src, DiagEngine &diag, Unit &unit, Pou *pou,
    const std::map<int, std::string> *sfcConditions) {
  Network network(src, diag, unit, pou, sfcConditions);
  return network.read(body);
}
