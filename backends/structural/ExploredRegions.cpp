//===- ExploredRegions.cpp - sr over an explored state space --------------===//
#include "backends/structural/ExploredRegions.h"
#include "backends/statespace/Exploring.h"

#include "backends/statespace/Writers.h"
#include "backends/structural/StateFile.h"
#include "ir/net/Parser.h"
#include "ir/net/Verifier.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Program.h"

using namespace netlift;
using namespace netlift::structural;

bool structural::parseAttributes(llvm::ArrayRef<std::string> texts,
                                 net::Design &design, DiagEngine &diag,
                                 std::vector<Attribute> &out) {
  for (const std::string &a : texts) {
    auto [name, pred] = llvm::StringRef(a).split('=');
    name = name.trim();
    llvm::StringRef text = pred.empty() ? name : pred.trim();
    unsigned id = diag.sourceMgr().AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(text, "<attr " + name.str() + ">"),
        llvm::SMLoc());
    net::Expr *e = net::parseExpression(id, diag, design);
    if (!e)
      return false;
    out.push_back({name.str(), e, pred.empty()});
  }
  return true;
}

bool structural::classifyExplored(engine::ExplorationSetup &setup,
                                  net::Design &design,
                                  llvm::ArrayRef<Attribute> attrs,
                                  bool collectExamples, Analysis &an,
                                  ExploredRegions &out, DiagEngine &diag,
                                  llvm::StringRef witnessDir) {
  for (const Attribute &a : attrs)
    if (!net::verifyPredicate(design, setup.top(), a.predicate, diag))
      return false;
  sem::Semantics &semantics = setup.semantics();
  engine::ExploreResult r;
  std::unique_ptr<engine::Explorer> graph =
      statespace::exploreGraph(setup, r, diag);
  if (!graph)
    return false;
  engine::Explorer &explorer = *graph;
  out.complete = r.complete;
  // Region of every state, then the counts (memory: one word per state
  // here; the counts themselves are per region).
  std::vector<Region> region(explorer.store().size());
  for (uint32_t s = 0; s < region.size(); ++s)
    for (size_t i = 0; i < attrs.size(); ++i) {
      sem::RuntimeError err;
      if (semantics.evalPredicate(attrs[i].predicate, explorer.store().state(s),
                                  err))
        region[s] |= Region(1) << i;
    }
  std::vector<char> dead(region.size(), 0);
  for (uint32_t d : r.deadlocks)
    dead[d] = 1;
  for (uint32_t s = 0; s < region.size(); ++s)
    an.addState(region[s], dead[s]);
  for (const engine::Edge &e : explorer.edges())
    an.addEdge(region[e.from], region[e.to]);
  if (collectExamples)
    for (uint32_t s = 0; s < region.size(); ++s)
      if (!out.examples.count(region[s]))
        out.examples[region[s]] = statespace::describeState(
            semantics, explorer.store().state(s), ", ");
  if (witnessDir.empty())
    return true;
  if (std::error_code ec = llvm::sys::fs::create_directories(witnessDir)) {
    diag.error(llvm::SMLoc(),
               "cannot create '" + witnessDir + "': " + ec.message());
    return false;
  }
  // States are numbered in discovery order: breadth-first (the default),
  // the first state of a region ends a shortest path into it.
  for (uint32_t s = 0; s < region.size(); ++s) {
    if (out.witnesses.count(region[s]))
      continue;
    std::string name = an.regionName(region[s]);
    statespace::TraceFileHeader h;
    h.formula = name;
    h.holds = true;
    h.witness = true;
    h.claim = "a shortest path into region " + name;
    std::string file =
        (witnessDir + "/region-" + llvm::Twine(region[s]) + ".html").str();
    if (!statespace::writeHtmlTraceFile(explorer, semantics, s, h,
                                        statespace::traceViewOf(setup), file,
                                        diag))
      return false;
    out.witnesses[region[s]] = file;
  }
  return true;
}

bool structural::classifyStateFile(llvm::StringRef path,
                                   llvm::StringRef edgesPath, bool csv,
                                   llvm::ArrayRef<Attribute> attrs,
                                   bool collectExamples, Analysis &an,
                                   ExploredRegions &out, DiagEngine &diag) {
  unsigned id = addInputFile(diag.sourceMgr(), path);
  unsigned edgesID =
      edgesPath.empty() ? 0 : addInputFile(diag.sourceMgr(), edgesPath);
  if (!id || (!edgesPath.empty() && !edgesID))
    return false;
  std::vector<StateFileAttribute> fileAttrs;
  for (const Attribute &a : attrs)
    fileAttrs.push_back({a.name, a.plain ? nullptr : a.predicate});
  StateFileResult sr;
  sr.collectExamples = collectExamples;
  if (csv ? !analyseStateCsv(id, edgesID, diag, fileAttrs, an, sr)
          : !analyseStateFile(id, diag, fileAttrs, an, sr))
    return false;
  out.complete = sr.complete;
  out.examples = std::move(sr.examples);
  return true;
}

std::string structural::renderAttributeGraphSvg(const Analysis &an,
                                                bool allRegions) {
  llvm::ErrorOr<std::string> dot = llvm::sys::findProgramByName("dot");
  if (!dot)
    return "";
  llvm::SmallString<128> in, out;
  if (llvm::sys::fs::createTemporaryFile("netlift-ag", "dot", in) ||
      llvm::sys::fs::createTemporaryFile("netlift-ag", "svg", out))
    return "";
  {
    std::error_code ec;
    llvm::raw_fd_ostream os(in, ec);
    if (ec)
      return "";
    an.writeDot(os, allRegions);
  }
  llvm::StringRef args[] = {*dot, "-Tsvg", in};
  llvm::Optional<llvm::StringRef> redirects[] = {
      llvm::None, llvm::StringRef(out), llvm::StringRef("")};
  int rc = llvm::sys::ExecuteAndWait(*dot, args, llvm::None, redirects);
  std::string svg;
  if (rc == 0)
    if (auto buf = llvm::MemoryBuffer::getFile(out))
      svg = (*buf)->getBuffer().str();
  llvm::sys::fs::remove(in);
  llvm::sys::fs::remove(out);
  return svg;
}
