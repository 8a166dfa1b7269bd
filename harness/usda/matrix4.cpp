#include "harness/usda/matrix4.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace obscura::usda::matrix4 {

Matrix4 identity() {
    return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
}

Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
    Matrix4 out{};
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double sum = 0.0;
            for (int k = 0; k < 4; ++k) sum += a[r * 4 + k] * b[k * 4 + c];
            out[r * 4 + c] = sum;
        }
    return out;
}

Matrix4 inverse(const Matrix4& m, bool* invertible) {
    // Gauss-Jordan elimination with partial pivoting on [m | I].
    Matrix4 a = m;
    Matrix4 inv = identity();
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int r = col + 1; r < 4; ++r)
            if (std::abs(a[r * 4 + col]) > std::abs(a[pivot * 4 + col])) pivot = r;
        if (std::abs(a[pivot * 4 + col]) < 1e-300) {
            if (invertible) *invertible = false;
            return identity();
        }
        for (int c = 0; c < 4; ++c) {
            std::swap(a[col * 4 + c], a[pivot * 4 + c]);
            std::swap(inv[col * 4 + c], inv[pivot * 4 + c]);
        }
        const double scaleBy = 1.0 / a[col * 4 + col];
        for (int c = 0; c < 4; ++c) {
            a[col * 4 + c] *= scaleBy;
            inv[col * 4 + c] *= scaleBy;
        }
        for (int r = 0; r < 4; ++r) {
            if (r == col) continue;
            const double factor = a[r * 4 + col];
            for (int c = 0; c < 4; ++c) {
                a[r * 4 + c] -= factor * a[col * 4 + c];
                inv[r * 4 + c] -= factor * inv[col * 4 + c];
            }
        }
    }
    if (invertible) *invertible = true;
    return inv;
}

Matrix4 translation(double x, double y, double z) {
    Matrix4 m = identity();
    m[12] = x;
    m[13] = y;
    m[14] = z;
    return m;
}

Matrix4 scale(double x, double y, double z) {
    Matrix4 m = identity();
    m[0] = x;
    m[5] = y;
    m[10] = z;
    return m;
}

Matrix4 rotation(int axis, double degrees) {
    const double radians = degrees * std::numbers::pi / 180.0;
    const double c = std::cos(radians);
    const double s = std::sin(radians);
    // The two axes the rotation turns into each other: X->Y for Z, Y->Z for X, Z->X for Y.
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    Matrix4 m = identity();
    m[u * 4 + u] = c;
    m[u * 4 + v] = s;
    m[v * 4 + u] = -s;
    m[v * 4 + v] = c;
    return m;
}

Matrix4 rotation(double real, double i, double j, double k) {
    const double length = std::sqrt(real * real + i * i + j * j + k * k);
    if (length == 0.0) return identity();
    const double w = real / length, x = i / length, y = j / length, z = k / length;
    return {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
            2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
            2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
            0,                       0,                       0,                       1};
}

}  // namespace obscura::usda::matrix4
