//===- netir-bench.cpp - time parse + verify + print of NetIR -------------===//
//
// Reads one NetIR file and reports, for each phase, the wall time and the
// throughput in MB/s of input, plus the peak resident memory as a multiple
// of the file size. The file is read once before timing so the figures
// measure netlift, not the disk.
//
//   netir-bench FILE [--repeat N]
//
//===----------------------------------------------------------------------===//
#include "ir/net/Parser.h"
#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"

#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <sys/resource.h>

using namespace netlift;
using Clock = std::chrono::steady_clock;

static double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

static long peakRssKiB() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

/// Counts bytes without storing them.
class CountingStream : public llvm::raw_ostream {
public:
  uint64_t bytes = 0;

private:
  void write_impl(const char *, size_t n) override { bytes += n; }
  uint64_t current_pos() const override { return bytes; }
};

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: netir-bench FILE [--repeat N]\n");
    return 1;
  }
  int repeat = 1;
  if (argc >= 4 && std::strcmp(argv[2], "--repeat") == 0)
    repeat = std::atoi(argv[3]);
  long baseline = peakRssKiB();
  auto bufOr = llvm::MemoryBuffer::getFile(argv[1], /*IsText=*/false,
                                           /*RequiresNullTerminator=*/false);
  if (!bufOr) {
    std::fprintf(stderr, "netir-bench: cannot read %s\n", argv[1]);
    return 1;
  }
  double mb = (*bufOr)->getBufferSize() / (1024.0 * 1024.0);
  // Touch the file so that page-ins are not timed.
  unsigned sum = 0;
  for (char c : (*bufOr)->getBuffer())
    sum += c;
  volatile unsigned sink = sum;
  (void)sink;
  double bestParse = 1e9, bestVerify = 1e9, bestPrint = 1e9;
  uint64_t printed = 0;
  size_t places = 0, transitions = 0;
  for (int r = 0; r < repeat; ++r) {
    llvm::SourceMgr sm;
    DiagEngine diag(sm);
    unsigned id = sm.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBuffer((*bufOr)->getBuffer(), argv[1], false),
        llvm::SMLoc());
    net::Design d;
    auto t0 = Clock::now();
    if (!net::parseNetIR(id, diag, d))
      return 1;
    auto t1 = Clock::now();
    if (!net::verifyDesign(d, diag))
      return 1;
    auto t2 = Clock::now();
    CountingStream os;
    net::printDesign(d, os);
    os.flush();
    auto t3 = Clock::now();
    bestParse = std::min(bestParse, seconds(t0, t1));
    bestVerify = std::min(bestVerify, seconds(t1, t2));
    bestPrint = std::min(bestPrint, seconds(t2, t3));
    printed = os.bytes;
    places = transitions = 0;
    size_t vecBytes = 0;
    for (auto &m : d.modules) {
      places += m->places.size();
      transitions += m->transitions.size();
      vecBytes += m->places.capacity() * sizeof(net::Place) +
                  m->transitions.capacity() * sizeof(net::Transition) +
                  m->vars.capacity() * sizeof(net::Var);
    }
    if (r == 0)
      std::printf("memory: arena %.1f MB, entity vectors %.1f MB (places "
                  "%zu/%zu, transitions %zu/%zu)\n",
                  d.arenaBytes() / 1048576.0, vecBytes / 1048576.0,
                  d.modules[0]->places.size(), d.modules[0]->places.capacity(),
                  d.modules[0]->transitions.size(),
                  d.modules[0]->transitions.capacity());
  }
  long peak = peakRssKiB();
  double peakMB = (peak - baseline) / 1024.0;
  std::printf("file            %.1f MB (%zu places, %zu transitions)\n", mb,
              places, transitions);
  std::printf("parse           %.3f s  %.1f MB/s\n", bestParse, mb / bestParse);
  std::printf("verify          %.3f s  %.1f MB/s\n", bestVerify,
              mb / bestVerify);
  std::printf("print           %.3f s  %.1f MB/s (%.1f MB written)\n",
              bestPrint, mb / bestPrint, printed / (1024.0 * 1024.0));
  std::printf("parse+verify+print %.3f s  %.1f MB/s\n",
              bestParse + bestVerify + bestPrint,
              mb / (bestParse + bestVerify + bestPrint));
  std::printf("peak memory     %.1f MB above start = %.2fx the file size "
              "(file included)\n",
              peakMB, peakMB / mb);
  return 0;
}
