// The ray oracle's sampling plan: which rays to cast, in a fixed order (design: "Oracle").
//
// Order: candidate buildings (boxes that may meet the view volume) in scene order, each with its
// surface samples in order (surface_samples.hpp); then the stratified grid over the view volume
// row by row, jittered by a SplitMix64 stream seeded with options.seed. The plan is produced in
// chunks so that a query over millions of rays needs memory for one chunk only.
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

inline constexpr std::uint32_t kNoBuilding = std::numeric_limits<std::uint32_t>::max();

// A ray in double precision, scene-local, from the camera's eye.
struct PlannedRay {
  Vec3 direction;         // unit length
  double t_near, t_far;   // metres along `direction`
  Vec3 target;            // the sample aimed at, or eye + t_far * direction
  std::uint32_t aimed_at; // index into Scene::buildings, or kNoBuilding for stratified rays
  RaySource source;
};

// The view volume as a cone of directions plus the extent it allows along each of them.
class ViewCone {
 public:
  explicit ViewCone(const Camera& camera);
  const ViewVolume& volume() const { return volume_; }
  // False when no point along the unit direction `d` lies in the view volume; otherwise the
  // extent: from the near plane (geometry before it is clipped, so it hides nothing) to far.
  bool extent(Vec3 d, double& t_near, double& t_far) const;

 private:
  ViewVolume volume_;
  Vec3 forward_;
  double near_, far_;
};

class RayPlan {
 public:
  RayPlan(const Scene& scene, const Camera& camera, const SamplingOptions& options);
  // Appends the next rays of the plan to `out` until it holds at least `count` rays or the plan
  // is exhausted; returns false once nothing was left to append.
  bool next(std::vector<PlannedRay>& out, std::size_t count);
  std::size_t candidates() const { return candidates_; }
  std::size_t capped_buildings() const { return capped_; }
  const ViewCone& cone() const { return cone_; }

 private:
  void plan_building(std::uint32_t index, std::vector<PlannedRay>& out);
  void plan_cell(std::vector<PlannedRay>& out);

  const Scene& scene_;
  const Camera& camera_;
  const SamplingOptions& options_;
  ViewCone cone_;
  CameraBasis basis_;
  std::uint32_t building_ = 0;  // next building to consider
  std::size_t cell_ = 0;        // next stratified cell, row-major
  int columns_ = 0, rows_ = 0;
  SplitMix64 rng_;
  std::size_t candidates_ = 0, capped_ = 0;
};

}  // namespace cullcheck::oracle
