//===- SpaceExReader.cpp - SpaceEx hybrid automata XML to NetIR -----------===//
//
// Reads SpaceEx's `sspaceex` XML (HyST, ARCH-COMP; FORMATS.md): base
// components (params, locations with flow and invariant, transitions with
// label, guard and assignment) and network components (binds with param
// maps). The system (`--top NAME`, else the last component) is flattened
// into one NetIR module:
//   - each location of each bound instance is a place `inst.loc`, the
//     first location of each instance marked;
//   - real params become `real` variables (unbounded range), constant
//     params are replaced by the values bound to them;
//   - the configuration (`model.cfg` beside the model, or --cfg) names the
//     system and gives the initial set: initial locations, values of
//     constants, initial values or intervals of variables (a variable it
//     leaves free starts anywhere); without one, variables start at 0;
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
#include "frontends/hybrid/SpaceExConfig.h"
#include "frontends/hybrid/SpaceExText.h"

#include "ir/net/Builder.h"
#include "ir/net/Clone.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"
#include "ir/net/Walk.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

#include <cmath>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <set>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::spaceex;
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
  /// `cfg`: the configuration read with the model, or null.
  SpaceExReader(unsigned bufferID, DiagEngine &diag, Design &design,
                StringRef top, Config *cfg, llvm::ArrayRef<RangeLine> ranges)
      : diag(diag), d(design), b(design),
        xml(diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer()),
        wantedTop(top.str()), cfg(cfg), ranges(ranges) {}
  bool run();
  /// Orders a transition's resets so that NetIR's statements in sequence
  /// do what SpaceEx's simultaneous assignment does.
  void simultaneousOrder(std::vector<Stmt *> &resets, pugi::xml_node at);
  /// Per variable, the real keeping its old value where resets read each
  /// other in a cycle.
  std::map<std::string, std::string> oldValueOf;

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
  /// --range and --ranges: bounds the user gives reals whose model leaves
  /// them open (SpaceEx declares no ranges; discretise needs finite ones).
  bool applyRanges();
  /// `var' in [-inf, inf]`: SpaceEx leaves the variable's rate free.
  Flow::Equation freeFlow(const std::string &var, llvm::SMLoc at);
  /// What a flow or an assignment says of each primed variable, in the
  /// order they are first named.
  struct PrimedBounds {
    struct Of {
      Expr *equal = nullptr, *lower = nullptr, *upper = nullptr;
      std::string text; // the first comparison naming it, for messages
    };
    std::map<std::string, Of> of;
    std::vector<std::string> order;
    /// `var`'s value (hi null) or interval [lo, hi]; false after an error.
    bool interval(SpaceExReader &r, pugi::xml_node node, const std::string &var,
                  llvm::StringRef what, const std::string &where, Expr *&lo,
                  Expr *&hi);
  };
  bool primedBound(pugi::xml_node node, llvm::StringRef c, const Bindings &bind,
                   const std::string &prefix, llvm::StringRef what,
                   PrimedBounds &acc);
  bool flowOf(pugi::xml_node loc, const Bindings &bind,
              const std::string &prefix, std::vector<Flow::Equation> &out);
  /// The configuration's initial set on the flat model: locations and
  /// variables' starts; every name it gives must be the system's.
  bool applyInitialSet(pugi::xml_node top);
  /// The forbidden set as a defined output `forbidden`, for `check`.
  bool addForbidden();
  /// The place of location `loc` of instance `inst` (`loc()` and the
  /// system's own name: its only instance); false after reporting at `at`.
  bool locationPlace(StringRef inst, StringRef loc, llvm::SMLoc at,
                     std::string &place, std::string *prefix = nullptr);
  pugi::xml_node topNode;

  // Expressions (SpaceEx math syntax) -------------------------------------
  struct ExprParser;
  Expr *parse(StringRef text, pugi::xml_node where, const Bindings &bind,
              const std::string &prefix, bool &ok);

  DiagEngine &diag;
  Design &d;
  Builder b;
  XmlBuffer xml;
  std::string wantedTop;
  Config *cfg;
  llvm::ArrayRef<RangeLine> ranges;
  pugi::xml_node root;
  Module *mod = nullptr;
  llvm::StringSet<> reals;
  /// Constants the initial set gives a range, not a value: reals that do
  /// not change.
  std::set<std::string> rangedConstants;
  /// Every flat name of a param (variables and constants; what the initial
  /// set may name) and its declaration in a base component if it has one,
  /// else in the system (for messages).
  std::map<std::string, pugi::xml_node> paramNode;
  /// Per instance (its prefix), its locations' places by name.
  std::map<std::string, std::vector<std::pair<std::string, uint32_t>>>
      locationsOf;
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
  /// The configuration's sets: `loc(inst) == name` is that location's
  /// place, and messages point into the configuration.
  bool inConfig = false;
  llvm::SMLoc configLoc = {};

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
    if (ok && inConfig)
      r.diag.error(configLoc, msg + " in '" + s.trim() + "'");
    else if (ok)
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
  /// The comparison operator at the current position, consumed.
  std::optional<BinaryOp> comparison() {
    static const std::pair<StringRef, BinaryOp> ops[] = {
        {"==", BinaryOp::Eq}, {"!=", BinaryOp::Ne}, {"<=", BinaryOp::Le},
        {">=", BinaryOp::Ge}, {"<", BinaryOp::Lt},  {">", BinaryOp::Gt},
        {"=", BinaryOp::Eq}};
    for (auto &[t, op] : ops)
      if (eat(t))
        return op;
    return std::nullopt;
  }
  Expr *cmpExpr() {
    Expr *a = addExpr();
    // A chain `a <= x <= b` is `a <= x & x <= b`; x is read again for the
    // second link, so that each comparison has its own operand.
    Expr *chain = nullptr;
    while (ok) {
      std::optional<BinaryOp> op = comparison();
      if (!op)
        break;
      skip();
      size_t start = pos;
      Expr *c = addExpr();
      if (!ok)
        return nullptr;
      Expr *cmp = r.b.binary(*op, a, c);
      chain = chain ? r.b.binary(BinaryOp::And, chain, cmp) : cmp;
      size_t end = pos;
      bool more = comparison().has_value();
      pos = more ? start : end;
      if (!more)
        break;
      a = addExpr();
      pos = end;
    }
    return ok ? (chain ? chain : a) : nullptr;
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
    Expr *exponent = unary();
    if (!ok)
      return nullptr;
    // A whole power stays a product, which keeps affine and polynomial
    // rates recognisable; any other is expt (C's pow).
    auto *lit = llvm::dyn_cast<net::RealLit>(exponent);
    if (!lit || lit->value != std::floor(lit->value) || lit->value < 1 ||
        lit->value > 16)
      return r.b.call(net::Builtin::Expt, {base, exponent});
    Expr *e = base;
    for (int i = 1; i < int(lit->value); ++i)
      e = r.b.binary(BinaryOp::Mul, e, base);
    return e;
  }
  /// `name(args)`: SpaceEx's mathematical functions as NetIR built-ins.
  Expr *function(StringRef name) {
    static const std::pair<const char *, net::Builtin> known[] = {
        {"sqrt", net::Builtin::Sqrt}, {"sin", net::Builtin::Sin},
        {"cos", net::Builtin::Cos},   {"tan", net::Builtin::Tan},
        {"asin", net::Builtin::Asin}, {"acos", net::Builtin::Acos},
        {"atan", net::Builtin::Atan}, {"exp", net::Builtin::Exp},
        {"ln", net::Builtin::Ln},     {"log", net::Builtin::Ln},
        {"abs", net::Builtin::Abs},   {"min", net::Builtin::Min},
        {"max", net::Builtin::Max},   {"pow", net::Builtin::Expt}};
    const auto *fn =
        llvm::find_if(known, [&](const auto &k) { return name == k.first; });
    if (fn == std::end(known))
      return fail("function '" + name +
                  "' is not one netlift knows (sqrt, sin, cos, tan, asin, "
                  "acos, atan, exp, ln, log (natural), abs, min, max, pow)");
    eat("(");
    std::vector<Expr *> args;
    if (!eat(")")) {
      do {
        args.push_back(addExpr());
        if (!ok)
          return nullptr;
      } while (eat(","));
      if (!eat(")"))
        return fail("expected ')' after the arguments of '" + name + "'");
    }
    if (args.size() != net::arity(fn->second))
      return fail("'" + name + "' takes " +
                  llvm::Twine(net::arity(fn->second)) + " argument" +
                  (net::arity(fn->second) == 1 ? "" : "s") + ", not " +
                  llvm::Twine(args.size()));
    return r.b.call(fn->second, args);
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
      if (name == "loc" && inConfig && eat("("))
        return location();
      if (pos < s.size() && s[pos] == '(')
        return function(name);
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
  /// After `loc(`: `inst) == name` as the place of that location.
  Expr *location() {
    size_t close = s.find(')', pos);
    if (close == StringRef::npos)
      return fail("expected ')'");
    StringRef inst = s.slice(pos, close).trim();
    pos = close + 1;
    if (!eat("==") && !eat("="))
      return fail("expected '==' after loc(" + inst + ")");
    skip();
    size_t start = pos;
    while (pos < s.size() && (isalnum((unsigned char)s[pos]) || s[pos] == '_'))
      ++pos;
    std::string place;
    if (!r.locationPlace(inst, s.slice(start, pos), configLoc, place)) {
      ok = false;
      return nullptr;
    }
    return r.b.ref(r.d.save(place));
  }
};

} // namespace

Flow::Equation SpaceExReader::freeFlow(const std::string &var, llvm::SMLoc at) {
  Flow::Equation fe;
  fe.loc = at;
  fe.var = d.save(var);
  fe.rate = b.realLit(-INFINITY, at);
  fe.rateHi = b.realLit(INFINITY, at);
  return fe;
}

std::string SpaceExReader::real(const std::string &flat, pugi::xml_node where) {
  (void)where;
  if (reals.insert(flat).second)
    realOrder.push_back(flat);
  return flat;
}

bool SpaceExReader::conditions(pugi::xml_node node, const Bindings &bind,
                               const std::string &prefix,
                               std::vector<Expr *> &out) {
  for (StringRef chained : conjuncts(node.child_value()))
    for (StringRef c : unchain(chained)) {
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

/// One comparison of a primed variable with an expression (`x' == e`,
/// `x' <= e`, `e <= x'`; a strict bound read as closed) added to what is
/// known of that variable's primed value; false after an error. `what`
/// names the part of the model for messages ("flow", "assignment").
bool SpaceExReader::primedBound(pugi::xml_node node, StringRef c,
                                const Bindings &bind, const std::string &prefix,
                                StringRef what, PrimedBounds &acc) {
  auto notOne = [&] {
    return error(node, what + " '" + c +
                           "' is not x' == expression or a bound of x' by an "
                           "expression (" +
                           (what == "flow"
                                ? "SpaceEx differential inclusions other than "
                                  "a <= x' <= b are not supported"
                                : "nondeterministic resets other than a <= "
                                  "x' <= b are not supported") +
                           ")");
  };
  // SpaceEx prints a flow plus a set (`... with offset
  // support_function(...)`) in the problems it flattens.
  if (c.contains("support_function("))
    return error(node, what + " '" + c +
                           "' adds a set given by its support function (a "
                           "differential inclusion netlift does not take; it "
                           "takes a <= x' <= b)");
  auto ops = comparisonOperators(c, /*singleEquals=*/true);
  if (ops.size() != 1)
    return notOne();
  StringRef opText = c.substr(ops[0].first, ops[0].second);
  if (opText == "=")
    opText = "==";
  StringRef sides[2] = {c.take_front(ops[0].first).trim(),
                        c.drop_front(ops[0].first + ops[0].second).trim()};
  Expr *parsed[2];
  std::string primed[2];
  for (int i = 0; i < 2; ++i) {
    ExprParser ep{*this, sides[i], 0, node, bind, prefix, true, {}};
    parsed[i] = ep.orExpr();
    ep.skip();
    if (ep.ok && ep.pos != sides[i].size())
      ep.fail("unexpected '" + sides[i].substr(ep.pos) + "'");
    if (!ep.ok)
      return false;
    primed[i] = ep.primed;
  }
  // The primed variable alone on one side, and no prime on the other.
  int side = -1;
  for (int i = 0; i < 2; ++i)
    if (auto *ref = llvm::dyn_cast<Ref>(parsed[i]); ref && !primed[i].empty() &&
                                                    ref->name == primed[i] &&
                                                    primed[1 - i].empty())
      side = i;
  if (side < 0 || opText == "!=")
    return notOne();
  std::string var = primed[side];
  PrimedBounds::Of &r = acc.of[var];
  if (r.text.empty()) {
    r.text = c.str();
    acc.order.push_back(var);
  }
  // `x' <= b` bounds from above; written `b >= x'` likewise.
  bool less = opText.startswith("<");
  Expr *&slot = opText == "=="          ? r.equal
                : (less == (side == 0)) ? r.upper
                                        : r.lower;
  if (slot)
    return error(node, what + " '" + c + "' gives " + var + "' a second " +
                           (opText == "=="      ? "value"
                            : &slot == &r.upper ? "upper bound"
                                                : "lower bound"));
  slot = parsed[1 - side];
  return true;
}

/// A location's flow: per variable an equation `x' == e`, or bounds of its
/// rate `a <= x' <= b` (also written `x' >= a & x' <= b`), which make a
/// rectangular flow `x' in [a, b]`.
bool SpaceExReader::flowOf(pugi::xml_node loc, const Bindings &bind,
                           const std::string &prefix,
                           std::vector<Flow::Equation> &out) {
  pugi::xml_node node = loc.child("flow");
  PrimedBounds acc;
  for (StringRef chained : conjuncts(node.child_value()))
    for (StringRef c : unchain(chained))
      if (c != "true" && !primedBound(node, c, bind, prefix, "flow", acc))
        return false;
  std::string where =
      "in location '" + std::string(loc.attribute("name").value()) + "'";
  for (const std::string &var : acc.order) {
    Flow::Equation fe;
    fe.loc = xml.locOf(node);
    fe.var = d.save(var);
    if (!acc.interval(*this, node, var, "flow", where, fe.rate, fe.rateHi))
      return false;
    out.push_back(fe);
  }
  return true;
}

bool SpaceExReader::PrimedBounds::interval(
    SpaceExReader &r, pugi::xml_node node, const std::string &var,
    StringRef what, const std::string &where, Expr *&lo, Expr *&hi) {
  Of &o = of[var];
  if (o.equal && (o.lower || o.upper))
    return r.error(node, what + " of '" + var + "' " + where +
                             " gives both a value and a bound of " + var +
                             "' ('" + o.text + "')");
  if (o.equal) {
    lo = o.equal;
    hi = nullptr;
    return true;
  }
  if (o.lower && o.upper) {
    lo = o.lower;
    hi = o.upper;
    return true;
  }
  // A reset bounded on one side (`y' >= 0`) leaves it any value past the
  // bound, and a rate so bounded (`x' >= 1`) any rate past it: an interval
  // open on the other side.
  if (o.lower || o.upper) {
    lo = o.lower ? o.lower : r.b.realLit(-INFINITY);
    hi = o.upper ? o.upper : r.b.realLit(INFINITY);
    return true;
  }
  return r.error(node, what + " of '" + var + "' " + where + " bounds " + var +
                           "' " + (o.lower ? "from below" : "from above") +
                           " only ('" + o.text +
                           "'): netlift takes an interval with both bounds, "
                           "a <= " +
                           var + "' <= b");
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
                                    const Bindings &given) {
  unsigned inst = numInstances++;
  labelsOf.emplace_back();
  Bindings bind = given;
  for (pugi::xml_node p : comp.children("param")) {
    std::string name = p.attribute("name").value();
    StringRef type = p.attribute("type").value();
    auto it = bind.find(name);
    if (it != bind.end() && type == "real") {
      paramNode.insert({it->second.name, p});
      // A constant the configuration's initial set fixes.
      if (!it->second.value && cfg &&
          StringRef(p.attribute("dynamics").value()) == "const")
        if (auto *bd = cfg->initial.lookup(it->second.name);
            bd && bd->lo && bd->hi && *bd->lo == *bd->hi)
          it->second.value = bd->lo;
    }
    if (type == "label") {
      labelsOf[inst].insert(it != bind.end() ? it->second.name
                                             : prefix + "." + name);
      continue;
    }
    if (type != "real")
      return error(p, "param type '" + type + "' is not supported");
    StringRef dyn = p.attribute("dynamics").value();
    // A constant the initial set gives a range: a real that starts
    // anywhere in it and never changes (no flow, no reset).
    if (dyn == "const" && it != bind.end() && !it->second.value && cfg &&
        cfg->initial.lookup(it->second.name)) {
      if (rangedConstants.insert(it->second.name).second)
        diag.note(xml.locOf(p),
                  "constant '" + it->second.name +
                      "' is given a range by the initial set: it is a real "
                      "that starts anywhere in it and does not change "
                      "(--param '" +
                      it->second.name + "=VALUE' fixes it)");
      continue;
    }
    if (dyn == "const" && (it == bind.end() || !it->second.value)) {
      std::string global = it != bind.end() ? it->second.name : name;
      return error(p, "constant '" + name + "' of component '" +
                          comp.attribute("id").value() +
                          "' is given no value (bind it to a number, give " +
                          "it a value in the initial set of the " +
                          "configuration, or " + "--param '" + global +
                          "=VALUE'" +
                          (cfg ? std::string(")")
                               : std::string("; no configuration was read: "
                                             "netlift reads the .cfg named "
                                             "like the model beside it, "
                                             "or --cfg FILE)")));
    }
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
    bool urgent = false;
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
    locationsOf[prefix].push_back({name, pl});
    placeOfId[id] = pl;
    // The invariant: a condition of the location (discretise bounds the
    // dwell time by it).
    std::vector<Expr *> invariant;
    if (!conditions(loc.child("invariant"), bind, prefix, invariant))
      return false;
    PendingFlow pf;
    pf.place = pl;
    pf.node = loc;
    // `flow false` (HyST's urgent locations): no time passes there, so its
    // variables need no flow; the location's invariant is `false`.
    if (StringRef(loc.child_value("flow")).trim() == "false") {
      pf.urgent = true;
      invariant.push_back(b.boolLit(false));
      b.addInvariant(pl, invariant, xml.locOf(loc.child("flow")));
      flows.push_back(std::move(pf));
      continue;
    }
    if (!invariant.empty())
      b.addInvariant(pl, invariant, xml.locOf(loc.child("invariant")));
    if (!flowOf(loc, bind, prefix, pf.eqs))
      return false;
    for (const Flow::Equation &fe : pf.eqs) {
      pf.vars.insert(fe.var.str());
      flowVars.insert(fe.var.str());
    }
    flows.push_back(std::move(pf));
  }
  if (placeOfId.empty())
    return error(comp, "component '" +
                           llvm::Twine(comp.attribute("id").value()) +
                           "' has no location");
  for (PendingFlow &pf : flows) {
    // A variable the component moves elsewhere changes freely here.
    for (const std::string &v : flowVars)
      if (!pf.urgent && !pf.vars.count(v))
        pf.eqs.push_back(freeFlow(v, xml.locOf(pf.node)));
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
    // `x := e`, `x' == e` (or `x' = e`), and `a <= x' <= b`: a reset to
    // any value in [a, b].
    pugi::xml_node assignment = t.child("assignment");
    PrimedBounds acc;
    for (StringRef c : conjuncts(assignment.child_value())) {
      if (c.contains(":=")) {
        auto [lhsText, rhsText] = c.split(":=");
        ExprParser ep{*this, lhsText, 0, assignment, bind, prefix, true, {}};
        auto *target = llvm::dyn_cast_or_null<Ref>(ep.orExpr());
        if (!ep.ok)
          return false;
        if (!target)
          return error(assignment,
                       "assignment '" + c + "' does not assign a variable");
        ExprParser rp{*this, rhsText, 0, assignment, bind, prefix, true, {}};
        Expr *value = rp.orExpr();
        if (!rp.ok)
          return false;
        PrimedBounds::Of &o = acc.of[target->name.str()];
        if (o.text.empty()) {
          o.text = c.str();
          acc.order.push_back(target->name.str());
        }
        if (o.equal)
          return error(assignment, "assignment '" + c + "' gives " +
                                       target->name + "' a second value");
        o.equal = value;
        continue;
      }
      for (StringRef one : unchain(c))
        if (!primedBound(assignment, one, bind, prefix, "assignment", acc))
          return false;
    }
    for (const std::string &var : acc.order) {
      Expr *lo = nullptr, *hi = nullptr;
      if (!acc.interval(*this, assignment, var, "assignment",
                        "on this transition", lo, hi))
        return false;
      Expr *value = hi ? b.call(Builtin::Between, {lo, hi}, lo->loc) : lo;
      pt.resets.push_back(b.assign(b.ref(d.save(var)), value));
    }
    protos.push_back(std::move(pt));
  }
  return true;
}

void SpaceExReader::simultaneousOrder(std::vector<Stmt *> &resets,
                                      pugi::xml_node at) {
  // SpaceEx assigns every variable at once, from the values before the
  // transition; NetIR runs an action's statements in order. A reset that
  // reads a variable another reset writes therefore goes first (`z' == x
  // & x' == 0`: z := x; x := 0). Resets reading each other in a cycle
  // (`x' == y & y' == x`) keep the old value of one in a real of its own,
  // assigned first and read in its place.
  size_t n = resets.size();
  auto assignOf = [&](size_t i) { return llvm::cast<AssignStmt>(resets[i]); };
  auto targetOf = [&](size_t i) {
    return llvm::cast<Ref>(assignOf(i)->target)->name;
  };
  auto readsName = [](const Expr *value, StringRef name) {
    bool found = false;
    walkExpr(value, [&](const Expr *e) {
      if (auto *r = llvm::dyn_cast<Ref>(e); r && r->name == name)
        found = true;
    });
    return found;
  };
  std::vector<Stmt *> ordered;
  std::vector<bool> placed(n);
  for (size_t done = 0; done < n;) {
    // The first reset, in the written order, that no unplaced reset reads.
    auto readByUnplaced = [&](size_t j) {
      for (size_t i = 0; i < n; ++i)
        if (i != j && !placed[i] && readsName(assignOf(i)->value, targetOf(j)))
          return true;
      return false;
    };
    size_t next = n;
    for (size_t j = 0; j < n && next == n; ++j)
      if (!placed[j] && !readByUnplaced(j))
        next = j;
    if (next < n) {
      placed[next] = true;
      ordered.push_back(resets[next]);
      ++done;
      continue;
    }
    // A cycle: the first unplaced reset's variable keeps its old value in
    // a real of its own, which the others read instead.
    size_t j = 0;
    while (placed[j])
      ++j;
    std::string target = targetOf(j).str();
    auto [it, fresh] = oldValueOf.try_emplace(target);
    if (fresh) {
      std::string name = target + "_old";
      while (mod->lookup(name).kind != SymKind::None)
        name += "_";
      it->second = name;
      b.addVar(d.save(name), d.types.getReal(-INFINITY, INFINITY), b.realLit(0),
               xml.locOf(at));
      diag.note(xml.locOf(at),
                "resets on this transition read each other's values before "
                "it (SpaceEx assigns them at once): the old value of '" +
                    target + "' is kept in a real '" + name +
                    "' of its own, assigned first");
    }
    StringRef old = d.save(it->second);
    ordered.push_back(b.assign(b.ref(old), b.ref(d.save(target))));
    for (size_t i = 0; i < n; ++i) {
      if (i == j || placed[i] || !readsName(assignOf(i)->value, target))
        continue;
      Expr *value = cloneExpr(b, *mod, assignOf(i)->value,
                              [](StringRef name) { return name.str(); });
      walkExpr(value, [&](const Expr *e) {
        if (auto *r = llvm::dyn_cast<Ref>(e); r && r->name == target)
          const_cast<Ref *>(r)->name = old;
      });
      resets[i] = b.assign(b.ref(targetOf(i)), value);
    }
  }
  resets = std::move(ordered);
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
  // The configuration names the system unless --top does.
  bool fromConfig = wantedTop.empty() && cfg && cfg->system;
  if (fromConfig)
    wantedTop = cfg->system->text.trim().trim('"').str();
  const std::string &want = wantedTop;
  for (pugi::xml_node c : root.children("component"))
    if (want.empty() || want == c.attribute("id").value())
      top = c;
  if (!top && fromConfig) {
    diag.error(cfg->system->loc, "system '" + want +
                                     "' of the configuration is not a "
                                     "component of the model");
    return false;
  }
  if (!top)
    return error(root, want.empty() ? llvm::Twine("no component")
                                    : "no component '" + want + "'");
  for (pugi::xml_node n : root.children())
    if (StringRef(n.name()) != "component")
      return error(n, "unsupported element <" + llvm::Twine(n.name()) +
                          "> in <sspaceex>");
  topNode = top;
  std::string modName = toIdentifier(top.attribute("id").value());
  mod = b.createModule(d.save(modName), false, xml.locOf(top));
  if (!mod)
    return error(top, "a module named '" + modName + "' exists");
  Bindings bind;
  for (pugi::xml_node p : top.children("param")) {
    std::string name = p.attribute("name").value();
    bind[name] = Binding{name, std::nullopt};
  }
  if (!instantiate(top, "", bind, 0))
    return false;
  for (pugi::xml_node p : top.children("param"))
    paramNode.insert({p.attribute("name").value(), p});
  // A variable no location gives a flow varies freely in SpaceEx (an input
  // or a disturbance, bounded by invariants); a NetIR real without a flow
  // stays constant, which would lose its behaviours.
  // Such a variable changes freely at all times: its flow is on a place
  // of its own, always marked.
  std::set<std::string> flowing;
  for (const Flow &f : mod->flows)
    for (const Flow::Equation &eq : f.equations)
      flowing.insert(eq.var.str());
  std::vector<Flow::Equation> free;
  for (const std::string &v : realOrder)
    if (!flowing.count(v) && !rangedConstants.count(v))
      free.push_back(
          freeFlow(v, xml.locOf(paramNode.count(v) ? paramNode[v] : top)));
  if (!free.empty()) {
    std::string name = "free";
    for (unsigned i = 1; mod->lookup(name).kind != SymKind::None; ++i)
      name = "free_" + std::to_string(i);
    uint32_t place = b.addPlace(d.save(name), 1, 1);
    b.addFlow(place, free);
    std::string names;
    for (const Flow::Equation &eq : free)
      names += (names.empty() ? "'" : ", '") + eq.var.str() + "'";
    diag.note(xml.locOf(top),
              "no location gives a flow to " + names + ": SpaceEx lets " +
                  (free.size() > 1 ? "them" : "it") +
                  " change freely (an input or a disturbance, bounded by "
                  "invariants), written `x' in [-inf, inf]` on the place '" +
                  name + "', always marked");
  }
  // Variables: declared before their use is resolved by the verifier.
  for (const std::string &v : realOrder)
    b.addVar(d.save(v), d.types.getReal(-INFINITY, INFINITY), b.realLit(0),
             paramNode.count(v) ? xml.locOf(paramNode[v]) : llvm::SMLoc());
  if (!applyRanges() || (cfg && !applyInitialSet(top)))
    return false;
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
    if (!resets.empty()) {
      simultaneousOrder(resets, parts.front()->node);
      b.setAction(t, resets);
    }
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

bool SpaceExReader::locationPlace(StringRef inst, StringRef loc, llvm::SMLoc at,
                                  std::string &place, std::string *prefix) {
  auto it = locationsOf.find(inst.str());
  if (it == locationsOf.end() && locationsOf.size() == 1 &&
      (inst.empty() || inst == topNode.attribute("id").value()))
    it = locationsOf.begin();
  if (it == locationsOf.end()) {
    diag.error(at, "no instance '" + inst + "' in the system");
    return false;
  }
  for (auto &[name, pl] : it->second)
    if (name == loc) {
      place = mod->places[pl].name.str();
      if (prefix)
        *prefix = it->first;
      return true;
    }
  diag.error(at, "instance '" + inst + "' has no location '" + loc + "'");
  return false;
}

bool SpaceExReader::addForbidden() {
  StringRef text = cfg->forbidden->text.trim();
  if (text.empty())
    return true;
  // Flat names, and a local's own name where only one local has it.
  Bindings flat;
  std::map<std::string, unsigned> shortUses;
  for (const std::string &v : realOrder)
    for (size_t dot = v.find('.'); dot != std::string::npos;
         dot = v.find('.', dot + 1))
      ++shortUses[v.substr(dot + 1)];
  for (const std::string &v : realOrder) {
    flat[v] = Binding{v, std::nullopt};
    for (size_t dot = v.find('.'); dot != std::string::npos;
         dot = v.find('.', dot + 1))
      if (shortUses[v.substr(dot + 1)] == 1 && !flat.count(v.substr(dot + 1)))
        flat[v.substr(dot + 1)] = Binding{v, std::nullopt};
  }
  // The system's constants the initial set (or --param) fixes.
  for (pugi::xml_node p : topNode.children("param"))
    if (StringRef(p.attribute("dynamics").value()) == "const")
      if (auto *bd = cfg->initial.lookup(p.attribute("name").value());
          bd && bd->lo && bd->hi && *bd->lo == *bd->hi &&
          !rangedConstants.count(p.attribute("name").value()))
        flat[p.attribute("name").value()] =
            Binding{p.attribute("name").value(), bd->lo};
  ExprParser ep{*this, text, 0, topNode, flat, "", true, {}};
  ep.inConfig = true;
  ep.configLoc = cfg->forbidden->loc;
  Expr *e = ep.orExpr();
  ep.skip();
  if (ep.ok && ep.pos != text.size())
    ep.fail("unexpected '" + text.substr(ep.pos) + "'");
  if (!ep.ok)
    return false;
  std::string name = "forbidden";
  if (mod->lookup(name).kind != SymKind::None)
    name = "cfg_forbidden";
  uint32_t port = b.addPort(d.save(name), PortKind::Cond, PortDir::Out,
                            d.types.getBool(), cfg->forbidden->loc);
  mod->ports[port].definition = e;
  mod->ports[port].definitionLoc = cfg->forbidden->loc;
  return true;
}

bool SpaceExReader::applyRanges() {
  for (const RangeLine &r : ranges) {
    net::Symbol s = mod->lookup(r.name);
    if (s.kind != SymKind::Var || !mod->vars[s.index].type->isReal()) {
      std::vector<std::string> reals;
      for (const Var &v : mod->vars)
        if (v.type->isReal())
          reals.push_back(v.name.str());
      diag.error(r.loc, "--range: '" + r.name +
                            "' names no real variable of the model" +
                            didYouMean(r.name, reals));
      return false;
    }
    double lo, hi;
    if (r.notNull || r.lo.getAsDouble(lo) || r.hi.getAsDouble(hi) ||
        !std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
      diag.error(r.loc, "the range of '" + r.name +
                            "' is not LO..HI with numbers LO < HI");
      return false;
    }
    mod->vars[s.index].type = d.types.getReal(lo, hi);
  }
  return true;
}

bool SpaceExReader::applyInitialSet(pugi::xml_node top) {
  InitialSet &init = cfg->initial;
  // Locations.
  std::map<std::string, std::string> chosen;
  for (const InitialSet::Location &l : init.locations) {
    std::string place, prefix;
    if (!locationPlace(l.instance, l.location, l.loc, place, &prefix))
      return false;
    auto [prev, fresh] = chosen.insert({prefix, l.location});
    if (!fresh && prev->second != l.location) {
      diag.error(l.loc,
                 "a second initial location for instance '" + l.instance + "'");
      return false;
    }
    for (auto &[name, pl] : locationsOf[prefix])
      mod->places[pl].tokens = name == l.location;
  }
  // Variables: the value or interval the set gives; free if none (when
  // there is a set: --param alone fixes only what it names).
  std::map<std::string, std::string> varOfKey;
  for (Var &v : mod->vars) {
    std::string key;
    InitialSet::Bounds *found = init.lookup(v.name, &key);
    if (!found && !cfg->initially)
      continue;
    if (!found) {
      v.init = b.realLit(-INFINITY);
      v.initHi = b.realLit(INFINITY);
      continue;
    }
    InitialSet::Bounds &bd = *found;
    auto [other, fresh] = varOfKey.insert({key, v.name.str()});
    if (!fresh) {
      diag.error(bd.loc, "'" + key + "' in the initial set may be '" +
                             other->second + "' or '" + v.name +
                             "'; name it with its instance");
      return false;
    }
    if (!bd.lo || !bd.hi) {
      diag.error(bd.loc, "the initial set bounds '" + v.name + "' only " +
                             (bd.lo ? "from below" : "from above") +
                             "; it must give both bounds or a value");
      return false;
    }
    v.init = b.realLit(*bd.lo);
    if (*bd.hi != *bd.lo)
      v.initHi = b.realLit(*bd.hi);
  }
  for (auto &[name, bd] : init.bounds)
    if (!llvm::any_of(paramNode, [&, &name = name](const auto &p) {
          return namedBy(p.first, name);
        })) {
      diag.error(bd.loc, "'" + name +
                             "' in the initial set is not a "
                             "variable or constant of system '" +
                             top.attribute("id").value() + "'");
      return false;
    }
  // What the user plots is observed even where the model reads it not:
  // discretise keeps those reals.
  if (cfg->outputVariables) {
    llvm::SmallVector<StringRef, 4> names;
    cfg->outputVariables->text.split(names, ',', -1, false);
    for (StringRef name : names) {
      name = name.trim();
      net::Symbol s = mod->lookup(name);
      if (s.kind == net::SymKind::Var && mod->vars[s.index].type->isReal())
        b.addAttribute(d.save(name), net::kObservedAttribute,
                       "output-variables", cfg->outputVariables->loc);
    }
  }
  return !cfg->forbidden || addForbidden();
}

/// The configuration that goes with a model: --cfg, else the file beside
/// it with the same name and `.cfg`.
static bool findConfig(FrontendContext &ctx, unsigned bufferID,
                       DiagEngine &diag, std::optional<Config> &cfg) {
  std::string path = ctx.options.spaceexConfig;
  if (path == "none")
    path.clear();
  else if (path.empty()) {
    llvm::SmallString<256> beside(
        diag.sourceMgr().getMemoryBuffer(bufferID)->getBufferIdentifier());
    llvm::sys::path::replace_extension(beside, "cfg");
    if (llvm::sys::fs::exists(beside)) {
      path = beside.str().str();
      diag.note(llvm::SMLoc(), "reading the SpaceEx configuration " + path +
                                   " (system and initial set; --cfg none reads "
                                   "none)");
    }
  }
  if (path.empty() && ctx.options.params.empty())
    return true;
  cfg.emplace();
  if (!path.empty() && !readConfig(path, diag, *cfg))
    return false;
  return addParams(ctx.options.params, diag, cfg->initial);
}

bool netlift::loadSpaceEx(FrontendContext &ctx, unsigned bufferID,
                          DiagEngine &diag, Design &design) {
  std::optional<Config> cfg;
  std::vector<RangeLine> ranges;
  if (!findConfig(ctx, bufferID, diag, cfg) ||
      !readRangeLines(ctx.options, diag, ranges))
    return false;
  return SpaceExReader(bufferID, diag, design, ctx.options.top,
                       cfg ? &*cfg : nullptr, ranges)
      .run();
}
