//===- FrontendRegistry.cpp - reading any supported input -----------------===//
#include "frontends/FrontendRegistry.h"

#include "ir/net/Parser.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Process.h"
#include "llvm/Support/raw_ostream.h"

using namespace netlift;
using llvm::StringRef;
using llvm::Twine;

static const FrontendInfo registry[] = {
#define NETLIFT_FRONTEND(ID, DESC, EXTS, LOAD, FINISH)                         \
  {#ID, DESC, EXTS, LOAD, FINISH},
#include "frontends/FrontendRegistry.def"
#undef NETLIFT_FRONTEND
};

llvm::ArrayRef<FrontendInfo> netlift::frontends() { return registry; }

static const FrontendInfo *byExtension(StringRef path) {
  StringRef ext = llvm::sys::path::extension(path);
  for (const FrontendInfo &f : registry) {
    llvm::SmallVector<StringRef, 4> exts;
    f.extensions.split(exts, ',');
    for (StringRef e : exts)
      if (!e.trim().empty() && e.trim().equals_insensitive(ext))
        return &f;
  }
  return nullptr;
}

/// Does `text` read like IEC 61131-3 source (a line opening a POU, a
/// declaration block or a configuration)?
static bool looksLikePlcSource(StringRef text) {
  // NetIR declares `var x : bool = false;` too: IEC text also closes its
  // sections (END_VAR, END_PROGRAM, ...), which NetIR never does.
  if (!StringRef(text.upper()).contains("END_"))
    return false;
  while (!text.empty()) {
    auto [line, rest] = text.split('\n');
    text = rest;
    StringRef word = line.ltrim().take_while(
        [](char c) { return isalpha((unsigned char)c) || c == '_'; });
    std::string up = word.upper();
    if (up == "PROGRAM" || up == "FUNCTION_BLOCK" || up == "FUNCTION" ||
        up == "VAR" || up == "VAR_INPUT" || up == "VAR_GLOBAL" ||
        up == "TYPE" || up == "CONFIGURATION")
      return true;
  }
  return false;
}

bool netlift::loadNetIR(FrontendContext &, unsigned bufferID, DiagEngine &diag,
                        net::Design &design) {
  if (!net::parseNetIR(bufferID, diag, design)) {
    // A .txt file or standard input is read as NetIR by default.
    const llvm::MemoryBuffer *buf = diag.sourceMgr().getMemoryBuffer(bufferID);
    if (looksLikePlcSource(buf->getBuffer()))
      diag.note(llvm::SMLoc::getFromPointer(buf->getBufferStart()),
                "this reads as IEC 61131-3 text, not NetIR: name the format "
                "with --from st (or --from il for Instruction List)");
    return false;
  }
  if (design.modules.empty()) {
    const llvm::MemoryBuffer *buf = diag.sourceMgr().getMemoryBuffer(bufferID);
    diag.error(llvm::SMLoc::getFromPointer(buf->getBufferStart()),
               "no module or system in this file");
    return false;
  }
  return true;
}

/// NETLIFT_VERIFY_ROUNDTRIP=1 (set by `lit --param roundtrip=1`) checks on
/// every NetIR input that printing, re-parsing and printing again gives the
/// same text, so the whole test suite exercises the printer and parser.
static bool checkRoundTrip(StringRef path, const net::Design &design,
                           DiagEngine &diag) {
  std::string first;
  llvm::raw_string_ostream os1(first);
  net::printDesign(design, os1, &diag.sourceMgr());
  os1.flush();
  llvm::SourceMgr sm;
  DiagEngine inner(sm);
  unsigned id = sm.AddNewSourceBuffer(llvm::MemoryBuffer::getMemBufferCopy(
                                          first, (path + ".printed.net").str()),
                                      llvm::SMLoc());
  net::Design again;
  if (!net::parseNetIR(id, inner, again) || !net::verifyDesign(again, inner)) {
    diag.error(llvm::SMLoc(), "round trip: the printed form of '" + path +
                                  "' does not parse back (see above)");
    return false;
  }
  std::string second;
  llvm::raw_string_ostream os2(second);
  net::printDesign(again, os2, &sm);
  os2.flush();
  if (first != second) {
    diag.error(llvm::SMLoc(),
               "round trip: printing '" + path + "' is not a fixed point");
    diag.note(llvm::SMLoc(), "--- first\n" + first + "--- second\n" + second);
    return false;
  }
  return true;
}

/// XML dialects share the extension .xml: the root element tells them
/// apart (the first element after the prolog and comments). `root` is set
/// to where it starts (empty when there is none).
static const FrontendInfo *sniffXml(StringRef text, StringRef &root) {
  size_t pos = 0;
  root = StringRef();
  while ((pos = text.find('<', pos)) != StringRef::npos) {
    StringRef rest = text.substr(pos + 1);
    if (rest.startswith("?") || rest.startswith("!")) {
      ++pos;
      continue;
    }
    root = rest.take_while([](char c) {
      return !isspace((unsigned char)c) && c != '>' && c != '/';
    });
    StringRef id =
        root == "sspaceex"  ? "spaceex"
        : root == "pnml"    ? "pnml"
        : root == "project" ? "plcopen"
        : root == "FBType" || root == "System" || root == "SubAppType" ||
                root == "AdapterType" || root == "DataType" ||
                root == "Function" || root == "DeviceType" ||
                root == "ResourceType" || root == "SegmentType" ||
                root == "AttributeDeclaration" || root == "GlobalConstants"
            ? "iec61499"
            : "";
    for (const FrontendInfo &f : registry)
      if (!id.empty() && f.id == id)
        return &f;
    return nullptr;
  }
  return nullptr;
}

static const FrontendInfo *chooseFrontend(StringRef path, StringRef from,
                                          DiagEngine &diag) {
  if (from.empty()) {
    const FrontendInfo *fe = byExtension(path);
    return fe ? fe : &registry[0]; // NetIR text is the default, as for stdin
  }
  for (const FrontendInfo &f : registry)
    if (f.id == from)
      return &f;
  std::string known;
  for (const FrontendInfo &f : registry)
    known += (known.empty() ? "" : ", ") + f.id.str();
  diag.error(llvm::SMLoc(),
             "unknown input format '" + from + "' (known: " + known + ")");
  return nullptr;
}

bool netlift::loadInputs(llvm::ArrayRef<std::string> given, StringRef from,
                         const FrontendOptions &options, DiagEngine &diag,
                         net::Design &design,
                         std::vector<std::string> &pipelines) {
  FrontendOptions withProject = options;
  std::optional<std::vector<std::string>> expanded =
      expandProjectInputs(given, diag, withProject);
  if (!expanded)
    return false;
  llvm::ArrayRef<std::string> paths = *expanded;
  FrontendContext ctx(withProject);
  bool allNet = true;
  for (const std::string &path : paths) {
    const FrontendInfo *fe = chooseFrontend(path, from, diag);
    if (!fe)
      return false;
    allNet &= fe->id == "net";
    unsigned id = addInputFile(diag.sourceMgr(), path);
    if (!id)
      return false;
    if (from.empty() &&
        llvm::sys::path::extension(path).equals_insensitive(".xml")) {
      StringRef text = diag.sourceMgr().getMemoryBuffer(id)->getBuffer();
      StringRef root;
      fe = sniffXml(text, root);
      if (!fe) {
        diag.error(
            llvm::SMLoc::getFromPointer(root.empty() ? text.data()
                                                     : root.data()),
            (root.empty() ? Twine("no XML root element")
                          : "XML root element <" + root + ">") +
                " not recognised (known: PLCopen <project>, SpaceEx "
                "<sspaceex>, PNML <pnml>, IEC 61499 "
                "<FBType>/<System>/<SubAppType>/<AdapterType>/<Function>/"
                "<DataType>/"
                "<DeviceType>/<ResourceType>/<SegmentType>); name the "
                "format "
                "with --from");
        return false;
      }
      allNet = false;
    }
    if (!fe->load(ctx, id, diag, design))
      return false;
  }
  // Each finish phase once, in registry order (the PLC frontends share
  // one).
  std::vector<decltype(FrontendInfo::finish)> finished;
  for (const FrontendInfo &f : registry)
    if (f.finish && !llvm::is_contained(finished, f.finish)) {
      finished.push_back(f.finish);
      if (!f.finish(ctx, diag, design))
        return false;
    }
  pipelines = std::move(ctx.pipelines);
  if (!pipelines.empty())
    return true; // verified by the caller, after the pipelines
  if (!net::verifyDesign(design, diag))
    return false;
  if (allNet) {
    if (options.verifyRoundTrip &&
        !checkRoundTrip(paths.size() == 1 ? StringRef(paths[0]) : "input",
                        design, diag))
      return false;
  }
  return true;
}

/// Appends the lines of `text` that say something (comments `#` and `//`
/// removed) as ranges.
static bool splitRangeLines(StringRef text, DiagEngine &diag,
                            std::vector<RangeLine> &out) {
  while (!text.empty()) {
    auto [line, rest] = text.split('\n');
    text = rest;
    StringRef body = line.split('#').first.split("//").first.trim();
    if (body.empty())
      continue;
    auto [name, range] = body.split(char(' '));
    range = range.trim();
    RangeLine r;
    r.name = name;
    r.loc = llvm::SMLoc::getFromPointer(name.data());
    auto [word, null] = range.split(char(' '));
    if (!name.empty() && word.equals_insensitive("NOT") &&
        null.trim().equals_insensitive("NULL")) {
      r.notNull = true;
      out.push_back(r);
      continue;
    }
    auto [lo, hi] = range.split("..");
    if (name.empty() || lo.trim().empty() || hi.trim().empty() ||
        !range.contains("..")) {
      diag.error(llvm::SMLoc::getFromPointer(line.data()),
                 "expected 'NAME LO..HI', or 'NAME NOT NULL'");
      return false;
    }
    r.lo = lo.trim();
    r.hi = hi.trim();
    out.push_back(r);
  }
  return true;
}

bool netlift::readRangeLines(const FrontendOptions &fo, DiagEngine &diag,
                             std::vector<RangeLine> &out) {
  if (!fo.rangesFile.empty()) {
    unsigned id = addInputFile(diag.sourceMgr(), fo.rangesFile);
    if (!id ||
        !splitRangeLines(diag.sourceMgr().getMemoryBuffer(id)->getBuffer(),
                         diag, out))
      return false;
  }
  if (fo.rangeOptions.empty())
    return true;
  // The options become a buffer of their own, one line each, so that an
  // error points at the option it is about.
  std::string lines;
  for (const std::string &opt : fo.rangeOptions) {
    auto [name, range] = StringRef(opt).split('=');
    lines += name.trim().str() + " " + range.trim().str() + "\n";
  }
  unsigned id = diag.sourceMgr().AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(lines, "<--range>"), llvm::SMLoc());
  return splitRangeLines(diag.sourceMgr().getMemoryBuffer(id)->getBuffer(),
                         diag, out);
}
