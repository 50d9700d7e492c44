// The guard of the guarded ΔH method: what a carried-over horizon proves about every camera
// within a bounded region around an anchor camera.
//
// Why the published ΔH needs a guard (thesis ch. 3.1.3, Fig. 3.10): it skips whatever lies
// behind parts of the horizon that rose since the last frame, on the grounds that it "was
// already occluded in frame t". But frame t's horizon was seen from another eye: after a
// lateral step, a building that hid behind an occluder can show beside it, while the horizon
// there has risen because of something else. The thesis's remedies are (2) update the
// carried-over horizon only with occluders wider than the distance moved, or (3) fall back to a
// full recompute. This file does both, with bounds instead of a heuristic:
//
//  - MotionRegion: the cameras within `radius` (plan) and `height` (vertical) of the anchor eye,
//    whose orientation differs from the anchor's by at most `turn` (|Δyaw| + |Δpitch| + |Δroll|,
//    which bounds the rotation angle between them), with the same fields of view and clip planes.
//  - RegionCertificate: one sweep from the anchor sorts every building into
//      hidden    — OH(OS) culls it from every camera of the region: tested against a horizon
//                  of occluder shadows shrunk for the region (spans narrowed by asin(ε / r) per
//                  side, elevations lowered to their minimum over the region, merged only once
//                  the sweep has passed the CVP's farthest point + 2ε), with its own span
//                  widened and its slope raised the same way. Occluders narrower than the
//                  motion vanish from this horizon: remedy (2), made exact;
//      visible   — OH(OS) keeps it from every camera of the region: it certainly meets the view
//                  volume, and one of its CVPs rises above a horizon of occluder shadows grown
//                  for the region, at a bin that every camera's azimuth coverage holds;
//      uncertain — everything else that may meet the view volume of some camera of the region;
//    plus, among the visible, the `relevant` ones: those whose shadow can reach the bins of an
//    uncertain building nearer than it, from some camera of the region.
//    Buildings certainly outside every camera's view volume are in no list.
//  - Outside the region, the guarded method re-anchors: remedy (3), and the guard "fires".
//
// Everything is proven against OH(OS)'s own tests (horizon_sweep.hpp), not geometry; the proofs
// are in motion_region.cpp. Numeric slack: 1e-9 rad on angles, 1e-9 relative on slopes and
// distances, far above the rounding of the values compared.
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

// View-volume tests over a region: the cameras whose eye lies within `reach` of `volume`'s and
// whose orientation is within `turn` radians of its camera's. certainly_meets: OH(OS) at every
// such camera tests the box (does not cull it by its view volume); may_meet: false only when
// every such camera culls it.
bool certainly_meets(const ViewVolume& volume, const Box3& box, double reach, double turn);
bool may_meet(const ViewVolume& volume, const Box3& box, double reach, double turn);
// True when may_meet(volume, box, reach, turn) holds for every box within `extent`, as it does
// for an all-round volume whose far plane lies beyond twice the L1 distance to the extent's
// farthest corner (may_meet's own shortcut, taken at that corner; the offsets it adds only shrink
// for a box inside). A sweep then skips the test (issue 17: 4% of a VbAoI graph).
bool meets_every_box(const ViewVolume& volume, const Box3& extent, double reach);

class RegionCertificate {
 public:
  RegionCertificate(const Scene& scene, const Quadtree& quadtree, std::uint32_t bins);

  // Recomputes the certificate for `region` (a sweep from its anchor). Statistics are added to
  // `stats` (cells and buildings tested, horizon nodes).
  // With `same_as_oh_os` (the guarded ΔH), "hidden" means OH(OS) culls it at every camera of the
  // region, so only buildings OH(OS) surely tests there may occlude. Without it (from-region
  // PVS), "hidden" means hidden from every camera, and any building's shrunk shadow counts:
  // a shadow is real occlusion whether or not its building is in the view volume; and an item is
  // tested by its span narrowed for the region (RegionBounds::seen_item), not widened; or, with
  // `narrow_targets` false, widened as for OH(OS) (what the certified shrinking did before).
  void certify(const MotionRegion& region, CullStatistics& stats, bool same_as_oh_os = true, bool narrow_targets = true);

  // Scene indices of the certainly visible buildings, ascending.
  const std::vector<std::uint32_t>& visible() const { return visible_; }
  // Scene indices of the buildings a query must sweep: the uncertain ones, and the relevant
  // certainly visible ones; `certainly_visible(i)` tells which.
  const std::vector<std::uint32_t>& swept() const { return swept_; }
  bool certainly_visible(std::uint32_t building) const { return visible_epoch_[building] == epoch_; }
  std::uint64_t hidden_count() const { return hidden_count_; }
  std::uint64_t uncertain_count() const { return uncertain_count_; }

 private:
  const Scene& scene_;
  const Quadtree& quadtree_;
  OcclusionHorizon shrunk_, grown_, uncertain_reach_;
  std::uint32_t epoch_ = 0;
  std::vector<std::uint32_t> visible_epoch_;
  std::vector<std::uint32_t> visible_, swept_;
  std::uint64_t hidden_count_ = 0, uncertain_count_ = 0;
};

}  // namespace cullcheck
