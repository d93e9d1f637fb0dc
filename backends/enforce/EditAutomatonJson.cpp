//===- EditAutomatonJson.cpp - edit automata as JSON ----------------------===//
#include "backends/enforce/EditAutomatonJson.h"

#include "llvm/Support/JSON.h"
#include "llvm/Support/MemoryBuffer.h"

#include <map>

using namespace netlift;
using namespace netlift::enforce;
using namespace netlift::automata;
using llvm::StringRef;

static constexpr StringRef kFormat = "netlift-edit-automaton";

/// A JSON string literal.
static void quoted(llvm::raw_ostream &os, StringRef s) {
  os << llvm::json::Value(s.str());
}

// Written by hand rather than through json::OStream so that each
// transition is one line: the files are read by people and diffed.
void netlift::enforce::writeEditAutomatonJson(const EditAutomaton &ea,
                                              llvm::raw_ostream &os) {
  os << "{\n  \"format\": \"" << kFormat << "\",\n  \"version\": 1,\n"
     << "  \"inputs\": [";
  for (size_t i = 0; i < ea.signals.size(); ++i) {
    if (i == ea.numInputs)
      os << "],\n  \"outputs\": [";
    else if (i)
      os << ", ";
    quoted(os, ea.signals[i]);
  }
  if (ea.numInputs == ea.signals.size())
    os << "],\n  \"outputs\": [";
  os << "],\n  \"initial\": ";
  quoted(os, ea.states[ea.initial].name);
  os << ",\n  \"states\": [\n";
  for (size_t s = 0; s < ea.states.size(); ++s) {
    os << "    {\"name\": ";
    quoted(os, ea.states[s].name);
    os << ", \"specified\": " << (ea.states[s].specified ? "true" : "false")
       << "}" << (s + 1 < ea.states.size() ? "," : "") << "\n";
  }
  os << "  ],\n  \"transitions\": [\n";
  for (size_t k = 0; k < ea.transitions.size(); ++k) {
    const EditTransition &t = ea.transitions[k];
    os << "    {\"from\": ";
    quoted(os, ea.states[t.from].name);
    os << ", \"event\": \"" << t.event << "\", \"kind\": \""
       << (t.kind == EditKind::Validate ? "validate" : "suppress")
       << "\", \"to\": ";
    quoted(os, ea.states[t.to].name);
    os << "}" << (k + 1 < ea.transitions.size() ? "," : "") << "\n";
  }
  os << "  ]\n}\n";
}

namespace {
/// Reports problems at the place of a JSON value in the file: llvm::json
/// keeps no positions, so the reader names the value by its path and finds
/// it in the text (the n-th occurrence of its key inside its array).
class JsonReader {
public:
  JsonReader(StringRef buf, DiagEngine &diag) : buf(buf), diag(diag) {}

  bool fail(const llvm::Twine &path, const llvm::Twine &msg,
            size_t offset = 0) {
    diag.error(llvm::SMLoc::getFromPointer(buf.data() + offset),
               path + ": " + msg);
    return false;
  }
  /// The offset of the `index`-th object of array `array` (approximate: the
  /// index-th '{' after the array's key), for error positions.
  size_t elementOffset(StringRef array, size_t index) const {
    size_t at = buf.find(("\"" + array + "\"").str());
    if (at == StringRef::npos)
      return 0;
    for (size_t k = 0;; ++k) {
      at = buf.find('{', at + 1);
      if (at == StringRef::npos)
        return 0;
      if (k == index)
        return at;
    }
  }

  StringRef buf;
  DiagEngine &diag;
};
} // namespace

bool netlift::enforce::readEditAutomatonJson(unsigned bufferID,
                                             DiagEngine &diag,
                                             EditAutomaton &ea) {
  StringRef buf = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  JsonReader r(buf, diag);
  llvm::Expected<llvm::json::Value> parsed = llvm::json::parse(buf);
  if (!parsed) {
    // llvm::json says "[LINE:COL, byte=N]: message".
    std::string msg = llvm::toString(parsed.takeError());
    size_t offset = 0;
    size_t byte = msg.find("byte=");
    // It counts the offending character as read: point at it.
    if (byte != std::string::npos)
      offset = std::min<size_t>(std::stoul(msg.substr(byte + 5)), buf.size());
    if (offset > 0)
      --offset;
    size_t colon = msg.find("]: ");
    diag.error(llvm::SMLoc::getFromPointer(buf.data() + offset),
               "malformed JSON: " +
                   (colon == std::string::npos ? msg : msg.substr(colon + 3)));
    return false;
  }
  const llvm::json::Object *root = parsed->getAsObject();
  auto format = root ? root->getString("format") : llvm::None;
  if (!format || *format != kFormat)
    return r.fail("format", "not a netlift edit automaton (expected "
                            "\"format\": \"" +
                                kFormat + "\")");
  auto version = root->getInteger("version");
  if (!version || *version != 1)
    return r.fail("version", "only version 1 is read");
  auto names = [&](StringRef key, std::vector<std::string> &out) {
    const llvm::json::Array *a = root->getArray(key);
    if (!a)
      return r.fail(key, "expected an array of signal names");
    for (const llvm::json::Value &v : *a) {
      auto s = v.getAsString();
      if (!s)
        return r.fail(key, "expected an array of signal names");
      out.push_back(s->str());
    }
    return true;
  };
  std::vector<std::string> outputs;
  if (!names("inputs", ea.signals) || !names("outputs", outputs))
    return false;
  ea.numInputs = ea.signals.size();
  ea.signals.insert(ea.signals.end(), outputs.begin(), outputs.end());

  std::map<std::string, uint32_t> stateIndex;
  const llvm::json::Array *states = root->getArray("states");
  if (!states || states->empty())
    return r.fail("states", "expected a non-empty array of states");
  for (size_t k = 0; k < states->size(); ++k) {
    std::string path = "states[" + std::to_string(k) + "]";
    const llvm::json::Object *o = (*states)[k].getAsObject();
    auto name = o ? o->getString("name") : llvm::None;
    auto specified = o ? o->getBoolean("specified") : llvm::None;
    if (!name || !specified)
      return r.fail(path, "expected {\"name\": ..., \"specified\": ...}",
                    r.elementOffset("states", k));
    if (!stateIndex.emplace(name->str(), ea.states.size()).second)
      return r.fail(path, "state '" + *name + "' is listed twice",
                    r.elementOffset("states", k));
    ea.states.push_back({name->str(), *specified});
  }
  auto initial = root->getString("initial");
  if (!initial || !stateIndex.count(initial->str()))
    return r.fail("initial", "expected the name of a listed state");
  ea.initial = stateIndex[initial->str()];
  if (!ea.states[ea.initial].specified)
    return r.fail("initial", "the initial state must be a specified state");

  const llvm::json::Array *transitions = root->getArray("transitions");
  if (!transitions)
    return r.fail("transitions", "expected an array of transitions");
  for (size_t k = 0; k < transitions->size(); ++k) {
    std::string path = "transitions[" + std::to_string(k) + "]";
    size_t at = r.elementOffset("transitions", k);
    const llvm::json::Object *o = (*transitions)[k].getAsObject();
    auto from = o ? o->getString("from") : llvm::None;
    auto to = o ? o->getString("to") : llvm::None;
    auto event = o ? o->getString("event") : llvm::None;
    auto kind = o ? o->getString("kind") : llvm::None;
    if (!from || !to || !event || !kind)
      return r.fail(path, "expected {\"from\", \"event\", \"kind\", \"to\"}",
                    at);
    for (auto name : {*from, *to})
      if (!stateIndex.count(name.str()))
        return r.fail(path, "unknown state '" + name + "'", at);
    if (event->size() != ea.signals.size() ||
        event->find_first_not_of("01") != StringRef::npos)
      return r.fail(path,
                    "event '" + *event + "' is not " +
                        llvm::Twine(ea.signals.size()) + " 0/1 digits",
                    at);
    if (*kind != "validate" && *kind != "suppress")
      return r.fail(path, "kind '" + *kind + "' is not validate or suppress",
                    at);
    EditTransition t{stateIndex[from->str()], event->str(),
                     *kind == "validate" ? EditKind::Validate
                                         : EditKind::Suppress,
                     stateIndex[to->str()]};
    if (!ea.add(t))
      return r.fail(path,
                    "a second transition from '" + *from + "' on " + *event +
                        " (the automaton must be deterministic)",
                    at);
  }
  return true;
}
