// Pixel truth for approximate methods (design: "Oracle", "Pixel truth"): Embree primary rays
// through the pixel centres at the camera's resolution give the id buffer of the full scene and
// the id buffer of the PVS alone; the pixels where they differ are MISDRAWN: a renderer that
// draws only the PVS shows something else there (an object behind, or the background).
//
// Pixels. Pixel (i, j): i is the column counted from the left, j the row counted from the top;
// ids are stored row-major, ids[j * width + i]; the resolution is resolution_of(camera). With
// u = 2 (i + 0.5) / width - 1 and v = 1 - 2 (j + 0.5) / height (both in (-1, 1), u to the right,
// v up) and the oracle's own view transform (view_transform.hpp: forward, right, up after pitch
// and roll, derived from the camera's raw fields), the ray of pixel (i, j):
//  - perspective: from the eye through forward + right * u tan(hfov / 2) + up * v tan(vfov / 2)
//    (the image plane at distance 1 along forward: ViewTransform::direction_through(u, v)),
//    normalised; t from near / along to
//    far / along, where along = the direction's component along forward, so the ray covers the
//    depths near..far along forward exactly;
//  - orthographic: from eye + right * u ortho_width / 2 + up * v ortho_height / 2 along forward,
//    t from near to far;
//  - omnidirectional: an equirectangular panorama, direction (cos e cos a, cos e sin a, sin e)
//    with azimuth a = 2 pi (i + 0.5) / width (from +x counter-clockwise) and elevation
//    e = pi / 2 - pi (j + 0.5) / height; t from 0 to far (the view volume is the ball of radius
//    far; near does not apply).
// A pixel shows the object of the ray's first hit in that extent: hits before the near plane
// are clipped (they hide nothing), and a pixel with no hit shows the background, kNoObject.
//
// Exactness: each pixel is one Embree ray (single precision, robust mode; the full render casts
// a row's pixels in packets of 16 neighbours, EmbreeScene::cast_packet), so only a pixel
// centre within about 1e-7 of the scene's extent of a silhouette edge is in doubt. The PVS-only
// buffer is exact as a first hit among the PVS's objects: Embree's context filter rejects the
// other objects' hits during traversal (embree_scene.hpp), the same as tracing a scene made of
// the PVS alone. Results do not depend on the thread count: every pixel is written by one ray.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/ray_oracle.hpp"

namespace cullcheck::oracle {

inline constexpr ObjectId kNoObject = std::numeric_limits<ObjectId>::max();  // background

// An id buffer: the object each pixel shows, row-major from the top-left pixel.
struct IdImage {
  int width = 0, height = 0;
  std::vector<ObjectId> ids;  // width * height entries, kNoObject for background

  ObjectId at(int i, int j) const { return ids[std::size_t(j) * std::size_t(width) + std::size_t(i)]; }
  friend bool operator==(const IdImage&, const IdImage&) = default;
};

// The full scene's id buffer against the PVS's.
struct PixelComparison {
  Resolution resolution;
  // Pixels whose full-scene object is not in the PVS (those are exactly the pixels where the
  // PVS-only buffer differs: see PixelOracle::compare).
  std::uint64_t misdrawn_pixels = 0;
  std::uint64_t largest_blob = 0;  // pixels in the largest 4-connected component of misdrawn pixels
  std::uint64_t blobs = 0;         // number of such components
  std::map<ObjectId, std::uint64_t> misdrawn_by_object;  // by the object the pixel truly shows (culled)
  // One replayable witness per culled-but-seen object: the ray of its first pixel in row-major
  // order whose hit point (recomputed in double precision) lies in the view volume
  // (RayOracle::replay gives that object back). Source RaySource::pixel.
  std::map<ObjectId, WitnessRay> witnesses;
  std::vector<std::uint8_t> misdrawn_mask;  // 1 where misdrawn, row-major like IdImage::ids
  IdImage drawn;  // the PVS-only buffer: what a renderer of the PVS alone shows
};

class PixelOracle {
 public:
  // Shares the ray oracle's Embree scene; `rays` must outlive this object.
  explicit PixelOracle(const RayOracle& rays);

  // The id buffer at the camera's resolution: of the full scene, or with `only`, of the objects
  // whose ids it lists (any order; ids not in the scene are ignored). Throws InputError if the
  // camera is unusable. `threads` casts rows in parallel; the image does not depend on it.
  IdImage render(const Camera& camera, const std::vector<ObjectId>* only = nullptr, int threads = 2) const;

  // Full render, then the comparison with `pvs` (ids in any order).
  PixelComparison compare(const Camera& camera, const std::vector<ObjectId>& pvs, int threads = 2) const;
  // The comparison with a full render done once (render(camera)) and reused for many PVSs.
  // Throws std::invalid_argument if `full` does not have the camera's resolution.
  PixelComparison compare(const IdImage& full, const Camera& camera, const std::vector<ObjectId>& pvs,
                          int threads = 2) const;

  const RayOracle& rays() const { return rays_; }

 private:
  const RayOracle& rays_;
};

// The ray of pixel (i, j) of `camera` as the header comment defines it: origin, direction (unit
// length), t_near, t_far and target (origin + t_far * direction) set, source RaySource::pixel.
WitnessRay pixel_ray(const Camera& camera, int i, int j);

}  // namespace cullcheck::oracle
