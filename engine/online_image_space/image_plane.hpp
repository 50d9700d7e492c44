// The image plane the occlusion masks live on (section 5.4): the camera's perspective view
// sampled with s square pixels across the horizontal field of view, widened beyond the view
// frustum in two ways:
//  - by `turn` radians on every side (the CLIP region): marks made at a critical frame must hold
//    until the next, and the view may turn up to critical_turn before that forces one, so a box
//    is tested over the part of it that a view turned that far (in yaw or pitch) can show;
//  - by a GUARD band of `guard` pixels around the clip region, where occluders are drawn too, so
//    that erosion at the clip region's edge shrinks real coverage instead of eating Δ + 1 pixels
//    of every edge.
// Pixel (i, j) covers [i, i+1) x [j, j+1) in image coordinates, i to the right, j down from the
// top. This is the engine's own projection, built from core's camera basis; the oracle derives
// its own (oracle/view_transform.hpp).
#pragma once

#include "core/camera.hpp"

namespace cullcheck::online {

struct ViewPoint {
  double x = 0.0, y = 0.0;  // image coordinates (pixels)
  double depth = 0.0;       // distance along the view direction (the z-buffer's depth)
};

class ImagePlane {
 public:
  // `s` pixels across the camera's horizontal field of view; `turn` radians of clip region beyond
  // the frustum on every side (each half-angle capped at 80 degrees); `guard` pixels beyond that.
  ImagePlane(const Camera& camera, int s, double turn = 0.0, int guard = 0);

  int width() const { return width_; }
  int height() const { return height_; }
  double near() const { return near_; }
  // Half-extent of the image plane at depth 1: tan(hfov / 2) and tan(vfov / 2) as sampled.
  double tan_half_h() const { return tan_h_; }
  double tan_half_v() const { return tan_v_; }
  const Vec3& eye() const { return eye_; }
  int guard() const { return guard_; }
  // Whether the clip region holds the widened view (false when its size was capped: then only a
  // box projecting wholly inside it can be judged).
  bool covers_view() const { return covers_view_; }  // the clip region is [guard, width - guard) x [guard, height - guard)

  // Camera space: x right, y up, z = depth along the view direction.
  Vec3 to_camera(Vec3 p) const {
    const Vec3 d = p - eye_;
    return {dot(d, basis_.right), dot(d, basis_.up), dot(d, basis_.forward)};
  }
  // A camera-space point with z > 0 on the image.
  ViewPoint project(Vec3 c) const {
    return {(c.x / (c.z * tan_h_) + 1.0) * 0.5 * width_, (1.0 - c.y / (c.z * tan_v_)) * 0.5 * height_, c.z};
  }
  // The camera-space direction through image point (x, y), at depth 1.
  Vec3 direction(double x, double y) const {
    return {(2.0 * x / width_ - 1.0) * tan_h_, (1.0 - 2.0 * y / height_) * tan_v_, 1.0};
  }
  // The smallest angle (radians) one pixel step subtends anywhere on the image, horizontally or
  // vertically: at the image's edges a pixel covers less angle than at its centre.
  double smallest_pixel_angle() const;

 private:
  Vec3 eye_;
  CameraBasis basis_;
  int width_ = 0, height_ = 0, guard_ = 0;
  bool covers_view_ = true;
  double tan_h_ = 0.0, tan_v_ = 0.0, near_ = 0.0;
};

}  // namespace cullcheck::online
