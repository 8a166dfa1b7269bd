#include "delegate/prims/mesh.h"

namespace obscura::delegate {

void Mesh::reset() {
    input_ = MeshInput{};
    vertices_.reset();
    indices_.reset();
    indexCount_ = 0;
}

void Mesh::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext& ctx) {
    if (bits & OBSCURA_DIRTY_TRANSFORM) {
        transform_ = s.sampleTransform(s.time(), s.time()).front().matrix;
        shutterTransforms_ = s.sampleTransform(ctx.shutterOpen, ctx.shutterClose);
    }
    if (bits & OBSCURA_DIRTY_VISIBILITY) visible_ = s.getToken("visibility") != "invisible";
    if (bits & OBSCURA_DIRTY_DOUBLE_SIDED) doubleSided_ = s.getBool("doubleSided");
    if (bits & OBSCURA_DIRTY_MATERIAL_ID) material_ = s.getPath("material:binding");

    constexpr ObscuraDirtyBits kGeometry =
        OBSCURA_DIRTY_POINTS | OBSCURA_DIRTY_TOPOLOGY | OBSCURA_DIRTY_NORMALS | OBSCURA_DIRTY_PRIMVAR;
    if (!(bits & kGeometry)) return;
    if (bits & OBSCURA_DIRTY_POINTS) input_.points = s.getFloatArray("points").value_or(std::vector<float>{});
    if (bits & OBSCURA_DIRTY_TOPOLOGY) {
        input_.faceVertexCounts = s.getIntArray("faceVertexCounts").value_or(std::vector<int32_t>{});
        input_.faceVertexIndices = s.getIntArray("faceVertexIndices").value_or(std::vector<int32_t>{});
        input_.leftHanded = s.getToken("orientation") == "leftHanded";
    }
    if (bits & OBSCURA_DIRTY_NORMALS) {
        input_.normals.reset();
        if (auto n = s.getFloatArray("normals")) input_.normals = MeshPrimvar{std::move(*n), s.interpolation("normals")};
    }
    if (bits & OBSCURA_DIRTY_PRIMVAR) {
        input_.displayColor.reset();
        if (auto c = s.getFloatArray("primvars:displayColor"))
            input_.displayColor = MeshPrimvar{std::move(*c), s.interpolation("primvars:displayColor")};
    }
    auto built = buildMeshGeometry(input_);
    if (auto* problem = std::get_if<std::string>(&built)) throw PrimDataError(s.path() + ": " + *problem);
    auto& geometry = std::get<MeshGeometry>(built);
    warnings_ = geometry.warnings;
    indexCount_ = static_cast<uint32_t>(geometry.indices.size());
    vertices_ = ctx.device.createBufferWithData(geometry.vertices.data(), geometry.vertices.size() * sizeof(passes::Vertex),
                                                VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, s.path().c_str());
    indices_ = ctx.device.createBufferWithData(geometry.indices.data(), geometry.indices.size() * sizeof(uint32_t),
                                               VK_BUFFER_USAGE_INDEX_BUFFER_BIT, s.path().c_str());
}

}  // namespace obscura::delegate
