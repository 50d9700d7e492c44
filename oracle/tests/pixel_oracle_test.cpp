// The pixel oracle on scenes whose pixel counts can be worked out by hand, against a brute-force
// PVS-only render, and across thread counts.
#include "oracle/pixel_oracle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "core/errors.hpp"
#include "oracle/oracle.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

std::uint64_t count(const IdImage& image, ObjectId id) { return std::uint64_t(std::count(image.ids.begin(), image.ids.end(), id)); }

// Looking straight down from 50 m over the square |x|, |y| <= 10 at 200 x 200 pixels: 0.1 m each.
Camera top_down_camera() {
  Camera c = ortho_camera({0, 0, 50}, 0.0, -kPi / 2, 20, 20);
  c.width = c.height = 200;
  return c;
}

void expect_witnesses_replay(const RayOracle& rays, const PixelComparison& cmp, const Camera& camera) {
  for (const auto& [id, w] : cmp.witnesses) {
    EXPECT_EQ(w.source, RaySource::pixel);
    const RayOracle::Replay replay = rays.replay(w, camera);
    ASSERT_TRUE(replay.hit.has_value()) << describe(w);
    EXPECT_EQ(*replay.hit, id) << describe(w);
    EXPECT_TRUE(replay.in_view_volume) << describe(w);
    EXPECT_NEAR(replay.t_hit, w.t_hit, 1e-9 * (1 + w.t_hit));
  }
  for (const auto& [id, pixels] : cmp.misdrawn_by_object) EXPECT_TRUE(cmp.witnesses.count(id)) << "no witness for " << id;
}

TEST(PixelOracle, TopDownOrthographicBoxCoversExactlyOneHundredByOneHundredPixels) {
  const Scene scene = scene_of({box_building(1, -5, -5, 5, 5, 10)});
  const Oracle oracle(scene);
  const PixelOracle& pixels = oracle.pixels();
  const Camera c = top_down_camera();
  const IdImage full = pixels.render(c);
  ASSERT_EQ(full.width, 200);
  ASSERT_EQ(full.height, 200);
  EXPECT_EQ(count(full, 1), 10'000u);
  EXPECT_EQ(count(full, kNoObject), 30'000u);

  const PixelComparison culled = pixels.compare(c, {});
  EXPECT_EQ(culled.resolution, (Resolution{200, 200}));
  EXPECT_EQ(culled.misdrawn_pixels, 10'000u);
  EXPECT_EQ(culled.largest_blob, 10'000u);
  EXPECT_EQ(culled.blobs, 1u);
  EXPECT_EQ(culled.misdrawn_by_object, (std::map<ObjectId, std::uint64_t>{{1, 10'000}}));
  EXPECT_EQ(std::count(culled.misdrawn_mask.begin(), culled.misdrawn_mask.end(), 1), 10'000);
  EXPECT_EQ(count(culled.drawn, kNoObject), 40'000u);
  // The witness is the first misdrawn pixel in row-major order, (i, j) = (50, 50). Pitch -pi/2
  // at yaw 0 gives right = -y and up = +x, so its ray starts at eye + right * (-4.95) + up * 4.95
  // and meets the roof 40 m down.
  ASSERT_EQ(culled.witnesses.size(), 1u);
  const WitnessRay& w = culled.witnesses.at(1);
  EXPECT_NEAR(w.origin.x, 4.95, 1e-12);
  EXPECT_NEAR(w.origin.y, 4.95, 1e-12);
  EXPECT_NEAR(w.origin.z, 50.0, 1e-12);
  EXPECT_NEAR(w.t_hit, 40.0, 1e-9);
  EXPECT_NEAR(w.hit_point.z, 10.0, 1e-9);
  EXPECT_NEAR(w.direction.z, -1.0, 1e-15);
  EXPECT_FALSE(culled.misdrawn_mask[49 * 200 + 50]);
  EXPECT_FALSE(culled.misdrawn_mask[50 * 200 + 49]);
  EXPECT_TRUE(culled.misdrawn_mask[50 * 200 + 50]);
  expect_witnesses_replay(oracle.rays(), culled, c);

  const PixelComparison kept = pixels.compare(full, c, {1});
  EXPECT_EQ(kept.misdrawn_pixels, 0u);
  EXPECT_EQ(kept.largest_blob, 0u);
  EXPECT_EQ(kept.blobs, 0u);
  EXPECT_TRUE(kept.misdrawn_by_object.empty());
  EXPECT_TRUE(kept.witnesses.empty());
  EXPECT_EQ(kept.drawn, full);
}

TEST(PixelOracle, SeparateCulledBoxesAreSeparateBlobsAndTouchingOnesMerge) {
  // A and B (6 m x 6 m, 3,600 pixels each) 4 m apart; C fills the gap between them.
  const Scene scene = scene_of({box_building(1, -8, -3, -2, 3, 10), box_building(2, 2, -3, 8, 3, 10),
                                box_building(3, -2, -3, 2, 3, 10)});
  const RayOracle rays(scene);
  const PixelOracle pixels(rays);
  const Camera c = top_down_camera();
  const IdImage full = pixels.render(c);
  EXPECT_EQ(count(full, 1), 3'600u);
  EXPECT_EQ(count(full, 2), 3'600u);
  EXPECT_EQ(count(full, 3), 2'400u);
  const PixelComparison two = pixels.compare(full, c, {3});
  EXPECT_EQ(two.misdrawn_pixels, 7'200u);
  EXPECT_EQ(two.largest_blob, 3'600u);
  EXPECT_EQ(two.blobs, 2u);
  EXPECT_EQ(two.misdrawn_by_object, (std::map<ObjectId, std::uint64_t>{{1, 3'600}, {2, 3'600}}));
  EXPECT_EQ(two.witnesses.size(), 2u);
  const PixelComparison one = pixels.compare(full, c, {2, 3});
  EXPECT_EQ(one.misdrawn_pixels, 3'600u);
  EXPECT_EQ(one.blobs, 1u);
  const PixelComparison merged = pixels.compare(full, c, {});
  EXPECT_EQ(merged.misdrawn_pixels, 9'600u);
  EXPECT_EQ(merged.largest_blob, 9'600u);
  EXPECT_EQ(merged.blobs, 1u);
  expect_witnesses_replay(rays, merged, c);

  // Boxes meeting at a corner only: their pixels touch diagonally, which is not 4-connected.
  const Scene corner = scene_of({box_building(1, 0, 0, 2, 2, 10), box_building(2, 2, 2, 4, 4, 10)});
  const RayOracle corner_rays(corner);
  const PixelComparison diagonal = PixelOracle(corner_rays).compare(c, {});
  EXPECT_EQ(diagonal.misdrawn_pixels, 800u);
  EXPECT_EQ(diagonal.largest_blob, 400u);
  EXPECT_EQ(diagonal.blobs, 2u);
}

// From (0, 0, 10) looking east with tan(hfov / 2) = 1 and tan(vfov / 2) = 0.75 at 320 x 240: the
// front face x = 10 of box W (0 <= y <= 15, z <= 20) takes every ray of the left half (y = -10 u
// in (0, 10), z = 10 + 7.5 v in (2.5, 17.5)) and none of the right half. H stands behind W,
// wholly inside W's shadow.
Scene half_wall_scene() { return scene_of({box_building(1, 10, 0, 11, 15, 20), box_building(2, 30, 5, 32, 8, 10)}); }
Camera half_wall_camera() {
  Camera c = level_camera({0, 0, 10}, 0.0, kPi / 2, 2 * std::atan(0.75));
  c.width = 320, c.height = 240;
  return c;
}

TEST(PixelOracle, PerspectiveWallFillsExactlyTheLeftHalfOfTheImage) {
  const Scene scene = half_wall_scene();
  const RayOracle rays(scene);
  const PixelOracle pixels(rays);
  const Camera c = half_wall_camera();
  const IdImage full = pixels.render(c);
  for (int j = 0; j < 240; ++j)
    for (int i = 0; i < 320; ++i) ASSERT_EQ(full.at(i, j), i < 160 ? 1u : kNoObject) << i << ", " << j;
  // Pixel (0, 0) is the top-left one: left (+y) and up.
  const WitnessRay top_left = pixel_ray(c, 0, 0);
  EXPECT_GT(top_left.direction.y, 0);
  EXPECT_GT(top_left.direction.z, 0);
  EXPECT_NEAR(top_left.t_near * dot(top_left.direction, Vec3{1, 0, 0}), c.near, 1e-12);  // near along forward
  EXPECT_NEAR(top_left.t_far * top_left.direction.x, c.far, 1e-6);

  const PixelComparison culled = pixels.compare(full, c, {2});
  EXPECT_EQ(culled.misdrawn_pixels, 160u * 240u);
  EXPECT_EQ(culled.largest_blob, 160u * 240u);
  EXPECT_EQ(culled.blobs, 1u);
  expect_witnesses_replay(rays, culled, c);
  const std::vector<ObjectId> only_h{2};
  EXPECT_EQ(culled.drawn, pixels.render(c, &only_h));
  EXPECT_GT(count(culled.drawn, 2), 0u);  // H shows where W is not drawn

  // H culled, but hidden behind W: nothing is misdrawn.
  const PixelComparison hidden = pixels.compare(full, c, {1});
  EXPECT_EQ(hidden.misdrawn_pixels, 0u);
  EXPECT_EQ(hidden.drawn, full);
  EXPECT_EQ(pixels.compare(full, c, {1, 2}).misdrawn_pixels, 0u);
}

TEST(PixelOracle, WindowInAWallMeshShowsTheBoxBehindIt) {
  // Looking east through a 10 m x 10 m orthographic box at 100 x 100 pixels (0.1 m each): the wall
  // mesh at x = 10 fills the view except its 2 m x 2 m window (400 pixels); the box behind it
  // (|y| <= 3, z <= 10: 60 x 100 pixels) shows through the window only.
  const Opening window{4, 6, 4, 6};
  const MeshObject wall = wall_mesh(1, {10, -5, 0}, {0, 1, 0}, 10, 10, &window);
  const Scene scene = scene_of({box_building(2, 20, -3, 22, 3, 10)}, {wall});
  const RayOracle rays(scene);
  const PixelOracle pixels(rays);
  Camera c = ortho_camera({0, 0, 5}, 0.0, 0.0, 10, 10);
  c.width = c.height = 100;
  const IdImage full = pixels.render(c);
  EXPECT_EQ(count(full, 1), 9'600u);
  EXPECT_EQ(count(full, 2), 400u);
  EXPECT_EQ(count(full, kNoObject), 0u);

  const PixelComparison box_culled = pixels.compare(full, c, {1});
  EXPECT_EQ(box_culled.misdrawn_pixels, 400u);
  EXPECT_EQ(box_culled.largest_blob, 400u);
  EXPECT_EQ(box_culled.misdrawn_by_object, (std::map<ObjectId, std::uint64_t>{{2, 400}}));
  expect_witnesses_replay(rays, box_culled, c);
  const WitnessRay& w = box_culled.witnesses.at(2);
  EXPECT_NEAR(w.hit_point.x, 20.0, 1e-9);
  EXPECT_LT(std::abs(w.origin.y), 1.0);
  EXPECT_GT(w.origin.z, 4.0);
  EXPECT_LT(w.origin.z, 6.0);

  const PixelComparison wall_culled = pixels.compare(full, c, {2});
  EXPECT_EQ(wall_culled.misdrawn_pixels, 9'600u);
  EXPECT_EQ(wall_culled.largest_blob, 9'600u);  // the frame is one blob
  EXPECT_EQ(count(wall_culled.drawn, 2), 6'000u);  // the whole box, once the wall is not drawn
  expect_witnesses_replay(rays, wall_culled, c);

  const Scene closed = scene_of({box_building(2, 20, -3, 22, 3, 10)}, {wall_mesh(1, {10, -5, 0}, {0, 1, 0}, 10, 10)});
  const RayOracle closed_rays(closed);
  const IdImage closed_full = PixelOracle(closed_rays).render(c);
  EXPECT_EQ(count(closed_full, 1), 10'000u);
  EXPECT_EQ(PixelOracle(closed_rays).compare(closed_full, c, {1}).misdrawn_pixels, 0u);
}

TEST(PixelOracle, OmnidirectionalPanoramaWrapsAroundAzimuthZero) {
  // 360 x 180 pixels: one degree each; column i looks at azimuth i + 0.5 degrees.
  const Scene scene = scene_of({box_building(1, 10, -5, 15, 5, 20), box_building(2, -5, 10, 5, 15, 20),
                                box_building(3, -15, -5, -10, 5, 20), box_building(4, -5, -15, 5, -10, 20)});
  const RayOracle rays(scene);
  Camera c = omni_camera({0, 0, 1.7});
  c.width = 360, c.height = 180;
  const IdImage full = PixelOracle(rays).render(c);
  EXPECT_EQ(full.at(0, 90), 1u);    // azimuth 0.5 deg, elevation -0.5 deg
  EXPECT_EQ(full.at(359, 90), 1u);  // azimuth 359.5 deg
  EXPECT_EQ(full.at(90, 90), 2u);
  EXPECT_EQ(full.at(180, 90), 3u);
  EXPECT_EQ(full.at(270, 90), 4u);
  EXPECT_EQ(full.at(45, 90), kNoObject);  // between the boxes
  EXPECT_EQ(full.at(0, 0), kNoObject);    // straight up
  // Box 1 spans azimuths within atan(0.5) = 26.57 deg of 0: columns 0..26 and 333..359 (333.5 deg is 26.5 deg short of 360).
  for (int i = 0; i < 360; ++i) {
    const bool in_span = i <= 26 || i >= 333;
    EXPECT_EQ(full.at(i, 90) == 1u, in_span) << i;
  }
}

// A seeded city of boxes and window walls, every coordinate a multiple of 1/64 m so that it is
// exactly a float however the oracle's whole-metre float origin is chosen: a scene made of a
// subset of its objects then gives Embree exactly the same numbers.
Scene snapped_city(std::uint64_t seed, Camera& camera) {
  const RandomCity city = random_city(seed);
  auto snap = [](double v) { return std::round(v * 64) / 64; };
  Scene s;
  for (const Building& b : city.scene.buildings)
    s.buildings.push_back(box_building(b.id, snap(b.bounds.lo.x), snap(b.bounds.lo.y), snap(b.bounds.hi.x),
                                       snap(b.bounds.hi.y), snap(b.height)));
  const Opening window{2, 4, 1, 3};
  for (std::size_t k = 0; k < 6 && k < s.buildings.size(); ++k) {
    const Building& b = s.buildings[k];
    s.meshes.push_back(wall_mesh(ObjectId(10'000 + k), {b.bounds.lo.x - 1, b.bounds.lo.y, 0}, {0, 1, 0}, 6, 5, &window));
  }
  camera = city.camera;
  camera.position = {snap(camera.position.x), snap(camera.position.y), snap(camera.position.z)};
  camera.width = 160, camera.height = 120;
  return s;
}

TEST(PixelOracle, PvsOnlyPixelsEqualABruteForceRenderAndASceneOfThePvsAlone) {
  for (std::uint64_t seed : {31, 32, 33}) {
    Camera c;
    const Scene scene = snapped_city(seed, c);
    const RayOracle rays(scene);
    const PixelOracle pixels(rays);
    const IdImage full = pixels.render(c);
    const std::vector<ObjectId> ids = scene.ids();
    SplitMix64 rng(seed);
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<ObjectId> pvs;  // keep about half, a different half each time
      for (ObjectId id : ids)
        if (rng.unit() < 0.5) pvs.push_back(id);
      const PixelComparison cmp = pixels.compare(full, c, pvs);
      const IdImage brute = pixels.render(c, &pvs);
      EXPECT_EQ(cmp.drawn, brute) << "seed " << seed << " trial " << trial;
      std::uint64_t differing = 0;
      for (std::size_t p = 0; p < full.ids.size(); ++p) {
        differing += full.ids[p] != brute.ids[p];
        EXPECT_EQ(bool(cmp.misdrawn_mask[p]), full.ids[p] != brute.ids[p]) << "pixel " << p;
      }
      EXPECT_EQ(cmp.misdrawn_pixels, differing);
      expect_witnesses_replay(rays, cmp, c);
      // The filter against a scene of the PVS's objects alone.
      Scene alone;
      for (const Building& b : scene.buildings)
        if (std::binary_search(pvs.begin(), pvs.end(), b.id)) alone.buildings.push_back(b);
      for (const MeshObject& m : scene.meshes)
        if (std::binary_search(pvs.begin(), pvs.end(), m.id)) alone.meshes.push_back(m);
      const RayOracle alone_rays(alone);
      EXPECT_EQ(PixelOracle(alone_rays).render(c), brute) << "seed " << seed << " trial " << trial;
      // The comparison has something to compare: culling half the objects misdraws some pixels.
      EXPECT_GT(cmp.misdrawn_pixels, 0u) << "seed " << seed << " trial " << trial;
      EXPECT_FALSE(cmp.misdrawn_by_object.empty()) << "seed " << seed << " trial " << trial;
    }
  }
}

TEST(PixelOracle, ImagesDoNotDependOnTheThreadCount) {
  for (std::uint64_t seed : {40, 41, 42}) {  // seed % 3: the three kinds of random_city camera
    const RandomCity city = random_city(seed);
    const RayOracle rays(city.scene);
    const PixelOracle pixels(rays);
    const IdImage one = pixels.render(city.camera, nullptr, 1);
    EXPECT_EQ(pixels.render(city.camera, nullptr, 2), one);
    EXPECT_EQ(pixels.render(city.camera, nullptr, 3), one);
    std::vector<ObjectId> pvs = city.scene.ids();
    pvs.resize(pvs.size() / 2);
    const PixelComparison a = pixels.compare(one, city.camera, pvs, 1), b = pixels.compare(one, city.camera, pvs, 3);
    EXPECT_EQ(a.drawn, b.drawn);
    EXPECT_EQ(a.misdrawn_mask, b.misdrawn_mask);
    EXPECT_EQ(a.witnesses, b.witnesses);
    EXPECT_EQ(a.misdrawn_by_object, b.misdrawn_by_object);
    EXPECT_EQ(a.largest_blob, b.largest_blob);
  }
}

TEST(PixelOracle, RejectsARenderOfAnotherResolutionAndBadCameras) {
  const Scene scene = scene_of({box_building(1, -5, -5, 5, 5, 10)});
  const RayOracle rays(scene);
  const PixelOracle pixels(rays);
  const IdImage full = pixels.render(top_down_camera());
  Camera other = top_down_camera();
  other.width = 100;
  EXPECT_THROW(pixels.compare(full, other, {}), std::invalid_argument);
  Camera bad = top_down_camera();
  bad.ortho_width = -1;
  EXPECT_THROW(pixels.render(bad), InputError);
  // The default resolution: 320 columns and square pixels.
  Camera level = level_camera({0, 0, 1.7}, 0.0, kPi / 2, 2 * std::atan(0.75));
  const IdImage d = pixels.render(level);
  EXPECT_EQ(d.width, 320);
  EXPECT_EQ(d.height, 240);
}

// With an empty PVS every pixel that shows an object is misdrawn. (The render's speed is
// BM_PixelOracleDefaultCity's, in oracle_bench, not a test's.)
TEST(PixelOracle, EmptyPvsMisdrawsEveryPixelThatShowsAnObject) {
  const RandomCity city = random_city(5);
  const RayOracle rays(city.scene);
  const PixelOracle pixels(rays);
  Camera c = city.camera;
  c.width = 640, c.height = 480;
  const IdImage full = pixels.render(c);
  ASSERT_EQ(full.ids.size(), 640u * 480u);
  const PixelComparison cmp = pixels.compare(full, c, {});
  EXPECT_GT(cmp.misdrawn_pixels, 0u);
  EXPECT_EQ(cmp.misdrawn_pixels, full.ids.size() - count(full, kNoObject));
}

}  // namespace
}  // namespace cullcheck::oracle
