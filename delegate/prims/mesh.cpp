#include "delegate/prims/mesh.h"

#include "delegate/prims/point_motion.h"

#include <algorithm>

namespace obscura::delegate {

void Mesh::reset() {
    input_ = MeshInput{};
    built_.reset();
    vertices_.reset();
    indices_.reset();
    shutterPositions_.reset();
    shutterPoints_.reset();
    pointsAnimated_ = false;
    indexCount_ = 0;
    localBounds_ = Aabb{};
    groupRanges_.clear();
    parts_.clear();
}

void Mesh::updateMaterialParts() {
    parts_.clear();
    for (size_t group = 0; group < groupRanges_.size(); ++group) {
        if (groupRanges_[group].count == 0) continue;
        // Group 0 holds the faces of no subset; a subset the host gave no material draws as they do.
        const bool ownMaterial = group == 0 || group - 1 >= subsetMaterials_.size();
        parts_.push_back({ownMaterial ? material_ : subsetMaterials_[group - 1], groupRanges_[group],
                          group == 0 ? std::string() : subsetSubject(subsets_, group - 1, path())});
    }
}

void Mesh::pullGprim(SceneAccess& s, SyncContext& ctx) {
    if (s.dirty("transform")) {
        transform_ = s.sampleTransform(s.time(), s.time()).front().matrix;
        shutterTransforms_ = s.sampleTransform(ctx.shutterOpen, ctx.shutterClose);
    }
    if (s.dirty("visibility")) visible_ = s.getToken("visibility") != "invisible";
    if (s.dirty("purpose")) purpose_ = purposeBit(s.getToken("purpose"));
    if (s.dirty("doubleSided")) doubleSided_ = s.getBool("doubleSided");
    if (s.dirty("material:binding")) {
        material_ = s.getPath("material:binding");
        updateMaterialParts();
    }
    if (s.dirty("primvars:displayOpacity")) {
        displayOpacity_ = 1.0f;
        varyingOpacity_.reset();
        if (auto opacity = s.getFloatArray("primvars:displayOpacity"); opacity && !opacity->empty()) {
            ObscuraInterpolation interpolation = s.interpolation("primvars:displayOpacity");
            if (interpolation == OBSCURA_INTERPOLATION_CONSTANT) displayOpacity_ = std::clamp(opacity->front(), 0.0f, 1.0f);
            else varyingOpacity_ = MeshPrimvar{std::move(*opacity), interpolation, 1};
        }
    }
}

size_t Mesh::setGeometry(MeshGeometry&& geometry, SyncContext& ctx, const std::string& path) {
    return useBuiltMesh(builtMesh(std::move(geometry)), ctx, path);
}

size_t Mesh::useBuiltMesh(std::shared_ptr<BuiltMesh> built, SyncContext& ctx, const std::string& path) {
    warnings_.clear();
    for (const std::string& warning : built->warnings) warnings_.push_back(path + ": " + warning);
    translucentVertices_ = built->translucentVertices;
    indexCount_ = built->indexCount;
    // Tessellators that do not group faces (implicit surfaces, curves) draw with one material.
    groupRanges_ = built->groupRanges.empty() ? std::vector<IndexRange>{{0, indexCount_}} : built->groupRanges;
    updateMaterialParts();
    localBounds_ = built->bounds;
    // The first prim to reach the device with this mesh uploads it (through the geometry cache,
    // which finds equal content built from other inputs); the others take its buffers.
    ctx.onDevice([this, &cache = ctx.geometry, built, path] {
        if (!built->buffers.vertices) {
            built->buffers = cache.get(built->content, path.c_str());
            built->content = {};
        }
        vertices_ = built->buffers.vertices;
        indices_ = built->buffers.indices;
        built_ = built;
    });
    return built->vertexCount;
}

std::optional<MeshPrimvar> pullPrimvar(SceneAccess& s, const char* name, size_t components) {
    auto values = s.getFloatArray(name);
    if (!values) return std::nullopt;
    return MeshPrimvar{std::move(*values), s.interpolation(name), components};
}

std::optional<std::array<std::vector<float>, 2>> Mesh::pullShutterPoints(SceneAccess& s, const std::vector<float>& points,
                                                                         const SyncContext& ctx) {
    if (!(ctx.shutterClose > ctx.shutterOpen)) return std::nullopt;
    auto motion = pointMotion(s.getFloatArray("velocities"), s.getFloatArray("accelerations"), points.size() / 3);
    std::array<std::vector<float>, 2> ends;
    for (int end = 0; end < 2; ++end) {
        double time = end == 0 ? ctx.shutterOpen : ctx.shutterClose;
        ends[size_t(end)] = motion ? movePoints(points, *motion, secondsBetween(s.time(), time, ctx.timeCodesPerSecond))
                                   : sampledOrFrame(s.getFloatArrayAt("points", time), points);
    }
    if (ends[0] == points && ends[1] == points) return std::nullopt;
    return ends;
}

void Mesh::setShutterPositions(const std::optional<std::array<std::vector<float>, 2>>& ends, size_t vertexCount,
                               SyncContext& ctx, const std::string& path) {
    if (!ends) return ctx.onDevice([this] { shutterPositions_.reset(); });
    if ((*ends)[0].size() != vertexCount * 3 || (*ends)[1].size() != (*ends)[0].size())
        throw PrimDataError(path + ": points at the shutter's ends do not match the prim's topology");
    std::vector<passes::ShutterPositions> positions(vertexCount);
    for (size_t v = 0; v < positions.size(); ++v)
        for (int k = 0; k < 3; ++k) {
            positions[v].open[k] = (*ends)[0][v * 3 + k];
            positions[v].close[k] = (*ends)[1][v * 3 + k];
        }
    ctx.onDevice([this, &device = ctx.device, positions = std::move(positions), path] {
        gpu::MemoryCategoryScope geometry(gpu::MemoryCategory::Geometry);
        shutterPositions_ = device.createBufferWithData(positions.data(), positions.size() * sizeof(positions[0]),
                                                        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, path.c_str());
    });
}

void Mesh::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext& ctx) {
    pullGprim(s, ctx);
    if (s.dirty("materialSubsets:materials")) {
        subsetMaterials_ = s.getPathArray("materialSubsets:materials");
        updateMaterialParts();
    }

    // The drawn polygons are made of everything but the placement, visibility and bindings.
    if (!s.anyDirtyBut({"transform", "visibility", "purpose", "doubleSided", "material:binding",
                        "materialSubsets:materials"}) &&
        !(bits & kDirtyTessellation))
        return;
    const bool pointsDirty = s.anyDirty({"points", "velocities", "accelerations"});
    if (pointsDirty) {
        input_.points = s.getFloatArray("points").value_or(std::vector<float>{});
        shutterPoints_ = pullShutterPoints(s, input_.points, ctx);
    }
    const bool topologyDirty =
        s.anyDirty({"faceVertexCounts", "faceVertexIndices", "orientation", "subdivisionScheme", "interpolateBoundary",
                    "faceVaryingLinearInterpolation", "creaseIndices", "creaseLengths", "creaseSharpnesses",
                    "cornerIndices", "cornerSharpnesses", "holeIndices", "obscura:refineLevel"});
    // Points that change under a kept topology are animated: from then on the refiner is kept.
    if (pointsDirty && !topologyDirty) pointsAnimated_ = true;
    if (topologyDirty) {
        input_.faceVertexCounts = s.getIntArray("faceVertexCounts").value_or(std::vector<int32_t>{});
        input_.faceVertexIndices = s.getIntArray("faceVertexIndices").value_or(std::vector<int32_t>{});
        input_.leftHanded = s.getToken("orientation") == "leftHanded";
        scheme_ = parseSubdivisionScheme(s.getToken("subdivisionScheme"));
        tags_.interpolateBoundary = s.getToken("interpolateBoundary");
        tags_.faceVaryingLinearInterpolation = s.getToken("faceVaryingLinearInterpolation");
        tags_.creaseIndices = s.getIntArray("creaseIndices").value_or(std::vector<int32_t>{});
        tags_.creaseLengths = s.getIntArray("creaseLengths").value_or(std::vector<int32_t>{});
        tags_.creaseSharpnesses = s.getFloatArray("creaseSharpnesses").value_or(std::vector<float>{});
        tags_.cornerIndices = s.getIntArray("cornerIndices").value_or(std::vector<int32_t>{});
        tags_.cornerSharpnesses = s.getFloatArray("cornerSharpnesses").value_or(std::vector<float>{});
        tags_.holeIndices = s.getIntArray("holeIndices").value_or(std::vector<int32_t>{});
        refineLevelOverride_ = s.getInt("obscura:refineLevel");
    }
    if (s.anyDirty({"materialSubsets:faceCounts", "materialSubsets:faceIndices", "materialSubsets:paths",
                    "subsetFamily:materialBind:familyType"})) {
        subsets_.faceCounts = s.getIntArray("materialSubsets:faceCounts").value_or(std::vector<int32_t>{});
        subsets_.faceIndices = s.getIntArray("materialSubsets:faceIndices").value_or(std::vector<int32_t>{});
        subsets_.paths = s.getPathArray("materialSubsets:paths");
        subsets_.familyType = s.getToken("subsetFamily:materialBind:familyType");
    }
    // The subsets split the drawn triangles by the face they come from (a subdivided mesh's by its
    // control face), never the surface: one vertex buffer, one index buffer ordered by material.
    FaceGroups faceGroups = assignFaceGroups(subsets_, input_.faceVertexCounts.size(), s.path());
    input_.faceGroups = std::move(faceGroups.groups);
    if (s.dirty("normals")) {
        input_.normals.reset();
        if (auto n = s.getFloatArray("normals")) input_.normals = MeshPrimvar{std::move(*n), s.interpolation("normals")};
    }
    if (s.dirty("primvars:displayColor")) {
        input_.displayColor.reset();
        if (auto c = s.getFloatArray("primvars:displayColor"))
            input_.displayColor = MeshPrimvar{std::move(*c), s.interpolation("primvars:displayColor")};
    }
    if (s.dirty("primvars:displayOpacity")) input_.displayOpacity = varyingOpacity_;
    if (s.dirty("primvars:st")) {
        input_.st.reset();
        if (auto st = s.getFloatArray("primvars:st"))
            input_.st = MeshPrimvar{std::move(*st), s.interpolation("primvars:st"), 2};
    }
    // Subdivision surfaces are refined with OpenSubdiv; the cache keeps the refiner for meshes
    // whose points move (animated, or sampled over the shutter), which refine again and again.
    int level = refineLevelOverride_ >= 0 ? refineLevelOverride_ : ctx.refineLevel;
    // A prim whose inputs equal another's (a repeated reference of one asset) takes its built mesh.
    const ContentKey key = inputKey(level);
    std::shared_ptr<BuiltMesh> built = ctx.builtMeshes.find(key);
    if (!built) {
        std::variant<MeshInput, std::string> refined = input_;
        // Refinement leaves out a primvar whose count does not fit the control mesh (authored
        // normals it ignores, as UsdGeomMesh specifies for subdivision surfaces).
        std::vector<std::string> dropped;
        if (scheme_ != SubdivisionScheme::None && level > 0) {
            refined = subdivision_.refine(input_, scheme_, tags_, level);
            dropped = interpolatedPrimvarProblems(input_);
        }
        if (auto* problem = std::get_if<std::string>(&refined)) throw PrimDataError(s.path() + ": " + *problem);
        auto geometry = buildMeshGeometry(std::get<MeshInput>(refined));
        if (auto* problem = std::get_if<std::string>(&geometry)) throw PrimDataError(s.path() + ": " + *problem);
        MeshGeometry& drawn = std::get<MeshGeometry>(geometry);
        drawn.warnings.insert(drawn.warnings.begin(), dropped.begin(), dropped.end());
        built = ctx.builtMeshes.insert(key, builtMesh(std::move(drawn)));
    }
    const size_t vertexCount = useBuiltMesh(std::move(built), ctx, s.path());
    warnings_.insert(warnings_.end(), faceGroups.warnings.begin(), faceGroups.warnings.end());
    std::optional<std::array<std::vector<float>, 2>> ends;
    if (shutterPoints_)
        ends = {drawnPositions((*shutterPoints_)[0], level, s.path()), drawnPositions((*shutterPoints_)[1], level, s.path())};
    setShutterPositions(ends, vertexCount, ctx, s.path());
    if (!pointsAnimated_ && !shutterPoints_) subdivision_.release();
}

ContentKey Mesh::inputKey(int level) const {
    ContentKeyBuilder key;
    key.addArray(input_.points);
    key.addArray(input_.faceVertexCounts);
    key.addArray(input_.faceVertexIndices);
    key.add(input_.leftHanded);
    for (const std::optional<MeshPrimvar>* primvar : {&input_.normals, &input_.displayColor, &input_.displayOpacity, &input_.st}) {
        key.add(primvar->has_value());
        if (!*primvar) continue;
        key.add((*primvar)->interpolation);
        key.add(uint64_t((*primvar)->components));
        key.addArray((*primvar)->values);
    }
    key.addArray(input_.faceGroups);
    // The refinement: none for a mesh drawn as its polygons, whatever its tags.
    const bool refined = scheme_ != SubdivisionScheme::None && level > 0;
    key.add(refined ? scheme_ : SubdivisionScheme::None);
    if (refined) {
        key.add(level);
        for (const std::string* token : {&tags_.interpolateBoundary, &tags_.faceVaryingLinearInterpolation}) {
            key.add(uint64_t(token->size()));
            key.add(token->data(), token->size());
        }
        key.addArray(tags_.creaseIndices);
        key.addArray(tags_.creaseLengths);
        key.addArray(tags_.creaseSharpnesses);
        key.addArray(tags_.cornerIndices);
        key.addArray(tags_.cornerSharpnesses);
        key.addArray(tags_.holeIndices);
    }
    return key.key();
}

std::vector<float> Mesh::drawnPositions(const std::vector<float>& points, int level, const std::string& path) {
    MeshInput input = input_;
    input.points = points;
    std::variant<MeshInput, std::string> refined = input;
    if (scheme_ != SubdivisionScheme::None && level > 0) refined = subdivision_.refine(input, scheme_, tags_, level);
    if (auto* problem = std::get_if<std::string>(&refined)) throw PrimDataError(path + ": " + *problem);
    auto built = buildMeshGeometry(std::get<MeshInput>(refined));
    if (auto* problem = std::get_if<std::string>(&built)) throw PrimDataError(path + ": " + *problem);
    std::vector<float> positions;
    for (const passes::Vertex& v : std::get<MeshGeometry>(built).vertices)
        positions.insert(positions.end(), v.position, v.position + 3);
    return positions;
}

}  // namespace obscura::delegate
