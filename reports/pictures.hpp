// Pictures of one frame (design: "Reports": "top-down maps of a frame (visible / culled /
// occluders, like the papers' figures)"), written as PNG (libspng).
//
//  - top_down_map: the scene in plan, north (+y) up and east (+x) to the right, every object's
//    plan outline filled by its class in this frame, the eye, the plan footprint of the view
//    volume within the scene's bounds, and the witness rays of the objects a method missed.
//  - frame_image: the pixel oracle's full-scene id buffer in false colour, misdrawn pixels in red.
//
// Everything here is a pure function of its inputs: the same frame gives the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/pixel_oracle.hpp"
#include "oracle/ray_oracle.hpp"

namespace cullcheck {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(Rgb, Rgb) = default;
};

// An 8-bit RGB image, row-major from the top-left pixel, 3 bytes per pixel.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;

  RgbImage() = default;
  RgbImage(int w, int h, Rgb fill);
  Rgb at(int i, int j) const;
  void set(int i, int j, Rgb c);  // ignores pixels outside the image
};

// Writes `image` as an 8-bit RGB PNG to a temporary file beside `path`, then renames it over
// `path`, so a failure never leaves a truncated picture. InputError naming the file when it
// cannot be written; std::runtime_error if encoding fails.
void write_png(const RgbImage& image, const std::string& path);
// The PNG file's bytes (what write_png writes), for pictures carried inline (the report page).
std::string encode_png(const RgbImage& image);
// Reads an 8-bit PNG back as RGB (InputError naming the file when it is unreadable).
RgbImage read_png(const std::string& path);

// The colours, so that readers (and tests) can tell the classes apart.
namespace map_colours {
inline constexpr Rgb kBackground{255, 255, 255};
inline constexpr Rgb kViewVolume{222, 233, 255};      // plan footprint of the view volume
inline constexpr Rgb kViewVolumeEdge{90, 130, 220};
inline constexpr Rgb kVisible{60, 170, 75};           // in the PVS and seen by the oracle
inline constexpr Rgb kCulled{200, 200, 200};          // not in the PVS, not seen: culled correctly
inline constexpr Rgb kOverEstimate{245, 180, 40};     // in the PVS, not seen
inline constexpr Rgb kMissed{255, 0, 0};              // seen, not in the PVS
inline constexpr Rgb kWitnessRay{150, 0, 0};
inline constexpr Rgb kEye{0, 70, 200};
}  // namespace map_colours

// How a top-down map places the scene: the plan box [lo, hi] (the scene's plan bounds and the
// eye, with a margin of 4% of the larger side, at least 1 m) at `metres_per_pixel`; pixel (i, j)
// (column from the left, row from the top) covers x in [lo.x + i m, lo.x + (i + 1) m) and
// y in (hi.y - (j + 1) m, hi.y - j m].
struct MapFrame {
  Box2 extent;
  double metres_per_pixel = 1.0;
  int width = 0, height = 0;

  Vec2 centre_of(int i, int j) const;  // the plan point at the centre of pixel (i, j)
  // The pixel holding plan point p (may lie outside the image).
  void pixel_of(Vec2 p, int& i, int& j) const;
};
// The frame of a map whose longer side is `size_px` pixels (at least 16).
MapFrame map_frame(const Scene& scene, const Camera& camera, int size_px);
// The frame of a map of the plan box `box` (grown by 4% of its larger side, at least 1 m), its
// longer side `size_px` pixels (at least 16).
MapFrame map_frame_of(Box2 box, int size_px);

// The top-down map of one frame. An object's class: MISSED (map_colours::kMissed) when it is in
// `missed` or is in `seen` but not in `pvs` (seen but culled); otherwise VISIBLE when in `pvs` and
// `seen`, OVER-ESTIMATE when in `pvs` only, CULLED when in neither. Ids in any order. Buildings
// are their footprints; mesh objects the plan projection of their triangles (vertical faces show
// as lines). Drawn in this order, each over the last: the view volume's plan footprint (plan
// points (x, y) of the scene's plan bounds where some z between the ground (or the scene's lowest
// point) and the scene's top lies in the view volume: exact for the plane-bounded volumes and the
// omnidirectional ball, tested at pixel centres), its edge, the objects by class (culled,
// over-estimate, visible, missed, so a missed object is never hidden) with a darker outline, each
// ray of `witness_rays` from its origin to its hit point, the eye.
RgbImage top_down_map(const Scene& scene, const Camera& camera, const std::vector<ObjectId>& pvs,
                      const std::vector<ObjectId>& seen, const std::vector<ObjectId>& missed,
                      const std::vector<oracle::WitnessRay>& witness_rays, int size_px);
// The same, of the part of the scene `frame` shows (a map zoomed on a frame's neighbourhood).
RgbImage top_down_map(const Scene& scene, const Camera& camera, const std::vector<ObjectId>& pvs,
                      const std::vector<ObjectId>& seen, const std::vector<ObjectId>& missed,
                      const std::vector<oracle::WitnessRay>& witness_rays, const MapFrame& frame);

// A deterministic false colour per object id (every channel in [48, 223], so never the misdrawn
// red), and the background colour of frame images.
Rgb false_colour(ObjectId id);
inline constexpr Rgb kFrameBackground{20, 20, 28};
inline constexpr Rgb kMisdrawn{255, 0, 0};

// The full-scene id buffer as a picture: each object in its false colour, the background dark,
// and every misdrawn pixel of `comparison` in kMisdrawn. Throws std::invalid_argument if the two
// do not have the same resolution.
RgbImage frame_image(const oracle::IdImage& full, const oracle::PixelComparison& comparison);

}  // namespace cullcheck
