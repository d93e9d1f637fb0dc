//===- NcesXml.h - flat modules for NCES tools (ViVe XML, .pnt) -*- C++ -*-===//
//
// Writes modules for the tools of the NCES community: ViVe's NCES XML
// (one FBType with its InterfaceList and an SNS of places, transitions and
// flow, condition and event arcs, FORMATS.md; or, for a module of
// instances, a composite FBType with an FBNetwork) and the INA-style `.pnt`
// place/transition table that SESA and INA read. NCES has no data: a module
// with variables, guards or actions must go through `lower-data` first, and
// a condition or output must be a place or a condition signal, not an
// expression; both are refused by name with that hint. docs/formats.md
// states how each NetIR construct is written.
//
//===----------------------------------------------------------------------===//
#ifndef NETLIFT_BACKENDS_NCES_NCESXML_H
#define NETLIFT_BACKENDS_NCES_NCESXML_H

#include "ir/net/Module.h"
#include "ir/support/Diagnostics.h"

#include "llvm/Support/raw_ostream.h"

namespace netlift::nces {

/// ViVe's NCES XML for flat module `m`. False after an error at the first
/// construct NCES cannot carry.
bool writeNcesXml(const net::Module &m, DiagEngine &diag,
                  llvm::raw_ostream &os);

/// ViVe's NCES XML for module `m` made of instances and connections: a
/// composite FBType whose FBNetwork mirrors them one to one (event
/// connections and condition connections). False after an error at a
/// construct NCES cannot carry (data, a module mixing instances with a net
/// of its own).
bool writeNcesComposite(const net::Module &m, DiagEngine &diag,
                        llvm::raw_ostream &os);

/// The place/transition part of flat module `m` as an INA `.pnt` table
/// (conditions, events and time are not part of it and are refused).
bool writePnt(const net::Module &m, DiagEngine &diag, llvm::raw_ostream &os);

/// `emit --to nces-xml --modular`: `top` and every module it instantiates,
/// each as `dir/<name>.xml` (modules of instances as composites). Every
/// file is built before any is written: an error leaves nothing.
bool writeNcesModules(const net::Module &top, llvm::StringRef dir,
                      DiagEngine &diag);
/// The same for the design's top module (or `topName`).
bool writeNcesModules(const net::Design &design, llvm::StringRef topName,
                      llvm::StringRef dir, DiagEngine &diag);

} // namespace netlift::nces

#endif
