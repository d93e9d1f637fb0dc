//===- st-bench.cpp - Structured Text frontend throughput -----------------===//
//
// Runs the ST frontend in-process over files and prints throughput and
// peak memory, in two figures: parsing alone (lexer + ANTLR parser + model
// building) over every file, and parse + check + lower to NetIR over the
// files that translate. Usage: st-bench [--repeat N] FILE...
//
//===----------------------------------------------------------------------===//
#include "frontends/plc/LowerToNet.h"
#include "frontends/plc/Sema.h"
#include "frontends/st/StFrontend.h"
#include "frontends/st/StdLib.h"
#include "ir/net/Module.h"

#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"

#include <chrono>
#include <cstring>
#include <sys/resource.h>

using namespace netlift;

static double seconds(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a)
      .count();
}

static long peakKiB() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

int main(int argc, char **argv) {
  int repeat = 1;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc)
      repeat = std::atoi(argv[++i]);
    else
      files.push_back(argv[i]);
  }
  std::vector<std::unique_ptr<llvm::MemoryBuffer>> bufs;
  size_t bytes = 0;
  for (auto &f : files) {
    auto b = llvm::MemoryBuffer::getFile(f);
    if (!b) {
      llvm::errs() << "cannot read " << f << "\n";
      return 1;
    }
    bytes += (*b)->getBufferSize();
    bufs.push_back(std::move(*b));
  }
  double parseBest = 1e9, fullBest = 1e9;
  long parsePeakKiB = 0;
  size_t parsedOk = 0, translated = 0, translatedBytes = 0;
  for (int r = 0; r < repeat; ++r) {
    parsedOk = translated = translatedBytes = 0;
    auto t0 = std::chrono::steady_clock::now();
    for (auto &b : bufs) {
      llvm::SourceMgr sm;
      llvm::raw_null_ostream null;
      sm.setDiagHandler([](const llvm::SMDiagnostic &, void *) {});
      DiagEngine diag(sm);
      unsigned id = sm.AddNewSourceBuffer(
          llvm::MemoryBuffer::getMemBuffer(b->getMemBufferRef()), {});
      plc::Unit unit;
      parsedOk += st::parseStructuredText(sm.getMemoryBuffer(id)->getBuffer(),
                                          diag, unit);
    }
    parseBest = std::min(parseBest, seconds(t0));
    if (r == 0)
      parsePeakKiB = peakKiB();
    auto t1 = std::chrono::steady_clock::now();
    for (auto &b : bufs) {
      llvm::SourceMgr sm;
      sm.setDiagHandler([](const llvm::SMDiagnostic &, void *) {});
      DiagEngine diag(sm);
      unsigned id = sm.AddNewSourceBuffer(
          llvm::MemoryBuffer::getMemBuffer(b->getMemBufferRef()), {});
      plc::Unit unit;
      net::Design design;
      if (st::parseStructuredText(sm.getMemoryBuffer(id)->getBuffer(), diag,
                                  unit) &&
          st::addStandardLibrary(diag, unit) && plc::checkUnit(unit, diag) &&
          plc::lowerToNet(unit, {}, diag, design)) {
        ++translated;
        translatedBytes += b->getBufferSize();
      }
    }
    fullBest = std::min(fullBest, seconds(t1));
  }
  long peak = peakKiB();
  double mb = bytes / 1e6;
  llvm::outs() << "files: " << files.size() << ", " << bytes
               << " bytes; parsed without error: " << parsedOk
               << ", translated: " << translated << "\n";
  llvm::outs() << "parse:                 " << parseBest << " s, "
               << mb / parseBest << " MB/s\n";
  llvm::outs() << "parse+check+lower all: " << fullBest << " s, "
               << mb / fullBest << " MB/s (every file, translated or "
               << "refused)\n";
  llvm::outs() << "peak RSS: parsing " << parsePeakKiB << " KiB, all " << peak
               << " KiB (" << (peak * 1024.0) / std::max<size_t>(bytes, 1)
               << "x the input)\n";
  return 0;
}
