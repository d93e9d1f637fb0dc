//===- Iec61499Environment.cpp - runtime-implemented FBs as environment ---===//
//
// A service interface FB (publish/subscribe, client/server, I/O) or an FB
// type whose behaviour only the runtime has, and that netlift ships no
// model of, becomes a module that does whatever its interface allows
// (docs/iec61499.md, "Blocks the runtime implements"):
//
//  - an input event is always accepted; one with a response (INIT ->
//    INITO, REQ -> CNF, X -> XO) leaves it pending, and the response is
//    emitted once, immediately or any time later (a transition that is not
//    urgent); a second request while one is pending is lost, as FORTE's
//    blocks drop it;
//  - an output event that answers nothing (IND, an I/O block's change) may
//    be emitted at any time, as the environment chooses;
//  - every data output is a free input of the model, read through the
//    output (`cond output QO = QO.env;`): whoever samples it with an event
//    sees any value of its type, which covers every value the block could
//    have sent with it.
//
// Data inputs stay inputs (the values sent to the block are observable in
// the network). `--opaque=refuse` refuses such blocks instead.
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail;

/// The output event that answers input event `in`, if any: `in` + "O"
/// (INIT -> INITO), or CNF for REQ.
static const Event *responseTo(const FbType &t, StringRef in) {
  for (const Event &e : t.eventOutputs)
    if (StringRef(e.name).equals_insensitive(in.str() + "O"))
      return &e;
  if (in.equals_insensitive("REQ"))
    for (const Event &e : t.eventOutputs)
      if (StringRef(e.name).equals_insensitive("CNF"))
        return &e;
  return nullptr;
}

std::string netlift::iec61499::detail::environmentInput(StringRef output) {
  return output.str() + ".env";
}

void Translator::environmentModule(FbType &t) {
  SMLoc at = t.src->locOf(t.root);
  const char *what =
      t.kind == TypeKind::Service ? "service interface FB" : "FB type";
  // Generic ports (ANY...) take their types from the connections of each
  // block (specializeGenericFunctions); the type alone has none to give.
  std::string generic;
  for (const auto *list : {&t.inputs, &t.outputs})
    for (const Var &v : *list)
      if (isGenericType(v.type))
        generic += (generic.empty() ? "" : ", ") + v.name + " : " + v.type;
  if (!generic.empty())
    diag.note(at, Twine(what) + " '" + t.name +
                      "' translated alone: its "
                      "ports of generic types (" +
                      generic +
                      ") are left out; in a network each block has them, "
                      "typed by its connections");
  if (!b.createModule(t.name, false, at))
    fail(at, "a module named '" + t.name + "' exists already");
  declarePorts(t, true);
  net::Module *m = b.getModule();
  // Data outputs read the environment's choice.
  for (const Var &v : t.outputs) {
    if (isGenericType(v.type))
      continue;
    SMLoc vat = t.src->locOf(v.node);
    bool isBool = StringRef(v.type).equals_insensitive("BOOL");
    b.addPort(environmentInput(v.name),
              isBool ? net::PortKind::Cond : net::PortKind::Data,
              net::PortDir::In, isBool ? nullptr : dataType(v.type, vat), vat);
    m->ports[m->findPort(v.name)].definition =
        b.ref(environmentInput(v.name), vat);
  }
  std::set<std::string> answers;
  for (const Event &e : t.eventInputs) {
    SMLoc eat = t.src->locOf(e.node);
    uint32_t port = m->findPort(e.name);
    const Event *r = responseTo(t, e.name);
    if (!r) {
      uint32_t accept = b.addTransition("accept_" + e.name, {}, {}, eat);
      b.setEvents(accept, {net::EventSource{port, true}});
      continue;
    }
    answers.insert(StringRef(r->name).upper());
    uint32_t idle = b.addPlace("idle_" + e.name, 1, 1, eat);
    uint32_t pending = b.addPlace("pending_" + e.name, 0, 1, eat);
    uint32_t accept =
        b.addTransition("accept_" + e.name, {net::PreArc{idle, 1, {}}},
                        {net::PostArc{pending, 1}}, eat);
    b.setEvents(accept, {net::EventSource{port, true}});
    // A request while one is pending: taken and dropped.
    uint32_t drop =
        b.addTransition("drop_" + e.name, {net::PreArc{pending, 1, {}}},
                        {net::PostArc{pending, 1}}, eat);
    b.setEvents(drop, {net::EventSource{port, true}});
    uint32_t answer =
        b.addTransition("answer_" + e.name, {net::PreArc{pending, 1, {}}},
                        {net::PostArc{idle, 1}}, eat);
    b.setEmits(answer, {uint32_t(m->findPort(r->name))});
  }
  for (const Event &e : t.eventOutputs) {
    if (answers.count(StringRef(e.name).upper()))
      continue;
    SMLoc eat = t.src->locOf(e.node);
    uint32_t ind = b.addTransition("occur_" + e.name, {}, {}, eat);
    b.setEmits(ind, {uint32_t(m->findPort(e.name))});
  }
  diag.note(at, Twine(what) + " '" + t.name +
                    "' is modelled as environment: its output events occur "
                    "as its interface allows and its data outputs take any "
                    "value (docs/iec61499.md)");
}
