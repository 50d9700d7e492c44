// Scene files: round trips, rebasing of far-from-origin coordinates, and bad input (design:
// "Bad input"): every malformed or hostile file is refused with an InputError that names the
// object and the field, never a crash or a silently different scene.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "core/scene_timeline.hpp"

namespace cullcheck {
namespace {

std::string scene_text(const std::string& buildings, const std::string& extra = "") {
  return R"({"format":"cullcheck-scene","version":1)" + extra + R"(,"buildings":[)" + buildings + "]}";
}

const char* kBox = R"({"id":7,"height":12.5,"footprint":[[0,0],[10,0],[10,8],[0,8]]})";

struct BadCase {
  std::string name, text, object, field;
};

TEST(SceneIo, RejectsBadInputNamingObjectAndField) {
  const std::vector<BadCase> cases = {
      {"not json", "{\"format\":", "scene", "(document)"},
      {"wrong format", R"({"format":"obj","version":1,"buildings":[]})", "scene", "format"},
      {"future version", R"({"format":"cullcheck-scene","version":9,"buildings":[]})", "scene", "version"},
      {"no buildings", R"({"format":"cullcheck-scene","version":1})", "scene", "buildings"},
      {"count mismatch", scene_text(kBox, R"(,"building_count":3)"), "scene", "building_count"},
      {"negative height", scene_text(R"({"id":1,"height":-3,"footprint":[[0,0],[1,0],[1,1]]})"), "building 1", "height"},
      {"zero height", scene_text(R"({"id":1,"height":0,"footprint":[[0,0],[1,0],[1,1]]})"), "building 1", "height"},
      {"infinite coordinate", scene_text(R"({"id":2,"height":3,"footprint":[[0,0],[1e999,0],[1,1]]})"), "scene", "(document)"},
      {"string coordinate", scene_text(R"({"id":2,"height":3,"footprint":[[0,0],["1",0],[1,1]]})"), "building 2", "footprint[1][0]"},
      {"self-intersecting", scene_text(R"({"id":3,"height":3,"footprint":[[0,0],[2,2],[2,0],[0,2]]})"), "building 3", "footprint"},
      {"two vertices", scene_text(R"({"id":4,"height":3,"footprint":[[0,0],[2,2]]})"), "building 4", "footprint"},
      {"zero area", scene_text(R"({"id":5,"height":3,"footprint":[[0,0],[1,1],[2,2]]})"), "building 5", "footprint"},
      {"repeated vertex", scene_text(R"({"id":6,"height":3,"footprint":[[0,0],[1,0],[1,0],[1,1]]})"), "building 6", "footprint[1]"},
      {"duplicate id", scene_text(std::string(kBox) + "," + kBox), "building 7", "id"},
      {"negative id", scene_text(R"({"id":-1,"height":3,"footprint":[[0,0],[1,0],[1,1]]})"), "building -1", "id"},
      {"missing height", scene_text(R"({"id":8,"footprint":[[0,0],[1,0],[1,1]]})"), "building 8", "height"},
      {"absurd height", scene_text(R"({"id":9,"height":1e6,"footprint":[[0,0],[1,0],[1,1]]})"), "building 9", "height"},
      {"beyond 1e9 m", scene_text(R"({"id":10,"height":3,"footprint":[[0,0],[2e9,0],[1,1]]})"), "building 10", "footprint[1]"},
  };
  for (const BadCase& c : cases) {
    try {
      (void)scene_from_json_text(c.text);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.object(), c.object) << c.name << ": " << e.what();
      EXPECT_EQ(e.field(), c.field) << c.name << ": " << e.what();
    }
  }
}

TEST(SceneIo, RoundTripIsByteIdenticalAndNormalisesOrientation) {
  // Clockwise with an explicit closing vertex: stored counter-clockwise, implicitly closed.
  const std::string text = scene_text(R"({"id":1,"height":4,"footprint":[[0,0],[0,5],[5,5],[5,0],[0,0]]})");
  const Scene scene = scene_from_json_text(text);
  ASSERT_EQ(scene.buildings.size(), 1u);
  EXPECT_EQ(scene.buildings[0].footprint.size(), 4u);
  EXPECT_GT(signed_area(scene.buildings[0].footprint), 0.0);
  const std::string written = scene_to_json_text(scene);
  EXPECT_EQ(scene_to_json_text(scene_from_json_text(written)), written);
}

TEST(SceneIo, NonConvexFootprintsBecomeConvexPrismsCoveringTheArea) {
  const Scene scene = scene_from_json_text(
      scene_text(R"({"id":1,"height":9,"footprint":[[0,0],[10,0],[10,2],[2,2],[2,10],[0,10]]})"));
  const Building& b = scene.buildings[0];
  ASSERT_GE(b.prisms.size(), 2u);
  double area = 0.0;
  for (const ConvexVerticalPrism& p : b.prisms) {
    EXPECT_TRUE(is_convex(p.ring));
    EXPECT_EQ(p.height, 9.0);
    area += signed_area(p.ring);
  }
  EXPECT_DOUBLE_EQ(area, signed_area(b.footprint));
}

// UTM-size coordinates (10^7 m) are rebased to a local origin on load: local geometry keeps its
// millimetres, and writing the scene back reproduces the input coordinates exactly.
TEST(SceneIo, FarCoordinatesAreRebasedWithoutLoss) {
  const std::string text = scene_text(
      R"({"id":1,"height":4,"footprint":[[10000000.001,5000000.002],[10000010.003,5000000.002],[10000010.003,5000008.004],[10000000.001,5000008.004]]})");
  const Scene scene = scene_from_json_text(text);
  EXPECT_NE(scene.origin.x, 0.0);
  const Box2 local = scene.bounds().plan();
  EXPECT_LT(std::abs(local.lo.x), 100.0);
  EXPECT_NEAR(local.hi.x - local.lo.x, 10.002, 1e-9);
  const Scene again = scene_from_json_text(scene_to_json_text(scene));
  EXPECT_EQ(again.buildings[0].footprint, scene.buildings[0].footprint);
  EXPECT_NE(scene_to_json_text(scene).find("10000000.001"), std::string::npos);
}

TEST(SceneIo, CameraValidationNamesTheField) {
  auto field_of = [](const std::string& text) {
    try {
      (void)camera_from_json_text(text);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of(R"({"position":[0,0,-1]})"), "position.z");
  EXPECT_EQ(field_of(R"({"position":[0,0,1],"hfov":3.5})"), "hfov");
  EXPECT_EQ(field_of(R"({"position":[0,0,1],"pitch":2})"), "pitch");
  EXPECT_EQ(field_of(R"({"position":[0,0,1],"near":5,"far":1})"), "far");
  EXPECT_EQ(field_of(R"({"position":[0,"x",1]})"), "position[1]");
  EXPECT_EQ(field_of(R"({"position":[0,0,1],"hfov":6.283185307179586})"), "(accepted)");
}

}  // namespace
}  // namespace cullcheck

namespace cullcheck {
namespace {

// A path's scene timeline: read, written back the same, and checked against its scene.
TEST(SceneIo, PathEventsRoundTripAndAreCheckedAgainstTheScene) {
  const std::string text =
      R"({"format":"cullcheck-path","version":1,"kind":"k","seed":0,"frames_per_second":30,"frames":[{"position":[0,0,1.7]},{"position":[1,0,1.7]},{"position":[2,0,1.7]}],)"
      R"("events":[{"frame":1,"vanish":[2,0]},{"frame":2,"appear":[0,5]}]})";
  const CameraPath path = path_from_json_text(text);
  ASSERT_EQ(path.events.size(), 2u);
  EXPECT_EQ(path.events[0].frame, 1u);
  EXPECT_EQ(path.events[0].vanish, (std::vector<ObjectId>{0, 2}));  // sorted
  EXPECT_EQ(path.events[1].appear, (std::vector<ObjectId>{0, 5}));
  EXPECT_EQ(path_from_json_text(path_to_json_text(path)).events, path.events);
  EXPECT_EQ(absent_at_start(path), (std::set<ObjectId>{5}));  // 5 appears first: absent before frame 2
  Scene scene;
  for (ObjectId id : {0u, 2u, 5u}) {
    Building b;
    b.id = id;
    b.footprint = {{10.0 * id, 0}, {10.0 * id + 5, 0}, {10.0 * id + 5, 5}, {10.0 * id, 5}};
    b.height = 10;
    finish_building(b);
    scene.buildings.push_back(b);
  }
  EXPECT_NO_THROW(validate_timeline(path, scene, 3));
  EXPECT_EQ(present_scene(scene, {0, 5}).ids(), std::vector<ObjectId>{2});
  const auto problem = [&](CameraPath p, std::size_t frames = 3) {
    try {
      validate_timeline(p, scene, frames);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(problem(path, 2), "path event 1: field 'frame': 2 is past the path's 2 frames");
  CameraPath twice = path;
  twice.events[1].frame = 1;
  EXPECT_EQ(problem(twice), "path event 1: field 'frame': 1 is not after the previous event's frame 1");
  CameraPath unknown = path;
  unknown.events[0].vanish = {7};
  EXPECT_EQ(problem(unknown), "path event 0: field 'vanish': object 7 is not in the scene (a timeline's objects must all be in it)");
  CameraPath again = path;  // 2 vanished at frame 1
  again.events[1].vanish = {2};
  EXPECT_EQ(problem(again), "path event 1: field 'vanish': object 2 is already absent");
  CameraPath empty = path;
  empty.events[0].vanish.clear();
  EXPECT_EQ(problem(empty), "path event 0: field '(event)': makes nothing appear or vanish");
  const auto parse_error = [](const std::string& events) {
    try {
      path_from_json_text(R"({"format":"cullcheck-path","frames_per_second":30,"frames":[{"position":[0,0,1.7]}],"events":)" + events + "}");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(parse_error(R"([{"frame":0,"vanish":[1,1]}])"), "path event 0: field 'vanish': names an object twice");
  EXPECT_EQ(parse_error(R"([{"frame":-1,"vanish":[1]}])"), "path event 0: field 'frame': must be a frame number (an integer >= 0)");
  EXPECT_EQ(parse_error(R"([{"frame":0,"hide":[1]}])"), "path event 0: field 'hide': is not a field of an event (frame, appear, vanish)");
  EXPECT_EQ(parse_error(R"([{"frame":0,"vanish":["a"]}])"), "path event 0: field 'vanish': holds \"a\", not an object id");
  EXPECT_EQ(parse_error(R"({})"), R"(path: field 'events': must be an array of {"frame": N, "appear": [ids], "vanish": [ids]})");
}

}  // namespace
}  // namespace cullcheck
