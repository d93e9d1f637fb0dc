//===- MealyWriters.cpp - Mealy machines as KISS2 and DOT -----------------===//
#include "backends/mealy/MealyWriters.h"

using namespace netlift;
using namespace netlift::mealy;
using namespace netlift::automata;

static bool defaultNames(const std::vector<std::string> &names, char prefix) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] != prefix + std::to_string(i + 1))
      return false;
  return true;
}

void netlift::mealy::writeKiss2(const MealyMachine &m, llvm::raw_ostream &os) {
  os << ".i " << m.inputs.size() << "\n.o " << m.outputs.size() << "\n";
  if (!defaultNames(m.inputs, 'i')) {
    os << ".ilb";
    for (const std::string &n : m.inputs)
      os << ' ' << n;
    os << '\n';
  }
  if (!defaultNames(m.outputs, 'o')) {
    os << ".ob";
    for (const std::string &n : m.outputs)
      os << ' ' << n;
    os << '\n';
  }
  // A machine over symbols keeps its alphabets as comments the KISS2
  // reader understands (and other tools skip).
  for (size_t k = 0; k < m.inputSymbols.size(); ++k)
    os << "# symbol input " << vectorBits(k, m.inputs.size()) << " = "
       << m.inputSymbols[k] << '\n';
  for (size_t k = 0; k < m.outputSymbols.size(); ++k)
    os << "# symbol output " << vectorBits(k, m.outputs.size()) << " = "
       << m.outputSymbols[k] << '\n';
  os << ".p " << m.transitions.size() << "\n.s " << m.states.size() << "\n.r "
     << m.states[m.initial] << '\n';
  for (const MealyTransition &t : m.transitions)
    os << t.input << ' ' << m.states[t.from] << ' ' << m.states[t.to] << ' '
       << t.output << '\n';
  os << ".e\n";
}

/// `text` as a DOT double-quoted string.
static void quoted(llvm::raw_ostream &os, llvm::StringRef text) {
  os << '"';
  for (char c : text)
    os << (c == '"' || c == '\\' ? "\\" : "") << c;
  os << '"';
}

void netlift::mealy::writeMealyDot(const MealyMachine &m,
                                   llvm::raw_ostream &os) {
  os << "digraph mealy {\n";
  for (const std::string &s : m.states) {
    os << "  ";
    quoted(os, s);
    os << " [shape=circle, label=";
    quoted(os, s);
    os << "];\n";
  }
  os << "  __start0 [label=\"\", shape=none];\n  __start0 -> ";
  quoted(os, m.states[m.initial]);
  os << " [label=\"\"];\n";
  std::vector<uint32_t> codes;
  for (const MealyTransition &t : m.transitions) {
    auto edge = [&](const std::string &in) {
      // The reader splits at the first " / " if there is one: symbols
      // containing '/' stay whole.
      std::string out = m.outputLabel(t.output);
      bool slashes = in.find('/') != std::string::npos ||
                     out.find('/') != std::string::npos;
      os << "  ";
      quoted(os, m.states[t.from]);
      os << " -> ";
      quoted(os, m.states[t.to]);
      os << " [label=";
      quoted(os, in + (slashes ? " / " : "/") + out);
      os << "];\n";
    };
    if (!m.isSymbolic()) {
      edge(t.input);
      continue;
    }
    // One edge per symbol of the row's cube.
    codes.clear();
    cubeVectors(t.input, codes);
    for (uint32_t c : codes)
      if (c < m.inputSymbols.size())
        edge(m.inputSymbols[c]);
  }
  os << "}\n";
}

void netlift::mealy::writeMealyInfo(const automata::MealyMachine &m,
                                    llvm::raw_ostream &os) {
  std::vector<int64_t> missing = m.unspecifiedVectors();
  int64_t incomplete = 0;
  for (int64_t n : missing)
    incomplete += n > 0;
  if (m.isSymbolic())
    os << "input symbols: " << m.inputSymbols.size()
       << ", output symbols: " << m.outputSymbols.size() << ", ";
  os << "inputs: " << m.inputs.size() << ", outputs: " << m.outputs.size()
     << ", states: " << m.states.size()
     << ", transitions: " << m.transitions.size()
     << ", initial: " << m.states[m.initial] << "\n";
  if (!missing.empty() && missing[0] < 0)
    os << "completeness: not checked (more than 24 inputs)\n";
  else if (incomplete == 0)
    os << "completeness: complete\n";
  else
    for (size_t s = 0; s < missing.size(); ++s)
      if (missing[s] > 0)
        os << "state " << m.states[s] << ": " << missing[s]
           << (m.isSymbolic() ? " input symbols" : " input vectors")
           << " unspecified\n";
}
