// The node hierarchy: Xforms with their static or animated transforms, and what each node carries.
#include <algorithm>
#include <cmath>
#include <string>

#include "harness/import/convert.h"

namespace obscura::harness::importer {

namespace {

constexpr std::string_view kTransformOp = "xformOp:transform";

std::string opOrder(const std::vector<std::string>& ops) {
    return array(ops.size(), [&](size_t i) { return stringLiteral(ops[i]); });
}

std::string valueText(const aiVector3D& v) { return tuple({v.x, v.y, v.z}); }
// USD writes quaternions real part first.
std::string valueText(const aiQuaternion& q) { return tuple({q.w, q.x, q.y, q.z}); }

// One op from a channel's keys (times in ticks, which are the layer's time codes), or the node's
// rest value when the channel has no usable key for it.
template <class Key, class Value>
void writeAnimatedOp(std::string_view declaration, const Key* keys, unsigned count, const Value& rest,
                     const std::string& nodeName, UsdaWriter& out, Warnings& warnings) {
    std::vector<std::pair<double, std::string>> samples;
    for (unsigned i = 0; i < count; ++i)
        if (std::isfinite(keys[i].mTime) && isFinite(keys[i].mValue))
            samples.emplace_back(keys[i].mTime, valueText(keys[i].mValue));
    if (samples.size() < count) warnings.add("node '" + nodeName + "': animation keys with non-finite values dropped");
    if (samples.empty()) {
        out.property(declaration, valueText(rest));
    } else {
        out.timeSamples(declaration, samples);
    }
}

std::vector<std::string> writeAnimatedTransform(const aiNode& node, const aiNodeAnim& channel, UsdaWriter& out,
                                                Warnings& warnings) {
    aiVector3D scale(1, 1, 1), position;
    aiQuaternion rotation;
    if (isFinite(node.mTransformation)) node.mTransformation.Decompose(scale, rotation, position);
    const std::string name = node.mName.C_Str();
    writeAnimatedOp("float3 xformOp:translate", channel.mPositionKeys, channel.mNumPositionKeys, position, name, out,
                    warnings);
    writeAnimatedOp("quatf xformOp:orient", channel.mRotationKeys, channel.mNumRotationKeys, rotation, name, out,
                    warnings);
    writeAnimatedOp("float3 xformOp:scale", channel.mScalingKeys, channel.mNumScalingKeys, scale, name, out, warnings);
    return {"xformOp:translate", "xformOp:orient", "xformOp:scale"};
}

void writeNodeTransform(const aiNode& node, const aiNodeAnim* channel, const std::optional<aiMatrix4x4>& correction,
                        UsdaWriter& out, Warnings& warnings) {
    std::vector<std::string> ops;
    if (correction) {
        // Outermost, so the whole scene turns into USD's frame.
        out.property("matrix4d xformOp:transform:upAxis", matrix(toUsdMatrix(*correction)));
        ops.emplace_back("xformOp:transform:upAxis");
    }
    if (channel) {
        const std::vector<std::string> animated = writeAnimatedTransform(node, *channel, out, warnings);
        ops.insert(ops.end(), animated.begin(), animated.end());
    } else {
        aiMatrix4x4 local = node.mTransformation;
        if (!isFinite(local)) {
            warnings.add("node '" + std::string(node.mName.C_Str()) + "': non-finite transform replaced by identity");
            local = aiMatrix4x4();
        }
        out.property("matrix4d " + std::string(kTransformOp), matrix(toUsdMatrix(local)));
        ops.emplace_back(kTransformOp);
    }
    out.property("uniform token[] xformOpOrder", opOrder(ops));
}

// Cameras and lights belong to the node of the same name (Assimp's rule; the first such node).
class NodeWriter {
public:
    NodeWriter(const Source& source, const Timeline& timeline, const std::vector<MaterialBinding>& materials,
               const std::map<const aiMesh*, std::string>& skeletons, UsdaWriter& out, Warnings& warnings)
        : source_(source), timeline_(timeline), materials_(materials), skeletons_(skeletons), out_(out),
          warnings_(warnings) {
        const aiScene& scene = source.scene;
        for (unsigned i = 0; i < scene.mNumCameras; ++i) attach(*scene.mCameras[i], cameras_, "camera");
        for (unsigned i = 0; i < scene.mNumLights; ++i) attach(*scene.mLights[i], lights_, "light");
    }

    void writeContents(const aiNode& node, const std::optional<aiMatrix4x4>& correction, NameScope& names) {
        const auto channel = timeline_.channels.find(&node);
        writeNodeTransform(node, channel == timeline_.channels.end() ? nullptr : channel->second, correction, out_,
                           warnings_);
        for (unsigned i = 0; i < node.mNumMeshes; ++i)
            writeMesh(*source_.scene.mMeshes[node.mMeshes[i]], materials_, skeletons_, names, out_, warnings_);
        for (auto [it, end] = cameras_.equal_range(&node); it != end; ++it)
            writeCamera(source_, *it->second, names, out_, warnings_);
        for (auto [it, end] = lights_.equal_range(&node); it != end; ++it)
            writeLight(source_, *it->second, names, out_, warnings_);
        for (unsigned i = 0; i < node.mNumChildren; ++i) {
            const aiNode& child = *node.mChildren[i];
            out_.beginPrim("Xform", names.claim(child.mName.C_Str(), "Node"));
            NameScope childNames;
            writeContents(child, std::nullopt, childNames);
            out_.endPrim();
        }
    }

private:
    template <class Item>
    void attach(const Item& item, std::multimap<const aiNode*, const Item*>& byNode, const std::string& what) {
        const aiNode* node = source_.scene.mRootNode->FindNode(item.mName);
        if (node) {
            byNode.emplace(node, &item);
        } else {
            warnings_.add(what + " '" + item.mName.C_Str() + "' belongs to no node; skipped");
        }
    }

    const Source& source_;
    const Timeline& timeline_;
    const std::vector<MaterialBinding>& materials_;
    const std::map<const aiMesh*, std::string>& skeletons_;
    UsdaWriter& out_;
    Warnings& warnings_;
    std::multimap<const aiNode*, const aiCamera*> cameras_;
    std::multimap<const aiNode*, const aiLight*> lights_;
};

void extendRange(std::optional<std::pair<double, double>>& range, double time) {
    if (!std::isfinite(time)) return;
    if (!range) range.emplace(time, time);
    range->first = std::min(range->first, time);
    range->second = std::max(range->second, time);
}

// The range covers the keys that are written (see writeAnimatedOp).
template <class Key>
void extendRange(std::optional<std::pair<double, double>>& range, const Key* keys, unsigned count) {
    for (unsigned i = 0; i < count; ++i)
        if (isFinite(keys[i].mValue)) extendRange(range, keys[i].mTime);
}

}  // namespace

std::array<float, 16> toUsdMatrix(const aiMatrix4x4& m) {
    return {m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4};
}

void Warnings::add(const std::string& message) {
    if (seen_.insert(message).second) messages_.push_back(message);
}

void writeMatrixTransform(const aiMatrix4x4& m, UsdaWriter& out) {
    out.property("matrix4d " + std::string(kTransformOp), matrix(toUsdMatrix(m)));
    out.property("uniform token[] xformOpOrder", opOrder({std::string(kTransformOp)}));
}

Timeline readTimeline(const aiScene& scene, Warnings& warnings) {
    Timeline timeline;
    if (scene.mNumAnimations == 0) return timeline;
    const aiAnimation& animation = *scene.mAnimations[0];
    const std::string name = animation.mName.C_Str();
    if (scene.mNumAnimations > 1)
        warnings.add("only the first animation ('" + name + "') is imported; " +
                     std::to_string(scene.mNumAnimations - 1) + " more ignored");
    // Assimp reports 0 ticks per second when the file does not say.
    if (animation.mTicksPerSecond > 0 && std::isfinite(animation.mTicksPerSecond))
        timeline.ticksPerSecond = animation.mTicksPerSecond;
    if (animation.mNumMeshChannels > 0 || animation.mNumMorphMeshChannels > 0)
        warnings.add("animation '" + name + "': mesh and morph target animation is not supported; ignored");
    for (unsigned i = 0; i < animation.mNumChannels; ++i) {
        const aiNodeAnim& channel = *animation.mChannels[i];
        const aiNode* node = scene.mRootNode->FindNode(channel.mNodeName);
        if (!node) {
            warnings.add("animation '" + name + "': channel for unknown node '" + channel.mNodeName.C_Str() +
                         "' ignored");
            continue;
        }
        timeline.channels[node] = &channel;
        extendRange(timeline.range, channel.mPositionKeys, channel.mNumPositionKeys);
        extendRange(timeline.range, channel.mRotationKeys, channel.mNumRotationKeys);
        extendRange(timeline.range, channel.mScalingKeys, channel.mNumScalingKeys);
    }
    return timeline;
}

void writeRootContents(const Source& source, const Timeline& timeline, const std::vector<MaterialBinding>& materials,
                       const std::map<const aiMesh*, std::string>& skeletons,
                       const std::optional<aiMatrix4x4>& rootCorrection, NameScope& names, UsdaWriter& out,
                       Warnings& warnings) {
    NodeWriter writer(source, timeline, materials, skeletons, out, warnings);
    writer.writeContents(*source.scene.mRootNode, rootCorrection, names);
}

}  // namespace obscura::harness::importer
