//===- PassManager.cpp - NetIR pipelines ----------------------------------===//
#include "passes/Pass.h"

#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"

#include "llvm/Support/MemoryBuffer.h"

#include <algorithm>

using namespace netlift;
using llvm::StringRef;

Pass::~Pass() = default;

// Pass factories, one per registry line, defined in the pass's own file.
namespace netlift {
#define NETLIFT_PASS(NAME, CLASS, SUMMARY, OPTIONS)                           \
  std::unique_ptr<Pass> create##CLASS(const PassOptions &);
#include "passes/PassRegistry.def"
#undef NETLIFT_PASS
} // namespace netlift

static const PassInfo registry[] = {
#define NETLIFT_PASS(NAME, CLASS, SUMMARY, OPTIONS)                           \
  {#NAME, SUMMARY, OPTIONS, create##CLASS},
#include "passes/PassRegistry.def"
#undef NETLIFT_PASS
};

llvm::ArrayRef<PassInfo> netlift::passRegistry() { return registry; }

const PassInfo *netlift::lookupPass(StringRef name) {
  for (const PassInfo &p : registry)
    if (p.name == name)
      return &p;
  return nullptr;
}

std::vector<std::string> PassInfo::optionKeys() const {
  std::vector<std::string> keys;
  llvm::SmallVector<StringRef, 4> parts;
  options.split(parts, ';', -1, false);
  for (StringRef p : parts)
    keys.push_back(p.trim().split('=').first.trim().str());
  return keys;
}

void netlift::printPassList(llvm::raw_ostream &os, bool markdown) {
  for (const PassInfo &p : registry) {
    llvm::SmallVector<StringRef, 4> opts;
    p.options.split(opts, ';', -1, false);
    if (markdown) {
      os << "## `" << p.name << "`\n\n" << p.summary << ".\n\n";
      if (!opts.empty()) {
        os << "Options:\n\n";
        for (StringRef o : opts)
          os << "- `" << o.trim().split(':').first << "`:"
             << o.trim().split(':').second << "\n";
        os << "\n";
      }
    } else {
      os << "  " << p.name;
      os.indent(p.name.size() < 14 ? 14 - p.name.size() : 1);
      os << p.summary << "\n";
      for (StringRef o : opts)
        os.indent(18) << "{" << o.trim() << "}\n";
    }
  }
}

void Statistics::add(StringRef pass, StringRef counter, uint64_t n,
                     StringRef desc) {
  Counter &c = counters[{pass.str(), counter.str()}];
  c.value += n;
  c.desc = desc.str();
}

void Statistics::print(llvm::raw_ostream &os) const {
  os << "===-------------------------------------------------------------"
        "-----===\n"
     << "                    ... Statistics Collected ...\n"
     << "===-------------------------------------------------------------"
        "-----===\n";
  for (const auto &[key, c] : counters) {
    std::string v = std::to_string(c.value);
    os.indent(v.size() < 8 ? 8 - v.size() : 0);
    os << v << " " << key.first << " - " << c.desc << "\n";
  }
}

namespace {
/// Recursive-descent parser of `pass{k=v,k=v},pass`.
class PipelineParser {
public:
  PipelineParser(StringRef text, DiagEngine &diag)
      : text(text), pos(0), diag(diag) {}
  bool parse(std::vector<std::pair<const PassInfo *, PassOptions>> &out);

private:
  llvm::SMLoc loc(size_t at) const {
    return llvm::SMLoc::getFromPointer(text.data() + at);
  }
  bool error(size_t at, const llvm::Twine &msg) {
    diag.error(loc(at), msg);
    return false;
  }
  void skipSpace() {
    while (pos < text.size() && isspace((unsigned char)text[pos]))
      ++pos;
  }
  StringRef word() {
    size_t start = pos;
    while (pos < text.size() &&
           (isalnum((unsigned char)text[pos]) || text[pos] == '_' ||
            text[pos] == '-' || text[pos] == '.'))
      ++pos;
    return text.slice(start, pos);
  }
  StringRef text;
  size_t pos;
  DiagEngine &diag;
};
} // namespace

bool PipelineParser::parse(
    std::vector<std::pair<const PassInfo *, PassOptions>> &out) {
  skipSpace();
  if (pos == text.size())
    return error(0, "empty pipeline");
  for (;;) {
    skipSpace();
    size_t at = pos;
    StringRef name = word();
    if (name.empty())
      return error(at, "expected a pass name");
    const PassInfo *info = lookupPass(name);
    if (!info)
      return error(at, "unknown pass '" + name +
                           "' (netlift opt --list-passes lists them)");
    PassOptions opts;
    skipSpace();
    if (pos < text.size() && text[pos] == '{') {
      ++pos;
      std::vector<std::string> keys = info->optionKeys();
      for (;;) {
        skipSpace();
        size_t kat = pos;
        StringRef key = word();
        if (key.empty())
          return error(kat, "expected an option name");
        if (std::find(keys.begin(), keys.end(), key.str()) == keys.end())
          return error(kat, "unknown option '" + key + "' for pass '" + name +
                                "'");
        skipSpace();
        if (pos >= text.size() || text[pos] != '=')
          return error(pos, "expected '=' after option '" + key + "'");
        ++pos;
        skipSpace();
        size_t vstart = pos;
        while (pos < text.size() && text[pos] != ',' && text[pos] != '}')
          ++pos;
        StringRef value = text.slice(vstart, pos).trim();
        if (value.empty())
          return error(vstart, "expected a value for option '" + key + "'");
        if (opts.count(key.str()))
          return error(kat, "option '" + key + "' given twice");
        opts[key.str()] = value.str();
        if (pos >= text.size())
          return error(pos, "expected '}' to close the options of '" + name +
                                "'");
        if (text[pos++] == '}')
          break;
      }
    }
    out.push_back({info, std::move(opts)});
    skipSpace();
    if (pos == text.size())
      return true;
    if (text[pos] != ',')
      return error(pos, "expected ',' between passes");
    ++pos;
  }
}

bool PassManager::parsePipeline(StringRef text, DiagEngine &diag) {
  auto &sm = diag.sourceMgr();
  unsigned id = sm.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, "<pipeline>"), llvm::SMLoc());
  StringRef copy = sm.getMemoryBuffer(id)->getBuffer();
  std::vector<std::pair<const PassInfo *, PassOptions>> parsed;
  if (!PipelineParser(copy, diag).parse(parsed))
    return false;
  for (auto &[info, opts] : parsed)
    pipeline.push_back({info, info->create(opts)});
  return true;
}

bool PassManager::run(net::Design &design, DiagEngine &diag) {
  for (Entry &e : pipeline) {
    if (!e.pass->run(design, diag, stats))
      return false;
    if (verifyEach && !net::verifyDesign(design, diag)) {
      llvm::errs() << "netlift: error: the IR is invalid after pass '"
                   << e.info->name << "'\n";
      return false;
    }
    if (printAfterAll) {
      *printAfterAll << "// -----// IR after " << e.info->name
                     << " //----- //\n";
      net::printDesign(design, *printAfterAll);
    }
  }
  return true;
}
