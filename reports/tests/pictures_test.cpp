// Pictures of a frame: pixels whose colour follows from the scene by hand, and the PNG round trip.
#include "reports/pictures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {
namespace {

namespace fs = std::filesystem;
namespace colours = map_colours;

Rgb darker(Rgb c) { return {std::uint8_t(c.r * 3 / 5), std::uint8_t(c.g * 3 / 5), std::uint8_t(c.b * 3 / 5)}; }

// CULLCHECK_PICTURES_DIR=<dir> keeps the pictures there, to look at them.
const char* kept_dir() { return std::getenv("CULLCHECK_PICTURES_DIR"); }

fs::path scratch_dir() {
  const fs::path dir = kept_dir() ? fs::path(kept_dir()) : fs::temp_directory_path() / ("cullcheck_pictures_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// Eye at (0, 0, 1.7) looking east (60 x 60 degrees): A ahead (visible, in the PVS); B hidden
// behind A (culled); C beside, seen but culled (missed); D hidden behind A but in the PVS
// (over-estimate); E behind the eye (culled); a wall mesh W far to the right of the view, in the
// PVS (over-estimate), a line in plan.
struct Frame {
  Scene scene;
  Camera camera;
  std::vector<ObjectId> pvs{1, 4, 6};
};

Frame tiny_frame() {
  Frame f;
  f.scene.buildings = {box_building(1, 10, -3, 12, 3, 10), box_building(2, 20, -2, 22, 2, 8), box_building(3, 20, 5, 22, 8, 8),
                       box_building(4, 30, -1, 32, 1, 5), box_building(5, -20, -3, -15, 3, 10)};
  MeshObject wall;
  wall.id = 6;
  wall.vertices = {{5, -20, 0}, {5, -12, 0}, {5, -12, 6}, {5, -20, 6}};
  wall.triangles = {{0, 1, 2}, {0, 2, 3}};
  validate_and_finish(wall);
  f.scene.meshes = {wall};
  f.camera.position = {0, 0, 1.7};
  f.camera.hfov = f.camera.vfov = kPi / 3;
  f.camera.width = 160, f.camera.height = 120;
  return f;
}

Rgb map_at(const RgbImage& map, const MapFrame& frame, Vec2 p) {
  int i, j;
  frame.pixel_of(p, i, j);
  return map.at(i, j);
}

TEST(Pictures, TopDownMapAndFrameImageShowTheMissedObjectInRed) {
  const Frame f = tiny_frame();
  const oracle::Oracle oracle(f.scene);
  const oracle::OracleResult seen = oracle.rays().witness(f.camera);
  ASSERT_EQ(seen.witnessed, (std::vector<ObjectId>{1, 3}));
  const std::vector<ObjectId> missed{3};
  const std::vector<oracle::WitnessRay> rays{seen.witnesses.at(3)};

  constexpr int kSize = 400;
  const RgbImage map = top_down_map(f.scene, f.camera, f.pvs, seen.witnessed, missed, rays, kSize);
  const MapFrame frame = map_frame(f.scene, f.camera, kSize);
  EXPECT_EQ(map.width, kSize);  // the scene is wider (x) than deep (y)
  EXPECT_EQ(map.height, frame.height);
  EXPECT_LT(map.height, kSize);
  EXPECT_EQ(map_at(map, frame, {21, 6.5}), colours::kMissed);      // C's centre
  EXPECT_EQ(map_at(map, frame, {11, 0}), colours::kVisible);       // A
  EXPECT_EQ(map_at(map, frame, {21, 0}), colours::kCulled);        // B
  EXPECT_EQ(map_at(map, frame, {31, 0}), colours::kOverEstimate);  // D
  EXPECT_EQ(map_at(map, frame, {-17.5, 0}), colours::kCulled);     // E
  EXPECT_EQ(map_at(map, frame, {5, -16}), darker(colours::kOverEstimate));  // W, edge-on: all outline
  EXPECT_EQ(map_at(map, frame, {25, 0}), colours::kViewVolume);    // in the frustum, between buildings
  EXPECT_EQ(map_at(map, frame, {-5, 0}), colours::kBackground);    // behind the eye
  EXPECT_EQ(map_at(map, frame, {33.5, 0}), colours::kBackground);  // in the frustum, beyond the scene's bounds
  EXPECT_EQ(map_at(map, frame, {0, 0}), colours::kEye);
  // The witness ray, half way from the eye to its hit on C.
  const oracle::WitnessRay& w = rays.front();
  EXPECT_EQ(map_at(map, frame, plan(w.origin + (w.hit_point - w.origin) * 0.5)), colours::kWitnessRay);

  const oracle::IdImage full = oracle.pixels().render(f.camera);
  const oracle::PixelComparison cmp = oracle.pixels().compare(full, f.camera, f.pvs);
  ASSERT_EQ(cmp.misdrawn_by_object.size(), 1u);
  ASSERT_GT(cmp.misdrawn_by_object.at(3), 0u);
  const RgbImage picture = frame_image(full, cmp);
  ASSERT_EQ(picture.width, 160);
  ASSERT_EQ(picture.height, 120);
  std::uint64_t red = 0;
  for (int j = 0; j < 120; ++j)
    for (int i = 0; i < 160; ++i) {
      const ObjectId id = full.at(i, j);
      const Rgb expected = id == 3 ? kMisdrawn : id == oracle::kNoObject ? kFrameBackground : false_colour(id);
      ASSERT_EQ(picture.at(i, j), expected) << i << ", " << j;
      red += id == 3;
    }
  EXPECT_EQ(red, cmp.misdrawn_pixels);
  EXPECT_NE(false_colour(1), false_colour(2));
  EXPECT_EQ(false_colour(1), false_colour(1));

  const fs::path dir = scratch_dir();
  const std::string map_png = (dir / "map.png").string(), frame_png = (dir / "frame.png").string();
  write_png(map, map_png);
  write_png(picture, frame_png);
  EXPECT_FALSE(fs::exists(map_png + ".tmp"));
  const RgbImage map_back = read_png(map_png), frame_back = read_png(frame_png);
  EXPECT_EQ(map_back.width, map.width);
  EXPECT_EQ(map_back.height, map.height);
  EXPECT_EQ(map_back.rgb, map.rgb);
  EXPECT_EQ(frame_back.width, 160);
  EXPECT_EQ(frame_back.height, 120);
  EXPECT_EQ(frame_back.rgb, picture.rgb);
  std::printf("pictures: %s (%d x %d), %s (%d x %d)\n", map_png.c_str(), map.width, map.height, frame_png.c_str(),
              picture.width, picture.height);
  EXPECT_THROW(write_png(map, (dir / "no_such_dir" / "map.png").string()), InputError);
  EXPECT_THROW(read_png((dir / "missing.png").string()), InputError);
  if (!kept_dir()) fs::remove_all(dir);
}

TEST(Pictures, OrthographicTopDownFootprintIsItsRectangle) {
  // Two boxes 60 m apart; the camera looks straight down on the 20 m x 10 m rectangle
  // |x| <= 10, |y| <= 5 around the origin.
  Scene scene;
  scene.buildings = {box_building(1, -32, -12, -28, 12, 10), box_building(2, 28, -12, 32, 12, 10)};
  Camera c;
  c.position = {0, 0, 50};
  c.pitch = -kPi / 2;
  c.projection = Projection::orthographic;
  c.ortho_width = 10;  // across (right = -y at yaw 0)
  c.ortho_height = 20;  // up the image (+x)
  c.near = 0, c.far = 100;
  const RgbImage map = top_down_map(scene, c, {}, {}, {}, {}, 640);
  const MapFrame frame = map_frame(scene, c, 640);
  EXPECT_EQ(map_at(map, frame, {9.5, 4.5}), colours::kViewVolume);
  EXPECT_EQ(map_at(map, frame, {-9.5, -4.5}), colours::kViewVolume);
  EXPECT_EQ(map_at(map, frame, {10.5, 0}), colours::kBackground);
  EXPECT_EQ(map_at(map, frame, {0, 5.5}), colours::kBackground);
  // Up the column through x = 0: the last pixel whose centre has y <= 5 is the footprint's edge.
  int i, j;
  frame.pixel_of({0, 0}, i, j);
  while (frame.centre_of(i, j - 1).y <= 5.0) --j;
  EXPECT_EQ(map.at(i, j), colours::kViewVolumeEdge);
  EXPECT_EQ(map.at(i, j + 1), colours::kViewVolume);
  EXPECT_EQ(map.at(i, j - 1), colours::kBackground);
  EXPECT_EQ(map_at(map, frame, {-30, 0}), colours::kCulled);
}

TEST(Pictures, FrameImageRefusesAComparisonOfAnotherResolution) {
  oracle::IdImage full;
  full.width = 4, full.height = 2;
  full.ids.assign(8, oracle::kNoObject);
  oracle::PixelComparison cmp;
  cmp.resolution = {2, 4};
  cmp.misdrawn_mask.assign(8, 0);
  EXPECT_THROW(frame_image(full, cmp), std::invalid_argument);
}

}  // namespace
}  // namespace cullcheck
