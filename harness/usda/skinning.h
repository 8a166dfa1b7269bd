// UsdSkel for the host: a point-based prim's binding to a Skeleton and its SkelAnimation resolved
// as UsdSkelBindingAPI, UsdSkelSkeletonQuery and UsdSkelSkinningQuery resolve them, its blend
// shapes weighted by the animation, and linear blend skinning of its points and normals at a time
// code, as UsdSkelImaging's skinPointsLBS and skinNormalsLBS kernels compute it
// (https://openusd.org/release/api/usd_skel_page_front.html).
// The host serves the skinned points as the prim's `points`, so the delegate samples them over the
// shutter like any deforming mesh's.
#pragma once

#include "harness/usda/matrix4.h"
#include "harness/usda/stage.h"

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace obscura::usda {

using matrix4::Matrix4;

// What is wrong with a prim's skinning data; the prim is drawn unskinned (at its rest points).
struct SkinningProblem {
    std::string message;
    SourceLocation where;  // the offending attribute or relationship
};

// A BlendShape prim bound to a skinned prim: point offsets added with the animation's weight.
// XXX: inbetween shapes and normalOffsets are not applied.
struct BlendShape {
    std::string name;                // as the prim's skel:blendShapes names it
    std::vector<double> offsets;     // xyz per offset
    std::vector<int> pointIndices;   // the point each offset moves; empty: one offset per point
    int animationIndex = -1;         // in the animation's blendShapes, -1 when it has no weight
    SourceLocation where;
};

struct Skinning {
    const Prim* prim = nullptr;       // the skinned prim
    const Prim* skeleton = nullptr;   // bound through skel:skeleton, inherited down namespace
    const Prim* animation = nullptr;  // the skeleton's skel:animationSource; null: rest pose
    std::vector<std::string> joints;        // the skeleton's joints, parents first
    std::vector<int> parents;               // per joint: its parent's index, -1 for a root
    std::vector<Matrix4> bindTransforms;    // per joint, skeleton space
    std::vector<Matrix4> restTransforms;    // per joint, parent space
    std::vector<int> animatedJoint;         // per skeleton joint: its index in the animation's joints, -1
    int influencesPerPoint = 0;             // elementSize of jointIndices / jointWeights; 0: blend shapes only
    bool constantInfluences = false;        // constant interpolation: one set for every point
    std::vector<int> influenceJoints;       // skeleton joint of each influence
    std::vector<float> influenceWeights;
    Matrix4 geomBindTransform = matrix4::identity();
    std::vector<BlendShape> blendShapes;
};

// A Skeleton's joints, rest pose and animation as UsdSkelSkeletonQuery reads them: the fields of
// Skinning that do not depend on a skinned prim (`prim` null, no influences).
std::variant<Skinning, SkinningProblem> resolveSkeleton(const Stage& stage, const Prim& skeleton);

// The skinning of `prim`, nullopt when it has none (no skeleton bound, or neither joint influences
// nor blend shapes), or what makes its data unusable.
std::optional<std::variant<Skinning, SkinningProblem>> resolveSkinning(const Stage& stage, const Prim& prim);

// Each joint's pose in skeleton space at `time`: the animation's joints composed down the
// hierarchy, rest transforms for the joints it leaves out. An animation whose arrays do not match
// its joints poses nothing: the rest pose is used and `problem` says why.
std::vector<Matrix4> skeletonPose(const Skinning& skinning, double time, std::string* problem);
// Each joint's skinning transform at `time`: its bind transform inverted, then its pose.
std::vector<Matrix4> skinningTransforms(const Skinning& skinning, double time, std::string* problem);

// Rest points (xyz) skinned at `time`, in the prim's own space: moved by the blend shapes' offsets
// times the animation's weights, then to bind space (geomBindTransform), blended over the joints'
// skinning transforms, then from the skeleton's space to the prim's (the prim's own transform
// cancels: skinned geometry follows the skeleton); without joint influences the shaped points
// stay in the prim's space. Empty with `problem` set when the influences or a shape's point
// indices do not fit the points.
std::vector<double> skinPoints(const Stage& stage, const Skinning& skinning, const std::vector<double>& rest,
                               double time, std::string* problem);
// Rest normals skinned the same way by the inverse transposes; `faceVertexIndices` maps
// faceVarying normals to their points (null for vertex normals).
std::vector<double> skinNormals(const Stage& stage, const Skinning& skinning, const std::vector<double>& rest,
                                const std::vector<double>* faceVertexIndices, size_t pointCount, double time,
                                std::string* problem);

// Whether the skinned result can change over time: the animation (joints or blend shape weights),
// the skeleton's or the prim's (when there is one) transform is time-sampled.
bool isSkinningAnimated(const Stage& stage, const Skinning& skinning);

}  // namespace obscura::usda
