// View-frustum culling in the camera's own frame (Sunar, Zin & Sembok, "Range Detection
// Technique", after Placeres 2005): a point is put in camera coordinates by three dot products
// (Eq. 3-4, 6-7) and tested against the frustum's ranges: near < z < far (Eq. 5), |y| < h / 2
// with h = 2 z tan(θ/2), θ the vertical field of view (Eq. 8-9), |x| < w / 2 with w = h times the
// aspect ratio (Eq. 10). Quadtree cells first, then buildings, as the six-plane method does.
//
// Three rules:
//   rdt            as published: an object whose centre lies behind the camera is not facing it
//                  (the front test); its bounding sphere is the centre's point test with every
//                  range widened by the radius; then its box's eight corners are point-tested,
//                  OUTSIDE when all eight are outside the frustum (INTERSECT counts as INSIDE).
//                  The paper claims only what is outside the frustum is dropped; it is not
//                  claimed here (claims_conservative false): the claims ledger checks it.
//   rdt_corrected  the same point tests made sound: no front test beyond the sphere's (all of
//                  it before the near plane); the sphere's side ranges widened by r / cos of the
//                  half angle (the distance to a side plane, not along the range); a box OUTSIDE
//                  only when its eight corners are outside the same one of the six ranges, which
//                  is decided from the box's centre and half-extents in camera coordinates (three
//                  dot products and six supports, no corner loop).
//   radar_frustum  Placeres's radar approach, as the Lighthouse3d tutorial that credits his Game
//                  Programming Gems 5 article describes it (the article itself is not at hand):
//                  the bounding sphere alone, with the same r / cos widening; the sides' and
//                  ends' ranges only, no boxes.
// Orthographic and half-turn or wider fields of view are not frusta these rules know.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

enum class RangeRule { published, corrected, radar };

// The camera's frame and ranges, set once per frame.
struct CameraRanges {
  Vec3 eye, x, y, z;  // right, up, forward (unit)
  double near = 0.0, far = 0.0;
  double tan_v = 0.0, tan_h = 0.0;              // tan of the half angles; tan_h = tan_v * aspect ratio
  double sphere_factor_y = 1.0, sphere_factor_x = 1.0;  // 1 / cos of the half angles
  // The corrected box test's directions, per frame: |z| and the four side planes' normals
  // (unnormalised: top y - z tan_v, bottom -y - z tan_v, right x - z tan_h, left -x - z tan_h),
  // each component made non-negative, so a box's half-extent along one is a dot product.
  Vec3 abs_z, abs_top, abs_bottom, abs_right, abs_left;
  explicit CameraRanges(const Camera& camera);
  Vec3 to_camera(Vec3 p) const {
    const Vec3 v = p - eye;
    return {dot(v, x), dot(v, y), dot(v, z)};
  }
};

// The tests one rule makes on a box (and its bounding sphere); true: OUTSIDE, drop it. `tests`
// counts point, sphere and box tests made.
bool range_outside(RangeRule rule, const CameraRanges& r, const Box3& box, std::uint64_t& tests);
// The same with the box's bounding-sphere radius (half its diagonal) known, as the paper keeps it
// with each object.
bool range_outside(RangeRule rule, const CameraRanges& r, const Box3& box, double radius, std::uint64_t& tests);

class RangeDetectionCulling final : public CullingMethod {
 public:
  RangeDetectionCulling(const Scene& scene, RangeRule rule, const MethodOptions& options = {});
  std::string name() const override;
  bool claims_conservative() const override { return rule_ != RangeRule::published; }
  std::string unsupported_camera(const Camera& camera) const override;
  CullResult cull(const Camera& camera) override;

 private:
  const Scene& scene_;
  RangeRule rule_;
  Quadtree quadtree_;
  std::vector<double> radius_;  // each building's bounding-sphere radius, by index
};

}  // namespace cullcheck
