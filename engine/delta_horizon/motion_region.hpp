// The guard of the guarded ΔH method: a carried-over horizon that stays valid while the camera
// moves within a bounded region around an anchor camera.
//
// Why the published ΔH needs a guard (thesis ch. 3.1.3, Fig. 3.10): it skips whatever lies
// behind parts of the horizon that rose since the last frame, on the grounds that it "was
// already occluded in frame t". But frame t's horizon was seen from another eye: after a
// lateral step, a building that hid behind a thin occluder can show beside it, while the
// horizon there has risen because of something else. The thesis's remedies are (2) update the
// carried-over horizon only with occluders wider than the distance moved, or (3) fall back to a
// full recompute. This file does both, with bounds instead of a heuristic:
//
//  - MotionRegion: the cameras within `radius` (plan) and `height` (vertical) of the anchor eye,
//    whose orientation differs from the anchor's by at most `turn` (|Δyaw| + |Δpitch| + |Δroll|,
//    which bounds the rotation angle between them), with the same fields of view and clip planes.
//  - certify_hidden: a sweep from the anchor over occluder shadows shrunk for the region (each
//    span narrowed by asin(ε / distance) per side, each elevation lowered to its minimum over the
//    region, each merged only after the sweep has passed its farthest point plus 2ε) that marks
//    every cell and building hidden from every camera of the region, each tested with its span
//    widened and its highest slope raised in the same way. Occluders narrower than the motion
//    vanish from the carried-over horizon: remedy (2), made exact.
//  - Outside the region, the guarded method re-anchors: remedy (3), and the guard "fires".
//
// What "hidden from every camera of the region" means is OH(OS)'s own test, not geometry: for
// any camera of the region, the full OH(OS) sweep (horizon_sweep.hpp) culls every marked item.
// The proof is in the comments of motion_region.cpp; numeric slack: 1e-9 rad on angles, 1e-9
// relative on slopes and distances, far above the rounding of the values compared.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

struct MotionRegion {
  Camera anchor;
  double radius = 1.0;  // ε, metres (plan)
  double height = 0.5;  // metres (vertical)
  double turn = 0.2;    // radians

  bool contains(const Camera& camera) const;
};

// Cells and buildings known hidden for every camera of a region, as epoch stamps (clearing is
// O(1): a new certificate takes a new epoch).
class HiddenCertificate {
 public:
  HiddenCertificate(const Scene& scene, const Quadtree& quadtree);

  // Recomputes the certificate for `region` (a sweep from its anchor). `horizon` is scratch
  // space for the shrunk horizon; its previous content is lost. Statistics are added to `stats`.
  void certify(const MotionRegion& region, OcclusionHorizon& horizon, CullStatistics& stats);

  bool cell_hidden(std::uint32_t cell) const { return cell_epoch_[cell] == epoch_; }
  bool building_hidden(std::uint32_t building) const { return building_epoch_[building] == epoch_; }
  std::uint64_t cells_hidden() const { return cells_hidden_; }
  std::uint64_t buildings_hidden() const { return buildings_hidden_; }

 private:
  const Scene& scene_;
  const Quadtree& quadtree_;
  std::uint32_t epoch_ = 0;
  std::vector<std::uint32_t> cell_epoch_, building_epoch_;
  std::uint64_t cells_hidden_ = 0, buildings_hidden_ = 0;
};

}  // namespace cullcheck
