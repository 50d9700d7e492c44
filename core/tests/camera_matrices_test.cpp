// View and projection matrices (core/camera_matrices.hpp) against projections worked out by hand,
// and a seeded property that they agree with ViewVolume::contains.
//
// Convention (the header's, OpenGL): row-major m[row][column]; clip = P * V * (x, y, z, 1);
// eye space has x to the image's right, y up the image, the camera looking down -z; a point is
// inside when -w <= x, y, z <= w, and NDC depth z / w runs from -1 (near) to +1 (far). The
// image's +x is cullcheck's `right` = (sin yaw, -cos yaw, 0) before pitch and roll, so V's rows
// are right, up and -forward.
//
// For a perspective camera P = [[1/tan(hfov/2), 0, 0, 0], [0, 1/tan(vfov/2), 0, 0],
// [0, 0, -(f+n)/(f-n), -2fn/(f-n)], [0, 0, -1, 0]]: a point at depth d along the view axis has
// w = d and NDC depth (f+n)/(f-n) - 2fn/((f-n) d).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>

#include "core/camera.hpp"
#include "core/camera_matrices.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {
namespace {

constexpr double kTol = 1e-12;  // rounding in tan(pi/4) = 0.9999999999999999 and sums of products

using Clip = std::array<double, 4>;

Clip clip_of(const Camera& c, Vec3 p) {
  const auto projection = projection_matrix(c);
  EXPECT_TRUE(projection.has_value());
  return transform(multiply(*projection, view_matrix(c)), p);
}

void expect_clip(const Camera& c, Vec3 p, Clip expected, double tol = kTol) {
  const Clip got = clip_of(c, p);
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(got[i], expected[i], tol) << "component " << i << " of clip(" << p.x << ", " << p.y << ", " << p.z << ")";
}

void expect_matrix(const Matrix4& m, const Matrix4& expected, double tol = kTol) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(m[r][c], expected[r][c], tol) << "m[" << r << "][" << c << "]";
}

// Eye at the origin, yaw 0 (looking along +x), hfov = vfov = pi/2, near 1, far 100.
Camera square_camera() {
  Camera c;
  c.position = {0, 0, 0};
  c.hfov = c.vfov = kPi / 2;
  c.near = 1;
  c.far = 100;
  return c;
}

TEST(CameraMatrices, ViewAndProjectionOfTheSquareCamera) {
  const Camera c = square_camera();
  // forward (1, 0, 0), right (0, -1, 0), up (0, 0, 1): rows right, up, -forward.
  expect_matrix(view_matrix(c), {{{0, -1, 0, 0}, {0, 0, 1, 0}, {-1, 0, 0, 0}, {0, 0, 0, 1}}});
  // 1/tan(pi/4) = 1; -(f+n)/(f-n) = -101/99; -2fn/(f-n) = -200/99.
  expect_matrix(*projection_matrix(c), {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -101.0 / 99, -200.0 / 99}, {0, 0, -1, 0}}});
  // P * V: row 2 = (-101/99) * (-1, 0, 0, 0) + (-200/99) * (0, 0, 0, 1); row 3 = -(-1, 0, 0, 0).
  expect_matrix(multiply(*projection_matrix(c), view_matrix(c)),
                {{{0, -1, 0, 0}, {0, 0, 1, 0}, {101.0 / 99, 0, 0, -200.0 / 99}, {1, 0, 0, 0}}});
}

TEST(CameraMatrices, SquareCameraProjectsPointsAsWorkedOut) {
  const Camera c = square_camera();
  // (10, 0, 0): on the axis at depth 10, so w = 10 and z = 1010/99 - 200/99 = 810/99; NDC depth
  // 810/990 = 9/11 = 0.8181...
  expect_clip(c, {10, 0, 0}, {0, 0, 810.0 / 99, 10});
  const Clip axis = clip_of(c, {10, 0, 0});
  EXPECT_NEAR(axis[2] / axis[3], 9.0 / 11, kTol);
  // (10, -10, 0): 10 m to the right (right = -y) at depth 10, on the right edge x = w.
  expect_clip(c, {10, -10, 0}, {10, 0, 810.0 / 99, 10});
  // (10, 10, 0): the left edge x = -w.
  expect_clip(c, {10, 10, 0}, {-10, 0, 810.0 / 99, 10});
  // (10, 0, 10): the top edge y = w; (10, 0, -10): the bottom edge y = -w.
  expect_clip(c, {10, 0, 10}, {0, 10, 810.0 / 99, 10});
  expect_clip(c, {10, 0, -10}, {0, -10, 810.0 / 99, 10});
  // The near plane (depth 1): z = 101/99 - 200/99 = -1 = -w. The far plane (depth 100):
  // z = 10100/99 - 200/99 = 100 = w. NDC depth -1 and +1.
  expect_clip(c, {1, 0, 0}, {0, 0, -1, 1});
  expect_clip(c, {100, 0, 0}, {0, 0, 100, 100});
  // Behind the eye w < 0: never inside.
  EXPECT_NEAR(clip_of(c, {-10, 0, 0})[3], -10, kTol);
}

TEST(CameraMatrices, YawAndTranslationAndUnequalFieldsOfView) {
  // Eye (5, 5, 2), yaw pi/2: forward (0, 1, 0), right (1, 0, 0), up (0, 0, 1) (up to 6e-17).
  // hfov pi/2 (1/tan = 1), vfov 2 atan(0.5) (1/tan = 2): x and y scale differently.
  Camera c = square_camera();
  c.position = {5, 5, 2};
  c.yaw = kPi / 2;
  c.vfov = 2 * std::atan(0.5);
  // V's translation column: -(right . eye) = -5, -(up . eye) = -2, (forward . eye) = 5.
  const Matrix4 v = view_matrix(c);
  EXPECT_NEAR(v[0][3], -5, kTol);
  EXPECT_NEAR(v[1][3], -2, kTol);
  EXPECT_NEAR(v[2][3], 5, kTol);
  EXPECT_NEAR(projection_matrix(c)->at(1)[1], 2, kTol);
  // (5, 15, 2): on the axis at depth 10; (15, 15, 2): 10 m right, x = w; (5, 15, 7): 5 m up,
  // y = 2 * 5 = 10 = w (the top edge of the narrower vertical field); (5, 15, 4.5): y = w / 2.
  expect_clip(c, {5, 15, 2}, {0, 0, 810.0 / 99, 10});
  expect_clip(c, {15, 15, 2}, {10, 0, 810.0 / 99, 10});
  expect_clip(c, {-5, 15, 2}, {-10, 0, 810.0 / 99, 10});
  expect_clip(c, {5, 15, 7}, {0, 10, 810.0 / 99, 10});
  expect_clip(c, {5, 15, 4.5}, {0, 5, 810.0 / 99, 10});
}

TEST(CameraMatrices, PitchTiltsTheImageUp) {
  // Pitch pi/4: forward (s, 0, s), up = right x forward = (0, -1, 0) x (s, 0, s) = (-s, 0, s),
  // s = sqrt(1/2). Looking 45 degrees up with a 90-degree vertical field, the horizon is the
  // bottom edge and the zenith the top edge.
  Camera c = square_camera();
  c.pitch = kPi / 4;
  const double s = std::sqrt(0.5);
  // (10, 0, 10): on the axis at depth 10 sqrt 2 = 14.142...
  const double d = 10 * std::sqrt(2.0);
  expect_clip(c, {10, 0, 10}, {0, 0, 101.0 / 99 * d - 200.0 / 99, d}, 1e-11);
  // (10, 0, 0): depth 10 s = 7.07, up component -10 s: y = -w (bottom edge).
  const Clip horizon = clip_of(c, {10, 0, 0});
  EXPECT_NEAR(horizon[3], 10 * s, kTol);
  EXPECT_NEAR(horizon[1], -10 * s, kTol);
  // (0, 0, 10): depth 10 s, up component +10 s: y = w (top edge).
  const Clip zenith = clip_of(c, {0, 0, 10});
  EXPECT_NEAR(zenith[3], 10 * s, kTol);
  EXPECT_NEAR(zenith[1], 10 * s, kTol);
  EXPECT_NEAR(zenith[0], 0, kTol);
}

TEST(CameraMatrices, PitchStraightUpKeepsAWellDefinedBasis) {
  // Pitch pi/2: forward (0, 0, 1), right (0, -1, 0) as at yaw 0, up = right x forward = (-1, 0, 0):
  // the top of the image points behind the yaw direction.
  Camera c = square_camera();
  c.pitch = kPi / 2;
  expect_clip(c, {0, 0, 10}, {0, 0, 810.0 / 99, 10});
  expect_clip(c, {-10, 0, 10}, {0, 10, 810.0 / 99, 10});
  expect_clip(c, {0, -10, 10}, {10, 0, 810.0 / 99, 10});
}

TEST(CameraMatrices, RollTurnsTheImageClockwise) {
  // Roll pi/2: right = up0 = (0, 0, 1), up = right x forward = (0, 0, 1) x (1, 0, 0) = (0, 1, 0).
  // What is above the camera appears at the right edge; what is to its left at the top edge.
  Camera c = square_camera();
  c.roll = kPi / 2;
  expect_clip(c, {10, 0, 10}, {10, 0, 810.0 / 99, 10});
  expect_clip(c, {10, 10, 0}, {0, 10, 810.0 / 99, 10});
  expect_clip(c, {10, -10, 0}, {0, -10, 810.0 / 99, 10});
}

TEST(CameraMatrices, OrthographicBox) {
  // Eye (0, 0, 10), yaw 0, 20 m x 10 m, near 1, far 51 (f - n = 50):
  // P = [[2/20, 0, 0, 0], [0, 2/10, 0, 0], [0, 0, -2/50, -52/50], [0, 0, 0, 1]].
  Camera c;
  c.position = {0, 0, 10};
  c.projection = Projection::orthographic;
  c.ortho_width = 20, c.ortho_height = 10;
  c.near = 1, c.far = 51;
  expect_matrix(*projection_matrix(c), {{{0.1, 0, 0, 0}, {0, 0.2, 0, 0}, {0, 0, -0.04, -1.04}, {0, 0, 0, 1}}});
  // Depth 1: z = 0.04 - 1.04 = -1. Depth 51: z = 2.04 - 1.04 = +1. Always w = 1.
  expect_clip(c, {1, 0, 10}, {0, 0, -1, 1});
  expect_clip(c, {51, 0, 10}, {0, 0, 1, 1});
  // (26, -10, 15): 10 m right, 5 m up, depth 26: the box's corner at mid-depth (1, 1, 0, 1).
  expect_clip(c, {26, -10, 15}, {1, 1, 0, 1});
  expect_clip(c, {26, 10, 5}, {-1, -1, 0, 1});
  // No perspective: the same lateral offset far away is still on the edge; depth 50 gives
  // z = 0.04 * 50 - 1.04 = 0.96.
  expect_clip(c, {50, -10, 10}, {1, 0, 0.96, 1});
  // An orthographic box from near = 0 keeps n = 0: the eye itself is at depth -1.
  c.near = 0, c.far = 50;
  expect_matrix(*projection_matrix(c), {{{0.1, 0, 0, 0}, {0, 0.2, 0, 0}, {0, 0, -0.04, -1}, {0, 0, 0, 1}}});
  expect_clip(c, {0, 0, 10}, {0, 0, -1, 1});
}

TEST(CameraMatrices, NearZeroUsesFarTimes1e7) {
  // near = 0, far = 100: the projection of n = 100 * 1e-7 = 1e-5:
  // -(f+n)/(f-n) = -1.00000020000002, -2fn/(f-n) = -2.00000020000002e-05.
  Camera c = square_camera();
  c.near = 0;
  const Matrix4 p = *projection_matrix(c);
  EXPECT_NEAR(p[2][2], -1.00000020000002, 1e-14);
  EXPECT_NEAR(p[2][3], -2.00000020000002e-05, 1e-18);
  Camera same = c;
  same.near = 100 * 1e-7;
  EXPECT_EQ(p, *projection_matrix(same));
  for (const auto& row : p)
    for (double v : row) EXPECT_TRUE(std::isfinite(v));
  // NDC depth -1 at depth 1e-5, +1 at depth 100.
  const Clip near = clip_of(c, {1e-5, 0, 0});
  EXPECT_NEAR(near[2] / near[3], -1, 1e-9);
  const Clip far = clip_of(c, {100, 0, 0});
  EXPECT_NEAR(far[2] / far[3], 1, 1e-12);
}

TEST(CameraMatrices, OmnidirectionalHasAFixedViewAndNoProjection) {
  // hfov 2 pi: the view ignores yaw, pitch and roll (looking along +x, z up): rows right (0,-1,0),
  // up (0,0,1), -forward (-1,0,0); translations -(-2) = 2, -3, -(-1) = 1 for the eye (1, 2, 3).
  Camera c;
  c.hfov = kTwoPi;
  c.position = {1, 2, 3};
  c.yaw = 1.0, c.pitch = 0.5, c.roll = -0.7;
  expect_matrix(view_matrix(c), {{{0, -1, 0, 2}, {0, 0, 1, -3}, {-1, 0, 0, 1}, {0, 0, 0, 1}}}, 0.0);
  EXPECT_FALSE(projection_matrix(c).has_value());
}

TEST(CameraMatrices, TransformAppliesTheMatrixToAColumnVector) {
  // m * (1, 2, 3, 1) for m = [[1,2,3,4],[5,6,7,8],[9,10,11,12],[0,0,0,2]]:
  // (1+4+9+4, 5+12+21+8, 9+20+33+12, 2) = (18, 46, 74, 2).
  const Matrix4 m = {{{1, 2, 3, 4}, {5, 6, 7, 8}, {9, 10, 11, 12}, {0, 0, 0, 2}}};
  EXPECT_EQ(transform(m, {1, 2, 3}), (Clip{18, 46, 74, 2}));
  // multiply is a * b, not b * a: with a swap matrix s on the left, rows swap; on the right, columns.
  const Matrix4 s = {{{0, 1, 0, 0}, {1, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
  EXPECT_EQ(multiply(s, m)[0], (std::array<double, 4>{5, 6, 7, 8}));
  EXPECT_EQ(multiply(m, s)[0], (std::array<double, 4>{2, 1, 3, 4}));
}

// --- Property: the matrices and the view volume agree -----------------------------------------

std::uint64_t property_seed() {
  if (const char* s = std::getenv("CULLCHECK_SEED")) return std::strtoull(s, nullptr, 10);
  return 20261125;
}

TEST(CameraMatricesProperty, ClipTestAgreesWithViewVolumeAwayFromBoundaries) {
  const std::uint64_t seed = property_seed();
  std::cout << "seed " << seed << " (replay: CULLCHECK_SEED=" << seed
            << " core_test --gtest_filter=CameraMatricesProperty.*)\n";
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  std::size_t inside = 0, outside = 0, skipped = 0, failures = 0, total = 0;
  for (int k = 0; k < 20000 && failures < 10; ++k) {
    Camera c;
    c.position = {uniform(-1000, 1000), uniform(-1000, 1000), uniform(0, 100)};
    c.yaw = uniform(0, kTwoPi);
    c.pitch = uniform(-kPi / 2, kPi / 2);
    c.roll = uniform(-kPi, kPi);
    const bool ortho = k % 4 == 0;
    if (ortho) {
      c.projection = Projection::orthographic;
      c.ortho_width = uniform(0.5, 200);
      c.ortho_height = uniform(0.5, 200);
      c.near = k % 8 == 0 ? 0.0 : uniform(0, 10);
      c.far = c.near + uniform(1, 1000);
    } else {
      c.hfov = uniform(0.05, 3.0);
      c.vfov = uniform(0.05, 3.0);
      c.near = uniform(0.01, 10);
      c.far = c.near * std::exp(uniform(std::log(2.0), std::log(1e4)));
    }
    validate(c);
    const CameraBasis b = basis_of(c);
    const ViewVolume volume(c);
    const Matrix4 pv = multiply(*projection_matrix(c), view_matrix(c));
    for (int j = 0; j < 20; ++j) {
      // Depths around the near and far planes as often as in between, offsets up to 1.3 times the
      // half-extent at that depth: about half the points fall inside.
      const int mode = j % 3;
      const double d = mode == 0 ? c.near + uniform(-0.5, 0.5) * std::max(c.near, 0.1)
                       : mode == 1 ? c.far * uniform(0.9, 1.1)
                                   : uniform(-0.1, 1.1) * c.far;
      const double half_w = ortho ? c.ortho_width / 2 : std::abs(d) * std::tan(c.hfov / 2);
      const double half_h = ortho ? c.ortho_height / 2 : std::abs(d) * std::tan(c.vfov / 2);
      const Vec3 p = c.position + b.forward * d + b.right * (half_w * uniform(-1.3, 1.3)) + b.up * (half_h * uniform(-1.3, 1.3));
      const Clip q = transform(pv, p);
      const double w = q[3];
      const double margin = std::min({w - std::abs(q[0]), w - std::abs(q[1]), w - std::abs(q[2])});
      ++total;
      if (std::abs(w) < 1e-12 || std::abs(margin) <= 1e-9 * std::abs(w)) {
        ++skipped;
        continue;
      }
      const bool by_clip = w > 0 && margin >= 0;
      const bool by_volume = volume.contains(p);
      (by_clip ? inside : outside) += 1;
      if (by_clip != by_volume) {
        ++failures;
        ADD_FAILURE() << "seed " << seed << " camera " << k << " point " << j << ": clip says "
                      << (by_clip ? "inside" : "outside") << ", ViewVolume says " << (by_volume ? "inside" : "outside")
                      << "; clip (" << q[0] << ", " << q[1] << ", " << q[2] << ", " << q[3] << "), point (" << p.x << ", "
                      << p.y << ", " << p.z << "), camera " << camera_to_json_text(c);
      }
    }
  }
  std::cout << total << " points: " << inside << " inside, " << outside << " outside, " << skipped
            << " within 1e-9 of a boundary (skipped)\n";
  // The property has power only if both answers are common and few points are skipped.
  EXPECT_GT(inside, total / 5) << "seed " << seed;
  EXPECT_GT(outside, total / 5) << "seed " << seed;
  EXPECT_LT(skipped, total / 100) << "seed " << seed;
}

}  // namespace
}  // namespace cullcheck
