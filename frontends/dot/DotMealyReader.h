//===- DotMealyReader.h - Mealy machines drawn in Graphviz DOT --*- C++ -*-===//
//
// Reads a Mealy machine written in DOT the way AALpy, LearnLib/AutomataLib
// and the Automata Wiki write them: one node per state, edges labelled
// `input/output` (spaces around the slash allowed, symbols with spaces,
// `&`, `|`, parentheses kept whole), a start pseudo-node (`__start0`, or a
// node with `shape=none|point` and an empty label) pointing at the initial
// state. The graph is parsed with the full DOT syntax (strict, subgraphs
// flattened, attribute defaults, ports, `+` string concatenation,
// comments); HTML labels are refused. Labels that are 0/1 vectors on both
// sides give a machine over Boolean signals (what `mealy --to dot` writes);
// any other labels a machine over symbols (Mealy.h). Moore machines
// (outputs on `record` nodes), DFAs and Moore-style edges without an
// output, and probabilistic edges (`a:0.5`, MDPs and Markov chains) are
// refused by name at the node or edge. docs/formats.md has the rules.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_FRONTENDS_DOT_DOTMEALYREADER_H
#define NETLIFT_FRONTENDS_DOT_DOTMEALYREADER_H

#include "ir/automata/Mealy.h"
#include "ir/support/Diagnostics.h"

namespace netlift::dot {

bool readMealyDot(unsigned bufferID, DiagEngine &diag,
                  automata::MealyMachine &machine);

} // namespace netlift::dot

#endif
