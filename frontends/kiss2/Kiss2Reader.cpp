//===- Kiss2Reader.cpp - KISS2 finite state machines ----------------------===//
#include "frontends/kiss2/Kiss2Reader.h"

#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"

#include <algorithm>

using namespace netlift;
using namespace netlift::kiss2;
using namespace netlift::automata;
using llvm::StringRef;

namespace {
struct Field {
  StringRef text;
  llvm::SMLoc loc() const { return llvm::SMLoc::getFromPointer(text.data()); }
};

void splitFields(StringRef line, llvm::SmallVectorImpl<Field> &out) {
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
    size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t')
      ++i;
    if (i > start)
      out.push_back({line.slice(start, i)});
  }
}
} // namespace

bool netlift::kiss2::readKiss2(unsigned bufferID, DiagEngine &diag,
                               MealyMachine &m) {
  StringRef buf = diag.sourceMgr().getMemoryBuffer(bufferID)->getBuffer();
  auto err = [&](llvm::SMLoc loc, const llvm::Twine &msg) {
    diag.error(loc, msg);
    return false;
  };
  int numIn = -1, numOut = -1;
  int64_t declaredRows = -1, declaredStates = -1;
  std::string reset;
  llvm::SMLoc resetLoc;
  std::vector<std::string> ilb, ob;
  llvm::SMLoc ilbLoc, obLoc, inLegendLoc, outLegendLoc;
  bool ended = false;
  StringRef rest = buf;
  while (!rest.empty() && !ended) {
    auto [rawLine, next] = rest.split('\n');
    rest = next;
    StringRef trimmed = rawLine.trim();
    // netlift's legend of a machine over symbols (MealyWriters.cpp):
    // `# symbol input|output CODE = SYMBOL`, codes 0, 1, ... in order.
    if (trimmed.consume_front("# symbol ")) {
      bool isInput = trimmed.consume_front("input ");
      if (!isInput && !trimmed.consume_front("output "))
        return err(llvm::SMLoc::getFromPointer(trimmed.data()),
                   "expected 'input' or 'output' in a symbol legend line");
      auto &symbols = isInput ? m.inputSymbols : m.outputSymbols;
      auto [code, symbol] = trimmed.split(" = ");
      if (symbol.empty() || code != vectorBits(symbols.size(), code.size()))
        return err(llvm::SMLoc::getFromPointer(trimmed.data()),
                   "expected '" + vectorBits(symbols.size(), code.size()) +
                       " = SYMBOL' (symbol codes count up from 0)");
      symbols.push_back(symbol.str());
      (isInput ? inLegendLoc : outLegendLoc) =
          llvm::SMLoc::getFromPointer(trimmed.data());
      continue;
    }
    StringRef line = rawLine.split('#').first.rtrim("\r");
    llvm::SmallVector<Field, 8> f;
    splitFields(line, f);
    if (f.empty())
      continue;
    for (const Field &x : f)
      for (char c : x.text)
        if ((unsigned char)c < 0x20 || (unsigned char)c >= 0x7f)
          return err(x.loc(), "unexpected byte in a KISS2 file (is this a "
                              "KISS2 file?)");
    StringRef head = f[0].text;
    if (head.startswith(".")) {
      auto number = [&](int64_t &out) {
        if (f.size() != 2 || f[1].text.getAsInteger(10, out) || out < 0)
          return err(f[0].loc(), "'" + head + "' needs one number");
        return true;
      };
      if (head == ".i" || head == ".o") {
        int64_t n;
        if (!number(n))
          return false;
        if (n > 64)
          return err(f[1].loc(),
                     "more than 64 " +
                         StringRef(head == ".i" ? "inputs" : "outputs") +
                         " are not supported");
        (head == ".i" ? numIn : numOut) = int(n);
      } else if (head == ".p") {
        if (!number(declaredRows))
          return false;
      } else if (head == ".s") {
        if (!number(declaredStates))
          return false;
      } else if (head == ".r") {
        if (f.size() != 2)
          return err(f[0].loc(), "'.r' needs one state name");
        reset = f[1].text.str();
        resetLoc = f[1].loc();
      } else if (head == ".ilb" || head == ".ob") {
        auto &names = head == ".ilb" ? ilb : ob;
        (head == ".ilb" ? ilbLoc : obLoc) = f[0].loc();
        for (size_t i = 1; i < f.size(); ++i)
          names.push_back(f[i].text.str());
      } else if (head == ".e" || head == ".end") {
        ended = true;
      } else {
        return err(f[0].loc(), "unsupported KISS2 directive '" + head + "'");
      }
      continue;
    }
    if (numIn < 0 || numOut < 0)
      return err(f[0].loc(),
                 "a transition before '.i' and '.o' gave the signal counts");
    if (f.size() != 4)
      return err(f[0].loc(), "a transition has 4 fields (inputs, state, next "
                             "state, outputs), this line has " +
                                 llvm::Twine(f.size()));
    auto checkCube = [&](const Field &x, int n, StringRef what) {
      if (int(x.text.size()) != n)
        return err(x.loc(), what + " '" + x.text + "' has " +
                                llvm::Twine(x.text.size()) +
                                " characters, expected " + llvm::Twine(n));
      for (size_t i = 0; i < x.text.size(); ++i)
        if (x.text[i] != '0' && x.text[i] != '1' && x.text[i] != '-')
          return err(llvm::SMLoc::getFromPointer(x.text.data() + i),
                     "unexpected '" + x.text.substr(i, 1) + "' in " + what +
                         " (expected 0, 1 or -)");
      return true;
    };
    if (!checkCube(f[0], numIn, "the input cube") ||
        !checkCube(f[3], numOut, "the output vector"))
      return false;
    for (int k : {1, 2})
      if (f[k].text == "*")
        return err(f[k].loc(), "'*' (any state) is not supported");
    MealyTransition t;
    t.input = f[0].text.str();
    t.from = m.stateIndex(f[1].text.str());
    t.to = m.stateIndex(f[2].text.str());
    t.output = f[3].text.str();
    t.loc = f[0].loc();
    m.transitions.push_back(std::move(t));
  }
  llvm::SMLoc start = llvm::SMLoc::getFromPointer(buf.data());
  if (numIn < 0 || numOut < 0)
    return err(start, "not a KISS2 machine: '.i' and '.o' are missing");
  if (m.transitions.empty())
    return err(start, "the machine has no transitions");
  if (!ilb.empty() && int(ilb.size()) != numIn)
    return err(ilbLoc, "'.ilb' names " + llvm::Twine(ilb.size()) +
                           " inputs, but '.i' says " + llvm::Twine(numIn));
  if (!ob.empty() && int(ob.size()) != numOut)
    return err(obLoc, "'.ob' names " + llvm::Twine(ob.size()) +
                          " outputs, but '.o' says " + llvm::Twine(numOut));
  if (m.inputSymbols.empty() != m.outputSymbols.empty())
    return err(m.inputSymbols.empty() ? outLegendLoc : inLegendLoc,
               "a symbol legend needs both input and output symbols");
  if (!m.inputSymbols.empty() &&
      (MealyMachine::symbolWidth(m.inputSymbols.size()) != unsigned(numIn) ||
       MealyMachine::symbolWidth(m.outputSymbols.size()) != unsigned(numOut)))
    return err(inLegendLoc,
               "the symbol legend does not match '.i'/'.o' (" +
                   llvm::Twine(m.inputSymbols.size()) + " input and " +
                   llvm::Twine(m.outputSymbols.size()) + " output symbols)");
  for (int i = 0; i < numIn; ++i)
    m.inputs.push_back(ilb.empty() ? "i" + std::to_string(i + 1) : ilb[i]);
  for (int i = 0; i < numOut; ++i)
    m.outputs.push_back(ob.empty() ? "o" + std::to_string(i + 1) : ob[i]);
  if (!reset.empty()) {
    auto it = std::find(m.states.begin(), m.states.end(), reset);
    if (it == m.states.end())
      return err(resetLoc,
                 "reset state '" + reset + "' has no transition from or to it");
    m.initial = uint32_t(it - m.states.begin());
  } else {
    m.initial = m.transitions[0].from;
  }
  if (declaredRows >= 0 && declaredRows != int64_t(m.transitions.size()))
    diag.warning(start, "'.p' says " + llvm::Twine(declaredRows) +
                            " transitions, the file has " +
                            llvm::Twine(m.transitions.size()));
  if (declaredStates >= 0 && declaredStates != int64_t(m.states.size()))
    diag.warning(start, "'.s' says " + llvm::Twine(declaredStates) +
                            " states, the file has " +
                            llvm::Twine(m.states.size()));
  return true;
}
