//===- BackendRegistry.cpp - the formats `emit` writes --------------------===//
#include "backends/BackendRegistry.h"

#include "backends/checkers/PnmlWriter.h"
#include "backends/checkers/Promela.h"
#include "backends/checkers/Smv.h"
#include "backends/nces/NcesXml.h"
#include "backends/nces/NetDot.h"
#include "ir/net/Printer.h"

using namespace netlift;

static bool writeNetText(const EmitInput &in, DiagEngine &diag,
                         llvm::raw_ostream &os) {
  net::printDesign(*in.design, os,
                   in.sourceLocations ? &diag.sourceMgr() : nullptr);
  return true;
}

static bool writeNetDrawing(const EmitInput &in, DiagEngine &,
                            llvm::raw_ostream &os) {
  writeDot(*in.design, os);
  return true;
}

static bool writePromelaSteps(const EmitInput &in, DiagEngine &diag,
                              llvm::raw_ostream &os) {
  return checkers::writePromela(in.setup->semantics(), diag, os, in.properties);
}

static bool writeSmvSteps(const EmitInput &in, DiagEngine &diag,
                          llvm::raw_ostream &os) {
  return checkers::writeSmv(in.setup->semantics(), diag, os, in.properties);
}

static bool writePnmlNet(const EmitInput &in, DiagEngine &diag,
                         llvm::raw_ostream &os) {
  return checkers::writePnml(*in.top, diag, os);
}

static bool writeNcesXmlModule(const EmitInput &in, DiagEngine &diag,
                               llvm::raw_ostream &os) {
  return nces::writeNcesXml(*in.top, diag, os);
}

static bool writePntTable(const EmitInput &in, DiagEngine &diag,
                          llvm::raw_ostream &os) {
  return nces::writePnt(*in.top, diag, os);
}

static const BackendInfo registry[] = {
#define NETLIFT_BACKEND(ID, EXT, INPUT, SUMMARY, WRITE)                        \
  {ID, EXT, EmitInputKind::INPUT, SUMMARY, WRITE},
#include "backends/BackendRegistry.def"
#undef NETLIFT_BACKEND
};

llvm::ArrayRef<BackendInfo> netlift::backends() { return registry; }

const BackendInfo *netlift::findBackend(llvm::StringRef id) {
  for (const BackendInfo &b : registry)
    if (b.id == id)
      return &b;
  return nullptr;
}

std::string netlift::describeBackends() {
  std::string s = "Output format:";
  for (const BackendInfo &b : registry)
    s += "\n    " + b.id.str() + " - " + b.summary.str();
  return s;
}

void netlift::printBackendTable(llvm::raw_ostream &os) {
  os << "| `emit --to` | extension | takes | what it writes |\n"
     << "|---|---|---|---|\n";
  for (const BackendInfo &b : registry) {
    llvm::StringRef takes = b.input == EmitInputKind::Design ? "the design"
                            : b.input == EmitInputKind::FlatTop
                                ? "the flattened top"
                                : "the top's steps";
    os << "| `" << b.id << "` | `" << b.extension << "` | " << takes << " | "
       << b.summary << " |\n";
  }
}
