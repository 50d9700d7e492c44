// The page's map: which run's frame it shows, its data in report.json, and the picture drawn
// back from that data (pixels whose colour follows from the scene by hand).
#include "reports/html/frame_map.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/pictures.hpp"

namespace cullcheck::html {
namespace {

namespace fs = std::filesystem;

MethodRun run_with(const std::string& method, bool conservative, std::size_t missed, std::size_t overestimate) {
  MethodRun r;
  r.method = method;
  r.claims_conservative = conservative;
  FrameSnapshot s;
  s.frame = 10 * missed + overestimate;
  for (std::size_t k = 0; k < missed; ++k) s.missed.push_back(ObjectId(k + 1));
  s.overestimate = overestimate;
  r.snapshot = s;
  return r;
}

TEST(MapChoice, TheConservativeMethodThatMissedMostComesFirst) {
  PathVerification v;
  v.runs = {run_with("frustum", true, 0, 50), run_with("oh_is", false, 9, 0), run_with("delta_h_guarded", true, 2, 1),
            run_with("oh_os_conservative", true, 1, 3)};
  EXPECT_EQ(choose_map_run(v, "", "oh_os_conservative")->method, "delta_h_guarded");
  v.runs[2].snapshot->missed.clear();
  v.runs[3].snapshot->missed.clear();
  EXPECT_EQ(choose_map_run(v, "", "oh_os_conservative")->method, "oh_is") << "then any method that missed";
  v.runs[1].snapshot->missed.clear();
  EXPECT_EQ(choose_map_run(v, "", "oh_os_conservative")->method, "oh_os_conservative") << "then the reference";
  EXPECT_EQ(choose_map_run(v, "", "not_there")->method, "frustum") << "then the first run";
  EXPECT_EQ(choose_map_run(v, "oh_is", "oh_os_conservative")->method, "oh_is") << "the method asked for";
}

TEST(MapChoice, AMethodThatIsNotThereIsNamedWithTheOnesThatAre) {
  PathVerification v;
  v.runs = {run_with("frustum", true, 0, 5)};
  try {
    choose_map_run(v, "oh_oss", "");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("oh_oss is not a method of this run (frustum)"), std::string::npos) << e.what();
  }
  v.runs[0].snapshot.reset();
  EXPECT_EQ(choose_map_run(v, "", ""), nullptr);
}

TEST(FrameSnapshots, AFrameIsWorseWhenItMissedMoreThenWhenItOverEstimatedMore) {
  FrameSnapshot a, b;
  a.missed = {1};
  b.overestimate = 40;
  EXPECT_TRUE(worse_frame(a, b));
  EXPECT_FALSE(worse_frame(b, a));
  a.missed.clear();
  a.overestimate = 40;
  EXPECT_FALSE(worse_frame(a, b)) << "the first of equally bad frames is kept";
}

// Eye at the origin looking east: building 1 ahead (seen, in the PVS), 2 behind it (culled),
// 3 to the north-east (seen, culled: missed, with its witness ray), 4 behind 1 but in the PVS.
struct Fixture {
  Scene scene;
  MethodRun run;
};

Fixture fixture() {
  Fixture f;
  f.scene.buildings = {box_building(1, 10, -3, 12, 3, 10), box_building(2, 20, -2, 22, 2, 8), box_building(3, 20, 5, 22, 8, 8),
                       box_building(4, 30, -1, 32, 1, 5)};
  f.run.method = "straw_man";
  FrameSnapshot s;
  s.frame = 7;
  s.camera.position = {0, 0, 1.7};
  s.camera.hfov = s.camera.vfov = kPi / 3;
  s.pvs = {1, 4};
  s.seen = {1, 3};
  s.missed = {3};
  oracle::WitnessRay ray;
  ray.origin = {0, 0, 1.7};
  ray.hit_point = {20, 6, 4};
  s.witness_rays = {ray};
  s.overestimate = 1;
  f.run.snapshot = s;
  return f;
}

Rgb pixel_at(const RgbImage& image, const MapFrame& frame, Vec2 p) {
  int i, j;
  frame.pixel_of(p, i, j);
  return image.at(i, j);
}

TEST(MapPicture, DrawsTheReportsFrameBackFromItsData) {
  const Fixture f = fixture();
  const nlohmann::json map = map_json(f.run, "test");
  EXPECT_EQ(map["frame"], 7);
  EXPECT_EQ(map["missed"], nlohmann::json({3}));
  EXPECT_EQ(map["witness_rays"][0]["hit"], nlohmann::json({20.0, 6.0, 4.0}));
  const std::string png = map_png(f.scene, map, 400);
  const fs::path file = fs::temp_directory_path() / ("cullcheck_frame_map_test_" + std::to_string(::getpid()) + ".png");
  write_text_file_atomically(file.string(), png);
  const RgbImage image = read_png(file.string());
  fs::remove(file);
  const MapFrame frame = map_frame_of(map_extent(f.scene, map), 400);
  ASSERT_EQ(image.width, frame.width);
  ASSERT_EQ(image.height, frame.height);
  EXPECT_EQ(pixel_at(image, frame, {11, 0}), map_colours::kVisible);
  EXPECT_EQ(pixel_at(image, frame, {21, 0}), map_colours::kCulled);
  EXPECT_EQ(pixel_at(image, frame, {21, 6.5}), map_colours::kMissed);
  EXPECT_EQ(pixel_at(image, frame, {31, 0}), map_colours::kOverEstimate);
  EXPECT_EQ(pixel_at(image, frame, {5, 1.5}), map_colours::kWitnessRay) << "the witness ray from the eye to its hit";
}

TEST(MapPicture, TheExtentHoldsWhatWasSeenAndIsNeverASliver) {
  const Fixture f = fixture();
  const Box2 box = map_extent(f.scene, map_json(f.run, "test"), /*min_half_span=*/5.0);
  EXPECT_LE(box.lo.x, 0.0);
  EXPECT_GE(box.hi.x, 22.0);
  EXPECT_GE(box.hi.y, 8.0);
  const double w = box.hi.x - box.lo.x, h = box.hi.y - box.lo.y;
  EXPECT_GE(std::min(w, h), 0.6 * std::max(w, h) - 1e-9);
}

TEST(MapPicture, AMapOfAnotherSceneIsRefusedNamingTheObject) {
  const Fixture f = fixture();
  nlohmann::json map = map_json(f.run, "test");
  map["seen"].push_back(99);
  try {
    map_png(f.scene, map, 200);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("names object 99, which the scene does not have"), std::string::npos) << e.what();
  }
  map.erase("camera");
  EXPECT_THROW(map_png(f.scene, map, 200), InputError);
}

}  // namespace
}  // namespace cullcheck::html
