// 4x4 matrices as USD's GfMatrix4d uses them: row-major, row vectors (p' = p * M), translation
// in elements 12..14.
#pragma once

#include <array>

namespace obscura::usda::matrix4 {

using Matrix4 = std::array<double, 16>;

Matrix4 identity();
Matrix4 multiply(const Matrix4& a, const Matrix4& b);  // a then b for row vectors
// The inverse; a singular matrix gives the identity and sets *invertible to false.
Matrix4 inverse(const Matrix4& m, bool* invertible = nullptr);

Matrix4 translation(double x, double y, double z);
Matrix4 scale(double x, double y, double z);
// Rotation about one axis (0 = X, 1 = Y, 2 = Z) by degrees, counter-clockwise looking down the axis.
Matrix4 rotation(int axis, double degrees);
// Rotation of a quaternion given real part first; it is normalized first.
Matrix4 rotation(double real, double i, double j, double k);

}  // namespace obscura::usda::matrix4
