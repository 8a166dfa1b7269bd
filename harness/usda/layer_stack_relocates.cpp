#include "harness/usda/layer_stack_relocates.h"

#include "harness/usda/sdf_path.h"

namespace obscura::usda {

namespace {

void collect(const std::map<std::string, Value>& metadata, const SourceLocation& where, Relocations& out,
             DiagnosticSink& diagnostics) {
    const auto pairs = metadata.find("relocates");
    if (pairs == metadata.end()) return;
    for (size_t i = 0; i + 1 < pairs->second.strings.size(); i += 2) {
        const std::string& source = pairs->second.strings[i];
        const std::string& target = pairs->second.strings[i + 1];
        if (sdfpath::hasPrefix(source, target) || sdfpath::hasPrefix(target, source)) {
            diagnostics.warn("relocates", where, "relocates <" + source + "> to <" + target + ">, inside itself; ignored");
            continue;
        }
        // Pcp: only prims brought in by an ancestor's arc can move, and a root prim has no ancestor.
        if (sdfpath::depthOf(source) < 2 || sdfpath::depthOf(target) < 2) {
            diagnostics.warn("relocates", where,
                             "relocates <" + source + "> to <" + target + ">: a root prim cannot be relocated; ignored");
            continue;
        }
        out.emplace(target, Relocation{source, where});
    }
}

void collect(const PrimSpec& spec, Relocations& out, DiagnosticSink& diagnostics) {
    collect(spec.metadata, spec.where, out, diagnostics);
    for (const auto& child : spec.children) collect(*child, out, diagnostics);
}

}  // namespace

Relocations collectRelocates(const LayerStack& stack, DiagnosticSink& diagnostics) {
    Relocations out;
    for (const Layer* layer : stack.layers) {
        collect(layer->metadata, SourceLocation{layer->identifier, 0, 0}, out, diagnostics);
        collect(layer->pseudoRoot, out, diagnostics);
    }
    return out;
}

}  // namespace obscura::usda
