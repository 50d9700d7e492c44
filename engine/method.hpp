// The one interface every culling method implements (conventions: "a thin, plain API").
//
// A method is built once for a scene (its preprocessing: quadtree, occluder lists, ...) and then
// answers queries: a camera in, a potentially visible set (PVS: sorted object ids) and
// statistics out. The CLI, the properties and the reports all go through this interface, and so
// does an outside culling system under test (subjects/: a program over the subject protocol, or
// its recorded per-frame visible sets): one more kind of method, not a parallel code path.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "engine/online_image_space/online_options.hpp"

namespace cullcheck {

class Quadtree;

struct CullStatistics {
  std::uint64_t cells_tested = 0;       // quadtree cells tested against frustum / horizon
  std::uint64_t buildings_tested = 0;   // buildings tested individually
  std::uint64_t horizon_nodes = 0;      // horizon entries (bins and blocks) read or written
  std::uint64_t occluders_applied = 0;  // CVP shadows merged into the horizon
  std::uint64_t items_skipped = 0;      // cells and buildings skipped untested (ΔH: known hidden)
  std::uint64_t guard_fires = 0;        // ΔH: 1 when this frame fell back to a full recompute
  std::uint64_t bound_tests = 0;        // frustum methods in camera space: point, sphere and box tests made
  // Filled by reports, not by the method, for methods that sweep a quadtree
  // (CullingMethod::swept_quadtree): the tests an exact top-down traversal of that quadtree needs
  // for this PVS (engine/spatial/traversal_bound.hpp); 0 for every other method.
  std::uint64_t exact_traversal_tests = 0;
  double cull_ms = 0.0;                 // wall time of this query (an outside subject's own figure when it sends one)
  double protocol_ms = 0.0;             // outside subjects: time in the protocol (serialising, pipes, parsing)
  // Work done for this query ahead of it on another thread (the guarded ΔH's prefetched
  // certificate, counted in the frame that takes it or throws it away): its wall time there, which
  // is not in cull_ms. cull_ms + background_ms is the query's work on both cores.
  double background_ms = 0.0;
};

// Adds one query's counts (not its times) to a total: a run's frames, a view cell's samples.
inline void add_counts(CullStatistics& totals, const CullStatistics& frame) {
  totals.cells_tested += frame.cells_tested;
  totals.buildings_tested += frame.buildings_tested;
  totals.horizon_nodes += frame.horizon_nodes;
  totals.occluders_applied += frame.occluders_applied;
  totals.items_skipped += frame.items_skipped;
  totals.guard_fires += frame.guard_fires;
  totals.bound_tests += frame.bound_tests;
  totals.exact_traversal_tests += frame.exact_traversal_tests;
}

struct CullResult {
  std::vector<ObjectId> pvs;  // sorted ascending, no duplicates
  CullStatistics stats;
  // Region methods with passive targets set (RegionCullingMethod::set_passive_targets): the ids
  // of the targets not hidden, sorted. Their tests are counted in `stats` too.
  std::vector<ObjectId> passive;
};

class CullingMethod {
 public:
  virtual ~CullingMethod() = default;
  // Stable name used in reports and on the command line, e.g. "oh_os_conservative".
  virtual std::string name() const = 0;
  // Whether the method claims oracle-witnessed ⊆ PVS (the property and CI gate enforce it).
  virtual bool claims_conservative() const = 0;
  // Whether that claim covers this camera. Methods whose claim depends on the camera (OH(IS):
  // level cameras only) override it; the CI gate counts a frame's violations only when it is true.
  virtual bool claims_conservative_for(const Camera& /*camera*/) const { return claims_conservative(); }
  // True when a result depends on earlier queries (ΔH carries its horizon from frame to frame):
  // such a method's failure replays only along the path that led to it.
  virtual bool incremental() const { return false; }
  // Approximate methods that accept misdrawn pixels (oracle/pixel_oracle.hpp) give their budget
  // per frame; conservative ones have none and must show 0.
  virtual std::optional<std::uint64_t> pixel_error_budget() const { return std::nullopt; }
  // Called before cull() with the frame's index along the path and its time in seconds, for
  // methods that are told (outside subjects); built-in methods ignore it.
  virtual void set_frame(std::size_t /*frame*/, double /*time_seconds*/) {}
  // Dynamic scenes (a path's scene timeline, core/scene_timeline.hpp): from the next query on,
  // the objects of `present` are the scene; `appeared` and `vanished` say what changed. A method
  // that follows changes in place returns true (on-line image-space culling: section 6's kd-tree
  // updates); the default returns false and the caller builds the method anew on `present`,
  // which must then outlive it.
  virtual bool update_scene(const Scene& /*present*/, const std::vector<ObjectId>& /*appeared*/,
                            const std::vector<ObjectId>& /*vanished*/) {
    return false;
  }
  // Why this method cannot answer for `camera` (empty when it can). Methods built on an
  // occlusion horizon work from one eye point, so the default refuses orthographic cameras;
  // frustum culling and outside subjects take every camera. A caller skips such a frame and
  // says so (reports count it) rather than asking.
  virtual std::string unsupported_camera(const Camera& camera) const;
  virtual CullResult cull(const Camera& camera) = 0;
  // The quadtree a method sweeps front to back, testing every non-empty child of each cell it
  // enters and every building of each leaf it enters (OH(OS)); null for every other method.
  // Reports hold its cells_tested + buildings_tested against the tests an exact traversal of the
  // same quadtree needs for the same PVS.
  virtual const Quadtree* swept_quadtree() const { return nullptr; }
};

struct MethodOptions {
  std::uint32_t horizon_bins = 4096;  // azimuth resolution of the occlusion horizon over 2*pi
  std::uint32_t quadtree_leaf_size = 8;  // max buildings per quadtree leaf
  // Guarded ΔH: the motion one carried-over horizon stays valid for (engine/delta_horizon/).
  // Plan distance from the anchor eye, metres (ε). Small, so that few buildings are uncertain:
  // with the prefetch a walk re-anchors every few frames off the critical path (issue 17: on the
  // 160,000-building walk 0.1 m gives the frame 13x OH(OS)'s speed at the median and 6x at p95,
  // 0.5 m 6x and 5x; the second thread's work grows the other way, see README).
  double delta_radius = 0.1;
  double delta_height = 0.5;  // vertical distance from the anchor eye, metres
  double delta_turn = 0.05;   // |Δyaw| + |Δpitch| + |Δroll| from the anchor camera, radians
  // Certify the next motion region ahead of the walk on a second thread while frames are
  // answered from the current one; the same PVS either way (delta_horizon/guarded_delta_horizon.hpp).
  bool delta_prefetch = true;
  // On-line image-space culling (engine/online_image_space/): Δ, s, ρ, D, V, R, ...
  OnlineCullingOptions online;
};

// A from-region query (thesis ch. 4): every camera whose eye lies within `radius` of
// camera.position in plan, at the same height, with camera's fields of view and clip planes,
// turned from camera by at most `turn` (|Δyaw| + |Δpitch| + |Δroll|, radians; Fig. 4.8's
// widened frustum). A from-region PVS holds every building visible from any of them.
struct ViewRegion {
  Camera camera;
  double radius = 0.0;
  double turn = 0.0;
};

class RegionCullingMethod {
 public:
  virtual ~RegionCullingMethod() = default;
  virtual std::string name() const = 0;
  // Whether the method claims oracle-witnessed ⊆ PVS for every camera of the region.
  virtual bool claims_conservative() const = 0;
  virtual CullResult cull_region(const ViewRegion& region) = 0;
  // A view cell's PVS is the union of its samples' region PVSs (engine/shrinking/view_cell.hpp).
  // `known[i]` (scene building index i) marks a building already in that union: a sweep-based
  // method accepts it without its horizon tests and casts its shadows, which leaves the union
  // unchanged (horizon_sweep.hpp) and saves the tests. The default ignores `known`.
  // `known_passive[i]` marks passive target i as held: it is left out of the sweep (it casts no
  // shadow) and of CullResult::passive. CullResult::pvs may come unsorted (only its union counts).
  virtual CullResult cull_region_carrying(const ViewRegion& region, const std::vector<char>& /*known*/,
                                          const std::vector<char>* /*known_passive*/ = nullptr) {
    return cull_region(region);
  }
  // Whether cull_region_carrying uses `known` (reports say where carrying saves nothing).
  virtual bool carries_known() const { return false; }
  // Passive targets (engine/shrinking/passive_targets.hpp; the VbAoI graph's nodes): prisms
  // tested like buildings that hide nothing. Once set (ids must be their indices), every query
  // also fills CullResult::passive. The default throws std::invalid_argument naming the method;
  // supports_passive_targets says beforehand.
  virtual bool supports_passive_targets() const { return false; }
  virtual void set_passive_targets(const Scene& targets);
};

// Names accepted by make_method, in report order.
std::vector<std::string> method_names();
// Why the named method (point or region) cannot run on `scene` (empty when it can): every method
// but frustum culling models objects as convex vertical prisms, so it needs a 2.5D scene
// (Scene::prisms_only). Reports list the methods skipped and this reason.
std::string method_unavailable_reason(std::string_view name, const Scene& scene);
// Throws std::invalid_argument naming the method when it is unknown or unavailable on `scene`.
std::unique_ptr<CullingMethod> make_method(std::string_view name, const Scene& scene, const MethodOptions& options = {});
// The same for from-region methods (engine/shrinking/).
std::vector<std::string> region_method_names();
std::unique_ptr<RegionCullingMethod> make_region_method(std::string_view name, const Scene& scene,
                                                        const MethodOptions& options = {});

}  // namespace cullcheck
