//===- StPous.cpp - ST POUs and what they hold ----------------------------===//
//
// The AstBuilder's POU level (StAstBuilder.h): programs, function blocks,
// functions, and what a POU holds besides its body — METHODs, PROPERTYs,
// ACTIONs, SFC steps and transitions — and the object-oriented
// declarations (CLASS, INTERFACE, ACTIONS blocks).
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/JumpExpansion.h"
#include "frontends/plc/SfcExpansion.h"
#include "frontends/st/StAstBuilder.h"
#include "frontends/st/StFrontend.h"

#include "llvm/ADT/StringExtras.h"

using namespace netlift;
using namespace netlift::st::detail;

/// ABSTRACT, FINAL and the access specifiers written before a name.
template <typename Mods> static void modifiers(const Mods &mods, Pou *p) {
  for (auto *m : mods) {
    std::string word = StringRef(m->getText()).upper();
    if (word == "ABSTRACT")
      p->isAbstract = true;
    else if (word == "PRIVATE" || word == "PROTECTED" || word == "INTERNAL")
      p->access = word;
  }
}

bool AstBuilder::property(P::PropertyDeclContext *c, Pou *owner) {
  for (auto *a : c->propertyAccessor()) {
    std::string kw = StringRef(a->kw->getText()).upper();
    bool get = kw == "GET";
    if ((!get && kw != "SET") || (a->end->getType() == P::END_GET) != get) {
      refuse(loc(a->kw), "expected GET ... END_GET or SET ... END_SET in "
                         "PROPERTY '" +
                             c->name->getText() + "'");
      return false;
    }
    Pou *acc = unit.make<Pou>();
    acc->kind = PouKind::Function;
    acc->name = c->name->getText();
    acc->loc = loc(a->kw);
    acc->property = get ? 'G' : 'S';
    modifiers(c->accessModifier(), acc);
    modifiers(a->accessModifier(), acc);
    for (auto *vb : a->pouVarBlock())
      varBlock(vb->varBlock(), acc->vars);
    for (VarDecl *v : acc->vars)
      if (v->section == VarSection::Inst)
        v->section = VarSection::Var;
    if (get) {
      acc->resultSyntax = typeSpec0(c->type);
    } else {
      // The value assigned is the accessor's input named like the
      // property.
      auto *v = unit.make<VarDecl>();
      v->name = acc->name;
      v->loc = loc(c->name);
      v->section = VarSection::Input;
      v->typeSyntax = typeSpec0(c->type);
      acc->vars.push_back(v);
    }
    bodyStatements(a->body, acc->body);
    if (failed || !plc::expandJumps(unit, *acc, diag))
      return failed = true, false;
    acc->methodOf = owner;
    owner->methods.push_back(acc);
    unit.pous.push_back(acc);
  }
  return true;
}

/// The parts every POU has: name, pragmas, variable blocks, body.
template <typename Ctx> Pou *AstBuilder::pou(PouKind kind, Ctx *c) {
  Pou *pou = unit.make<Pou>();
  pou->kind = kind;
  pou->name = c->name->getText();
  pou->loc = loc(c->name);
  pou->attrs = pragmasBefore(c->getStart());
  if constexpr (std::is_same_v<Ctx, P::FunctionDeclContext> ||
                std::is_same_v<Ctx, P::MethodDeclContext>) {
    // Without a result type (IEC 61131-3 3rd edition, CODESYS) a function
    // gives its outputs only.
    if (c->result)
      pou->resultSyntax = typeSpec(c->result);
  }
  for (auto *vb : c->pouVarBlock())
    varBlock(vb->varBlock(), pou->vars);
  if constexpr (!std::is_same_v<Ctx, P::MethodDeclContext>)
    for (VarDecl *v : pou->vars)
      if (v->section == VarSection::Inst)
        v->section = VarSection::Var;
  bodyStatements(c->body, pou->body);
  if (skipped)
    if (auto it = skipped->find(c->getStop()->getStartIndex());
        it != skipped->end())
      for (StringRef group : it->second)
        if (!st::parseStatements(group, diag, unit, pou->body)) {
          failed = true; // reported where it is
          return nullptr;
        }
  if (!plc::expandJumps(unit, *pou, diag)) {
    failed = true;
    return nullptr;
  }
  unit.pous.push_back(pou);
  return pou;
}

bool AstBuilder::members(const std::vector<P::FbMemberContext *> &ms,
                         StringRef where, Pou *pou) {
  if (ms.empty())
    return true;
  auto *chart = unit.make<SfcChart>();
  for (auto *m : ms) {
    if (auto *md = m->methodDecl()) {
      if (!method(md, pou))
        return false;
    } else if (auto *pd = m->propertyDecl()) {
      if (!property(pd, pou))
        return false;
    } else if (auto *s = m->sfcStep()) {
      if (!sfcStep(s, *chart))
        return false;
    } else if (auto *t = m->sfcTransition()) {
      if (!sfcTransition(t, *chart, pou))
        return false;
    } else {
      auto *a = m->sfcAction();
      auto *action = unit.make<SfcAction>();
      action->name = a->name->getText();
      action->loc = loc(a->name);
      statements(a->body, action->body);
      if (failed)
        return false;
      chart->actions.push_back(action);
    }
  }
  if (chart->steps.empty() && chart->transitions.empty()) {
    // CODESYS actions: code of the POU run on its instance when called
    // (`A();`, `inst.A();`), as a method without variables.
    for (SfcAction *a : chart->actions) {
      Pou *action = unit.make<Pou>();
      action->kind = PouKind::Function;
      action->name = a->name;
      action->loc = a->loc;
      action->body = std::move(a->body);
      action->isAction = true;
      action->methodOf = pou;
      pou->methods.push_back(action);
      unit.pous.push_back(action);
    }
    return true;
  }
  if (chart->steps.empty()) {
    refuse(pou->loc, "an SFC transition without steps");
    return false;
  }
  if (!pou->body.empty()) {
    refuse(pou->body[0]->loc, "statements in the body of a " + where +
                                  " written in SFC (IEC 61131-3 gives a "
                                  "body one language)");
    return false;
  }
  pou->sfc = chart;
  return plc::expandSfc(unit, *pou, diag) || (failed = true, false);
}

bool AstBuilder::sfcStep(P::SfcStepContext *c, SfcChart &chart) {
  auto *step = unit.make<SfcStep>();
  step->name = c->name->getText();
  step->loc = loc(c->name);
  step->initial = c->kw->getType() == P::INITIAL_STEP;
  for (auto *a : c->actionAssociation()) {
    SfcAssociation assoc;
    assoc.action = a->action->getText();
    assoc.loc = loc(a->action);
    auto args = a->expression();
    size_t i = 0;
    auto nameOf = [](P::ExpressionContext *e) { return e->getText(); };
    static const char *const kQualifiers[] = {"N", "R", "S",  "P",  "P0", "P1",
                                              "L", "D", "SD", "DS", "SL"};
    if (!args.empty()) {
      std::string q = StringRef(nameOf(args[0])).upper();
      if (llvm::is_contained(kQualifiers, q)) {
        assoc.qualifier = q;
        ++i;
      }
    }
    bool timed = llvm::is_contained(
        std::initializer_list<StringRef>{"L", "D", "SD", "DS", "SL"},
        assoc.qualifier);
    if (timed) {
      if (i >= args.size()) {
        refuse(assoc.loc, "action qualifier " + assoc.qualifier +
                              " needs a time (" + assoc.action + "(" +
                              assoc.qualifier + ", T#1s))");
        return false;
      }
      assoc.time = expr(args[i++]);
      if (!assoc.time)
        return false;
    }
    for (; i < args.size(); ++i) {
      auto *p = dynamic_cast<P::PrimaryExprContext *>(args[i]);
      if (!p || !dynamic_cast<P::VariablePrimaryContext *>(p->primary())) {
        refuse(loc(args[i]), "'" + nameOf(args[i]) +
                                 "' is not an action qualifier or an "
                                 "indicator variable");
        return false;
      }
      assoc.indicators.push_back(nameOf(args[i]));
    }
    step->actions.push_back(std::move(assoc));
  }
  chart.steps.push_back(step);
  return true;
}

bool AstBuilder::sfcTransition(P::SfcTransitionContext *c, SfcChart &chart,
                               Pou *pou) {
  auto *t = unit.make<SfcTransition>();
  t->loc = loc(c->kw);
  if (c->name)
    t->name = c->name->getText();
  if (c->priorityKw) {
    if (!StringRef(c->priorityKw->getText()).equals_insensitive("PRIORITY")) {
      refuse(loc(c->priorityKw), "expected PRIORITY := n, found '" +
                                     c->priorityKw->getText() + "'");
      return false;
    }
    if (!st::parseIntegerLiteral(c->priority->getText(), t->priority)) {
      refuse(loc(c->priority), "transition priority out of range");
      return false;
    }
  }
  auto stepSet = [&](P::SfcStepSetContext *s, std::vector<std::string> &names,
                     std::vector<SMLoc> &locs) {
    for (auto *i : s->ident()) {
      names.push_back(i->getText());
      locs.push_back(loc(i));
    }
  };
  stepSet(c->from, t->from, t->fromLocs);
  stepSet(c->to, t->to, t->toLocs);
  if (c->il) {
    // The instruction list between ':' and END_TRANSITION; its current
    // result is the condition.
    if (!unit.instructionListReader) {
      refuse(loc(c->il), "a transition condition in Instruction List is not "
                         "supported here (write it as ':= expression;')");
      return false;
    }
    size_t begin = c->il->getStopIndex() + 1;
    size_t end = c->END_TRANSITION().back()->getSymbol()->getStartIndex();
    StmtList own = std::move(pou->body);
    pou->body.clear();
    Expr *result = nullptr;
    bool ok = unit.instructionListReader(text.substr(begin, end - begin), diag,
                                         unit, pou, &result);
    llvm::append_range(chart.networks, pou->body);
    pou->body = std::move(own);
    if (!ok) {
      failed = true;
      return false;
    }
    if (!result) {
      refuse(loc(c->il), "the instruction list of this transition computes "
                         "no result (start it with LD)");
      return false;
    }
    t->condition = result;
    t->conditionText = "IL";
    chart.transitions.push_back(t);
    return true;
  }
  t->condition = expr(c->cond);
  if (!t->condition)
    return false;
  t->conditionText = text.substr(c->cond->getStart()->getStartIndex(),
                                 c->cond->getStop()->getStopIndex() + 1 -
                                     c->cond->getStart()->getStartIndex())
                         .str();
  chart.transitions.push_back(t);
  return true;
}

Pou *AstBuilder::program(P::ProgramDeclContext *c) {
  Pou *p = pou(PouKind::Program, c);
  if (!p || !members(c->fbMember(), "program", p))
    return nullptr;
  return p;
}

Pou *AstBuilder::functionBlock(P::FunctionBlockDeclContext *c) {
  Pou *p = pou(PouKind::FunctionBlock, c);
  if (!p)
    return nullptr;
  modifiers(c->accessModifier(), p);
  if (c->ext) {
    p->extends = c->ext->getText();
    p->extendsLoc = loc(c->ext);
  }
  if (c->IMPLEMENTS())
    for (auto *q : c->qualifiedName())
      if (q != c->ext)
        p->implements.push_back(q->getText());
  if (!members(c->fbMember(), "function block", p))
    return nullptr;
  return p;
}

Pou *AstBuilder::classDecl(P::ClassDeclContext *c) {
  Pou *p = unit.make<Pou>();
  p->kind = PouKind::FunctionBlock;
  p->name = c->name->getText();
  p->loc = loc(c->name);
  p->attrs = pragmasBefore(c->getStart());
  modifiers(c->accessModifier(), p);
  if (c->ext) {
    p->extends = c->ext->getText();
    p->extendsLoc = loc(c->ext);
  }
  for (auto *vb : c->pouVarBlock())
    varBlock(vb->varBlock(), p->vars);
  for (VarDecl *v : p->vars)
    if (v->section == VarSection::Inst)
      v->section = VarSection::Var;
  if (failed)
    return nullptr;
  unit.pous.push_back(p);
  return members(c->fbMember(), "class", p) ? p : nullptr;
}

Pou *AstBuilder::interfaceDecl(P::InterfaceDeclContext *c) {
  Pou *p = unit.make<Pou>();
  p->kind = PouKind::FunctionBlock;
  p->name = c->name->getText();
  p->loc = loc(c->name);
  p->isInterface = p->isAbstract = true;
  for (auto *q : c->qualifiedName())
    p->implements.push_back(q->getText());
  unit.pous.push_back(p);
  for (auto *m : c->methodDecl()) {
    Pou *method = this->method(m, p);
    if (!method)
      return nullptr;
    method->isAbstract = true;
    if (!method->body.empty()) {
      refuse(loc(m), "a method of an INTERFACE has no body");
      return nullptr;
    }
  }
  for (auto *d : c->propertyDecl())
    if (!property(d, p))
      return nullptr;
  for (Pou *m : p->methods)
    m->isAbstract = true;
  return p;
}

void AstBuilder::actionsBlock(P::ActionsBlockContext *c) {
  Pou *owner = nullptr;
  if (c->owner) {
    owner = unit.findPou(c->owner->getText());
    if (!owner) {
      refuse(loc(c->owner), "ACTIONS for '" + c->owner->getText() +
                                "', which is not declared before them");
      return;
    }
  } else {
    for (Pou *p : unit.pous)
      if (!p->methodOf && !p->isLibrary)
        owner = p;
    if (!owner) {
      refuse(loc(c->ACTIONS()), "ACTIONS without a POU before them");
      return;
    }
  }
  for (auto *a : c->sfcAction()) {
    Pou *action = unit.make<Pou>();
    action->kind = PouKind::Function;
    action->name = a->name->getText();
    action->loc = loc(a->name);
    statements(a->body, action->body);
    if (failed)
      return;
    action->isAction = true;
    action->methodOf = owner;
    owner->methods.push_back(action);
    unit.pous.push_back(action);
  }
}

Pou *AstBuilder::method(P::MethodDeclContext *c, Pou *owner) {
  Pou *m = pou(PouKind::Function, c);
  if (!m)
    return nullptr;
  modifiers(c->accessModifier(), m);
  m->methodOf = owner;
  owner->methods.push_back(m);
  // VAR_INST: kept in the instance between calls; a member of the block
  // under the method's name (`M__x`), which the method's body names.
  std::map<std::string, std::string> renamed;
  for (auto it = m->vars.begin(); it != m->vars.end();) {
    VarDecl *v = *it;
    if (v->section != VarSection::Inst) {
      ++it;
      continue;
    }
    std::string member = m->name + "__" + v->name;
    renamed[StringRef(v->name).upper()] = member;
    v->name = member;
    v->section = VarSection::Var;
    owner->vars.push_back(v);
    it = m->vars.erase(it);
  }
  if (!renamed.empty()) {
    m->varsReordered();
    forEachStmt(m->body, nullptr, [&](Expr *root) {
      forEachNestedExpr(root, [&](Expr *e) {
        if (e->kind == ExprKind::Name && !e->ofThis)
          if (auto r = renamed.find(StringRef(e->name).upper());
              r != renamed.end())
            e->name = r->second;
      });
    });
  }
  return m;
}

Pou *AstBuilder::methodFromBody(P::MethodBodyOnlyContext *c, StringRef name,
                                StringRef resultType, SMLoc at, Pou *owner) {
  Pou *m = unit.make<Pou>();
  m->kind = PouKind::Function;
  m->name = name.str();
  m->loc = at;
  if (!resultType.empty()) {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, at);
    ts->name = resultType.str();
    m->resultSyntax = ts;
  }
  for (auto *vb : c->pouVarBlock())
    varBlock(vb->varBlock(), m->vars);
  for (VarDecl *v : m->vars)
    if (v->section == VarSection::Inst) {
      refuse(v->loc, "VAR_INST in method '" + name +
                         "' written as a body alone (write it as "
                         "METHOD ... END_METHOD)");
      return nullptr;
    }
  bodyStatements(c->body, m->body);
  if (failed || !plc::expandJumps(unit, *m, diag)) {
    failed = true;
    return nullptr;
  }
  m->methodOf = owner;
  owner->methods.push_back(m);
  unit.pous.push_back(m);
  return m;
}

Pou *AstBuilder::function(P::FunctionDeclContext *c) {
  return pou(PouKind::Function, c);
}
