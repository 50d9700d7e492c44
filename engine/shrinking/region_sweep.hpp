// The front-to-back sweep shared by the from-region shrinking methods (region_shrinking.hpp,
// minkowski_shrinking.hpp): OH(OS)'s sweep (horizon_sweep.hpp) from the region's centre, culling
// by the region's view volumes (Fig. 4.8: the frustum widened to every camera of the region; the
// horizon is kept over the full circle, which only hides less than the widened frustum's coverage
// would). Buildings are tested with their own, unshrunk CVPs; `cast` queues a visible one's
// shadows, shrunk as the method shrinks them.
#pragma once

#include <algorithm>
#include <chrono>
#include <optional>
#include <vector>

#include "core/elapsed.hpp"
#include "engine/delta_horizon/motion_region.hpp"
#include "engine/horizon/horizon_sweep.hpp"
#include "engine/shrinking/passive_targets.hpp"

namespace cullcheck {

// `guard_every_eye` (the conservative methods): `cast` is handed the centre's unclipped distance
// + ε, beyond which no eye of the disc clips anything; false (the published method, which knows no
// near plane) hands it the centre's alone.
// `known`, when given, marks buildings the caller already holds (RegionCullingMethod::
// cull_region_carrying): they are accepted untested and cast their shadows, and the PVS is
// returned unsorted.
// `cast_reads_spans`: false when `cast` ignores its spans argument (sweep_horizon).
// `narrow_targets`: test targets by target_span with ε = the region's radius (horizon_sweep.hpp);
// only for shadows narrowed as that proof assumes (shrink_adjustable_corrected's).
// `passive`, when given, is swept after the buildings against the same shadows (passive_targets.hpp)
// into result.passive; `known_passive` marks targets already held, which are left out of it.
template <class CastShadows>
CullResult sweep_region(const Scene& scene, const Quadtree& quadtree, OcclusionHorizon& horizon, const ViewRegion& region,
                        const CastShadows& cast, const std::vector<char>* known = nullptr,
                        PassiveTargets* passive = nullptr, const std::vector<char>* known_passive = nullptr,
                        bool guard_every_eye = true, bool cast_reads_spans = true, bool narrow_targets = false) {
  const double reach = guard_every_eye ? region.radius : 0.0;
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  ShadowQueue pending;
  std::vector<Shadow> log;
  if (passive) pending.record_into(&log);
  const bool every_box_meets = meets_every_box(ViewVolume(region.camera), quadtree.extent(), region.radius);
  sweep_horizon(
      scene, quadtree, horizon, region.camera, /*restrict_to_coverage=*/false,
      [&](const ViewVolume& volume, const Box3& box) {
        return every_box_meets || may_meet(volume, box, region.radius, region.turn);
      },
      // The near-plane guard for every eye of the disc, not the centre's alone: a CVP nearer
      // than the centre's unclipped distance + ε may lie in front of another eye's near plane,
      // and clipped geometry hides nothing (properties/region_drawn_scenes_test.cpp).
      [&](ShadowQueue& queue, std::uint32_t index, Vec3 eye, double distance, double unclipped,
          const std::vector<std::optional<ConvexSpan>>& spans) {
        cast(queue, index, eye, distance, unclipped + reach, spans);
      },
      [&](std::uint32_t b) { return known && (*known)[b] != 0; }, [](bool, std::uint32_t) { return false; }, pending,
      result, cast_reads_spans, narrow_targets ? region.radius : 0.0, /*finish_horizon=*/false);
  // A carrying query's PVS is only united into a view cell's (issue 17: sorting it cost about 3%
  // of a VbAoI graph), so it is left in sweep order.
  if (!known) std::sort(result.pvs.begin(), result.pvs.end());
  if (passive) result.passive = passive->visible(region, log, known_passive, result.stats);
  result.stats.cull_ms = ms_since(start);
  return result;
}

// Queues the shadows of a visible building's occluders shrunk beforehand (the methods that shrink
// footprints in preprocessing): each shrunk CVP with OH(OS)'s conservative rule from the centre;
// one that may reach in front of the near plane, or that holds the eye, casts none (nor one whose
// shadow is not usable_shadow).
inline void queue_shrunk_shadows(ShadowQueue& pending, const std::vector<ConvexVerticalPrism>& shrunk, Vec3 eye,
                                 double distance, double unclipped) {
  const Vec2 e = plan(eye);
  const bool may_be_clipped = distance < unclipped;
  for (const ConvexVerticalPrism& prism : shrunk) {
    const auto span = convex_span(prism.ring, e);
    if (!span || (may_be_clipped && min_boundary_distance(prism.ring, e) < unclipped)) continue;
    const double farthest = max_vertex_distance(prism.ring, e);
    const double slope = shadow_slope(ShadowRule::conservative, prism, eye, *span);
    if (usable_shadow(farthest, slope)) pending.push(farthest, span->span, slope);
  }
}

}  // namespace cullcheck
