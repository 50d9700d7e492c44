// Scene files: round trips, rebasing of far-from-origin coordinates, and bad input (design:
// "Bad input"): every malformed or hostile file is refused with an InputError that names the
// object and the field, never a crash or a silently different scene.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/errors.hpp"
#include "core/scene_io.hpp"

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
