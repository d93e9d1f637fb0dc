//===- PlcInputs.cpp - reading PLC sources into one translation -----------===//
//
// The ST and TwinCAT loaders of the registry append what they read to one
// PLC unit; finishPlcInputs adds the standard function blocks, checks the
// unit and lowers it to NetIR once every input file is read, so that a
// program and the function blocks it uses may come from different files.
//
//===----------------------------------------------------------------------===//
#include "frontends/FrontendRegistry.h"
#include "frontends/il/IlFrontend.h"
#include "frontends/plc/LowerToNet.h"
#include "frontends/plc/Sema.h"
#include "frontends/st/StFrontend.h"
#include "frontends/st/StdLib.h"

#include "llvm/Support/MemoryBuffer.h"

#include <pugixml.hpp>

using namespace netlift;
using llvm::SMLoc;
using llvm::StringRef;

FrontendOptions &netlift::frontendOptions() {
  static FrontendOptions opts;
  return opts;
}

static std::unique_ptr<plc::Unit> &pendingUnit() {
  static std::unique_ptr<plc::Unit> unit;
  return unit;
}

static plc::Unit &unitForLoading() {
  auto &u = pendingUnit();
  if (!u)
    u = std::make_unique<plc::Unit>();
  return *u;
}

bool netlift::loadStructuredText(unsigned bufferID, DiagEngine &diag,
                                 net::Design &) {
  StringRef text = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  return st::parseStructuredText(text, diag, unitForLoading());
}

bool netlift::loadInstructionList(unsigned bufferID, DiagEngine &diag,
                                  net::Design &) {
  return il::parseInstructionList(bufferID, diag, unitForLoading());
}

/// `--ranges FILE`: one `NAME LO..HI` per line; `#` or `//` start comments.
static bool readRanges(StringRef path, DiagEngine &diag,
                       plc::LowerOptions &opts) {
  unsigned id = addInputFile(diag.sourceMgr(), path);
  if (!id)
    return false;
  StringRef text = diag.sourceMgr().getMemoryBuffer(id)->getBuffer();
  while (!text.empty()) {
    auto [line, rest] = text.split('\n');
    text = rest;
    StringRef body = line;
    body = body.split('#').first.split("//").first.trim();
    if (body.empty())
      continue;
    auto [name, range] = body.split(char(' '));
    range = range.trim();
    auto [lo, hi] = range.split("..");
    int64_t l, h;
    if (name.empty() || lo.trim().getAsInteger(10, l) ||
        hi.trim().getAsInteger(10, h) || l > h) {
      diag.error(SMLoc::getFromPointer(line.data()),
                 "expected 'NAME LO..HI' with LO <= HI");
      return false;
    }
    opts.ranges[name.upper()] = {l, h};
  }
  return true;
}

bool netlift::finishPlcInputs(DiagEngine &diag, net::Design &design) {
  std::unique_ptr<plc::Unit> unit = std::move(pendingUnit());
  if (!unit)
    return true;
  const FrontendOptions &fo = frontendOptions();
  plc::LowerOptions opts;
  opts.top = fo.top;
  opts.timescaleNs = fo.timescaleNs;
  opts.scanPeriodNs = fo.scanPeriodNs;
  if (!fo.rangesFile.empty() && !readRanges(fo.rangesFile, diag, opts))
    return false;
  if (!st::addStandardLibrary(diag, *unit))
    return false;
  if (!plc::checkUnit(*unit, diag))
    return false;
  return plc::lowerToNet(*unit, opts, diag, design);
}

//===----------------------------------------------------------------------===//
// TwinCAT 3 (.TcPOU, .TcGVL, .TcDUT)
//===----------------------------------------------------------------------===//

bool netlift::loadTwinCat(unsigned bufferID, DiagEngine &diag,
                          net::Design &) {
  StringRef text = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  SMLoc start = SMLoc::getFromPointer(text.data());
  diag.error(start, "TwinCAT input is not supported yet");
  return false;
}
