#include "engine/frustum/range_detection.hpp"

#include "core/elapsed.hpp"
#include "engine/frustum/box_walk.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace cullcheck {
namespace {

// A box is dropped only when it lies this far (metres) beyond a range's plane, as the six-plane
// test does (core/camera.cpp): rounding cannot drop one that touches the frustum.
constexpr double kSlack = 1e-7;

// Eq. 5, 9, 10 for one point in camera coordinates.
bool point_inside(const CameraRanges& r, Vec3 c) {
  if (!(r.near < c.z && c.z < r.far)) return false;
  const double half_h = c.z * r.tan_v, half_w = c.z * r.tan_h;  // h / 2 and w / 2 at that depth
  return -half_h < c.y && c.y < half_h && -half_w < c.x && c.x < half_w;
}

// The bounding sphere of a box: its centre and half diagonal.
double radius_of(const Box3& b) { return 0.5 * length(b.hi - b.lo); }

// The sphere outside the frustum's ranges. `published`: every range widened by r; otherwise the
// sides by r / cos(half angle), the distance from the centre to the side plane.
bool sphere_outside(const CameraRanges& r, Vec3 c, double radius, bool published) {
  const double slack = published ? 0.0 : kSlack;
  if (c.z < r.near - radius - slack || c.z > r.far + radius + slack) return true;
  const double dy = published ? radius : (radius + slack) * r.sphere_factor_y;
  const double dx = published ? radius : (radius + slack) * r.sphere_factor_x;
  const double half_h = c.z * r.tan_v, half_w = c.z * r.tan_h;
  return c.y > half_h + dy || c.y < -half_h - dy || c.x > half_w + dx || c.x < -half_w - dx;
}

// All eight corners beyond one and the same range: from the box's centre `c` (camera
// coordinates) and half-extents `h`, its support along each range's plane normal.
bool box_outside_one_range(const CameraRanges& r, Vec3 c, Vec3 h) {
  const double sz = dot(h, r.abs_z);
  if (c.z + sz < r.near - kSlack || c.z - sz > r.far + kSlack) return true;
  // y - z tan_v > 0 at every corner (above the top), and the three others alike; the normals
  // are 1 / cos(half angle) long.
  const double slack_y = kSlack * r.sphere_factor_y, slack_x = kSlack * r.sphere_factor_x;
  const double vy = c.z * r.tan_v, vx = c.z * r.tan_h;
  return c.y - vy - dot(h, r.abs_top) > slack_y || -c.y - vy - dot(h, r.abs_bottom) > slack_y ||
         c.x - vx - dot(h, r.abs_right) > slack_x || -c.x - vx - dot(h, r.abs_left) > slack_x;
}

}  // namespace

CameraRanges::CameraRanges(const Camera& camera) : eye(camera.position), near(camera.near), far(camera.far) {
  const CameraBasis b = basis_of(camera);
  x = b.right, y = b.up, z = b.forward;
  tan_v = std::tan(camera.vfov / 2);
  tan_h = std::tan(camera.hfov / 2);  // = tan_v times the aspect ratio tan(hfov/2) / tan(vfov/2)
  sphere_factor_y = 1.0 / std::cos(camera.vfov / 2);
  sphere_factor_x = 1.0 / std::cos(camera.hfov / 2);
  const auto abs_of = [](Vec3 v) { return Vec3{std::abs(v.x), std::abs(v.y), std::abs(v.z)}; };
  abs_z = abs_of(z);
  abs_top = abs_of(y - z * tan_v);
  abs_bottom = abs_of(y * -1.0 - z * tan_v);
  abs_right = abs_of(x - z * tan_h);
  abs_left = abs_of(x * -1.0 - z * tan_h);
}

bool range_outside(RangeRule rule, const CameraRanges& r, const Box3& box, std::uint64_t& tests) {
  return range_outside(rule, r, box, radius_of(box), tests);
}

bool range_outside(RangeRule rule, const CameraRanges& r, const Box3& box, double radius, std::uint64_t& tests) {
  const Vec3 centre = r.to_camera((box.lo + box.hi) * 0.5);
  switch (rule) {
    case RangeRule::published: {
      ++tests;
      if (centre.z < 0.0) return true;  // the front test: not facing the camera
      ++tests;
      if (sphere_outside(r, centre, radius, true)) return true;
      for (int k = 0; k < 8; ++k) {
        ++tests;
        const Vec3 corner{k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z};
        if (point_inside(r, r.to_camera(corner))) return false;  // INSIDE or INTERSECT
      }
      return true;  // OUTSIDE: all eight corners outside
    }
    case RangeRule::corrected:
      ++tests;
      if (sphere_outside(r, centre, radius, false)) return true;
      ++tests;
      return box_outside_one_range(r, centre, (box.hi - box.lo) * 0.5);
    case RangeRule::radar:
      ++tests;
      return sphere_outside(r, centre, radius, false);
  }
  return false;
}

RangeDetectionCulling::RangeDetectionCulling(const Scene& scene, RangeRule rule, const MethodOptions& options)
    : scene_(scene), rule_(rule), quadtree_(scene, options.quadtree_leaf_size) {
  radius_.reserve(scene.buildings.size());
  for (const Building& b : scene.buildings) radius_.push_back(radius_of(b.bounds));
}

std::string RangeDetectionCulling::name() const {
  switch (rule_) {
    case RangeRule::published: return "rdt";
    case RangeRule::corrected: return "rdt_corrected";
    case RangeRule::radar: return "radar_frustum";
  }
  return "rdt";
}

std::string RangeDetectionCulling::unsupported_camera(const Camera& camera) const {
  if (camera.orthographic()) return "orthographic camera: " + name() + " tests the ranges of a perspective frustum";
  if (!(camera.hfov < kPi) || !(camera.vfov < kPi))
    return "field of view of half a turn or more: " + name() + " tests the ranges of a frustum (tan of the half angle)";
  return "";
}

CullResult RangeDetectionCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  const CameraRanges ranges(camera);
  std::uint64_t tests = 0;
  walk_boxes(
      quadtree_, scene_, [&](const Box3& box) { return !range_outside(rule_, ranges, box, tests); },
      [&](const Box3& box, std::int64_t index) {
        return !(index >= 0 ? range_outside(rule_, ranges, box, radius_[static_cast<std::size_t>(index)], tests)
                            : range_outside(rule_, ranges, box, tests));
      },
      result);
  result.stats.bound_tests = tests;
  result.stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
