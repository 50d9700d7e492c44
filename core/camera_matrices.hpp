// A camera as the 4x4 view and projection matrices an engine uses as is (the subject protocol
// sends them with every frame; README "The subject protocol").
//
// Convention (OpenGL's): eye space is right-handed with x to the right of the image, y up the
// image and the camera looking down -z; clip = projection * view * (x, y, z, 1) for scene-local
// column vectors, and a point is inside the view volume when -w <= x, y, z <= w in clip space
// (normalised depth from -1 at the near plane to +1 at the far plane). Matrices are row-major:
// m[row][column]. A perspective camera with near = 0 gets the projection of near = far * 1e-7
// (a projection needs near > 0). Omnidirectional cameras have a view matrix (looking along +x,
// z up, whatever yaw, pitch and roll say: the view volume is a ball) and no projection.
#pragma once

#include <array>
#include <optional>

#include "core/camera.hpp"

namespace cullcheck {

using Matrix4 = std::array<std::array<double, 4>, 4>;

Matrix4 view_matrix(const Camera& camera);
std::optional<Matrix4> projection_matrix(const Camera& camera);
Matrix4 multiply(const Matrix4& a, const Matrix4& b);
// (x, y, z, w) = m * (p, 1).
std::array<double, 4> transform(const Matrix4& m, Vec3 p);

}  // namespace cullcheck
