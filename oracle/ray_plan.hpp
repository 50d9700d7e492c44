// The ray oracle's sampling plan: which rays to cast, in a fixed order (design: "Oracle").
//
// Order: candidate objects (buildings, then mesh objects, whose boxes may meet the view volume)
// in scene order, each with its surface samples in order (surface_samples.hpp); then the
// stratified grid over the view volume row by row, jittered by a SplitMix64 stream seeded with
// options.seed. The plan is produced in chunks so that a query over millions of rays needs
// memory for one chunk only.
//
// Where rays start: a perspective or omnidirectional camera's rays start at the eye. An
// orthographic camera's rays are parallel to its view direction: the ray aimed at a sample point
// p starts on the near plane directly in front of p (p minus (depth of p - near) along the view
// direction), so every ray has its own origin; samples before the near plane or outside the
// ortho_width x ortho_height rectangle get no ray (nothing there is in the view volume).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/ray_oracle.hpp"
#include "oracle/sampling.hpp"
#include "oracle/splitmix64.hpp"

namespace cullcheck::oracle {

inline constexpr std::uint32_t kNoObjectIndex = std::numeric_limits<std::uint32_t>::max();

// A ray in double precision, scene-local.
struct PlannedRay {
  Vec3 origin;            // the eye, or for an orthographic camera a point on the near plane
  Vec3 direction;         // unit length
  double t_near, t_far;   // metres along `direction`
  Vec3 target;            // the sample aimed at, or origin + t_far * direction
  std::uint32_t aimed_at; // object index (mesh.hpp: buildings, then meshes), or kNoObjectIndex
  RaySource source;
};

// The view volume and the extent it allows along each ray.
class ViewCone {
 public:
  explicit ViewCone(const Camera& camera);
  const ViewVolume& volume() const { return volume_; }
  // Perspective and omnidirectional cameras: false when no point along the unit direction `d`
  // from the eye lies in the view volume; otherwise the extent: from the near plane (geometry
  // before it is clipped, so it hides nothing) to far. Omnidirectional: [0, far].
  // Orthographic cameras: every ray has direction forward() and t in [0, far - near] from its
  // origin on the near plane; `d` must be forward() (anything else gives false).
  bool extent(Vec3 d, double& t_near, double& t_far) const;
  // The ray toward sample point `p`, or false when it cannot meet p inside the view volume.
  bool ray_toward(Vec3 p, PlannedRay& out) const;
  Vec3 forward() const { return basis_.forward; }

 private:
  ViewVolume volume_;
  CameraBasis basis_;
  Vec3 eye_;
  double near_, far_;
  bool orthographic_;
  double half_width_ = 0.0, half_height_ = 0.0;  // orthographic rectangle
};

class RayPlan {
 public:
  RayPlan(const Scene& scene, const Camera& camera, const SamplingOptions& options);
  // Appends the next rays of the plan to `out` until it holds at least `count` rays or the plan
  // is exhausted; returns false once nothing was left to append.
  bool next(std::vector<PlannedRay>& out, std::size_t count);
  std::size_t candidates() const { return candidates_; }
  std::size_t capped_objects() const { return capped_; }
  const ViewCone& cone() const { return cone_; }

 private:
  void plan_object(std::uint32_t index, std::vector<PlannedRay>& out);
  void plan_cell(std::vector<PlannedRay>& out);

  const Scene& scene_;
  const Camera& camera_;
  const SamplingOptions& options_;
  ViewCone cone_;
  CameraBasis basis_;
  std::uint32_t object_ = 0;  // next object to consider (buildings, then meshes)
  std::size_t cell_ = 0;      // next stratified cell, row-major
  int columns_ = 0, rows_ = 0;
  SplitMix64 rng_;
  std::size_t candidates_ = 0, capped_ = 0;
};

}  // namespace cullcheck::oracle
