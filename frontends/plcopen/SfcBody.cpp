//===- SfcBody.cpp - graphical SFC bodies of PLCopen XML ------------------===//
//
// Reads an <SFC> body into the chart textual SFC gives (PlcAst.h's
// SfcChart), which expandSfc then turns into scan code: the same chart in
// either form is one model. Steps and transitions are joined through
// divergences, convergences and jump steps by following each element's
// connectionPointIn; a selection's priority is the transitions' `priority`
// attribute, then their left-to-right position in the drawing.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/SfcExpansion.h"
#include "frontends/plcopen/PlcOpen.h"
#include "frontends/st/StFrontend.h"

#include <map>
#include <set>

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plcopen;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

class SfcReader {
public:
  SfcReader(XmlSource &src, DiagEngine &diag, Unit &unit, Pou *pou,
            const SfcBodyReader &readBody)
      : src(src), diag(diag), unit(unit), pou(pou), readBody(readBody) {}
  bool read(pugi::xml_node sfc, pugi::xml_node pouNode);

private:
  struct Failure {};
  [[noreturn]] void fail(pugi::xml_node at, const llvm::Twine &msg) {
    diag.error(src.locOf(at), msg);
    throw Failure();
  }
  std::vector<int> inputs(pugi::xml_node e) const;
  pugi::xml_node element(int id, pugi::xml_node from);
  void stepsBefore(pugi::xml_node e, std::vector<pugi::xml_node> &out);
  void stepsAfter(pugi::xml_node e, std::vector<pugi::xml_node> &out,
                  std::set<int> &seen);
  std::string stepName(pugi::xml_node step);
  Expr *condition(pugi::xml_node t);
  void actionBlock(pugi::xml_node block);
  SfcAction *namedAction(StringRef name);
  /// The POU's <section><element name=...> (an action or a transition).
  pugi::xml_node pouPart(StringRef section, StringRef element,
                         StringRef name) const {
    pugi::xml_node found;
    if (pugi::xml_node all = child(pouNode, section))
      for (pugi::xml_node d : all.children())
        if (localName(d) == element &&
            sameName(d.attribute("name").value(), name))
          found = d;
    return found;
  }

  XmlSource &src;
  DiagEngine &diag;
  Unit &unit;
  Pou *pou;
  const SfcBodyReader &readBody;
  SfcChart *chart = nullptr;
  pugi::xml_node pouNode;
  std::map<int, pugi::xml_node> byId;
  /// Elements by the ids their inputs connect to.
  std::map<int, std::vector<pugi::xml_node>> successors;
  std::map<int, SfcStep *> steps;
  std::map<std::string, SfcAction *> actionsByName;
  int inlineActions = 0;
  std::set<std::string> readTransitions;
  bool hasNetworks = false;
  std::map<int, std::string> wired;
};

} // namespace

std::vector<int> SfcReader::inputs(pugi::xml_node e) const {
  std::vector<int> ids;
  for (pugi::xml_node in : e.children())
    if (localName(in) == "connectionPointIn")
      for (pugi::xml_node c : in.children())
        if (localName(c) == "connection")
          ids.push_back(c.attribute("refLocalId").as_int(-1));
  return ids;
}

pugi::xml_node SfcReader::element(int id, pugi::xml_node from) {
  auto it = byId.find(id);
  if (it == byId.end())
    fail(from, "connection to localId " + llvm::Twine(id) +
                   ", which the SFC body does not have");
  return it->second;
}

std::string SfcReader::stepName(pugi::xml_node step) {
  std::string name = step.attribute("name").value();
  if (name.empty())
    fail(step, "<step> without a name");
  return name;
}

/// The steps a transition leaves: through a selection divergence (one
/// step) or a simultaneous convergence (several).
void SfcReader::stepsBefore(pugi::xml_node e,
                            std::vector<pugi::xml_node> &out) {
  StringRef kind = localName(e);
  if (kind == "step") {
    out.push_back(e);
    return;
  }
  if (kind == "selectionDivergence" || kind == "simultaneousConvergence") {
    for (int id : inputs(e))
      stepsBefore(element(id, e), out);
    return;
  }
  fail(e, "<" + kind.str() +
              "> before a transition: expected a step, a "
              "selection divergence or a simultaneous "
              "convergence");
}

/// The steps a transition enters: through a simultaneous divergence
/// (several), a selection convergence or a jump step.
void SfcReader::stepsAfter(pugi::xml_node e, std::vector<pugi::xml_node> &out,
                           std::set<int> &seen) {
  StringRef kind = localName(e);
  int id = e.attribute("localId").as_int(-1);
  if (kind == "step") {
    out.push_back(e);
    return;
  }
  if (!seen.insert(id).second)
    fail(e, "the SFC body's connections form a loop without a step");
  if (kind == "jumpStep") {
    StringRef target = e.attribute("targetName").value();
    for (auto &[sid, s] : byId)
      if (localName(s) == "step" &&
          sameName(s.attribute("name").value(), target)) {
        out.push_back(s);
        return;
      }
    fail(e, "jump to step '" + target + "', which the chart does not have");
  }
  if (kind == "simultaneousDivergence" || kind == "selectionConvergence") {
    for (pugi::xml_node next : successors[id])
      stepsAfter(next, out, seen);
    return;
  }
  if (kind == "macroStep")
    fail(e, "macro steps are not supported");
  fail(e, "<" + kind.str() +
              "> after a transition: expected a step, a jump "
              "step, a simultaneous divergence or a "
              "selection convergence");
}

Expr *SfcReader::condition(pugi::xml_node t) {
  pugi::xml_node cond = child(t, "condition");
  if (!cond)
    fail(t, "<transition> without a <condition>");
  if (pugi::xml_node in = child(cond, "inline")) {
    pugi::xml_node st = child(in, "ST");
    if (!st)
      fail(in, "an inline transition condition in a language other than "
               "ST is not supported");
    StringRef text = src.placeText(st);
    Expr *e = st::parseStExpression(text, diag, unit);
    if (!e)
      throw Failure();
    return e;
  }
  if (pugi::xml_node ref = child(cond, "reference")) {
    // A POU transition: its body sets a BOOL named like it (an ST body
    // may also be `:= expression;`).
    std::string name = ref.attribute("name").value();
    pugi::xml_node def = pouPart("transitions", "transition", name);
    if (!def)
      fail(ref,
           "transition '" + name + "' is not among the POU's <transitions>");
    pugi::xml_node body = child(def, "body");
    if (pugi::xml_node st = body ? child(body, "ST") : pugi::xml_node()) {
      StringRef text = src.placeText(st);
      if (text.ltrim().startswith(":=")) {
        size_t at = text.find(":=");
        StringRef rest = text.substr(at + 2).rtrim().rtrim(';');
        // Keep the offset so that diagnostics point into the file.
        Expr *e = st::parseStExpression(
            StringRef(text.data() + at + 2, rest.size()), diag, unit);
        if (!e)
          throw Failure();
        return e;
      }
    }
    SMLoc at = src.locOf(def);
    if (readTransitions.insert(StringRef(name).upper()).second) {
      if (!body || pou->find(name))
        fail(def, "transition '" + name +
                      "' has no body, or the name of a variable");
      AstMaker(unit).declare(*pou, name, "BOOL", at, VarSection::Temp);
      StmtList computed;
      if (!readBody(body, computed))
        throw Failure();
      llvm::append_range(chart->networks, computed);
    }
    Expr *e = unit.make<Expr>(ExprKind::Name, at);
    e->name = name;
    return e;
  }
  if (!child(cond, "connectionPointIn"))
    fail(cond, "a <condition> with neither an inline expression, a "
               "reference nor a connection");
  // Wired from the networks drawn beside the chart (read in read()).
  std::string var =
      "__SFC_CONDITION_" + std::to_string(t.attribute("localId").as_int());
  Expr *e = unit.make<Expr>(ExprKind::Name, src.locOf(cond));
  e->name = var;
  return e;
}

SfcAction *SfcReader::namedAction(StringRef name) {
  auto it = actionsByName.find(name.upper());
  if (it != actionsByName.end())
    return it->second;
  pugi::xml_node def = pouPart("actions", "action", name);
  if (!def)
    return nullptr; // a Boolean variable as the action
  auto *a = unit.make<SfcAction>();
  a->name = name.str();
  a->loc = src.locOf(def);
  pugi::xml_node body = child(def, "body");
  if (!body)
    fail(def, "action '" + name + "' has no <body>");
  if (!readBody(body, a->body))
    throw Failure();
  chart->actions.push_back(a);
  actionsByName[name.upper()] = a;
  return a;
}

void SfcReader::actionBlock(pugi::xml_node block) {
  std::vector<int> in = inputs(block);
  if (in.size() != 1 || localName(element(in[0], block)) != "step")
    fail(block, "an <actionBlock> must be connected to one step");
  SfcStep *step = steps.at(in[0]);
  for (pugi::xml_node a : block.children()) {
    if (localName(a) != "action")
      continue;
    SfcAssociation assoc;
    assoc.loc = src.locOf(a);
    if (pugi::xml_attribute q = a.attribute("qualifier"))
      assoc.qualifier = StringRef(q.value()).upper();
    static const char *const kQualifiers[] = {"N", "R", "S",  "P",  "P0", "P1",
                                              "L", "D", "SD", "DS", "SL"};
    if (!llvm::is_contained(kQualifiers, assoc.qualifier))
      fail(a, "unknown action qualifier '" + assoc.qualifier + "'");
    if (pugi::xml_attribute d = a.attribute("duration")) {
      bool found;
      StringRef text = src.placeAttribute(a, "duration", &found);
      assoc.time = st::parseStExpression(text, diag, unit);
      if (!assoc.time)
        throw Failure();
    }
    if (pugi::xml_attribute ind = a.attribute("indicator"))
      if (*ind.value())
        assoc.indicators.push_back(ind.value());
    if (pugi::xml_node ref = child(a, "reference")) {
      assoc.action = ref.attribute("name").value();
      namedAction(assoc.action);
    } else if (pugi::xml_node inl = child(a, "inline")) {
      auto *act = unit.make<SfcAction>();
      act->name = step->name + "_INLINE" + std::to_string(++inlineActions);
      act->loc = src.locOf(inl);
      pugi::xml_node st = child(inl, "ST");
      if (!st)
        fail(inl, "an inline action in a language other than ST is not "
                  "supported (make it a POU action)");
      if (!st::parseStatements(src.placeText(st), diag, unit, act->body))
        throw Failure();
      chart->actions.push_back(act);
      actionsByName[StringRef(act->name).upper()] = act;
      assoc.action = act->name;
    } else {
      fail(a, "<action> with neither a <reference> nor an <inline> body");
    }
    step->actions.push_back(std::move(assoc));
  }
}

bool SfcReader::read(pugi::xml_node sfc, pugi::xml_node p) {
  pouNode = p;
  chart = unit.make<SfcChart>();
  try {
    for (pugi::xml_node e : sfc.children()) {
      if (e.type() != pugi::node_element)
        continue;
      StringRef kind = localName(e);
      if (kind == "comment" || kind == "documentation" || kind == "addData")
        continue;
      int id = e.attribute("localId").as_int(-1);
      if (id < 0)
        fail(e, "<" + kind.str() + "> without a localId");
      if (!byId.emplace(id, e).second)
        fail(e, "localId " + llvm::Twine(id) + " is used twice");
      if (kind == "macroStep")
        fail(e, "macro steps are not supported");
      static const char *const kChart[] = {"step",
                                           "transition",
                                           "selectionDivergence",
                                           "selectionConvergence",
                                           "simultaneousDivergence",
                                           "simultaneousConvergence",
                                           "jumpStep",
                                           "actionBlock"};
      if (!llvm::is_contained(kChart, kind))
        hasNetworks = true; // LD/FBD beside the chart
      if (kind == "transition")
        if (pugi::xml_node c =
                child(child(e, "condition"), "connectionPointIn"))
          wired[id] = "__SFC_CONDITION_" + std::to_string(id);
    }
    if (hasNetworks || !wired.empty()) {
      for (auto &[id, var] : wired)
        AstMaker(unit).declare(*pou, var, "BOOL", src.locOf(byId[id]),
                               VarSection::Temp);
      StmtList own = std::move(pou->body);
      pou->body.clear();
      bool ok = readGraphicalBody(sfc, src, diag, unit, pou, &wired);
      chart->networks = std::move(pou->body);
      pou->body = std::move(own);
      if (!ok)
        return false;
    }
    for (auto &[id, e] : byId)
      for (int in : inputs(e))
        successors[in].push_back(e);
    for (auto &[id, e] : byId)
      if (localName(e) == "step") {
        // Vendor data naming an action (CODESYS's entry/exit step
        // actions) would run code the chart does not show: refused.
        for (pugi::xml_node add : e.children())
          if (localName(add) == "addData")
            for (pugi::xml_node d : add.children())
              if (StringRef(d.attribute("name").value())
                      .contains_insensitive("action"))
                fail(d, "step '" + stepName(e) + "' has vendor step actions (" +
                            d.attribute("name").value() +
                            "): entry and exit actions are not supported");
        auto *s = unit.make<SfcStep>();
        s->name = stepName(e);
        s->loc = src.locOf(e);
        s->initial = isTrue(e.attribute("initialStep"));
        steps[id] = s;
        chart->steps.push_back(s);
      }
    // Transitions in priority order: `priority`, then left to right.
    std::vector<pugi::xml_node> transitions;
    for (auto &[id, e] : byId)
      if (localName(e) == "transition")
        transitions.push_back(e);
    auto x = [](pugi::xml_node e) {
      pugi::xml_node pos = child(e, "position");
      return pos ? pos.attribute("x").as_double() : 0.0;
    };
    std::stable_sort(
        transitions.begin(), transitions.end(),
        [&](pugi::xml_node a, pugi::xml_node b) { return x(a) < x(b); });
    for (pugi::xml_node t : transitions) {
      auto *tr = unit.make<SfcTransition>();
      tr->loc = src.locOf(t);
      tr->name = t.attribute("name").value();
      if (pugi::xml_attribute pr = t.attribute("priority"))
        tr->priority = pr.as_llong();
      std::vector<pugi::xml_node> from, to;
      std::vector<int> in = inputs(t);
      if (in.size() != 1)
        fail(t, "a <transition> must have one input connection");
      stepsBefore(element(in[0], t), from);
      std::set<int> seen;
      int id = t.attribute("localId").as_int();
      if (successors[id].empty())
        fail(t, "a <transition> that leads nowhere");
      for (pugi::xml_node next : successors[id])
        stepsAfter(next, to, seen);
      for (pugi::xml_node s : from) {
        tr->from.push_back(stepName(s));
        tr->fromLocs.push_back(src.locOf(s));
      }
      for (pugi::xml_node s : to) {
        tr->to.push_back(stepName(s));
        tr->toLocs.push_back(src.locOf(s));
      }
      tr->condition = condition(t);
      pugi::xml_node cond = child(t, "condition");
      if (pugi::xml_node in = child(cond, "inline"))
        tr->conditionText = src.placeText(child(in, "ST")).trim().str();
      else if (pugi::xml_node ref = child(cond, "reference"))
        tr->conditionText = ref.attribute("name").value();
      else
        tr->conditionText = "(network)";
      chart->transitions.push_back(tr);
    }
    for (auto &[id, e] : byId)
      if (localName(e) == "actionBlock")
        actionBlock(e);
  } catch (Failure &) {
    return false;
  }
  if (chart->steps.empty()) {
    diag.error(src.locOf(sfc), "SFC body of '" + pou->name + "' has no step");
    return false;
  }
  pou->sfc = chart;
  return expandSfc(unit, *pou, diag);
}

bool plcopen::readSfcBody(pugi::xml_node sfc, pugi::xml_node pouNode,
                          XmlSource &src, DiagEngine &diag, Unit &unit,
                          Pou *pou, const SfcBodyReader &readBody) {
  return SfcReader(src, diag, unit, pou, readBody).read(sfc, pouNode);
}
