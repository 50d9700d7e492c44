// Cameras (core/camera.hpp) and their JSON (core/scene_io.cpp): orthographic view boxes, the
// resolution and its defaults, "aspect", the errors that name their field, and exact round trips.
// Every expected value is worked out by hand in the comment beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {
namespace {

// The field an InputError names, or "(accepted)" when the text is accepted.
std::string field_of_error(const std::string& text) {
  try {
    (void)camera_from_json_text(text);
  } catch (const InputError& e) {
    EXPECT_EQ(e.object(), "camera") << e.what();
    return e.field();
  }
  return "(accepted)";
}

std::string field_of_validation_error(const Camera& c) {
  try {
    validate(c);
  } catch (const InputError& e) {
    return e.field();
  }
  return "(accepted)";
}

// --- The orthographic view volume ------------------------------------------------------------

// Eye (0, 0, 10), yaw 0, pitch 0: forward = (1, 0, 0), right = (sin 0, -cos 0, 0) = (0, -1, 0),
// up = right x forward = (0, 0, 1). A 20 x 10 m box from near 1 to far 50 is therefore
//   x in [1, 50] (near, far),  y in [-10, 10] (right: y = -10; left: y = +10),  z in [5, 15].
Camera ortho_camera() {
  Camera c;
  c.position = {0, 0, 10};
  c.projection = Projection::orthographic;
  c.ortho_width = 20;
  c.ortho_height = 10;
  c.near = 1;
  c.far = 50;
  return c;
}

constexpr double kJust = 1e-6;  // far above rounding at these magnitudes, far below any extent

TEST(OrthographicViewVolume, IsTheBoxAlongTheViewAxis) {
  const ViewVolume v(ortho_camera());
  ASSERT_EQ(v.plane_count, 6);
  EXPECT_FALSE(v.omnidirectional);
  struct Case {
    const char* plane;
    Vec3 inside, outside;
  };
  const Case cases[] = {
      {"near x = 1", {1 + kJust, 0, 10}, {1 - kJust, 0, 10}},
      {"far x = 50", {50 - kJust, 0, 10}, {50 + kJust, 0, 10}},
      {"right y = -10", {25, -10 + kJust, 10}, {25, -10 - kJust, 10}},
      {"left y = +10", {25, 10 - kJust, 10}, {25, 10 + kJust, 10}},
      {"top z = 15", {25, 0, 15 - kJust}, {25, 0, 15 + kJust}},
      {"bottom z = 5", {25, 0, 5 + kJust}, {25, 0, 5 - kJust}},
  };
  for (const Case& c : cases) {
    EXPECT_TRUE(v.contains(c.inside)) << c.plane;
    EXPECT_FALSE(v.contains(c.outside)) << c.plane;
  }
  // Corners of the box are inside; a point behind the eye (x = -1) is not: the box starts at near.
  EXPECT_TRUE(v.contains({1 + kJust, -10 + kJust, 5 + kJust}));
  EXPECT_TRUE(v.contains({50 - kJust, 10 - kJust, 15 - kJust}));
  EXPECT_FALSE(v.contains({-1, 0, 10}));
  // Unlike a perspective frustum, the box does not widen with distance: (49, 11, 10) is outside.
  EXPECT_FALSE(v.contains({49, 11, 10}));
}

TEST(OrthographicViewVolume, TurnsWithYaw) {
  // Yaw pi/2: forward = (0, 1, 0), right = (1, 0, 0) (up to 6e-17), up = (0, 0, 1): the box is
  //   y in [1, 50], x in [-10, 10], z in [5, 15].
  Camera c = ortho_camera();
  c.yaw = kPi / 2;
  const ViewVolume v(c);
  EXPECT_TRUE(v.contains({0, 1 + kJust, 10}));
  EXPECT_FALSE(v.contains({0, 1 - kJust, 10}));
  EXPECT_TRUE(v.contains({0, 50 - kJust, 10}));
  EXPECT_FALSE(v.contains({0, 50 + kJust, 10}));
  EXPECT_TRUE(v.contains({10 - kJust, 25, 10}));
  EXPECT_FALSE(v.contains({10 + kJust, 25, 10}));
  EXPECT_TRUE(v.contains({-10 + kJust, 25, 10}));
  EXPECT_FALSE(v.contains({-10 - kJust, 25, 10}));
  EXPECT_TRUE(v.contains({0, 25, 15 - kJust}));
  EXPECT_FALSE(v.contains({0, 25, 15 + kJust}));
  // The yaw-0 box's points are now outside: (25, 0, 10) is 25 m to the right.
  EXPECT_FALSE(v.contains({25, 0, 10}));
}

TEST(OrthographicViewVolume, BoxTestIsConservativeAndRejectsBoxesOutside) {
  const ViewVolume v(ortho_camera());
  // Entirely beyond the far plane (x > 50), entirely to the left (y > 10): rejected.
  EXPECT_FALSE(v.may_intersect(Box3{{51, -1, 9}, {60, 1, 11}}));
  EXPECT_FALSE(v.may_intersect(Box3{{10, 11, 9}, {20, 12, 11}}));
  // Straddling the left side (y from 9 to 12): kept.
  EXPECT_TRUE(v.may_intersect(Box3{{10, 9, 9}, {20, 12, 11}}));
}

TEST(OrthographicViewVolume, ValidationNamesTheExtent) {
  Camera c = ortho_camera();
  EXPECT_EQ(field_of_validation_error(c), "(accepted)");
  c.ortho_width = 0;
  EXPECT_EQ(field_of_validation_error(c), "ortho_width");
  c = ortho_camera();
  c.ortho_height = -1;
  EXPECT_EQ(field_of_validation_error(c), "ortho_height");
  c = ortho_camera();
  c.near = 0;  // an orthographic box may start at the eye
  EXPECT_EQ(field_of_validation_error(c), "(accepted)");
}

// --- Resolution ------------------------------------------------------------------------------

TEST(Resolution, DefaultsToSquarePixelsOver320Columns) {
  // Perspective, hfov = pi/3, vfov = pi/4 (the defaults): rows = round(320 tan(pi/8) / tan(pi/6))
  // = round(320 * 0.41421356 / 0.57735027) = round(229.58) = 230.
  Camera c;
  EXPECT_EQ(resolution_of(c), (Resolution{320, 230}));
  // hfov = vfov: square image, 320 x 320.
  c.vfov = c.hfov;
  EXPECT_EQ(resolution_of(c), (Resolution{320, 320}));
  // Orthographic 40 m x 30 m: rows = round(320 * 30 / 40) = 240.
  Camera o = ortho_camera();
  o.ortho_width = 40, o.ortho_height = 30;
  EXPECT_EQ(resolution_of(o), (Resolution{320, 240}));
  // Omnidirectional (hfov = 2 pi): an equirectangular panorama, 2 pi across and pi high: 320 x 160.
  Camera omni;
  omni.hfov = kTwoPi;
  EXPECT_EQ(resolution_of(omni), (Resolution{320, 160}));
  // The row count is clamped to [1, 8192]: 1000 m x 1 m gives round(0.32) = 0 -> 1 row, and
  // 1 m x 100 m gives 32000 -> 8192 rows.
  o.ortho_width = 1000, o.ortho_height = 1;
  EXPECT_EQ(resolution_of(o), (Resolution{320, 1}));
  o.ortho_width = 1, o.ortho_height = 100;
  EXPECT_EQ(resolution_of(o), (Resolution{320, 8192}));
}

TEST(Resolution, GivenResolutionIsUsedAsIs) {
  Camera c;
  c.width = 640, c.height = 100;  // not square pixels: the given size wins
  EXPECT_EQ(resolution_of(c), (Resolution{640, 100}));
  c.hfov = kTwoPi;
  EXPECT_EQ(resolution_of(c), (Resolution{640, 100}));
}

TEST(Resolution, ValidationNamesTheResolution) {
  Camera c;
  c.width = 640;  // one side only
  EXPECT_EQ(field_of_validation_error(c), "resolution");
  c.height = 8193;
  EXPECT_EQ(field_of_validation_error(c), "resolution");
  c.height = -4, c.width = -4;
  EXPECT_EQ(field_of_validation_error(c), "resolution");
  c.width = 8192, c.height = 1;  // both limits themselves are fine
  EXPECT_EQ(field_of_validation_error(c), "(accepted)");
}

// --- Camera JSON: reading --------------------------------------------------------------------

TEST(CameraJson, ReadsAnOrthographicCamera) {
  const Camera c = camera_from_json_text(
      R"({"position":[1,2,3],"yaw":0.5,"projection":"orthographic","ortho_width":40,"ortho_height":30,"near":0,"far":200})");
  EXPECT_TRUE(c.orthographic());
  EXPECT_FALSE(c.omnidirectional());
  EXPECT_EQ(c.ortho_width, 40.0);
  EXPECT_EQ(c.ortho_height, 30.0);
  EXPECT_EQ(c.near, 0.0);
  EXPECT_EQ(c.far, 200.0);
  EXPECT_EQ(c.yaw, 0.5);
  EXPECT_EQ(c.width, 0);  // no resolution given: the default applies (320 x 240)
  EXPECT_EQ(resolution_of(c), (Resolution{320, 240}));
  // "perspective" spelled out is the default.
  EXPECT_FALSE(camera_from_json_text(R"({"position":[0,0,2],"projection":"perspective"})").orthographic());
}

TEST(CameraJson, ReadsResolution) {
  const Camera c = camera_from_json_text(R"({"position":[0,0,2],"hfov":1.0,"vfov":0.5,"resolution":[640,200]})");
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 200);
  // Both fields of view were given, so the resolution derives neither of them.
  EXPECT_EQ(c.hfov, 1.0);
  EXPECT_EQ(c.vfov, 0.5);
}

TEST(CameraJson, AspectDerivesTheMissingFieldOfView) {
  // hfov = pi/2, aspect 2: vfov = 2 atan(tan(pi/4) / 2) = 2 atan(0.5) = 0.9272952180016122.
  Camera c = camera_from_json_text(R"({"position":[0,0,2],"hfov":1.5707963267948966,"aspect":2})");
  EXPECT_NEAR(c.vfov, 0.9272952180016122, 1e-15);
  EXPECT_EQ(c.hfov, kPi / 2);
  // vfov = pi/2, aspect 2: hfov = 2 atan(tan(pi/4) * 2) = 2 atan(2) = 2.214297435588181.
  c = camera_from_json_text(R"({"position":[0,0,2],"vfov":1.5707963267948966,"aspect":2})");
  EXPECT_NEAR(c.hfov, 2.214297435588181, 1e-15);
  EXPECT_EQ(c.vfov, kPi / 2);
  // Aspect alone keeps the default hfov pi/3: vfov = 2 atan(tan(pi/6) / (4/3))
  // = 2 atan(0.4330127) = 0.8172757101951849.
  c = camera_from_json_text(R"({"position":[0,0,2],"aspect":1.3333333333333333})");
  EXPECT_EQ(c.hfov, kPi / 3);
  EXPECT_NEAR(c.vfov, 0.8172757101951849, 1e-15);
}

TEST(CameraJson, ResolutionGivesTheAspectForSquarePixels) {
  // [640, 480] is aspect 4/3; with the default hfov pi/3 that is the vfov 0.8172757101951849
  // worked out above.
  Camera c = camera_from_json_text(R"({"position":[0,0,2],"resolution":[640,480]})");
  EXPECT_NEAR(c.vfov, 0.8172757101951849, 1e-15);
  // [640, 320] with hfov = pi/2: vfov = 2 atan(0.5) = 0.9272952180016122.
  c = camera_from_json_text(R"({"position":[0,0,2],"hfov":1.5707963267948966,"resolution":[640,320]})");
  EXPECT_NEAR(c.vfov, 0.9272952180016122, 1e-15);
  // An explicit aspect beats the resolution's: aspect 1 with hfov = pi/2 gives vfov = pi/2.
  c = camera_from_json_text(R"({"position":[0,0,2],"hfov":1.5707963267948966,"aspect":1,"resolution":[640,320]})");
  EXPECT_NEAR(c.vfov, kPi / 2, 1e-15);
  // A 360-degree camera takes no aspect from its resolution: vfov keeps its default pi/4.
  c = camera_from_json_text(R"({"position":[0,0,2],"hfov":6.283185307179586,"resolution":[640,320]})");
  EXPECT_TRUE(c.omnidirectional());
  EXPECT_EQ(c.vfov, kPi / 4);
}

TEST(CameraJson, AspectDerivesTheMissingOrthographicExtent) {
  // ortho_width 40, aspect 2: ortho_height = 40 / 2 = 20.
  Camera c = camera_from_json_text(R"({"position":[0,0,2],"projection":"orthographic","ortho_width":40,"aspect":2})");
  EXPECT_EQ(c.ortho_width, 40.0);
  EXPECT_EQ(c.ortho_height, 20.0);
  // ortho_height 30, aspect 0.5: ortho_width = 30 * 0.5 = 15.
  c = camera_from_json_text(R"({"position":[0,0,2],"projection":"orthographic","ortho_height":30,"aspect":0.5})");
  EXPECT_EQ(c.ortho_width, 15.0);
  EXPECT_EQ(c.ortho_height, 30.0);
  // ortho_width 40 with a 400 x 300 resolution: ortho_height = 40 / (4/3) = 30.
  c = camera_from_json_text(R"({"position":[0,0,2],"projection":"orthographic","ortho_width":40,"resolution":[400,300]})");
  EXPECT_DOUBLE_EQ(c.ortho_height, 30.0);
  EXPECT_EQ(resolution_of(c), (Resolution{400, 300}));
}

TEST(CameraJson, ErrorsNameTheirField) {
  struct Case {
    const char* name;
    std::string text, field;
  };
  const std::vector<Case> cases = {
      {"hfov, vfov and aspect", R"({"position":[0,0,2],"hfov":1,"vfov":0.5,"aspect":2})", "aspect"},
      {"ortho extents and aspect",
       R"({"position":[0,0,2],"projection":"orthographic","ortho_width":4,"ortho_height":3,"aspect":2})", "aspect"},
      {"aspect zero", R"({"position":[0,0,2],"hfov":1,"aspect":0})", "aspect"},
      {"resolution with one side", R"({"position":[0,0,2],"resolution":[640]})", "resolution"},
      {"resolution with three sides", R"({"position":[0,0,2],"resolution":[640,480,3]})", "resolution"},
      {"resolution zero", R"({"position":[0,0,2],"resolution":[0,480]})", "resolution"},
      {"resolution above 8192", R"({"position":[0,0,2],"resolution":[8193,480]})", "resolution"},
      {"resolution fractional", R"({"position":[0,0,2],"resolution":[640.5,480]})", "resolution"},
      {"resolution not an array", R"({"position":[0,0,2],"resolution":640})", "resolution"},
      {"ortho without extents", R"({"position":[0,0,2],"projection":"orthographic"})", "ortho_width"},
      {"ortho with width only", R"({"position":[0,0,2],"projection":"orthographic","ortho_width":4})", "ortho_height"},
      {"ortho with height only", R"({"position":[0,0,2],"projection":"orthographic","ortho_height":4})", "ortho_width"},
      {"ortho with aspect only", R"({"position":[0,0,2],"projection":"orthographic","aspect":2})", "ortho_width"},
      {"ortho with resolution only", R"({"position":[0,0,2],"projection":"orthographic","resolution":[4,3]})",
       "ortho_width"},
      {"ortho width negative", R"({"position":[0,0,2],"projection":"orthographic","ortho_width":-4,"ortho_height":3})",
       "ortho_width"},
      {"unknown projection", R"({"position":[0,0,2],"projection":"fisheye"})", "projection"},
      {"projection not a string", R"({"position":[0,0,2],"projection":1})", "projection"},
  };
  for (const Case& c : cases) EXPECT_EQ(field_of_error(c.text), c.field) << c.name;
}

// --- Camera JSON: writing and round trips ----------------------------------------------------

TEST(CameraJson, PerspectiveWithoutResolutionWritesExactlyTheOldKeys) {
  Camera c;
  c.position = {1, 2, 3};
  c.yaw = 0.5, c.pitch = 0.25, c.roll = 0.0;
  c.hfov = 1.0, c.vfov = 0.75, c.near = 0.5, c.far = 1000.0;
  // nlohmann::json writes keys in sorted order; doubles in their shortest round-trip form.
  EXPECT_EQ(camera_to_json_text(c),
            R"({"far":1000.0,"hfov":1.0,"near":0.5,"pitch":0.25,"position":[1.0,2.0,3.0],"roll":0.0,"vfov":0.75,"yaw":0.5})"
            "\n");
}

TEST(CameraJson, OrthographicAndResolutionAreWritten) {
  Camera c = ortho_camera();
  c.width = 64, c.height = 32;
  // No hfov / vfov for an orthographic camera; its extents and the projection instead.
  EXPECT_EQ(camera_to_json_text(c),
            R"({"far":50.0,"near":1.0,"ortho_height":10.0,"ortho_width":20.0,"pitch":0.0,"position":[0.0,0.0,10.0],)"
            R"("projection":"orthographic","resolution":[64,32],"roll":0.0,"yaw":0.0})"
            "\n");
}

void expect_same_camera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.yaw, b.yaw);
  EXPECT_EQ(a.pitch, b.pitch);
  EXPECT_EQ(a.roll, b.roll);
  EXPECT_EQ(a.near, b.near);
  EXPECT_EQ(a.far, b.far);
  EXPECT_EQ(a.projection, b.projection);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  if (a.orthographic()) {
    EXPECT_EQ(a.ortho_width, b.ortho_width);
    EXPECT_EQ(a.ortho_height, b.ortho_height);
  } else {
    EXPECT_EQ(a.hfov, b.hfov);
    EXPECT_EQ(a.vfov, b.vfov);
  }
}

TEST(CameraJson, RoundTripIsExact) {
  std::vector<Camera> cameras;
  Camera p;  // awkward doubles that have no short decimal form
  p.position = {0.1 + 0.2, -1234567.891, 1.0 / 3.0};
  p.yaw = kPi / 7, p.pitch = -kPi / 2, p.roll = 1e-300;
  p.hfov = 2.0 / 3.0, p.vfov = std::nextafter(1.0, 2.0), p.near = 0.0, p.far = 12345.678901234567;
  cameras.push_back(p);
  p.width = 1920, p.height = 1080;  // resolution not square with the fields of view: kept as given
  cameras.push_back(p);
  p.width = 1, p.height = 8192;
  cameras.push_back(p);
  Camera o = ortho_camera();
  o.ortho_width = 0.1, o.ortho_height = 1e7, o.yaw = 6.2;
  cameras.push_back(o);
  o.width = 333, o.height = 7;
  cameras.push_back(o);
  Camera omni;
  omni.hfov = kTwoPi, omni.vfov = kPi, omni.far = 500;  // vfov pi is unused at 360 degrees
  cameras.push_back(omni);
  for (const Camera& c : cameras) {
    const std::string text = camera_to_json_text(c);
    SCOPED_TRACE(text);
    const Camera back = camera_from_json_text(text);
    expect_same_camera(c, back);
    EXPECT_EQ(camera_to_json_text(back), text);
  }
}

}  // namespace
}  // namespace cullcheck
