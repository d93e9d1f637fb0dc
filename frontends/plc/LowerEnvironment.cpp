//===- LowerEnvironment.cpp - what the translated POU's caller chooses ----===//
//
// A function block translated as the top (`--top FB`) runs as a program
// does, once per scan, and its caller becomes the environment. NetIR's
// input ports carry scalars and strings, so what the caller passes whole —
// an array or structure input, a VAR_IN_OUT (the caller's variable, which
// the caller may change between two calls) — is chosen scalar by scalar:
// one free input port per scalar, copied into the variable at the start of
// every scan. A VAR_IN_OUT is also an output port, so what the block leaves
// in the caller's variable is observable. Choosing every value afresh each
// scan covers whatever the caller does between calls, the value it left
// unchanged included; it is the sound side of not knowing the caller.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/Lowering.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plc::detail;

/// The most scalars netlift gives free input ports for one value: past it,
/// a translation would be made of ports, and an exploration could not
/// choose them anyway.
static constexpr size_t kMaxEnvironmentScalars = 4096;

void Lowering::addFreeInputPort(const std::string &port, const PType *t,
                                const std::string &shown, SMLoc at) {
  if (t->kind == PTypeKind::Bool) {
    b.addPort(port, net::PortKind::Cond, net::PortDir::In, nullptr, at);
    return;
  }
  const net::Type *nt = netType(t, at, "input " + shown);
  // A free value of its full type: an exploration asks for a range where
  // it must enumerate one (ExplorationSetup).
  if ((t->kind == PTypeKind::Int && !t->isSubrange) ||
      t->kind == PTypeKind::Time || t->kind == PTypeKind::Date)
    b.addAttribute(port, net::kNeedsRangeAttribute,
                   design.save(shown + " : " + t->str()), at);
  b.addPort(port, net::PortKind::Data, net::PortDir::In, nt, at);
}

void Lowering::declareEnvironmentValue(VarDecl *v, const std::string &name) {
  const PType *t = v->type;
  bool inOut = v->section == VarSection::InOut;
  std::string what =
      std::string(inOut ? "VAR_IN_OUT '" : "input '") + v->name + "'";
  // The scalars, each with the selectors that reach it from the variable
  // and the suffix its port is named by (`buf_0`, `s_a`, `m_1_m2`).
  struct Selector {
    std::string field; // else the index
    int64_t index = 0;
  };
  struct Scalar {
    std::vector<Selector> path;
    std::string suffix;
    const PType *type;
  };
  std::vector<Scalar> scalars;
  std::function<void(const PType *, Scalar &)> collect = [&](const PType *pt,
                                                             Scalar &at) {
    const PType *base = baseOf(pt);
    switch (base->kind) {
    case PTypeKind::Array:
      forEachIndex(base, [&](llvm::ArrayRef<int64_t> index) {
        Scalar inner = at;
        for (int64_t i : index)
          inner.path.push_back({"", i});
        inner.suffix = elementPath(inner.suffix, index);
        collect(base->elem, inner);
      });
      return;
    case PTypeKind::Struct:
      if (base->isUnion)
        break; // one scalar: its bytes (LowerUnions.cpp)
      for (VarDecl *fld : base->fields) {
        Scalar inner = at;
        inner.path.push_back({sanitize(fld->name), 0});
        inner.suffix += "_" + sanitize(fld->name);
        collect(fld->type, inner);
      }
      return;
    case PTypeKind::FunctionBlock:
      refuse(v->loc, what + " is an instance of " + base->str() +
                         " that the caller owns: translate the caller, "
                         "which calls it");
    case PTypeKind::Reference:
      refuse(v->loc, what + " holds a reference (" + base->str() +
                         "): what it designates belongs to the caller; "
                         "translate the caller");
    default:
      break;
    }
    at.type = pt;
    scalars.push_back(at);
    if (scalars.size() > kMaxEnvironmentScalars)
      refuse(v->loc, what + " of type " + t->str() + " has more than " +
                         Twine(kMaxEnvironmentScalars) +
                         " scalars, each a free input of the model; "
                         "translate its caller");
  };
  Scalar whole;
  collect(t, whole);

  // The variable the body reads and writes: a VAR_IN_OUT's is an output
  // port (what the block leaves in the caller's variable); an input's is
  // a variable of the scan.
  varTypes[name] = t;
  if (inOut) {
    uint32_t p = t->kind == PTypeKind::Bool
                     ? b.addPort(name, net::PortKind::Cond, net::PortDir::Out,
                                 nullptr, v->loc)
                     : b.addPort(name, net::PortKind::Data, net::PortDir::Out,
                                 netType(t, v->loc, what), v->loc);
    mod->ports[p].init = defaultValue(t, v->loc);
  } else {
    declareTemp(name, t, v->loc);
  }
  // A port name the POU's own declarations do not use.
  auto freeName = [&](std::string n) {
    std::string candidate = n;
    for (unsigned i = 2; mod->lookup(candidate).kind != net::SymKind::None ||
                         (currentProgram && currentProgram->find(candidate));
         ++i)
      candidate = n + "_" + std::to_string(i);
    return candidate;
  };
  std::vector<NStmt *> &samples = environmentSamples[v];
  for (Scalar &s : scalars) {
    std::string port = freeName(name + (inOut ? "_in" : "") + s.suffix);
    addFreeInputPort(port, s.type, v->name + s.suffix, v->loc);
    auto scalar = [&] {
      NExpr *x = b.ref(name, v->loc);
      for (Selector &step : s.path)
        x = step.field.empty()
                ? b.index(x, b.intLit(step.index, v->loc), v->loc)
                : b.field(x, step.field, v->loc);
      return x;
    };
    samples.push_back(b.assign(scalar(), b.ref(port, v->loc), v->loc));
    if (!inOut)
      environmentResets[v].push_back(
          b.assign(scalar(), defaultValue(s.type, v->loc), v->loc));
  }
}

bool Lowering::isEnvironmentValue(VarDecl *v) const {
  if (!v->owner || !runAsProgram(v->owner) || !v->type)
    return false;
  if (v->section == VarSection::InOut)
    return true;
  const PType *t = baseOf(v->type);
  return v->section == VarSection::Input &&
         (t->kind == PTypeKind::Array ||
          (t->kind == PTypeKind::Struct && !t->isUnion));
}

NExpr *Lowering::clockReading(Expr *call) {
  std::string fn = StringRef(call->name).upper();
  if (opts.opaqueRefused)
    refuse(call->loc, fn + "() reads the PLC's clock, which netlift does not "
                           "model (--opaque=refuse; the default models it as "
                           "environment)");
  // One reading per scan: a scan is one step, and the clock's millisecond
  // (TIME) does not move within one on the PLCs netlift knows of.
  std::string port = "_" + StringRef(fn).lower() + "_now";
  if (mod->lookup(port).kind == net::SymKind::None) {
    addFreeInputPort(port, elementaryType(fn), fn + "()", call->loc);
    diag.note(call->loc,
              fn +
                  "() reads the PLC's clock: modelled as environment, the "
                  "free input '" +
                  port +
                  "' read once per scan (any value: the model does not "
                  "know that the clock advances)");
  }
  return b.ref(port, call->loc);
}
