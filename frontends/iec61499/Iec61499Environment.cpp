//===- Iec61499Environment.cpp - runtime-implemented FBs as environment ---===//
//
// A service interface FB (publish/subscribe, client/server, I/O) or an FB
// type whose behaviour only the runtime has, and that netlift ships no
// model of, becomes a module that does whatever its interface allows
// (docs/iec61499.md, "Blocks the runtime implements"):
//
//  - an input event is always accepted; one with a response (INIT ->
//    INITO, REQ -> CNF, X -> XO) is answered, immediately or any time
//    later (a transition that is not urgent); a request arriving while
//    one waits shares its response;
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

/// The data a publisher sends (SD_1...) or a subscriber receives (RD_1...).
static std::vector<const Var *> messageVars(const FbType &t, bool publisher) {
  std::vector<const Var *> out;
  for (const Var &v : publisher ? t.inputs : t.outputs)
    if (StringRef(v.name).startswith_insensitive(publisher ? "SD_" : "RD_"))
      out.push_back(&v);
  return out;
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
  for (const auto *list : {&t.inputs, &t.outputs})
    for (const Var &v : *list)
      if (!elementaryType(v.type) && !isGenericType(v.type))
        fail(t.src->locOf(v.node),
             "port '" + v.name + "' of " + what + " '" + t.name +
                 "' modelled as environment has the structured type " + v.type +
                 ": not supported");
  if (!b.createModule(t.name, false, at))
    fail(at, "a module named '" + t.name + "' exists already");
  environmentModules.insert(t.name);
  declarePorts(t, true);
  net::Module *m = b.getModule();
  bool sender = !t.sendEvent.empty();
  bool receiver = !t.deliverEvent.empty();
  auto isCond = [&](const Var &v) {
    return StringRef(v.type).equals_insensitive("BOOL") &&
           !v.node.attribute("ArraySize");
  };
  auto typeOf = [&](const Var &v) -> const net::Type * {
    return isCond(v) ? design.types.getBool()
                     : portType(v, t.src->locOf(v.node));
  };
  auto kindOf = [&](const Var &v) {
    return isCond(v) ? net::PortKind::Cond : net::PortKind::Data;
  };
  auto portType = [&](const Var &v) -> const net::Type * {
    return kindOf(v) == net::PortKind::Cond ? nullptr : typeOf(v);
  };
  // A receiver's message: what the channel brought, kept until it is
  // delivered.
  std::vector<net::Stmt *> receive;
  if (receiver)
    for (const Var *v : messageVars(t, false)) {
      SMLoc vat = t.src->locOf(v->node);
      std::string buf = "_buf_" + v->name, in = "_RCV_" + v->name;
      b.addPort(in, kindOf(*v), net::PortDir::In, portType(*v), vat);
      b.addVar(buf, typeOf(*v), nullptr, vat);
      receive.push_back(b.assign(b.ref(buf, vat), b.ref(in, vat), vat));
      m->ports[m->findPort(v->name)].definition = b.ref(buf, vat);
    }
  // Data outputs read the environment's choice.
  for (const Var &v : t.outputs) {
    if (isGenericType(v.type) || m->ports[m->findPort(v.name)].definition)
      continue;
    SMLoc vat = t.src->locOf(v.node);
    b.addPort(environmentInput(v.name), kindOf(v), net::PortDir::In,
              portType(v), vat);
    m->ports[m->findPort(v.name)].definition =
        b.ref(environmentInput(v.name), vat);
  }
  // A sender's event sends the message: _SENT with its data, as the
  // block's inputs stand when the event arrives (the receiver samples them
  // in that step, as a block samples the data WITH an event).
  auto sends = [&](StringRef event, llvm::ArrayRef<uint32_t> on, SMLoc eat) {
    if (!StringRef(t.sendEvent).equals_insensitive(event))
      return;
    uint32_t sent = b.addPort("_SENT", net::PortKind::Event, net::PortDir::Out,
                              nullptr, eat);
    for (uint32_t tr : on)
      b.setEmits(tr, {sent});
    for (const Var *v : messageVars(t, true)) {
      std::string out = "_SENT_" + v->name;
      uint32_t p =
          b.addPort(out, kindOf(*v), net::PortDir::Out, portType(*v), eat);
      m->ports[p].definition = b.ref(v->name, eat);
    }
  };
  std::set<std::string> answers;
  for (const Event &e : t.eventInputs) {
    SMLoc eat = t.src->locOf(e.node);
    uint32_t port = m->findPort(e.name);
    const Event *r = responseTo(t, e.name);
    // A client's CNF is the server's answer the channel delivers.
    if (r && StringRef(r->name).equals_insensitive(t.deliverEvent))
      r = nullptr;
    if (!r) {
      uint32_t accept = b.addTransition("accept_" + e.name, {}, {}, eat);
      b.setEvents(accept, {net::EventSource{port, true}});
      sends(e.name, {accept}, eat);
      continue;
    }
    answers.insert(StringRef(r->name).upper());
    // One request waits for its response at a time; one arriving while
    // another waits shares its response (`merge_REQ`). FORTE's service
    // blocks answer before the next request comes; letting the model's
    // later answers pile up would make every such loop unbounded.
    uint32_t idle = b.addPlace("idle_" + e.name, 1, 1, eat);
    uint32_t waiting = b.addPlace("waiting_" + e.name, 0, 1, eat);
    uint32_t accept =
        b.addTransition("accept_" + e.name, {net::PreArc{idle, 1, {}}},
                        {net::PostArc{waiting, 1}}, eat);
    uint32_t merge =
        b.addTransition("merge_" + e.name, {net::PreArc{waiting, 1, {}}},
                        {net::PostArc{waiting, 1}}, eat);
    for (uint32_t tr : {accept, merge})
      b.setEvents(tr, {net::EventSource{port, true}});
    sends(e.name, {accept, merge}, eat);
    uint32_t answer =
        b.addTransition("answer_" + e.name, {net::PreArc{waiting, 1, {}}},
                        {net::PostArc{idle, 1}}, eat);
    b.setEmits(answer, {uint32_t(m->findPort(r->name))});
  }
  std::optional<uint32_t> arrived;
  if (receiver) {
    // One message held at a time: a second before it is delivered
    // is out of range of `_messages_waiting` (a runtime error with its
    // trace), never silently lost. A held message also marks `arrived`,
    // which the delivery empties before the next tick (a deadline): the
    // network's latency is below the design's time unit. Without it the
    // environment could hold a message while time passes, and every
    // periodic publisher would overflow its subscriber. Capacity 2, so
    // that a second message is received (and is the error) rather than
    // refused by a full place.
    b.addVar("_messages_waiting", design.types.getRange(0, 1), nullptr, at);
    arrived = b.addPlace("arrived", 0, 2, at);
    uint32_t rcv =
        b.addPort("_RCV", net::PortKind::Event, net::PortDir::In, nullptr, at);
    uint32_t get =
        b.addTransition("receive", {}, {net::PostArc{*arrived, 1}}, at);
    b.setEvents(get, {net::EventSource{rcv, true}});
    if (lossyChannels) {
      // Each message is received or lost (`lose`): the two take the same
      // token, so exactly one of them reacts to it.
      uint32_t line = b.addPlace("line", 1, 1, at);
      uint32_t lose = b.addTransition("lose", {net::PreArc{line, 1, {}}},
                                      {net::PostArc{line, 1}}, at);
      b.setEvents(lose, {net::EventSource{rcv, true}});
      m->transitions[get].setArcs(
          design.copy(llvm::ArrayRef<net::PreArc>{net::PreArc{line, 1, {}}}),
          design.copy(llvm::ArrayRef<net::PostArc>{net::PostArc{line, 1},
                                                   net::PostArc{*arrived, 1}}));
    }
    receive.push_back(
        b.assign(b.ref("_messages_waiting", at),
                 b.binary(net::BinaryOp::Add, b.ref("_messages_waiting", at),
                          b.intLit(1, at), at),
                 at));
    b.setAction(get, receive);
  }
  for (const Event &e : t.eventOutputs) {
    if (answers.count(StringRef(e.name).upper()))
      continue;
    SMLoc eat = t.src->locOf(e.node);
    if (receiver && StringRef(e.name).equals_insensitive(t.deliverEvent)) {
      net::Interval beforeTick;
      beforeTick.hi = 0;
      beforeTick.deadline = true;
      uint32_t deliver = b.addTransition(
          "deliver_" + e.name, {net::PreArc{*arrived, 1, beforeTick}}, {}, eat);
      b.setEmits(deliver, {uint32_t(m->findPort(e.name))});
      b.setAction(deliver, {b.assign(b.ref("_messages_waiting", eat),
                                     b.intLit(0, eat), eat)});
      continue;
    }
    uint32_t ind = b.addTransition("occur_" + e.name, {}, {}, eat);
    b.setEmits(ind, {uint32_t(m->findPort(e.name))});
  }
  if (sender || receiver) {
    std::string how;
    if (sender)
      how = "it sends its SD_i with " + t.sendEvent;
    if (receiver)
      how += (sender ? "; " : "") + std::string("what it receives is ") +
             "delivered by its " + t.deliverEvent + ", before time advances";
    diag.note(at, Twine(what) + " '" + t.name +
                      "' is modelled as an end of a channel: " + how +
                      " (docs/iec61499.md)");
  } else
    diag.note(at, Twine(what) + " '" + t.name +
                      "' is modelled as environment: its output events "
                      "occur as its interface allows and its data outputs "
                      "take any value (docs/iec61499.md)");
}

//===----------------------------------------------------------------------===//
// Channels: a PUBLISH_n and the SUBSCRIBE_n blocks of the same network with
// the same ID. The publisher's accepted REQ sends its SD_1..SD_n
// (`_SENT`, `_SD_i`); each subscriber keeps the message (`_RCV`, `_RD_i`)
// until its IND delivers it, before the next tick, with RD_i the values sent. A
// second message before the first is delivered is a runtime error (the
// channel holds one): lossless, never silently dropped.
//===----------------------------------------------------------------------===//

std::vector<Translator::Channel> Translator::channelsOf(XmlSource &src,
                                                        pugi::xml_node net) {
  std::vector<Channel> out;
  if (!opaqueAsEnvironment)
    return out;
  for (pugi::xml_node fb : blocksOf(net)) {
    StringRef type = fb.attribute("Type").value();
    bool client = type.startswith_insensitive("CLIENT_");
    bool pub = type.startswith_insensitive("PUBLISH_") || client;
    bool sub = type.startswith_insensitive("SUBSCRIBE_") ||
               type.startswith_insensitive("SERVER_");
    if (!pub && !sub)
      continue;
    std::string id;
    for (pugi::xml_node p : fb.children("Parameter"))
      if (StringRef(p.attribute("Name").value()).equals_insensitive("ID"))
        id = StringRef(src.placeAttribute(p, "Value")).trim().trim("\"'").str();
    if (id.empty())
      continue;
    bool pair = client || type.startswith_insensitive("SERVER_");
    auto it = std::find_if(out.begin(), out.end(), [&](const Channel &c) {
      return c.id == id && c.clientServer == pair;
    });
    if (it == out.end()) {
      out.push_back({id, pair, {}, {}});
      it = out.end() - 1;
    }
    (pub ? it->publishers : it->subscribers).push_back(fb);
  }
  llvm::erase_if(out, [](const Channel &c) {
    return c.publishers.empty() || c.subscribers.empty();
  });
  return out;
}

void Translator::makeChannelEnds(XmlSource &src, pugi::xml_node net) {
  for (const Channel &c : channelsOf(src, net)) {
    const char *senders = c.clientServer ? "client" : "publisher";
    if (c.publishers.size() > 1)
      fail(src.locOf(c.publishers[1]),
           "a second " + Twine(senders) + " with ID '" + c.id +
               "' in this network: netlift connects one " + senders +
               " to its " + (c.clientServer ? "server" : "subscribers"));
    if (c.clientServer && c.subscribers.size() > 1)
      fail(src.locOf(c.subscribers[1]),
           "a second server with ID '" + c.id +
               "' in this network: netlift connects one client to one "
               "server");
    pugi::xml_node first = c.publishers[0];
    FbType *pub = findType(first.attribute("Type").value(), src.locOf(first));
    // What one end sends the other receives, datum by datum.
    auto matches = [&](const FbType &from, const FbType &to) {
      std::vector<const Var *> sent = messageVars(from, true),
                               got = messageVars(to, false);
      bool same = got.size() == sent.size();
      for (size_t i = 0; same && i < got.size(); ++i)
        same = StringRef(got[i]->type).equals_insensitive(sent[i]->type);
      return same;
    };
    for (pugi::xml_node fb : c.subscribers) {
      FbType *sub = findType(fb.attribute("Type").value(), src.locOf(fb));
      if (!matches(*pub, *sub) || (c.clientServer && !matches(*sub, *pub)))
        fail(src.locOf(fb),
             (c.clientServer ? "server '" : "subscriber '") +
                 Twine(fb.attribute("Name").value()) + "' (ID '" + c.id +
                 "') does not receive what '" +
                 first.attribute("Name").value() + "' sends" +
                 (c.clientServer ? " or answer what it receives" : "") +
                 ": the data and their types must match one by one");
    }
    auto end = [&](pugi::xml_node fb, StringRef send, StringRef deliver) {
      FbType *t = findType(fb.attribute("Type").value(), src.locOf(fb));
      std::string name = t->name + "__CHANNEL";
      FbType &ct =
          generatedType(name, interfaceXml(name, *t, [](const Var &v) {
                                return v.type;
                              }) + "</InterfaceList>\n<Service/>\n</FBType>\n");
      ct.sendEvent = send.str();
      ct.deliverEvent = deliver.str();
      retype(fb, name);
    };
    if (c.clientServer) {
      end(first, "REQ", "CNF");
      end(c.subscribers[0], "RSP", "IND");
      continue;
    }
    end(first, "REQ", "");
    for (pugi::xml_node fb : c.subscribers)
      end(fb, "", "IND");
  }
}

void Translator::connectChannels(XmlSource &src, pugi::xml_node net) {
  auto connect = [&](pugi::xml_node from, pugi::xml_node to, SMLoc at) {
    StringRef fromName = design.save(from.attribute("Name").value()),
              toName = design.save(to.attribute("Name").value());
    b.addConnection({fromName, "_SENT", at}, {toName, "_RCV", at}, at);
    std::vector<const Var *> sent =
        messageVars(*findType(from.attribute("Type").value(), at), true);
    std::vector<const Var *> got =
        messageVars(*findType(to.attribute("Type").value(), at), false);
    for (size_t i = 0; i < sent.size(); ++i)
      b.addConnection({fromName, design.save("_SENT_" + sent[i]->name), at},
                      {toName, design.save("_RCV_" + got[i]->name), at}, at);
  };
  for (const Channel &c : channelsOf(src, net)) {
    pugi::xml_node p = c.publishers[0];
    SMLoc at = src.locOf(p);
    for (pugi::xml_node fb : c.subscribers) {
      connect(p, fb, at);
      if (c.clientServer)
        connect(fb, p, at);
    }
  }
}
