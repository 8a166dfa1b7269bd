#include "harness/usda/skinning.h"

#include <algorithm>
#include <map>

namespace obscura::usda {
namespace {

namespace m4 = matrix4;

// UsdSkelImaging's kernels skip influences this small.
constexpr double kWeightEpsilon = 1e-5;

std::optional<Value> valueAt(const Prim& prim, const std::string& name, double time) {
    const Attribute* attribute = prim.attribute(name);
    auto value = attribute ? attribute->evaluate(time) : std::nullopt;
    if (!value || value->blocked) return std::nullopt;
    return value;
}

// A relationship inherited down namespace (UsdSkelBindingAPI's skel:skeleton and
// skel:animationSource): the prim's own, else its nearest ancestor's.
const Relationship* inheritedRelationship(const Prim& prim, const std::string& name) {
    for (const Prim* p = &prim; p; p = p->parent)
        if (const Relationship* rel = p->relationship(name); rel && !rel->targets.empty()) return rel;
    return nullptr;
}

std::vector<Matrix4> matrices(const Value& value) {
    std::vector<Matrix4> out(value.numbers.size() / 16);
    for (size_t i = 0; i < out.size(); ++i) std::copy_n(value.numbers.begin() + long(16 * i), 16, out[i].begin());
    return out;
}

// A joint's parent is the joint named by its path's parent path (UsdSkelTopology); a joint whose
// parent path is not a joint is a root.
std::string parentPath(const std::string& joint) {
    const auto slash = joint.rfind('/');
    return slash == std::string::npos ? "" : joint.substr(0, slash);
}

// UsdSkelMakeTransform: scale, then rotate, then translate (row vectors).
Matrix4 jointTransform(const double* translate, const double* rotate, const double* scale) {
    Matrix4 m = scale ? m4::scale(scale[0], scale[1], scale[2]) : m4::identity();
    m = m4::multiply(m, m4::rotation(rotate[0], rotate[1], rotate[2], rotate[3]));
    return m4::multiply(m, m4::translation(translate[0], translate[1], translate[2]));
}

void transformPoint(const double* p, const Matrix4& m, double weight, double* out) {
    for (int c = 0; c < 3; ++c)
        out[c] += weight * (p[0] * m[size_t(c)] + p[1] * m[size_t(4 + c)] + p[2] * m[size_t(8 + c)] + m[size_t(12 + c)]);
}

// A normal goes through the inverse transpose of what its surface goes through; for row vectors
// n' = n * inverse(M)^T, i.e. component c is the dot of n with row c of inverse(M).
void transformNormal(const double* n, const Matrix4& inverse, double weight, double* out) {
    for (int c = 0; c < 3; ++c)
        out[c] += weight * (n[0] * inverse[size_t(4 * c)] + n[1] * inverse[size_t(4 * c + 1)] +
                            n[2] * inverse[size_t(4 * c + 2)]);
}

Matrix4 skelToPrim(const Stage& stage, const Skinning& skinning, double time) {
    return m4::multiply(stage.worldTransform(*skinning.skeleton, time),
                        m4::inverse(stage.worldTransform(*skinning.prim, time)));
}

std::string influenceCountProblem(const Skinning& skinning, size_t pointCount) {
    if (skinning.constantInfluences) return {};
    const size_t expected = pointCount * size_t(skinning.influencesPerPoint);
    if (skinning.influenceJoints.size() == expected) return {};
    return "primvars:skel:jointIndices and jointWeights have " + std::to_string(skinning.influenceJoints.size()) +
           " values but vertex interpolation with elementSize " + std::to_string(skinning.influencesPerPoint) +
           " needs " + std::to_string(expected) + " (" + std::to_string(pointCount) + " points)";
}

// jointIndices and jointWeights, checked against each other and the joints they index.
std::optional<SkinningProblem> readInfluences(const Prim& prim, const Attribute& indices,
                                              const Attribute& weights, const std::map<std::string, int>& jointIndex,
                                              Skinning& out) {
    auto meta = [](const Attribute& a, const char* key) -> const Value* {
        const auto it = a.metadata.find(key);
        return it == a.metadata.end() ? nullptr : &it->second;
    };
    auto interpolationOf = [&](const Attribute& a) {
        const Value* v = meta(a, "interpolation");
        return v && !v->strings.empty() ? v->strings.front() : std::string("constant");  // UsdGeomPrimvar's fallback
    };
    auto elementSizeOf = [&](const Attribute& a) {
        const Value* v = meta(a, "elementSize");
        return v && !v->numbers.empty() ? int(v->numbers.front()) : 1;
    };
    const std::string interpolation = interpolationOf(indices);
    const int elementSize = elementSizeOf(indices);
    if (interpolation != "constant" && interpolation != "vertex")
        return SkinningProblem{"primvars:skel:jointIndices has " + interpolation +
                                   " interpolation; UsdSkel takes constant or vertex", indices.where};
    if (interpolationOf(weights) != interpolation || elementSizeOf(weights) != elementSize)
        return SkinningProblem{"primvars:skel:jointWeights has another interpolation or elementSize than jointIndices",
                               weights.where};
    if (elementSize < 1)
        return SkinningProblem{"primvars:skel:jointIndices has elementSize " + std::to_string(elementSize), indices.where};
    auto indexValues = indices.evaluate(0.0);
    auto weightValues = weights.evaluate(0.0);
    if (!indexValues || !weightValues) return SkinningProblem{"joint influences have no value", indices.where};
    if (indexValues->numbers.size() != weightValues->numbers.size())
        return SkinningProblem{"primvars:skel:jointWeights has " + std::to_string(weightValues->numbers.size()) +
                                   " values but jointIndices has " + std::to_string(indexValues->numbers.size()),
                               weights.where};
    if (indexValues->numbers.size() % size_t(elementSize) != 0 ||
        (interpolation == "constant" && indexValues->numbers.size() != size_t(elementSize)))
        return SkinningProblem{"primvars:skel:jointIndices has " + std::to_string(indexValues->numbers.size()) +
                                   " values, not a whole number of sets of elementSize " + std::to_string(elementSize) +
                                   (interpolation == "constant" ? " (constant: exactly one set)" : ""),
                               indices.where};
    // skel:joints on the prim: its indices name these joints, mapped to the skeleton's by name.
    std::vector<int> toSkeleton;
    if (auto own = valueAt(prim, "skel:joints", 0.0)) {
        for (const std::string& name : own->strings) {
            const auto it = jointIndex.find(name);
            if (it == jointIndex.end())
                return SkinningProblem{"skel:joints names \"" + name + "\", which the skeleton does not have",
                                       prim.attribute("skel:joints")->where};
            toSkeleton.push_back(it->second);
        }
    } else {
        for (int j = 0; j < int(jointIndex.size()); ++j) toSkeleton.push_back(j);
    }
    out.influencesPerPoint = elementSize;
    out.constantInfluences = interpolation == "constant";
    for (size_t i = 0; i < indexValues->numbers.size(); ++i) {
        const double index = indexValues->numbers[i];
        if (!(index >= 0 && index < double(toSkeleton.size())))
            return SkinningProblem{"primvars:skel:jointIndices[" + std::to_string(i) + "] = " +
                                       std::to_string(int64_t(index)) + " is outside the " +
                                       std::to_string(toSkeleton.size()) + " joints",
                                   indices.where};
        out.influenceJoints.push_back(toSkeleton[size_t(index)]);
        out.influenceWeights.push_back(float(weightValues->numbers[i]));
    }
    return std::nullopt;
}

// skel:blendShapes and skel:blendShapeTargets: the BlendShape prims in the order of their names,
// each with the index of its weight among the animation's blendShapes.
std::optional<SkinningProblem> readBlendShapes(const Stage& stage, const Prim& prim, const Prim* animation,
                                               Skinning& out) {
    auto names = valueAt(prim, "skel:blendShapes", 0.0);
    if (!names || names->strings.empty()) return std::nullopt;
    const Relationship* targets = prim.relationship("skel:blendShapeTargets");
    const size_t count = targets ? targets->targets.size() : 0;
    if (count != names->strings.size())
        return SkinningProblem{"skel:blendShapes names " + std::to_string(names->strings.size()) +
                                   " shapes but skel:blendShapeTargets has " + std::to_string(count),
                               prim.attribute("skel:blendShapes")->where};
    std::map<std::string, int> weightIndex;
    if (auto animated = animation ? valueAt(*animation, "blendShapes", 0.0) : std::nullopt)
        for (size_t i = 0; i < animated->strings.size(); ++i) weightIndex.emplace(animated->strings[i], int(i));
    for (size_t i = 0; i < count; ++i) {
        const Prim* shape = stage.find(targets->targets[i]);
        if (!shape || shape->typeName != "BlendShape")
            return SkinningProblem{"skel:blendShapeTargets names <" + targets->targets[i] + ">, which is no BlendShape",
                                   targets->where};
        BlendShape b;
        b.name = names->strings[i];
        b.where = shape->where;
        if (auto offsets = valueAt(*shape, "offsets", 0.0)) b.offsets = offsets->numbers;
        if (auto indices = valueAt(*shape, "pointIndices", 0.0))
            for (double index : indices->numbers) b.pointIndices.push_back(int(index));
        if (!b.pointIndices.empty() && b.pointIndices.size() * 3 != b.offsets.size())
            return SkinningProblem{"<" + shape->path + "> has " + std::to_string(b.offsets.size() / 3) + " offsets for " +
                                       std::to_string(b.pointIndices.size()) + " pointIndices",
                                   shape->where};
        if (const auto it = weightIndex.find(b.name); it != weightIndex.end()) b.animationIndex = it->second;
        out.blendShapes.push_back(std::move(b));
    }
    return std::nullopt;
}

// The points moved by the blend shapes' offsets at their weights at `time`, or empty with `problem`.
std::vector<double> shaped(const Skinning& skinning, std::vector<double> points, double time, std::string* problem) {
    if (skinning.blendShapes.empty()) return points;
    auto weights = skinning.animation ? valueAt(*skinning.animation, "blendShapeWeights", time) : std::nullopt;
    for (const BlendShape& shape : skinning.blendShapes) {
        const double weight = weights && shape.animationIndex >= 0 && size_t(shape.animationIndex) < weights->numbers.size()
                                  ? weights->numbers[size_t(shape.animationIndex)]
                                  : 0.0;
        if (weight == 0.0) continue;
        if (shape.pointIndices.empty() && shape.offsets.size() != points.size()) {
            if (problem) *problem = "blend shape \"" + shape.name + "\" has " + std::to_string(shape.offsets.size() / 3) +
                                    " offsets for " + std::to_string(points.size() / 3) + " points";
            return {};
        }
        for (size_t o = 0; o < shape.offsets.size() / 3; ++o) {
            const size_t point = shape.pointIndices.empty() ? o : size_t(shape.pointIndices[o]);
            if (point >= points.size() / 3) {
                if (problem) *problem = "blend shape \"" + shape.name + "\" moves point " + std::to_string(point) +
                                        ", outside the " + std::to_string(points.size() / 3) + " points";
                return {};
            }
            for (size_t c = 0; c < 3; ++c) points[3 * point + c] += weight * shape.offsets[3 * o + c];
        }
    }
    return points;
}

}  // namespace

std::variant<Skinning, SkinningProblem> resolveSkeleton(const Stage& stage, const Prim& skeleton) {
    Skinning out;
    out.skeleton = &skeleton;
    auto joints = valueAt(skeleton, "joints", 0.0);
    if (!joints || joints->strings.empty())
        return SkinningProblem{"its Skeleton <" + skeleton.path + "> has no joints", skeleton.where};
    out.joints = joints->strings;
    std::map<std::string, int> jointIndex;
    for (size_t j = 0; j < out.joints.size(); ++j) {
        const auto parent = jointIndex.find(parentPath(out.joints[j]));
        out.parents.push_back(parent == jointIndex.end() ? -1 : parent->second);
        if (!jointIndex.emplace(out.joints[j], int(j)).second)
            return SkinningProblem{"its Skeleton <" + skeleton.path + "> names joint \"" + out.joints[j] + "\" twice",
                                   skeleton.attribute("joints")->where};
    }
    // UsdSkelTopology: a parent comes before its children.
    for (size_t j = 0; j < out.joints.size(); ++j)
        if (out.parents[j] < 0 && jointIndex.count(parentPath(out.joints[j])))
            return SkinningProblem{"its Skeleton <" + skeleton.path + "> lists joint \"" + out.joints[j] +
                                       "\" before its parent",
                                   skeleton.attribute("joints")->where};
    auto bind = valueAt(skeleton, "bindTransforms", 0.0);
    if (!bind || bind->numbers.size() != 16 * out.joints.size())
        return SkinningProblem{"its Skeleton <" + skeleton.path + "> has " + std::to_string(bind ? bind->size() : 0) +
                                   " bindTransforms for " + std::to_string(out.joints.size()) + " joints",
                               skeleton.attribute("bindTransforms") ? skeleton.attribute("bindTransforms")->where
                                                                    : skeleton.where};
    out.bindTransforms = matrices(*bind);
    if (auto rest = valueAt(skeleton, "restTransforms", 0.0); rest && rest->numbers.size() == bind->numbers.size()) {
        out.restTransforms = matrices(*rest);
    } else {
        // Without rest transforms the skeleton rests in its bind pose.
        for (size_t j = 0; j < out.joints.size(); ++j) {
            const Matrix4& jointBind = out.bindTransforms[j];
            const int parent = out.parents[j];
            out.restTransforms.push_back(
                parent < 0 ? jointBind : m4::multiply(jointBind, m4::inverse(out.bindTransforms[size_t(parent)])));
        }
    }
    out.animatedJoint.assign(out.joints.size(), -1);
    if (const Relationship* source = inheritedRelationship(skeleton, "skel:animationSource")) {
        out.animation = stage.find(source->targets.front());
        if (!out.animation || out.animation->typeName != "SkelAnimation")
            return SkinningProblem{"skel:animationSource of <" + skeleton.path + "> targets <" +
                                       source->targets.front() + ">, which is no SkelAnimation",
                                   source->where};
        auto animated = valueAt(*out.animation, "joints", 0.0);
        for (size_t a = 0; animated && a < animated->strings.size(); ++a)
            if (const auto it = jointIndex.find(animated->strings[a]); it != jointIndex.end())
                out.animatedJoint[size_t(it->second)] = int(a);
    }
    return out;
}

std::optional<std::variant<Skinning, SkinningProblem>> resolveSkinning(const Stage& stage, const Prim& prim) {
    const Relationship* binding = inheritedRelationship(prim, "skel:skeleton");
    const Attribute* indices = prim.attribute("primvars:skel:jointIndices");
    const Attribute* weights = prim.attribute("primvars:skel:jointWeights");
    const bool shapes = prim.attribute("skel:blendShapes") != nullptr;
    if (!binding || (!indices && !weights && !shapes)) return std::nullopt;
    if (!indices != !weights)
        return SkinningProblem{std::string("has primvars:skel:") + (indices ? "jointIndices without jointWeights"
                                                                            : "jointWeights without jointIndices"),
                               (indices ? indices : weights)->where};
    // Skinning applies beneath a SkelRoot only (UsdSkelRoot).
    const Prim* root = &prim;
    while (root && root->typeName != "SkelRoot") root = root->parent;
    if (!root) return SkinningProblem{"is bound to a Skeleton but is not beneath a SkelRoot", binding->where};

    const Prim* skeleton = stage.find(binding->targets.front());
    if (!skeleton || skeleton->typeName != "Skeleton")
        return SkinningProblem{"skel:skeleton targets <" + binding->targets.front() + ">, which is no Skeleton",
                               binding->where};
    auto resolved = resolveSkeleton(stage, *skeleton);
    if (auto* problem = std::get_if<SkinningProblem>(&resolved)) return *problem;
    Skinning out = std::get<Skinning>(std::move(resolved));
    out.prim = &prim;
    std::map<std::string, int> jointIndex;
    for (size_t j = 0; j < out.joints.size(); ++j) jointIndex.emplace(out.joints[j], int(j));
    if (indices)
        if (auto problem = readInfluences(prim, *indices, *weights, jointIndex, out)) return *problem;
    if (auto problem = readBlendShapes(stage, prim, out.animation, out)) return *problem;
    if (auto bindTransform = valueAt(prim, "primvars:skel:geomBindTransform", 0.0);
        bindTransform && bindTransform->numbers.size() == 16)
        std::copy_n(bindTransform->numbers.begin(), 16, out.geomBindTransform.begin());
    return out;
}

std::vector<Matrix4> skeletonPose(const Skinning& skinning, double time, std::string* problem) {
    std::vector<Matrix4> local = skinning.restTransforms;
    if (skinning.animation) {
        const Prim& animation = *skinning.animation;
        const size_t count = valueAt(animation, "joints", 0.0).value_or(Value{}).strings.size();
        auto translations = valueAt(animation, "translations", time);
        auto rotations = valueAt(animation, "rotations", time);
        auto scales = valueAt(animation, "scales", time);  // optional: unit scale
        auto fits = [&](const std::optional<Value>& v, int width) {
            return v && v->tupleSize == width && v->numbers.size() == count * size_t(width);
        };
        if (fits(translations, 3) && fits(rotations, 4) && (!scales || fits(scales, 3))) {
            for (size_t j = 0; j < local.size(); ++j) {
                const int a = skinning.animatedJoint[j];
                if (a < 0) continue;
                local[j] = jointTransform(&translations->numbers[size_t(3 * a)], &rotations->numbers[size_t(4 * a)],
                                          scales ? &scales->numbers[size_t(3 * a)] : nullptr);
            }
        } else if (problem) {
            *problem = "<" + animation.path + ">: translations, rotations and scales at time " + std::to_string(time) +
                       " do not hold one value for each of its " + std::to_string(count) +
                       " joints; the rest pose is used";
        }
    }
    std::vector<Matrix4> skel(local.size());
    for (size_t j = 0; j < local.size(); ++j) {
        const int parent = skinning.parents[j];
        skel[j] = parent < 0 ? local[j] : m4::multiply(local[j], skel[size_t(parent)]);
    }
    return skel;
}

std::vector<Matrix4> skinningTransforms(const Skinning& skinning, double time, std::string* problem) {
    std::vector<Matrix4> out = skeletonPose(skinning, time, problem);
    for (size_t j = 0; j < out.size(); ++j) out[j] = m4::multiply(m4::inverse(skinning.bindTransforms[j]), out[j]);
    return out;
}

std::vector<double> skinPoints(const Stage& stage, const Skinning& skinning, const std::vector<double>& authored,
                               double time, std::string* problem) {
    const size_t count = authored.size() / 3;
    if (std::string mismatch = influenceCountProblem(skinning, count); !mismatch.empty()) {
        if (problem) *problem = mismatch;
        return {};
    }
    const std::vector<double> rest = shaped(skinning, authored, time, problem);
    // UsdSkelImaging: without joint influences the shaped points are the result.
    if (rest.empty() || skinning.influencesPerPoint == 0) return rest;
    const std::vector<Matrix4> joints = skinningTransforms(skinning, time, problem);
    const Matrix4 toPrim = skelToPrim(stage, skinning, time);
    const size_t k = size_t(skinning.influencesPerPoint);
    std::vector<double> out(rest.size());
    for (size_t i = 0; i < count; ++i) {
        double bound[3] = {0, 0, 0}, skinned[3] = {0, 0, 0};
        transformPoint(&rest[3 * i], skinning.geomBindTransform, 1.0, bound);
        const size_t first = skinning.constantInfluences ? 0 : i * k;
        for (size_t n = first; n < first + k; ++n)
            if (skinning.influenceWeights[n] > kWeightEpsilon)
                transformPoint(bound, joints[size_t(skinning.influenceJoints[n])], skinning.influenceWeights[n], skinned);
        transformPoint(skinned, toPrim, 1.0, &out[3 * i]);
    }
    return out;
}

std::vector<double> skinNormals(const Stage& stage, const Skinning& skinning, const std::vector<double>& rest,
                                const std::vector<double>* faceVertexIndices, size_t pointCount, double time,
                                std::string* problem) {
    if (std::string mismatch = influenceCountProblem(skinning, pointCount); !mismatch.empty()) {
        if (problem) *problem = mismatch;
        return {};
    }
    // XXX: blend shapes' normalOffsets are not applied.
    if (skinning.influencesPerPoint == 0) return rest;
    std::vector<Matrix4> joints = skinningTransforms(skinning, time, problem);
    for (Matrix4& m : joints) m = m4::inverse(m);
    const Matrix4 bindInverse = m4::inverse(skinning.geomBindTransform);
    const Matrix4 toPrimInverse = m4::inverse(skelToPrim(stage, skinning, time));
    const size_t k = size_t(skinning.influencesPerPoint);
    std::vector<double> out(rest.size());
    for (size_t i = 0; i < rest.size() / 3; ++i) {
        const size_t point = faceVertexIndices ? size_t((*faceVertexIndices)[i]) : i;
        if (point >= pointCount) {
            if (problem) *problem = "faceVertexIndices[" + std::to_string(i) + "] is outside the points";
            return {};
        }
        double bound[3] = {0, 0, 0}, skinned[3] = {0, 0, 0};
        transformNormal(&rest[3 * i], bindInverse, 1.0, bound);
        const size_t first = skinning.constantInfluences ? 0 : point * k;
        for (size_t n = first; n < first + k; ++n)
            if (skinning.influenceWeights[n] > kWeightEpsilon)
                transformNormal(bound, joints[size_t(skinning.influenceJoints[n])], skinning.influenceWeights[n], skinned);
        transformNormal(skinned, toPrimInverse, 1.0, &out[3 * i]);
    }
    return out;
}

bool isSkinningAnimated(const Stage& stage, const Skinning& skinning) {
    if (skinning.animation)
        for (const char* name : {"translations", "rotations", "scales", "blendShapeWeights"})
            if (const Attribute* a = skinning.animation->attribute(name); a && a->isAnimated()) return true;
    return !stage.transformSampleTimes(*skinning.skeleton).empty() ||
           (skinning.prim && !stage.transformSampleTimes(*skinning.prim).empty());
}

}  // namespace obscura::usda
