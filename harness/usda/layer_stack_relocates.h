// The relocates a layer stack authors (its layers' metadata and its prims', anchored to the prim
// by the parser). Relocates belong to the layer stack's composition: they move prims within the
// stack's own namespace, and that namespace is mapped through the arcs that reach the stack, so a
// referenced asset's relocates apply under whatever path references it (Pcp's layer stack
// relocates).
#pragma once

#include <map>
#include <string>

#include "harness/usda/diagnostics.h"
#include "harness/usda/layer_registry.h"

namespace obscura::usda {

struct Relocation {
    std::string source;
    SourceLocation where;  // where it is authored: the prim's spec, or the layer for layer metadata
};

// Target path -> relocation, in the stack's namespace.
using Relocations = std::map<std::string, Relocation>;

// Stronger layers first, so the first opinion on a target wins. A relocate Pcp rejects (source and
// target nested in each other, which would repeat namespace; a root prim as either end, which no
// arc can bring) is reported and left out.
Relocations collectRelocates(const LayerStack& stack, DiagnosticSink& diagnostics);

}  // namespace obscura::usda
