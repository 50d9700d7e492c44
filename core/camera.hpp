// Camera and view volume (design: "Scene model").
//
// A camera has a position, yaw (azimuth of the view direction), pitch (positive looks up) and
// roll (about the view direction, positive turns the image clockwise as seen by the viewer).
// Three kinds of view volume:
//  - perspective: full fields of view 0 < hfov < pi and 0 < vfov < pi, bounded by six planes
//    (near and far measured along the view direction);
//  - orthographic: a box ortho_width x ortho_height metres across, centred on the view axis
//    through `position`, from near to far along the view direction (fields of view unused);
//  - omnidirectional (hfov == 2*pi, the thesis's 360-degree mode for panoramas and radar): the
//    whole sphere of directions out to distance `far`; yaw, pitch, roll and vfov are ignored.
// A camera also has a resolution, where pixel errors are measured (oracle/pixel_oracle.hpp):
// width x height pixels over the image plane (an equirectangular panorama when
// omnidirectional); 0 means the default, kDefaultImageWidth columns and square pixels.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/geometry.hpp"

namespace cullcheck {

enum class Projection : std::uint8_t { perspective, orthographic };

struct Camera {
  Vec3 position;
  double yaw = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
  double hfov = kPi / 3.0;
  double vfov = kPi / 4.0;
  double near = 0.1;
  double far = 1.0e5;
  Projection projection = Projection::perspective;
  double ortho_width = 0.0;   // orthographic: full width of the view box, metres
  double ortho_height = 0.0;  // orthographic: full height, metres
  int width = 0;              // resolution in pixels; 0 = default (resolution_of)
  int height = 0;

  bool orthographic() const { return projection == Projection::orthographic; }
  bool omnidirectional() const { return !orthographic() && hfov >= kTwoPi; }
};

inline constexpr int kDefaultImageWidth = 320;
inline constexpr int kMaxImageSide = 8192;

struct Resolution {
  int width = 0, height = 0;
  friend bool operator==(Resolution, Resolution) = default;
};
// The camera's resolution: width x height when set; otherwise kDefaultImageWidth columns and
// as many rows as square pixels give (half as many for an omnidirectional panorama), at least 1.
Resolution resolution_of(const Camera& camera);

// Throws InputError naming `object` if the camera is not usable (non-finite values, fov or
// orthographic extent out of range, near/far inverted, eye below the ground plane, resolution
// set on one side only or beyond kMaxImageSide).
void validate(const Camera& camera, const std::string& object = "camera");

// Orthonormal camera basis: forward (view direction), right, up (after pitch and roll).
struct CameraBasis {
  Vec3 forward, right, up;
};
CameraBasis basis_of(const Camera& camera);

// A plane n.p + d >= 0 on the inside.
struct Plane {
  Vec3 n;
  double d = 0.0;
  double signed_distance(Vec3 p) const { return dot(n, p) + d; }
};

// The view volume as planes (a frustum, or a box for an orthographic camera); omnidirectional
// cameras have none and are bounded by `far` alone.
struct ViewVolume {
  Vec3 eye;
  std::array<Plane, 6> planes{};
  int plane_count = 0;
  double far = 0.0;
  bool omnidirectional = false;

  explicit ViewVolume(const Camera& camera);
  // Exact membership for a point (used by the oracle to keep only hits inside the volume).
  bool contains(Vec3 p) const;
  // Conservative: false only if the box lies entirely outside (used by engine culling).
  bool may_intersect(const Box3& box) const;
};

}  // namespace cullcheck
