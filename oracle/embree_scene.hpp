// The oracle's Embree scene: the triangulated scene (mesh.hpp) in one Embree scene, and the two
// ways the oracle asks it for a first hit. Internal to the oracle: included by its .cpp files
// only (it includes Embree; the public headers do not).
//
// Built once by a single-threaded Embree device, so the BVH, and with it the choice between
// exactly equal hits, is the same on every run. rtcIntersect1 is thread-safe: rays are cast
// from the oracle's own threads.
#pragma once

#include <embree3/rtcore.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/scene.hpp"
#include "oracle/mesh.hpp"
#include "oracle/ray_oracle.hpp"

namespace cullcheck::oracle {

struct EmbreeHit {
  float t = 0.0f;
  std::uint32_t triangle = RTC_INVALID_GEOMETRY_ID;
  bool hit() const { return triangle != RTC_INVALID_GEOMETRY_ID; }
};

// The next float above `x`, as std::nextafter(x, +inf) gives it; positive finite values (every
// planned ray's t_far) take the integer step inline, the rest go to libm. Inline: once per ray.
inline float next_float_up(float x) {
  if (x > 0.0f && x < std::numeric_limits<float>::max()) return std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) + 1u);
  return std::nextafter(x, std::numeric_limits<float>::infinity());
}

// A ray as Embree takes it: `origin_local` relative to the mesh's origin, rounded to floats;
// t_far rounded up by one ulp (rounding it down could stop a ray just short of its sample's face).
// Inline: the oracle converts every ray it casts.
inline RayLog::Ray to_float(Vec3 o, Vec3 d, double t_near, double t_far) {
  return {{float(o.x), float(o.y), float(o.z)}, {float(d.x), float(d.y), float(d.z)}, float(t_near), next_float_up(float(t_far))};
}
RTCRayHit embree_ray(const RayLog::Ray& r);

class EmbreeScene {
 public:
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  const TriangleMesh& mesh() const { return mesh_; }
  RTCScene handle() const { return scene_; }

  // The first hit of `r` in [t_near, t_far] among all triangles.
  EmbreeHit cast(const RayLog::Ray& r) const;
  // The first hits of rays[0..n), n at most kPacket, cast as one packet (rtcIntersect16, 8 or 4,
  // the widest this Embree supports; one by one if none). Rays from one eye toward nearby
  // samples share most of their traversal, which a packet walks once.
  // With `allowed_objects`, the first hits among those objects, as cast_among finds them.
  static constexpr std::size_t kPacket = 16;
  void cast_packet(const RayLog::Ray* rays, std::size_t n, EmbreeHit* hits,
                   const std::vector<std::uint8_t>* allowed_objects = nullptr) const;
  int packet_width() const { return packet_width_; }
  // The first hit among the triangles of the objects whose flag is set (indexed by object index,
  // mesh.hpp), found exactly: Embree's context filter rejects every other hit during traversal,
  // so the result is the first hit of the same ray in the scene made of those objects alone.
  EmbreeHit cast_among(const RayLog::Ray& r, const std::vector<std::uint8_t>& allowed_objects) const;

  // The hit recomputed in double precision on the hit triangle's plane, so a view-volume test
  // is not blurred by Embree's float t (falls back to it for rays grazing the plane).
  double exact_t(Vec3 origin, Vec3 direction, const EmbreeHit& hit) const;

 private:
  TriangleMesh mesh_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  int packet_width_ = 1;
};

}  // namespace cullcheck::oracle
