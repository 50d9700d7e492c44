// The oracle's own view transform (design: "Independence": the oracle shares no view-volume code
// with the engine). Built from the Camera's raw fields alone, not from core's basis_of,
// ViewVolume or camera_matrices, so that a wrong roll sign or half-angle there is not agreed on
// here; oracle/tests/view_transform_test.cpp pins it to hand-computed projections and checks it
// against core/camera_matrices (what subjects receive) on many random cameras.
//
// Derivation. Eye space is OpenGL's: x to the right of the image, y up it, the camera looking
// down -z. The rotation from eye space to the world is a product of elementary rotations:
//   world_from_eye = Rz(yaw) * Base * Rx(pitch) * Rz(roll),
// where Base maps the canonical camera (yaw = pitch = roll = 0: looking along +x, z up) to eye
// space's axes (eye -z -> world +x, eye y -> world +z, eye x -> world -y). Rx(pitch) tips the view
// direction -z up toward +y (positive pitch looks up). Rz(roll) turns the camera counter-clockwise
// about its view axis as the viewer sees it, so the world turns clockwise in the image (core/
// camera.hpp: positive roll turns the image clockwise as seen by the viewer).
//
// Clip space (the oracle's convention, not OpenGL's: it needs no near > 0 and keeps depth in
// metres): clip = projection * view * (p, 1) gives (x, y, z, w) with z the depth along the view
// direction, in metres. Perspective: x = eye_x / tan(hfov/2), y = eye_y / tan(vfov/2), w = z =
// depth. Orthographic: x = 2 eye_x / ortho_width, y = 2 eye_y / ortho_height, w = 1, z = depth.
// A point is inside the view volume when -w <= x <= w, -w <= y <= w and near <= z <= far.
// Omnidirectional cameras (hfov = 2 pi): the ball of radius far around the eye; the view matrix
// is the translation alone and there is no projection (yaw, pitch, roll, vfov and near unused).
//
// Exactness: double precision throughout; `contains` is a point test with no tolerance,
// `may_meet` is conservative (it widens every plane by a relative 1e-9, far above the rounding of
// the sums it compares).
#pragma once

#include <array>
#include <optional>

#include "core/camera.hpp"

namespace cullcheck::oracle {

using Matrix4d = std::array<std::array<double, 4>, 4>;  // m[row][column], column vectors

struct Clip {
  double x = 0.0, y = 0.0, z = 0.0, w = 0.0;
};

// An affine function of world points, f(p) = dot(n, p - eye) + d; >= 0 on the inside.
struct ClipPlane {
  Vec3 n;
  double d = 0.0;
};

// The distance from `eye` to the nearest point of `box` (0 inside it).
double distance_to_box(Vec3 eye, const Box3& box);

class ViewTransform {
 public:
  explicit ViewTransform(const Camera& camera);

  const Matrix4d& view() const { return view_; }               // eye space from world
  const Matrix4d& world_from_eye() const { return inverse_view_; }
  // Clip space from eye space; nullopt for an omnidirectional camera.
  const std::optional<Matrix4d>& projection() const { return projection_; }

  Vec3 eye() const { return eye_; }
  // The world directions of eye space's axes: the view direction (-z), right (x) and up (y).
  Vec3 forward() const { return {-inverse_view_[0][2], -inverse_view_[1][2], -inverse_view_[2][2]}; }
  Vec3 right() const { return {inverse_view_[0][0], inverse_view_[1][0], inverse_view_[2][0]}; }
  Vec3 up() const { return {inverse_view_[0][1], inverse_view_[1][1], inverse_view_[2][1]}; }
  bool orthographic() const { return orthographic_; }
  bool omnidirectional() const { return omnidirectional_; }
  double near() const { return near_; }
  double far() const { return far_; }

  // projection * view * (p, 1), computed on p - eye (the translation folded in exactly).
  // Omnidirectional: (p - eye, 1).
  Clip clip(Vec3 p) const;
  // Exact point test in clip space (the ball |p - eye| <= far when omnidirectional).
  bool contains(Vec3 p) const;
  // Conservative: false only when the box lies wholly outside one of the six planes (outside
  // the ball when omnidirectional). With `depth` false, near and far are ignored.
  bool may_meet(const Box3& box, bool depth = true) const;
  // The six planes of the volume in world space (left, right, bottom, top: w + x, w - x, w + y,
  // w - y; then near, far), rows of projection * view. Omnidirectional cameras have none.
  const std::array<ClipPlane, 6>& planes() const { return planes_; }

  // Perspective: the world direction (unit length) through the image-plane point (u, v) in
  // normalised device coordinates ([-1, 1] across the image, u right, v up), by the inverse of
  // projection * view: clip (u, v, 1, 1) is eye-space (u tan(hfov/2), v tan(vfov/2), -1).
  Vec3 direction_through(double u, double v) const;
  // Orthographic: the point on the near plane at (u, v) in normalised device coordinates.
  Vec3 near_point_at(double u, double v) const;
  // Perspective and omnidirectional: whether the ray from the eye along unit direction `d` has
  // points in the view volume, and if so their extent in metres along it: from the near plane
  // (depth = near) to the far plane (depth = far), or [0, far] when omnidirectional.
  bool extent(Vec3 d, double& t_near, double& t_far) const;

 private:
  Vec3 eye_;
  Matrix4d view_{}, inverse_view_{};
  std::optional<Matrix4d> projection_;
  std::array<ClipPlane, 6> planes_{};
  bool orthographic_ = false, omnidirectional_ = false;
  double near_ = 0.0, far_ = 0.0;
  double tan_h_ = 0.0, tan_v_ = 0.0;  // perspective half-angle tangents
};

// Inline: the ray oracle asks it once per ray it plans.
inline bool ViewTransform::extent(Vec3 d, double& t_near, double& t_far) const {
  if (omnidirectional_) {
    t_near = 0.0, t_far = far_;
    return true;
  }
  if (orthographic_) return false;
  // The side planes pass through the eye, so they are a test on the direction alone.
  for (int i = 0; i < 4; ++i)
    if (dot(planes_[i].n, d) < 0.0) return false;
  const double along = dot(planes_[4].n, d);  // depth per metre along d
  if (!(along > 0.0)) return false;
  t_near = near_ / along, t_far = far_ / along;
  return true;
}

}  // namespace cullcheck::oracle
