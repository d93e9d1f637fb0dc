//===- PassManager.cpp - NetIR pipelines ----------------------------------===//
#include "passes/Pass.h"

#include "ir/net/Printer.h"
#include "ir/net/Verifier.h"
#include "ir/support/Suggest.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"

#include <algorithm>

using namespace netlift;
using llvm::StringRef;

Pass::~Pass() = default;

bool ReportStream::open(const PassOptions &opts, StringRef pass,
                        DiagEngine &diag) {
  if (!opts.has("report"))
    return true;
  std::string path = opts.text("report");
  if (path == "-") {
    os = &llvm::outs();
    return true;
  }
  std::error_code ec;
  file = std::make_unique<llvm::raw_fd_ostream>(path, ec);
  if (ec) {
    diag.error(llvm::SMLoc(),
               pass + ": cannot write '" + path + "': " + ec.message());
    return false;
  }
  os = file.get();
  return true;
}

//===----------------------------------------------------------------------===//
// Typed option values (checked by the pipeline parser)
//===----------------------------------------------------------------------===//

std::string PassOptions::text(StringRef key, StringRef dflt) const {
  auto it = values.find(key.str());
  return it == values.end() ? dflt.str() : it->second;
}

std::vector<std::string> PassOptions::list(StringRef key) const {
  std::vector<std::string> items;
  std::string value = text(key); // the parts point into it
  llvm::SmallVector<StringRef, 8> parts;
  StringRef(value).split(parts, ',', -1, false);
  for (StringRef p : parts)
    if (!p.trim().empty())
      items.push_back(p.trim().str());
  return items;
}

uint64_t PassOptions::wholeNumber(StringRef key) const {
  uint64_t n = 0;
  StringRef(text(key)).trim().getAsInteger(10, n);
  return n;
}

double PassOptions::number(StringRef key) const {
  double d = 0;
  StringRef(text(key)).trim().getAsDouble(d);
  return d;
}

std::vector<double> PassOptions::numbers(StringRef key) const {
  std::vector<double> out;
  for (const std::string &item : list(key)) {
    double d = 0;
    StringRef(item).getAsDouble(d);
    out.push_back(d);
  }
  return out;
}

bool PassOptions::flag(StringRef key, bool dflt) const {
  if (!has(key))
    return dflt;
  std::string v = text(key);
  return v == "true" || v == "1";
}

/// Why `value` is not of `info`'s kind, or "" when it is.
static std::string checkOptionValue(const PassOptionInfo &info,
                                    StringRef value) {
  auto items = [&] {
    llvm::SmallVector<StringRef, 8> parts;
    value.split(parts, ',', -1, true);
    return parts;
  };
  // Names are checked against the model by the pass; here they only must
  // be one word each.
  auto isName = [](StringRef n) {
    n = n.trim();
    return !n.empty() && llvm::none_of(n, [](char c) {
      return isspace((unsigned char)c) || c == ',' || c == '{' || c == '}' ||
             c == '=';
    });
  };
  switch (info.kind) {
  case OptionKind::Name:
    return isName(value) ? "" : "a name";
  case OptionKind::Names:
    for (StringRef n : items())
      if (!isName(n))
        return "names separated by commas";
    return "";
  case OptionKind::Count: {
    uint64_t n;
    return !value.getAsInteger(10, n) && n >= 1 ? "" : "a whole number from 1";
  }
  case OptionKind::Number:
  case OptionKind::PositiveNumber: {
    double d;
    if (value.getAsDouble(d))
      return "a number";
    return info.kind == OptionKind::PositiveNumber && !(d > 0)
               ? "a positive number"
               : "";
  }
  case OptionKind::Numbers:
    for (StringRef n : items()) {
      double d;
      if (n.trim().getAsDouble(d))
        return "numbers separated by commas";
    }
    return "";
  case OptionKind::Bool:
    return value == "true" || value == "false" || value == "1" || value == "0"
               ? ""
               : "true or false";
  case OptionKind::File:
    return "";
  case OptionKind::Choice: {
    llvm::SmallVector<StringRef, 4> words;
    info.value.split(words, '|');
    return llvm::is_contained(words, value)
               ? ""
               : "one of " + llvm::join(words, ", ");
  }
  case OptionKind::Components:
    for (StringRef c : items()) {
      auto [n, m] = c.trim().split(':');
      if (!isName(n) || !isName(m))
        return "NAME:MODULE items separated by commas";
    }
    return "";
  }
  return "";
}

// Pass factories, one per registry line, defined in the pass's own file.
namespace netlift {
#define NETLIFT_PASS(NAME, CLASS, SUMMARY)                                     \
  std::unique_ptr<Pass> create##CLASS(const PassOptions &);
#define NETLIFT_PASS_OPTION(PASS, KEY, KIND, VALUE, MEANING)
#include "passes/PassRegistry.def"
#undef NETLIFT_PASS
#undef NETLIFT_PASS_OPTION
} // namespace netlift

static const PassInfo registry[] = {
#define NETLIFT_PASS(NAME, CLASS, SUMMARY) {#NAME, SUMMARY, create##CLASS},
#define NETLIFT_PASS_OPTION(PASS, KEY, KIND, VALUE, MEANING)
#include "passes/PassRegistry.def"
#undef NETLIFT_PASS
#undef NETLIFT_PASS_OPTION
};

static const PassOptionInfo optionRegistry[] = {
#define NETLIFT_PASS(NAME, CLASS, SUMMARY)
#define NETLIFT_PASS_OPTION(PASS, KEY, KIND, VALUE, MEANING)                   \
  {#PASS, #KEY, OptionKind::KIND, VALUE, MEANING},
#include "passes/PassRegistry.def"
#undef NETLIFT_PASS
#undef NETLIFT_PASS_OPTION
};

llvm::ArrayRef<PassInfo> netlift::passRegistry() { return registry; }

const PassInfo *netlift::lookupPass(StringRef name) {
  for (const PassInfo &p : registry)
    if (p.name == name)
      return &p;
  return nullptr;
}

std::vector<const PassOptionInfo *> PassInfo::options() const {
  std::vector<const PassOptionInfo *> out;
  for (const PassOptionInfo &o : optionRegistry)
    if (o.pass == name)
      out.push_back(&o);
  return out;
}

const PassOptionInfo *PassInfo::option(StringRef key) const {
  for (const PassOptionInfo &o : optionRegistry)
    if (o.pass == name && o.key == key)
      return &o;
  return nullptr;
}

void netlift::printPassList(llvm::raw_ostream &os, bool markdown) {
  if (markdown)
    os << "# Pass reference\n\n"
          "Generated by `netlift opt --list-passes-markdown` from "
          "`passes/PassRegistry.def`;\na test keeps this page in sync. Run "
          "passes with `netlift opt IN -p 'a,b{key=value}'`.\n\n";
  for (const PassInfo &p : registry) {
    std::vector<const PassOptionInfo *> opts = p.options();
    if (markdown) {
      os << "## `" << p.name << "`\n\n" << p.summary << ".\n\n";
      if (!opts.empty()) {
        os << "Options:\n\n";
        for (const PassOptionInfo *o : opts)
          os << "- `" << o->key << "=" << o->value << "`: " << o->meaning
             << "\n";
        os << "\n";
      }
    } else {
      os << "  " << p.name;
      os.indent(p.name.size() < 14 ? 14 - p.name.size() : 1);
      os << p.summary << "\n";
      for (const PassOptionInfo *o : opts)
        os.indent(18) << "{" << o->key << "=" << o->value << ": " << o->meaning
                      << "}\n";
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
    if (!info) {
      std::vector<std::string> names;
      for (const PassInfo &p : registry)
        names.push_back(p.name.str());
      std::string hint = closestName(name, names);
      return error(at,
                   "unknown pass '" + name + "' (" +
                       (hint.empty() ? "" : "did you mean '" + hint + "'? ") +
                       "netlift opt --list-passes lists them)");
    }
    PassOptions opts;
    skipSpace();
    if (pos < text.size() && text[pos] == '{') {
      ++pos;
      for (;;) {
        skipSpace();
        size_t kat = pos;
        StringRef key = word();
        if (key.empty())
          return error(kat, "expected an option name");
        const PassOptionInfo *option = info->option(key);
        if (!option) {
          std::vector<std::string> keys;
          for (const PassOptionInfo *o : info->options())
            keys.push_back(o->key.str());
          return error(kat, "unknown option '" + key + "' for pass '" + name +
                                "'" + didYouMean(key, keys));
        }
        skipSpace();
        if (pos >= text.size() || text[pos] != '=')
          return error(pos, "expected '=' after option '" + key + "'");
        ++pos;
        skipSpace();
        size_t vstart = pos;
        // A value may itself be a comma-separated list (`points=1,2,3`): a
        // comma ends it only when the next option `key=` follows.
        auto startsOption = [&](size_t at) {
          size_t q = at + 1;
          while (q < text.size() && isspace((unsigned char)text[q]))
            ++q;
          size_t w = q;
          while (q < text.size() &&
                 (isalnum((unsigned char)text[q]) || text[q] == '_'))
            ++q;
          if (q == w || isdigit((unsigned char)text[w]))
            return false;
          while (q < text.size() && isspace((unsigned char)text[q]))
            ++q;
          return q < text.size() && text[q] == '=';
        };
        while (pos < text.size() && text[pos] != '}' &&
               !(text[pos] == ',' && startsOption(pos)))
          ++pos;
        StringRef value = text.slice(vstart, pos).trim();
        if (value.empty())
          return error(vstart, "expected a value for option '" + key + "'");
        if (opts.has(key))
          return error(kat, "option '" + key + "' given twice");
        std::string want = checkOptionValue(*option, value);
        if (!want.empty())
          return error(value.data() - text.data(), name + ": " + key +
                                                       "= takes " + want +
                                                       ", not '" + value + "'");
        opts.set(key, value);
        if (pos >= text.size())
          return error(pos,
                       "expected '}' to close the options of '" + name + "'");
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
      diag.error(llvm::SMLoc(),
                 "the IR is invalid after pass '" + e.info->name + "'");
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
