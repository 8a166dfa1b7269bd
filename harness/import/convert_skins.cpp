// Skinned meshes as UsdSkel. Each mesh with bones gets a Skeleton of its own whose joints are its
// bones, flat (every joint a root): a joint's transform is its node's relative to the root node,
// which is the Skeleton's space since Skeletons sit under Root. Bind transforms are the bones'
// offset matrices inverted: glTF's inverse bind matrices map the mesh's vertices (in the space the
// skin was bound in, the mesh's own node ignored) into each joint's, as UsdSkel's do with an
// identity geomBindTransform. The first animation poses the joints at every key time of any node
// on their paths from the root.
#include <algorithm>
#include <set>

#include "harness/import/convert.h"

namespace obscura::harness::importer {

namespace {

// A channel's value at `time`: keys held before the first and after the last, linear (slerp for
// rotations) between; non-finite keys are skipped as writeAnimatedOp skips them.
template <class Key, class Value, class Blend>
Value sampleKeys(const Key* keys, unsigned count, double time, const Value& rest, Blend blend) {
    const Key* previous = nullptr;
    for (unsigned i = 0; i < count; ++i) {
        if (!std::isfinite(keys[i].mTime) || !isFinite(keys[i].mValue)) continue;
        if (keys[i].mTime >= time) {
            if (!previous || keys[i].mTime == time) return keys[i].mValue;
            const double t = (time - previous->mTime) / (keys[i].mTime - previous->mTime);
            return blend(previous->mValue, keys[i].mValue, static_cast<float>(t));
        }
        previous = &keys[i];
    }
    return previous ? previous->mValue : rest;
}

aiMatrix4x4 localTransformAt(const aiNode& node, const Timeline& timeline, std::optional<double> time) {
    const auto channel = timeline.channels.find(&node);
    if (!time || channel == timeline.channels.end() || !isFinite(node.mTransformation)) return node.mTransformation;
    const aiNodeAnim& anim = *channel->second;
    aiVector3D scale(1, 1, 1), position;
    aiQuaternion rotation;
    node.mTransformation.Decompose(scale, rotation, position);
    auto lerp = [](const aiVector3D& a, const aiVector3D& b, float t) { return a + (b - a) * t; };
    auto slerp = [](const aiQuaternion& a, const aiQuaternion& b, float t) {
        aiQuaternion out;
        aiQuaternion::Interpolate(out, a, b, t);
        return out;
    };
    return aiMatrix4x4(sampleKeys(anim.mScalingKeys, anim.mNumScalingKeys, *time, scale, lerp),
                       sampleKeys(anim.mRotationKeys, anim.mNumRotationKeys, *time, rotation, slerp),
                       sampleKeys(anim.mPositionKeys, anim.mNumPositionKeys, *time, position, lerp));
}

// The node's transform relative to the root node at `time` (its rest transform without one).
aiMatrix4x4 transformBelowRoot(const aiNode& node, const aiNode& root, const Timeline& timeline,
                               std::optional<double> time) {
    aiMatrix4x4 m = localTransformAt(node, timeline, time);
    for (const aiNode* parent = node.mParent; parent && parent != &root; parent = parent->mParent)
        m = localTransformAt(*parent, timeline, time) * m;
    return m;
}

// Every key time of the channels of the joints' nodes and their ancestors below the root.
std::set<double> keyTimes(const std::vector<const aiNode*>& joints, const aiNode& root, const Timeline& timeline) {
    std::set<double> times;
    auto add = [&](const auto* keys, unsigned count) {
        for (unsigned i = 0; i < count; ++i)
            if (std::isfinite(keys[i].mTime) && isFinite(keys[i].mValue)) times.insert(keys[i].mTime);
    };
    for (const aiNode* node : joints)
        for (const aiNode* n = node; n && n != &root; n = n->mParent)
            if (const auto channel = timeline.channels.find(n); channel != timeline.channels.end()) {
                add(channel->second->mPositionKeys, channel->second->mNumPositionKeys);
                add(channel->second->mRotationKeys, channel->second->mNumRotationKeys);
                add(channel->second->mScalingKeys, channel->second->mNumScalingKeys);
            }
    return times;
}

std::string matrices(const std::vector<aiMatrix4x4>& values) {
    return array(values.size(), [&](size_t i) { return matrix(toUsdMatrix(values[i])); });
}

// The joints' transforms at `time`, as UsdSkelAnimation's translations, rotations (real part
// first) and scales.
std::array<std::string, 3> jointPose(const std::vector<const aiNode*>& joints, const aiNode& root,
                                     const Timeline& timeline, double time) {
    std::vector<aiVector3D> scales(joints.size()), positions(joints.size());
    std::vector<aiQuaternion> rotations(joints.size());
    for (size_t j = 0; j < joints.size(); ++j)
        transformBelowRoot(*joints[j], root, timeline, time).Decompose(scales[j], rotations[j], positions[j]);
    auto vectors = [](const std::vector<aiVector3D>& v) {
        return array(v.size(), [&](size_t i) { return tuple({v[i].x, v[i].y, v[i].z}); });
    };
    return {vectors(positions),
            array(rotations.size(), [&](size_t i) {
                const aiQuaternion& q = rotations[i];
                return tuple({q.w, q.x, q.y, q.z});
            }),
            vectors(scales)};
}

void writeSkeleton(const Source& source, const Timeline& timeline, const aiMesh& mesh,
                   const std::vector<const aiNode*>& joints, const std::string& path, UsdaWriter& out) {
    const aiNode& root = *source.scene.mRootNode;
    NameScope jointNames;
    std::vector<std::string> names;
    std::vector<aiMatrix4x4> binds, rests;
    for (unsigned b = 0; b < mesh.mNumBones; ++b) {
        names.push_back(stringLiteral(jointNames.claim(mesh.mBones[b]->mName.C_Str(), "Joint")));
        binds.push_back(aiMatrix4x4(mesh.mBones[b]->mOffsetMatrix).Inverse());
        rests.push_back(transformBelowRoot(*joints[b], root, timeline, std::nullopt));
    }
    const std::string jointList = array(names.size(), [&](size_t i) { return names[i]; });
    out.property("uniform token[] joints", jointList);
    out.property("uniform matrix4d[] bindTransforms", matrices(binds));
    out.property("uniform matrix4d[] restTransforms", matrices(rests));
    const std::set<double> times = keyTimes(joints, root, timeline);
    if (times.empty()) return;
    out.property("rel skel:animationSource", pathRef(path + "/Animation"));
    out.beginPrim("SkelAnimation", "Animation");
    out.property("uniform token[] joints", jointList);
    std::array<std::vector<std::pair<double, std::string>>, 3> samples;
    for (double time : times) {
        std::array<std::string, 3> pose = jointPose(joints, root, timeline, time);
        for (size_t k = 0; k < 3; ++k) samples[k].emplace_back(time, std::move(pose[k]));
    }
    out.timeSamples("float3[] translations", samples[0]);
    out.timeSamples("quatf[] rotations", samples[1]);
    out.timeSamples("half3[] scales", samples[2]);
    out.endPrim();
}

}  // namespace

bool hasSkinnedMeshes(const aiScene& scene) {
    for (unsigned i = 0; i < scene.mNumMeshes; ++i)
        if (scene.mMeshes[i]->HasBones()) return true;
    return false;
}

std::map<const aiMesh*, std::string> writeSkeletons(const Source& source, const Timeline& timeline,
                                                    const std::string& scopePath, UsdaWriter& out, Warnings& warnings) {
    std::map<const aiMesh*, std::string> skeletons;
    NameScope names;
    for (unsigned i = 0; i < source.scene.mNumMeshes; ++i) {
        const aiMesh& mesh = *source.scene.mMeshes[i];
        if (!mesh.HasBones()) continue;
        const std::string label = "mesh '" + std::string(mesh.mName.C_Str()) + "'";
        std::vector<const aiNode*> joints;
        for (unsigned b = 0; b < mesh.mNumBones; ++b) {
            const aiBone& bone = *mesh.mBones[b];
            const aiNode* node = source.scene.mRootNode->FindNode(bone.mName);
            if (!node || !isFinite(bone.mOffsetMatrix)) {
                warnings.add(label + ": bone '" + bone.mName.C_Str() +
                             (node ? "' has a non-finite offset matrix" : "' names no node") +
                             "; the mesh is imported in its bind pose");
                break;
            }
            joints.push_back(node);
        }
        if (joints.size() != mesh.mNumBones) continue;
        const std::string name = names.claim(mesh.mName.C_Str(), "Skeleton");
        out.beginPrim("Skeleton", name);
        skeletons[&mesh] = scopePath + "/" + name;
        writeSkeleton(source, timeline, mesh, joints, skeletons[&mesh], out);
        out.endPrim();
    }
    return skeletons;
}

void writeSkinBinding(const aiMesh& mesh, const std::vector<unsigned>& writtenVertices, const std::string& skeleton,
                      UsdaWriter& out) {
    // Each vertex's (joint, weight) pairs; the element size is the most any vertex has, the
    // others padded with zero weights.
    std::vector<std::vector<std::pair<unsigned, float>>> influences(mesh.mNumVertices);
    for (unsigned b = 0; b < mesh.mNumBones; ++b)
        for (unsigned w = 0; w < mesh.mBones[b]->mNumWeights; ++w) {
            const aiVertexWeight& weight = mesh.mBones[b]->mWeights[w];
            if (weight.mVertexId < mesh.mNumVertices && std::isfinite(weight.mWeight))
                influences[weight.mVertexId].emplace_back(b, weight.mWeight);
        }
    size_t perVertex = 1;
    for (unsigned v : writtenVertices) perVertex = std::max(perVertex, influences[v].size());
    std::vector<std::string> indices, weights;
    for (unsigned v : writtenVertices)
        for (size_t k = 0; k < perVertex; ++k) {
            const bool has = k < influences[v].size();
            indices.push_back(std::to_string(has ? influences[v][k].first : 0));
            weights.push_back(number(has ? influences[v][k].second : 0.0f));
        }
    auto list = [](const std::vector<std::string>& items) { return array(items.size(), [&](size_t i) { return items[i]; }); };
    out.property("rel skel:skeleton", pathRef(skeleton));
    out.vertexProperty("int[] primvars:skel:jointIndices", list(indices), perVertex);
    out.vertexProperty("float[] primvars:skel:jointWeights", list(weights), perVertex);
}

}  // namespace obscura::harness::importer
