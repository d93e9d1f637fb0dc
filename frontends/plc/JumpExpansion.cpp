//===- JumpExpansion.cpp - JMP and labels in ST as structured code --------===//
//
// A body `s0; a: s1; JMP a; b: s2;` becomes (backward jump, so a loop):
//
//   __JMP_SEGMENT := 0;
//   WHILE __JMP_SEGMENT >= 0 DO
//     __JMP_TAKEN := FALSE;
//     CASE __JMP_SEGMENT OF
//       0: s0; IF NOT __JMP_TAKEN THEN __JMP_SEGMENT := 1; END_IF;
//       1: s1; __JMP_SEGMENT := 1; __JMP_TAKEN := TRUE;
//       2: s2; IF NOT __JMP_TAKEN THEN __JMP_SEGMENT := -1; END_IF;
//     END_CASE;
//   END_WHILE;
//
// and with forward jumps only, segment k runs as
// `IF NOT __JMP_TAKEN OR __JMP_SEGMENT = k THEN __JMP_TAKEN := FALSE; sk
// END_IF;`, with no loop (so the exports that refuse unbounded loops still
// take it). Inside a segment, a jump skips what follows it: the statements
// after one that may jump run under IF NOT __JMP_TAKEN, and a jump inside a
// loop leaves it with EXIT (and every enclosing loop of the segment after
// it).
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/JumpExpansion.h"

#include <map>

using namespace netlift;
using namespace netlift::plc;
using llvm::SMLoc;
using llvm::StringRef;

namespace {

constexpr StringRef kSegment = "__JMP_SEGMENT", kTaken = "__JMP_TAKEN";

class JumpExpander : AstMaker {
public:
  JumpExpander(Unit &unit, Pou &pou, DiagEngine &diag)
      : AstMaker(unit), pou(pou), diag(diag) {}
  bool run();

private:
  static bool hasJump(StmtList &list);
  bool check(const StmtList &list, bool inLoop);
  StmtList rewrite(const StmtList &list, bool inLoop);
  Stmt *setSegment(int64_t k, SMLoc at) {
    return assign(nameRef(kSegment, at), intLit(k, at), at);
  }
  Expr *notTaken(SMLoc at) { return unary(Op::Not, nameRef(kTaken, at), at); }

  Pou &pou;
  DiagEngine &diag;
  /// Label (upper case) -> its segment (1...).
  std::map<std::string, int64_t> segments;
  /// The segment being rewritten, and whether a jump goes back.
  int64_t current = 0;
  bool backward = false;
};

/// The nested statement lists of `s`, with whether they are a loop's body.
void forEachNested(Stmt *s, llvm::function_ref<void(StmtList &, bool loop)> f) {
  for (auto &[c, body] : s->arms)
    f(body, false);
  for (CaseArmSyntax &arm : s->caseArms)
    f(arm.body, false);
  f(s->elseBody, false);
  f(s->body, s->kind == StmtKind::For || s->kind == StmtKind::While ||
                 s->kind == StmtKind::Repeat);
}

} // namespace

bool JumpExpander::hasJump(StmtList &list) {
  bool found = false;
  forEachStmt(list, [&](Stmt *s) {
    found |= s->kind == StmtKind::Jump || s->kind == StmtKind::Label;
  });
  return found;
}

// Labels stand at the top level only: the grammar reads `name :` inside
// a structured statement as a case label or a syntax error.
bool JumpExpander::check(const StmtList &list, bool inLoop) {
  for (Stmt *s : list) {
    if (s->kind == StmtKind::Jump &&
        !segments.count(StringRef(s->target->name).upper())) {
      diag.error(s->target->loc, "JMP to '" + s->target->name +
                                     "', which is not a label of this body");
      return false;
    }
    // The segments run inside a loop of netlift's: an EXIT outside the
    // user's loops must not leave it.
    if ((s->kind == StmtKind::Exit || s->kind == StmtKind::Continue) &&
        !inLoop) {
      diag.error(s->loc,
                 StringRef(s->kind == StmtKind::Exit ? "EXIT" : "CONTINUE") +
                     " outside a loop");
      return false;
    }
    bool ok = true;
    forEachNested(s, [&](StmtList &l, bool loop) {
      ok = ok && check(l, inLoop || loop);
    });
    if (!ok)
      return false;
  }
  return true;
}

StmtList JumpExpander::rewrite(const StmtList &list, bool inLoop) {
  StmtList out;
  for (size_t i = 0; i < list.size(); ++i) {
    Stmt *s = list[i];
    if (s->kind == StmtKind::Jump) {
      int64_t target = segments.at(StringRef(s->target->name).upper());
      backward |= target <= current;
      out.push_back(setSegment(target, s->loc));
      out.push_back(
          assign(nameRef(kTaken, s->loc), boolLit(true, s->loc), s->loc));
      if (inLoop)
        out.push_back(unit.make<Stmt>(StmtKind::Exit, s->loc));
      return out; // what follows a jump in its list never runs
    }
    StmtList one = {s};
    if (!hasJump(one)) {
      out.push_back(s);
      continue;
    }
    bool loop = s->kind == StmtKind::For || s->kind == StmtKind::While ||
                s->kind == StmtKind::Repeat;
    forEachNested(
        s, [&](StmtList &l, bool isLoop) { l = rewrite(l, inLoop || isLoop); });
    out.push_back(s);
    if (loop && inLoop) // leave the enclosing loop too
      out.push_back(when(nameRef(kTaken, s->loc),
                         {unit.make<Stmt>(StmtKind::Exit, s->loc)}, s->loc));
    StmtList rest(list.begin() + i + 1, list.end());
    if (!rest.empty())
      out.push_back(when(notTaken(s->loc), rewrite(rest, inLoop), s->loc));
    return out;
  }
  return out;
}

bool JumpExpander::run() {
  if (!hasJump(pou.body))
    return true;
  // Segments: what precedes the first label, then one per label.
  std::vector<StmtList> parts(1);
  std::vector<SMLoc> starts = {pou.loc};
  for (Stmt *s : pou.body) {
    if (s->kind != StmtKind::Label) {
      parts.back().push_back(s);
      continue;
    }
    std::string name = StringRef(s->target->name).upper();
    if (!segments.emplace(name, int64_t(parts.size())).second) {
      diag.error(s->loc, "label '" + s->target->name + "' is defined twice");
      return false;
    }
    parts.emplace_back();
    starts.push_back(s->loc);
  }
  if (!check(pou.body, false))
    return false;
  std::vector<StmtList> rewritten;
  for (size_t k = 0; k < parts.size(); ++k) {
    current = int64_t(k);
    rewritten.push_back(rewrite(parts[k], false));
  }
  SMLoc at = pou.loc;
  declare(pou, kSegment, "DINT", at, VarSection::Temp);
  declare(pou, kTaken, "BOOL", at, VarSection::Temp);
  StmtList body;
  body.push_back(setSegment(0, at));
  body.push_back(assign(nameRef(kTaken, at), boolLit(false, at), at));
  if (!backward) {
    body.insert(body.end(), rewritten[0].begin(), rewritten[0].end());
    for (size_t k = 1; k < rewritten.size(); ++k) {
      SMLoc sk = starts[k];
      Expr *here =
          binary(Op::Eq, nameRef(kSegment, sk), intLit(int64_t(k), sk), sk);
      StmtList seg = {assign(nameRef(kTaken, sk), boolLit(false, sk), sk)};
      seg.insert(seg.end(), rewritten[k].begin(), rewritten[k].end());
      body.push_back(when(binary(Op::Or, notTaken(sk), here, sk), seg, sk));
    }
    pou.body = std::move(body);
    return true;
  }
  Stmt *dispatch = unit.make<Stmt>(StmtKind::Case, at);
  dispatch->value = nameRef(kSegment, at);
  for (size_t k = 0; k < rewritten.size(); ++k) {
    SMLoc sk = starts[k];
    CaseArmSyntax arm;
    arm.labels.push_back({intLit(int64_t(k), sk), nullptr});
    arm.body = rewritten[k];
    int64_t next = k + 1 < rewritten.size() ? int64_t(k + 1) : -1;
    arm.body.push_back(when(notTaken(sk), {setSegment(next, sk)}, sk));
    dispatch->caseArms.push_back(std::move(arm));
  }
  Stmt *loop = unit.make<Stmt>(StmtKind::While, at);
  loop->value = binary(Op::Ge, nameRef(kSegment, at), intLit(0, at), at);
  loop->body = {assign(nameRef(kTaken, at), boolLit(false, at), at), dispatch};
  body.pop_back(); // __JMP_TAKEN is reset in the loop
  body.push_back(loop);
  pou.body = std::move(body);
  return true;
}

bool netlift::plc::expandJumps(Unit &unit, Pou &pou, DiagEngine &diag) {
  return JumpExpander(unit, pou, diag).run();
}
