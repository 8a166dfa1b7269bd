// A mesh's material subsets (UsdGeomSubset children of familyName materialBind and elementType
// face, as Hydra's HdGeomSubsets): which faces draw with which material. Pure CPU code.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace obscura::delegate {

// The subsets as the mesh schema's materialSubsets:* attributes carry them.
struct MaterialSubsets {
    std::vector<int32_t> faceCounts;   // faces of each subset
    std::vector<int32_t> faceIndices;  // every subset's face indices, one subset's after another
    std::vector<std::string> paths;    // each subset's GeomSubset prim, for messages; may be empty
    std::string familyType = "unrestricted";  // partition | nonOverlapping | unrestricted
};

// What a message about subset `subset` of the mesh at `meshPath` starts with: the subset's prim
// ("/World/Mesh/Red", so a host locates what follows on it), else the mesh and the subset's number.
std::string subsetSubject(const MaterialSubsets& subsets, size_t subset, const std::string& meshPath);

struct FaceGroups {
    // Per face: 0 when it is in no subset, k + 1 when subset k is the first that lists it. Empty
    // when there are no subsets.
    std::vector<uint32_t> groups;
    // Indices ignored, overlaps and gaps the family forbids: whole messages, each naming its prim.
    std::vector<std::string> warnings;
};

// Each face's group on the mesh at `meshPath` of `faceCount` faces. Bad data drops as little as
// it can: an index outside the faces is ignored, and so is a face an earlier subset holds; counts
// that do not add up to the indices drop every subset (each with a warning).
FaceGroups assignFaceGroups(const MaterialSubsets& subsets, size_t faceCount, const std::string& meshPath);

}  // namespace obscura::delegate
