// Occlusion queries on the CPU for the slice-wise culling (Yılmaz & Güdükbay §4.2), exact about
// coverage where the paper's hardware queries sample it.
//
// The paper draws the shrunk occluders into a depth buffer and asks the GPU how many fragments of
// an occludee's box pass the depth test; it zooms the view on the occludee (1024 x 768) and
// draws two fragments per pixel so that rasterisation errors do not hide a box that shows.
// A hardware depth buffer still samples: a gap between occluders narrower than a pixel, or a
// far box smaller than one, can fall between samples. Here a pixel holds instead the depth up to
// which its WHOLE square is covered:
//
//   D(Q) = the least d such that the triangles whose depth over Q is at most d cover Q entirely.
//
// A box is hidden in Q when D(Q) is less than the box's least depth over Q: every ray through Q
// then meets an occluder before it can reach any point of the box. That least depth comes from
// the box's faces turned to the eye (a ray enters the box through one of them; 1/depth is affine
// over each face's projection), and is never taken below the box's least depth overall. Coverage is decided geometrically
// (the square minus the projected triangles, nearest first, as convex pieces), so occluders fuse
// inside a pixel as well as across pixels, and nothing thinner than a pixel is ever lost between
// samples: a box this buffer calls hidden has no point visible from the eye against the drawn
// triangles. Hence it cannot miss what the paper's zoomed, two-fragment query catches (that query
// reports only fragments that really pass; a fragment that passes is a visible point, which makes
// some pixel here not covered in front of it). Resolution only trades tightness (a pixel's depth
// bound is the worst over its square) for time.
//
// Depth is the eye-space distance along the view axis; 1/depth is affine over a projected
// triangle, so a triangle's greatest depth over Q ∩ T is bounded from its plane at Q's corners
// and at its own vertices. Triangles are clipped at the near plane (what lies nearer is dropped:
// less coverage, never more).
//
// Tolerance, stated: a piece of a square left uncovered that is thinner than 1e-9 pixel is taken
// as covered (the round-off of clipping along an edge two triangles share); with pixels of at most
// a few centimetres that is a gap far below the oracle's single-precision rays. Projected
// triangles are first clipped to a guard band of three times the image, so that the round-off
// scales with the image, not with how far a triangle near the eye projects. Everything else is
// plain double arithmetic.
//
// Cost: a triangle costs its rows and touched pixels; a pixel wholly inside a triangle only
// lowers a bound, a pixel on a triangle's edge keeps a fragment (triangle, depth bound), and the
// exact subtraction runs lazily, once per pixel a box test reaches, remembered until a fragment
// is added there.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::slice_wise {

// A perspective view: from `eye` along `forward`, the image window [u0, u1] x [v0, v1] on the plane
// at distance 1 (u along `right`, v along `up`), width x height pixels.
struct PerspectiveView {
  Vec3 eye;
  Vec3 right{1, 0, 0}, up{0, 0, 1}, forward{0, 1, 0};  // orthonormal
  double u0 = -1, u1 = 1, v0 = -1, v1 = 1;
  int width = 256, height = 256;
  double near = 0.05;  // metres along forward; nearer geometry is clipped away
};

// The view from `eye` zoomed on `box` (the paper's zoomed occlusion test): forward towards the
// box's centre, the window the box's projected corners span, resolution x resolution pixels.
// nullopt when the box comes within 2 near of the eye plane or spans more than 160 degrees: the
// caller must then take the box as visible.
std::optional<PerspectiveView> zoomed_view(Vec3 eye, const Box3& box, int resolution, double near);

// The six faces of a cube map at `eye` (+x, -x, +y, -y, +z, -z), each 90 x 90 degrees.
std::array<PerspectiveView, 6> cube_views(Vec3 eye, int resolution, double near);

struct BufferStatistics {
  std::uint64_t triangles = 0;          // drawn (after near clipping, each piece once)
  std::uint64_t full_pixels = 0;        // pixel bounds lowered by a triangle containing the square
  std::uint64_t fragments = 0;          // partial coverages kept
  std::uint64_t exact_evaluations = 0;  // pixels whose coverage was subtracted out
  std::uint64_t box_tests = 0;
};

// What a box test saw.
struct BoxVisibility {
  bool visible = false;      // some pixel of the box's projection inside the image is not covered in front of it
  bool in_image = false;     // the projection (of the part at depth >= near) meets the image
  bool beyond_image = false; // the projection leaves the image
  bool crosses_near = false; // part of the box lies nearer than the near plane
  double nearest = 0.0;      // the box's least depth (>= near)
  double farthest = 0.0;     // the box's greatest depth
};

// A small convex polygon in pixel coordinates (a clipped triangle, a piece of a pixel).
struct ConvexPolygon {
  std::array<Vec2, 12> p;
  int n = 0;
};

class OcclusionBuffer {
 public:
  void reset(const PerspectiveView& view);
  const PerspectiveView& view() const { return view_; }

  void draw_triangle(Vec3 a, Vec3 b, Vec3 c);
  // The depth range of `box` in this view and whether its projection meets the image, without
  // testing pixels.
  BoxVisibility locate_box(const Box3& box) const { return locate_box(box, hull_); }
  // locate_box, then whether any pixel of the box's projection inside the image is not covered
  // in front of the box's least depth over that pixel. Stops at the first such pixel.
  BoxVisibility test_box(const Box3& box);

  const BufferStatistics& statistics() const { return stats_; }
  // The covered depth of pixel (x, y) (exact: evaluates the pixel if it must); +inf if not covered.
  double covered_depth(int x, int y);

 private:
  struct Fragment {
    std::uint32_t triangle;
    std::int32_t next;
    double depth;  // the triangle's greatest depth over the pixel
  };
  Vec3 to_camera(Vec3 p) const;  // (right, up, forward) coordinates
  Vec2 to_pixel(Vec3 camera) const;
  BoxVisibility locate_box(const Box3& box, std::vector<Vec2>& hull) const;
  void raster_triangle(const std::array<Vec3, 3>& camera);
  bool hidden_at(std::size_t pixel, double depth);
  double evaluate(std::size_t pixel);

  PerspectiveView view_;
  double sx_ = 1, sy_ = 1;                 // pixels per unit of u, v
  std::vector<double> full_;               // least depth of a triangle containing the whole square
  std::vector<double> exact_;              // remembered D(Q), valid when !dirty_
  std::vector<std::uint8_t> dirty_;
  std::vector<std::int32_t> head_;         // fragment list per pixel
  std::vector<Fragment> fragments_;
  std::vector<ConvexPolygon> polygons_;
  mutable std::vector<Vec2> hull_;  // scratch of the box tests (called per occluder, block and slice)  // drawn triangles in pixel coordinates, clipped to the guard band
  BufferStatistics stats_;
};

// x-extent of a convex polygon (n vertices, either orientation) within the strip y0 <= y <= y1;
// false when it does not meet the strip.
bool strip_extent(const Vec2* polygon, int n, double y0, double y1, double& x_lo, double& x_hi);

}  // namespace cullcheck::slice_wise
