//===- MealyWriters.cpp - Mealy machines as KISS2 and DOT -----------------===//
#include "backends/mealy/MealyWriters.h"

using namespace netlift;
using namespace netlift::automata;

static bool defaultNames(const std::vector<std::string> &names, char prefix) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] != prefix + std::to_string(i + 1))
      return false;
  return true;
}

void netlift::writeKiss2(const MealyMachine &m, llvm::raw_ostream &os) {
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
  os << ".p " << m.transitions.size() << "\n.s " << m.states.size() << "\n.r "
     << m.states[m.initial] << '\n';
  for (const MealyTransition &t : m.transitions)
    os << t.input << ' ' << m.states[t.from] << ' ' << m.states[t.to] << ' '
       << t.output << '\n';
  os << ".e\n";
}

void netlift::writeMealyDot(const MealyMachine &m, llvm::raw_ostream &os) {
  os << "digraph mealy {\n";
  for (const std::string &s : m.states)
    os << "  \"" << s << "\" [shape=circle, label=\"" << s << "\"];\n";
  os << "  __start0 [label=\"\", shape=none];\n  __start0 -> \""
     << m.states[m.initial] << "\" [label=\"\"];\n";
  for (const MealyTransition &t : m.transitions)
    os << "  \"" << m.states[t.from] << "\" -> \"" << m.states[t.to]
       << "\" [label=\"" << t.input << '/' << t.output << "\"];\n";
  os << "}\n";
}
