//===- gen-net.cpp - generate large NetIR modules for benchmarks ----------===//
//
// Writes a NetIR module of roughly the requested size made of repeated
// "cells" that use every common construct: places with tokens and
// capacities, transitions with weighted and timed pre-arcs, condition arcs,
// event arcs, guards and small actions over data variables. Deterministic:
// the same size gives the same bytes.
//
//   gen-net SIZE_MB [-o FILE] [--pt]
//
// --pt writes a plain place/transition net (weighted arcs and time
// intervals only, the shape of Model Checking Contest nets); the default
// mixes in condition and event arcs, guards and actions (the shape of a
// translated PLC program).
//
//===----------------------------------------------------------------------===//
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

int main(int argc, char **argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: gen-net SIZE_MB [-o FILE]\n");
    return 1;
  }
  double mb = std::atof(argv[1]);
  FILE *out = stdout;
  bool pt = false;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "-o") == 0 && i + 1 < argc)
      out = std::fopen(argv[++i], "w");
    else if (std::strcmp(argv[i], "--pt") == 0)
      pt = true;
  }
  if (!out) {
    std::perror("gen-net");
    return 1;
  }
  const size_t target = size_t(mb * 1024 * 1024);
  size_t written = 0;
  auto put = [&](const std::string &s) {
    std::fwrite(s.data(), 1, s.size(), out);
    written += s.size();
  };
  put("timescale 1ms;\n\nmodule Big {\n  event input tick;\n"
      "  cond input enable;\n");
  // Cells: first their variables, then the net.
  size_t cells = 0;
  std::string body;
  std::string vars;
  char buf[1024];
  while (written + body.size() + vars.size() < target) {
    size_t i = cells++;
    if (pt) {
      size_t j = (i * 7919 + 13) % (i + 1); // an earlier cell: cross links
      std::snprintf(buf, sizeof buf,
                    "  place a%zu(1), b%zu, c%zu cap 3;\n"
                    "  trans s%zu : a%zu[1,5] -> b%zu, c%zu;\n"
                    "  trans m%zu : b%zu, c%zu -> a%zu, 2*c%zu;\n"
                    "  trans r%zu : 2*c%zu[0,inf] -> a%zu;\n",
                    i, i, i, i, i, i, j, i, i, i, i, j, i, i, j);
      body += buf;
      continue;
    }
    std::snprintf(buf, sizeof buf, "  var n%zu : 0..15 = %zu;\n", i, i % 16);
    vars += buf;
    std::snprintf(
        buf, sizeof buf,
        "  place a%zu(1), b%zu, c%zu cap 3, d%zu;\n"
        "  trans s%zu : a%zu[1,5] -> b%zu cond enable on tick;\n"
        "  trans m%zu : b%zu -> 2*c%zu guard n%zu < 15 { n%zu := n%zu + 1; }\n"
        "  trans r%zu : 2*c%zu[0,inf] -> d%zu cond not a%zu;\n"
        "  trans e%zu : d%zu -> a%zu on r%zu {\n"
        "    if n%zu > 7 { n%zu := 0; } else { n%zu := n%zu * 2 %% 16; }\n"
        "  }\n",
        i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i, i,
        i);
    body += buf;
  }
  put(vars);
  put(body);
  put("}\n");
  if (out != stdout)
    std::fclose(out);
  std::fprintf(stderr, "gen-net: %zu cells, %zu bytes\n", cells, written);
  return 0;
}
