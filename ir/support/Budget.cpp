//===- Budget.cpp - the time and memory a run may take --------------------===//
#include "ir/support/Budget.h"

#include <cstdio>
#include <unistd.h>

using namespace netlift;

uint64_t netlift::residentBytes() {
  FILE *f = std::fopen("/proc/self/statm", "r");
  if (!f)
    return 0;
  unsigned long long size = 0, resident = 0;
  int n = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  if (n != 2)
    return 0;
  return uint64_t(resident) * uint64_t(sysconf(_SC_PAGESIZE));
}

Budget::Budget(double seconds, uint64_t maxBytes)
    : timed(seconds > 0), maxBytes(maxBytes) {
  if (timed)
    deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(seconds));
}

bool Budget::overMemory(uint64_t &bytes) {
  bytes = residentBytes();
  peak = bytes > peak ? bytes : peak;
  return maxBytes && bytes > maxBytes;
}

const char *Budget::spent() {
  // Once spent, always spent: a check whose answer was swallowed (a
  // probing evaluation) must not let the run go on.
  if (what)
    return what;
  if (timed && Clock::now() > deadline)
    return what = "time";
  if (maxBytes && (calls++ & 255) == 0) {
    uint64_t bytes;
    if (overMemory(bytes))
      return what = "memory";
  }
  return nullptr;
}
