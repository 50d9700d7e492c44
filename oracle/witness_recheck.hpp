// The double-precision re-check of a witness ray (design: "nothing is silently wrong").
//
// The ray oracle and the pixel oracle cast in single precision (Embree, on coordinates rebased
// to the mesh's origin), so a ray that passes a silhouette edge by less than float rounding may
// be reported hitting an object it misses, or missing an occluder in front of it. Before such a
// witness makes a violation, the re-check casts the same ray (its double origin, direction and
// extent) against the oracle's triangles in double precision, brute force over the objects whose
// boxes the ray meets, with a watertight ray/triangle test (Woop, Benthin and Wald 2013: no ray
// slips between two triangles sharing an edge). The witness STANDS when the first hit belongs to
// the witnessed object and lies in the view volume (the oracle's ViewTransform); it is DROPPED
// when a nearer triangle of another object blocks it, when the ray reaches nothing, or when the
// hit lies outside the view volume. A tie at the same t with the witnessed object is not "nearer".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "oracle/mesh.hpp"
#include "oracle/ray_oracle.hpp"

namespace cullcheck::oracle {

enum class RecheckVerdict : std::uint8_t {
  stands,        // first hit on the witnessed object, inside the view volume
  blocked,       // a nearer triangle of another object
  reaches_nothing,
  outside_view,  // the first hit is on the object but outside the view volume
};
const char* name(RecheckVerdict v);

struct WitnessRecheck {
  RecheckVerdict verdict = RecheckVerdict::stands;
  std::optional<ObjectId> first_hit;  // the object hit first in double precision
  double t_hit = 0.0;
  bool stands() const { return verdict == RecheckVerdict::stands; }
  std::string describe() const;  // one line, e.g. "blocked by object 7 at t = 12.5"
};

// Witnesses re-checked and dropped (reports and the gate print them).
struct WitnessRecheckCounts {
  std::uint64_t checked = 0;
  std::uint64_t dropped = 0;
  WitnessRecheckCounts& operator+=(const WitnessRecheckCounts& o) {
    checked += o.checked, dropped += o.dropped;
    return *this;
  }
  friend bool operator==(const WitnessRecheckCounts&, const WitnessRecheckCounts&) = default;
};

// The oracle's triangles in double precision, with a box per object for the bound filter.
class DoublePrecisionScene {
 public:
  explicit DoublePrecisionScene(const TriangleMesh& mesh);  // the mesh must outlive this object

  struct Hit {
    double t = 0.0;
    std::uint32_t object_index = 0;  // mesh.hpp: buildings, then meshes
    std::uint32_t triangle = 0;
  };
  // The first hit in [t_near, t_far] of the ray origin + t * direction; among hits at exactly
  // the same t, the one on `prefer` (an object index) if any.
  std::optional<Hit> first_hit(Vec3 origin, Vec3 direction, double t_near, double t_far,
                               std::uint32_t prefer = UINT32_MAX) const;

  // Re-checks `ray` as a witness of `object` (an id) for `camera`.
  WitnessRecheck recheck(const WitnessRay& ray, ObjectId object, const Camera& camera) const;

  const TriangleMesh& mesh() const { return mesh_; }

 private:
  const TriangleMesh& mesh_;
  std::vector<Box3> boxes_;                // per object index
  std::vector<std::uint32_t> first_, end_;  // per object index: its triangles [first, end)
};

}  // namespace cullcheck::oracle
