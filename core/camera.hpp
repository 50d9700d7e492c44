// Camera and view volume (design: "Scene model").
//
// A camera has a position, yaw (azimuth of the view direction), pitch (positive looks up) and
// roll (about the view direction, positive turns the image clockwise as seen by the viewer), and
// full horizontal and vertical fields of view. Two kinds of view volume:
//  - perspective: 0 < hfov < pi and 0 < vfov < pi, bounded by six planes (near and far measured
//    along the view direction);
//  - omnidirectional (hfov == 2*pi, the thesis's 360-degree mode for panoramas and radar): the
//    whole sphere of directions out to distance `far`; yaw, pitch, roll and vfov are ignored.
#pragma once

#include <array>
#include <string>

#include "core/geometry.hpp"

namespace cullcheck {

struct Camera {
  Vec3 position;
  double yaw = 0.0;
  double pitch = 0.0;
  double roll = 0.0;
  double hfov = kPi / 3.0;
  double vfov = kPi / 4.0;
  double near = 0.1;
  double far = 1.0e5;

  bool omnidirectional() const { return hfov >= kTwoPi; }
};

// Throws InputError naming `object` if the camera is not usable (non-finite values, fov out of
// range, near/far inverted, eye below the ground plane).
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

// The view volume as planes; omnidirectional cameras have none and are bounded by `far` alone.
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
