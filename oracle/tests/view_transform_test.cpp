// The oracle's own view transform against hand-computed projections (literal expected numbers),
// and against core/camera_matrices (what subjects receive) on many random cameras: two
// independent derivations of the same convention must agree.
//
// Replay one random camera: ORACLE_VIEW_SEED=<seed> oracle_test --gtest_filter='ViewTransform.*'
#include "oracle/view_transform.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "core/camera_matrices.hpp"
#include "oracle/splitmix64.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

constexpr double kTol = 1e-12;

Camera perspective(Vec3 eye, double yaw, double pitch, double roll, double hfov, double vfov) {
  Camera c;
  c.position = eye;
  c.yaw = yaw, c.pitch = pitch, c.roll = roll;
  c.hfov = hfov, c.vfov = vfov;
  c.near = 0.1, c.far = 1000.0;
  return c;
}

// Normalised device coordinates (x / w, y / w) and the depth z.
struct Ndc {
  double x, y, depth;
};
Ndc ndc(const ViewTransform& v, Vec3 p) {
  const Clip c = v.clip(p);
  return {c.x / c.w, c.y / c.w, c.z};
}

TEST(ViewTransform, PointStraightAheadIsAtTheImageCentreAtItsDistance) {
  const ViewTransform v(perspective({1, 2, 3}, 0, 0, 0, 90 * kDeg, 60 * kDeg));
  const Clip c = v.clip({11, 2, 3});
  EXPECT_NEAR(c.x, 0.0, kTol);
  EXPECT_NEAR(c.y, 0.0, kTol);
  EXPECT_NEAR(c.z, 10.0, kTol);
  EXPECT_NEAR(c.w, 10.0, kTol);
  EXPECT_TRUE(v.contains({11, 2, 3}));
  EXPECT_FALSE(v.contains({-9, 2, 3}));  // behind the eye
}

TEST(ViewTransform, HorizontalHalfAngleEdgesMapToPlusAndMinusOne) {
  // hfov 90 degrees: tan 45 = 1, so a point 10 m ahead and 10 m to the side is on the edge.
  // Yaw 0 looks along +x, so the right of the image is world -y.
  const ViewTransform v(perspective({1, 2, 3}, 0, 0, 0, 90 * kDeg, 60 * kDeg));
  EXPECT_NEAR(ndc(v, {11, -8, 3}).x, 1.0, kTol);   // right edge
  EXPECT_NEAR(ndc(v, {11, 12, 3}).x, -1.0, kTol);  // left edge
  EXPECT_TRUE(v.contains({11, -7.999, 3}));
  EXPECT_FALSE(v.contains({11, -8.001, 3}));
  EXPECT_TRUE(v.contains({11, 11.999, 3}));
  EXPECT_FALSE(v.contains({11, 12.001, 3}));
}

TEST(ViewTransform, VerticalHalfAngleEdgesMapToPlusAndMinusOne) {
  // vfov 60 degrees: the top edge 10 m ahead is 10 tan 30 = 5.7735026918962573 m up.
  const ViewTransform v(perspective({1, 2, 3}, 0, 0, 0, 90 * kDeg, 60 * kDeg));
  EXPECT_NEAR(ndc(v, {11, 2, 3 + 5.7735026918962573}).y, 1.0, 1e-9);
  EXPECT_NEAR(ndc(v, {11, 2, 3 - 5.7735026918962573}).y, -1.0, 1e-9);
  EXPECT_TRUE(v.contains({11, 2, 3 + 5.77}));
  EXPECT_FALSE(v.contains({11, 2, 3 + 5.78}));
  EXPECT_FALSE(v.contains({11, 2, 3 - 5.78}));
}

TEST(ViewTransform, YawTurnsTheViewCounterClockwiseFromEast) {
  // Yaw 90 degrees looks north (+y); the image's right is then east (+x).
  const ViewTransform v(perspective({0, 0, 0}, 90 * kDeg, 0, 0, 90 * kDeg, 90 * kDeg));
  const Ndc ahead = ndc(v, {0, 10, 0});
  EXPECT_NEAR(ahead.x, 0.0, kTol);
  EXPECT_NEAR(ahead.depth, 10.0, kTol);
  EXPECT_NEAR(ndc(v, {5, 10, 0}).x, 0.5, kTol);
}

TEST(ViewTransform, PositivePitchLooksUp) {
  // Pitch 30 degrees: a horizontal point 1 m ahead is 0.5 m below the view axis and 0.866 m
  // along it, so at y = -0.5 / 0.8660254 = -tan 30 = -0.57735026918962573 (vfov 90: tan 45 = 1).
  const ViewTransform v(perspective({0, 0, 0}, 0, 30 * kDeg, 0, 90 * kDeg, 90 * kDeg));
  const Ndc p = ndc(v, {1, 0, 0});
  EXPECT_NEAR(p.x, 0.0, kTol);
  EXPECT_NEAR(p.y, -0.57735026918962573, kTol);
  EXPECT_NEAR(p.depth, 0.86602540378443865, kTol);
  EXPECT_NEAR(v.forward().z, 0.5, kTol);
}

TEST(ViewTransform, PositiveRollTurnsTheImageClockwise) {
  // Unrolled, a point above the view axis is at (0, 0.5) and a point to the right at (0.5, 0).
  // Turning the image clockwise by 90 degrees moves top to right and right to bottom.
  const Vec3 above{10, 0, 5}, right{10, -5, 0};
  const ViewTransform level(perspective({0, 0, 0}, 0, 0, 0, 90 * kDeg, 90 * kDeg));
  EXPECT_NEAR(ndc(level, above).y, 0.5, kTol);
  EXPECT_NEAR(ndc(level, right).x, 0.5, kTol);

  const ViewTransform plus(perspective({0, 0, 0}, 0, 0, 90 * kDeg, 90 * kDeg, 90 * kDeg));
  EXPECT_NEAR(ndc(plus, above).x, 0.5, kTol);
  EXPECT_NEAR(ndc(plus, above).y, 0.0, kTol);
  EXPECT_NEAR(ndc(plus, right).x, 0.0, kTol);
  EXPECT_NEAR(ndc(plus, right).y, -0.5, kTol);

  const ViewTransform minus(perspective({0, 0, 0}, 0, 0, -90 * kDeg, 90 * kDeg, 90 * kDeg));
  EXPECT_NEAR(ndc(minus, above).x, -0.5, kTol);
  EXPECT_NEAR(ndc(minus, above).y, 0.0, kTol);
  EXPECT_NEAR(ndc(minus, right).x, 0.0, kTol);
  EXPECT_NEAR(ndc(minus, right).y, 0.5, kTol);
}

TEST(ViewTransform, OrthographicBoxLookingStraightDown) {
  // Pitch -90 degrees from yaw 0: the view direction is -z, the image's right stays world -y and
  // its up becomes world +x. A 20 x 10 m box: x_ndc = 2 (p . right) / 20, y_ndc = 2 (p . up) / 10.
  const Camera c = ortho_camera({0, 0, 10}, 0, -90 * kDeg, 20, 10);
  const ViewTransform v(c);
  const Clip corner = v.clip({5, -10, 0});
  EXPECT_NEAR(corner.x, 1.0, kTol);
  EXPECT_NEAR(corner.y, 1.0, kTol);
  EXPECT_NEAR(corner.z, 10.0, kTol);
  EXPECT_EQ(corner.w, 1.0);
  EXPECT_NEAR(v.clip({-2.5, 5, 3}).x, -0.5, kTol);
  EXPECT_NEAR(v.clip({-2.5, 5, 3}).y, -0.5, kTol);
  EXPECT_TRUE(v.contains({4.9, -9.9, 0}));
  EXPECT_FALSE(v.contains({5.1, 0, 0}));
  EXPECT_FALSE(v.contains({0, 10.1, 0}));
  EXPECT_FALSE(v.contains({0, 0, 11}));  // behind the eye plane (near = 0)
  const Vec3 p = v.near_point_at(1, 1);
  EXPECT_NEAR(p.x, 5.0, kTol);
  EXPECT_NEAR(p.y, -10.0, kTol);
  EXPECT_NEAR(p.z, 10.0, kTol);
}

TEST(ViewTransform, NearAndFarBoundTheDepth) {
  Camera c = perspective({0, 0, 0}, 0, 0, 0, 90 * kDeg, 90 * kDeg);
  c.near = 2.0, c.far = 50.0;
  const ViewTransform v(c);
  EXPECT_FALSE(v.contains({1.999, 0, 0}));
  EXPECT_TRUE(v.contains({2.0, 0, 0}));
  EXPECT_TRUE(v.contains({50.0, 0, 0}));
  EXPECT_FALSE(v.contains({50.001, 0, 0}));
}

TEST(ViewTransform, OmnidirectionalIsTheBallOfRadiusFar) {
  Camera c = omni_camera({1, 1, 1});
  c.far = 10.0;
  c.yaw = 1.0, c.pitch = 0.5, c.roll = 0.3;  // ignored
  const ViewTransform v(c);
  EXPECT_TRUE(v.contains({1, 1, 11}));
  EXPECT_TRUE(v.contains({-8.99, 1, 1}));
  EXPECT_FALSE(v.contains({1, 11.01, 1}));
  EXPECT_TRUE(v.may_meet({{10.9, 1, 1}, {20, 2, 2}}));
  EXPECT_FALSE(v.may_meet({{11.1, 1, 1}, {20, 2, 2}}));
}

TEST(ViewTransform, RaysThroughTheImageComeFromTheInverse) {
  const ViewTransform v(perspective({0, 0, 0}, 0, 0, 0, 90 * kDeg, 60 * kDeg));
  const Vec3 centre = v.direction_through(0, 0);
  EXPECT_NEAR(centre.x, 1.0, kTol);
  EXPECT_NEAR(centre.y, 0.0, kTol);
  EXPECT_NEAR(centre.z, 0.0, kTol);
  const Vec3 right = v.direction_through(1, 0);  // 45 degrees to the right: (1, -1, 0) / sqrt 2
  EXPECT_NEAR(right.x, 0.70710678118654752, kTol);
  EXPECT_NEAR(right.y, -0.70710678118654752, kTol);
  EXPECT_NEAR(right.z, 0.0, kTol);
  const Vec3 top = v.direction_through(0, 1);  // 30 degrees up
  EXPECT_NEAR(top.x, 0.86602540378443865, kTol);
  EXPECT_NEAR(top.z, 0.5, kTol);
  double t0 = 0, t1 = 0;
  ASSERT_TRUE(v.extent(right, t0, t1));
  EXPECT_NEAR(t0, 0.1 * 1.4142135623730951, 1e-12);
  EXPECT_NEAR(t1, 1000 * 1.4142135623730951, 1e-9);
  EXPECT_FALSE(v.extent({0, 1, 0}, t0, t1));  // 90 degrees to the left
}

// Two derivations of one convention: core/camera_matrices (basis vectors, what subjects get)
// and the oracle's product of elementary rotations.
Camera random_camera(SplitMix64& rng) {
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.unit(); };
  Camera c;
  c.position = {uniform(-1e4, 1e4), uniform(-1e4, 1e4), uniform(0, 300)};
  c.yaw = uniform(-10, 10);
  c.pitch = uniform(-kPi / 2, kPi / 2);
  c.roll = uniform(-kPi, kPi);
  c.near = uniform(0.01, 2), c.far = c.near + uniform(10, 5000);
  if (rng.next() % 4 == 0) {
    c.projection = Projection::orthographic;
    c.ortho_width = uniform(1, 500), c.ortho_height = uniform(1, 500);
  } else {
    c.hfov = uniform(0.01, kPi - 0.01), c.vfov = uniform(0.01, kPi - 0.01);
  }
  return c;
}

void check_agreement(std::uint64_t seed) {
  SplitMix64 rng(seed);
  const Camera c = random_camera(rng);
  const std::string replay = "replay: ORACLE_VIEW_SEED=" + std::to_string(seed) + " oracle_test --gtest_filter='ViewTransform.*'";
  const ViewTransform oracle_view(c);
  const Matrix4 core_view = view_matrix(c);
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < 4; ++k)
      ASSERT_NEAR(oracle_view.view()[r][k], core_view[r][k], 1e-9 * (1 + std::abs(core_view[r][k]))) << "view[" << r << "][" << k << "]\n" << replay;
  const Matrix4 core_vp = multiply(*projection_matrix(c), core_view);
  for (int i = 0; i < 20; ++i) {
    const Vec3 p = c.position + Vec3{rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5} * 200.0;
    const std::array<double, 4> k = transform(core_vp, p);
    const Clip o = oracle_view.clip(p);
    if (c.orthographic()) {
      ASSERT_NEAR(o.x, k[0], 1e-9 * (1 + std::abs(k[0]))) << replay;
      ASSERT_NEAR(o.y, k[1], 1e-9 * (1 + std::abs(k[1]))) << replay;
      const double depth = (k[2] * (c.far - c.near) + (c.far + c.near)) / 2;  // OpenGL's z back to metres
      ASSERT_NEAR(o.z, depth, 1e-7 * (1 + std::abs(depth))) << replay;
    } else {
      ASSERT_NEAR(o.w, k[3], 1e-9 * (1 + std::abs(k[3]))) << replay;  // both: w = depth
      ASSERT_NEAR(o.x, k[0], 1e-9 * (1 + std::abs(k[0]))) << replay;
      ASSERT_NEAR(o.y, k[1], 1e-9 * (1 + std::abs(k[1]))) << replay;
    }
  }
}

TEST(ViewTransform, AgreesWithCoreCameraMatricesOnRandomCameras) {
  if (const char* seed = std::getenv("ORACLE_VIEW_SEED")) {
    check_agreement(std::strtoull(seed, nullptr, 10));
    return;
  }
  for (std::uint64_t seed = 1; seed <= 2000; ++seed) {
    check_agreement(seed);
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace cullcheck::oracle
