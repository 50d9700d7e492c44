// Guarded incremental occlusion horizon, ΔH (thesis ch. 3.1.3, with the guard that Fig. 3.10
// calls for; see motion_region.hpp for the guard and why the published method needs one).
//
// Claim: from a point, 6 DoF, up to 360 degrees, the same PVS as full OH(OS) with the
// conservative shadow rule at every frame, whatever the camera path; so it is conservative
// wherever OH(OS) is. Frame-to-frame coherence is used as follows:
//  - carried over from an anchor frame: a certificate for every camera within a motion region
//    around the anchor, sorting the buildings into certainly hidden, certainly visible and
//    uncertain (the thesis's "skip what lies behind the risen parts" and "test the openings",
//    with both proven for the whole region rather than assumed from one frame to the next);
//  - each frame inside the region rebuilds H(t+1) front to back from the uncertain buildings
//    and the certainly visible ones whose shadows can reach them, with OH(OS)'s tests; the PVS
//    is the certainly visible plus the uncertain ones found visible;
//  - a camera outside the region (moved more than `delta_radius`/`delta_height`, turned more
//    than `delta_turn`, other field of view or clip planes) re-anchors the region at itself:
//    the guard fires, and the frame costs a certificate sweep on top of its own.
// Prefetch (MethodOptions::delta_prefetch, issue 17): right after re-anchoring, a second thread
// certifies the region the walk will need next (centred 1.9 ε further along the last step,
// where re-anchoring on a straight walk would put it), and sorts its swept buildings by distance
// from that region's centre. When the guard fires and that region holds the camera, the frame
// takes both instead of certifying and sorting from scratch on the critical path; otherwise it
// waits for the thread and certifies as before. The thread is started once (BackgroundTask).
// Which certificate is used depends only on the camera path, never on timing, so statistics are
// as deterministic as the PVS, which is OH(OS)'s either way. The certificate's work is counted
// in the frame that takes it (cells, buildings, horizon entries), and its wall time on the other
// core is not in cull_ms.
// Fixed vertices (issue 17): with each certificate, the swept buildings' tangent and farthest
// vertices and the edges that can be nearest are found for the whole region where they provably
// do not change in it (disc_vertices), so a frame reads a few vertices for a span and its
// distances instead of walking every ring; the values are OH(OS)'s bit for bit. A certainly
// visible building's shadow is queued with the bins raise() would round its span to, found from
// the fixed tangents without the span where that is certain (span_inner_bins, box_bins.hpp).
// horizon() materialises the horizon OH(OS) would leave (every visible building's shadows) on
// demand; the per-frame sweep only builds it where uncertain buildings need it.
// Statistics: items_skipped counts buildings decided without a test; guard_fires is 1 on
// re-anchoring.
#pragma once

#include <optional>
#include <utility>
#include <vector>

#include "core/background_task.hpp"
#include "engine/delta_horizon/motion_region.hpp"
#include "engine/horizon/horizon_sweep.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/horizon/polar_geometry.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class GuardedDeltaHorizonCulling final : public CullingMethod {
 public:
  GuardedDeltaHorizonCulling(const Scene& scene, const MethodOptions& options = {});
  ~GuardedDeltaHorizonCulling() override;
  // current_ and spare_ point into this object.
  GuardedDeltaHorizonCulling(const GuardedDeltaHorizonCulling&) = delete;
  GuardedDeltaHorizonCulling& operator=(const GuardedDeltaHorizonCulling&) = delete;
  std::string name() const override { return "delta_h_guarded"; }
  bool claims_conservative() const override { return true; }
  bool incremental() const override { return true; }
  CullResult cull(const Camera& camera) override;

  // H(t) as OH(OS) would leave it after the last query (built on demand).
  OcclusionHorizon& horizon();
  const RegionCertificate& certificate() const { return *current_; }
  // Re-anchorings answered by the prefetched certificate, since construction.
  std::uint64_t prefetch_hits() const { return prefetch_hits_; }

 private:
  const Scene& scene_;
  MethodOptions options_;
  Quadtree quadtree_;
  OcclusionHorizon horizon_, final_;
  RegionCertificate first_, second_;
  RegionCertificate* current_ = &first_;
  RegionCertificate* spare_ = &second_;  // the prefetch thread's while next_ is pending
  std::optional<MotionRegion> region_;
  std::optional<MotionRegion> next_region_;
  CullStatistics next_stats_;
  std::uint64_t prefetch_hits_ = 0;
  std::optional<Camera> last_camera_;
  std::vector<std::uint32_t> last_found_;  // scene indices of the uncertain buildings the last query found visible
  // A swept building, its distance from the eye (the order of the sweep), and where its
  // vertices fixed for the region start in `vertices_`: [p] CVP p (its box needs none: box_hidden
  // reads the box's bins, horizon_sweep.hpp).
  struct Swept {
    double distance;
    std::uint32_t building;
    std::uint32_t vertices;
    bool operator<(const Swept& o) const { return distance != o.distance ? distance < o.distance : building < o.building; }
  };
  std::vector<Swept> order_;                 // swept buildings by distance
  std::vector<DiscVertices> vertices_;       // fixed over *region_ (polar_geometry.hpp)
  std::vector<ObjectId> visible_ids_;        // the certainly visible buildings' ids, ascending
  std::vector<Swept> next_order_;            // *spare_'s, from next_region_'s centre
  std::vector<DiscVertices> next_vertices_;  // fixed over *next_region_
  std::vector<ObjectId> next_visible_ids_;
  // A query's scratch, kept for its capacity.
  ShadowQueue pending_;
  std::vector<std::optional<ConvexSpan>> spans_;
  std::vector<ObjectId> found_ids_;
  // Certifies next_region_ into *spare_ and sorts next_order_ (declared last: joined first).
  BackgroundTask prefetch_;
};

}  // namespace cullcheck
