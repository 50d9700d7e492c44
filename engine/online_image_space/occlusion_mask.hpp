// The occluders' depth image and the hierarchical occlusion masks (sections 5.2 and 5.4), on the
// CPU: the method's own rasteriser, not the oracle's ray caster.
//
// Depth image. Each occluder polygon (convex) is clipped to the near plane, projected, and
// written to the pixels whose centres it covers. A pixel keeps, of the polygons over its centre,
// the smallest of their greatest depths over the pixel's square: 1/depth is affine on the image
// for a plane, so a polygon's greatest depth over a square is at one of its corners (capped by
// the polygon's own farthest vertex). Rasterising by pixel centres is what OpenGL does; it marks
// pixels that the union only partly covers, which the extra pixel of erosion removes.
//
// Primary mask M_0. The covered pixels are eroded by Δ + 1 pixels with a square structuring
// element (a pixel stays when every pixel within Chebyshev distance Δ + 1 is covered; outside
// the image counts as uncovered), and a kept pixel's value is the greatest value of the 3 x 3
// pixels around it, so that it bounds the occluders' depth over its whole square even where the
// polygon over its centre did not cover all of it. Uncovered pixels hold +infinity.
//
// Hierarchy M_1..M_m: each pixel of M_{i+1} is the maximum over a b x b block of M_i, so a
// test passed against a coarse pixel holds for every fine pixel in it.
//
// The occlusion test (section 5.5): a box is occluded when it lies wholly in front of the eye
// (beyond the near plane) and every mask pixel that its projection's bounding rectangle meets
// within the clip region (image_plane.hpp) holds a value smaller than the box's nearest depth;
// the rest of the rectangle is outside every view the clip region allows for.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/online_image_space/image_plane.hpp"

namespace cullcheck::online {

class DepthImage {
 public:
  explicit DepthImage(const ImagePlane& plane);
  // Rasterises one convex polygon (world coordinates); returns the pixels it wrote.
  std::uint64_t draw(const Vec3* vertices, std::uint32_t count);
  // The ground plane z = 0 as an occluder, out to depth `far` (pixels whose centre sees the ground).
  // It hides nothing (every object stands on it) but fills the mask below the horizon, so that
  // erosion does not eat the foot of every facade, where far buildings' boxes end.
  std::uint64_t draw_ground(double far);
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<double>& depth() const { return depth_; }  // +inf where nothing was drawn

 private:
  // Pixel (i, j) keeps the smaller of its value and the plane's greatest depth over its square
  // (1/depth = A x + B y + C), at most `cap`.
  void keep_deepest_corner(int i, int j, double A, double B, double C, double cap);

  const ImagePlane& plane_;
  int width_, height_;
  std::vector<double> depth_;
};

struct MaskTest {
  std::uint64_t cells = 0;  // mask pixels visited, all levels
};

class OcclusionMask {
 public:
  // M_0: `image` eroded by `shrink_pixels` + 1.
  OcclusionMask(const ImagePlane& plane, const DepthImage& image, int shrink_pixels);
  // M_1..M_levels (all down to one pixel when levels < 0), each of `block` x `block` pixels.
  void build_hierarchy(int block, int levels);

  bool occluded(const Box3& box, MaskTest* stats = nullptr) const;
  // Pixels of M_0 that hold an occluder depth (finite).
  std::uint64_t covered_pixels() const;
  const std::vector<double>& level(std::size_t i) const { return levels_[i]; }
  std::size_t level_count() const { return levels_.size(); }

 private:
  bool rectangle_behind(int level, int x0, int y0, int x1, int y1, double depth, MaskTest* stats) const;

  const ImagePlane& plane_;
  int block_ = 2;
  std::vector<std::vector<double>> levels_;
  std::vector<int> widths_, heights_;
};

}  // namespace cullcheck::online
