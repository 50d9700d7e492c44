// The slice-wise culling's occlusion queries (engine/slice_wise/occlusion_buffer.hpp): a box the
// buffer calls hidden has no point visible from the eye, checked by rays cast in double precision
// against the drawn triangles; occluders fuse inside a pixel (two triangles sharing an edge hide
// what a single one would); a gap far thinner than a pixel is not lost between samples.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "engine/slice_wise/occlusion_buffer.hpp"
#include "properties/property_run.hpp"

namespace cullcheck::slice_wise {
namespace {

using Triangle = std::array<Vec3, 3>;

// Möller-Trumbore in double: the ray parameter of the hit, or +inf.
double hit(Vec3 o, Vec3 d, const Triangle& t) {
  const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3 p = cross(d, e2);
  const double det = dot(e1, p);
  if (std::abs(det) < 1e-15) return HUGE_VAL;
  const Vec3 s = o - t[0];
  const double u = dot(s, p) / det;
  if (u < 0 || u > 1) return HUGE_VAL;
  const Vec3 q = cross(s, e1);
  const double v = dot(d, q) / det;
  if (v < 0 || u + v > 1) return HUGE_VAL;
  const double tt = dot(e2, q) / det;
  return tt > 0 ? tt : HUGE_VAL;
}

OcclusionBuffer buffer_on(Vec3 eye, const Box3& box, int resolution) {
  OcclusionBuffer b;
  const auto view = zoomed_view(eye, box, resolution, 0.05);
  EXPECT_TRUE(view.has_value());
  b.reset(*view);
  return b;
}

// A wall x in [x0, x1], z in [0, top] at y = 10, as two triangles sharing its diagonal.
void draw_wall(OcclusionBuffer& b, double x0, double x1, double top = 20) {
  b.draw_triangle({x0, 10, 0}, {x1, 10, 0}, {x1, 10, top});
  b.draw_triangle({x0, 10, 0}, {x1, 10, top}, {x0, 10, top});
}

TEST(OcclusionBuffer, TwoTrianglesSharingAnEdgeHideTheBoxBehindThem) {
  const Vec3 eye{0, 0, 2};
  const Box3 box{{-2, 30, 0}, {2, 34, 8}};
  for (int resolution : {8, 64, 256}) {
    OcclusionBuffer b = buffer_on(eye, box, resolution);
    EXPECT_TRUE(b.test_box(box).visible) << "nothing drawn yet";
    draw_wall(b, -1, 1, 6);  // seen from the eye it just covers the box; its diagonal crosses the view
    const BoxVisibility r = b.test_box(box);
    EXPECT_FALSE(r.visible) << resolution << " pixels: the diagonal's pixels are covered by the two triangles together";
    EXPECT_GT(b.statistics().fragments, 0u) << "the diagonal crosses pixels neither triangle covers alone";
  }
}

TEST(OcclusionBuffer, AGapThinnerThanAPixelShowsTheBoxBehind) {
  const Vec3 eye{0, 0, 2};
  const Box3 box{{-2, 30, 0}, {2, 34, 8}};
  OcclusionBuffer b = buffer_on(eye, box, 32);  // pixels about 0.04 rad wide: 0.4 m on the wall
  draw_wall(b, -10, 0.3);
  draw_wall(b, 0.301, 10);  // a 1 mm slit
  EXPECT_TRUE(b.test_box(box).visible) << "a 1 mm slit at 10 m, 400 times thinner than a pixel, still shows";
  OcclusionBuffer closed = buffer_on(eye, box, 32);
  draw_wall(closed, -10, 0.3);
  draw_wall(closed, 0.3, 10);  // the same walls touching
  EXPECT_FALSE(closed.test_box(box).visible);
}

TEST(OcclusionBuffer, ABoxInFrontOfTheWallShows) {
  const Vec3 eye{0, 0, 2};
  const Box3 box{{-2, 5, 0}, {2, 6, 8}};
  OcclusionBuffer b = buffer_on(eye, box, 64);
  draw_wall(b, -10, 10);
  EXPECT_TRUE(b.test_box(box).visible);
}

TEST(OcclusionBuffer, ABoxTheBufferHidesIsHiddenFromEveryRay) {
  int hidden = 0, visible = 0;
  const PropertyOutcome outcome = run_property("occlusion-buffer-hidden-means-hidden", 300, true, [&] {
    const double bx = *rc::gen::inRange(-20, 21), by = *rc::gen::inRange(25, 60);
    const double sx = *rc::gen::inRange(1, 10), sz = *rc::gen::inRange(1, 15);
    const Box3 box{{bx, by, 0}, {bx + sx, by + sx, sz}};
    const Vec3 eye{0, 0, 1.7};
    const int resolution = *rc::gen::element(8, 32, 128);
    OcclusionBuffer b = buffer_on(eye, box, resolution);
    // Occluders between the eye and the box: wall pieces and loose triangles, some touching.
    std::vector<Triangle> drawn;
    const int pieces = *rc::gen::inRange(1, 12);
    for (int k = 0; k < pieces; ++k) {
      const double y = *rc::gen::inRange(5, 24), x0 = *rc::gen::inRange(-30, 30), w = *rc::gen::inRange(1, 25);
      const double h = *rc::gen::inRange(2, 30), lean = *rc::gen::inRange(-3, 4);
      const Triangle t1{Vec3{x0, y, 0}, Vec3{x0 + w, y + lean, 0}, Vec3{x0 + w, y + lean, h}};
      const Triangle t2{Vec3{x0, y, 0}, Vec3{x0 + w, y + lean, h}, Vec3{x0, y, h}};
      for (const Triangle& t : {t1, t2}) b.draw_triangle(t[0], t[1], t[2]), drawn.push_back(t);
    }
    const BoxVisibility r = b.test_box(box);
    if (r.visible) {
      ++visible;
      return;
    }
    ++hidden;
    // Rays to points of the box (its corners, its faces' grid): each meets a triangle first.
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j)
        for (int k = 0; k <= 8; ++k) {
          const Vec3 p{box.lo.x + sx * i / 8.0, box.lo.y + sx * j / 8.0, sz * k / 8.0};
          const Vec3 d = p - eye;
          double nearest = HUGE_VAL;
          for (const Triangle& t : drawn) nearest = std::min(nearest, hit(eye, d, t));
          RC_ASSERT(nearest < 1.0);
        }
  });
  std::cerr << "boxes hidden " << hidden << ", visible " << visible << "\n";
  EXPECT_TRUE(outcome.held);
  EXPECT_GT(hidden, 20) << "the property must reach hidden boxes to check anything";
  EXPECT_GT(visible, 20);
}

}  // namespace
}  // namespace cullcheck::slice_wise
