#include "harness/usda/tet_mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

namespace obscura::usda {
namespace {

// An index array's problem: not whole elements of `tuple` indices, or an index outside the points.
std::optional<AttributeProblem> indicesProblem(const char* name, const std::vector<double>& indices, size_t tuple,
                                               size_t pointCount) {
    if (indices.size() % tuple != 0)
        return AttributeProblem{name, std::string(name) + " has " + std::to_string(indices.size()) +
                                          " indices, not a whole number of " + std::to_string(tuple) + "s"};
    for (size_t i = 0; i < indices.size(); ++i)
        if (!(indices[i] >= 0 && indices[i] < double(pointCount)))
            return AttributeProblem{name, std::string(name) + "[" + std::to_string(i / tuple) + "] names point " +
                                              std::to_string(int64_t(indices[i])) + ", outside the " +
                                              std::to_string(pointCount) + " points"};
    return std::nullopt;
}

}  // namespace

std::vector<int> tetSurfaceFaces(const std::vector<int>& tetVertexIndices) {
    // UsdGeomTetMesh's faces of tet (0, 1, 2, 3): each counter-clockwise seen from outside a tet
    // whose point 3 lies on the side of (p1 - p0) x (p2 - p0) (UsdGeomTetMesh::FindInvertedElements'
    // positive orientation).
    static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    // Sorted corners -> how many tets have the face, and its winding in the last of them.
    std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> faces;
    for (size_t tet = 0; tet + 3 < tetVertexIndices.size(); tet += 4) {
        for (const auto& face : kFaces) {
            const std::array<int, 3> triangle{tetVertexIndices[tet + size_t(face[0])], tetVertexIndices[tet + size_t(face[1])],
                                              tetVertexIndices[tet + size_t(face[2])]};
            std::array<int, 3> sorted = triangle;
            std::sort(sorted.begin(), sorted.end());
            auto& [count, winding] = faces[sorted];
            ++count;
            winding = triangle;
        }
    }
    std::vector<std::array<int, 3>> surface;
    for (const auto& [sorted, found] : faces)
        if (found.first == 1) surface.push_back(found.second);
    std::sort(surface.begin(), surface.end());
    std::vector<int> out;
    for (const auto& triangle : surface) out.insert(out.end(), triangle.begin(), triangle.end());
    return out;
}

std::variant<std::vector<int>, AttributeProblem> tetMeshSurface(const Prim& prim, double time) {
    auto numbers = [&](const char* name) -> std::optional<std::vector<double>> {
        const Attribute* attribute = prim.attribute(name);
        auto value = attribute ? attribute->evaluate(time) : std::nullopt;
        if (!value) return std::nullopt;
        return value->numbers.vector();
    };
    const size_t pointCount = numbers("points").value_or(std::vector<double>{}).size() / 3;
    if (auto authored = numbers("surfaceFaceVertexIndices")) {
        if (auto problem = indicesProblem("surfaceFaceVertexIndices", *authored, 3, pointCount)) return *problem;
        return std::vector<int>(authored->begin(), authored->end());
    }
    const std::vector<double> tets = numbers("tetVertexIndices").value_or(std::vector<double>{});
    if (auto problem = indicesProblem("tetVertexIndices", tets, 4, pointCount)) return *problem;
    return tetSurfaceFaces(std::vector<int>(tets.begin(), tets.end()));
}

std::string tetSurfacePrimvarProblem(size_t surfaceFaces, size_t count, const std::string& interpolation,
                                     size_t elementSize) {
    const bool uniform = interpolation == "uniform";
    const size_t expected = (uniform ? surfaceFaces : 3 * surfaceFaces) * elementSize;
    if (count == expected) return {};
    return std::to_string(count) + " values but " + interpolation + " interpolation needs " +
           std::to_string(expected) + (uniform ? " (one per surface face)" : " (one per surface face corner)");
}

}  // namespace obscura::usda
