// World and scene-local cameras (core/coordinates.hpp) and the "coordinates"/"origin" keys of
// camera and path JSON (core/scene_io.cpp): the frame a file says, the --coordinates fallback and
// its conflicts, exact conversion (and refusal when it would round), and the refusal of a path
// whose every eye lies far outside the scene. Expected values are worked out in the comments.
#include <gtest/gtest.h>

#include <string>

#include "core/coordinates.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {
namespace {

// One 20 m x 10 m block at world [5000000, 5000020] x [3000000, 3000010], 15 m high: 5e6 m from
// the origin, so it is rebased to the whole-metre centre (5000010, 3000005) and its local plan
// bounds are [-10, 10] x [-5, 5]; eye_margin = max(1000, 20, 10) = 1000 m.
Scene far_block() {
  return scene_from_json_text(
      R"({"format":"cullcheck-scene","version":1,"buildings":[{"id":1,"height":15,)"
      R"("footprint":[[5000000,3000000],[5000020,3000000],[5000020,3000010],[5000000,3000010]]}]})");
}

std::string path_text(const std::string& frame_keys, const std::string& positions) {
  return R"({"format":"cullcheck-path","version":1,"frames_per_second":30,)" + frame_keys + R"("frames":[)" + positions + "]}";
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Coordinates, FarSceneIsRebasedToItsWholeMetreCentre) {
  const Scene s = far_block();
  EXPECT_EQ(s.origin, (Vec2{5000010, 3000005}));
  EXPECT_EQ(s.bounds().plan().lo, (Vec2{-10, -5}));
  EXPECT_EQ(eye_margin(s), 1000.0);
}

TEST(Coordinates, PathFileSaysItsFrame) {
  const CameraPath world = path_from_json_text(path_text(R"("coordinates":"world",)", R"({"position":[1,2,3]})"));
  EXPECT_EQ(world.coordinates, CoordinateFrame::world);
  EXPECT_FALSE(world.origin);
  const CameraPath local = path_from_json_text(path_text(R"("coordinates":"local","origin":[7,8],)", R"({"position":[1,2,3]})"));
  EXPECT_EQ(local.coordinates, CoordinateFrame::local);
  EXPECT_EQ(local.origin, (Vec2{7, 8}));
  // An origin alone means local coordinates relative to it.
  EXPECT_EQ(path_from_json_text(path_text(R"("origin":[7,8],)", R"({"position":[1,2,3]})")).coordinates, CoordinateFrame::local);
  // Old files say nothing.
  const CameraPath old = path_from_json_text(path_text("", R"({"position":[1,2,3]})"));
  EXPECT_FALSE(old.coordinates);
  EXPECT_FALSE(old.origin);
  // Written back with both keys, and read back the same.
  EXPECT_NE(path_to_json_text(local).find(R"("coordinates":"local")"), std::string::npos);
  EXPECT_NE(path_to_json_text(local).find(R"("origin":[7.0,8.0])"), std::string::npos);
  EXPECT_EQ(path_to_json_text(path_from_json_text(path_to_json_text(local))), path_to_json_text(local));
  EXPECT_EQ(path_to_json_text(old).find("coordinates"), std::string::npos);
}

TEST(Coordinates, BadFrameKeysNameTheField) {
  EXPECT_EQ(message_of([] { path_from_json_text(path_text(R"("coordinates":"utm",)", R"({"position":[1,2,3]})")); }),
            "path: field 'coordinates': must be \"local\" (scene-local metres) or \"world\" (local + the scene's origin), got \"utm\"");
  EXPECT_EQ(message_of([] { path_from_json_text(path_text(R"("coordinates":"world","origin":[1,2],)", R"({"position":[1,2,3]})")); }),
            "path: field 'origin': names the origin local coordinates are relative to: world coordinates have none");
  EXPECT_EQ(message_of([] { path_from_json_text(path_text(R"("origin":[1,2,3],)", R"({"position":[1,2,3]})")); }),
            "path: field 'origin': must be [x, y]");
  EXPECT_NE(message_of([] { path_from_json_text(path_text(R"("origin":[1,NaN],)", R"({"position":[1,2,3]})")); })
                .find("is not valid JSON"),
            std::string::npos);
  EXPECT_EQ(message_of([] { path_from_json_text(path_text("", R"({"position":[1,2,3]},{"position":[1,2,3],"coordinates":"world"})")); }),
            "path frame 1: field 'coordinates': belongs to the whole path (its top level), not to one frame");
  // Where only scene-local cameras belong (protocol frames, generator parameters), a frame key is
  // refused rather than ignored.
  EXPECT_EQ(message_of([] { camera_from_json_text(R"({"position":[1,2,3],"coordinates":"world"})"); }),
            "camera: field 'coordinates': cameras here are scene-local: only camera files and flags (--camera, --from) say their frame");
  const CameraPath one = single_camera_from_json_text(R"({"position":[1,2,3],"coordinates":"world","yaw":0.5})", "--camera");
  EXPECT_EQ(one.coordinates, CoordinateFrame::world);
  ASSERT_EQ(one.frames.size(), 1u);
  EXPECT_EQ(one.frames[0].yaw, 0.5);
}

TEST(Coordinates, WorldPathOnRebasedSceneEqualsTheLocalOne) {
  const Scene s = far_block();
  // World (5000012.25, 3000001.5) - origin (5000010, 3000005) = local (2.25, -3.5), exactly.
  CameraPath world = path_from_json_text(path_text(R"("coordinates":"world",)", R"({"position":[5000012.25,3000001.5,1.7],"yaw":1})"));
  CameraPath local = path_from_json_text(path_text("", R"({"position":[2.25,-3.5,1.7],"yaw":1})"));
  const CoordinateConversion w = to_scene_local(world, s, std::nullopt, "w.json");
  const CoordinateConversion l = to_scene_local(local, s, std::nullopt, "l.json");
  EXPECT_EQ(world.frames[0].position, (Vec3{2.25, -3.5, 1.7}));
  EXPECT_EQ(path_to_json_text(world), path_to_json_text(local));
  EXPECT_EQ(w.given, CoordinateFrame::world);
  EXPECT_EQ(w.decided_by, "file");
  EXPECT_TRUE(w.moved);
  EXPECT_EQ(w.origin, (Vec2{5000010, 3000005}));
  EXPECT_EQ(l.given, CoordinateFrame::local);
  EXPECT_EQ(l.decided_by, "default");
  EXPECT_FALSE(l.moved);
  // Afterwards both say local, with the scene's origin.
  EXPECT_EQ(world.coordinates, CoordinateFrame::local);
  EXPECT_EQ(world.origin, (Vec2{5000010, 3000005}));
  EXPECT_EQ(coordinates_line(w, "w.json"),
            "coordinates: scene-local metres, world = local + origin [5000010.0, 3000005.0]; w.json given in world coordinates "
            "(said by the file), converted to scene-local");
  EXPECT_EQ(coordinates_line(l, "l.json"),
            "coordinates: scene-local metres, world = local + origin [5000010.0, 3000005.0]; l.json given in local coordinates "
            "(default: files that do not say are local), used as they are");
}

TEST(Coordinates, LocalPathOfAnotherOriginIsMovedToTheScenes) {
  const Scene s = far_block();
  // Local (12.25, -3.5) to origin (5000000, 3000005) is world (5000012.25, 3000001.5), local
  // (2.25, -3.5) to the scene's origin (5000010, 3000005).
  CameraPath p = path_from_json_text(path_text(R"("origin":[5000000,3000005],)", R"({"position":[12.25,-3.5,1.7]})"));
  const CoordinateConversion c = to_scene_local(p, s, std::nullopt, "p.json");
  EXPECT_EQ(p.frames[0].position, (Vec3{2.25, -3.5, 1.7}));
  EXPECT_TRUE(c.moved);
  EXPECT_EQ(c.declared_origin, (Vec2{5000000, 3000005}));
}

TEST(Coordinates, FlagAppliesToFilesThatDoNotSayAndMustNotContradictThem) {
  const Scene s = far_block();
  CameraPath silent = path_from_json_text(path_text("", R"({"position":[5000012.25,3000001.5,1.7]})"));
  const CoordinateConversion c = to_scene_local(silent, s, CoordinateFrame::world, "silent.json");
  EXPECT_EQ(silent.frames[0].position, (Vec3{2.25, -3.5, 1.7}));
  EXPECT_EQ(c.decided_by, "--coordinates");
  CameraPath says_local = path_from_json_text(path_text(R"("coordinates":"local",)", R"({"position":[2,3,1.7]})"));
  EXPECT_EQ(message_of([&] { to_scene_local(says_local, s, CoordinateFrame::world, "l.json"); }),
            "l.json: field 'coordinates': says local but --coordinates says world: drop one of them");
  // Agreeing is fine.
  CameraPath says_world = path_from_json_text(path_text(R"("coordinates":"world",)", R"({"position":[5000010,3000005,1.7]})"));
  EXPECT_EQ(to_scene_local(says_world, s, CoordinateFrame::world, "w.json").decided_by, "file");
  EXPECT_EQ(says_world.frames[0].position, (Vec3{0, 0, 1.7}));
}

TEST(Coordinates, ConversionThatWouldRoundIsRefused) {
  // A fractional origin read from scene JSON: 5000000.3 - 0.1 is not a double, so the camera
  // would move by a rounding error; it must be given in local coordinates instead.
  Scene s = far_block();
  s.origin = {0.1, 0.0};
  CameraPath p = path_from_json_text(path_text(R"("coordinates":"world",)", R"({"position":[5000000.3,0,1.7]})"));
  EXPECT_EQ(message_of([&] { to_scene_local(p, s, std::nullopt, "p.json"); }),
            "p.json: field 'frames[0].position': [5000000.3, 0.0] (world) minus the scene's origin [0.1, 0.0] would round in "
            "double precision: give this camera in scene-local coordinates");
}

TEST(Coordinates, LocalPositionMovedToAnotherOriginIsRoundedOnceAndSaysByHowMuch) {
  // 0.1 (local to origin (5000011, 3000005)) is 1.1 local to the scene's (5000010, 3000005):
  // 0.1 + 1 rounds (0.1's low bits are finer than 1.1's ulp); TwoSum gives the loss exactly:
  // 0.1 + 1 - fl(0.1 + 1) = -8.326672684688674e-17.
  const Scene s = far_block();
  CameraPath p = path_from_json_text(path_text(R"("origin":[5000011,3000005],)", R"({"position":[0.1,0,1.7]})"));
  const CoordinateConversion c = to_scene_local(p, s, std::nullopt, "p.json");
  EXPECT_EQ(p.frames[0].position.x, 1.1);
  EXPECT_EQ(c.rounding_m, 8.326672684688674e-17);
  EXPECT_NE(coordinates_line(c, "p.json").find("converted to scene-local (rounded by at most 8.326672684688674e-17 m)"), std::string::npos);
}

TEST(Coordinates, WorldPathReadAsLocalIsRefusedNotPassedVacuously) {
  const Scene s = far_block();
  // The world path of the first test, read as local (the default): 5e6 m from the block.
  CameraPath p = path_from_json_text(path_text("", R"({"position":[5000012.25,3000001.5,1.7]},{"position":[5000013,3000001.5,1.7]})"));
  const CoordinateConversion c = to_scene_local(p, s, std::nullopt, "walk.json");
  EXPECT_EQ(message_of([&] { require_an_eye_near_the_scene(p, s, c, "walk.json"); }),
            "walk.json: field 'frames[0].position': every eye of the path (2 frames) lies outside the scene's plan bounds grown "
            "by 1000.0 m, so it would see nothing: the first is at [5000012.25, 3000001.5, 1.7] scene-local, the bounds are "
            "x [-10.0, 10.0], y [-5.0, 5.0] scene-local, the origin is [5000010.0, 3000005.0] (world = local + origin); a file "
            "without \"coordinates\" is read as scene-local: if its positions are world coordinates, say \"coordinates\": "
            "\"world\" in it or give --coordinates world");
  // The same camera said to be world but far from this scene (another city's path).
  CameraPath other = single_camera_from_json_text(R"({"position":[9000000,3000000,1.7],"coordinates":"world"})", "--camera");
  const CoordinateConversion o = to_scene_local(other, s, std::nullopt, "--camera");
  EXPECT_NE(message_of([&] { require_an_eye_near_the_scene(other, s, o, "--camera"); })
                .find("--camera: field 'position': the eye lies outside the scene's plan bounds grown by 1000.0 m, so it would "
                      "see nothing: it is at [3999990.0, -5.0, 1.7] scene-local"),
            std::string::npos);
}

TEST(Coordinates, OneEyeNearTheSceneIsEnoughAndTheMarginIsInclusive) {
  const Scene s = far_block();
  // Bounds [-10, 10] x [-5, 5] grown by 1000 m: x up to 1010 is near, 1010.5 is not.
  auto check = [&](const std::string& positions) {
    CameraPath p = path_from_json_text(path_text("", positions));
    const CoordinateConversion c = to_scene_local(p, s, std::nullopt, "p.json");
    require_an_eye_near_the_scene(p, s, c, "p.json");
  };
  EXPECT_NO_THROW(check(R"({"position":[1010,0,1.7]})"));
  EXPECT_THROW(check(R"({"position":[1010.5,0,1.7]})"), InputError);
  EXPECT_NO_THROW(check(R"({"position":[0,-1005,300]})"));
  EXPECT_THROW(check(R"({"position":[0,-1005.5,300]})"), InputError);
  EXPECT_NO_THROW(check(R"({"position":[99999,0,1.7]},{"position":[3,0,1.7]})"));  // the second eye is near
  // A scene without objects has no bounds to hold an eye to.
  Scene empty;
  CameraPath far = path_from_json_text(path_text("", R"({"position":[1e8,0,1.7]})"));
  const CoordinateConversion c = to_scene_local(far, empty, std::nullopt, "p.json");
  EXPECT_NO_THROW(require_an_eye_near_the_scene(far, empty, c, "p.json"));
}

TEST(Coordinates, MarginGrowsWithTheScene) {
  // A 3 km x 200 m city: the margin is its larger side.
  const Scene s = scene_from_json_text(
      R"({"format":"cullcheck-scene","version":1,"buildings":[{"id":1,"height":5,"footprint":[[0,0],[3000,0],[3000,200],[0,200]]}]})");
  EXPECT_EQ(eye_margin(s), 3000.0);
}

TEST(Coordinates, ParseFlag) {
  EXPECT_EQ(parse_coordinate_frame("world"), CoordinateFrame::world);
  EXPECT_EQ(parse_coordinate_frame("local"), CoordinateFrame::local);
  EXPECT_EQ(message_of([] { parse_coordinate_frame("utm"); }), "command line: field '--coordinates': must be world or local, got 'utm'");
}

}  // namespace
}  // namespace cullcheck
