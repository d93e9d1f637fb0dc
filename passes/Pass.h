//===- Pass.h - NetIR passes and pipelines ----------------------*- C++ -*-===//
//
// A pass transforms a verified Design in place. Passes are registered in
// PassRegistry.def (one line each) and run by a PassManager built from a
// pipeline text such as `flatten,foo{k=v}`. The manager verifies after each
// pass on request, prints the IR after each pass on request, and collects
// the counters passes report (printed by --stats).
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_PASSES_PASS_H
#define NETLIFT_PASSES_PASS_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/raw_ostream.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace netlift {

/// What an option's value must be (PassRegistry.def says which).
enum class OptionKind {
  Name,
  Names,
  Count,
  Number,
  Numbers,
  PositiveNumber,
  Bool,
  File,
  Choice,
  Components
};

/// One option a pass takes, declared in PassRegistry.def.
struct PassOptionInfo {
  llvm::StringRef pass;
  llvm::StringRef key;
  OptionKind kind;
  llvm::StringRef value;   // as the docs write it: NAME, N, a|b
  llvm::StringRef meaning; // one line
};

/// The option values given to one pass (`name{k=v,k2=v2}`), checked
/// against their kinds when the pipeline was parsed; passes read them
/// typed.
class PassOptions {
public:
  bool has(llvm::StringRef key) const { return values.count(key.str()); }
  /// Name, File, Choice: the text (`dflt` when absent).
  std::string text(llvm::StringRef key, llvm::StringRef dflt = "") const;
  /// Names, Numbers, Components: the comma-separated items, trimmed.
  std::vector<std::string> list(llvm::StringRef key) const;
  /// Count.
  uint64_t wholeNumber(llvm::StringRef key) const;
  /// Number, PositiveNumber.
  double number(llvm::StringRef key) const;
  std::vector<double> numbers(llvm::StringRef key) const;
  /// Bool (`dflt` when absent).
  bool flag(llvm::StringRef key, bool dflt = false) const;
  /// Sets a value (a pass handing options on to the passes it runs).
  void set(llvm::StringRef key, llvm::StringRef value) {
    values[key.str()] = value.str();
  }

private:
  std::map<std::string, std::string> values;
};

/// Named counters, printed by --stats in name order.
class Statistics {
public:
  void add(llvm::StringRef pass, llvm::StringRef counter, uint64_t n,
           llvm::StringRef desc);
  void print(llvm::raw_ostream &os) const;
  bool empty() const { return counters.empty(); }

private:
  struct Counter {
    uint64_t value = 0;
    std::string desc;
  };
  std::map<std::pair<std::string, std::string>, Counter> counters;
};

/// The stream a pass writes its human-readable report to, from the option
/// `report=FILE` (`-`: standard output); no stream when the option is absent.
class ReportStream {
public:
  /// False after reporting that FILE cannot be written.
  bool open(const PassOptions &opts, llvm::StringRef pass, DiagEngine &diag);
  llvm::raw_ostream *get() const { return os; }

private:
  std::unique_ptr<llvm::raw_fd_ostream> file;
  llvm::raw_ostream *os = nullptr;
};

class Pass {
public:
  virtual ~Pass();
  /// Runs on the design; returns false after reporting an error.
  virtual bool run(net::Design &design, DiagEngine &diag,
                   Statistics &stats) = 0;
};

struct PassInfo {
  llvm::StringRef name;
  llvm::StringRef summary;
  std::unique_ptr<Pass> (*create)(const PassOptions &);
  /// The options this pass takes, in registry order.
  std::vector<const PassOptionInfo *> options() const;
  const PassOptionInfo *option(llvm::StringRef key) const;
};

llvm::ArrayRef<PassInfo> passRegistry();
const PassInfo *lookupPass(llvm::StringRef name);

/// Prints the registry (for --list-passes); markdown for docs/passes.md.
void printPassList(llvm::raw_ostream &os, bool markdown);

class PassManager {
public:
  /// Parses a pipeline; reports errors into `diag` with positions in the
  /// pipeline text.
  bool parsePipeline(llvm::StringRef text, DiagEngine &diag);
  bool run(net::Design &design, DiagEngine &diag);

  bool verifyEach = false;
  llvm::raw_ostream *printAfterAll = nullptr;
  Statistics stats;

private:
  struct Entry {
    const PassInfo *info;
    std::unique_ptr<Pass> pass;
  };
  std::vector<Entry> pipeline;
};

} // namespace netlift

#endif
