//===- PlcOpenReader.cpp - PLCopen TC6 XML declarations and bodies --------===//
//
// Reads a PLCopen project into the PLC model: data types, POUs and their
// interfaces, configurations; ST and IL bodies through their frontends,
// LD and FBD bodies through GraphicalBody.cpp, SFC bodies (with the POU's
// actions and transitions) through SfcBody.cpp.
//
//===----------------------------------------------------------------------===//
#include "frontends/plcopen/PlcOpen.h"

#include "frontends/il/IlFrontend.h"
#include "frontends/plc/JumpExpansion.h"
#include "frontends/st/StFrontend.h"

using namespace netlift;
using namespace netlift::plc;
using namespace netlift::plcopen;
using llvm::SMLoc;
using llvm::StringRef;

//===----------------------------------------------------------------------===//
// Declarations
//===----------------------------------------------------------------------===//

namespace {

class Reader {
public:
  Reader(XmlSource &src, DiagEngine &diag, Unit &unit)
      : src(src), diag(diag), unit(unit) {}

  bool project(pugi::xml_node root);

private:
  bool fail(pugi::xml_node at, const llvm::Twine &msg) {
    diag.error(src.locOf(at), msg);
    return false;
  }
  TypeSyntax *type(pugi::xml_node holder);
  Expr *bound(pugi::xml_node element, const char *attr);
  Initializer *initializer(pugi::xml_node value);
  bool variables(pugi::xml_node section, VarSection kind,
                 std::vector<VarDecl *> &out);
  bool interface(pugi::xml_node iface, Pou *pou);
  bool pou(pugi::xml_node p);
  bool body(pugi::xml_node b, Pou *pou, pugi::xml_node pouNode);
  bool configuration(pugi::xml_node c);
  Expr *interval(pugi::xml_node task);

  XmlSource &src;
  DiagEngine &diag;
  Unit &unit;
};

} // namespace

static const char *const elementaryTypes[] = {
    "BOOL",  "SINT", "INT",  "DINT",  "LINT",  "USINT", "UINT",  "UDINT",
    "ULINT", "BYTE", "WORD", "DWORD", "LWORD", "REAL",  "LREAL", "TIME",
    "DATE",  "DT",   "TOD",  "LTIME", "CHAR",  "WCHAR"};

/// The type held by a <type> or <baseType> element.
TypeSyntax *Reader::type(pugi::xml_node holder) {
  pugi::xml_node t;
  for (pugi::xml_node c : holder.children())
    if (c.type() == pugi::node_element) {
      t = c;
      break;
    }
  if (!t) {
    fail(holder, "<" + std::string(holder.name()) + "> names no type");
    return nullptr;
  }
  StringRef kind = localName(t);
  SMLoc at = src.locOf(t);
  for (const char *e : elementaryTypes)
    if (kind == e) {
      auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, at);
      ts->name = e;
      return ts;
    }
  if (kind == "derived") {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, at);
    ts->name = t.attribute("name").value();
    return ts;
  }
  if (kind == "string" || kind == "wstring") {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::String, at);
    ts->name = kind == "string" ? "STRING" : "WSTRING";
    if (t.attribute("length") && !(ts->length = bound(t, "length")))
      return nullptr;
    return ts;
  }
  if (kind == "array") {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Array, at);
    for (pugi::xml_node d : t.children())
      if (localName(d) == "dimension") {
        Expr *lo = bound(d, "lower"), *hi = bound(d, "upper");
        if (!lo || !hi)
          return nullptr;
        ts->dims.push_back({lo, hi});
      }
    ts->elem = type(child(t, "baseType"));
    return ts->elem ? ts : nullptr;
  }
  if (kind == "subrangeSigned" || kind == "subrangeUnsigned") {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Subrange, at);
    pugi::xml_node range = child(t, "range");
    TypeSyntax *base = type(child(t, "baseType"));
    if (!base)
      return nullptr;
    if (base->kind != TypeSyntaxKind::Named) {
      fail(t, "a subrange needs an elementary integer base type");
      return nullptr;
    }
    ts->name = base->name;
    ts->lo = bound(range, "lower");
    ts->hi = bound(range, "upper");
    return ts->lo && ts->hi ? ts : nullptr;
  }
  if (kind == "enum") {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Enum, at);
    for (pugi::xml_node v : child(t, "values").children())
      if (localName(v) == "value") {
        EnumValueSyntax ev;
        ev.name = v.attribute("name").value();
        ev.loc = src.locOf(v);
        if (v.attribute("value")) {
          ev.value = bound(v, "value");
          if (!ev.value)
            return nullptr;
        }
        ts->enumerators.push_back(ev);
      }
    return ts;
  }
  if (kind == "struct") {
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Struct, at);
    return variables(t, VarSection::Var, ts->fields) ? ts : nullptr;
  }
  if (kind == "pointer") {
    // <pointer><baseType>T</baseType></pointer>: POINTER TO T.
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Reference, at);
    ts->refKind = RefKind::Pointer;
    pugi::xml_node base = t.child("baseType");
    if (!base) {
      fail(t, "<pointer> has no <baseType>");
      return nullptr;
    }
    ts->elem = type(base);
    return ts->elem ? ts : nullptr;
  }
  auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Refused, at);
  ts->refused = "the PLCopen type <" + kind.str() + "> is not supported";
  return ts;
}

/// An expression written in an attribute (array bounds, enumerator values).
Expr *Reader::bound(pugi::xml_node element, const char *attr) {
  bool found = false;
  StringRef text = src.placeAttribute(element, attr, &found);
  if (!found) {
    fail(element, "<" + std::string(element.name()) +
                      "> needs the attribute '" + attr + "'");
    return nullptr;
  }
  return st::parseStExpression(text, diag, unit);
}

Initializer *Reader::initializer(pugi::xml_node value) {
  pugi::xml_node v;
  for (pugi::xml_node c : value.children())
    if (c.type() == pugi::node_element && localName(c) != "documentation") {
      v = c;
      break;
    }
  if (!v) {
    fail(value, "empty initial value");
    return nullptr;
  }
  StringRef kind = localName(v);
  if (kind == "simpleValue") {
    auto *i = unit.make<Initializer>(Initializer::Value, src.locOf(v));
    i->value = bound(v, "value");
    return i->value ? i : nullptr;
  }
  if (kind == "arrayValue") {
    auto *i = unit.make<Initializer>(Initializer::Array, src.locOf(v));
    for (pugi::xml_node e : v.children())
      if (localName(e) == "value") {
        int64_t count = 1;
        if (e.attribute("repetitionValue") &&
            !st::parseIntegerLiteral(e.attribute("repetitionValue").value(),
                                     count)) {
          fail(e, "malformed repetitionValue");
          return nullptr;
        }
        Initializer *inner = initializer(e);
        if (!inner)
          return nullptr;
        i->elems.push_back({count, inner});
      }
    return i;
  }
  if (kind == "structValue") {
    auto *i = unit.make<Initializer>(Initializer::Struct, src.locOf(v));
    for (pugi::xml_node e : v.children())
      if (localName(e) == "value") {
        Initializer *inner = initializer(e);
        if (!inner)
          return nullptr;
        i->fields.push_back({e.attribute("member").value(), inner});
      }
    return i;
  }
  fail(v, "unknown initial value <" + kind.str() + ">");
  return nullptr;
}

bool Reader::variables(pugi::xml_node section, VarSection kind,
                       std::vector<VarDecl *> &out) {
  for (pugi::xml_node v : section.children()) {
    if (localName(v) != "variable")
      continue;
    auto *d = unit.make<VarDecl>();
    d->name = v.attribute("name").value();
    d->loc = src.locOf(v);
    d->section = kind;
    d->constant = isTrue(section.attribute("constant"));
    d->retain = isTrue(section.attribute("retain")) ||
                isTrue(section.attribute("persistent"));
    d->location = v.attribute("address").value();
    if (d->name.empty())
      return fail(v, "<variable> without a name");
    d->typeSyntax = type(child(v, "type"));
    if (!d->typeSyntax)
      return false;
    if (pugi::xml_node init = child(v, "initialValue")) {
      // tc6_0200 files write string initial values without quotes.
      pugi::xml_node simple = child(init, "simpleValue");
      StringRef text = simple.attribute("value").value();
      // So do Beremiz's, for a type derived from STRING (SVGHMI's
      // HMI_STRING, the project's own).
      auto isString = [&](TypeSyntax *t) {
        for (int depth = 0; t && depth < 8; ++depth) {
          if (t->kind == TypeSyntaxKind::String)
            return true;
          if (t->kind != TypeSyntaxKind::Named)
            return false;
          if (StringRef(t->name).equals_insensitive("HMI_STRING"))
            return true;
          TypeDecl *td = unit.findType(t->name);
          t = td ? td->type : nullptr;
        }
        return false;
      };
      if (isString(d->typeSyntax) && simple && !text.startswith("'") &&
          !text.startswith("\"")) {
        auto *i = unit.make<Initializer>(Initializer::Value, src.locOf(simple));
        i->value = unit.make<Expr>(ExprKind::StringLit, i->loc);
        i->value->name = "'" + text.str() + "'";
        d->typeSyntax->init = i;
        out.push_back(d);
        continue;
      }
      d->typeSyntax->init = initializer(init);
      if (!d->typeSyntax->init)
        return false;
    }
    out.push_back(d);
  }
  return true;
}

bool Reader::interface(pugi::xml_node iface, Pou *pou) {
  static const std::pair<const char *, VarSection> sections[] = {
      {"localVars", VarSection::Var},
      {"tempVars", VarSection::Temp},
      {"inputVars", VarSection::Input},
      {"outputVars", VarSection::Output},
      {"inOutVars", VarSection::InOut},
      {"externalVars", VarSection::External},
      {"globalVars", VarSection::Global},
      {"accessVars", VarSection::Access}};
  for (pugi::xml_node s : iface.children()) {
    if (s.type() != pugi::node_element)
      continue;
    StringRef name = localName(s);
    if (name == "returnType") {
      pou->resultSyntax = type(s);
      if (!pou->resultSyntax)
        return false;
      continue;
    }
    if (name == "documentation" || name == "addData")
      continue;
    bool known = false;
    for (auto &[tag, kind] : sections)
      if (name == tag) {
        known = true;
        if (!variables(s, kind, pou->vars))
          return false;
      }
    if (!known)
      return fail(s, "unknown interface section <" + name.str() + ">");
  }
  return true;
}

bool Reader::body(pugi::xml_node b, Pou *pou, pugi::xml_node pouNode) {
  pugi::xml_node lang;
  for (pugi::xml_node c : b.children())
    if (c.type() == pugi::node_element && localName(c) != "documentation" &&
        localName(c) != "addData") {
      lang = c;
      break;
    }
  if (!lang)
    return fail(b, "the body of POU '" + pou->name + "' is empty");
  StringRef kind = localName(lang);
  if (kind == "ST")
    return st::parseStatements(src.placeText(lang), diag, unit, pou->body) &&
           expandJumps(unit, *pou, diag);
  if (kind == "IL")
    return il::parseInstructionListBody(src.placeText(lang), diag, unit, pou);
  if (kind == "LD" || kind == "FBD")
    return readGraphicalBody(lang, src, diag, unit, pou);
  if (kind == "SFC") {
    // An action's or transition's body is read as the POU's own would be
    // (its variables, its temporaries), then set apart.
    SfcBodyReader part = [&](pugi::xml_node partBody, StmtList &out) {
      StmtList own = std::move(pou->body);
      pou->body.clear();
      bool ok = body(partBody, pou, pouNode);
      out = std::move(pou->body);
      pou->body = std::move(own);
      return ok;
    };
    return readSfcBody(lang, pouNode, src, diag, unit, pou, part);
  }
  return fail(lang, "unknown body language <" + kind.str() + "> in POU '" +
                        pou->name + "'");
}

bool Reader::pou(pugi::xml_node p) {
  StringRef kind = p.attribute("pouType").value();
  PouKind k;
  if (kind == "program")
    k = PouKind::Program;
  else if (kind == "functionBlock")
    k = PouKind::FunctionBlock;
  else if (kind == "function")
    k = PouKind::Function;
  else
    return fail(p, "unknown pouType '" + kind.str() + "'");
  Pou *pou = unit.make<Pou>();
  pou->kind = k;
  pou->name = p.attribute("name").value();
  pou->loc = src.locOf(p);
  // Actions and transitions belong to an SFC body; elsewhere they are
  // CODESYS actions, called as statements.
  pugi::xml_node b = child(p, "body");
  bool sfc = b && child(b, "SFC");
  for (const char *part : {"actions", "transitions"})
    if (pugi::xml_node n = child(p, part))
      for (pugi::xml_node a : n.children())
        if (a.type() == pugi::node_element && !sfc)
          return fail(
              a, "POU " + std::string(part).substr(0, strlen(part) - 1) + " '" +
                     a.attribute("name").value() + "' of '" + pou->name +
                     "' outside an SFC body is not supported (a "
                     "CODESYS action, called as a statement)");
  if (pugi::xml_node iface = child(p, "interface"))
    if (!interface(iface, pou))
      return false;
  if (k == PouKind::Function && !pou->resultSyntax)
    return fail(p, "function '" + pou->name + "' has no <returnType>");
  if (!b)
    return fail(p, "POU '" + pou->name +
                       "' has no <body> (a block implemented outside IEC "
                       "61131-3, e.g. in C, cannot be modelled)");
  unit.pous.push_back(pou);
  return body(b, pou, p);
}

/// A task's interval: an IEC duration (`T#20ms`), or in tc6_0200 files an
/// xsd:time (`00:00:00.100000`).
Expr *Reader::interval(pugi::xml_node task) {
  StringRef v = StringRef(task.attribute("interval").value()).trim();
  llvm::SmallVector<StringRef, 3> parts;
  v.split(parts, ':');
  if (parts.size() != 3)
    return bound(task, "interval");
  auto [secs, frac] = parts[2].split('.');
  int64_t h, m, sec, f = 0;
  if (parts[0].getAsInteger(10, h) || parts[1].getAsInteger(10, m) ||
      secs.getAsInteger(10, sec) || frac.size() > 9 ||
      (!frac.empty() && frac.getAsInteger(10, f))) {
    fail(task, "malformed task interval '" + v.str() + "'");
    return nullptr;
  }
  for (size_t i = frac.size(); i < 9; ++i)
    f *= 10;
  auto *e = unit.make<Expr>(ExprKind::TimeLit, src.locOf(task));
  e->intValue = ((h * 60 + m) * 60 + sec) * 1'000'000'000 + f;
  return e;
}

bool Reader::configuration(pugi::xml_node c) {
  Configuration *cfg = unit.make<Configuration>();
  cfg->name = c.attribute("name").value();
  cfg->loc = src.locOf(c);
  auto instance = [&](pugi::xml_node pi, StringRef task) {
    ProgramInstance inst;
    inst.name = pi.attribute("name").value();
    inst.loc = src.locOf(pi);
    inst.task = task.str();
    // tc6_0200 called it `type`.
    inst.typeName =
        pi.attribute(pi.attribute("typeName") ? "typeName" : "type").value();
    inst.typeLoc = inst.loc;
    cfg->programs.push_back(inst);
  };
  auto items = [&](pugi::xml_node holder) {
    for (pugi::xml_node n : holder.children()) {
      StringRef name = localName(n);
      if (name == "globalVars") {
        if (!variables(n, VarSection::Global, cfg->globals))
          return false;
      } else if (name == "pouInstance") {
        instance(n, "");
      } else if (name == "task") {
        Task task;
        task.name = n.attribute("name").value();
        task.loc = src.locOf(n);
        if (n.attribute("interval") && !(task.interval = interval(n)))
          return false;
        if (n.attribute("single") && !(task.single = bound(n, "single")))
          return false;
        if (n.attribute("priority") && !(task.priority = bound(n, "priority")))
          return false;
        cfg->tasks.push_back(task);
        for (pugi::xml_node pi : n.children())
          if (localName(pi) == "pouInstance")
            instance(pi, task.name);
      }
    }
    return true;
  };
  if (!items(c))
    return false;
  for (pugi::xml_node r : c.children())
    if (localName(r) == "resource" && !items(r))
      return false;
  unit.configs.push_back(cfg);
  return true;
}

bool Reader::project(pugi::xml_node root) {
  pugi::xml_node types = child(root, "types");
  for (pugi::xml_node dt : child(types, "dataTypes").children()) {
    if (localName(dt) != "dataType")
      continue;
    auto *td = unit.make<TypeDecl>();
    td->name = dt.attribute("name").value();
    td->loc = src.locOf(dt);
    td->type = type(child(dt, "baseType"));
    if (!td->type)
      return false;
    if (pugi::xml_node init = child(dt, "initialValue"))
      if (!(td->type->init = initializer(init)))
        return false;
    unit.types.push_back(td);
  }
  // A POU holding a construct netlift refuses is kept with its refusal,
  // reported only if the translation reaches it (Sema).
  for (pugi::xml_node p : child(types, "pous").children()) {
    if (localName(p) != "pou")
      continue;
    size_t before = unit.pous.size();
    diag.beginDeferral();
    bool ok = pou(p);
    std::optional<DiagEngine::Deferred> refusal = diag.endDeferral();
    if (ok)
      continue;
    if (!refusal)
      return false; // a syntax error, reported where it is
    StringRef kind = p.attribute("pouType").value();
    keepRefusedPou(unit, before,
                   kind == "program"         ? PouKind::Program
                   : kind == "functionBlock" ? PouKind::FunctionBlock
                                             : PouKind::Function,
                   p.attribute("name").value(), src.locOf(p), refusal->loc,
                   std::move(refusal->message));
  }
  pugi::xml_node configs = child(child(root, "instances"), "configurations");
  for (pugi::xml_node c : configs.children())
    if (localName(c) == "configuration" && !configuration(c))
      return false;
  return true;
}

bool plcopen::readPlcOpen(unsigned bufferID, DiagEngine &diag, Unit &unit) {
  XmlSource src(bufferID, diag);
  pugi::xml_document doc;
  pugi::xml_parse_result r =
      doc.load_buffer(src.raw().data(), src.raw().size(), pugi::parse_default,
                      pugi::encoding_utf8);
  if (!r) {
    size_t off = std::min<size_t>(r.offset, src.raw().size());
    diag.error(SMLoc::getFromPointer(src.raw().data() + off),
               llvm::Twine("malformed XML: ") + r.description());
    return false;
  }
  pugi::xml_node root = doc.document_element();
  if (localName(root) != "project") {
    diag.error(src.locOf(root), "not a PLCopen TC6 project (the root element "
                                "is <" +
                                    std::string(root.name()) + ">)");
    return false;
  }
  // PLCopen XML written by CODESYS or TwinCAT converts TIME to numbers in
  // milliseconds; Beremiz's and OpenPLC's (and unnamed editors') go
  // through matiec, in seconds.
  pugi::xml_node header = root.child("fileHeader");
  std::string who =
      StringRef(std::string(header.attribute("companyName").value()) + " " +
                header.attribute("productName").value())
          .lower();
  if (llvm::any_of(std::initializer_list<StringRef>{"codesys", "3s-smart",
                                                    "twincat", "beckhoff"},
                   [&](StringRef v) { return StringRef(who).contains(v); }))
    unit.inferTimeNumbers(TimeNumbers::Milliseconds,
                          "milliseconds, as CODESYS and TwinCAT convert: the "
                          "PLCopen file was written by " +
                              who);
  else
    unit.inferTimeNumbers(TimeNumbers::Seconds,
                          "seconds, as matiec (OpenPLC, Beremiz) converts: "
                          "the PLCopen file was not written by CODESYS or "
                          "TwinCAT");
  Reader reader(src, diag, unit);
  return reader.project(root);
}
