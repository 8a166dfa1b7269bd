// USD's native instancing as Hydra draws it (UsdImaging's instance adapter): instanceable prims
// whose composition arcs are the same (usda/instancing_key.h) share one prototype, and the host
// serves each prototype's geometry once, under the first instance, with one instancer prim that
// places it at every instance — the delegate's instancer, as a PointInstancer is served. The reader
// composes an instance's descendants from its arcs alone (usda/prim_index.h), so the first instance
// is a faithful prototype of them all.
//
// Choices where the plugin cannot do what USD does:
//  - what an instance root hands down to its prototype's geometry (its material binding, its
//    purpose, and the constant primvars it or its ancestors author, which USD's primvar inheritance
//    gives the prototype's gprims that lack their own) is the first instance's: instances that
//    differ there are grouped apart, as UsdImaging groups them by inherited binding. Hydra serves
//    inherited primvars as the instancer's per-instance primvars, but the delegate's instancer
//    (schemas/instancer.json) carries placements and visibility only, so grouping is what keeps
//    each instance's own colour; instances that hand down the same values still share;
//  - an instance's transform reaches the instancer as position, orientation and scale (the
//    instancer's attributes), so an instance whose transform shears (at the stage's start time)
//    is not instanced: its geometry is served as any other prim's;
//  - instances inside another instance's prototype (a building's instanced windows) are drawn as
//    part of it, at every outer instance, not instanced again: Hydra nests instancers there, but the
//    delegate's instancer takes meshes as prototypes, not other instancers (schemas/instancer.json);
//  - only geometry (rprims) is instanced; cameras and lights inside instances are served at
//    every instance, and materials once, from the prototype (the geometry's bindings resolve to
//    the first instance's copies).
#pragma once

#include "harness/usda/stage.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace obscura::harness {

struct NativeInstancer {
    std::string path;                            // the instancer prim inserted for it
    const usda::Prim* prototype = nullptr;       // the first instance: its geometry is the prototype's
    std::vector<const usda::Prim*> instances;    // in stage order, `prototype` first; instanceId indexes them
};

class NativeInstancing {
public:
    // What an instance root hands down to its descendants beyond its composition arcs (binding,
    // purpose, constant primvars), as text: instances that differ there do not share a prototype.
    using HandedDown = std::function<std::string(const usda::Prim&)>;

    NativeInstancing() = default;
    // Groups the stage's instances at `time`; instances inside another instance are part of its
    // prototype (drawn with it), not instanced again.
    NativeInstancing(const usda::Stage& stage, const HandedDown& handedDown, double time);

    const std::vector<NativeInstancer>& instancers() const { return instancers_; }
    const NativeInstancer* instancer(const std::string& path) const;
    // Whether `prim` lies in an instance other than its prototype's first: its geometry is drawn
    // through the instancer, not served itself.
    bool drawnByInstancer(const usda::Prim& prim) const;
    // The instancer whose prototype (the first instance) holds `prim`, or null.
    const NativeInstancer* prototypeHolding(const usda::Prim& prim) const;
    // Whether the instances' placements or visibility can change over time.
    bool hasAnimatedTransforms(const NativeInstancer& instancer, const usda::Stage& stage) const;
    bool hasAnimatedVisibility(const NativeInstancer& instancer, const usda::Stage& stage) const;

    // The instancer's attributes at `time` (schemas/instancer.json): protoIndices, positions,
    // orientations, scales and invisibleIds; nullopt for the others.
    std::optional<usda::Value> value(const NativeInstancer& instancer, const usda::Stage& stage,
                                     const std::string& attribute, double time) const;

private:
    std::vector<NativeInstancer> instancers_;
    std::unordered_map<std::string, size_t> byPath_;                  // instancer path -> index
    std::unordered_map<const usda::Prim*, size_t> prototypes_;        // first instance -> instancer
    std::unordered_set<const usda::Prim*> others_;                    // the instances after the first
};

// Whether two instancers (of a stage and of the one read before it) place the same instances of
// the same prototype, the same way at `time` and over time, and show the same ones.
bool samePlacements(const NativeInstancer& a, const usda::Stage& stageOfA, const NativeInstancer& b,
                    const usda::Stage& stageOfB, double time);

// A row-vector transform (usda/matrix4.h) as USD's instance transform: translation, rotation as
// a unit quaternion (w, x, y, z, real part first) and scale along the rotated axes; nullopt when
// it shears (the rows are not perpendicular), which that form cannot hold.
struct InstancePlacement {
    std::array<double, 3> position;
    std::array<double, 4> orientation;
    std::array<double, 3> scale;
};
std::optional<InstancePlacement> decomposeInstanceTransform(const std::array<double, 16>& m);

}  // namespace obscura::harness
