#include "core/camera.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace cullcheck {
namespace {

void require_finite(double v, const std::string& object, const char* field) {
  if (!std::isfinite(v)) throw InputError(object, field, "must be a finite number");
}

// Slack on plane tests so that rounding in a box-corner test can never reject a box that holds
// a point the exact point test accepts. 1e-7 m is far below any modelled feature.
constexpr double kPlaneSlack = 1e-7;

}  // namespace

void validate(const Camera& c, const std::string& object) {
  require_finite(c.position.x, object, "position.x");
  require_finite(c.position.y, object, "position.y");
  require_finite(c.position.z, object, "position.z");
  require_finite(c.yaw, object, "yaw");
  require_finite(c.pitch, object, "pitch");
  require_finite(c.roll, object, "roll");
  require_finite(c.hfov, object, "hfov");
  require_finite(c.vfov, object, "vfov");
  require_finite(c.near, object, "near");
  require_finite(c.far, object, "far");
  // Occlusion arguments assume a viewer on or above the ground plane (nothing is seen through it).
  if (c.position.z < 0.0) throw InputError(object, "position.z", "eye is below the ground plane (z < 0)");
  if (c.pitch < -kPi / 2 || c.pitch > kPi / 2) throw InputError(object, "pitch", "must lie in [-pi/2, pi/2]");
  if ((c.width == 0) != (c.height == 0)) throw InputError(object, "resolution", "give both width and height, or neither");
  if (c.width < 0 || c.height < 0 || c.width > kMaxImageSide || c.height > kMaxImageSide)
    throw InputError(object, "resolution", "each side must lie in [1, 8192] pixels");
  if (c.orthographic()) {
    require_finite(c.ortho_width, object, "ortho_width");
    require_finite(c.ortho_height, object, "ortho_height");
    if (!(c.ortho_width > 0.0 && c.ortho_width <= 1e7)) throw InputError(object, "ortho_width", "must lie in (0, 1e7] metres");
    if (!(c.ortho_height > 0.0 && c.ortho_height <= 1e7)) throw InputError(object, "ortho_height", "must lie in (0, 1e7] metres");
    if (!(c.near >= 0.0)) throw InputError(object, "near", "must be >= 0");
  } else if (!c.omnidirectional()) {
    if (!(c.hfov > 0.0 && c.hfov < kPi))
      throw InputError(object, "hfov", "must lie in (0, pi) for a perspective camera, or be 2*pi for 360-degree mode");
    if (!(c.vfov > 0.0 && c.vfov < kPi)) throw InputError(object, "vfov", "must lie in (0, pi)");
    if (!(c.near >= 0.0)) throw InputError(object, "near", "must be >= 0");
  }
  if (!(c.far > c.near)) throw InputError(object, "far", "must be greater than near");
}

Resolution resolution_of(const Camera& c) {
  if (c.width > 0 && c.height > 0) return {c.width, c.height};
  double rows_per_column = 0.5;  // an equirectangular panorama: 2 pi across, pi high
  if (c.orthographic()) {
    rows_per_column = c.ortho_height / c.ortho_width;
  } else if (!c.omnidirectional()) {
    rows_per_column = std::tan(c.vfov / 2) / std::tan(c.hfov / 2);
  }
  const double rows = std::round(kDefaultImageWidth * rows_per_column);
  return {kDefaultImageWidth, static_cast<int>(std::clamp(rows, 1.0, double(kMaxImageSide)))};
}

CameraBasis basis_of(const Camera& c) {
  const Vec3 forward{std::cos(c.pitch) * std::cos(c.yaw), std::cos(c.pitch) * std::sin(c.yaw), std::sin(c.pitch)};
  // Right before roll is horizontal, so pitch +-90 degrees keeps a well-defined basis.
  const Vec3 right0{std::sin(c.yaw), -std::cos(c.yaw), 0.0};
  const Vec3 up0 = cross(right0, forward);
  const Vec3 right = right0 * std::cos(c.roll) + up0 * std::sin(c.roll);
  return {forward, right, cross(right, forward)};
}

ViewVolume::ViewVolume(const Camera& c) : eye(c.position), far(c.far), omnidirectional(c.omnidirectional()) {
  if (omnidirectional) return;
  const CameraBasis b = basis_of(c);
  if (c.orthographic()) {
    // |(p - eye).right| <= width / 2 and |(p - eye).up| <= height / 2, then near and far.
    const Vec3 normals[6] = {b.right * -1.0, b.right, b.up * -1.0, b.up, b.forward, b.forward * -1.0};
    const double half[4] = {c.ortho_width / 2, c.ortho_width / 2, c.ortho_height / 2, c.ortho_height / 2};
    for (int i = 0; i < 6; ++i) planes[i] = {normals[i], -dot(normals[i], eye) + (i < 4 ? half[i] : 0.0)};
    planes[4].d -= c.near;
    planes[5].d += c.far;
    plane_count = 6;
    return;
  }
  const double sh = std::sin(c.hfov / 2), ch = std::cos(c.hfov / 2);
  const double sv = std::sin(c.vfov / 2), cv = std::cos(c.vfov / 2);
  const Vec3 normals[6] = {
      b.forward * sh - b.right * ch, b.forward * sh + b.right * ch,  // right, left sides
      b.forward * sv - b.up * cv,    b.forward * sv + b.up * cv,     // top, bottom sides
      b.forward,                     b.forward * -1.0,               // near, far
  };
  for (int i = 0; i < 6; ++i) planes[i] = {normals[i], -dot(normals[i], eye)};
  planes[4].d -= c.near;
  planes[5].d += c.far;
  plane_count = 6;
}

bool ViewVolume::contains(Vec3 p) const {
  if (omnidirectional) return length(p - eye) <= far;
  for (int i = 0; i < plane_count; ++i)
    if (planes[i].signed_distance(p) < 0.0) return false;
  return true;
}

bool ViewVolume::may_intersect(const Box3& box) const {
  if (omnidirectional) {
    const double dx = std::max({box.lo.x - eye.x, 0.0, eye.x - box.hi.x});
    const double dy = std::max({box.lo.y - eye.y, 0.0, eye.y - box.hi.y});
    const double dz = std::max({box.lo.z - eye.z, 0.0, eye.z - box.hi.z});
    return std::sqrt(dx * dx + dy * dy + dz * dz) <= far + kPlaneSlack;
  }
  for (int i = 0; i < plane_count; ++i) {
    const Vec3& n = planes[i].n;
    const Vec3 corner{n.x >= 0 ? box.hi.x : box.lo.x, n.y >= 0 ? box.hi.y : box.lo.y, n.z >= 0 ? box.hi.z : box.lo.z};
    if (planes[i].signed_distance(corner) < -kPlaneSlack) return false;
  }
  return true;
}

}  // namespace cullcheck
