//===- SpaceExReader.cpp - SpaceEx hybrid automata XML to NetIR -----------===//
//
// Reads SpaceEx's `sspaceex` XML (HyST, ARCH-COMP; FORMATS.md): base
// components (params, locations with flow and invariant, transitions with
// label, guard and assignment) and network components (binds with param
// maps). The system (`--top NAME`, else the last component) is flattened
// into one NetIR module:
//   - each location of each bound instance is a place `inst.loc`, the
//     first location of each instance marked;
//   - real params become `real` variables (unbounded range, starting at 0:
//     SpaceEx keeps ranges and initial states in its .cfg file, which is
//     not read), constant params are replaced by the values bound to them;
//   - flows `x' == e` become `flow` blocks, invariants `invariant` blocks,
//     guards NetIR guards, resets `x' == e` / `x := e` actions;
//   - transitions sharing a label synchronise: one NetIR transition per
//     combination of one transition per instance that has the label.
// What NetIR cannot say is refused with the element's position: variables
// left free in a location's flow, functions (sin, exp, ...), non-integer
// powers, and params without a value.
//
//===----------------------------------------------------------------------===//
#include "frontends/FrontendRegistry.h"
#include "frontends/XmlSupport.h"

#include "ir/net/Builder.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"

#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <set>

using namespace netlift;
using namespace netlift::net;
using llvm::StringRef;

namespace {

/// What a component's param is bound to in the flat model.
struct Binding {
  std::string name;            // a flat variable or label
  std::optional<double> value; // or a constant
};
using Bindings = std::map<std::string, Binding>;

struct ProtoTransition {
  uint32_t from, to;
  std::string label; // flat label name, empty: none
  unsigned instance;
  std::vector<Expr *> guards;
  std::vector<Stmt *> resets;
  pugi::xml_node node;
};

class SpaceExReader {
public:
  /// `top`: the component to translate (--top); empty: the last one.
  SpaceExReader(unsigned bufferID, DiagEngine &diag, Design &design,
                StringRef top)
      : diag(diag), d(design), b(design),
        xml(diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer()),
        wantedTop(top.str()) {}
  bool run();

private:
  bool error(pugi::xml_node n, const llvm::Twine &msg) {
    diag.error(xml.locOf(n), msg);
    return false;
  }
  /// The conjuncts of a guard or invariant element, chained comparisons
  /// split, `true` left out.
  bool conditions(pugi::xml_node node, const Bindings &bind,
                  const std::string &prefix, std::vector<Expr *> &out);
  bool instantiate(pugi::xml_node comp, const std::string &prefix,
                   const Bindings &bind, unsigned depth);
  bool instantiateBase(pugi::xml_node comp, const std::string &prefix,
                       const Bindings &bind);
  pugi::xml_node component(StringRef id) {
    for (pugi::xml_node c : root.children("component"))
      if (id == c.attribute("id").value())
        return c;
    return {};
  }
  std::string real(const std::string &flat, pugi::xml_node where);

  // Expressions (SpaceEx math syntax) -------------------------------------
  struct ExprParser;
  Expr *parse(StringRef text, pugi::xml_node where, const Bindings &bind,
              const std::string &prefix, bool &ok);

  DiagEngine &diag;
  Design &d;
  Builder b;
  XmlBuffer xml;
  std::string wantedTop;
  pugi::xml_node root;
  Module *mod = nullptr;
  llvm::StringSet<> reals;
  /// Texts made from the file's (a chained comparison's parts).
  std::deque<std::string> ownedText;
  std::vector<std::string> realOrder;
  std::vector<ProtoTransition> protos;
  std::vector<std::set<std::string>> labelsOf; // per instance
  unsigned numInstances = 0;
};

/// Recursive descent over SpaceEx's infix syntax: | & ! comparisons + - * /
/// ^ unary minus, parentheses, numbers, names; `x'` is the primed name.
struct SpaceExReader::ExprParser {
  SpaceExReader &r;
  StringRef s;
  size_t pos = 0;
  pugi::xml_node where;
  const Bindings &bind;
  const std::string &prefix;
  bool ok = true;
  std::string primed; // set when the last primary was `x'`

  void skip() {
    while (pos < s.size() && isspace((unsigned char)s[pos]))
      ++pos;
  }
  bool eat(StringRef t) {
    skip();
    if (s.substr(pos).startswith(t)) {
      pos += t.size();
      return true;
    }
    return false;
  }
  Expr *fail(const llvm::Twine &msg) {
    if (ok)
      r.error(where, msg + " in '" + s.trim() + "'");
    ok = false;
    return nullptr;
  }
  Expr *orExpr() {
    Expr *e = andExpr();
    while (ok && (eat("||") || eat("|")))
      e = r.b.binary(BinaryOp::Or, e, andExpr());
    return e;
  }
  Expr *andExpr() {
    Expr *e = notExpr();
    while (ok && (eat("&&") || eat("&")))
      e = r.b.binary(BinaryOp::And, e, notExpr());
    return e;
  }
  Expr *notExpr() {
    skip();
    if (pos < s.size() && s[pos] == '!' && !s.substr(pos).startswith("!=")) {
      ++pos;
      return r.b.unary(UnaryOp::Not, notExpr());
    }
    return cmpExpr();
  }
  Expr *cmpExpr() {
    Expr *a = addExpr();
    if (!ok)
      return nullptr;
    static const std::pair<StringRef, BinaryOp> ops[] = {
        {"==", BinaryOp::Eq}, {"!=", BinaryOp::Ne}, {"<=", BinaryOp::Le},
        {">=", BinaryOp::Ge}, {"<", BinaryOp::Lt},  {">", BinaryOp::Gt},
        {"=", BinaryOp::Eq}};
    for (auto &[t, op] : ops)
      if (eat(t))
        return r.b.binary(op, a, addExpr());
    return a;
  }
  Expr *addExpr() {
    Expr *e = mulExpr();
    for (;;) {
      if (!ok)
        return nullptr;
      if (eat("+"))
        e = r.b.binary(BinaryOp::Add, e, mulExpr());
      else if (eat("-"))
        e = r.b.binary(BinaryOp::Sub, e, mulExpr());
      else
        return e;
    }
  }
  Expr *mulExpr() {
    Expr *e = powExpr();
    for (;;) {
      if (!ok)
        return nullptr;
      if (eat("*"))
        e = r.b.binary(BinaryOp::Mul, e, powExpr());
      else if (eat("/"))
        e = r.b.binary(BinaryOp::Div, e, powExpr());
      else
        return e;
    }
  }
  Expr *powExpr() {
    Expr *base = unary();
    if (!ok || !eat("^"))
      return base;
    skip();
    size_t start = pos;
    while (pos < s.size() && isdigit((unsigned char)s[pos]))
      ++pos;
    unsigned long long n;
    if (start == pos || s.slice(start, pos).getAsInteger(10, n) || n == 0 ||
        n > 16)
      return fail("only whole powers from 1 to 16 are supported (x^k)");
    Expr *e = base;
    for (unsigned long long i = 1; i < n; ++i)
      e = r.b.binary(BinaryOp::Mul, e, base);
    return e;
  }
  Expr *unary() {
    if (eat("-"))
      return r.b.unary(UnaryOp::Neg, unary());
    if (eat("+"))
      return unary();
    return primary();
  }
  Expr *primary() {
    skip();
    if (pos >= s.size())
      return fail("unexpected end of the expression");
    if (s[pos] == '(') {
      ++pos;
      Expr *e = orExpr();
      if (ok && !eat(")"))
        return fail("expected ')'");
      return e;
    }
    if (isdigit((unsigned char)s[pos]) || s[pos] == '.') {
      size_t start = pos;
      while (pos < s.size() &&
             (isdigit((unsigned char)s[pos]) || s[pos] == '.' ||
              ((s[pos] == 'e' || s[pos] == 'E') && pos + 1 < s.size()) ||
              ((s[pos] == '-' || s[pos] == '+') &&
               (s[pos - 1] == 'e' || s[pos - 1] == 'E'))))
        ++pos;
      double v;
      if (s.slice(start, pos).getAsDouble(v))
        return fail("malformed number '" + s.slice(start, pos) + "'");
      return r.b.realLit(v);
    }
    if (isalpha((unsigned char)s[pos]) || s[pos] == '_') {
      size_t start = pos;
      while (pos < s.size() &&
             (isalnum((unsigned char)s[pos]) || s[pos] == '_' || s[pos] == '.'))
        ++pos;
      std::string name = s.slice(start, pos).str();
      skip();
      if (pos < s.size() && s[pos] == '(')
        return fail("function '" + name +
                    "' has no NetIR counterpart (flows and guards use + - * "
                    "/ and whole powers)");
      if (name == "true")
        return r.b.boolLit(true);
      if (name == "false")
        return r.b.boolLit(false);
      bool isPrimed = pos < s.size() && s[pos] == '\'';
      if (isPrimed)
        ++pos;
      auto it = bind.find(name);
      if (it == bind.end())
        return fail("'" + name + "' is not a param of this component");
      if (it->second.value) {
        if (isPrimed)
          return fail("constant '" + name + "' cannot be primed");
        return r.b.realLit(*it->second.value);
      }
      std::string flat = r.real(it->second.name, where);
      if (isPrimed)
        primed = flat;
      return r.b.ref(r.d.save(flat));
    }
    return fail("unexpected '" + s.substr(pos, 1) + "'");
  }
};

} // namespace

std::string SpaceExReader::real(const std::string &flat, pugi::xml_node where) {
  (void)where;
  if (reals.insert(flat).second)
    realOrder.push_back(flat);
  return flat;
}

/// Splits a conjunction `a & b & c` at top-level '&' (not inside parens).
static std::vector<StringRef> conjuncts(StringRef text) {
  std::vector<StringRef> out;
  int depth = 0;
  size_t start = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '(')
      ++depth;
    else if (c == ')')
      --depth;
    else if (c == '&' && depth == 0) {
      out.push_back(text.slice(start, i).trim());
      if (i + 1 < text.size() && text[i + 1] == '&')
        ++i;
      start = i + 1;
    }
  }
  out.push_back(text.substr(start).trim());
  llvm::erase_if(out, [](StringRef s) { return s.empty(); });
  return out;
}

/// A chained comparison `a <= x <= b` (SpaceEx writes bounds so) as the
/// comparisons it chains, `a <= x` and `x <= b`; anything else as it is.
static std::vector<std::string> unchain(StringRef c) {
  std::vector<std::pair<size_t, size_t>> ops; // position, length
  int depth = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    char ch = c[i];
    if (ch == '(')
      ++depth;
    else if (ch == ')')
      --depth;
    else if (depth == 0 &&
             (ch == '<' || ch == '>' ||
              (ch == '=' && i + 1 < c.size() && c[i + 1] == '='))) {
      size_t len = i + 1 < c.size() && c[i + 1] == '=' ? 2 : 1;
      ops.push_back({i, len});
      i += len - 1;
    }
  }
  if (ops.size() < 2)
    return {c.str()};
  std::vector<std::string> out;
  size_t from = 0;
  for (size_t k = 0; k < ops.size(); ++k) {
    size_t end = k + 1 < ops.size() ? ops[k + 1].first : c.size();
    out.push_back(c.slice(from, end).trim().str());
    from = ops[k].first + ops[k].second;
  }
  return out;
}

bool SpaceExReader::conditions(pugi::xml_node node, const Bindings &bind,
                               const std::string &prefix,
                               std::vector<Expr *> &out) {
  for (StringRef chained : conjuncts(node.child_value()))
    for (const std::string &one : unchain(chained)) {
      StringRef c = ownedText.emplace_back(one);
      if (c == "true")
        continue;
      ExprParser ep{*this, c, 0, node, bind, prefix, true, {}};
      Expr *e = ep.orExpr();
      ep.skip();
      if (ep.ok && ep.pos != c.size())
        ep.fail("unexpected '" + c.substr(ep.pos) + "'");
      if (!ep.ok)
        return false;
      out.push_back(e);
    }
  return true;
}

bool SpaceExReader::instantiate(pugi::xml_node comp, const std::string &prefix,
                                const Bindings &bind, unsigned depth) {
  if (depth > 32)
    return error(comp, "components bind each other more than 32 levels deep");
  if (!comp.child("bind"))
    return instantiateBase(comp, prefix, bind);
  for (pugi::xml_node n : comp.children()) {
    StringRef tag = n.name();
    if (tag != "bind" && tag != "param" && tag != "note")
      return error(n,
                   "unsupported element <" + tag + "> in a network component");
  }
  for (pugi::xml_node bn : comp.children("bind")) {
    StringRef cid = bn.attribute("component").value();
    pugi::xml_node sub = component(cid);
    if (!sub)
      return error(bn, "no component '" + cid + "' to bind");
    std::string as = bn.attribute("as").value();
    if (as.empty())
      as = cid.str();
    std::string subPrefix = prefix.empty() ? as : prefix + "." + as;
    Bindings inner;
    for (pugi::xml_node p : sub.children("param")) {
      std::string name = p.attribute("name").value();
      bool local = StringRef(p.attribute("local").value()) == "true";
      Binding bd;
      bd.name = subPrefix + "." + name;
      if (!local) {
        pugi::xml_node mapped;
        for (pugi::xml_node mp : bn.children("map"))
          if (name == mp.attribute("key").value())
            mapped = mp;
        if (mapped) {
          StringRef v = StringRef(mapped.child_value()).trim();
          double num;
          if (!v.getAsDouble(num)) {
            bd.value = num;
          } else {
            auto it = bind.find(v.str());
            if (it != bind.end())
              bd = it->second;
            else
              bd.name = prefix.empty() ? v.str() : prefix + "." + v.str();
          }
        }
      }
      inner[name] = bd;
    }
    if (!instantiate(sub, subPrefix, inner, depth + 1))
      return false;
  }
  return true;
}

bool SpaceExReader::instantiateBase(pugi::xml_node comp,
                                    const std::string &prefix,
                                    const Bindings &bind) {
  unsigned inst = numInstances++;
  labelsOf.emplace_back();
  for (pugi::xml_node p : comp.children("param")) {
    std::string name = p.attribute("name").value();
    StringRef type = p.attribute("type").value();
    auto it = bind.find(name);
    if (type == "label") {
      labelsOf[inst].insert(it != bind.end() ? it->second.name
                                             : prefix + "." + name);
      continue;
    }
    if (type != "real")
      return error(p, "param type '" + type + "' is not supported");
    StringRef dyn = p.attribute("dynamics").value();
    if (dyn == "const" && (it == bind.end() || !it->second.value))
      return error(p, "constant '" + name + "' of component '" +
                          comp.attribute("id").value() +
                          "' is given no value (bind it to a number)");
  }
  for (pugi::xml_node n : comp.children()) {
    StringRef tag = n.name();
    if (tag != "param" && tag != "location" && tag != "transition" &&
        tag != "note")
      return error(n, "unsupported element <" + tag + "> in a component");
  }
  // Locations.
  std::map<std::string, uint32_t> placeOfId;
  std::set<std::string> flowVars; // the vars this component gives flows to
  struct PendingFlow {
    uint32_t place;
    std::vector<Flow::Equation> eqs;
    std::set<std::string> vars;
    pugi::xml_node node;
  };
  std::vector<PendingFlow> flows;
  bool first = true;
  for (pugi::xml_node loc : comp.children("location")) {
    std::string id = loc.attribute("id").value();
    std::string name = loc.attribute("name").value();
    if (name.empty())
      name = "loc" + id;
    std::string flat = prefix.empty() ? name : prefix + "." + name;
    if (mod->lookup(flat).kind != SymKind::None)
      return error(loc, "location name '" + name + "' is used twice");
    uint32_t pl = b.addPlace(d.save(flat), first ? 1 : 0, 1, xml.locOf(loc));
    first = false;
    placeOfId[id] = pl;
    // The invariant: a condition of the location (discretise bounds the
    // dwell time by it).
    std::vector<Expr *> invariant;
    if (!conditions(loc.child("invariant"), bind, prefix, invariant))
      return false;
    if (!invariant.empty())
      b.addInvariant(pl, invariant, xml.locOf(loc.child("invariant")));
    PendingFlow pf;
    pf.place = pl;
    pf.node = loc;
    for (StringRef c : conjuncts(loc.child_value("flow"))) {
      if (c == "true")
        continue;
      ExprParser ep{*this, c, 0, loc.child("flow"), bind, prefix, true, {}};
      Expr *e = ep.orExpr();
      ep.skip();
      if (!ep.ok)
        return false;
      auto *eq = llvm::dyn_cast<BinaryExpr>(e);
      auto *lhs = eq ? llvm::dyn_cast<Ref>(eq->lhs) : nullptr;
      if (ep.pos != c.size() || !eq || eq->op != BinaryOp::Eq || !lhs ||
          lhs->name != ep.primed)
        return error(loc.child("flow"),
                     "flow '" + c +
                         "' is not an equation x' == expression (SpaceEx "
                         "differential inclusions are not supported)");
      Flow::Equation fe;
      fe.var = lhs->name;
      fe.rate = eq->rhs;
      pf.eqs.push_back(fe);
      pf.vars.insert(lhs->name.str());
      flowVars.insert(lhs->name.str());
    }
    flows.push_back(std::move(pf));
  }
  if (placeOfId.empty())
    return error(comp, "component '" +
                           llvm::Twine(comp.attribute("id").value()) +
                           "' has no location");
  for (PendingFlow &pf : flows) {
    for (const std::string &v : flowVars)
      if (!pf.vars.count(v))
        return error(pf.node, "'" + v + "' has no flow in location '" +
                                  pf.node.attribute("name").value() +
                                  "' (SpaceEx leaves it free there; netlift "
                                  "would hold it constant)");
    if (!pf.eqs.empty())
      b.addFlow(pf.place, pf.eqs);
  }
  // Transitions.
  for (pugi::xml_node t : comp.children("transition")) {
    ProtoTransition pt;
    pt.node = t;
    pt.instance = inst;
    auto s = placeOfId.find(t.attribute("source").value());
    auto g = placeOfId.find(t.attribute("target").value());
    if (s == placeOfId.end() || g == placeOfId.end())
      return error(t, "transition between unknown locations");
    pt.from = s->second;
    pt.to = g->second;
    StringRef label = StringRef(t.child_value("label")).trim();
    if (!label.empty()) {
      auto it = bind.find(label.str());
      pt.label =
          it != bind.end() ? it->second.name : prefix + "." + label.str();
      labelsOf[inst].insert(pt.label);
    }
    if (!conditions(t.child("guard"), bind, prefix, pt.guards))
      return false;
    for (StringRef c : conjuncts(t.child_value("assignment"))) {
      // `x' == e`, `x' = e` or `x := e`.
      auto [lhsText, rhsText] = c.split(":=");
      bool assign = c.contains(":=");
      ExprParser ep{*this, assign ? lhsText : c,
                    0,     t.child("assignment"),
                    bind,  prefix,
                    true,  {}};
      Expr *e = ep.orExpr();
      if (!ep.ok)
        return false;
      Ref *target = nullptr;
      Expr *value = nullptr;
      if (assign) {
        target = llvm::dyn_cast<Ref>(e);
        ExprParser rp{*this, rhsText, 0,    t.child("assignment"),
                      bind,  prefix,  true, {}};
        value = rp.orExpr();
        if (!rp.ok)
          return false;
      } else if (auto *eq = llvm::dyn_cast<BinaryExpr>(e);
                 eq && eq->op == BinaryOp::Eq && !ep.primed.empty()) {
        target = llvm::dyn_cast<Ref>(eq->lhs);
        value = eq->rhs;
      }
      if (!target || !value)
        return error(t.child("assignment"),
                     "assignment '" + c +
                         "' is not x' == expression or x := expression "
                         "(nondeterministic resets are not supported)");
      pt.resets.push_back(b.assign(target, value));
    }
    protos.push_back(std::move(pt));
  }
  return true;
}

bool SpaceExReader::run() {
  pugi::xml_document doc;
  if (!xml.parse(doc, diag))
    return false;
  root = doc.child("sspaceex");
  if (!root)
    return error(doc.first_child(),
                 "not a SpaceEx file: the root element is <" +
                     llvm::Twine(doc.first_child().name()) +
                     ">, expected <sspaceex>");
  pugi::xml_node top;
  const std::string &want = wantedTop;
  for (pugi::xml_node c : root.children("component"))
    if (want.empty() || want == c.attribute("id").value())
      top = c;
  if (!top)
    return error(root, want.empty() ? llvm::Twine("no component")
                                    : "no component '" + want + "'");
  for (pugi::xml_node n : root.children())
    if (StringRef(n.name()) != "component")
      return error(n, "unsupported element <" + llvm::Twine(n.name()) +
                          "> in <sspaceex>");
  std::string modName = toIdentifier(top.attribute("id").value());
  mod = b.createModule(d.save(modName), false, xml.locOf(top));
  if (!mod)
    return error(top, "a module named '" + modName + "' exists");
  Bindings bind;
  for (pugi::xml_node p : top.children("param"))
    bind[p.attribute("name").value()] =
        Binding{p.attribute("name").value(), std::nullopt};
  if (!instantiate(top, "", bind, 0))
    return false;
  // Variables: declared before their use is resolved by the verifier.
  for (const std::string &v : realOrder)
    b.addVar(d.save(v), d.types.getReal(-INFINITY, INFINITY), b.realLit(0));
  // Transitions: unlabelled ones alone, labelled ones synchronised.
  std::map<std::string, std::vector<std::vector<const ProtoTransition *>>>
      byLabel;
  unsigned counter = 0;
  auto emit = [&](llvm::ArrayRef<const ProtoTransition *> parts,
                  StringRef label) {
    std::vector<PreArc> pre;
    std::vector<PostArc> post;
    std::vector<Expr *> guards;
    std::vector<Stmt *> resets;
    for (const ProtoTransition *p : parts) {
      pre.push_back({p->from, 1, {}});
      post.push_back({p->to});
      guards.insert(guards.end(), p->guards.begin(), p->guards.end());
      resets.insert(resets.end(), p->resets.begin(), p->resets.end());
    }
    std::string name = toIdentifier((label.empty() ? "t" : label.str() + "_") +
                                        std::to_string(counter++),
                                    /*keepDots=*/true);
    uint32_t t = b.addTransition(d.save(name), pre, post,
                                 xml.locOf(parts.front()->node));
    Expr *g = nullptr;
    for (Expr *e : guards)
      g = g ? b.binary(BinaryOp::And, g, e) : e;
    if (g)
      b.setGuard(t, g);
    if (!resets.empty())
      b.setAction(t, resets);
  };
  for (const ProtoTransition &p : protos)
    if (p.label.empty())
      emit({&p}, "");
  std::set<std::string> labels;
  for (const ProtoTransition &p : protos)
    if (!p.label.empty())
      labels.insert(p.label);
  for (const std::string &l : labels) {
    // Per instance that knows the label, its transitions on it.
    std::vector<std::vector<const ProtoTransition *>> sets;
    for (unsigned i = 0; i < numInstances; ++i) {
      if (!labelsOf[i].count(l))
        continue;
      std::vector<const ProtoTransition *> mine;
      for (const ProtoTransition &p : protos)
        if (p.instance == i && p.label == l)
          mine.push_back(&p);
      sets.push_back(std::move(mine));
    }
    std::vector<const ProtoTransition *> pick(sets.size());
    std::function<void(size_t)> product = [&](size_t k) {
      if (k == sets.size()) {
        emit(pick, l);
        return;
      }
      for (const ProtoTransition *p : sets[k]) {
        pick[k] = p;
        product(k + 1);
      }
    };
    size_t combos = 1;
    for (auto &s : sets)
      combos *= std::max<size_t>(s.size(), 1);
    if (combos > 100000)
      return error(top, "label '" + l + "' synchronises " +
                            std::to_string(combos) +
                            " combinations of transitions");
    product(0);
  }
  return true;
}

bool netlift::loadSpaceEx(FrontendContext &ctx, unsigned bufferID,
                          DiagEngine &diag, Design &design) {
  return SpaceExReader(bufferID, diag, design, ctx.options.top).run();
}
