//===- PlcInputs.cpp - reading PLC sources into one translation -----------===//
//
// The ST, IL, TwinCAT and PLCopen loaders of the registry append what they read
// to one PLC unit; finishPlcInputs adds the standard function blocks, checks
// the unit and lowers it to NetIR once every input file is read, so that a
// program and the function blocks it uses may come from different files.
//
//===----------------------------------------------------------------------===//
#include "frontends/FrontendRegistry.h"
#include "frontends/XmlSupport.h"
#include "frontends/iec61499/Iec61499.h"
#include "frontends/il/IlFrontend.h"
#include "frontends/plc/LowerToNet.h"
#include "frontends/plc/Sema.h"
#include "frontends/plcopen/PlcOpen.h"
#include "frontends/st/StFrontend.h"
#include "frontends/st/StLexer.h"
#include "frontends/st/StdLib.h"

#include "llvm/Support/MemoryBuffer.h"

#include <pugixml.hpp>

#include <algorithm>

using namespace netlift;
using llvm::SMLoc;
using llvm::StringRef;

// FrontendContext lives here, where plc::Unit is a complete type.
FrontendContext::FrontendContext(const FrontendOptions &options)
    : options(options) {}

FrontendContext::~FrontendContext() = default;

plc::Unit &FrontendContext::plcUnit() {
  if (!plc) {
    plc = std::make_unique<plc::Unit>();
    plc->sfcDialect =
        options.sfcCodesys ? plc::SfcDialect::Codesys : plc::SfcDialect::Iec;
    for (const std::string &d : options.defines) {
      auto [name, value] = StringRef(d).split('=');
      plc->defines[name.trim().upper()] = value.trim().str();
    }
    plc->projectName = options.projectName;
    if (options.timeUnit == "s")
      plc->inferTimeNumbers(plc::TimeNumbers::Seconds,
                            "seconds (--time-unit s)");
    else if (options.timeUnit == "ms")
      plc->inferTimeNumbers(plc::TimeNumbers::Milliseconds,
                            "milliseconds (--time-unit ms)");
    plc->instructionListReader = [](llvm::StringRef body, DiagEngine &diag,
                                    plc::Unit &unit, plc::Pou *pou,
                                    plc::Expr **result) {
      return il::parseInstructionListBody(body, diag, unit, pou, result);
    };
  }
  return *plc;
}

/// The unit PLC loaders append to; remembers where the first file starts.
static plc::Unit &unitFor(FrontendContext &ctx, unsigned bufferID) {
  if (!ctx.firstPlcFile)
    ctx.firstPlcFile = bufferID;
  return ctx.plcUnit();
}

std::unique_ptr<plc::Unit> FrontendContext::takePlcUnit() {
  return std::move(plc);
}

bool netlift::parseDurationOption(StringRef flag, StringRef text,
                                  std::optional<int64_t> &out,
                                  DiagEngine &diag) {
  if (text.empty())
    return true;
  int64_t ns;
  std::string error;
  if (!st::parseDuration(("T#" + text).str(), ns, error) || ns <= 0) {
    diag.error(SMLoc(), "--" + flag + "=" + text +
                            ": expected a positive duration such as 10ms" +
                            (error.empty() ? "" : " (" + error + ")"));
    return false;
  }
  out = ns;
  return true;
}

static st::ParseOptions parseOptions(const FrontendContext &ctx) {
  st::ParseOptions po;
  po.longPartTokens = ctx.options.stLongPartTokens;
  po.groupTokens = ctx.options.stGroupTokens;
  return po;
}

bool netlift::loadStructuredText(FrontendContext &ctx, unsigned bufferID,
                                 DiagEngine &diag, net::Design &) {
  StringRef text = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  return st::parseStructuredText(text, diag, unitFor(ctx, bufferID),
                                 parseOptions(ctx));
}

bool netlift::loadInstructionList(FrontendContext &ctx, unsigned bufferID,
                                  DiagEngine &diag, net::Design &) {
  return il::parseInstructionList(bufferID, diag, unitFor(ctx, bufferID));
}

bool netlift::loadPlcOpen(FrontendContext &ctx, unsigned bufferID,
                          DiagEngine &diag, net::Design &) {
  return plcopen::readPlcOpen(bufferID, diag, unitFor(ctx, bufferID));
}

/// `--ranges FILE` and `--range NAME=LO..HI`: integer bounds of inputs (or
/// `NAME NOT NULL`, for a reference input).
static bool readRanges(const FrontendOptions &fo, DiagEngine &diag,
                       plc::LowerOptions &opts) {
  std::vector<RangeLine> lines;
  if (!readRangeLines(fo, diag, lines))
    return false;
  for (const RangeLine &r : lines) {
    if (r.notNull) {
      opts.ranges[r.name.upper()] = {1, 1, r.name.str(), r.loc, true};
      continue;
    }
    int64_t l, h;
    if (r.lo.getAsInteger(10, l) || r.hi.getAsInteger(10, h) || l > h) {
      diag.error(r.loc, "the range of '" + r.name + "' is not LO..HI with " +
                            "integers LO <= HI");
      return false;
    }
    opts.ranges[r.name.upper()] = {l, h, r.name.str(), r.loc};
  }
  return true;
}

bool netlift::finishPlcInputs(FrontendContext &ctx, DiagEngine &diag,
                              net::Design &design) {
  std::unique_ptr<plc::Unit> unit = ctx.takePlcUnit();
  if (!unit)
    return true;
  const FrontendOptions &fo = ctx.options;
  plc::LowerOptions opts;
  opts.top = fo.top;
  opts.opaqueRefused = fo.opaqueRefused;
  opts.callerElements = fo.callerElements;
  opts.timescaleNs = fo.timescaleNs;
  opts.scanPeriodNs = fo.scanPeriodNs;
  opts.unitStart = SMLoc::getFromPointer(
      diag.sourceMgr().getMemoryBuffer(ctx.firstPlcFile)->getBufferStart());
  if (!readRanges(fo, diag, opts))
    return false;
  if (!st::addStandardLibrary(diag, *unit) ||
      (unit->twinCat && !st::addTwinCatLibrary(diag, *unit)) ||
      (!unit->twinCat && !st::addBeremizLibrary(diag, *unit)))
    return false;
  plc::CheckOptions co;
  co.top = fo.top;
  co.warnUnusedRefused = fo.warnUnusedRefused;
  co.opaqueRefused = fo.opaqueRefused;
  bool checked = plc::checkUnit(*unit, diag, co);
  // A library of function blocks: each translated that can be, each that
  // cannot reported.
  if (fo.top.empty() && plc::isLibrary(*unit))
    return plc::lowerLibrary(*unit, opts, diag, design) && checked;
  return checked && plc::lowerToNet(*unit, opts, diag, design);
}

//===----------------------------------------------------------------------===//
// TwinCAT 3 (.TcPOU, .TcGVL, .TcDUT)
//===----------------------------------------------------------------------===//

/// Where a CDATA section's text starts and ends, searching from `from`.
static bool cdataAfter(StringRef text, size_t from, size_t limit, size_t &begin,
                       size_t &end) {
  size_t open = text.find("<![CDATA[", from);
  if (open == StringRef::npos || open > limit)
    return false;
  begin = open + 9;
  end = text.find("]]>", begin);
  return end != StringRef::npos;
}

/// A TwinCAT task (`.TcTTO`): its cycle time (in microseconds) and the
/// programs it calls, as a configuration's task and program instances.
template <typename At>
static bool twinCatTask(pugi::xml_node task, plc::Unit &unit, At at,
                        DiagEngine &diag) {
  plc::Configuration *cfg = nullptr;
  for (plc::Configuration *c : unit.configs)
    if (c->name == "TwinCAT")
      cfg = c;
  if (!cfg) {
    cfg = unit.make<plc::Configuration>();
    cfg->name = "TwinCAT";
    cfg->loc = at(task.offset_debug());
    unit.configs.push_back(cfg);
  }
  plc::Task t;
  t.name = task.attribute("Name").value();
  t.loc = at(task.offset_debug());
  if (pugi::xml_node cycle = task.child("CycleTime")) {
    int64_t us = 0;
    if (StringRef(cycle.text().get()).trim().getAsInteger(10, us) || us <= 0) {
      diag.error(at(cycle.offset_debug()),
                 "a task's <CycleTime> is a positive number of microseconds");
      return false;
    }
    auto *interval =
        unit.make<plc::Expr>(plc::ExprKind::TimeLit, at(cycle.offset_debug()));
    interval->intValue = us * 1000;
    t.interval = interval;
  }
  // Read by the runtime's record of its tasks (_TaskInfo[i].Priority).
  if (pugi::xml_node priority = task.child("Priority")) {
    int64_t value = 0;
    if (StringRef(priority.text().get()).trim().getAsInteger(10, value) ||
        value < 0) {
      diag.error(at(priority.offset_debug()),
                 "a task's <Priority> is a number, 0 or more");
      return false;
    }
    t.priority = unit.make<plc::Expr>(plc::ExprKind::IntLit,
                                      at(priority.offset_debug()));
    t.priority->intValue = value;
  }
  cfg->tasks.push_back(t);
  for (pugi::xml_node call : task.children("PouCall")) {
    plc::ProgramInstance pi;
    pi.name = call.child("Name").text().get();
    pi.loc = pi.typeLoc = at(call.offset_debug());
    pi.typeName = pi.name;
    pi.task = t.name;
    cfg->programs.push_back(pi);
  }
  return true;
}

/// TwinCAT keeps a POU's declaration and its body in two CDATA sections of
/// an XML file. The Structured Text parser reads a copy of the file in
/// which everything but those sections is blanked (line ends kept) and the
/// closing END_ keyword is appended, so every location is the XML file's
/// own line and column.
bool netlift::loadTwinCat(FrontendContext &ctx, unsigned bufferID,
                          DiagEngine &diag, net::Design &) {
  llvm::SourceMgr &sm = diag.sourceMgr();
  const llvm::MemoryBuffer *buf = sm.getMemoryBuffer(bufferID);
  StringRef text = buf->getBuffer();
  auto at = [&](ptrdiff_t offset) {
    return SMLoc::getFromPointer(text.data() +
                                 std::clamp<ptrdiff_t>(offset, 0, text.size()));
  };
  pugi::xml_document doc;
  if (!XmlBuffer(text).parse(doc, diag))
    return false;
  pugi::xml_node root = doc.child("TcPlcObject");
  if (!root) {
    diag.error(at(0), "not a TwinCAT file (no TcPlcObject element)");
    return false;
  }
  unitFor(ctx, bufferID)
      .inferTimeNumbers(plc::TimeNumbers::Milliseconds,
                        "milliseconds, as TwinCAT converts");
  unitFor(ctx, bufferID).twinCat = true;
  std::string blanked(text.size(), ' ');
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n')
      blanked[i] = '\n';
  std::vector<bool> kept(text.size(), false);
  std::string trailer, globalList;
  // Where the section kept last ends: a method's closing keyword goes
  // after it.
  size_t lastKeptEnd = 0;
  auto keep = [&](pugi::xml_node element, bool required,
                  pugi::xml_node owner = {}) {
    size_t from = size_t(element.offset_debug());
    pugi::xml_node next = element.next_sibling();
    size_t limit = next ? size_t(next.offset_debug()) : text.size();
    size_t b, e;
    if (!element || !cdataAfter(text, from, limit, b, e)) {
      if (required && !element)
        diag.error(at(size_t(owner.offset_debug())),
                   "expected a <Declaration> with its Structured Text in <" +
                       std::string(owner.name()) + ">");
      else if (required)
        diag.error(at(from), "expected the Structured Text of <" +
                                 std::string(element.name()) +
                                 "> in a CDATA section");
      return !required;
    }
    for (size_t i = b; i < e; ++i) {
      blanked[i] = text[i];
      kept[i] = true;
    }
    lastKeptEnd = e;
    return true;
  };
  // The keywords the XML implies (END_METHOD after a method, ACTION before
  // an action's body) are written into the blanked markup between two
  // kept sections, on one line, so no location moves.
  auto place = [&](size_t from, size_t limit, const std::string &words) {
    size_t run = 0;
    for (size_t i = from; i < std::min(limit, text.size()); ++i) {
      run = kept[i] || blanked[i] == '\n' ? 0 : run + 1;
      if (run == words.size() + 2) {
        blanked.replace(i - words.size(), words.size(), words);
        for (size_t k = i - words.size() - 1; k <= i; ++k)
          kept[k] = true;
        return true;
      }
    }
    diag.error(at(from), "no room in the XML markup for '" + words +
                             "' (the TwinCAT file is laid out unusually)");
    return false;
  };
  auto declaration = [&](pugi::xml_node owner, bool required) {
    return keep(owner.child("Declaration"), required, owner);
  };
  auto endOf = [&](pugi::xml_node element) {
    pugi::xml_node next = element.next_sibling();
    for (pugi::xml_node up = element.parent(); !next && up; up = up.parent())
      next = up.next_sibling();
    return next ? size_t(next.offset_debug()) : text.size();
  };
  // The ST of an <Implementation>; none (an abstract method's) is empty.
  auto implementation = [&](pugi::xml_node owner) {
    pugi::xml_node impl = owner.child("Implementation");
    if (!impl)
      return true;
    pugi::xml_node body = impl.first_child();
    while (body && body.type() != pugi::node_element)
      body = body.next_sibling();
    if (body && StringRef(body.name()) != "ST") {
      diag.error(at(body.offset_debug()),
                 "TwinCAT <" + std::string(body.name()) +
                     "> bodies are not supported (only ST)");
      return false;
    }
    return !body || keep(body, false);
  };
  for (pugi::xml_node obj : root.children()) {
    if (obj.type() != pugi::node_element)
      continue;
    StringRef kind = obj.name();
    if (kind == "GVL" || kind == "DUT") {
      if (!declaration(obj, true))
        return false;
      if (kind == "GVL")
        globalList = obj.attribute("Name").value();
      continue;
    }
    if (kind == "Task") {
      if (!twinCatTask(obj, unitFor(ctx, bufferID), at, diag))
        return false;
      continue;
    }
    if (kind != "POU" && kind != "Itf") {
      diag.error(at(obj.offset_debug()),
                 "TwinCAT <" + kind.str() + "> objects are not supported");
      return false;
    }
    // A POU, or an interface (its methods' and properties' declarations,
    // without bodies).
    pugi::xml_node decl = obj.child("Declaration");
    if (!declaration(obj, true) || !implementation(obj))
      return false;
    if (kind == "Itf")
      trailer += "\nEND_INTERFACE";
    for (pugi::xml_node part : obj.children()) {
      StringRef pn = part.name();
      std::string name = part.attribute("Name").value();
      if (pn == "Method") {
        if (!declaration(part, true) || !implementation(part) ||
            !place(lastKeptEnd, endOf(part), "END_METHOD"))
          return false;
      } else if (pn == "Action") {
        pugi::xml_node impl = part.child("Implementation");
        size_t b, e;
        if (!impl ||
            !cdataAfter(text, size_t(impl.offset_debug()), endOf(part), b, e)) {
          diag.error(at(part.offset_debug()),
                     "expected the Structured Text of action '" + name +
                         "' in a CDATA section");
          return false;
        }
        if (!place(size_t(part.offset_debug()), b, "ACTION " + name + ":") ||
            !implementation(part) ||
            !place(lastKeptEnd, endOf(part), "END_ACTION"))
          return false;
      } else if (pn == "Property") {
        if (!declaration(part, true))
          return false;
        for (const char *accessor : {"Get", "Set"}) {
          pugi::xml_node acc = part.child(accessor);
          if (!acc)
            continue;
          std::string kw = StringRef(accessor).upper();
          if (!place(lastKeptEnd, size_t(acc.offset_debug()) + 4, kw) ||
              !declaration(acc, false) || !implementation(acc) ||
              !place(lastKeptEnd, endOf(acc), "END_" + kw))
            return false;
        }
        if (!place(lastKeptEnd, endOf(part), "END_PROPERTY"))
          return false;
      } else if (pn == "Transition") {
        diag.error(at(part.offset_debug()),
                   "Transition '" + name + "' of POU '" +
                       obj.attribute("Name").value() +
                       "' is not supported (SFC parts are refused)");
        return false;
      }
    }
    // The closing keyword the declaration's first keyword calls for.
    // (keep() above has required the declaration's CDATA section.)
    size_t db = 0, de = 0;
    if (!cdataAfter(text, size_t(decl.offset_debug()), text.size(), db, de))
      de = db;
    llvm::SourceMgr scratch;
    DiagEngine quiet(scratch);
    st::StLexer lexer(text.substr(db, de - db), quiet);
    lexer.setSilent();
    for (;;) {
      auto t = lexer.nextToken();
      if (t->getType() == antlr4::Token::EOF)
        break;
      if (t->getChannel() != 0)
        continue;
      size_t kw = t->getType();
      trailer += kw == st::StLexer::keywordType("PROGRAM") ? "\nEND_PROGRAM"
                 : kw == st::StLexer::keywordType("FUNCTION_BLOCK")
                     ? "\nEND_FUNCTION_BLOCK"
                 : kw == st::StLexer::keywordType("FUNCTION") ? "\nEND_FUNCTION"
                                                              : "";
      break;
    }
  }
  unsigned id =
      sm.AddNewSourceBuffer(llvm::MemoryBuffer::getMemBufferCopy(
                                blanked + trailer, buf->getBufferIdentifier()),
                            SMLoc());
  plc::Unit &unit = unitFor(ctx, bufferID);
  size_t globalsBefore = unit.globals.size();
  if (!st::parseStructuredText(sm.getMemoryBuffer(id)->getBuffer(), diag, unit,
                               parseOptions(ctx)))
    return false;
  for (size_t i = globalsBefore; i < unit.globals.size(); ++i)
    unit.globals[i]->globalList = globalList;
  return true;
}

//===----------------------------------------------------------------------===//
// IEC 61499
//===----------------------------------------------------------------------===//

bool netlift::loadIec61499(FrontendContext &ctx, unsigned bufferID,
                           DiagEngine &, net::Design &) {
  ctx.iec61499Files.push_back(bufferID);
  return true;
}

bool netlift::finishIec61499Inputs(FrontendContext &ctx, DiagEngine &diag,
                                   net::Design &design) {
  std::vector<unsigned> ids = std::move(ctx.iec61499Files);
  ctx.iec61499Files.clear();
  if (ids.empty())
    return true;
  const FrontendOptions &fo = ctx.options;
  iec61499::Options options;
  options.typeLibraries = fo.typeLibraries;
  options.timescaleNs = fo.timescaleNs;
  if (!fo.fbSemantics.empty())
    options.semantics = fo.fbSemantics;
  options.opaqueAsEnvironment = !fo.opaqueRefused;
  options.lossyChannels = fo.lossyChannels;
  return iec61499::translate(ids, options, diag, design, ctx.pipelines);
}
