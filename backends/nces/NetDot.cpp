//===- NetDot.cpp - drawing a net with Graphviz ---------------------------===//
#include "backends/nces/NetDot.h"

#include "ir/net/Printer.h"

#include "llvm/ADT/DenseSet.h"

using namespace netlift;
using namespace netlift::net;
using llvm::raw_ostream;
using llvm::StringRef;

static std::string quote(StringRef s) {
  std::string out = "\"";
  // Labels use "\n" line breaks on purpose, so only quotes are escaped;
  // NetIR names never contain a backslash.
  for (char c : s) {
    if (c == '"')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

/// Collects the places and cond ports an expression reads, for drawing
/// condition arcs from them.
static void signalSources(const Expr *e, llvm::SmallVectorImpl<Symbol> &out) {
  switch (e->getKind()) {
  case ExprKind::Ref: {
    auto *r = llvm::cast<Ref>(e);
    if (r->sym.kind == SymKind::Place || r->sym.kind == SymKind::Port)
      out.push_back(r->sym);
    return;
  }
  case ExprKind::Unary:
    return signalSources(llvm::cast<UnaryExpr>(e)->operand, out);
  case ExprKind::Binary:
    signalSources(llvm::cast<BinaryExpr>(e)->lhs, out);
    return signalSources(llvm::cast<BinaryExpr>(e)->rhs, out);
  case ExprKind::Cond: {
    auto *c = llvm::cast<CondExpr>(e);
    signalSources(c->cond, out);
    signalSources(c->thenExpr, out);
    return signalSources(c->elseExpr, out);
  }
  default:
    return;
  }
}

/// A controller translated from SFC keeps its chart in pragmas of its step
/// and transition variables (frontends/plc/SfcExpansion.cpp); it is drawn
/// as the chart, steps as places and transitions as bars, beside the net
/// the chart became (one scan transition).
static void writeSfcCharts(const Module &m, StringRef pre, raw_ostream &os) {
  constexpr StringRef kStep = "netlift sfc_step",
                      kTrans = "netlift sfc_transition ";
  std::vector<std::pair<std::string, bool>> steps; // scope, initial
  std::vector<std::pair<std::string, std::string>> transitions; // prefix, text
  for (const Attribute &a : m.attributes) {
    if (a.key != "pragma")
      continue;
    StringRef v = a.value;
    if (v.startswith(kTrans)) {
      size_t dot = a.target.rfind('.');
      std::string prefix =
          dot == StringRef::npos ? "" : a.target.substr(0, dot + 1).str();
      transitions.push_back({prefix, v.drop_front(kTrans.size()).str()});
    } else if (v == kStep || v == "netlift sfc_step initial") {
      steps.push_back({a.target.str(), v.endswith("initial")});
    }
  }
  if (steps.empty())
    return;
  auto node = [&](StringRef scope) {
    return quote(pre.str() + "sfc_" + scope.str());
  };
  os << "    subgraph " << quote("cluster_" + pre.str() + "sfc")
     << " {\n      label=\"SFC\";\n";
  for (auto &[scope, initial] : steps)
    os << "      " << node(scope)
       << " [shape=circle, label=" << quote(scope + (initial ? "\\n*" : ""))
       << (initial ? ", peripheries=2" : "") << "];\n";
  for (size_t i = 0; i < transitions.size(); ++i) {
    auto &[prefix, text] = transitions[i];
    StringRef rest = text;
    auto [arcs, cond] = rest.split(" : ");
    auto [from, to] = arcs.split(" -> ");
    std::string bar = pre.str() + "sfc_t" + std::to_string(i);
    os << "      " << quote(bar)
       << " [shape=box, style=filled, fillcolor=black, height=0.05, "
          "width=0.5, label=\"\", xlabel="
       << quote(cond) << "];\n";
    llvm::SmallVector<StringRef, 4> names;
    from.split(names, ',');
    for (StringRef s : names)
      os << "      " << node(prefix + s.str()) << " -> " << quote(bar) << ";\n";
    names.clear();
    to.split(names, ',');
    for (StringRef s : names)
      os << "      " << quote(bar) << " -> " << node(prefix + s.str()) << ";\n";
  }
  os << "    }\n";
}

static void writeModule(const Module &m, unsigned idx, raw_ostream &os) {
  std::string pre = "m" + std::to_string(idx) + "_";
  auto id = [&](StringRef kind, uint32_t i) {
    return quote(pre + kind.str() + std::to_string(i));
  };
  os << "  subgraph " << quote("cluster_" + m.name.str()) << " {\n";
  os << "    label="
     << quote((m.isSystem ? "system " : "module ") + m.name.str()) << ";\n";
  for (uint32_t i = 0; i < m.ports.size(); ++i) {
    const Port &p = m.ports[i];
    StringRef shape = p.kind == PortKind::Event  ? "cds"
                      : p.kind == PortKind::Cond ? "house"
                                                 : "parallelogram";
    os << "    " << id("port", i) << " [shape=" << shape << ", label="
       << quote(spelling(p.kind).str() + (p.isInput() ? " in " : " out ") +
                p.name.str())
       << "];\n";
  }
  for (uint32_t i = 0; i < m.places.size(); ++i) {
    const Place &p = m.places[i];
    std::string label = p.name.str();
    if (p.tokens)
      label += "\\n" + std::string(p.tokens <= 3 ? p.tokens : 1, '*');
    if (p.tokens > 3)
      label += std::to_string(p.tokens);
    os << "    " << id("p", i) << " [shape=circle, label=" << quote(label)
       << "];\n";
  }
  for (uint32_t i = 0; i < m.transitions.size(); ++i) {
    const Transition &t = m.transitions[i];
    std::string label = t.name.str();
    if (Expr *g = t.guard())
      label += "\\n[" + exprToString(g) + "]";
    if (t.hasAction())
      label += "\\n{...}";
    os << "    " << id("t", i)
       << " [shape=box, height=0.2, label=" << quote(label)
       << (t.urgent ? ", penwidth=3" : "") << "];\n";
  }
  for (uint32_t i = 0; i < m.instances.size(); ++i)
    os << "    " << id("inst", i) << " [shape=component, label="
       << quote(m.instances[i].name.str() + " : " +
                m.instances[i].moduleName.str())
       << "];\n";
  writeSfcCharts(m, pre, os);
  os << "  }\n";

  // Flow arcs: solid; weight and time interval as the label.
  for (uint32_t i = 0; i < m.transitions.size(); ++i) {
    const Transition &t = m.transitions[i];
    for (const PreArc &a : t.pre()) {
      std::string label;
      if (a.weight != 1)
        label += std::to_string(a.weight);
      if (!a.time.isTrivial())
        label += "[" + std::to_string(a.time.lo) + "," +
                 (a.time.hi == kInf ? std::string("inf")
                                    : std::to_string(a.time.hi)) +
                 "]";
      os << "  " << id("p", a.place) << " -> " << id("t", i);
      if (!label.empty())
        os << " [label=" << quote(label) << "]";
      os << ";\n";
    }
    for (const PostArc &a : t.post()) {
      os << "  " << id("t", i) << " -> " << id("p", a.place);
      if (a.weight != 1)
        os << " [label=" << quote(std::to_string(a.weight)) << "]";
      os << ";\n";
    }
    // Condition arcs: dashed, dot head.
    llvm::SmallVector<Symbol, 4> srcs;
    for (const Expr *c : t.conds())
      signalSources(c, srcs);
    llvm::DenseSet<uint64_t> drawn;
    for (Symbol s : srcs) {
      if (!drawn.insert((uint64_t(s.kind) << 32) | s.index).second)
        continue;
      os << "  " << id(s.kind == SymKind::Place ? "p" : "port", s.index)
         << " -> " << id("t", i)
         << " [style=dashed, arrowhead=dot, color=blue];\n";
    }
    // Event arcs: dotted, open head.
    for (const EventSource &s : t.events())
      os << "  " << id(s.fromPort ? "port" : "t", s.index) << " -> "
         << id("t", i) << " [style=dotted, arrowhead=onormal, color=red];\n";
    for (uint32_t p : t.emits())
      os << "  " << id("t", i) << " -> " << id("port", p)
         << " [style=dotted, arrowhead=onormal, color=red];\n";
  }
  // Defined outputs read places and inputs: dashed like condition arcs.
  for (uint32_t i = 0; i < m.ports.size(); ++i) {
    const Port &p = m.ports[i];
    if (!p.definition)
      continue;
    llvm::SmallVector<Symbol, 4> srcs;
    signalSources(p.definition, srcs);
    for (Symbol s : srcs)
      os << "  " << id(s.kind == SymKind::Place ? "p" : "port", s.index)
         << " -> " << id("port", i)
         << " [style=dashed, arrowhead=dot, color=blue];\n";
  }
  for (const Connection &c : m.connections) {
    auto end = [&](const Endpoint &e) {
      if (e.instance.empty())
        return id("port", m.findPort(e.port));
      return id("inst", m.lookup(e.instance).index);
    };
    os << "  " << end(c.from) << " -> " << end(c.to) << " [label="
       << quote((c.from.instance.empty() ? "" : c.from.port.str()) + "->" +
                (c.to.instance.empty() ? "" : c.to.port.str()))
       << ", color=gray40];\n";
  }
}

void netlift::writeDot(const Design &d, raw_ostream &os) {
  os << "digraph netlift {\n  rankdir=LR;\n  node [fontname=Helvetica];\n"
        "  edge [fontname=Helvetica, fontsize=10];\n";
  for (unsigned i = 0; i < d.modules.size(); ++i)
    writeModule(*d.modules[i], i, os);
  os << "}\n";
}
