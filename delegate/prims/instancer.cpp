#include "delegate/prims/instancer.h"

#include <cmath>
#include <set>

namespace obscura::delegate {

Matrix4d instanceTransform(const float* p, const float* q, const float* s) {
    double w = q ? q[0] : 1.0, x = q ? q[1] : 0.0, y = q ? q[2] : 0.0, z = q ? q[3] : 0.0;
    double n = std::sqrt(w * w + x * x + y * y + z * z);
    if (n > 0) w /= n, x /= n, y /= n, z /= n;
    // Rows are the images of the local axes (row-vector convention).
    double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
                      {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
                      {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
    Matrix4d m = kIdentity;
    for (int row = 0; row < 3; ++row)
        for (int c = 0; c < 3; ++c) m[row * 4 + c] = r[row][c] * (s ? s[row] : 1.0);
    for (int c = 0; c < 3; ++c) m[12 + c] = p[c];
    return m;
}

int Instancer::prototypeOf(const std::string& meshPath) const {
    for (size_t i = 0; i < prototypes_.size(); ++i) {
        const std::string& root = prototypes_[i];
        if (meshPath == root || (meshPath.size() > root.size() && meshPath.compare(0, root.size(), root) == 0 &&
                                 meshPath[root.size()] == '/'))
            return static_cast<int>(i);
    }
    return -1;
}

void Instancer::reset() {
    prototypes_.clear();
    protoIndices_.clear();
    byPrototype_.clear();
}

void Instancer::pull(SceneAccess& s, ObscuraDirtyBits bits, SyncContext&) {
    if (bits & OBSCURA_DIRTY_TRANSFORM) transform_ = s.sampleTransform(s.time(), s.time()).front().matrix;
    if (bits & OBSCURA_DIRTY_VISIBILITY) {
        visible_ = s.getToken("visibility") != "invisible";
        invisible_ = s.getIntArray("invisibleIds").value_or(std::vector<int32_t>{});
    }
    if (bits & OBSCURA_DIRTY_TOPOLOGY) {
        prototypes_ = s.getPathArray("prototypes");
        protoIndices_ = s.getIntArray("protoIndices").value_or(std::vector<int32_t>{});
    }
    if (bits & OBSCURA_DIRTY_POINTS) {
        positions_ = s.getFloatArray("positions").value_or(std::vector<float>{});
        orientations_ = s.getFloatArray("orientations").value_or(std::vector<float>{});
        scales_ = s.getFloatArray("scales").value_or(std::vector<float>{});
    }
    rebuildInstances(s.path());
}

void Instancer::rebuildInstances(const std::string& path) {
    const size_t n = protoIndices_.size();
    if (positions_.size() != 3 * n)
        throw PrimDataError(path + ": positions has " + std::to_string(positions_.size() / 3) + " entries for " +
                            std::to_string(n) + " instances");
    if (!orientations_.empty() && orientations_.size() != 4 * n)
        throw PrimDataError(path + ": orientations has " + std::to_string(orientations_.size() / 4) +
                            " entries for " + std::to_string(n) + " instances");
    if (!scales_.empty() && scales_.size() != 3 * n)
        throw PrimDataError(path + ": scales has " + std::to_string(scales_.size() / 3) + " entries for " +
                            std::to_string(n) + " instances");
    std::set<int32_t> hidden(invisible_.begin(), invisible_.end());
    byPrototype_.assign(prototypes_.size(), {});
    for (size_t i = 0; i < n; ++i) {
        int32_t proto = protoIndices_[i];
        if (proto < 0 || size_t(proto) >= prototypes_.size())
            throw PrimDataError(path + ": protoIndices[" + std::to_string(i) + "] = " + std::to_string(proto) +
                                " is outside the " + std::to_string(prototypes_.size()) + " prototypes");
        if (hidden.count(int32_t(i))) continue;
        Matrix4d local = instanceTransform(&positions_[3 * i], orientations_.empty() ? nullptr : &orientations_[4 * i],
                                           scales_.empty() ? nullptr : &scales_[3 * i]);
        byPrototype_[size_t(proto)].push_back(multiply(local, transform_));
    }
}

}  // namespace obscura::delegate
