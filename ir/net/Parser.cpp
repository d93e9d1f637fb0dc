//===- Parser.cpp - NetIR text parser: files, types, modules --------------===//
#include "ir/net/ParserImpl.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace netlift;
using namespace netlift::net;
using namespace netlift::net::detail;

bool Parser::parseInt(int64_t &v, StringRef what) {
  if (!tok.is(Tok::Int))
    return errorHere("expected " + what + ", found " + describe());
  if (tok.text.getAsInteger(10, v))
    return errorHere("integer literal '" + tok.text + "' is too large");
  consume();
  return true;
}

bool Parser::parseSignedInt(int64_t &v, StringRef what) {
  bool neg = false;
  if (tok.is(Tok::Minus)) {
    neg = true;
    consume();
  }
  if (!parseInt(v, what))
    return false;
  if (neg)
    v = -v;
  return true;
}

bool Parser::parseUInt32(uint32_t &v, StringRef what, bool allowInf) {
  if (allowInf && tok.isIdent("inf")) {
    v = kInf;
    consume();
    return true;
  }
  if (!tok.is(Tok::Int))
    return errorHere("expected " + what + ", found " + describe());
  uint64_t x;
  if (tok.text.getAsInteger(10, x) || x >= kInf)
    return errorHere("'" + tok.text + "' is too large for " + what +
                     " (at most " + llvm::Twine(kInf - 1) + ")");
  v = uint32_t(x);
  consume();
  return true;
}

bool Parser::parseRateBound(Expr *&e) {
  Lexer before = lex;
  Token beforeTok = tok;
  SMLoc at = tok.loc();
  bool neg = tok.is(Tok::Minus);
  if (neg)
    consume();
  if (tok.isIdent("inf")) {
    consume();
    e = b.realLit(neg ? -INFINITY : INFINITY, at);
    return true;
  }
  lex = before;
  tok = beforeTok;
  return (e = parseExpr()) != nullptr;
}

bool Parser::parseRealBound(double &v) {
  bool neg = false;
  if (tok.is(Tok::Minus)) {
    neg = true;
    consume();
  }
  if (tok.isIdent("inf")) {
    v = INFINITY;
  } else if (tok.is(Tok::Int) || tok.is(Tok::Real)) {
    v = strtod(tok.text.str().c_str(), nullptr);
  } else {
    return errorHere("expected a number or 'inf', found " + describe());
  }
  consume();
  if (neg)
    v = -v;
  return true;
}

//===----------------------------------------------------------------------===//
// Top level
//===----------------------------------------------------------------------===//

bool Parser::parseFile() {
  while (!tok.is(Tok::Eof)) {
    if (tok.isIdent("module")) {
      consume();
      if (!parseModule(false))
        return false;
    } else if (tok.isIdent("system")) {
      consume();
      if (!parseModule(true))
        return false;
    } else if (tok.isIdent("type")) {
      consume();
      if (!parseTypeDecl())
        return false;
    } else if (tok.isIdent("timescale")) {
      if (!parseTimescale())
        return false;
    } else if (tok.isIdent("source")) {
      if (!parseSourceDecl())
        return false;
    } else {
      return errorHere("expected 'module', 'system', 'type', 'timescale' or "
                       "'source', found " +
                       describe());
    }
  }
  resolveStmtLocations();
  return !failed;
}

bool Parser::parseTimescale() {
  SMLoc loc = tok.loc();
  consume();
  if (sawTimescale)
    return error(loc, "timescale given twice");
  sawTimescale = true;
  int64_t amount;
  if (!parseInt(amount, "a time amount"))
    return false;
  if (amount <= 0)
    return error(loc, "timescale must be positive");
  if (!tok.is(Tok::Ident))
    return errorHere("expected a time unit (ns, us, ms, s, min, h), found " +
                     describe());
  StringRef unit = tok.text;
  if (!llvm::StringSwitch<bool>(unit)
           .Cases("ns", "us", "ms", "s", "min", "h", true)
           .Default(false))
    return errorHere("unknown time unit '" + unit +
                     "' (expected ns, us, ms, s, min or h)");
  consume();
  Timescale ts{uint64_t(amount), design.save(unit), loc};
  if (!design.mergeTimescale(ts)) {
    error(loc, "timescale " + ts.str() + " differs from the timescale " +
                   design.timescale->str() +
                   " of an earlier file; the models of one design must "
                   "agree on the length of a tick");
    diag.note(design.timescale->loc, "the earlier timescale");
    return false;
  }
  return expect(Tok::Semi, "';'");
}

bool Parser::parseTypeDecl() {
  StringRef name;
  SMLoc loc;
  if (!parseSimpleName(name, loc, "a type name"))
    return false;
  if (design.types.lookup(name))
    return error(loc, "redefinition of type '" + name + "'");
  if (!expect(Tok::Equal, "'='"))
    return false;
  name = design.save(name);
  if (tok.isIdent("enum")) {
    consume();
    if (!expect(Tok::LBrace, "'{'"))
      return false;
    std::vector<StringRef> enums;
    do {
      StringRef e;
      SMLoc eloc;
      if (!parseSimpleName(e, eloc, "an enumerator"))
        return false;
      for (StringRef prev : enums)
        if (prev == e)
          return error(eloc, "duplicate enumerator '" + e + "'");
      enums.push_back(design.save(e));
    } while (tok.is(Tok::Comma) && (consume(), true));
    if (!expect(Tok::RBrace, "'}'"))
      return false;
    design.types.createEnum(name, std::move(enums));
  } else if (tok.isIdent("struct")) {
    consume();
    if (!expect(Tok::LBrace, "'{'"))
      return false;
    std::vector<Field> fields;
    while (!tok.is(Tok::RBrace)) {
      StringRef f;
      SMLoc floc;
      if (!parseSimpleName(f, floc, "a field name"))
        return false;
      for (const Field &prev : fields)
        if (prev.name == f)
          return error(floc, "duplicate field '" + f + "'");
      const Type *ft;
      if (!expect(Tok::Colon, "':'") || !parseType(ft, false) ||
          !expect(Tok::Semi, "';'"))
        return false;
      fields.push_back({design.save(f), ft});
    }
    consume();
    if (fields.empty())
      return error(loc, "struct '" + name + "' has no fields");
    design.types.createRecord(name, std::move(fields));
  } else {
    const Type *t;
    if (!parseType(t, false))
      return false;
    design.types.addAlias(name, t);
  }
  design.types.namedTypes().back().loc = loc;
  return expect(Tok::Semi, "';'");
}

bool Parser::parseType(const Type *&type, bool allowReal) {
  SMLoc loc = tok.loc();
  if (tok.is(Tok::Int) || tok.is(Tok::Minus)) {
    int64_t lo, hi;
    if (!parseSignedInt(lo, "a lower bound") || !expect(Tok::DotDot, "'..'") ||
        !parseSignedInt(hi, "an upper bound"))
      return false;
    if (lo > hi)
      return error(loc,
                   "empty range " + llvm::Twine(lo) + ".." + llvm::Twine(hi));
    type = design.types.getRange(lo, hi);
    return true;
  }
  if (!tok.is(Tok::Ident))
    return errorHere("expected a type, found " + describe());
  StringRef word = tok.text;
  if (word == "bool") {
    consume();
    type = design.types.getBool();
    return true;
  }
  if (word == "array") {
    consume();
    int64_t lo, hi;
    const Type *elem;
    if (!expect(Tok::LBrack, "'['") || !parseSignedInt(lo, "an index") ||
        !expect(Tok::DotDot, "'..'") || !parseSignedInt(hi, "an index") ||
        !expect(Tok::RBrack, "']'") || !expectIdent("of") ||
        !parseType(elem, false))
      return false;
    if (lo > hi)
      return error(loc, "array has an empty index range");
    type = design.types.getArray(elem, lo, hi);
    return true;
  }
  if (word == "clock") {
    consume();
    int64_t lo, hi;
    if (!parseSignedInt(lo, "0") || !expect(Tok::DotDot, "'..'") ||
        !parseSignedInt(hi, "the clock's cap"))
      return false;
    if (lo != 0 || hi < 0)
      return error(loc, "a clock ranges over 0..cap");
    type = design.types.getClock(hi);
    return true;
  }
  if (word == "real32" || word == "real64") {
    consume();
    type = design.types.getFloat(word == "real32" ? 32 : 64);
    return true;
  }
  if (word == "string" || word == "wstring") {
    consume();
    int64_t n;
    if (!expect(Tok::LBrack, "'[' and the string's length") ||
        !parseSignedInt(n, "a length") || !expect(Tok::RBrack, "']'"))
      return false;
    if (n < 1 || n > 65535)
      return error(loc,
                   "a string's length must be 1..65535, not " + llvm::Twine(n));
    type = design.types.getString(uint32_t(n), word == "wstring");
    return true;
  }
  if (word == "real") {
    if (!allowReal)
      return errorHere("'real' is only allowed for hybrid variables "
                       "(`real x : [lo, hi]`)");
  }
  bool isSigned = word.startswith("int");
  if (isSigned || word.startswith("uint")) {
    unsigned width;
    if (!word.drop_front(isSigned ? 3 : 4).getAsInteger(10, width)) {
      if (width != 8 && width != 16 && width != 32 && width != 64)
        return errorHere("unsupported integer width in '" + word +
                         "' (8, 16, 32 or 64)");
      consume();
      Overflow ov = Overflow::Error;
      if (tok.isIdent("wrap")) {
        ov = Overflow::Wrap;
        consume();
      } else if (tok.isIdent("error")) {
        consume();
      }
      type = design.types.getInt(width, isSigned, ov);
      return true;
    }
  }
  if (const Type *named = design.types.lookup(word)) {
    consume();
    type = named;
    return true;
  }
  return errorHere("unknown type '" + word + "'");
}

bool Parser::parseModule(bool isSystem) {
  StringRef name;
  SMLoc loc;
  if (!parseSimpleName(name, loc, "a module name"))
    return false;
  Module *m = b.createModule(name, isSystem, loc);
  if (!m) {
    error(loc, "redefinition of module '" + name + "'");
    diag.note(design.lookupModule(name)->loc, "previous definition is here");
    return false;
  }
  if (!expect(Tok::LBrace, "'{'"))
    return false;
  fixups.clear();
  definitions.clear();
  reservedForModule = false;
  while (!tok.is(Tok::RBrace)) {
    if (tok.is(Tok::Eof))
      return errorHere("expected '}' to end module '" + name + "'");
    if (!parseModuleItem())
      return false;
  }
  consume();
  return resolveModuleFixups();
}

/// Large modules would otherwise grow their vectors and symbol table many
/// times (each growth touching fresh memory). Once a module is clearly
/// large, estimate what the rest of the text declares and reserve once.
void Parser::reserveForLargeModule() {
  reservedForModule = true;
  // Start at the newline before the current declaration so it is counted.
  const char *p = tok.text.data();
  while (p > bufferStart && *p != '\n')
    --p;
  const char *end = bufferEnd;
  size_t places = 0, transitions = 0, vars = 0;
  for (; p < end; ++p) {
    if (*p != '\n')
      continue;
    const char *q = p + 1;
    while (q < end && (*q == ' ' || *q == '\t'))
      ++q;
    size_t rest = size_t(end - q);
    if (rest > 6 && !memcmp(q, "trans ", 6))
      ++transitions;
    else if (rest > 6 && !memcmp(q, "place ", 6)) {
      ++places;
      for (const char *c = q; c < end && *c != ';' && *c != '\n'; ++c)
        places += *c == ',';
    } else if (rest > 4 && !memcmp(q, "var ", 4))
      ++vars;
    else if (rest > 2 && *q == '}' && (q[1] == '\n' || q[1] == '\r'))
      break; // the end of this module (canonical layout)
  }
  Module *m = b.getModule();
  m->reserve(m->places.size() + places, m->transitions.size() + transitions,
             m->vars.size() + vars);
}

bool Parser::parseModuleItem() {
  Module *cur = b.getModule();
  if (!reservedForModule &&
      cur->places.size() + cur->transitions.size() >= kLargeModule)
    reserveForLargeModule();
  if (!tok.is(Tok::Ident))
    return errorHere("expected a declaration, found " + describe());
  StringRef kw = tok.text;
  // `name = expr;` defines an output signal, whatever the name.
  Lexer peekLex = lex;
  Token after = peekLex.next();
  if (after.is(Tok::Equal))
    return parseDefinition();
  if (kw == "event" || kw == "cond" || kw == "data") {
    PortKind kind = kw == "event"  ? PortKind::Event
                    : kw == "cond" ? PortKind::Cond
                                   : PortKind::Data;
    consume();
    return parsePortDecl(kind);
  }
  consume();
  if (kw == "place")
    return parsePlaceDecl();
  if (kw == "trans")
    return parseTransDecl();
  if (kw == "var")
    return parseVarDecl(false);
  if (kw == "clock")
    return parseVarDecl(true);
  if (kw == "real")
    return parseRealDecl();
  if (kw == "flow")
    return parseFlowDecl();
  if (kw == "invariant")
    return parseInvariantDecl();
  if (kw == "inst")
    return parseInstDecl();
  if (kw == "connect")
    return parseConnectDecl();
  if (kw == "attr")
    return parseAttrDecl();
  return error(SMLoc::getFromPointer(kw.data()),
               "unknown declaration '" + kw +
                   "' (expected event, cond, data, place, trans, var, clock, "
                   "real, flow, inst, connect, attr or 'name = expr;')");
}

bool Parser::parsePortDecl(PortKind kind) {
  Module *m = b.getModule();
  PortDir dir;
  if (tok.isIdent("input"))
    dir = PortDir::In;
  else if (tok.isIdent("output"))
    dir = PortDir::Out;
  else
    return errorHere("expected 'input' or 'output', found " + describe());
  SMLoc dirLoc = tok.loc();
  consume();
  if (m->isSystem)
    return error(dirLoc, "a system has no interface; declare ports in a "
                         "module");
  struct Pending {
    StringRef name;
    SMLoc loc;
    Expr *def = nullptr;
    SMLoc defLoc;
    Expr *init = nullptr;
  };
  llvm::SmallVector<Pending, 4> names;
  auto parseTail = [&](Pending &p) {
    if (dir == PortDir::Out && kind != PortKind::Event) {
      if (tok.is(Tok::Equal)) {
        p.defLoc = tok.loc();
        consume();
        if (!(p.def = parseExpr()))
          return false;
      } else if (tok.isIdent("init")) {
        consume();
        if (!(p.init = parseExpr()))
          return false;
      }
    }
    return true;
  };
  do {
    Pending p;
    // Ports of a flattened module carry qualified names (`c.start`).
    if (!parseName(p.name, p.loc, "a port name"))
      return false;
    // Cond ports and stored outputs may carry their definition inline;
    // data ports give their type after the last name.
    if (kind == PortKind::Cond && !parseTail(p))
      return false;
    names.push_back(p);
  } while (tok.is(Tok::Comma) && (consume(), true));
  const Type *type = nullptr;
  if (kind == PortKind::Data) {
    if (!expect(Tok::Colon, "':' and the type of the data port") ||
        !parseType(type, false))
      return false;
    if (names.size() == 1 && !parseTail(names[0]))
      return false;
  }
  if (!expect(Tok::Semi, "';'"))
    return false;
  for (Pending &p : names) {
    uint32_t i = b.addPort(p.name, kind, dir, type, p.loc);
    m->ports[i].definition = p.def;
    m->ports[i].definitionLoc = p.defLoc;
    m->ports[i].init = p.init;
  }
  return true;
}

bool Parser::parsePlaceDecl() {
  do {
    StringRef name;
    SMLoc loc;
    if (!parseName(name, loc, "a place name"))
      return false;
    uint32_t tokens = 0, cap = 1;
    if (tok.is(Tok::LParen)) {
      consume();
      if (!parseUInt32(tokens, "a token count", false) ||
          !expect(Tok::RParen, "')'"))
        return false;
    }
    if (tok.isIdent("cap")) {
      consume();
      if (!parseUInt32(cap, "a capacity", true))
        return false;
      if (cap == 0)
        return error(loc, "place '" + name + "' has capacity 0");
    }
    b.addPlace(name, tokens, cap, loc);
  } while (tok.is(Tok::Comma) && (consume(), true));
  return expect(Tok::Semi, "';'");
}

bool Parser::parseArcList(bool pre, llvm::SmallVectorImpl<PreArc> &preArcs,
                          llvm::SmallVectorImpl<PostArc> &postArcs,
                          llvm::SmallVectorImpl<SMLoc> &locs,
                          llvm::SmallVectorImpl<StringRef> &names) {
  if (tok.is(Tok::LParen)) {
    consume();
    return expect(Tok::RParen, "')' (an empty arc list is written '()')");
  }
  do {
    uint32_t weight = 1;
    if (tok.is(Tok::Int)) {
      if (!parseUInt32(weight, "an arc weight", false) ||
          !expect(Tok::Star, "'*' after the arc weight"))
        return false;
      if (weight == 0)
        return errorHere("arc weight must be at least 1");
    }
    StringRef name;
    SMLoc loc;
    if (!parseName(name, loc, "a place name"))
      return false;
    Interval iv;
    if (tok.is(Tok::LBrack)) {
      if (!pre)
        return errorHere("time intervals belong on pre-arcs (before '->')");
      consume();
      if (!parseUInt32(iv.lo, "a lower time bound", false) ||
          !expect(Tok::Comma, "','") ||
          !parseUInt32(iv.hi, "an upper time bound or 'inf'", true))
        return false;
      if (iv.lo > iv.hi)
        return error(loc, "empty time interval [" + llvm::Twine(iv.lo) + "," +
                              llvm::Twine(iv.hi) + "]");
      if (tok.isIdent("deadline")) {
        if (iv.hi == kInf)
          return errorHere("a deadline needs a finite upper bound");
        consume();
        iv.deadline = true;
      }
      if (!expect(Tok::RBrack, "']'"))
        return false;
    }
    for (StringRef prev : names)
      if (prev == name)
        return error(loc, "place '" + name + "' appears twice in the " +
                              (pre ? "pre" : "post") +
                              "-set; give the arc a weight instead");
    if (pre)
      preArcs.push_back({0, weight, iv});
    else
      postArcs.push_back({0, weight});
    locs.push_back(loc);
    names.push_back(name);
  } while (tok.is(Tok::Comma) && (consume(), true));
  return true;
}

bool Parser::parseTransDecl() {
  // Names already declared are resolved at once; forward references wait
  // for the end of the module. Most nets declare places first, so this
  // keeps the pending list (and peak memory) small.
  pendingInTrans.clear();
  if (!parseTransDeclBody())
    return false;
  Module *m = b.getModule();
  for (const Fixup &f : pendingInTrans) {
    Symbol s = m->lookup(f.name);
    if (s.kind == SymKind::None)
      fixups.push_back(f);
    else if (!applyFixup(f, s))
      return false;
  }
  return true;
}

bool Parser::parseTransDeclBody() {
  StringRef name;
  SMLoc loc;
  if (!parseName(name, loc, "a transition name"))
    return false;
  if (!expect(Tok::Colon, "':'"))
    return false;
  llvm::SmallVector<PreArc, 4> pre;
  llvm::SmallVector<PostArc, 4> post;
  llvm::SmallVector<SMLoc, 8> preLocs, postLocs;
  llvm::SmallVector<StringRef, 8> preNames, postNames;
  if (!parseArcList(true, pre, post, preLocs, preNames) ||
      !expect(Tok::Arrow, "'->'") ||
      !parseArcList(false, pre, post, postLocs, postNames))
    return false;
  uint32_t t = b.addTransition(name, pre, post, loc);
  for (unsigned i = 0; i < preNames.size(); ++i)
    pendingInTrans.push_back(
        {FixKind::PrePlace, t, i, preNames[i], preLocs[i]});
  for (unsigned i = 0; i < postNames.size(); ++i)
    pendingInTrans.push_back(
        {FixKind::PostPlace, t, i, postNames[i], postLocs[i]});

  bool seenCond = false, seenOn = false, seenEmit = false, seenGuard = false;
  for (;;) {
    if (tok.isIdent("cond")) {
      if (seenCond)
        return errorHere("'cond' given twice");
      seenCond = true;
      consume();
      llvm::SmallVector<Expr *, 4> conds;
      do {
        Expr *e = parseExpr();
        if (!e)
          return false;
        conds.push_back(e);
      } while (tok.is(Tok::Comma) && (consume(), true));
      b.setConds(t, conds);
    } else if (tok.isIdent("on")) {
      if (seenOn)
        return errorHere("'on' given twice");
      seenOn = true;
      consume();
      llvm::SmallVector<EventSource, 4> srcs;
      llvm::SmallVector<SMLoc, 4> locs;
      EventMode mode = EventMode::Or;
      bool sawOr = false, sawAnd = false;
      for (;;) {
        StringRef ev;
        SMLoc evLoc;
        if (!parseName(ev, evLoc, "an event source"))
          return false;
        pendingInTrans.push_back(
            {FixKind::Event, t, uint32_t(srcs.size()), ev, evLoc});
        srcs.push_back({0, false});
        locs.push_back(evLoc);
        if (tok.is(Tok::Pipe))
          sawOr = true;
        else if (tok.is(Tok::Amp))
          sawAnd = true;
        else
          break;
        if (sawOr && sawAnd)
          return errorHere("mixing '|' and '&' in one event list; a "
                           "transition has one event mode");
        consume();
      }
      if (sawAnd)
        mode = EventMode::And;
      b.setEvents(t, srcs, mode);
      b.extras(t).eventLocs = design.copy(llvm::ArrayRef<SMLoc>(locs));
    } else if (tok.isIdent("emit")) {
      if (seenEmit)
        return errorHere("'emit' given twice");
      seenEmit = true;
      consume();
      llvm::SmallVector<uint32_t, 4> outs;
      llvm::SmallVector<SMLoc, 4> locs;
      do {
        StringRef ev;
        SMLoc evLoc;
        if (!parseName(ev, evLoc, "an event output"))
          return false;
        pendingInTrans.push_back(
            {FixKind::Emit, t, uint32_t(outs.size()), ev, evLoc});
        outs.push_back(0);
        locs.push_back(evLoc);
      } while (tok.is(Tok::Comma) && (consume(), true));
      b.setEmits(t, outs);
      b.extras(t).emitLocs = design.copy(llvm::ArrayRef<SMLoc>(locs));
    } else if (tok.isIdent("guard")) {
      if (seenGuard)
        return errorHere("'guard' given twice");
      seenGuard = true;
      consume();
      Expr *g = parseExpr();
      if (!g)
        return false;
      b.setGuard(t, g);
    } else if (tok.isIdent("urgent")) {
      if (b.getModule()->transitions[t].urgent)
        return errorHere("'urgent' given twice");
      consume();
      b.setUrgent(t);
    } else {
      break;
    }
  }
  if (tok.is(Tok::LBrace)) {
    Block body;
    if (!parseBlock(body))
      return false;
    b.setAction(t, body);
    return true;
  }
  if (tok.is(Tok::Semi)) {
    consume();
    return true;
  }
  return errorHere("expected 'cond', 'on', 'emit', 'guard', 'urgent', an "
                   "action block or ';', found " +
                   describe());
}

bool Parser::parseVarDecl(bool isClock) {
  llvm::SmallVector<std::pair<StringRef, SMLoc>, 4> names;
  do {
    StringRef name;
    SMLoc loc;
    if (!parseName(name, loc, "a variable name"))
      return false;
    names.push_back({name, loc});
  } while (tok.is(Tok::Comma) && (consume(), true));
  if (!expect(Tok::Colon, "':'"))
    return false;
  const Type *type;
  SMLoc typeLoc = tok.loc();
  if (isClock) {
    int64_t lo, hi;
    if (!parseSignedInt(lo, "0") || !expect(Tok::DotDot, "'..'") ||
        !parseSignedInt(hi, "the clock's cap"))
      return false;
    if (lo != 0 || hi < 0)
      return error(typeLoc, "a clock ranges over 0..cap");
    type = design.types.getClock(hi);
  } else if (!parseType(type, false)) {
    return false;
  }
  Expr *init = nullptr;
  if (!parseInitAndSemi(init))
    return false;
  for (auto &[n, l] : names)
    b.addVar(n, type, init, l);
  return true;
}

/// `[= expr] ;` ending a variable declaration.
bool Parser::parseInitAndSemi(Expr *&init) {
  if (tok.is(Tok::Equal)) {
    consume();
    if (!(init = parseExpr()))
      return false;
  }
  return expect(Tok::Semi, "';'");
}

bool Parser::parseRealDecl() {
  StringRef name;
  SMLoc loc;
  if (!parseName(name, loc, "a variable name"))
    return false;
  double lo = -INFINITY, hi = INFINITY;
  if (!expect(Tok::Colon, "':'") || !expect(Tok::LBrack, "'['") ||
      !parseRealBound(lo) || !expect(Tok::Comma, "','") ||
      !parseRealBound(hi) || !expect(Tok::RBrack, "']'"))
    return false;
  if (lo > hi)
    return error(loc, "empty real interval");
  Expr *init = nullptr, *initHi = nullptr;
  // `in [a, b]`: the initial value is anywhere between a and b (either
  // may be infinite: a SpaceEx initial set that does not bound it).
  if (tok.isIdent("in")) {
    consume();
    SMLoc at = tok.loc();
    double a, c;
    if (!expect(Tok::LBrack, "'['") || !parseRealBound(a) ||
        !expect(Tok::Comma, "','") || !parseRealBound(c) ||
        !expect(Tok::RBrack, "']'") || !expect(Tok::Semi, "';'"))
      return false;
    init = b.realLit(a, at);
    initHi = b.realLit(c, at);
  } else if (!parseInitAndSemi(init)) {
    return false;
  }
  uint32_t v = b.addVar(name, design.types.getReal(lo, hi), init, loc);
  b.getModule()->vars[v].initHi = initHi;
  return true;
}

bool Parser::parseInvariantDecl() {
  StringRef place;
  SMLoc loc;
  if (!parseName(place, loc, "a place name") || !expect(Tok::LBrace, "'{'"))
    return false;
  std::vector<Expr *> conds;
  while (!tok.is(Tok::RBrace)) {
    Expr *c = parseExpr();
    if (!c || !expect(Tok::Semi, "';'"))
      return false;
    conds.push_back(c);
  }
  consume();
  Module *m = b.getModule();
  Invariant inv;
  inv.loc = loc;
  inv.place = 0;
  inv.placeName = design.save(place);
  inv.conditions = design.copy(llvm::ArrayRef<Expr *>(conds));
  fixups.push_back(
      {FixKind::InvariantPlace, uint32_t(m->invariants.size()), 0, place, loc});
  m->invariants.push_back(inv);
  return true;
}

bool Parser::parseFlowDecl() {
  StringRef place;
  SMLoc loc;
  if (!parseName(place, loc, "a place name"))
    return false;
  if (!expect(Tok::LBrace, "'{'"))
    return false;
  std::vector<Flow::Equation> eqs;
  while (!tok.is(Tok::RBrace)) {
    Flow::Equation eq;
    if (!parseName(eq.var, eq.loc, "a real variable"))
      return false;
    if (!expect(Tok::Prime, "''' (a flow is written x' = rate)"))
      return false;
    if (tok.isIdent("in")) {
      // A rectangular flow `x' in [lo, hi]`.
      consume();
      if (!expect(Tok::LBrack, "'['") || !parseRateBound(eq.rate) ||
          !expect(Tok::Comma, "','") || !parseRateBound(eq.rateHi) ||
          !expect(Tok::RBrack, "']'") || !expect(Tok::Semi, "';'"))
        return false;
      eqs.push_back(eq);
      continue;
    }
    if (!expect(Tok::Equal, "'=' or 'in'"))
      return false;
    if (!(eq.rate = parseExpr()) || !expect(Tok::Semi, "';'"))
      return false;
    eqs.push_back(eq);
  }
  consume();
  Module *m = b.getModule();
  // The place may be declared later: resolve at the end of the module.
  Flow f;
  f.loc = loc;
  f.place = 0;
  f.placeName = design.save(place);
  for (auto &e : eqs)
    e.var = design.save(e.var);
  f.equations = design.copy(llvm::ArrayRef<Flow::Equation>(eqs));
  fixups.push_back(
      {FixKind::FlowPlace, uint32_t(m->flows.size()), 0, place, loc});
  m->flows.push_back(f);
  return true;
}

bool Parser::parseInstDecl() {
  StringRef name, type;
  SMLoc loc, typeLoc;
  if (!parseSimpleName(name, loc, "an instance name") ||
      !expect(Tok::Colon, "':'") ||
      !parseSimpleName(type, typeLoc, "a module name"))
    return false;
  uint32_t i = b.addInstance(name, type, loc);
  b.getModule()->instances[i].moduleLoc = typeLoc;
  return expect(Tok::Semi, "';'");
}

bool Parser::parseEndpoint(Endpoint &e) {
  StringRef n;
  SMLoc loc;
  if (!parseName(n, loc, "a port ('inst.port' or 'port')"))
    return false;
  e.loc = loc;
  // Instance names are never qualified, so `a.b.c` is port `b.c` of
  // instance `a` (or the module's own port `a.b.c`, which the verifier
  // recognises when there is no instance `a`).
  auto [inst, port] = n.split('.');
  if (port.empty()) {
    e.instance = "";
    e.port = n;
  } else {
    e.instance = inst;
    e.port = port;
  }
  return true;
}

bool Parser::parseConnectDecl() {
  SMLoc loc = tok.loc();
  Endpoint from, to;
  if (!parseEndpoint(from) || !expect(Tok::Arrow, "'->'") || !parseEndpoint(to))
    return false;
  b.addConnection(from, to, loc);
  return expect(Tok::Semi, "';'");
}

/// `attr [TARGET] KEY = "VALUE";`
bool Parser::parseAttrDecl() {
  SMLoc loc = tok.loc();
  StringRef target, key;
  SMLoc nameLoc;
  if (!parseName(key, nameLoc, "an attribute target or key"))
    return false;
  if (!tok.is(Tok::Equal)) {
    target = key;
    if (!parseSimpleName(key, nameLoc, "an attribute key"))
      return false;
  }
  if (key.contains('.'))
    return error(nameLoc, "an attribute key '" + key +
                              "' must not be qualified (no '.')");
  if (!expect(Tok::Equal, "'='"))
    return false;
  std::string value;
  if (!parseQuotedText(value))
    return false;
  b.addAttribute(target, key, value, loc);
  return expect(Tok::Semi, "';'");
}

bool Parser::parseQuotedText(std::string &out) {
  if (!tok.is(Tok::String))
    return errorHere("expected a string (\"...\"), found " + describe());
  StringRef quoted = tok.text.drop_front().drop_back();
  for (size_t i = 0; i < quoted.size(); ++i) {
    char c = quoted[i];
    if (c == '\\') {
      char n = quoted[++i];
      if (n != '"' && n != '\\' && n != 'n' && n != 't')
        return error(SMLoc::getFromPointer(quoted.data() + i - 1),
                     llvm::Twine("unknown escape '\\") + llvm::Twine(n) +
                         "' (write \\\", \\\\, \\n or \\t)");
      c = n == 'n' ? '\n' : n == 't' ? '\t' : n;
    }
    out += c;
  }
  consume();
  return true;
}

bool Parser::parseDefinition() {
  Definition d;
  d.name = tok.text;
  d.loc = tok.loc();
  consume(); // name
  consume(); // '='
  if (!(d.expr = parseExpr()) || !expect(Tok::Semi, "';'"))
    return false;
  definitions.push_back(d);
  return true;
}

bool Parser::applyFixup(const Fixup &f, Symbol s) {
  Module *m = b.getModule();
  auto kindName = [&]() -> std::string {
    switch (s.kind) {
    case SymKind::Place:
      return "a place";
    case SymKind::Transition:
      return "a transition";
    case SymKind::Port: {
      const Port &p = m->ports[s.index];
      return ((p.kind == PortKind::Event ? "an " : "a ") + spelling(p.kind) +
              (p.isInput() ? " input" : " output"))
          .str();
    }
    case SymKind::Var:
      return "a variable";
    case SymKind::Instance:
      return "an instance";
    default:
      return "undefined";
    }
  };
  switch (f.kind) {
  case FixKind::PrePlace:
  case FixKind::PostPlace:
  case FixKind::FlowPlace:
  case FixKind::InvariantPlace: {
    if (s.kind == SymKind::None)
      return error(f.loc, "unknown place '" + f.name + "'" +
                              didYouMean(f.name, m->declaredNames()));
    if (s.kind != SymKind::Place) {
      StringRef role = f.kind == FixKind::FlowPlace        ? "a flow"
                       : f.kind == FixKind::InvariantPlace ? "an invariant"
                                                           : "a flow arc";
      return error(f.loc, role + " needs a place, but '" + f.name + "' is " +
                              kindName());
    }
    if (f.kind == FixKind::FlowPlace) {
      m->flows[f.trans].place = s.index;
    } else if (f.kind == FixKind::InvariantPlace) {
      m->invariants[f.trans].place = s.index;
    } else {
      Transition &t = m->transitions[f.trans];
      if (f.kind == FixKind::PrePlace)
        t.mutablePre()[f.slot].place = s.index;
      else
        t.mutablePost()[f.slot].place = s.index;
    }
    break;
  }
  case FixKind::Event: {
    if (s.kind == SymKind::None)
      return error(f.loc, "unknown event source '" + f.name + "'" +
                              didYouMean(f.name, m->declaredNames()));
    EventSource src;
    if (s.kind == SymKind::Transition) {
      src = {s.index, false};
    } else if (s.kind == SymKind::Port &&
               m->ports[s.index].kind == PortKind::Event &&
               m->ports[s.index].isInput()) {
      src = {s.index, true};
    } else {
      return error(f.loc, "event arc source '" + f.name + "' is " + kindName() +
                              "; an event arc comes from a transition or "
                              "an event input");
    }
    Transition &t = m->transitions[f.trans];
    const_cast<EventSource &>(t.extras->events[f.slot]) = src;
    break;
  }
  case FixKind::Emit: {
    if (s.kind == SymKind::None)
      return error(f.loc, "unknown event output '" + f.name + "'" +
                              didYouMean(f.name, m->declaredNames()));
    if (!(s.kind == SymKind::Port &&
          m->ports[s.index].kind == PortKind::Event &&
          m->ports[s.index].isOutput()))
      return error(f.loc, "'emit' needs an event output, but '" + f.name +
                              "' is " + kindName());
    Transition &t = m->transitions[f.trans];
    const_cast<uint32_t &>(t.extras->emits[f.slot]) = s.index;
    break;
  }
  }
  return true;
}

bool Parser::resolveModuleFixups() {
  Module *m = b.getModule();
  for (const Fixup &f : fixups)
    if (!applyFixup(f, m->lookup(f.name)))
      return false;
  for (const Definition &d : definitions) {
    int p = m->findPort(d.name);
    if (p < 0 || !m->ports[p].isOutput() || m->ports[p].kind == PortKind::Event)
      return error(d.loc, "'" + d.name +
                              "' is not a cond or data output of module '" +
                              m->name + "'; only outputs are defined by '='");
    Port &port = m->ports[p];
    if (port.definition) {
      error(d.loc, "output '" + d.name + "' is defined twice");
      diag.note(port.definitionLoc, "previous definition is here");
      return false;
    }
    if (port.init)
      return error(d.loc, "output '" + d.name +
                              "' has an initial value, so it is stored and "
                              "cannot also be defined");
    port.definition = d.expr;
    port.definitionLoc = d.loc;
  }
  return true;
}

bool netlift::net::parseNetIR(unsigned bufferID, DiagEngine &diag,
                              Design &design) {
  const llvm::MemoryBuffer *buf = diag.sourceMgr().getMemoryBuffer(bufferID);
  Parser p(buf->getBuffer(), diag, design);
  return p.parseFile();
}

Expr *netlift::net::parseExpression(unsigned bufferID, DiagEngine &diag,
                                    Design &design) {
  const llvm::MemoryBuffer *buf = diag.sourceMgr().getMemoryBuffer(bufferID);
  Parser p(buf->getBuffer(), diag, design);
  return p.parseWholeExpression();
}

EmbeddedParser::EmbeddedParser(StringRef buffer, DiagEngine &diag,
                               Design &design)
    : impl(std::make_unique<Parser>(buffer, diag, design)) {}
EmbeddedParser::~EmbeddedParser() = default;
const Token &EmbeddedParser::token() const { return impl->current(); }
void EmbeddedParser::consume() { impl->advance(); }
bool EmbeddedParser::expect(Tok k, StringRef what) {
  return impl->expectToken(k, what);
}
bool EmbeddedParser::errorHere(const llvm::Twine &msg) {
  return impl->reportHere(msg);
}
bool EmbeddedParser::error(SMLoc loc, const llvm::Twine &msg) {
  return impl->report(loc, msg);
}
Expr *EmbeddedParser::expr() { return impl->expression(); }
bool EmbeddedParser::block(Block &out) { return impl->statements(out); }
bool EmbeddedParser::type(const Type *&t) { return impl->typeDecl(t); }
bool EmbeddedParser::name(StringRef &n, SMLoc &loc, StringRef what) {
  return impl->name(n, loc, what);
}
bool EmbeddedParser::failed() const { return impl->hasFailed(); }
