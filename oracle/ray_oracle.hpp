// Embree ray-sampling oracle (design: "Oracle", first bullet): a lower bound of the true
// visible set in full 3D, for any camera.
//
// Rays are cast toward sample points on every candidate object's surface (buildings and mesh
// objects whose boxes may meet the view volume: vertices, edge points, a grid on each face, and
// edge/corner points inset into the faces), just beside every candidate building's silhouette
// edges (grazing rays, ray_plan.hpp) and over the whole view volume (a seeded jittered grid). From the eye for perspective and omnidirectional cameras; for an orthographic camera
// the rays are parallel to the view direction and each starts on the near plane in front of its
// target (ray_plan.hpp). An object is WITNESSED VISIBLE when some ray's first hit lies on it and
// inside the view volume (the oracle's own ViewTransform::contains, view_transform.hpp, tested
// on the hit point recomputed in double precision on the hit triangle's plane). Rays start at the near plane (geometry nearer than it
// is clipped, so it hides nothing) and end at the far plane, or just beyond their sample point.
//
// Casting (ray_oracle.cpp): the plan's units (an object's rays, or a run of stratified cells) are
// cast on options.threads threads, 16 neighbouring rays to a packet (EmbreeScene::cast_packet),
// and merged in plan order, so the answer does not depend on the thread count; an object's
// surface-sample rays stop once they have found its kept witnesses (SamplingOptions::
// stop_when_witnessed). ray_oracle_units_test holds both to the plan cast one ray at a time.
//
// Exactness: every witness is one concrete ray, kept so it can be replayed; it is exact up to
// Embree's single-precision intersection (about 1e-7 of the scene's extent), which matters only
// for rays that graze an edge: before a witness makes a violation it is re-cast in double
// precision (witness_recheck.hpp, Oracle::recheck_witness). Densifying the samples converges on
// the true set from below.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/mesh.hpp"
#include "oracle/sampling.hpp"

namespace cullcheck::oracle {

class EmbreeScene;  // embree_scene.hpp, internal to the oracle

enum class RaySource : std::uint8_t {
  surface_sample,  // aimed at a sample point on a candidate object
  stratified,      // one jittered ray per cell of the image-plane (or sphere) grid
  pixel,           // a primary ray through a pixel centre (pixel_oracle.hpp)
  grazing,         // just beside a candidate building's silhouette edge (ray_plan.hpp)
};

// One ray that proves an object visible; enough to replay and print it.
struct WitnessRay {
  Vec3 origin;     // where the ray starts, scene-local metres: the eye, or for an orthographic
                   // camera a point on its near plane (sampling) or its eye plane (pixels)
  Vec3 direction;  // unit length
  double t_near = 0.0, t_far = 0.0;  // the ray's extent, metres along `direction`
  double t_hit = 0.0;                // first hit
  Vec3 hit_point;                    // origin + t_hit * direction, inside the view volume
  Vec3 target;                       // sample point aimed at, or origin + t_far * direction
  std::uint32_t triangle = 0;        // Embree primID in the oracle's mesh
  ObjectId aimed_at = 0;             // surface samples and grazing rays: the object aimed at
  RaySource source = RaySource::surface_sample;

  friend bool operator==(const WitnessRay&, const WitnessRay&) = default;
};
std::string describe(const WitnessRay& ray);  // one line, for failure messages
void to_json(nlohmann::json& j, const WitnessRay& ray);

inline constexpr std::size_t kFurtherWitnesses = 3;

struct OracleResult {
  std::vector<ObjectId> witnessed;          // sorted ids
  std::map<ObjectId, WitnessRay> witnesses;  // the first witnessing ray of each, in ray order
  // The next kFurtherWitnesses witnessing rays of each object, in ray order: tried in turn when
  // the first does not stand the double-precision re-check (Oracle::confirm_witness).
  std::map<ObjectId, std::vector<WitnessRay>> further_witnesses;
  std::uint64_t rays_cast = 0;
  std::uint64_t grazing_rays = 0;           // of rays_cast: silhouette-grazing rays
  // Surface-sample rays not cast because their object already had every witness kept
  // (SamplingOptions::stop_when_witnessed); not in rays_cast.
  std::uint64_t rays_skipped = 0;
  std::size_t candidates = 0;               // objects whose box may meet the view volume
  std::size_t capped_objects = 0;           // candidates whose samples hit the per-object cap
  double elapsed_seconds = 0.0;             // wall time of the whole query
  SamplingOptions density;                  // the density used (reports print it)

  double rays_per_second() const { return elapsed_seconds > 0 ? double(rays_cast) / elapsed_seconds : 0.0; }
};

// Per triangle (primID in the oracle's mesh): the first ray whose first hit lies on it inside the
// view volume. Asked for by properties that hold a method to finer than objects (slice-wise).
using TriangleWitnesses = std::map<std::uint32_t, WitnessRay>;

// The rays of one query, exactly as handed to Embree, for replaying them bare.
struct RayLog {
  struct Ray {
    float org[3], dir[3];
    float t_near, t_far;
  };
  std::vector<Ray> rays;
};

class RayOracle {
 public:
  // Triangulates the scene and builds one Embree scene (robust, high build quality, built by a
  // single-threaded device so the BVH, and hence tie-breaking between equal hits, is the same on
  // every run). The Scene must outlive the oracle.
  explicit RayOracle(const Scene& scene);
  ~RayOracle();
  RayOracle(const RayOracle&) = delete;
  RayOracle& operator=(const RayOracle&) = delete;

  // Throws InputError if the camera or options are unusable. If `log` is given, every ray cast
  // is appended to it; if `triangles` is, every witnessed triangle is added to it (a triangle
  // already there keeps its ray).
  OracleResult witness(const Camera& camera, const SamplingOptions& options = {}, RayLog* log = nullptr,
                       TriangleWitnesses* triangles = nullptr) const;

  // The object hit first by `ray` (re-cast through Embree), if any, and whether that hit lies
  // in the view volume of `camera`. Used to check witnesses and to replay a failure.
  struct Replay {
    std::optional<ObjectId> hit;
    bool in_view_volume = false;
    double t_hit = 0.0;
  };
  Replay replay(const WitnessRay& ray, const Camera& camera) const;

  // Re-casts exactly the logged rays in a bare loop (no sample generation, no bookkeeping),
  // repeating the log until at least `min_seconds` have passed, on `threads` threads: one by one
  // through rtcIntersect1, or with `packets` in packets of consecutive rays as witness() casts
  // them. Gives the Embree-only rate to print next to OracleResult::rays_per_second().
  double bare_embree_rays_per_second(const RayLog& log, int threads = 1, double min_seconds = 0.2, bool packets = false) const;

  // Whether the segment from `a` to `b` is clear of every object (one Embree occlusion ray over
  // exactly that segment; exact up to single precision, so only a segment grazing a wall or roof
  // edge is in doubt). The VbAoI channel-grouping property's line of sight between avatar eyes.
  bool line_of_sight(Vec3 a, Vec3 b) const;
  // Every pair (i, j), i < j, of `eyes` with a clear line of sight, sorted; on `threads` threads.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> mutually_visible(const std::vector<Vec3>& eyes,
                                                                        int threads = 1) const;

  const TriangleMesh& mesh() const;
  const Scene& scene() const;
  // The Embree scene, for the oracle's other ray casters (PixelOracle shares it).
  const EmbreeScene& embree() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cullcheck::oracle
