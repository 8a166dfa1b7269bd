// A Skeleton drawn as a guide, as Storm draws one (UsdSkelImaging's bone mesh, purpose guide):
// each joint that has a parent is joined to it by a thin bone, a square pyramid whose base sits at
// the parent joint and whose apex is the joint. The mesh is in the skeleton's space, posed by its
// animation at a time code; its topology does not change over time, so an animated skeleton only
// moves its points.
#pragma once

#include "harness/usda/skinning.h"

namespace obscura::usda {

// The base's half-width as a share of the bone's length: thin enough to read as a line between
// joints, wide enough to cover pixels at the sizes a skeleton is viewed at.
constexpr double kBoneHalfWidth = 0.1;

struct BoneMesh {
    Value points;             // point3f[], xyz per point: per bone four base corners, then the apex
    Value faceVertexCounts;   // int[]: per bone four triangular sides, then the base
    Value faceVertexIndices;  // int[]
};

// The number of bones: joints with a parent.
size_t boneCount(const Skinning& skeleton);
// The bones of `skeleton` (resolveSkeleton) posed at `time`; `problem` as skeletonPose sets it.
BoneMesh boneMesh(const Skinning& skeleton, double time, std::string* problem);

}  // namespace obscura::usda
