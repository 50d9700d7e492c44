// The ray oracle's sampling plan: which rays to cast, in a fixed order (design: "Oracle").
//
// Order: candidate objects (buildings, then mesh objects) in scene order, each with its surface
// samples in order (surface_samples.hpp) and its silhouette-grazing rays; then
// the stratified grid over the view volume row by row, jittered by a SplitMix64 stream seeded
// with options.seed. The plan is produced unit by unit (an object, or a run of cells), so that a
// query over millions of rays needs memory for the units in flight only, on any thread. Everything here is in the oracle's own view transform
// (view_transform.hpp), nothing in core's.
//
// Candidates: the objects whose box may meet the view volume by ViewTransform::may_meet, a
// conservative test in clip space (a box is dropped only when all of it lies outside one plane).
//
// Silhouette-grazing rays (the slivers beside an occluder's outline, where rounding bugs live):
// a building's vertical edge is on its silhouette when the two walls meeting there do not both
// face the eye or both face away, a roof edge when its wall and the roof do not (an edge seen
// exactly edge-on counts). A mesh object's edge is on its silhouette when it bounds one triangle
// only, or its triangles do not all lie with the eye on the same side of their planes (or one is
// seen edge-on); vertices equal in position are one vertex (mesh.hpp). Along each silhouette edge, at max(edge_samples, length / spacing)
// intervals (ends included), two rays pass the edge point p on either side, aimed at p moved by
// the graze distance (sampling.hpp) along the direction perpendicular to both the ray and the
// edge, and run on to the far plane: one just misses the occluder and witnesses what lies behind
// it, the other just hits it.
//
// Where rays start: a perspective or omnidirectional camera's rays start at the eye. An
// orthographic camera's rays are parallel to its view direction: the ray aimed at a sample point
// p starts on the near plane directly in front of p (p minus (depth of p - near) along the view
// direction), so every ray has its own origin; samples before the near plane or outside the
// ortho_width x ortho_height rectangle get no ray (nothing there is in the view volume).
#pragma once

#include <cstdint>
#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/mesh.hpp"
#include "oracle/ray_oracle.hpp"
#include "oracle/sample_cache.hpp"
#include "oracle/sampling.hpp"
#include "oracle/splitmix64.hpp"
#include "oracle/surface_samples.hpp"
#include "oracle/view_transform.hpp"

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
  const ViewTransform& transform() const { return transform_; }
  // Perspective and omnidirectional cameras: false when no point along the unit direction `d`
  // from the eye lies in the view volume; otherwise the extent: from the near plane (geometry
  // before it is clipped, so it hides nothing) to far. Omnidirectional: [0, far].
  // Orthographic cameras: every ray has direction forward() and t in [0, far - near] from its
  // origin on the near plane; `d` must be forward() (anything else gives false).
  bool extent(Vec3 d, double& t_near, double& t_far) const;
  // The ray toward sample point `p`, or false when it cannot meet p inside the view volume.
  // It ends just beyond p, or with `to_far`, at the far plane. Inline: once per planned ray.
  bool ray_toward(Vec3 p, PlannedRay& out, bool to_far = false) const;
  // ray_toward(p, ray, to_far) for each of `points` in order, appending the rays it gives (copies
  // of `prototype` with the ray's fields set) to `out`. The same rays bit for bit, computed a run
  // of points at a time so that the square roots and divisions of neighbouring points overlap.
  // With `within`, a box holding every point, tests that box settles for all of them are skipped.
  void rays_toward(const std::vector<Vec3>& points, const PlannedRay& prototype, std::vector<PlannedRay>& out,
                   const Box3* within = nullptr, bool to_far = false) const;
  // The same rays as Embree is handed them, to_float(origin - mesh_origin, ...), appended to
  // `cast`, with the index of each one's point appended to `aim`.
  void cast_rays_toward(const std::vector<Vec3>& points, Vec3 mesh_origin, std::vector<RayLog::Ray>& cast,
                        std::vector<std::uint32_t>& aim, const Box3* within = nullptr, bool to_far = false) const;
  Vec3 forward() const { return forward_; }
  // What holds for the ray toward every point of `box` (perspective cameras), by a margin far
  // above the rounding of ray_toward's arithmetic, so that skipping the test changes no bit:
  // every direction passes the four side planes; every surface ray ends at its point (the
  // distance beyond it is shorter than the extent to the far plane).
  struct BoxSettles {
    bool sides = false, before_far = false;
  };
  BoxSettles settles(const Box3& box) const;

 private:
  bool ortho_ray_toward(Vec3 p, PlannedRay& out, bool to_far) const;
  // ray_toward over a run of points: emit(i, origin, direction, t_near, t_far) for each point i
  // that has a ray (rays_toward and cast_rays_toward write what they keep of it).
  template <class Emit>
  void each_ray_toward(const std::vector<Vec3>& points, const Box3* within, bool to_far, Emit&& emit) const;

  ViewTransform transform_;
  Vec3 forward_;
  double near_, far_;
  bool orthographic_;
};

// What planning some units found; each thread keeps its own and the caller adds them up.
struct PlanTally {
  std::size_t candidates = 0, capped = 0;
  std::uint64_t grazing = 0;
};

// One unit's rays as Embree is handed them, with what rebuilds each one's PlannedRay bit for bit
// (RayPlan::planned): the index of the point it aims at, or of its stratified cell. The casting
// loop then moves 36 bytes a ray instead of a double-precision ray and its float copy; the few
// rays whose hit may witness something are rebuilt.
struct UnitRays {
  std::vector<RayLog::Ray> cast;     // to_float of each planned ray, in plan order
  std::vector<std::uint32_t> aim;    // per ray: its surface sample, grazing aim, or cell - first_cell
  std::uint32_t object = kNoObjectIndex;       // the unit's object, or kNoObjectIndex for a run of cells
  const std::vector<Vec3>* surface = nullptr;  // the object's surface samples (kept, or the caller's scratch)
  std::vector<Vec3> grazing;                   // the points its grazing rays aim at
  std::size_t surface_rays = 0;                // rays [0, surface_rays) are surface-sample rays
  std::size_t first_cell = 0;

  std::size_t size() const { return cast.size(); }
  void clear() { cast.clear(), aim.clear(), grazing.clear(), object = kNoObjectIndex, surface = nullptr, surface_rays = 0, first_cell = 0; }
};

// The plan as independent units, so that any unit can be planned on any thread: the objects
// 0..objects()-1, then the stratified cells 0..cells()-1 row-major. Concatenated in that order
// they are the plan's rays in plan order.
class RayPlan {
 public:
  // `mesh` is triangulate(scene): the plan samples the oracle's own roofs. With `cache`, surface
  // samples are taken from it (and kept there) instead of computed for this plan alone.
  RayPlan(const Scene& scene, const TriangleMesh& mesh, const Camera& camera, const SamplingOptions& options,
          SampleCache* cache = nullptr);
  std::size_t objects() const { return scene_.object_count(); }
  std::size_t cells() const { return std::size_t(columns_) * std::size_t(rows_); }
  // Object `index`'s rays into `out` (replacing what it held): its surface samples, then its
  // grazing rays (none when its box cannot meet the view volume). Returns how many surface-sample
  // rays lead. `samples` is scratch memory, one per thread, which `out` may point into until the
  // next call.
  std::size_t object_rays(std::uint32_t index, UnitRays& out, PlanTally& tally, SurfaceSamples& samples) const;
  // The rays of stratified cells [first, last) into `out`. Cell c's jitter is draws 2c and 2c + 1
  // of the SplitMix64 stream seeded with options.seed, wherever the run starts.
  void cell_rays(std::size_t first, std::size_t last, UnitRays& out) const;
  // Ray k of a unit in double precision, as planned: cast[k] is to_float of it.
  PlannedRay planned(const UnitRays& unit, std::size_t k) const;
  // The same two, appending every ray planned in double precision (for tests and tools).
  std::size_t object_rays(std::uint32_t index, std::vector<PlannedRay>& out, PlanTally& tally, SurfaceSamples& samples) const;
  void cell_rays(std::size_t first, std::size_t last, std::vector<PlannedRay>& out) const;
  const ViewCone& cone() const { return cone_; }

 private:
  // The points the grazing rays aim at, in plan order, appended to `aims`.
  void plan_grazing(std::uint32_t index, std::vector<Vec3>& aims) const;
  void plan_mesh_grazing(std::uint32_t index, std::vector<Vec3>& aims) const;
  void graze_along(Vec3 p0, Vec3 p1, std::vector<Vec3>& aims) const;
  bool plan_cell(std::size_t cell, SplitMix64& rng, PlannedRay& out) const;

  const Scene& scene_;
  const TriangleMesh& mesh_;
  const Camera& camera_;
  const SamplingOptions& options_;
  ViewCone cone_;
  std::optional<SampleCache::AtDensity> cache_;
  int columns_ = 0, rows_ = 0;
};

// A ray ends this far beyond its sample point (relative, plus absolute metres): far enough that
// float rounding cannot make it stop short of the sample's face, near enough that a ray grazing
// past the sample's edge does not go on to witness what lies behind it.
inline constexpr double kBeyondRelative = 1e-5;
inline constexpr double kBeyondAbsolute = 1e-5;

inline bool ViewCone::extent(Vec3 d, double& t_near, double& t_far) const {
  if (orthographic_) {
    if (!(d == forward_)) return false;
    t_near = 0.0, t_far = far_ - near_;
    return true;
  }
  return transform_.extent(d, t_near, t_far);
}

[[gnu::always_inline]] inline bool ViewCone::ray_toward(Vec3 p, PlannedRay& out, bool to_far) const {
  if (orthographic_) return ortho_ray_toward(p, out, to_far);
  const Vec3 to = p - transform_.eye();
  const double distance = length(to);
  if (!(distance > 0.0)) return false;
  out.origin = transform_.eye();
  out.direction = to * (1.0 / distance);
  if (!transform_.extent(out.direction, out.t_near, out.t_far)) return false;
  if (!to_far) out.t_far = std::min(out.t_far, distance * (1.0 + kBeyondRelative) + kBeyondAbsolute);
  out.target = p;
  return out.t_far > out.t_near;
}

}  // namespace cullcheck::oracle
