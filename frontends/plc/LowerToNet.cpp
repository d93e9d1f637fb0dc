//===- LowerToNet.cpp - a checked PLC program as a NetIR controller -------===//
//
// How the scan body is built:
//  - Every variable of the program, and every member of every FB instance
//    (recursively, named `inst.member`), is a NetIR variable or port.
//  - An FB call assigns the instance's inputs, runs the FB body inlined with
//    the instance's names, then copies the outputs bound with `=>`.
//  - A function call is inlined before the statement that uses it, into
//    variables private to that call site (`F_1.x`); calls are hoisted in
//    evaluation order, and an ELSIF whose condition calls a function
//    becomes a nested IF so the call runs only when the IEC order says so.
//  - RETURN, EXIT and CONTINUE set flag variables; the statements after one
//    run under `if not flag`.
//  - Integer arithmetic is exact in NetIR; where an intermediate IEC result
//    could leave its type (INT + INT), it is wrapped explicitly to that
//    type's width, and stores wrap through the `wrap` integer types. An
//    interval analysis skips the wrap where overflow is impossible.
//  - Variables whose value cannot matter in the next scan are reset at the
//    end of the scan action, so states do not differ in dead values: the
//    locals of inlined functions, VAR_TEMP, control flags, FB members never
//    read, and FB inputs every call passes and nobody reads from outside.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/LowerToNet.h"
#include "frontends/plc/Sema.h"

#include "ir/net/Builder.h"
#include "ir/net/Names.h"
#include "ir/net/Parser.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringSet.h"

#include <numeric>
#include <set>

using namespace netlift;
using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;
using llvm::Twine;
using NExpr = net::Expr;
using NStmt = net::Stmt;
using Sink = std::vector<NStmt *>;

static void collectWritten(StmtList &l, std::set<VarDecl *> &w);

namespace {

/// Thrown to abandon the translation after the first refusal; caught in
/// lowerToNet. (One refusal per run: later ones would mostly be echoes.)
struct Refusal {};

struct Range {
  int64_t lo, hi;
  bool exact; // false: unknown (treat as unbounded)
};

/// The lowering of one POU body invocation: whose names, under which
/// prefix, with which VAR_IN_OUT aliases, and the control flags in force.
struct Frame {
  Pou *pou = nullptr;
  std::string prefix; // "" for the top program, "t1." for an instance
  std::map<VarDecl *, NExpr *> aliases; // VAR_IN_OUT -> caller's lvalue
  std::string returnFlag;               // set when the body has RETURN
  bool external = false; // program frame: reads of FB members count as
                         // reads from outside the instance
};

struct LoopCtx {
  std::string exitFlag, continueFlag;
};

struct InstanceUse {
  unsigned calls = 0;
  std::map<std::string, unsigned> given; // input member -> calls giving it
};

struct ClockUse {
  std::string var;    // the clock variable
  std::string member; // the FB input bounding it (PT)
  std::string path;   // the instance path
  int64_t cap = 0;
  std::vector<std::string> timeMembers; // TIME members retyped 0..cap
};

class Lowering {
public:
  Lowering(Unit &u, const LowerOptions &o, DiagEngine &d, net::Design &des)
      : unit(u), opts(o), diag(d), design(des), b(des) {}
  bool run();
  bool runEventDriven(std::vector<EventDrivenBlock> &blocks);

private:
  [[noreturn]] void refuse(SMLoc at, const Twine &msg) {
    diag.error(at, msg);
    throw Refusal{};
  }

  // Time.
  void collectTimes(Pou *p, std::set<Pou *> &seen, std::vector<int64_t> &ns);
  void collectTimesExpr(Expr *e, std::set<Pou *> &seen,
                        std::vector<int64_t> &ns);
  void collectTimesStmts(StmtList &l, std::set<Pou *> &seen,
                         std::vector<int64_t> &ns);
  int64_t ticks(int64_t ns, SMLoc at);

  // Types and declarations.
  const net::Type *netType(const PType *t, SMLoc at, StringRef what);
  /// `v`'s initial value (`init`, else its type's); inside an aggregate
  /// (`at` given) every element is spelt out, defaults included.
  NExpr *initialValue(VarDecl *v, Initializer *init, const PType *t,
                      std::optional<SMLoc> at = std::nullopt);
  /// An array (from dimension `dim` on) or structure initial value.
  NExpr *aggregateValue(VarDecl *v, Initializer *init, const PType *t,
                        size_t dim, SMLoc at);
  NExpr *defaultValue(const PType *t, SMLoc at);
  std::string unique(std::string name);
  static std::string sanitize(StringRef name);
  void declareProgramVar(VarDecl *v);
  void declareInstance(const std::string &path, Pou *fb, Initializer *init);
  uint32_t declareTemp(const std::string &name, const PType *t, SMLoc at);
  std::optional<std::pair<int64_t, int64_t>> inputRange(VarDecl *v);

  /// Picks the tick from the durations `ns` (and the options, or a model
  /// read before) and sets the design's timescale.
  void chooseTick(std::vector<int64_t> ns);

  // Bodies.
  /// One program of a module: the prefix of its own names ("" when the
  /// module is the program's alone), the scan it runs in, and what its
  /// lowering produces.
  struct ProgramRun {
    Pou *pou = nullptr;
    std::string prefix;
    std::string scan, cycle; // the scan transition and its place
    int64_t period = 1;
    Sink action;
    std::vector<std::pair<std::string, NExpr *>> resets; // end of its scan
    size_t membersBegin = 0, membersEnd = 0;             // its FB members
  };
  /// The globals `program` reads or writes (its body, the FBs and
  /// functions it calls, its instance's arguments).
  std::set<VarDecl *> globalsUsedBy(Pou *program);
  /// While one program's declarations or body are lowered: its names'
  /// prefix is in force and end-of-scan resets go to it.
  struct InProgram {
    Lowering &L;
    ProgramRun &run;
    InProgram(Lowering &l, ProgramRun &r) : L(l), run(r) {
      L.currentProgram = r.pou;
      L.programPrefix = r.prefix;
      std::swap(L.resets, r.resets);
    }
    ~InProgram() { std::swap(L.resets, run.resets); }
  };
  void startModule(const std::string &name, SMLoc loc);
  void declareProgram(ProgramRun &run);
  void lowerProgramBody(ProgramRun &run);
  void deadValueResets(ProgramRun &run);
  /// One module holding `runs`; runs with the same scan share it, in
  /// order.
  void lowerPrograms(const std::string &name, SMLoc loc,
                     std::vector<ProgramRun> &runs);
  void capClocks();
  /// Pragmas become `pragma` attributes of what they annotate (see
  /// attachPragmas).
  void keepPragmas(const std::string &target,
                   const std::vector<Attribute> &attrs) {
    for (const Attribute &a : attrs)
      pendingPragmas.push_back({target, &a});
  }
  void attachPragmas();
  std::vector<std::pair<std::string, const Attribute *>> pendingPragmas;
  void lowerEventBlock(EventDrivenBlock &block);
  void body(StmtList &list, Frame &f, Sink &out,
            const std::vector<LoopCtx> &loops);
  void stmt(Stmt *s, Frame &f, Sink &out, const std::vector<LoopCtx> &loops);
  NExpr *expr(Expr *e, Frame &f, Sink &pre);
  NExpr *lvalue(Expr *e, Frame &f, Sink &pre);
  NExpr *varRef(VarDecl *v, Frame &f, SMLoc at);
  std::string instancePath(Expr *e, Frame &f);
  void fbCall(Expr *call, Frame &f, Sink &out);
  void enabledBody(Pou *callee, const std::string &prefix, Expr *call,
                   Frame &nf, Sink &out);
  void noteClockBound(const std::string &member, Expr *value, Frame &f,
                      SMLoc at);
  NExpr *functionCall(Expr *call, Frame &f, Sink &pre);
  NExpr *stdCall(Expr *call, Frame &f, Sink &pre);
  NExpr *convert(NExpr *v, const PType *from, const PType *to, SMLoc at);
  NExpr *wrapTo(NExpr *v, const PType *t, Range r, SMLoc at);
  NExpr *maskTo(NExpr *v, const PType *t, SMLoc at);
  Range rangeOf(Expr *e);
  std::optional<int64_t> constValue(Expr *e, Frame &f);
  bool mayJump(const StmtList &l, bool loopLevel);
  std::optional<int64_t> loopBound(Stmt *loop, Stmt *before, Frame &f);
  Stmt *previous = nullptr; // the statement before the one being lowered
  void assign(NExpr *target, NExpr *value, const PType *targetType,
              Expr *valueExpr, Sink &out, SMLoc at);

  Unit &unit;
  const LowerOptions &opts;
  DiagEngine &diag;
  net::Design &design;
  net::Builder b;
  int64_t tickNs = 0;

  // Per module.
  net::Module *mod = nullptr;
  std::map<const PType *, const net::Type *> typeCache;
  std::vector<std::pair<std::string, NExpr *>> resets; // end-of-scan
  std::set<std::string> resetNames;
  std::vector<std::string> instanceMembers; // FB member variables
  std::set<std::string> externallyRead;     // `inst.member` read by caller
  std::map<std::string, InstanceUse> instanceUses;
  std::map<std::string, ClockUse> clocks;          // by clock variable name
  std::map<std::string, std::string> clockOfBound; // `t.PT` -> clock var
  std::map<std::string, Pou *> instanceTypes;
  std::map<std::string, const PType *> varTypes; // NetIR var -> PLC type
  std::set<VarDecl *> written;
  std::map<VarDecl *, std::pair<int64_t, int64_t>> inputRanges;
  unsigned callSites = 0, flags = 0, loopVars = 0;
  /// The configuration's instance of each translated program.
  std::map<Pou *, std::pair<ProgramInstance *, Configuration *>> instanceOf;
  /// The instance whose arguments bind a program's inputs and outputs.
  std::map<Pou *, ProgramInstance *> argumentsOf;
  /// Inputs of the program being lowered that an argument feeds.
  std::set<VarDecl *> boundInputs;
  Pou *currentProgram = nullptr;
  /// The prefix of the current program's own names (see ProgramRun).
  std::string programPrefix;
  /// Lowering an event-driven block: inputs take their full types.
  bool eventDriven = false;
};

} // namespace

//===----------------------------------------------------------------------===//
// Time
//===----------------------------------------------------------------------===//

void Lowering::collectTimesExpr(Expr *e, std::set<Pou *> &seen,
                                std::vector<int64_t> &ns) {
  if (!e)
    return;
  if (e->kind == ExprKind::TimeLit && e->intValue != 0)
    ns.push_back(std::abs(e->intValue));
  for (Expr *o : e->operands)
    collectTimesExpr(o, seen, ns);
  for (CallArg &a : e->args)
    collectTimesExpr(a.value, seen, ns);
  if (e->callee)
    collectTimes(e->callee, seen, ns);
  if (e->kind == ExprKind::Call && e->var && e->var->type &&
      e->var->type->kind == PTypeKind::FunctionBlock)
    collectTimes(e->var->type->fb, seen, ns);
}

void Lowering::collectTimesStmts(StmtList &l, std::set<Pou *> &seen,
                                 std::vector<int64_t> &ns) {
  for (Stmt *s : l) {
    for (Expr *e : {s->target, s->value, s->from, s->to, s->by})
      collectTimesExpr(e, seen, ns);
    for (auto &[c, body] : s->arms) {
      collectTimesExpr(c, seen, ns);
      collectTimesStmts(body, seen, ns);
    }
    for (auto &arm : s->caseArms)
      collectTimesStmts(arm.body, seen, ns);
    collectTimesStmts(s->elseBody, seen, ns);
    collectTimesStmts(s->body, seen, ns);
  }
}

static void initTimes(Initializer *init, std::vector<int64_t> &ns) {
  if (!init)
    return;
  if (init->value && init->value->kind == ExprKind::TimeLit &&
      init->value->intValue)
    ns.push_back(std::abs(init->value->intValue));
  for (auto &[n, i] : init->elems)
    initTimes(i, ns);
  for (auto &[n, i] : init->fields)
    initTimes(i, ns);
}

void Lowering::collectTimes(Pou *p, std::set<Pou *> &seen,
                            std::vector<int64_t> &ns) {
  if (!seen.insert(p).second)
    return;
  for (VarDecl *v : p->vars) {
    if (v->typeSyntax)
      initTimes(v->typeSyntax->init, ns);
    if (v->type && v->type->kind == PTypeKind::FunctionBlock)
      collectTimes(v->type->fb, seen, ns);
  }
  collectTimesStmts(p->body, seen, ns);
}

std::string plc::formatDuration(int64_t ns) {
  static const struct {
    const char *unit;
    int64_t ns;
  } units[] = {{"h", 3600000000000}, {"m", 60000000000}, {"s", 1000000000},
               {"ms", 1000000},      {"us", 1000},       {"ns", 1}};
  for (auto &u : units)
    if (ns % u.ns == 0)
      return std::to_string(ns / u.ns) + u.unit;
  return std::to_string(ns) + "ns";
}

int64_t Lowering::ticks(int64_t ns, SMLoc at) {
  if (ns % tickNs != 0)
    refuse(at, "time value " + formatDuration(ns) +
                   " is not a whole number of ticks (one tick is " +
                   formatDuration(tickNs) + "; choose --timescale)");
  return ns / tickNs;
}

//===----------------------------------------------------------------------===//
// Types and declarations
//===----------------------------------------------------------------------===//

std::string Lowering::sanitize(StringRef name) {
  std::string bare;
  for (char c : name)
    if (c != '%')
      bare += c;
  return net::toIdentifier(bare);
}

std::string Lowering::unique(std::string name) {
  std::string n = name;
  for (unsigned i = 2; mod->lookup(n).kind != net::SymKind::None; ++i)
    n = name + "_" + std::to_string(i);
  return n;
}

const net::Type *Lowering::netType(const PType *t, SMLoc at, StringRef what) {
  auto it = typeCache.find(t);
  if (it != typeCache.end())
    return it->second;
  net::TypeTable &tt = design.types;
  const net::Type *r = nullptr;
  switch (t->kind) {
  case PTypeKind::Bool:
  case PTypeKind::AnyInt:
  case PTypeKind::Time:
    r = scalarNetType(t, tt);
    break;
  case PTypeKind::Int:
    if (t->width == 64 && !t->isSigned && !t->isSubrange)
      refuse(at, "64-bit unsigned type " + t->str() + " of " + what +
                     " is not supported (values are held in 64 signed bits)");
    r = scalarNetType(t, tt);
    break;
  case PTypeKind::Real:
    refuse(at, t->str() + " " + what +
                   ": REAL arithmetic is not supported (it cannot be "
                   "modelled exactly)");
  case PTypeKind::String:
    refuse(at, t->str() + " " + what + ": strings are not supported");
  case PTypeKind::Date:
    refuse(at, t->str() + " " + what +
                   ": dates and times of day are not supported");
  case PTypeKind::Enum: {
    std::string name = sanitize(t->name.empty() ? "Enum" : t->name);
    if (const net::Type *existing = tt.lookup(name)) {
      r = existing;
      break;
    }
    std::vector<StringRef> names;
    for (auto &e : t->enumerators)
      names.push_back(design.save(sanitize(e)));
    r = tt.createEnum(design.save(name), names);
    break;
  }
  case PTypeKind::Array: {
    const net::Type *elem = netType(t->elem, at, what);
    for (size_t d = t->dims.size(); d-- > 0;)
      elem = tt.getArray(elem, t->dims[d].first, t->dims[d].second);
    r = elem;
    break;
  }
  case PTypeKind::Struct: {
    std::string name = sanitize(t->name.empty() ? "Struct" : t->name);
    if (const net::Type *existing = tt.lookup(name)) {
      r = existing;
      break;
    }
    std::vector<net::Field> fields;
    for (VarDecl *f : t->fields)
      fields.push_back({design.save(sanitize(f->name)),
                        netType(f->type, f->loc, "field " + f->name)});
    r = tt.createRecord(design.save(name), fields);
    break;
  }
  case PTypeKind::FunctionBlock:
  case PTypeKind::Void:
    refuse(at, "internal: no NetIR type for " + t->str());
  }
  typeCache[t] = r;
  return r;
}

const net::Type *plc::scalarNetType(const PType *t, net::TypeTable &tt) {
  switch (t->kind) {
  case PTypeKind::Bool:
    return tt.getBool();
  case PTypeKind::Int:
    if (t->isSubrange)
      return tt.getRange(t->lo, t->hi);
    if (t->width == 64 && !t->isSigned)
      return nullptr;
    return tt.getInt(t->width, t->isSigned, net::Overflow::Wrap);
  case PTypeKind::AnyInt:
    return tt.getInt(64, true, net::Overflow::Wrap);
  case PTypeKind::Time:
    return tt.getInt(64, true, net::Overflow::Error);
  default:
    return nullptr;
  }
}

NExpr *Lowering::defaultValue(const PType *t, SMLoc at) {
  switch (t->kind) {
  case PTypeKind::Bool:
    return b.boolLit(false, at);
  case PTypeKind::Int:
    return b.intLit(t->isSubrange ? t->lo : 0, at);
  case PTypeKind::Time:
  case PTypeKind::AnyInt:
    return b.intLit(0, at);
  case PTypeKind::Enum:
    return b.ref(sanitize(t->name) + "#" + sanitize(t->enumerators[0]), at);
  default:
    return nullptr; // aggregates: NetIR's defaults match IEC's
  }
}

/// Whether a value of type `t` starts anywhere else than at IEC's default
/// (a structure field with its own initial value).
static bool hasDeclaredInitial(const PType *t) {
  if (t->kind == PTypeKind::Array)
    return hasDeclaredInitial(t->elem);
  if (t->kind == PTypeKind::Struct)
    for (VarDecl *f : t->fields)
      if ((f->typeSyntax && f->typeSyntax->init) || hasDeclaredInitial(f->type))
        return true;
  return false;
}

NExpr *Lowering::aggregateValue(VarDecl *v, Initializer *init, const PType *t,
                                size_t dim, SMLoc at) {
  // Sema has checked the initialiser's shape against the type (array list
  // for an array, field list for a structure, one dimension); the count is
  // checked here.
  std::vector<NExpr *> elems;
  std::vector<StringRef> names;
  if (t->kind == PTypeKind::Array) {
    auto [lo, hi] = t->dims[dim];
    size_t n = size_t(hi - lo + 1);
    auto element = [&](Initializer *e) {
      return dim + 1 < t->dims.size() ? aggregateValue(v, e, t, dim + 1, at)
                                      : initialValue(v, e, t->elem, at);
    };
    if (init) {
      for (auto &[count, inner] : init->elems)
        for (int64_t k = 0; k < count; ++k) {
          if (elems.size() == n)
            refuse(init->loc, "the initialiser of '" + v->name +
                                  "' has more than the " + Twine(n) +
                                  " elements of its array");
          elems.push_back(element(inner));
        }
    }
    // IEC 61131-3: elements the list does not reach keep their default.
    while (elems.size() < n)
      elems.push_back(element(nullptr));
  } else {
    for (VarDecl *f : t->fields) {
      Initializer *given = f->typeSyntax ? f->typeSyntax->init : nullptr;
      if (init)
        for (auto &[name, inner] : init->fields)
          if (sameName(name, f->name))
            given = inner;
      elems.push_back(initialValue(f, given, f->type, at));
      names.push_back(design.save(sanitize(f->name)));
    }
  }
  return b.aggregate(elems, names, init ? init->loc : at);
}

NExpr *Lowering::initialValue(VarDecl *v, Initializer *init, const PType *t,
                              std::optional<SMLoc> at) {
  SMLoc loc = at ? *at : v->loc;
  if (t->kind == PTypeKind::Array || t->kind == PTypeKind::Struct) {
    // Aggregates start at IEC's defaults unless something says otherwise,
    // and NetIR's defaults are the same: no initial value needed then.
    if (!init && !at && !hasDeclaredInitial(t))
      return nullptr;
    return aggregateValue(v, init, t, 0, loc);
  }
  if (!init)
    return defaultValue(t, loc);
  if (init->kind != Initializer::Value)
    refuse(init->loc, "an array or structure initialiser for '" + v->name +
                          "' of type " + t->str());
  Frame none;
  Expr *e = init->value;
  if (t->kind == PTypeKind::Enum) {
    if (e->enumValue < 0)
      refuse(e->loc, "initial value must be an enumerator");
    return b.ref(sanitize(t->name) + "#" +
                     sanitize(t->enumerators[e->enumValue]),
                 e->loc);
  }
  if (e->kind == ExprKind::StringLit)
    refuse(e->loc, "STRING variable '" + v->name +
                       "' is not supported (string operations beyond "
                       "constants are refused)");
  std::optional<int64_t> c = constValue(e, none);
  if (!c)
    refuse(e->loc, "initial value of '" + v->name + "' must be a constant");
  if (t->kind == PTypeKind::Bool)
    return b.boolLit(*c != 0, e->loc);
  return b.intLit(*c, e->loc);
}

std::optional<std::pair<int64_t, int64_t>> Lowering::inputRange(VarDecl *v) {
  auto parse = [](StringRef s) -> std::optional<std::pair<int64_t, int64_t>> {
    s = s.trim().trim("'\"").trim();
    auto [a, c] = s.split("..");
    int64_t lo, hi;
    if (a.trim().getAsInteger(10, lo) || c.trim().getAsInteger(10, hi) ||
        lo > hi)
      return std::nullopt;
    return std::make_pair(lo, hi);
  };
  for (auto &a : v->attrs) {
    StringRef t(a.text);
    t.consume_front("netlift");
    t = t.trim();
    // `{range 0..100}`, `{netlift range 0..100}`,
    // `{attribute 'range' := '0..100'}`.
    if (t.consume_front("range")) {
      if (auto r = parse(t))
        return r;
      refuse(a.loc, "malformed range pragma (write {range LO..HI})");
    }
    if (t.consume_front("attribute") && t.trim().consume_front("'range'")) {
      StringRef rest = t.trim();
      rest.consume_front("'range'");
      rest = rest.trim();
      rest.consume_front(":=");
      if (auto r = parse(rest))
        return r;
      refuse(a.loc, "malformed range attribute (write {attribute 'range' := "
                    "'LO..HI'})");
    }
  }
  auto it = opts.ranges.find(StringRef(v->name).upper());
  if (it != opts.ranges.end())
    return it->second;
  if (!v->location.empty()) {
    it = opts.ranges.find(StringRef(v->location).upper());
    if (it != opts.ranges.end())
      return it->second;
  }
  return std::nullopt;
}

void Lowering::declareProgramVar(VarDecl *v) {
  if (!v->type)
    refuse(v->loc, "internal: untyped variable");
  const PType *t = v->type;
  if (v->section == VarSection::External)
    return; // the global is declared once
  std::string name = (v->owner ? programPrefix : "") + sanitize(v->name);
  if (t->kind == PTypeKind::FunctionBlock) {
    keepPragmas(name, v->attrs);
    declareInstance(name, t->fb, v->typeSyntax ? v->typeSyntax->init : nullptr);
    return;
  }
  if (v->section == VarSection::InOut)
    refuse(v->loc, "VAR_IN_OUT of the translated program '" +
                       currentProgram->name + "' has nothing to refer to");
  keepPragmas(name, v->attrs);
  // An input bound to a global by a program argument is fed from it.
  bool isInput = (v->area() == 'I' || v->section == VarSection::Input) &&
                 !boundInputs.count(v);
  bool isOutput = v->area() == 'Q' || v->section == VarSection::Output;
  varTypes[name] = t;
  if (isInput) {
    if (t->kind == PTypeKind::Bool) {
      b.addPort(name, net::PortKind::Cond, net::PortDir::In, nullptr, v->loc);
      return;
    }
    const net::Type *nt = nullptr;
    if (auto r = inputRange(v)) {
      if (t->kind != PTypeKind::Int && t->kind != PTypeKind::Time)
        refuse(v->loc,
               "a range is given for non-integer input '" + v->name + "'");
      if (r->first < t->lo || r->second > t->hi)
        if (t->kind == PTypeKind::Int)
          refuse(v->loc, "range " + Twine(r->first) + ".." + Twine(r->second) +
                             " of input '" + v->name + "' exceeds " + t->str());
      nt = design.types.getRange(r->first, r->second);
      inputRanges[v] = *r;
    } else if (eventDriven || t->kind == PTypeKind::Enum ||
               (t->kind == PTypeKind::Int && t->isSubrange)) {
      nt = netType(t, v->loc, "input " + v->name);
    } else if (t->kind == PTypeKind::Int || t->kind == PTypeKind::Time) {
      refuse(v->loc, "input '" + v->name + "' of type " + t->str() +
                         " is unbounded: give its range with a pragma "
                         "{range LO..HI} before the declaration, a subrange "
                         "type, or --ranges FILE");
    } else {
      nt = netType(t, v->loc, "input " + v->name);
    }
    if (!nt->isScalar())
      refuse(v->loc, "input '" + v->name + "' of type " + t->str() +
                         ": inputs must be scalars");
    b.addPort(name, net::PortKind::Data, net::PortDir::In, nt, v->loc);
    return;
  }
  if (v->section == VarSection::Temp) {
    declareTemp(name, t, v->loc);
    return;
  }
  NExpr *init =
      initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr, t);
  if (isOutput) {
    const net::Type *nt = netType(t, v->loc, "output " + v->name);
    uint32_t p = t->kind == PTypeKind::Bool
                     ? b.addPort(name, net::PortKind::Cond, net::PortDir::Out,
                                 nullptr, v->loc)
                     : b.addPort(name, net::PortKind::Data, net::PortDir::Out,
                                 nt, v->loc);
    mod->ports[p].init = init;
    return;
  }
  b.addVar(name, netType(t, v->loc, "variable " + v->name), init, v->loc);
}

void Lowering::declareInstance(const std::string &path, Pou *fb,
                               Initializer *init) {
  instanceTypes[path] = fb;
  // The block type's pragmas go to the instance, as flatten would carry a
  // module's. netlift's own blocks' pragmas are directives to netlift.
  if (!fb->isLibrary)
    keepPragmas(path, fb->attrs);
  for (VarDecl *m : fb->vars) {
    if (m->section == VarSection::External)
      continue;
    std::string name = path + "." + sanitize(m->name);
    if (!fb->isLibrary)
      keepPragmas(name, m->attrs);
    Initializer *mi = m->typeSyntax ? m->typeSyntax->init : nullptr;
    if (init && init->kind == Initializer::Struct)
      for (auto &[fname, finit] : init->fields)
        if (sameName(fname, m->name))
          mi = finit;
    if (m->type->kind == PTypeKind::FunctionBlock) {
      declareInstance(name, m->type->fb, mi);
      continue;
    }
    if (m->section == VarSection::InOut)
      continue; // an alias of the caller's variable at each call
    varTypes[name] = m->type;
    bool isClock = false;
    std::string bound;
    for (auto &a : m->attrs) {
      StringRef t(a.text);
      if (t.consume_front("netlift clock")) {
        isClock = true;
        bound = t.trim().str();
      }
    }
    if (isClock) {
      // The cap is fixed once every call is lowered (see run()).
      b.addVar(name, design.types.getClock(1), nullptr, m->loc);
      ClockUse &cu = clocks[name];
      cu.var = name;
      cu.member = bound;
      cu.path = path;
      clockOfBound[path + "." + sanitize(bound)] = name;
      for (VarDecl *o : fb->vars)
        if (o->type && o->type->kind == PTypeKind::Time && o != m)
          cu.timeMembers.push_back(path + "." + sanitize(o->name));
      continue;
    }
    if (m->section == VarSection::Temp) {
      declareTemp(name, m->type, m->loc);
      continue;
    }
    b.addVar(name, netType(m->type, m->loc, "member " + m->name),
             initialValue(m, mi, m->type), m->loc);
    instanceMembers.push_back(name);
    if (m->edge) // what the caller passed last time
      b.addVar(name + ".prev", design.types.getBool(), b.boolLit(false, m->loc),
               m->loc);
  }
}

uint32_t Lowering::declareTemp(const std::string &name, const PType *t,
                               SMLoc at) {
  varTypes[name] = t;
  NExpr *init = defaultValue(t, at);
  uint32_t x = b.addVar(name, netType(t, at, "variable " + name), init, at);
  if (resetNames.insert(name).second && init)
    resets.push_back({name, init});
  return x;
}

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

std::optional<int64_t> Lowering::constValue(Expr *e, Frame &f) {
  if (!e)
    return std::nullopt;
  switch (e->kind) {
  case ExprKind::IntLit:
  case ExprKind::BoolLit:
    return e->intValue;
  case ExprKind::TimeLit:
    return ticks(e->intValue, e->loc);
  case ExprKind::Unary: {
    auto a = constValue(e->operands[0], f);
    if (!a)
      return a;
    if (e->op == Op::Neg)
      return -*a;
    if (e->op == Op::Not && e->type && e->type->kind == PTypeKind::Bool)
      return int64_t(!*a);
    if (e->op == Op::Plus)
      return a;
    return std::nullopt;
  }
  case ExprKind::Binary: {
    auto a = constValue(e->operands[0], f), c = constValue(e->operands[1], f);
    if (!a || !c)
      return std::nullopt;
    switch (e->op) {
    case Op::Add:
      return *a + *c;
    case Op::Sub:
      return *a - *c;
    case Op::Mul:
      return *a * *c;
    case Op::Div:
      return *c ? std::optional<int64_t>(*a / *c) : std::nullopt;
    case Op::Mod:
      return *c ? std::optional<int64_t>(*a % *c) : std::nullopt;
    default:
      return std::nullopt;
    }
  }
  case ExprKind::Name: {
    // A constant, or a variable nobody ever writes, has its initial value.
    VarDecl *v = e->var;
    if (!v || v->section == VarSection::Input || v->area() == 'I' ||
        v->section == VarSection::InOut || written.count(v) ||
        (v->owner && v->owner->kind != PouKind::Program && !v->constant))
      return std::nullopt;
    if (!v->type ||
        (v->type->kind != PTypeKind::Int && v->type->kind != PTypeKind::Time &&
         v->type->kind != PTypeKind::Bool))
      return std::nullopt;
    Initializer *init = v->typeSyntax ? v->typeSyntax->init : nullptr;
    if (!init)
      return v->type->isSubrange ? v->type->lo : 0;
    if (init->kind != Initializer::Value)
      return std::nullopt;
    return constValue(init->value, f);
  }
  default:
    return std::nullopt;
  }
}

Range Lowering::rangeOf(Expr *e) {
  const PType *t = e->type;
  Range full{0, 0, false};
  if (t && t->kind == PTypeKind::Bool)
    full = {0, 1, true};
  else if (t && t->kind == PTypeKind::Int)
    full = {t->lo, t->hi, true};
  switch (e->kind) {
  case ExprKind::IntLit:
    return {e->intValue, e->intValue, true};
  case ExprKind::Name:
  case ExprKind::Field:
  case ExprKind::Index:
    if (auto it = inputRanges.find(e->var); it != inputRanges.end())
      return {it->second.first, it->second.second, true};
    if (e->var && e->var->type && e->var->type->kind == PTypeKind::Int)
      return {e->var->type->lo, e->var->type->hi, true};
    return full;
  case ExprKind::Unary:
    if (e->op == Op::Neg) {
      Range a = rangeOf(e->operands[0]);
      if (a.exact && a.lo != INT64_MIN)
        return {-a.hi, -a.lo, true};
      return {0, 0, false};
    }
    return e->op == Op::Plus ? rangeOf(e->operands[0]) : full;
  case ExprKind::Binary: {
    Range a = rangeOf(e->operands[0]), c = rangeOf(e->operands[1]);
    if (!a.exact || !c.exact)
      return {0, 0, false};
    auto fits = [](__int128 v) {
      return v >= INT64_MIN / 4 && v <= INT64_MAX / 4;
    };
    __int128 lo, hi;
    switch (e->op) {
    case Op::Add:
      lo = __int128(a.lo) + c.lo;
      hi = __int128(a.hi) + c.hi;
      break;
    case Op::Sub:
      lo = __int128(a.lo) - c.hi;
      hi = __int128(a.hi) - c.lo;
      break;
    case Op::Mul: {
      __int128 p[] = {__int128(a.lo) * c.lo, __int128(a.lo) * c.hi,
                      __int128(a.hi) * c.lo, __int128(a.hi) * c.hi};
      lo = *std::min_element(p, p + 4);
      hi = *std::max_element(p, p + 4);
      break;
    }
    default:
      return full;
    }
    if (!fits(lo) || !fits(hi))
      return {0, 0, false};
    return {int64_t(lo), int64_t(hi), true};
  }
  default:
    return full;
  }
}

NExpr *Lowering::maskTo(NExpr *v, const PType *t, SMLoc at) {
  if (t->width >= 64)
    return v;
  int64_t mask = (int64_t(1) << t->width) - 1;
  return b.binary(net::BinaryOp::BitAnd, v, b.intLit(mask, at), at);
}

NExpr *Lowering::wrapTo(NExpr *v, const PType *t, Range r, SMLoc at) {
  t = t && t->isSubrange ? t->base : t;
  if (!t || t->kind != PTypeKind::Int || t->width >= 64)
    return v;
  if (r.exact && r.lo >= t->lo && r.hi <= t->hi)
    return v;
  if (!t->isSigned)
    return maskTo(v, t, at);
  int64_t half = int64_t(1) << (t->width - 1);
  NExpr *shifted = b.binary(net::BinaryOp::Add, v, b.intLit(half, at), at);
  return b.binary(net::BinaryOp::Sub, maskTo(shifted, t, at),
                  b.intLit(half, at), at);
}

std::string Lowering::instancePath(Expr *e, Frame &f) {
  // An FB instance is a Name (a variable of this frame or a global).
  if (e->kind != ExprKind::Name || !e->var)
    refuse(e->loc, "function block instances must be named directly (arrays "
                   "and structures of instances are not supported)");
  VarDecl *v = e->var;
  if (!v->owner)
    return sanitize(v->name);
  return f.prefix + sanitize(v->name);
}

NExpr *Lowering::varRef(VarDecl *v, Frame &f, SMLoc at) {
  auto alias = f.aliases.find(v);
  if (alias != f.aliases.end())
    return alias->second;
  if (!v->owner) // a global
    return b.ref(sanitize(v->name), at);
  return b.ref(f.prefix + sanitize(v->name), at);
}

NExpr *Lowering::lvalue(Expr *e, Frame &f, Sink &pre) {
  switch (e->kind) {
  case ExprKind::Name:
    if (!e->var)
      refuse(e->loc, "cannot assign to '" + e->name + "'");
    return varRef(e->var, f, e->loc);
  case ExprKind::Field: {
    Expr *base = e->base();
    if (base->type && base->type->kind == PTypeKind::FunctionBlock) {
      std::string path = instancePath(base, f) + "." + sanitize(e->var->name);
      if (f.external)
        externallyRead.insert(path);
      return b.ref(path, e->loc);
    }
    return b.field(lvalue(base, f, pre), sanitize(e->name), e->loc);
  }
  case ExprKind::Index: {
    NExpr *r = lvalue(e->base(), f, pre);
    for (size_t i = 1; i < e->operands.size(); ++i)
      r = b.index(r, expr(e->operands[i], f, pre), e->loc);
    return r;
  }
  default:
    refuse(e->loc, "cannot assign to this expression");
  }
}

NExpr *Lowering::expr(Expr *e, Frame &f, Sink &pre) {
  if (e->type && e->type->kind == PTypeKind::Real)
    refuse(e->loc, "REAL arithmetic is not supported (it cannot be modelled "
                   "exactly)");
  if (e->type && e->type->kind == PTypeKind::String)
    refuse(e->loc, "string operations are not supported");
  if (e->type && e->type->kind == PTypeKind::Date)
    refuse(e->loc, "dates and times of day are not supported");
  switch (e->kind) {
  case ExprKind::IntLit:
    if (e->type && e->type->kind == PTypeKind::Bool)
      return b.boolLit(e->intValue != 0, e->loc);
    return b.intLit(e->intValue, e->loc);
  case ExprKind::BoolLit:
    return b.boolLit(e->intValue != 0, e->loc);
  case ExprKind::TimeLit:
    return b.intLit(ticks(e->intValue, e->loc), e->loc);
  case ExprKind::RealLit:
    refuse(e->loc, "REAL values are not supported");
  case ExprKind::StringLit:
    refuse(e->loc, "string literals are not supported");
  case ExprKind::DateLit:
    refuse(e->loc, "date and time-of-day literals are not supported");
  case ExprKind::EnumLit:
    return b.ref(sanitize(e->type->name) + "#" +
                     sanitize(e->type->enumerators[e->enumValue]),
                 e->loc);
  case ExprKind::Name:
    if (!e->var && e->enumValue >= 0)
      return b.ref(sanitize(e->type->name) + "#" +
                       sanitize(e->type->enumerators[e->enumValue]),
                   e->loc);
    if (e->var && e->var->type &&
        e->var->type->kind == PTypeKind::FunctionBlock)
      refuse(e->loc, "a function block instance is not a value");
    return lvalue(e, f, pre);
  case ExprKind::Field:
  case ExprKind::Index:
    return lvalue(e, f, pre);
  case ExprKind::BitAccess: {
    NExpr *base = expr(e->base(), f, pre);
    NExpr *shifted = b.binary(net::BinaryOp::Shr, base,
                              b.intLit(e->intValue, e->loc), e->loc);
    NExpr *bit =
        b.binary(net::BinaryOp::BitAnd, shifted, b.intLit(1, e->loc), e->loc);
    return b.binary(net::BinaryOp::Ne, bit, b.intLit(0, e->loc), e->loc);
  }
  case ExprKind::Deref:
    refuse(e->loc, "dereference is not supported");
  case ExprKind::Unary: {
    NExpr *a = expr(e->operands[0], f, pre);
    switch (e->op) {
    case Op::Plus:
      return a;
    case Op::Neg:
      return wrapTo(b.unary(net::UnaryOp::Neg, a, e->loc), e->type, rangeOf(e),
                    e->loc);
    default: {
      const PType *t = e->type->isSubrange ? e->type->base : e->type;
      if (t->kind == PTypeKind::Bool)
        return b.unary(net::UnaryOp::Not, a, e->loc);
      NExpr *n = b.unary(net::UnaryOp::BitNot, a, e->loc);
      return t->kind == PTypeKind::Int && !t->isSigned ? maskTo(n, t, e->loc)
                                                       : n;
    }
    }
  }
  case ExprKind::Binary: {
    if (e->op == Op::Pow)
      refuse(e->loc, "'**' (EXPT) is REAL arithmetic, which is not "
                     "supported");
    NExpr *l = expr(e->operands[0], f, pre);
    NExpr *r = expr(e->operands[1], f, pre);
    const PType *lt = e->operands[0]->type;
    bool logical = lt && (lt->kind == PTypeKind::Bool);
    net::BinaryOp op;
    switch (e->op) {
    case Op::Or:
    case Op::OrElse:
      op = logical ? net::BinaryOp::Or : net::BinaryOp::BitOr;
      break;
    case Op::Xor:
      op = logical ? net::BinaryOp::Xor : net::BinaryOp::BitXor;
      break;
    case Op::And:
    case Op::AndThen:
      op = logical ? net::BinaryOp::And : net::BinaryOp::BitAnd;
      break;
    case Op::Eq:
      op = net::BinaryOp::Eq;
      break;
    case Op::Ne:
      op = net::BinaryOp::Ne;
      break;
    case Op::Lt:
      op = net::BinaryOp::Lt;
      break;
    case Op::Le:
      op = net::BinaryOp::Le;
      break;
    case Op::Gt:
      op = net::BinaryOp::Gt;
      break;
    case Op::Ge:
      op = net::BinaryOp::Ge;
      break;
    case Op::Add:
      op = net::BinaryOp::Add;
      break;
    case Op::Sub:
      op = net::BinaryOp::Sub;
      break;
    case Op::Mul:
      op = net::BinaryOp::Mul;
      break;
    case Op::Div:
      op = net::BinaryOp::Div;
      break;
    case Op::Mod:
      op = net::BinaryOp::Mod;
      break;
    default:
      refuse(e->loc, "unsupported operator");
    }
    // Booleans compared for order (FALSE < TRUE) become integers in NetIR.
    if (logical && (op == net::BinaryOp::Lt || op == net::BinaryOp::Le ||
                    op == net::BinaryOp::Gt || op == net::BinaryOp::Ge)) {
      l = b.cond(l, b.intLit(1, e->loc), b.intLit(0, e->loc), e->loc);
      r = b.cond(r, b.intLit(1, e->loc), b.intLit(0, e->loc), e->loc);
    }
    NExpr *v = b.binary(op, l, r, e->loc);
    if (op == net::BinaryOp::Add || op == net::BinaryOp::Sub ||
        op == net::BinaryOp::Mul || op == net::BinaryOp::Div)
      v = wrapTo(v, e->type, rangeOf(e), e->loc);
    return v;
  }
  case ExprKind::Call:
    if (e->callee)
      return functionCall(e, f, pre);
    return stdCall(e, f, pre);
  }
  refuse(e->loc, "unsupported expression");
}

NExpr *Lowering::convert(NExpr *v, const PType *from, const PType *to,
                         SMLoc at) {
  from = from && from->isSubrange ? from->base : from;
  to = to && to->isSubrange ? to->base : to;
  if (!from || from->kind == PTypeKind::AnyInt)
    from = to;
  if (to->kind == PTypeKind::Bool) {
    if (from->kind == PTypeKind::Bool)
      return v;
    return b.binary(net::BinaryOp::Ne, v, b.intLit(0, at), at);
  }
  if (from->kind == PTypeKind::Bool && to->kind == PTypeKind::Int)
    return b.cond(v, b.intLit(1, at), b.intLit(0, at), at);
  if (from->kind == PTypeKind::Int && to->kind == PTypeKind::Int)
    return wrapTo(v, to, {from->lo, from->hi, true}, at);
  if (from->kind == PTypeKind::Time && to->kind == PTypeKind::Int) {
    // TIME converts to milliseconds.
    if (tickNs % 1000000 != 0)
      refuse(at, "TIME to integer conversion gives milliseconds, but a tick "
                 "is not a whole number of milliseconds (choose "
                 "--timescale)");
    NExpr *ms =
        b.binary(net::BinaryOp::Mul, v, b.intLit(tickNs / 1000000, at), at);
    return wrapTo(ms, to, {0, 0, false}, at);
  }
  if (from->kind == PTypeKind::Int && to->kind == PTypeKind::Time) {
    if (1000000 % tickNs != 0)
      refuse(at, "integer to TIME conversion reads milliseconds, but a "
                 "millisecond is not a whole number of ticks");
    return b.binary(net::BinaryOp::Mul, v, b.intLit(1000000 / tickNs, at), at);
  }
  if (from->kind == to->kind && from->kind == PTypeKind::Time)
    return v;
  refuse(at, "conversion from " + from->str() + " to " + to->str() +
                 " is not supported");
}

NExpr *Lowering::stdCall(Expr *e, Frame &f, Sink &pre) {
  StdFnInfo info = lookupStdFunction(e->name);
  std::vector<NExpr *> a;
  std::vector<Expr *> src;
  for (CallArg &arg : e->args) {
    a.push_back(expr(arg.value, f, pre));
    src.push_back(arg.value);
  }
  SMLoc at = e->loc;
  auto chain = [&](net::BinaryOp op, size_t from, bool wrap) {
    NExpr *r = a[from];
    for (size_t i = from + 1; i < a.size(); ++i)
      r = b.binary(op, r, a[i], at);
    return wrap ? wrapTo(r, e->type, {0, 0, false}, at) : r;
  };
  bool logical =
      !src.empty() && src[0]->type && src[0]->type->kind == PTypeKind::Bool;
  switch (info.fn) {
  case StdFn::Abs:
    return wrapTo(b.call(net::Builtin::Abs, {a[0]}, at), e->type, {0, 0, false},
                  at);
  case StdFn::Min:
  case StdFn::Max: {
    net::Builtin fn =
        info.fn == StdFn::Min ? net::Builtin::Min : net::Builtin::Max;
    NExpr *r = a[0];
    for (size_t i = 1; i < a.size(); ++i)
      r = b.call(fn, {r, a[i]}, at);
    return r;
  }
  case StdFn::Limit:
    return b.call(net::Builtin::Max,
                  {a[0], b.call(net::Builtin::Min, {a[1], a[2]}, at)}, at);
  case StdFn::Sel:
    return b.cond(a[0], a[2], a[1], at);
  case StdFn::Mux: {
    // An out-of-range K is an error (IEC): storing it into a variable of
    // range 0..n-1 makes the model report it.
    std::string k = unique("MUX_" + std::to_string(++callSites) + ".K");
    PType *range = unit.make<PType>(*elementaryType("DINT"));
    range->name.clear();
    range->isSubrange = true;
    range->base = elementaryType("DINT");
    range->lo = 0;
    range->hi = int64_t(a.size()) - 2;
    declareTemp(k, range, at);
    pre.push_back(b.assign(b.ref(k, at), a[0], at));
    NExpr *r = a.back();
    for (size_t i = a.size() - 1; i-- > 1;)
      r = b.cond(b.binary(net::BinaryOp::Eq, b.ref(k, at),
                          b.intLit(int64_t(i) - 1, at), at),
                 a[i], r, at);
    return r;
  }
  case StdFn::Move:
    return a[0];
  case StdFn::Add:
    return chain(net::BinaryOp::Add, 0, true);
  case StdFn::Mul:
    return chain(net::BinaryOp::Mul, 0, true);
  case StdFn::Sub:
    return chain(net::BinaryOp::Sub, 0, true);
  case StdFn::Div:
    return chain(net::BinaryOp::Div, 0, true);
  case StdFn::Mod:
    return chain(net::BinaryOp::Mod, 0, false);
  case StdFn::And:
    return chain(logical ? net::BinaryOp::And : net::BinaryOp::BitAnd, 0,
                 false);
  case StdFn::Or:
    return chain(logical ? net::BinaryOp::Or : net::BinaryOp::BitOr, 0, false);
  case StdFn::Xor:
    return chain(logical ? net::BinaryOp::Xor : net::BinaryOp::BitXor, 0,
                 false);
  case StdFn::Not: {
    if (logical)
      return b.unary(net::UnaryOp::Not, a[0], at);
    const PType *t = e->type;
    NExpr *n = b.unary(net::UnaryOp::BitNot, a[0], at);
    return t->kind == PTypeKind::Int && !t->isSigned ? maskTo(n, t, at) : n;
  }
  case StdFn::Shl:
  case StdFn::Shr:
  case StdFn::Rol:
  case StdFn::Ror: {
    const PType *t = e->type->isSubrange ? e->type->base : e->type;
    NExpr *x =
        t->isSigned && info.fn != StdFn::Shl ? maskTo(a[0], t, at) : a[0];
    if (info.fn == StdFn::Shl)
      return wrapTo(b.binary(net::BinaryOp::Shl, x, a[1], at), t, {0, 0, false},
                    at);
    if (info.fn == StdFn::Shr)
      return wrapTo(b.binary(net::BinaryOp::Shr, x, a[1], at), t, {0, 0, false},
                    at);
    // Rotations by n mod width.
    NExpr *n = b.binary(net::BinaryOp::Mod, a[1], b.intLit(t->width, at), at);
    NExpr *back = b.binary(net::BinaryOp::Sub, b.intLit(t->width, at), n, at);
    NExpr *left = info.fn == StdFn::Rol ? n : back;
    NExpr *right = info.fn == StdFn::Rol ? back : n;
    NExpr *r =
        b.binary(net::BinaryOp::BitOr,
                 maskTo(b.binary(net::BinaryOp::Shl, x, left, at), t, at),
                 b.binary(net::BinaryOp::Shr, maskTo(x, t, at), right, at), at);
    return wrapTo(r, t, {0, 0, false}, at);
  }
  case StdFn::Gt:
  case StdFn::Ge:
  case StdFn::Eq:
  case StdFn::Le:
  case StdFn::Lt:
  case StdFn::Ne: {
    net::BinaryOp op = info.fn == StdFn::Gt   ? net::BinaryOp::Gt
                       : info.fn == StdFn::Ge ? net::BinaryOp::Ge
                       : info.fn == StdFn::Eq ? net::BinaryOp::Eq
                       : info.fn == StdFn::Le ? net::BinaryOp::Le
                       : info.fn == StdFn::Lt ? net::BinaryOp::Lt
                                              : net::BinaryOp::Ne;
    NExpr *r = b.binary(op, a[0], a[1], at);
    for (size_t i = 2; i < a.size(); ++i)
      r = b.binary(net::BinaryOp::And, r, b.binary(op, a[i - 1], a[i], at), at);
    return r;
  }
  case StdFn::Convert:
    return convert(a[0], src[0]->type, info.to, at);
  case StdFn::RealMath:
    refuse(at, "'" + e->name +
                   "' is REAL arithmetic, which is not "
                   "supported");
  case StdFn::StringOp:
    refuse(at, "string function '" + e->name + "' is not supported");
  case StdFn::Refused:
  case StdFn::None:
    break;
  }
  refuse(at, "standard function '" + e->name + "' is not supported");
}

//===----------------------------------------------------------------------===//
// Calls
//===----------------------------------------------------------------------===//

NExpr *Lowering::functionCall(Expr *call, Frame &f, Sink &pre) {
  Pou *fn = call->callee;
  std::string prefix =
      unique(sanitize(fn->name) + "_" + std::to_string(++callSites)) + ".";
  Frame nf;
  nf.pou = fn;
  nf.prefix = prefix;
  nf.external = false;
  if (mayJump(fn->body, false)) {
    nf.returnFlag = prefix + "_return";
    declareTemp(nf.returnFlag, elementaryType("BOOL"), call->loc);
    pre.push_back(b.assign(b.ref(nf.returnFlag, call->loc),
                           b.boolLit(false, call->loc), call->loc));
  }
  // Locals and the result live in variables of this call site, reset at
  // the end of the scan (functions have no memory).
  std::vector<VarDecl *> locals = fn->vars;
  locals.push_back(fn->resultVar);
  std::map<std::string, CallArg *> byName;
  for (CallArg &a : call->args)
    byName[StringRef(a.name).upper()] = &a;
  for (VarDecl *v : locals) {
    if (v->section == VarSection::External)
      continue;
    auto given = byName.find(StringRef(v->name).upper());
    if (v->section == VarSection::InOut) {
      nf.aliases[v] = lvalue(given->second->value, f, pre);
      continue;
    }
    std::string name = prefix + sanitize(v->name);
    declareTemp(name, v->type, v->loc);
    NExpr *init;
    if (given != byName.end() && !given->second->isOutput)
      init = expr(given->second->value, f, pre);
    else
      init = initialValue(v, v->typeSyntax ? v->typeSyntax->init : nullptr,
                          v->type);
    if (init)
      assign(b.ref(name, v->loc), init, v->type,
             given != byName.end() && !given->second->isOutput
                 ? given->second->value
                 : nullptr,
             pre, call->loc);
  }
  enabledBody(fn, prefix, call, nf, pre);
  for (CallArg &a : call->args)
    if (a.isOutput) {
      NExpr *v = b.ref(prefix + sanitize(a.name), a.loc);
      if (a.negated)
        v = b.unary(net::UnaryOp::Not, v, a.loc);
      pre.push_back(b.assign(lvalue(a.value, f, pre), v, a.loc));
    }
  return b.ref(prefix + sanitize(fn->name), call->loc);
}

/// The body of a called function or FB under IEC's EN/ENO rule: with EN
/// FALSE the body does not run and ENO is FALSE; otherwise ENO starts TRUE
/// and the body may clear it. EN is TRUE when the call does not give it.
void Lowering::enabledBody(Pou *callee, const std::string &prefix, Expr *call,
                           Frame &nf, Sink &out) {
  VarDecl *en = callee->find("EN"), *eno = callee->find("ENO");
  if (en && en->section != VarSection::Input)
    en = nullptr;
  if (eno && eno->section != VarSection::Output)
    eno = nullptr;
  SMLoc at = call->loc;
  if (en) {
    bool given = false;
    for (CallArg &a : call->args)
      given |= !a.isOutput && sameName(a.name, "EN");
    if (!given)
      out.push_back(
          b.assign(b.ref(prefix + "EN", at), b.boolLit(true, at), at));
  }
  if (eno)
    out.push_back(b.assign(b.ref(prefix + "ENO", at),
                           en ? b.ref(prefix + "EN", at) : b.boolLit(true, at),
                           at));
  if (!en) {
    body(callee->body, nf, out, {});
    return;
  }
  Sink guarded;
  body(callee->body, nf, guarded, {});
  net::IfArm arm{b.ref(prefix + "EN", at),
                 design.copy(llvm::ArrayRef<NStmt *>(guarded))};
  out.push_back(b.ifStmt({arm}, false, {}, at));
}

void Lowering::noteClockBound(const std::string &member, Expr *value, Frame &f,
                              SMLoc at) {
  // A timer's bounding input (PT) must be a constant wherever it is set:
  // its largest value is the cap of the timer's clock.
  auto it = clockOfBound.find(member);
  if (it == clockOfBound.end())
    return;
  ClockUse &cu = clocks[it->second];
  std::optional<int64_t> c = constValue(value, f);
  if (!c)
    refuse(at, cu.member + " of timer '" + cu.path +
                   "' must be a constant (it bounds the timer's clock)");
  cu.cap = std::max(cu.cap, *c);
}

void Lowering::fbCall(Expr *call, Frame &f, Sink &out) {
  Expr callee(ExprKind::Name, call->loc);
  callee.var = call->var;
  callee.name = call->name;
  std::string path = instancePath(&callee, f);
  Pou *fb = call->var->type->fb;
  InstanceUse &use = instanceUses[path];
  ++use.calls;
  Frame nf;
  nf.pou = fb;
  nf.prefix = path + ".";
  if (mayJump(fb->body, false)) {
    nf.returnFlag = path + "._return";
    if (mod->lookup(nf.returnFlag).kind == net::SymKind::None)
      declareTemp(nf.returnFlag, elementaryType("BOOL"), call->loc);
    out.push_back(b.assign(b.ref(nf.returnFlag, call->loc),
                           b.boolLit(false, call->loc), call->loc));
  }
  for (CallArg &a : call->args) {
    if (a.isOutput)
      continue;
    VarDecl *p = fb->find(a.name);
    if (p->section == VarSection::InOut) {
      nf.aliases[p] = lvalue(a.value, f, out);
      continue;
    }
    ++use.given[sanitize(p->name)];
    std::string member = path + "." + sanitize(p->name);
    NExpr *v = expr(a.value, f, out);
    if (p->edge) {
      // x : BOOL R_EDGE sees TRUE only at a rising edge of the argument.
      NExpr *prev = b.ref(member + ".prev", a.loc);
      NExpr *edge =
          p->edge == 'R'
              ? b.binary(net::BinaryOp::And, v,
                         b.unary(net::UnaryOp::Not, prev, a.loc), a.loc)
              : b.binary(net::BinaryOp::And,
                         b.unary(net::UnaryOp::Not, v, a.loc),
                         b.ref(member + ".prev", a.loc), a.loc);
      out.push_back(b.assign(b.ref(member, a.loc), edge, a.loc));
      out.push_back(b.assign(b.ref(member + ".prev", a.loc), v, a.loc));
      continue;
    }
    assign(b.ref(member, a.loc), v, p->type, a.value, out, a.loc);
    noteClockBound(member, a.value, f, a.loc);
  }
  for (VarDecl *v : fb->vars)
    if (v->edge) {
      bool given = false;
      for (CallArg &a : call->args)
        given |= !a.isOutput && sameName(a.name, v->name);
      // No new value: no edge.
      if (!given)
        out.push_back(b.assign(b.ref(path + "." + sanitize(v->name), v->loc),
                               b.boolLit(false, v->loc), v->loc));
    }
  for (VarDecl *v : fb->vars)
    if (v->section == VarSection::Temp &&
        v->type->kind != PTypeKind::FunctionBlock)
      if (NExpr *init = defaultValue(v->type, v->loc))
        out.push_back(b.assign(b.ref(path + "." + sanitize(v->name), v->loc),
                               init, v->loc));
  enabledBody(fb, path + ".", call, nf, out);
  for (CallArg &a : call->args)
    if (a.isOutput) {
      std::string member = path + "." + sanitize(a.name);
      externallyRead.insert(member);
      NExpr *v = b.ref(member, a.loc);
      if (a.negated)
        v = b.unary(net::UnaryOp::Not, v, a.loc);
      out.push_back(b.assign(lvalue(a.value, f, out), v, a.loc));
    }
}

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

bool Lowering::mayJump(const StmtList &l, bool loopLevel) {
  for (Stmt *s : l) {
    switch (s->kind) {
    case StmtKind::Return:
      return true;
    case StmtKind::Exit:
    case StmtKind::Continue:
      if (loopLevel)
        return true;
      break;
    case StmtKind::If:
      for (auto &[c, body] : s->arms)
        if (mayJump(body, loopLevel))
          return true;
      if (mayJump(s->elseBody, loopLevel))
        return true;
      break;
    case StmtKind::Case:
      for (auto &arm : s->caseArms)
        if (mayJump(arm.body, loopLevel))
          return true;
      if (mayJump(s->elseBody, loopLevel))
        return true;
      break;
    case StmtKind::For:
    case StmtKind::While:
    case StmtKind::Repeat:
      // EXIT/CONTINUE inside bind to the inner loop; RETURN still escapes.
      if (mayJump(s->body, false))
        return true;
      break;
    default:
      break;
    }
  }
  return false;
}

void Lowering::assign(NExpr *target, NExpr *value, const PType *targetType,
                      Expr *valueExpr, Sink &out, SMLoc at) {
  if (targetType && targetType->kind == PTypeKind::Bool && valueExpr &&
      valueExpr->type && valueExpr->type->kind == PTypeKind::AnyInt)
    value = b.boolLit(valueExpr->intValue != 0, at);
  out.push_back(b.assign(target, value, at));
}

void Lowering::body(StmtList &list, Frame &f, Sink &out,
                    const std::vector<LoopCtx> &loops) {
  for (size_t i = 0; i < list.size(); ++i) {
    Stmt *s = list[i];
    previous = i ? list[i - 1] : nullptr;
    stmt(s, f, out, loops);
    if (i + 1 == list.size())
      break;
    StmtList one{s};
    if (!mayJump(one, !loops.empty()))
      continue;
    // The rest runs only if no RETURN/EXIT/CONTINUE has been taken.
    NExpr *taken = nullptr;
    auto add = [&](const std::string &flag) {
      if (flag.empty())
        return;
      NExpr *r = b.ref(flag, s->loc);
      taken = taken ? b.binary(net::BinaryOp::Or, taken, r, s->loc) : r;
    };
    add(f.returnFlag);
    if (!loops.empty()) {
      add(loops.back().exitFlag);
      add(loops.back().continueFlag);
    }
    Sink rest;
    StmtList tail(list.begin() + i + 1, list.end());
    body(tail, f, rest, loops);
    if (!taken) {
      out.insert(out.end(), rest.begin(), rest.end());
      return;
    }
    net::IfArm arm{b.unary(net::UnaryOp::Not, taken, s->loc),
                   design.copy(llvm::ArrayRef<NStmt *>(rest))};
    out.push_back(b.ifStmt({arm}, false, {}, s->loc));
    return;
  }
}

/// An upper bound on the iterations of a WHILE or REPEAT loop of the form
///   i := c0;  WHILE i < C DO ... i := i + s; ... END_WHILE
///   i := c0;  REPEAT ... i := i + s; ... UNTIL i >= C END_REPEAT
/// (any of < <= > >= <>, the counter on either side, s of either sign):
/// the counter is set to a constant just before the loop, changed by
/// exactly one top-level `i := i +/- s` in the body and written nowhere
/// else in it, and compared with a constant. Null when no bound is proved.
std::optional<int64_t> Lowering::loopBound(Stmt *loop, Stmt *before, Frame &f) {
  Expr *cond = loop->value;
  if (!cond || cond->kind != ExprKind::Binary)
    return std::nullopt;
  Op op = cond->op;
  Expr *lhs = cond->operands[0], *rhs = cond->operands[1];
  if (lhs->kind != ExprKind::Name || !lhs->var) {
    std::swap(lhs, rhs);
    static const std::map<Op, Op> mirror = {{Op::Lt, Op::Gt}, {Op::Gt, Op::Lt},
                                            {Op::Le, Op::Ge}, {Op::Ge, Op::Le},
                                            {Op::Ne, Op::Ne}, {Op::Eq, Op::Eq}};
    auto m = mirror.find(op);
    if (m == mirror.end())
      return std::nullopt;
    op = m->second;
  }
  if (lhs->kind != ExprKind::Name || !lhs->var)
    return std::nullopt;
  VarDecl *i = lhs->var;
  std::optional<int64_t> limit = constValue(rhs, f);
  if (!limit)
    return std::nullopt;
  // The constant start.
  if (!before || before->kind != StmtKind::Assign ||
      before->target->kind != ExprKind::Name || before->target->var != i)
    return std::nullopt;
  std::optional<int64_t> start = constValue(before->value, f);
  if (!start)
    return std::nullopt;
  // The one step.
  std::optional<int64_t> step;
  StmtList others;
  for (Stmt *st : loop->body) {
    if (st->kind == StmtKind::Assign && st->target->kind == ExprKind::Name &&
        st->target->var == i && st->value->kind == ExprKind::Binary &&
        (st->value->op == Op::Add || st->value->op == Op::Sub) &&
        st->value->operands[0]->kind == ExprKind::Name &&
        st->value->operands[0]->var == i && !step) {
      step = constValue(st->value->operands[1], f);
      if (!step)
        return std::nullopt;
      if (st->value->op == Op::Sub)
        step = -*step;
      continue;
    }
    others.push_back(st);
  }
  if (!step || *step == 0)
    return std::nullopt;
  std::set<VarDecl *> w;
  collectWritten(others, w);
  if (w.count(i))
    return std::nullopt;
  // Iterations while the condition holds (WHILE) or until it holds
  // (REPEAT, at least one).
  bool isWhile = loop->kind == StmtKind::While;
  auto holds = [&](int64_t v) {
    switch (op) {
    case Op::Lt:
      return v < *limit;
    case Op::Le:
      return v <= *limit;
    case Op::Gt:
      return v > *limit;
    case Op::Ge:
      return v >= *limit;
    case Op::Ne:
      return v != *limit;
    case Op::Eq:
      return v == *limit;
    default:
      return false;
    }
  };
  const int64_t kMax = 100000;
  int64_t v = *start;
  for (int64_t n = 0; n <= kMax; ++n) {
    if (isWhile ? !holds(v) : (n > 0 && holds(v)))
      return n;
    v += *step;
  }
  return std::nullopt;
}

void Lowering::stmt(Stmt *s, Frame &f, Sink &out,
                    const std::vector<LoopCtx> &loops) {
  auto flagVar = [&](const char *what) {
    std::string name =
        unique(std::string("_") + what + std::to_string(++flags));
    declareTemp(name, elementaryType("BOOL"), s->loc);
    return name;
  };
  switch (s->kind) {
  case StmtKind::Assign: {
    NExpr *value = expr(s->value, f, out);
    if (s->target->kind == ExprKind::BitAccess) {
      // x.3 := v  is  x := v ? x | 8 : x & ~8  (masked to x's width).
      Expr *base = s->target->base();
      NExpr *target = lvalue(base, f, out);
      const PType *t = base->type->isSubrange ? base->type->base : base->type;
      int64_t bit = int64_t(1) << s->target->intValue;
      NExpr *set = b.binary(net::BinaryOp::BitOr, lvalue(base, f, out),
                            b.intLit(bit, s->loc), s->loc);
      NExpr *clear = b.binary(net::BinaryOp::BitAnd, lvalue(base, f, out),
                              b.intLit(~bit, s->loc), s->loc);
      NExpr *r =
          b.cond(value, wrapTo(set, t, {0, 0, false}, s->loc), clear, s->loc);
      out.push_back(b.assign(target, r, s->loc));
      return;
    }
    NExpr *target = lvalue(s->target, f, out);
    if (auto *r = llvm::dyn_cast<net::Ref>(target))
      noteClockBound(r->name.str(), s->value, f, s->loc);
    assign(target, value, s->target->type, s->value, out, s->loc);
    return;
  }
  case StmtKind::Call: {
    Expr *c = s->value;
    if (c->var) {
      fbCall(c, f, out);
      return;
    }
    if (c->callee) {
      functionCall(c, f, out);
      return;
    }
    Sink pre;
    expr(c, f, pre); // a standard function whose result is dropped
    out.insert(out.end(), pre.begin(), pre.end());
    return;
  }
  case StmtKind::If: {
    // Conditions after the first that need hoisted calls start a nested IF
    // in the ELSE branch, so their calls run only when reached.
    std::function<void(size_t, Sink &)> build = [&](size_t from, Sink &dst) {
      std::vector<net::IfArm> arms;
      for (size_t k = from; k < s->arms.size(); ++k) {
        Sink pre;
        NExpr *c = expr(s->arms[k].first, f, pre);
        if (!pre.empty() && k != from) {
          // Finish this IF with an ELSE holding the rest.
          Sink elseBody;
          build(k, elseBody);
          dst.push_back(b.ifStmt(arms, true,
                                 design.copy(llvm::ArrayRef<NStmt *>(elseBody)),
                                 s->loc));
          return;
        }
        dst.insert(dst.end(), pre.begin(), pre.end());
        Sink armBody;
        body(s->arms[k].second, f, armBody, loops);
        arms.push_back({c, design.copy(llvm::ArrayRef<NStmt *>(armBody))});
      }
      Sink elseBody;
      body(s->elseBody, f, elseBody, loops);
      dst.push_back(b.ifStmt(arms, s->hasElse && !elseBody.empty(),
                             design.copy(llvm::ArrayRef<NStmt *>(elseBody)),
                             s->loc));
    };
    build(0, out);
    return;
  }
  case StmtKind::Case: {
    NExpr *sel = expr(s->value, f, out);
    std::vector<net::CaseArm> arms;
    for (auto &arm : s->caseArms) {
      std::vector<net::CaseLabel> labels;
      for (auto &l : arm.labels) {
        auto label = [&](Expr *e) -> NExpr * {
          if (e->enumValue >= 0)
            return b.ref(sanitize(e->type->name) + "#" +
                             sanitize(e->type->enumerators[e->enumValue]),
                         e->loc);
          std::optional<int64_t> c = constValue(e, f);
          if (!c)
            refuse(e->loc, "CASE label must be a constant");
          return b.intLit(*c, e->loc);
        };
        labels.push_back({label(l.lo), l.hi ? label(l.hi) : nullptr});
      }
      Sink armBody;
      body(arm.body, f, armBody, loops);
      arms.push_back({design.copy(llvm::ArrayRef<net::CaseLabel>(labels)),
                      design.copy(llvm::ArrayRef<NStmt *>(armBody))});
    }
    Sink elseBody;
    body(s->elseBody, f, elseBody, loops);
    out.push_back(b.caseStmt(sel, arms, s->hasElse,
                             design.copy(llvm::ArrayRef<NStmt *>(elseBody)),
                             s->loc));
    return;
  }
  case StmtKind::For: {
    std::optional<int64_t> from = constValue(s->from, f);
    std::optional<int64_t> to = constValue(s->to, f);
    std::optional<int64_t> by = s->by ? constValue(s->by, f) : int64_t(1);
    if (!from || !to || !by)
      refuse(s->loc, "FOR loop bounds must be constants (netlift unrolls "
                     "nothing it cannot bound)");
    if (*by == 0)
      refuse(s->by->loc, "FOR loop step is 0");
    // Assigning the loop variable inside the body is not allowed (IEC).
    int64_t n = *by > 0 ? (*to >= *from ? (*to - *from) / *by + 1 : 0)
                        : (*from >= *to ? (*from - *to) / -*by + 1 : 0);
    LoopCtx loop;
    if (mayJump(s->body, true)) {
      loop.exitFlag = flagVar("exit");
      loop.continueFlag = flagVar("continue");
      out.push_back(b.assign(b.ref(loop.exitFlag, s->loc),
                             b.boolLit(false, s->loc), s->loc));
    }
    std::vector<LoopCtx> inner = loops;
    inner.push_back(loop);
    NExpr *var = lvalue(s->target, f, out);
    std::string k = "_k" + std::to_string(++loopVars);
    Sink iter;
    NExpr *value = b.binary(net::BinaryOp::Add, b.intLit(*from, s->loc),
                            b.binary(net::BinaryOp::Mul, b.ref(k, s->loc),
                                     b.intLit(*by, s->loc), s->loc),
                            s->loc);
    iter.push_back(b.assign(var, value, s->loc));
    if (!loop.continueFlag.empty())
      iter.push_back(b.assign(b.ref(loop.continueFlag, s->loc),
                              b.boolLit(false, s->loc), s->loc));
    body(s->body, f, iter, inner);
    Sink loopBody;
    NExpr *stop = nullptr;
    if (!loop.exitFlag.empty())
      stop = b.ref(loop.exitFlag, s->loc);
    if (!f.returnFlag.empty())
      stop = stop ? b.binary(net::BinaryOp::Or, stop,
                             b.ref(f.returnFlag, s->loc), s->loc)
                  : b.ref(f.returnFlag, s->loc);
    if (stop) {
      net::IfArm arm{b.unary(net::UnaryOp::Not, stop, s->loc),
                     design.copy(llvm::ArrayRef<NStmt *>(iter))};
      loopBody.push_back(b.ifStmt({arm}, false, {}, s->loc));
    } else {
      loopBody = iter;
    }
    if (n > 0)
      out.push_back(b.forStmt(k, b.intLit(0, s->loc), b.intLit(n - 1, s->loc),
                              loopBody, s->loc));
    // After a loop that ran to its end the variable is one step past it.
    NExpr *final = b.intLit(*from + n * *by, s->loc);
    NStmt *after = b.assign(lvalue(s->target, f, out), final, s->loc);
    if (stop) {
      net::IfArm arm{b.unary(net::UnaryOp::Not, stop, s->loc),
                     design.copy(llvm::ArrayRef<NStmt *>(after))};
      out.push_back(b.ifStmt({arm}, false, {}, s->loc));
    } else {
      out.push_back(after);
    }
    return;
  }
  case StmtKind::While:
  case StmtKind::Repeat: {
    bool isWhile = s->kind == StmtKind::While;
    std::optional<int64_t> n = loopBound(s, previous, f);
    if (!n)
      refuse(s->loc, Twine(isWhile ? "WHILE" : "REPEAT") +
                         " loop refused: netlift cannot prove a bound on its "
                         "iterations (it proves `i := c; WHILE i < C DO ... "
                         "i := i + s; END_WHILE` and the like; otherwise use "
                         "FOR with constant bounds)");
    // for k in 0..n-1 { if <still looping> { body } }: the bound is an
    // upper bound, the condition keeps the iteration count exact.
    LoopCtx loop;
    loop.exitFlag = flagVar("exit");
    if (mayJump(s->body, true))
      loop.continueFlag = flagVar("continue");
    out.push_back(b.assign(b.ref(loop.exitFlag, s->loc),
                           b.boolLit(false, s->loc), s->loc));
    std::vector<LoopCtx> inner = loops;
    inner.push_back(loop);
    Sink iter;
    if (isWhile) {
      // Leaving the loop is an EXIT at the top of the iteration.
      Sink cond;
      NExpr *c = expr(s->value, f, cond);
      iter.insert(iter.end(), cond.begin(), cond.end());
      net::IfArm stop{
          b.unary(net::UnaryOp::Not, c, s->loc),
          design.copy(llvm::ArrayRef<NStmt *>(b.assign(
              b.ref(loop.exitFlag, s->loc), b.boolLit(true, s->loc), s->loc)))};
      iter.push_back(b.ifStmt({stop}, false, {}, s->loc));
    }
    Sink bodyStmts;
    if (!loop.continueFlag.empty())
      bodyStmts.push_back(b.assign(b.ref(loop.continueFlag, s->loc),
                                   b.boolLit(false, s->loc), s->loc));
    body(s->body, f, bodyStmts, inner);
    if (!isWhile) {
      Sink cond;
      NExpr *c = expr(s->value, f, cond);
      bodyStmts.insert(bodyStmts.end(), cond.begin(), cond.end());
      net::IfArm stop{c, design.copy(llvm::ArrayRef<NStmt *>(
                             b.assign(b.ref(loop.exitFlag, s->loc),
                                      b.boolLit(true, s->loc), s->loc)))};
      bodyStmts.push_back(b.ifStmt({stop}, false, {}, s->loc));
    }
    NExpr *running =
        b.unary(net::UnaryOp::Not, b.ref(loop.exitFlag, s->loc), s->loc);
    if (!f.returnFlag.empty())
      running = b.binary(
          net::BinaryOp::And, running,
          b.unary(net::UnaryOp::Not, b.ref(f.returnFlag, s->loc), s->loc),
          s->loc);
    net::IfArm run{running, design.copy(llvm::ArrayRef<NStmt *>(bodyStmts))};
    iter.push_back(b.ifStmt({run}, false, {}, s->loc));
    std::string k = "_k" + std::to_string(++loopVars);
    if (*n > 0)
      out.push_back(b.forStmt(k, b.intLit(0, s->loc), b.intLit(*n - 1, s->loc),
                              iter, s->loc));
    return;
  }
  case StmtKind::Exit:
  case StmtKind::Continue: {
    const LoopCtx &loop = loops.back();
    const std::string &flag =
        s->kind == StmtKind::Exit ? loop.exitFlag : loop.continueFlag;
    out.push_back(
        b.assign(b.ref(flag, s->loc), b.boolLit(true, s->loc), s->loc));
    return;
  }
  case StmtKind::Return:
    if (f.returnFlag.empty())
      refuse(s->loc, "internal: RETURN without a flag");
    out.push_back(
        b.assign(b.ref(f.returnFlag, s->loc), b.boolLit(true, s->loc), s->loc));
    return;
  }
}

//===----------------------------------------------------------------------===//
// Modules
//===----------------------------------------------------------------------===//

static void collectWritten(StmtList &l, std::set<VarDecl *> &w);

static void writtenBy(Expr *target, std::set<VarDecl *> &w) {
  while (target && target->kind != ExprKind::Name)
    target = target->base();
  if (target && target->var)
    w.insert(target->var);
}

static void collectWritten(StmtList &l, std::set<VarDecl *> &w) {
  for (Stmt *s : l) {
    if (s->kind == StmtKind::Assign || s->kind == StmtKind::For)
      writtenBy(s->target, w);
    if (s->kind == StmtKind::Call)
      for (CallArg &a : s->value->args)
        if (a.isOutput)
          writtenBy(a.value, w);
    for (auto &[c, body] : s->arms)
      collectWritten(body, w);
    for (auto &arm : s->caseArms)
      collectWritten(arm.body, w);
    collectWritten(s->elseBody, w);
    collectWritten(s->body, w);
  }
}

/// Names read anywhere in NetIR statements (assignment targets excluded,
/// except the bases of indexed or field targets, which are read-modify-
/// write).
static void readNames(NExpr *e, llvm::StringSet<> &out) {
  if (!e)
    return;
  switch (e->getKind()) {
  case net::ExprKind::Ref:
    out.insert(llvm::cast<net::Ref>(e)->name);
    return;
  case net::ExprKind::Index: {
    auto *x = llvm::cast<net::IndexExpr>(e);
    readNames(x->base, out);
    readNames(x->index, out);
    return;
  }
  case net::ExprKind::Field:
    readNames(llvm::cast<net::FieldExpr>(e)->base, out);
    return;
  case net::ExprKind::Unary:
    readNames(llvm::cast<net::UnaryExpr>(e)->operand, out);
    return;
  case net::ExprKind::Binary:
    readNames(llvm::cast<net::BinaryExpr>(e)->lhs, out);
    readNames(llvm::cast<net::BinaryExpr>(e)->rhs, out);
    return;
  case net::ExprKind::Cond: {
    auto *c = llvm::cast<net::CondExpr>(e);
    readNames(c->cond, out);
    readNames(c->thenExpr, out);
    readNames(c->elseExpr, out);
    return;
  }
  case net::ExprKind::Call:
    for (NExpr *a : llvm::cast<net::CallExpr>(e)->args)
      readNames(a, out);
    return;
  default:
    return;
  }
}

static void readNames(llvm::ArrayRef<NStmt *> body, llvm::StringSet<> &out) {
  for (NStmt *s : body) {
    if (auto *a = llvm::dyn_cast<net::AssignStmt>(s)) {
      readNames(a->value, out);
      if (!llvm::isa<net::Ref>(a->target))
        readNames(a->target, out);
    } else if (auto *i = llvm::dyn_cast<net::IfStmt>(s)) {
      for (const net::IfArm &arm : i->arms) {
        readNames(arm.cond, out);
        readNames(arm.body, out);
      }
      readNames(i->elseBody, out);
    } else if (auto *c = llvm::dyn_cast<net::CaseStmt>(s)) {
      readNames(c->selector, out);
      for (const net::CaseArm &arm : c->arms)
        readNames(arm.body, out);
      readNames(c->elseBody, out);
    } else if (auto *f = llvm::dyn_cast<net::ForStmt>(s)) {
      readNames(f->body, out);
    }
  }
}

std::set<VarDecl *> Lowering::globalsUsedBy(Pou *program) {
  std::set<VarDecl *> globalsUsed;
  std::function<void(Expr *)> scanExpr = [&](Expr *e) {
    if (!e)
      return;
    if (e->var && !e->var->owner && e->var->section == VarSection::Global)
      globalsUsed.insert(e->var);
    for (Expr *o : e->operands)
      scanExpr(o);
    for (CallArg &a : e->args)
      scanExpr(a.value);
  };
  std::set<Pou *> visited;
  std::function<void(Pou *)> scanPou;
  std::function<void(StmtList &)> scanStmts = [&](StmtList &l) {
    for (Stmt *s : l) {
      for (Expr *e : {s->target, s->value, s->from, s->to, s->by})
        scanExpr(e);
      if (s->kind == StmtKind::Call && s->value->var &&
          s->value->var->type->kind == PTypeKind::FunctionBlock)
        scanPou(s->value->var->type->fb);
      if (s->value && s->value->callee)
        scanPou(s->value->callee);
      for (auto &[c, body] : s->arms) {
        scanExpr(c);
        scanStmts(body);
      }
      for (auto &arm : s->caseArms)
        scanStmts(arm.body);
      scanStmts(s->elseBody);
      scanStmts(s->body);
    }
  };
  scanPou = [&](Pou *p) {
    if (!visited.insert(p).second)
      return;
    scanStmts(p->body);
  };
  scanPou(program);
  if (auto it = argumentsOf.find(program); it != argumentsOf.end())
    for (CallArg &a : it->second->args)
      globalsUsed.insert(a.value->var);
  return globalsUsed;
}

void Lowering::startModule(const std::string &name, SMLoc loc) {
  mod = b.createModule(name, false, loc);
  if (!mod)
    refuse(loc, "a module named '" + name + "' exists already");
  resets.clear();
  resetNames.clear();
  instanceMembers.clear();
  externallyRead.clear();
  instanceUses.clear();
  clocks.clear();
  clockOfBound.clear();
  instanceTypes.clear();
  varTypes.clear();
  pendingPragmas.clear();
}

void Lowering::declareProgram(ProgramRun &run) {
  InProgram in(*this, run);
  Pou *program = run.pou;
  run.membersBegin = instanceMembers.size();
  // A module of its own takes the program's pragmas; in a module of
  // several programs they go to the program's scope.
  keepPragmas(run.prefix.empty() ? ""
                                 : run.prefix.substr(0, run.prefix.size() - 1),
              program->attrs);
  // Program arguments: inputs read their global at the start of the scan,
  // outputs write theirs at the end (IEC 61131-3 2.7.1).
  boundInputs.clear();
  if (auto it = argumentsOf.find(program); it != argumentsOf.end())
    for (CallArg &a : it->second->args)
      if (!a.isOutput)
        boundInputs.insert(program->find(a.name));
  // Globals this program uses are variables of the module (declared by
  // the first program of the module that uses them).
  for (VarDecl *g : globalsUsedBy(program)) {
    if (mod->lookup(sanitize(g->name)).kind == net::SymKind::None)
      declareProgramVar(g);
  }
  for (VarDecl *v : program->vars)
    declareProgramVar(v);
  run.membersEnd = instanceMembers.size();
}

/// Clock caps, and the TIME members they bound.
void Lowering::capClocks() {
  auto varIndex = [&](StringRef name) -> int32_t {
    net::Symbol sym = mod->lookup(name);
    return sym.kind == net::SymKind::Var ? int32_t(sym.index) : -1;
  };
  for (auto &[name, cu] : clocks) {
    int32_t x = varIndex(name);
    // The instance's own initial PT counts too (never called: cap 0).
    int32_t bound = varIndex(cu.path + "." + sanitize(cu.member));
    if (bound >= 0)
      if (auto *lit =
              llvm::dyn_cast_or_null<net::IntLit>(mod->vars[bound].init))
        cu.cap = std::max(cu.cap, lit->value);
    int64_t cap = std::max<int64_t>(cu.cap, 1);
    mod->vars[x].type = design.types.getClock(cap);
    // The clock parks at PT when idle, so it starts there too.
    mod->vars[x].init = b.intLit(cap, mod->vars[x].loc);
    for (auto &tm : cu.timeMembers)
      if (int32_t i = varIndex(tm); i >= 0)
        mod->vars[i].type = design.types.getRange(0, cap);
  }
}

/// A pragma goes to the port, variable or instance scope its declaration
/// became. A declaration that became none (a constant, a block without
/// state) gives its pragma to the module, with the declaration's name in
/// front, so that no pragma is lost.
void Lowering::attachPragmas() {
  for (auto &[target, a] : pendingPragmas) {
    if (mod->isAttributeTarget(target))
      b.addAttribute(target, "pragma", a->text, a->loc);
    else
      b.addAttribute("", "pragma", target + ": " + a->text, a->loc);
  }
  pendingPragmas.clear();
}

void Lowering::lowerProgramBody(ProgramRun &run) {
  InProgram in(*this, run);
  Pou *program = run.pou;
  std::vector<std::pair<VarDecl *, VarDecl *>> argIn, argOut; // (var, global)
  if (auto it = argumentsOf.find(program); it != argumentsOf.end())
    for (CallArg &a : it->second->args)
      (a.isOutput ? argOut : argIn)
          .push_back({program->find(a.name), a.value->var});

  Frame top;
  top.pou = program;
  top.prefix = run.prefix;
  top.external = true;
  Sink &action = run.action;
  if (mayJump(program->body, false)) {
    top.returnFlag = unique(run.prefix + "_return");
    declareTemp(top.returnFlag, elementaryType("BOOL"), program->loc);
  }
  for (auto &[v, g] : argIn)
    action.push_back(b.assign(b.ref(run.prefix + sanitize(v->name), v->loc),
                              b.ref(sanitize(g->name), v->loc), v->loc));
  body(program->body, top, action, {});
  for (auto &[v, g] : argOut)
    action.push_back(b.assign(b.ref(sanitize(g->name), v->loc),
                              b.ref(run.prefix + sanitize(v->name), v->loc),
                              v->loc));
}

/// FB members nobody reads after the scan go back to their initial values
/// at its end, so that states do not differ by values no one will see.
void Lowering::deadValueResets(ProgramRun &run) {
  auto varIndex = [&](StringRef name) -> int32_t {
    net::Symbol sym = mod->lookup(name);
    return sym.kind == net::SymKind::Var ? int32_t(sym.index) : -1;
  };
  llvm::StringSet<> read;
  readNames(run.action, read);
  for (size_t k = run.membersBegin; k < run.membersEnd; ++k) {
    const std::string &m = instanceMembers[k];
    bool dead = !read.count(m) && !externallyRead.count(m);
    if (!dead) {
      // An input every call passes and nobody reads from outside.
      size_t dot = m.rfind('.');
      std::string path = m.substr(0, dot), member = m.substr(dot + 1);
      auto use = instanceUses.find(path);
      Pou *fb = instanceTypes[path];
      VarDecl *decl = fb ? fb->find(member) : nullptr;
      if (decl && decl->section == VarSection::Input &&
          use != instanceUses.end() && use->second.calls > 0 &&
          use->second.given[member] == use->second.calls &&
          !externallyRead.count(m))
        dead = true;
      // A timer's bounding input keeps its value: the clock parks at it.
      if (clockOfBound.count(m))
        dead = false;
    }
    if (!dead || resetNames.count(m))
      continue;
    int32_t i = varIndex(m);
    if (i >= 0 && mod->vars[i].init) {
      run.resets.push_back({m, mod->vars[i].init});
      resetNames.insert(m);
    }
  }
}

void Lowering::lowerPrograms(const std::string &name, SMLoc loc,
                             std::vector<ProgramRun> &runs) {
  startModule(name, loc);
  for (ProgramRun &run : runs)
    declareProgram(run);
  for (ProgramRun &run : runs)
    lowerProgramBody(run);
  capClocks();
  attachPragmas();
  for (ProgramRun &run : runs)
    deadValueResets(run);
  // One urgent scan per task, every `period` ticks: its programs in order,
  // each followed by its end-of-scan resets.
  for (size_t i = 0; i < runs.size(); ++i) {
    bool first = true;
    for (size_t j = 0; j < i; ++j)
      first &= runs[j].scan != runs[i].scan;
    if (!first)
      continue;
    Sink action;
    for (ProgramRun &run : runs) {
      if (run.scan != runs[i].scan)
        continue;
      action.insert(action.end(), run.action.begin(), run.action.end());
      for (auto &[var, init] : run.resets)
        action.push_back(b.assign(b.ref(var, init->loc), init, init->loc));
    }
    SMLoc at = runs[i].pou->loc;
    uint32_t period = uint32_t(runs[i].period);
    uint32_t cycle = b.addPlace(runs[i].cycle, 1, 1, at);
    net::PreArc pre{cycle, 1, net::Interval{period, period}};
    net::PostArc post{cycle, 1};
    uint32_t scan = b.addTransition(runs[i].scan, {pre}, {post}, at);
    b.setUrgent(scan);
    b.setAction(scan, action);
  }
}

void Lowering::chooseTick(std::vector<int64_t> ns) {
  ns.insert(ns.end(), opts.extraTimesNs.begin(), opts.extraTimesNs.end());
  if (opts.scanPeriodNs)
    ns.push_back(*opts.scanPeriodNs);
  // A NetIR or hybrid file read with the program (a plant model) fixes
  // the tick already: the program's times are counted in it.
  std::optional<int64_t> designNs;
  if (design.timescale)
    designNs = int64_t(design.timescale->nanoseconds());
  if (opts.timescaleNs && designNs && *opts.timescaleNs != *designNs)
    refuse(SMLoc(), "--timescale " + formatDuration(*opts.timescaleNs) +
                        " differs from the timescale " +
                        design.timescale->str() +
                        " of a model read with the program");
  if (opts.timescaleNs) {
    tickNs = *opts.timescaleNs;
  } else if (designNs) {
    tickNs = *designNs;
  } else {
    int64_t g = 0;
    for (int64_t v : ns)
      g = std::gcd(g, v);
    tickNs = g ? g : 1000000; // no time at all: 1 ms, unused
  }
  if (!design.timescale && (!ns.empty() || opts.timescaleNs)) {
    static const struct {
      const char *unit;
      int64_t ns;
    } units[] = {{"h", 3600000000000}, {"min", 60000000000}, {"s", 1000000000},
                 {"ms", 1000000},      {"us", 1000},         {"ns", 1}};
    for (auto &u : units)
      if (tickNs % u.ns == 0) {
        net::Timescale ts;
        ts.amount = uint64_t(tickNs / u.ns);
        ts.unit = u.unit;
        design.timescale = ts;
        break;
      }
  }
}

bool Lowering::run() {
  // Which programs.
  std::vector<std::pair<Pou *, Task *>> tops;
  auto taskOf = [&](Configuration *c, StringRef name) -> Task * {
    for (Task &t : c->tasks)
      if (sameName(t.name, name))
        return &t;
    return nullptr;
  };
  if (!opts.top.empty()) {
    for (Configuration *c : unit.configs)
      for (ProgramInstance &pi : c->programs)
        if (sameName(pi.name, opts.top) || sameName(pi.typeName, opts.top))
          if (Pou *p = unit.findPou(pi.typeName)) {
            tops.push_back({p, taskOf(c, pi.task)});
            instanceOf.try_emplace(p, &pi, c);
          }
    if (tops.empty()) {
      Pou *p = unit.findPou(opts.top);
      if (!p || p->kind == PouKind::Function || p->isLibrary) {
        diag.error(SMLoc(), "no program, program instance or function block "
                            "named '" +
                                opts.top + "' (--top)");
        return false;
      }
      tops.push_back({p, nullptr});
    }
  } else {
    for (Configuration *c : unit.configs)
      for (ProgramInstance &pi : c->programs)
        if (Pou *p = unit.findPou(pi.typeName)) {
          bool dup = false;
          for (auto &[q, t] : tops)
            dup |= q == p;
          if (!dup) {
            tops.push_back({p, taskOf(c, pi.task)});
            instanceOf.try_emplace(p, &pi, c);
          }
        }
    if (tops.empty())
      for (Pou *p : unit.pous)
        if (p->kind == PouKind::Program)
          tops.push_back({p, nullptr});
    if (tops.empty()) {
      SMLoc at; // not in netlift's own library
      for (Pou *p : unit.pous)
        if (!p->isLibrary) {
          at = p->loc;
          break;
        }
      if (at.isValid()) {
        diag.error(at, "no PROGRAM to translate (use --top NAME to "
                       "translate a function block as the controller)");
        return false;
      }
      at = !unit.types.empty()     ? unit.types[0]->loc
           : !unit.globals.empty() ? unit.globals[0]->loc
                                   : opts.unitStart;
      diag.error(at, "no PROGRAM to translate: the input declares no "
                     "program, function block or function (only types or "
                     "global variables)");
      return false;
    }
  }
  // Program instance arguments bind the program's inputs and outputs to
  // globals; netlift writes one module per program, so a program can have
  // its arguments from one instance only.
  for (Configuration *c : unit.configs)
    for (ProgramInstance &pi : c->programs) {
      Pou *p = unit.findPou(pi.typeName);
      bool translated = false;
      for (auto &[q, t] : tops)
        translated |= q == p;
      if (!translated || pi.args.empty())
        continue;
      auto [it, fresh] = argumentsOf.try_emplace(p, &pi);
      if (!fresh) {
        diag.error(pi.loc, "program '" + p->name +
                               "' has arguments in two instances ('" +
                               it->second->name + "' and '" + pi.name +
                               "'), but netlift writes one module per program");
        return false;
      }
    }

  try {
    // Variables written anywhere are not constants.
    for (Pou *p : unit.pous)
      collectWritten(p->body, written);

    // The tick.
    std::vector<int64_t> ns;
    std::set<Pou *> seen;
    for (auto &[p, task] : tops) {
      collectTimes(p, seen, ns);
      if (task && task->interval && task->interval->kind == ExprKind::TimeLit)
        ns.push_back(task->interval->intValue);
    }
    for (VarDecl *g : unit.globals)
      if (g->typeSyntax)
        initTimes(g->typeSyntax->init, ns);
    chooseTick(std::move(ns));

    std::vector<ProgramRun> runs;
    for (auto &[p, task] : tops) {
      int64_t period = 1;
      SMLoc at = p->loc;
      if (opts.scanPeriodNs) {
        period = ticks(*opts.scanPeriodNs, at);
      } else if (task && task->interval) {
        if (task->interval->kind != ExprKind::TimeLit)
          refuse(task->interval->loc, "task INTERVAL must be a duration "
                                      "literal");
        period = ticks(task->interval->intValue, task->interval->loc);
      }
      if (task && task->single)
        refuse(task->single->loc, "event tasks (SINGLE) are not supported");
      if (period <= 0)
        refuse(at, "the scan period must be positive");
      ProgramRun run;
      run.pou = p;
      run.period = period;
      run.scan = "scan";
      run.cycle = "cycle";
      if (task) {
        run.scan = sanitize(task->name) + ".scan";
        run.cycle = sanitize(task->name) + ".cycle";
      }
      runs.push_back(std::move(run));
    }
    // Programs that share a variable (a global neither constant nor an FB
    // instance) run in one module; otherwise each is a module of its own.
    std::map<VarDecl *, unsigned> users;
    bool shared = false;
    for (ProgramRun &run : runs)
      for (VarDecl *g : globalsUsedBy(run.pou)) {
        if (g->constant || ++users[g] < 2)
          continue;
        if (g->type && g->type->kind == PTypeKind::FunctionBlock)
          refuse(g->loc, "function block instance '" + g->name +
                             "' is a global called by several programs; "
                             "netlift does not model a shared instance");
        shared = true;
      }
    if (!shared) {
      for (ProgramRun &run : runs) {
        std::vector<ProgramRun> one{std::move(run)};
        one[0].scan = "scan";
        one[0].cycle = "cycle";
        lowerPrograms(sanitize(one[0].pou->name), one[0].pou->loc, one);
      }
    } else {
      // One module for them all, named after their configuration: each
      // program's own names under its instance's name, the globals
      // bare, one scan per task (or `scan` alone when there is one task).
      std::string name = "Programs";
      SMLoc at = runs[0].pou->loc;
      if (auto it = instanceOf.find(runs[0].pou); it != instanceOf.end()) {
        name = sanitize(it->second.second->name);
        at = it->second.second->loc;
      }
      bool oneScan = true;
      for (ProgramRun &run : runs) {
        oneScan &= run.scan == runs[0].scan;
        auto it = instanceOf.find(run.pou);
        run.prefix = sanitize(it != instanceOf.end() ? it->second.first->name
                                                     : run.pou->name) +
                     ".";
      }
      if (oneScan)
        for (ProgramRun &run : runs) {
          run.scan = "scan";
          run.cycle = "cycle";
        }
      lowerPrograms(name, at, runs);
    }
  } catch (Refusal &) {
    return false;
  }
  return !diag.hadError();
}

void Lowering::lowerEventBlock(EventDrivenBlock &block) {
  eventDriven = true;
  Pou *pou = block.pou;
  startModule(sanitize(pou->name), pou->loc);
  ProgramRun run;
  run.pou = pou;
  declareProgram(run);
  resets = std::move(run.resets); // its temporaries, reset after reactions
  std::map<std::string, uint32_t> eventPorts;
  for (auto &[name, loc] : block.eventInputs)
    eventPorts[name] =
        b.addPort(name, net::PortKind::Event, net::PortDir::In, nullptr, loc);
  for (auto &[name, loc] : block.eventOutputs)
    eventPorts[name] =
        b.addPort(name, net::PortKind::Event, net::PortDir::Out, nullptr, loc);
  // One event at a time: reactions and sends share this token, so events
  // that arrive together are taken one per successor, never two in one
  // step, and a block never sends while it reacts.
  uint32_t ready = b.addPlace("ready", 1, 1, pou->loc);
  for (EventHandler &h : block.handlers) {
    Frame top;
    top.pou = pou;
    top.external = true;
    Sink action;
    if (mayJump(h.body, false))
      refuse(h.loc, "RETURN or a jump out of an algorithm is not supported "
                    "in an IEC 61499 function block");
    body(h.body, top, action, {});
    // Temporaries are back at their initial values after every reaction.
    if (!h.latch)
      for (auto &[name, init] : resets)
        action.push_back(b.assign(b.ref(name, init->loc), init, init->loc));
    uint32_t t = h.latch ? b.addTransition("recv_" + h.event, {}, {}, h.loc)
                         : b.addTransition("recv_" + h.event,
                                           {net::PreArc{ready, 1, {}}},
                                           {net::PostArc{ready, 1}}, h.loc);
    b.setEvents(t, {net::EventSource{eventPorts.at(h.event), true}});
    b.setAction(t, action);
  }
  for (EventSend &send : block.sends) {
    Frame top;
    top.pou = pou;
    top.external = true;
    Sink pre, action;
    NExpr *guard = expr(send.guard, top, pre);
    if (!pre.empty())
      refuse(send.loc, "internal: a send guard needs statements");
    body(send.body, top, action, {});
    for (auto &[name, init] : resets)
      action.push_back(b.assign(b.ref(name, init->loc), init, init->loc));
    uint32_t t =
        b.addTransition("send_" + send.event, {net::PreArc{ready, 1, {}}},
                        {net::PostArc{ready, 1}}, send.loc);
    b.setGuard(t, guard);
    b.setEmits(t, {eventPorts.at(send.event)});
    b.setUrgent(t);
    b.setAction(t, action);
  }
  capClocks();
  attachPragmas();
  eventDriven = false;
}

bool Lowering::runEventDriven(std::vector<EventDrivenBlock> &blocks) {
  try {
    for (Pou *p : unit.pous)
      collectWritten(p->body, written);
    std::vector<int64_t> ns;
    std::set<Pou *> seen;
    for (EventDrivenBlock &block : blocks) {
      collectTimes(block.pou, seen, ns);
      for (EventHandler &h : block.handlers)
        collectTimesStmts(h.body, seen, ns);
    }
    chooseTick(std::move(ns));
    for (EventDrivenBlock &block : blocks)
      lowerEventBlock(block);
  } catch (Refusal &) {
    return false;
  }
  return !diag.hadError();
}

bool plc::lowerEventDriven(Unit &unit, std::vector<EventDrivenBlock> &blocks,
                           const LowerOptions &opts, DiagEngine &diag,
                           net::Design &design) {
  Lowering l(unit, opts, diag, design);
  return l.runEventDriven(blocks);
}

bool plc::lowerToNet(Unit &unit, const LowerOptions &opts, DiagEngine &diag,
                     net::Design &design) {
  Lowering l(unit, opts, diag, design);
  return l.run();
}
