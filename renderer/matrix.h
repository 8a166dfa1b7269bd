// 4x4 double matrices in USD's convention (GfMatrix4d): row-major storage, row vectors
// (p' = p * M), translation in elements 12..14. Uploaded as float in the same order, such a
// matrix is the column-major GLSL matrix of the transposed (column-vector) transform, so
// shaders use `M * v` with no conversion.
#pragma once

#include <array>
#include <cmath>

namespace obscura {

using Matrix4d = std::array<double, 16>;
using Vec3d = std::array<double, 3>;

constexpr Matrix4d kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

inline Matrix4d multiply(const Matrix4d& a, const Matrix4d& b) {
    Matrix4d r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[i * 4 + k] * b[k * 4 + j];
            r[i * 4 + j] = s;
        }
    return r;
}

inline Matrix4d transpose(const Matrix4d& m) {
    Matrix4d r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r[i * 4 + j] = m[j * 4 + i];
    return r;
}

// General inverse by cofactors; returns false for a singular matrix.
bool invert(const Matrix4d& m, Matrix4d& out);

inline Vec3d transformPoint(const Vec3d& p, const Matrix4d& m) {
    Vec3d r{};
    double w = p[0] * m[3] + p[1] * m[7] + p[2] * m[11] + m[15];
    for (int j = 0; j < 3; ++j) r[j] = (p[0] * m[j] + p[1] * m[4 + j] + p[2] * m[8 + j] + m[12 + j]) / w;
    return r;
}

inline Vec3d transformDirection(const Vec3d& d, const Matrix4d& m) {
    return {d[0] * m[0] + d[1] * m[4] + d[2] * m[8], d[0] * m[1] + d[1] * m[5] + d[2] * m[9],
            d[0] * m[2] + d[1] * m[6] + d[2] * m[10]};
}

inline Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3d add(const Vec3d& a, const Vec3d& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3d scale(const Vec3d& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3d& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
inline Vec3d normalized(const Vec3d& v) {
    double l = length(v);
    return l > 0 ? Vec3d{v[0] / l, v[1] / l, v[2] / l} : v;
}

template <typename Out>
Out toFloats(const Matrix4d& m) {
    Out r{};
    for (int i = 0; i < 16; ++i) r[i] = static_cast<float>(m[i]);
    return r;
}

}  // namespace obscura
