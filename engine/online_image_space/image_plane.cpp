#include "engine/online_image_space/image_plane.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::online {

ImagePlane::ImagePlane(const Camera& camera, int s, double turn, int guard)
    : eye_(camera.position), basis_(basis_of(camera)), guard_(std::max(0, guard)), near_(camera.near) {
  const double pixel = 2.0 * std::tan(camera.hfov / 2) / std::max(1, s);  // image-plane units at depth 1
  const double cap = 80.0 * kPi / 180.0;
  const double clip_h = std::tan(std::min(cap, camera.hfov / 2 + std::max(0.0, turn)));
  const double clip_v = std::tan(std::min(cap, camera.vfov / 2 + std::max(0.0, turn)));
  // Each half-extent at most s pixels (twice the frustum's own half-width), so a narrow field of
  // view or an extreme aspect cannot ask for a huge mask; a capped clip region no longer holds
  // the view, and the occlusion test then refuses what crosses its edge (covers_view).
  const double cap_pixels = std::max(1, s);
  const double half_w = std::ceil(clip_h / pixel - 1e-9), half_h = std::ceil(clip_v / pixel - 1e-9);
  covers_view_ = half_w <= cap_pixels && half_h <= cap_pixels;
  width_ = 2 * static_cast<int>(std::min(half_w, cap_pixels)) + 2 * guard_;
  height_ = 2 * static_cast<int>(std::min(half_h, cap_pixels)) + 2 * guard_;
  tan_h_ = pixel * width_ / 2;  // square pixels
  tan_v_ = pixel * height_ / 2;
}

double ImagePlane::smallest_pixel_angle() const {
  // A step of p along x at image-plane point (x, y, 1) turns the direction by about
  // p sqrt(1 + y^2) / (1 + x^2 + y^2); over the image that is smallest at (edge, 0) or at a
  // corner (the function of y rises then falls), and likewise for steps along y.
  const double p = 2.0 * tan_h_ / width_;
  const double x2 = tan_h_ * tan_h_, y2 = tan_v_ * tan_v_;
  const double corner = 1.0 + x2 + y2;
  const double along_x = std::min(1.0 / (1.0 + x2), std::sqrt(1.0 + y2) / corner);
  const double along_y = std::min(1.0 / (1.0 + y2), std::sqrt(1.0 + x2) / corner);
  return p * std::min(along_x, along_y);
}

}  // namespace cullcheck::online
