//===- SfcExpansion.cpp - a Sequential Function Chart as scan code --------===//
//
// One scan of an SFC POU, in the order the statements below are made:
//  1. steps whose elapsed time T is read refresh it (their clocks count
//     ticks, see NETLIFT_SFC_TIMED_STEP in StdLib.cpp);
//  2. every transition is cleared against the step flags and the values
//     at this point (the scan's start): it fires when all its source steps
//     are active, its condition holds and no transition before it in
//     priority order that shares a source step fires;
//  3. the steps take their new activity (deactivated by a firing
//     transition from them, activated by one to them; activating an
//     active step that stays active is a runtime error);
//  4. each action's control (IEC 61131-3's ACTION_CONTROL, specialised to
//     the qualifiers the chart uses) decides whether its body runs.
// With --sfc-dialect codesys, 4 comes before 2 and 3.
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/SfcExpansion.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"

#include <algorithm>
#include <map>

using namespace netlift;
using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

/// Makes the AST of the generated statements.
class Expander : AstMaker {
public:
  Expander(Unit &unit, Pou &pou, DiagEngine &diag)
      : AstMaker(unit), pou(pou), chart(*pou.sfc), diag(diag) {}
  bool run();

private:
  // AST construction (AstMaker's, and these).
  Expr *name(StringRef n, SMLoc at) { return nameRef(n, at); }
  Expr *field(StringRef base, StringRef member, SMLoc at) {
    return AstMaker::field(name(base, at), member, at);
  }
  Expr *timeLit(int64_t ns, SMLoc at) {
    Expr *e = unit.make<Expr>(ExprKind::TimeLit, at);
    e->intValue = ns;
    return e;
  }
  Expr *negate(Expr *a, SMLoc at) { return unary(Op::Not, a, at); }
  Expr *boolToInt(Expr *b, SMLoc at) {
    Expr *c = make(ExprKind::Call, at);
    c->name = "BOOL_TO_INT";
    CallArg a;
    a.value = b;
    a.loc = at;
    c->args.push_back(std::move(a));
    return c;
  }
  /// A fresh copy of `e` (a duration written once, used by several timers).
  Expr *copy(Expr *e) {
    Expr *c = unit.make<Expr>(*e);
    for (Expr *&o : c->operands)
      o = copy(o);
    for (CallArg &a : c->args)
      a.value = copy(a.value);
    return c;
  }
  /// a OR b OR ... (FALSE when empty). Every tree made here is fresh: an
  /// expression node belongs to one place of the AST.
  Expr *anyOf(const std::vector<Expr *> &xs, SMLoc at) {
    if (xs.empty())
      return boolLit(false, at);
    Expr *r = xs[0];
    for (size_t i = 1; i < xs.size(); ++i)
      r = binary(Op::Or, r, xs[i], at);
    return r;
  }
  Stmt *call(StringRef instance,
             std::vector<std::pair<StringRef, Expr *>> inputs, SMLoc at) {
    Expr *c = unit.make<Expr>(ExprKind::Call, at);
    c->name = instance.str();
    for (auto &[n, v] : inputs) {
      CallArg a;
      a.name = n.str();
      a.value = v;
      a.loc = at;
      c->args.push_back(std::move(a));
    }
    Stmt *s = unit.make<Stmt>(StmtKind::Call, at);
    s->value = c;
    return s;
  }
  VarDecl *declare(StringRef n, StringRef type, SMLoc at,
                   VarSection section = VarSection::Var) {
    VarDecl *v = AstMaker::declare(pou, n, type, at, section);
    // The chart's machinery (transition firings, action flags and
    // counters) is not the user's: traces hide it. Steps stay, with X, T.
    v->generated = n.startswith("__SFC_");
    return v;
  }

  bool checkChart();
  void findTimeReads();
  Expr *stepTimeCap(SfcStep *step);
  void expandAction(StringRef action, SMLoc at);

  Pou &pou;
  SfcChart &chart;
  DiagEngine &diag;
  bool failed = false;
  /// Steps by upper-case name.
  std::map<std::string, SfcStep *> steps;
  /// Steps whose T is read somewhere in the POU.
  llvm::StringSet<> timedSteps;
  /// What each step's T is compared with.
  std::map<std::string, std::vector<Expr *>> comparedWith;
  /// Every action and what associates it: (step, association).
  std::vector<std::string> actionOrder;
  std::map<std::string, std::vector<std::pair<SfcStep *, SfcAssociation *>>>
      associations;
  std::map<std::string, SfcAction *> actions;
  /// The flags read of each action: 1 Q, 2 A.
  std::map<std::string, int> flagsRead;
  StmtList out;
};

std::string key(StringRef name) { return name.upper(); }

/// Every expression under the statements of `list`.
void forEachExpr(StmtList &list, llvm::function_ref<void(Expr *)> f) {
  forEachStmt(list, nullptr, [&](Expr *e) { forEachNestedExpr(e, f); });
}

void forEachChartExpr(SfcChart &chart, llvm::function_ref<void(Expr *)> f) {
  for (SfcTransition *t : chart.transitions)
    forEachNestedExpr(t->condition, f);
  for (SfcAction *a : chart.actions)
    forEachExpr(a->body, f);
  for (SfcStep *s : chart.steps)
    for (SfcAssociation &a : s->actions)
      forEachNestedExpr(a.time, f);
}

} // namespace

bool Expander::checkChart() {
  for (SfcStep *s : chart.steps) {
    if (!steps.emplace(key(s->name), s).second) {
      diag.error(s->loc, "step '" + s->name + "' is declared twice");
      return false;
    }
    if (VarDecl *v = pou.find(s->name)) {
      diag.error(s->loc, "step '" + s->name + "' has the name of variable '" +
                             v->name + "'");
      return false;
    }
  }
  if (llvm::none_of(chart.steps, [](SfcStep *s) { return s->initial; })) {
    diag.error(chart.steps[0]->loc,
               "the chart of '" + pou.name + "' has no INITIAL_STEP");
    return false;
  }
  for (SfcTransition *t : chart.transitions) {
    auto known = [&](const std::vector<std::string> &names,
                     const std::vector<SMLoc> &locs) {
      for (size_t i = 0; i < names.size(); ++i)
        if (!steps.count(key(names[i]))) {
          diag.error(locs[i], "transition names step '" + names[i] +
                                  "', which the chart does not declare");
          return false;
        }
      return true;
    };
    if (!known(t->from, t->fromLocs) || !known(t->to, t->toLocs))
      return false;
  }
  for (SfcAction *a : chart.actions) {
    if (!actions.emplace(key(a->name), a).second) {
      diag.error(a->loc, "action '" + a->name + "' is declared twice");
      return false;
    }
    // One name, one thing: `A.X` must say whether it is a step or not.
    if (steps.count(key(a->name))) {
      diag.error(a->loc, "action '" + a->name + "' has the name of a step");
      return false;
    }
  }
  for (SfcStep *s : chart.steps)
    for (SfcAssociation &a : s->actions) {
      auto &list = associations[key(a.action)];
      if (list.empty())
        actionOrder.push_back(a.action);
      list.push_back({s, &a});
    }
  // The 3rd edition's action flags: A.Q (the action control's Q) and A.A
  // (the body runs: Q, the final run, a pulse) become variables of the
  // action's control, kept from scan to scan once read.
  bool bad = false;
  forEachChartExpr(chart, [&](Expr *e) {
    if (bad || e->kind != ExprKind::Field ||
        e->base()->kind != ExprKind::Name ||
        !actions.count(key(e->base()->name)))
      return;
    SfcAction *a = actions[key(e->base()->name)];
    bool q = sameName(e->name, "Q");
    if (!q && !sameName(e->name, "A")) {
      diag.error(e->loc, "'" + e->base()->name + "." + e->name +
                             "': an action's flags are Q and A");
      bad = true;
      return;
    }
    flagsRead[key(a->name)] |= q ? 1 : 2;
    e->kind = ExprKind::Name;
    e->name = "__SFC_" + a->name + (q ? "_Q" : "_A");
    e->operands.clear();
  });
  if (bad)
    return false;
  for (SfcAction *a : chart.actions)
    if (!associations.count(key(a->name)))
      diag.warning(a->loc, "action '" + a->name +
                               "' is associated with no step: it never runs");
  return true;
}

void Expander::findTimeReads() {
  auto stepTime = [&](Expr *e) {
    return e->kind == ExprKind::Field && sameName(e->name, "T") &&
                   e->base()->kind == ExprKind::Name &&
                   steps.count(key(e->base()->name))
               ? key(e->base()->name)
               : std::string();
  };
  forEachChartExpr(chart, [&](Expr *e) {
    if (std::string s = stepTime(e); !s.empty())
      timedSteps.insert(s);
    if (e->kind != ExprKind::Binary ||
        (e->op != Op::Eq && e->op != Op::Ne && e->op != Op::Lt &&
         e->op != Op::Le && e->op != Op::Gt && e->op != Op::Ge))
      return;
    for (int side = 0; side < 2; ++side)
      if (std::string s = stepTime(e->operands[side]); !s.empty())
        comparedWith[s].push_back(e->operands[1 - side]);
  });
}

/// A step's elapsed time stops counting at twice the largest value it is
/// compared with (each comparison is then exact), computed at every scan
/// from what it is compared with; the clock's bound is that expression's
/// bound (a preset from an input without a range has none, as for TON).
/// A step whose T is only read, never compared, counts to twice the
/// longest duration the POU writes.
Expr *Expander::stepTimeCap(SfcStep *step) {
  SMLoc at = step->loc;
  std::vector<Expr *> limits;
  for (Expr *e : comparedWith[key(step->name)])
    limits.push_back(copy(e));
  if (limits.empty()) {
    int64_t longest = 0;
    auto see = [&](Expr *e) {
      if (e->kind == ExprKind::TimeLit)
        longest = std::max(longest, e->intValue);
    };
    forEachChartExpr(chart, see);
    for (VarDecl *v : pou.vars)
      if (v->typeSyntax && v->typeSyntax->init &&
          v->typeSyntax->init->kind == Initializer::Value)
        forEachNestedExpr(v->typeSyntax->init->value, see);
    if (longest == 0) {
      diag.error(at, "the chart reads the elapsed time of step '" + step->name +
                         "' (.T), but '" + pou.name +
                         "' neither compares it with anything nor writes a "
                         "duration to bound it");
      return nullptr;
    }
    limits.push_back(timeLit(longest, at));
  }
  if (limits.size() == 1)
    limits.push_back(copy(limits[0]));
  Expr *max = unit.make<Expr>(ExprKind::Call, at);
  max->name = "MAX";
  for (Expr *l : limits) {
    CallArg a;
    a.value = l;
    a.loc = at;
    max->args.push_back(std::move(a));
  }
  Expr *two = unit.make<Expr>(ExprKind::IntLit, at);
  two->intValue = 2;
  return binary(Op::Mul, max, two, at);
}

void Expander::expandAction(StringRef actionName, SMLoc at) {
  auto &list = associations[key(actionName)];
  std::string base = "__SFC_" + actionName.str();
  // The qualifiers' inputs: the new step flags of the steps associating
  // the action with each.
  std::map<std::string, std::vector<std::pair<std::string, SMLoc>>> inputs;
  Expr *time = nullptr;
  std::string timeText;
  for (auto &[step, a] : list) {
    inputs[a->qualifier].push_back({step->name, a->loc});
    if (a->time) {
      // IEC's action control has one time input per action.
      std::string text = a->time->kind == ExprKind::TimeLit
                             ? std::to_string(a->time->intValue)
                             : a->time->name;
      if (time && text != timeText) {
        diag.error(a->loc, "action '" + actionName.str() +
                               "' is given two different times: IEC 61131-3 "
                               "controls an action with one");
        failed = true;
        return;
      }
      time = a->time;
      timeText = text;
    }
  }
  auto in = [&](StringRef q) {
    std::vector<Expr *> flags;
    for (auto &[step, loc] : inputs[q.str()])
      flags.push_back(field(step, "X", loc));
    return anyOf(flags, at);
  };
  auto has = [&](StringRef q) { return inputs.count(q.str()) != 0; };
  std::vector<Expr *> terms;
  // A stored flag: set by `set`, reset (with priority) by R.
  auto stored = [&](StringRef suffix, Expr *set) {
    std::string flag = base + "_" + suffix.str();
    declare(flag, "BOOL", at);
    out.push_back(
        assign(name(flag, at),
               binary(Op::And, binary(Op::Or, name(flag, at), set, at),
                      negate(in("R"), at), at),
               at));
    return flag;
  };
  // A TON on `pt`: its Q.
  auto timer = [&](StringRef suffix, Expr *input) {
    std::string t = base + "_" + suffix.str();
    declare(t, "TON", at);
    out.push_back(call(t, {{"IN", input}, {"PT", copy(time)}}, at));
    return t;
  };
  // An edge of `input` (rising, or falling with `falling`).
  auto edge = [&](StringRef suffix, llvm::function_ref<Expr *()> input,
                  bool falling) {
    std::string m = base + "_" + suffix.str();
    declare(m, "BOOL", at);
    std::string e = m + "_EDGE";
    declare(e, "BOOL", at, VarSection::Temp);
    out.push_back(
        assign(name(e, at),
               falling ? binary(Op::And, name(m, at), negate(input(), at), at)
                       : binary(Op::And, input(), negate(name(m, at), at), at),
               at));
    out.push_back(assign(name(m, at), input(), at));
    return e;
  };
  if (has("N"))
    terms.push_back(in("N"));
  if (has("S"))
    terms.push_back(name(stored("S", in("S")), at));
  if (has("L")) {
    std::string t = timer("L", in("L"));
    terms.push_back(
        binary(Op::And, in("L"), negate(field(t, "Q", at), at), at));
  }
  if (has("D"))
    terms.push_back(field(timer("D", in("D")), "Q", at));
  if (has("P")) {
    auto p = [&] { return in("P"); };
    terms.push_back(name(edge("P", p, false), at));
  }
  if (has("SD")) {
    std::string flag = stored("SD", in("SD"));
    terms.push_back(field(timer("SD_TMR", name(flag, at)), "Q", at));
  }
  if (has("DS")) {
    std::string t = timer("DS_TMR", in("DS"));
    terms.push_back(name(stored("DS", field(t, "Q", at)), at));
  }
  if (has("SL")) {
    std::string flag = stored("SL", in("SL"));
    std::string t = timer("SL_TMR", name(flag, at));
    terms.push_back(
        binary(Op::And, name(flag, at), negate(field(t, "Q", at), at), at));
  }
  // P1 and P0 (3rd edition) run the action once at the step's activation
  // and deactivation without being part of Q.
  std::vector<Expr *> pulses;
  auto p1 = [&] { return in("P1"); };
  auto p0 = [&] { return in("P0"); };
  if (has("P1"))
    pulses.push_back(name(edge("P1", p1, false), at));
  if (has("P0"))
    pulses.push_back(name(edge("P0", p0, true), at));
  auto found = actions.find(key(actionName));
  if (found == actions.end()) {
    // A Boolean variable as the action: it holds whether the action runs
    // (no final scan: a variable has no body to run once more).
    llvm::append_range(terms, pulses);
    Expr *value = anyOf(terms, at);
    // The same value, but a change made while a step resetting the action
    // is active is shown at that step's R association (a trace's `busy:
    // 1 -> 0` points at `busy(R)`, not at the `busy(S)` that set it).
    if (has("R")) {
      Stmt *s = unit.make<Stmt>(StmtKind::If, at);
      for (auto &[step, loc] : inputs["R"])
        s->arms.push_back({field(step, "X", loc),
                           {assign(name(actionName, loc), copy(value), loc)}});
      SMLoc other = at; // the first association that does not reset it
      for (auto &[step, a] : list)
        if (a->qualifier != "R") {
          other = a->loc;
          break;
        }
      s->hasElse = true;
      s->elseBody.push_back(assign(name(actionName, other), value, other));
      out.push_back(s);
      return;
    }
    out.push_back(assign(name(actionName, at), value, at));
    return;
  }
  // Q, the scan after Q falls (the final run of the body) and the pulses
  // run the body.
  // A flag the chart reads (A.Q, A.A) keeps its value between scans, as
  // the action control's outputs do; otherwise it is scan-local.
  int read = flagsRead[key(found->second->name)];
  std::string q = "__SFC_" + found->second->name + "_Q";
  declare(q, "BOOL", at, read & 1 ? VarSection::Var : VarSection::Temp);
  out.push_back(assign(name(q, at), anyOf(terms, at), at));
  std::vector<Expr *> runs = {name(q, at)};
  auto qFlag = [&] { return name(q, at); };
  runs.push_back(name(edge("LAST_Q", qFlag, true), at));
  llvm::append_range(runs, pulses);
  Expr *runsNow = anyOf(runs, at);
  if (read & 2) {
    std::string active = "__SFC_" + found->second->name + "_A";
    declare(active, "BOOL", at);
    out.push_back(assign(name(active, at), runsNow, at));
    runsNow = name(active, at);
  }
  out.push_back(when(runsNow, found->second->body, at));
}

bool Expander::run() {
  if (!checkChart())
    return false;
  findTimeReads();
  std::map<SfcStep *, Expr *> caps;
  for (SfcStep *s : chart.steps)
    if (timedSteps.count(key(s->name)))
      if (!(caps[s] = stepTimeCap(s)))
        return false;
  // One note, at the first step whose time is read, naming them all.
  SfcStep *firstTimed = nullptr;
  std::string timedNames;
  unsigned numTimed = 0;
  for (SfcStep *s : chart.steps)
    if (timedSteps.count(key(s->name))) {
      firstTimed = firstTimed ? firstTimed : s;
      timedNames += (timedNames.empty() ? "'" : ", '") + s->name + "'";
      ++numTimed;
    }
  if (firstTimed)
    diag.note(firstTimed->loc,
              std::string("the elapsed time (.T) of step") +
                  (numTimed > 1 ? "s " : " ") + timedNames +
                  " stops counting at twice the largest value it is "
                  "compared with: comparisons are exact");
  auto isTimed = [&](SfcStep *s) { return timedSteps.count(key(s->name)); };
  for (SfcStep *s : chart.steps) {
    VarDecl *v = declare(
        s->name, isTimed(s) ? "NETLIFT_SFC_TIMED_STEP" : "NETLIFT_SFC_STEP",
        s->loc);
    // The chart for drawings (emit --to dot), as pragmas of the step and
    // transition variables.
    v->attrs.push_back(
        {s->initial ? "netlift sfc_step initial" : "netlift sfc_step", s->loc});
    if (s->initial) {
      auto *init = unit.make<Initializer>(Initializer::Struct, s->loc);
      auto *x = unit.make<Initializer>(Initializer::Value, s->loc);
      x->value = boolLit(true, s->loc);
      init->fields.push_back({"X", x});
      v->typeSyntax->init = init;
    }
  }
  // 1. Elapsed times as of the scan's start.
  for (SfcStep *s : chart.steps)
    if (isTimed(s))
      out.push_back(call(s->name,
                         {{"ACTIVE", field(s->name, "X", s->loc)},
                          {"ACTIVATED_WHILE_ACTIVE", intLit(0, s->loc)},
                          {"RESTART", boolLit(false, s->loc)},
                          {"CAP", copy(caps[s])}},
                         s->loc));
  size_t evolutionStart = out.size();
  // 2. Clearing, in priority order: PRIORITY first (lowest number first),
  // then the order of the text (left to right in a drawing).
  std::vector<size_t> order(chart.transitions.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    int64_t pa = chart.transitions[a]->priority,
            pb = chart.transitions[b]->priority;
    return (pa < 0 ? INT64_MAX : pa) < (pb < 0 ? INT64_MAX : pb);
  });
  llvm::append_range(out, chart.networks);
  std::vector<std::string> fires(chart.transitions.size());
  std::vector<size_t> cleared;
  for (size_t i : order) {
    SfcTransition *t = chart.transitions[i];
    fires[i] = "__SFC_FIRES_" + std::to_string(i + 1);
    VarDecl *f = declare(fires[i], "BOOL", t->loc, VarSection::Temp);
    f->attrs.push_back(
        {"netlift sfc_transition " + llvm::join(t->from, ",") + " -> " +
             llvm::join(t->to, ",") + " : " +
             llvm::join(llvm::split(t->conditionText, '\n'), " "),
         t->loc});
    Expr *c = t->condition;
    for (size_t k = t->from.size(); k-- > 0;)
      c = binary(Op::And, field(t->from[k], "X", t->fromLocs[k]), c, t->loc);
    for (size_t j : cleared) {
      SfcTransition *u = chart.transitions[j];
      bool shares = llvm::any_of(t->from, [&](const std::string &s) {
        return llvm::any_of(
            u->from, [&](const std::string &r) { return sameName(r, s); });
      });
      if (shares)
        c = binary(Op::And, c, negate(name(fires[j], t->loc), t->loc), t->loc);
    }
    out.push_back(assign(name(fires[i], t->loc), c, t->loc));
    cleared.push_back(i);
  }
  // 3. The new activity.
  for (SfcStep *s : chart.steps) {
    SMLoc sl = s->loc;
    std::vector<std::string> into, outOf;
    for (size_t i = 0; i < chart.transitions.size(); ++i) {
      SfcTransition *t = chart.transitions[i];
      auto names = [&](const std::vector<std::string> &v) {
        return llvm::any_of(
            v, [&](const std::string &n) { return sameName(n, s->name); });
      };
      if (names(t->to))
        into.push_back(fires[i]);
      if (names(t->from))
        outOf.push_back(fires[i]);
    }
    if (into.empty() && outOf.empty() && !isTimed(s))
      continue; // never changes
    auto any = [&](const std::vector<std::string> &names) {
      std::vector<Expr *> xs;
      for (const std::string &n : names)
        xs.push_back(name(n, sl));
      return anyOf(xs, sl);
    };
    auto stays = [&] {
      return binary(Op::And, field(s->name, "X", sl), negate(any(outOf), sl),
                    sl);
    };
    Expr *active = binary(Op::Or, stays(), any(into), sl);
    // Unsafe: activated while it stays active, or by two transitions.
    std::vector<Expr *> twice = {binary(Op::And, any(into), stays(), sl)};
    for (size_t i = 0; i < into.size(); ++i)
      for (size_t j = i + 1; j < into.size(); ++j)
        twice.push_back(
            binary(Op::And, name(into[i], sl), name(into[j], sl), sl));
    std::vector<std::pair<StringRef, Expr *>> args = {
        {"ACTIVE", active},
        {"ACTIVATED_WHILE_ACTIVE", boolToInt(anyOf(twice, sl), sl)}};
    if (isTimed(s)) {
      args.push_back({"RESTART", any(into)});
      args.push_back({"CAP", caps[s]});
    }
    out.push_back(call(s->name, args, s->loc));
  }
  // 4. Actions, in the order the chart first names them.
  size_t actionsStart = out.size();
  for (const std::string &a : actionOrder) {
    expandAction(a, associations[key(a)].front().second->loc);
    if (failed)
      return false;
  }
  // CODESYS runs the actions of the activity the scan starts with, then
  // evolves the chart.
  if (unit.sfcDialect == SfcDialect::Codesys)
    std::rotate(out.begin() + evolutionStart, out.begin() + actionsStart,
                out.end());
  pou.body = std::move(out);
  return true;
}

bool netlift::plc::expandSfc(Unit &unit, Pou &pou, DiagEngine &diag) {
  return Expander(unit, pou, diag).run();
}
