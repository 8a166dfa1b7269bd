#include "delegate/material_subsets.h"

#include <algorithm>

namespace obscura::delegate {

std::string subsetSubject(const MaterialSubsets& subsets, size_t subset, const std::string& meshPath) {
    return subset < subsets.paths.size() ? subsets.paths[subset] : meshPath + ": material subset " + std::to_string(subset);
}

FaceGroups assignFaceGroups(const MaterialSubsets& subsets, size_t faceCount, const std::string& meshPath) {
    FaceGroups out;
    if (subsets.faceCounts.empty()) return out;
    int64_t total = 0;
    for (size_t subset = 0; subset < subsets.faceCounts.size(); ++subset) {
        if (subsets.faceCounts[subset] < 0) {
            out.warnings.push_back(meshPath + ": materialSubsets:faceCounts[" + std::to_string(subset) + "] is " +
                                   std::to_string(subsets.faceCounts[subset]) + "; material subsets ignored");
            return out;
        }
        total += subsets.faceCounts[subset];
    }
    if (total != int64_t(subsets.faceIndices.size())) {
        out.warnings.push_back(meshPath + ": materialSubsets:faceCounts sum to " + std::to_string(total) +
                               " but materialSubsets:faceIndices has " + std::to_string(subsets.faceIndices.size()) +
                               " entries; material subsets ignored");
        return out;
    }
    // UsdGeomSubset's family types: only unrestricted lets a face be in two subsets.
    const bool overlapsAllowed = subsets.familyType == "unrestricted";
    out.groups.assign(faceCount, 0);
    size_t next = 0;
    for (size_t subset = 0; subset < subsets.faceCounts.size(); ++subset) {
        const uint32_t group = uint32_t(subset + 1);
        for (int32_t k = 0; k < subsets.faceCounts[subset]; ++k, ++next) {
            const int32_t face = subsets.faceIndices[next];
            const std::string index = "indices[" + std::to_string(k) + "] = " + std::to_string(face);
            if (face < 0 || size_t(face) >= faceCount) {
                out.warnings.push_back(subsetSubject(subsets, subset, meshPath) + ": " + index + " is outside the mesh's " +
                                       std::to_string(faceCount) + " faces; ignored");
                continue;
            }
            uint32_t& owner = out.groups[size_t(face)];
            if (owner == group) continue;
            if (owner != 0) {
                if (!overlapsAllowed)
                    out.warnings.push_back(subsetSubject(subsets, subset, meshPath) + ": " + index + " is also in " +
                                           subsetSubject(subsets, owner - 1, meshPath) + ", which a " +
                                           subsets.familyType + " family forbids; the first keeps it");
                continue;
            }
            owner = group;
        }
    }
    if (subsets.familyType == "partition") {
        const size_t left = size_t(std::count(out.groups.begin(), out.groups.end(), 0u));
        if (left > 0)
            out.warnings.push_back(meshPath + ": subsetFamily:materialBind:familyType is partition but " +
                                   std::to_string(left) + " of the " + std::to_string(faceCount) +
                                   " faces are in no material subset; they draw with material:binding");
    }
    return out;
}

}  // namespace obscura::delegate
