#include "core/camera_matrices.hpp"

#include <cmath>

namespace cullcheck {

Matrix4 view_matrix(const Camera& c) {
  CameraBasis b = basis_of(c);
  if (c.omnidirectional()) b = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}};
  // Rows: right, up, -forward; then the eye moved to the origin.
  const Vec3 rows[3] = {b.right, b.up, b.forward * -1.0};
  Matrix4 m{};
  for (int r = 0; r < 3; ++r) m[r] = {rows[r].x, rows[r].y, rows[r].z, -dot(rows[r], c.position)};
  m[3] = {0, 0, 0, 1};
  return m;
}

std::optional<Matrix4> projection_matrix(const Camera& c) {
  if (c.omnidirectional()) return std::nullopt;
  const double f = c.far;
  Matrix4 m{};
  if (c.orthographic()) {
    const double n = c.near;
    m[0] = {2.0 / c.ortho_width, 0, 0, 0};
    m[1] = {0, 2.0 / c.ortho_height, 0, 0};
    m[2] = {0, 0, -2.0 / (f - n), -(f + n) / (f - n)};
    m[3] = {0, 0, 0, 1};
    return m;
  }
  const double n = c.near > 0.0 ? c.near : f * 1e-7;
  m[0] = {1.0 / std::tan(c.hfov / 2), 0, 0, 0};
  m[1] = {0, 1.0 / std::tan(c.vfov / 2), 0, 0};
  m[2] = {0, 0, -(f + n) / (f - n), -2.0 * f * n / (f - n)};
  m[3] = {0, 0, -1, 0};
  return m;
}

Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
  Matrix4 m{};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      for (int k = 0; k < 4; ++k) m[r][c] += a[r][k] * b[k][c];
  return m;
}

std::array<double, 4> transform(const Matrix4& m, Vec3 p) {
  std::array<double, 4> out{};
  for (int r = 0; r < 4; ++r) out[r] = m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3];
  return out;
}

}  // namespace cullcheck
