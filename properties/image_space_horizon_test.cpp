// OH(IS), the image-space occlusion horizon of Downs et al. (thesis ch. 3.1.1), against the
// oracle and on hand-built scenes:
//  - conservative for level cameras (its 4-DoF claim) over generated cities, street-level and
//    rooftop eyes, narrow, ordinary and 360-degree fields of view, occluders below and above the
//    eye, deep near planes;
//  - not conservative once the camera pitches or rolls (Fig. 3.3): a RapidCheck search must find
//    a counterexample on its own and shrink it, and the case it found stays a regression test;
//  - unit cases: a wall hides what is behind it, the screen's x range is binned without
//    wrap-around up to its edges, occluders in front of the near plane are not used, the claim
//    covers level and 360-degree cameras only, 360 degrees is view-frustum culling, extreme
//    cameras never crash, and the design's numerical extremes hold for level cameras.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>

#include "core/scene_io.hpp"
#include "engine/image_space/image_space_horizon.hpp"
#include "engine/method.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "oracle/oracle.hpp"
#include "properties/property_oracle.hpp"
#include "properties/property_run.hpp"
#include "reports/claims.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;
using generators::SceneCase;

// What the oracle sees and OH(IS) culled, with the oracle's description of the first such
// building (its witness ray), empty when OH(IS) kept everything the oracle saw.
struct Miss {
  std::vector<ObjectId> buildings;
  std::string description;
};
Miss oh_is_misses(const oracle::Oracle& truth, CullingMethod& oh_is, const Camera& camera, const oracle::OracleOptions& options) {
  const oracle::OracleAnswer seen = truth.visible_set(camera, options);
  const std::vector<ObjectId> pvs = oh_is.cull(camera).pvs;
  Miss miss;
  std::set_difference(seen.visible.begin(), seen.visible.end(), pvs.begin(), pvs.end(), std::back_inserter(miss.buildings));
  if (miss.buildings.empty()) return miss;
  const ObjectId first = miss.buildings.front();
  miss.description = "building " + std::to_string(first) + " seen by the oracle (" + seen.model + ")" +
                     (seen.sampling ? ": " + oracle::describe(seen.sampling->witnesses.at(first)) : "") + " but culled";
  return miss;
}
Miss oh_is_misses(const Scene& scene, const Camera& camera, const oracle::OracleOptions& options = {}) {
  return oh_is_misses(oracle::Oracle(scene), *make_method("oh_is", scene), camera, options);
}

// The replay names the oracle density too: slivers seen at one density may be missed at another.
std::string replay_of(const SceneCase& c) {
  std::ostringstream replay;
  const oracle::SamplingOptions density = property_oracle().sampling;
  replay << "cullcheck verify " << c << " --method oh_is --spacing " << density.spacing_m << " --frustum-resolution "
         << density.frustum_resolution;
  return replay.str();
}

// --- Conservative for level cameras -------------------------------------------------------------

rc::Gen<SceneCase> level(rc::Gen<SceneCase> cases) {
  return rc::gen::map(std::move(cases), [](SceneCase c) {
    c.camera.pitch = 0.0;
    c.camera.roll = 0.0;
    return c;
  });
}

void check_level_camera(const SceneCase& c) {
  const Scene scene = generators::scene_of(c.spec);
  RC_PRE(!scene.buildings.empty());
  RC_ASSERT(make_method("oh_is", scene)->claims_conservative_for(c.camera));
  const Miss miss = oh_is_misses(scene, c.camera, property_oracle());
  if (!miss.buildings.empty()) RC_LOG() << "replay: " << replay_of(c) << "\n" << miss.description << "\n";
  RC_ASSERT(miss.buildings.empty());
}

RC_GTEST_PROP(ImageSpaceHorizon, ConservativeForLevelCamerasOnGeneratedScenes, ()) {
  check_level_camera(*level(rcgen::scene_case()));
}

RC_GTEST_PROP(ImageSpaceHorizon, ConservativeForLevelCamerasWithOccludersBelowTheEye, ()) {
  check_level_camera(*level(rcgen::scene_case(rcgen::low_occluder_spec(1.7))));
}

RC_GTEST_PROP(ImageSpaceHorizon, ConservativeForLevelCamerasWithOccludersAboveTheEye, ()) {
  check_level_camera(*level(rcgen::scene_case(rcgen::tall_occluder_spec(1.7))));
}

// Narrow views (1-5 degrees: a few bins of screen per metre of wall) and near planes from 1 cm
// to 5 m (what reaches in front of the near plane must not occlude).
RC_GTEST_PROP(ImageSpaceHorizon, ConservativeForLevelCamerasWithNarrowViewsAndDeepNearPlanes, ()) {
  SceneCase c = *level(rcgen::scene_case());
  if (*rc::gen::arbitrary<bool>()) {
    c.camera.hfov = *rc::gen::element(1.0, 2.0, 5.0) * kPi / 180;
    c.camera.vfov = c.camera.hfov;
  }
  c.camera.near = *rc::gen::element(0.1, 0.01, 0.5, 2.0, 5.0);
  c.camera.far = std::max(c.camera.far, c.camera.near * 2);
  check_level_camera(c);
}

// --- Not conservative under pitch and roll (Fig. 3.3) -------------------------------------------

// A perspective camera from the usual generators, then tilted: pitch and roll on a 0.1-degree
// grid, not both zero, shrinking towards the smallest tilt that still fails.
rc::Gen<SceneCase> tilted_case() {
  const auto tilt = rc::gen::suchThat(rc::gen::tuple(rcgen::detail::signed_grid(900, generators::radians(0.1)),
                                                     rcgen::detail::signed_grid(1800, generators::radians(0.1))),
                                      [](const std::tuple<double, double>& t) { return std::get<0>(t) != 0.0 || std::get<1>(t) != 0.0; });
  return rc::gen::mapcat(rcgen::manhattan_spec(), [tilt](const generators::SceneSpec& spec) {
    const Scene scene = generators::scene_of(spec);
    return rc::gen::map(rc::gen::tuple(rcgen::camera_in(scene), tilt), [spec](const std::tuple<Camera, std::tuple<double, double>>& t) {
      SceneCase c{spec, std::get<0>(t)};
      std::tie(c.camera.pitch, c.camera.roll) = std::get<1>(t);
      if (c.camera.omnidirectional()) c.camera.hfov = kPi / 3, c.camera.vfov = kPi / 4;  // 360 degrees: no view plane
      return c;
    });
  });
}

TEST(ImageSpaceHorizon, SearchFindsTheFailureUnderPitchAndRollAndShrinksIt) {
  std::string shrunk;
  const bool held = check_expecting_failure("OH(IS) under pitch and roll", [&shrunk] {
    const SceneCase c = *tilted_case();
    const Scene scene = generators::scene_of(c.spec);
    RC_ASSERT(!make_method("oh_is", scene)->claims_conservative_for(c.camera));
    const Miss miss = oh_is_misses(scene, c.camera, property_oracle());
    if (miss.buildings.empty()) return;
    shrunk = "replay: " + replay_of(c) + "\n  " + std::to_string(scene.buildings.size()) + " buildings; " + miss.description;
    RC_FAIL(miss.description);  // RapidCheck's last failing case is its shrunk one
  });
  EXPECT_FALSE(held) << "the search found no pitched or rolled camera for which OH(IS) culls a visible building";
  std::cerr << "shrunk counterexample: " << shrunk << "\n";
}

// The claims ledger's search (reports/claims.cpp, what `cullcheck report` runs) with its default
// budget: tilted cameras refute the view-plane horizon with a replay, their level twins do not.
TEST(ImageSpaceHorizon, ClaimsLedgerRefutesPitchAndRollAndKeepsLevelCameras) {
  const std::vector<ClaimCheck> claims = check_image_space_pitch_roll({});
  ASSERT_EQ(claims.size(), 2u);
  EXPECT_EQ(claims[0].id, "downs-oh-is-pitch-roll");
  EXPECT_FALSE(claims[0].holds) << "the default search no longer finds a pitched or rolled counterexample";
  EXPECT_NE(claims[0].counterexample_replay.find("--method oh_is --camera"), std::string::npos);
  EXPECT_EQ(claims[1].id, "downs-oh-is-level-cameras");
  EXPECT_TRUE(claims[1].holds) << claims[1].counterexample_replay << "\n" << claims[1].counterexample_detail;
  EXPECT_EQ(claims[0].frames_checked, claims[1].frames_checked);
}

// A recorded counterexample of two buildings, 0 and 1: from the tilted camera, OH(IS) culls
// `seen` although the (densely sampling) oracle sees it; OH(OS), which builds its horizon before
// the view transform, keeps both; and OH(IS) keeps both once the same camera is levelled, so the
// tilt is what breaks it. A failure prints the scene and the camera for `cullcheck verify`.
void expect_tilt_breaks_oh_is(const Scene& scene, const Camera& tilted, ObjectId seen) {
  oracle::OracleOptions dense;
  dense.sampling.spacing_m = 0.5;
  dense.sampling.frustum_resolution = 512;
  const std::vector<ObjectId> both{0, 1};
  Camera level = tilted;
  level.pitch = level.roll = 0.0;
  EXPECT_FALSE(make_method("oh_is", scene)->claims_conservative_for(tilted));
  EXPECT_EQ(oh_is_misses(scene, tilted, dense).buildings, std::vector<ObjectId>{seen});
  EXPECT_EQ(make_method("oh_os_conservative", scene)->cull(tilted).pvs, both);
  EXPECT_EQ(make_method("oh_is", scene)->cull(level).pvs, both);
  if (testing::Test::HasFailure())
    std::cerr << "scene (save as case.json): " << scene_to_json_text(scene) << "replay: cullcheck verify --scene case.json "
              << "--method oh_is --spacing 0.5 --frustum-resolution 512 --camera '" << camera_to_json_text(tilted) << "'\n";
}

// The case the search above shrank to (default RapidCheck seed), recorded: the two buildings of
// `cullcheck generate --generator manhattan --seed 0 --params '{"block_size":20,"blocks_x":1,
// "blocks_y":2,"buildings_per_block":1,"street_width":6,"thin_fraction":0.0,"tower_fraction":0.0}'`
// and a street-level eye rolled by 30.8 degrees (Fig. 3.3c). Building 1 shows past a corner of
// building 0; rolled, the screen's columns lean, and building 0's shadow (one height over its
// whole screen-x range) covers the strip beside its silhouette where building 1 shows.
TEST(ImageSpaceHorizon, RecordedRollCounterexample) {
  Scene scene;
  scene.buildings = {box_building(0, -8.711, -21.25, 8.221, -4.315, 26.53), box_building(1, -4.678, 7.01, 8.581, 21.583, 34.636)};
  expect_tilt_breaks_oh_is(scene, {.position = {-18.711, -31.25, 1.5}, .yaw = 0.6021385919380436, .roll = 0.5375614096142535}, 1);
}

// Pitch alone is enough (Fig. 3.3b): found by the same search with the roll held at 0 (RC_PARAMS
// seed=3), two buildings of `--generator manhattan --seed 0 --params '{"block_size":20,
// "blocks_x":2,"blocks_y":2,"buildings_per_block":2,"street_width":6,"thin_fraction":0.17,
// "tower_fraction":0.0}'`. The eye looks 0.2 degrees down past the corner of a 29 m building
// 2.5 m away; its vertical edges lean on the screen, so the top corner (far above the view)
// widens the shadow's x range past the edge's visible bottom, and the published height (that
// top's y) hides the strip at the bottom of the view where the far building shows.
TEST(ImageSpaceHorizon, RecordedPitchCounterexample) {
  Scene scene;
  scene.buildings = {box_building(0, -21.852, -8.847, -14.169, -6.952, 26.53), box_building(1, -11.772, -6.758, -5.709, -5.082, 29.153)};
  expect_tilt_breaks_oh_is(
      scene, {.position = {-8.669424, -2.618479, 1.5}, .yaw = 4.070107815650776, .pitch = -0.2 * kPi / 180, .hfov = kPi / 6, .vfov = kPi / 12}, 0);
}

// --- Unit cases -----------------------------------------------------------------------------------

TEST(ImageSpaceHorizon, LevelCameraWallHidesWhatIsBehindIt) {
  Scene scene;
  scene.buildings = {box_building(0, 10, -5, 12, 5, 5),     // the wall: screen x in [-0.5, 0.5], top y 0.33
                     box_building(1, 30, -2, 35, 2, 10),    // behind it, top y 0.28: hidden
                     box_building(2, 60, -2, 65, 2, 40),    // behind it, top y 0.64: shows over it
                     box_building(3, 30, 20, 35, 25, 5),    // beside it, in view
                     box_building(4, -20, -2, -15, 2, 10)};  // behind the camera
  const Camera c{.position = {0, 0, 1.7}, .hfov = kPi / 2, .vfov = kPi / 3};
  auto method = make_method("oh_is", scene);
  const CullResult r = method->cull(c);
  EXPECT_EQ(r.pvs, (std::vector<ObjectId>{0, 2, 3}));
  EXPECT_GT(r.stats.occluders_applied, 0u);
  EXPECT_GT(r.stats.horizon_nodes, 0u);
  EXPECT_EQ(r.stats.buildings_tested, 5u);
  EXPECT_EQ(make_method("oh_os_conservative", scene)->cull(c).pvs, r.pvs) << "level camera: both horizons are exact here";
  EXPECT_EQ(dynamic_cast<ImageSpaceHorizonCulling&>(*method).horizon().check_invariants(), "");
}

TEST(ImageSpaceHorizon, ScreenEdgesAreBinnedWithoutWrapAround) {
  ViewPlaneHorizon h(64);
  h.reset(1.0);
  constexpr double inf = std::numeric_limits<double>::infinity();
  // Margins beside the screen are hidden from the start; the screen's outermost bins are not.
  EXPECT_EQ(h.bin_value(0), inf);
  EXPECT_EQ(h.bin_value(63), inf);
  EXPECT_EQ(h.bin_value(1), -inf);
  EXPECT_EQ(h.bin_value(62), -inf);
  EXPECT_EQ(h.bin_of(-1.0), 1u);
  EXPECT_EQ(h.bin_of(1.0), 62u);
  EXPECT_EQ(h.bin_of(-1.001), 0u);
  EXPECT_EQ(h.bin_of(1.001), 63u);
  // A shadow from beyond the left edge to the middle raises the leftmost screen bin...
  h.raise(-5.0, 0.0, 2.0);
  EXPECT_NEAR(h.bin_value(1), 2.0, 1e-8);
  EXPECT_EQ(h.bin_value(0), inf);
  // ...and nothing at the right edge: a range touching the right edge does not wrap to the left.
  EXPECT_EQ(h.bin_value(62), -inf);
  EXPECT_EQ(h.min_over(0.99, 1.0), -inf);
  EXPECT_FALSE(h.hides(0.99, 3.0, -100.0));
  EXPECT_TRUE(h.hides(-1.0, -0.99, 1.9));
  EXPECT_TRUE(h.hides(-3.0, -0.99, 1.9)) << "straddling the left edge reads the margin (+inf) and bin 1";
  EXPECT_FALSE(h.hides(-1.0, -0.99, 2.1));
  // Wholly beside the screen: hidden whatever its height.
  EXPECT_EQ(h.min_over(-3.0, -2.0), inf);
  EXPECT_EQ(h.min_over(2.0, 3.0), inf);
  // A shadow beyond both edges raises every screen bin; one that stops at an edge keeps the
  // bins it does not cover wholly.
  h.raise(-2.0, 2.0, 1.0);
  EXPECT_NEAR(h.min_over(-1.0, 1.0), 1.0, 1e-8);
  EXPECT_EQ(h.check_invariants(), "");

  // Through the method: a wall across the whole 90-degree view hides what is behind it up to
  // both edges, and only the wall.
  Scene scene;
  scene.buildings = {box_building(0, 10, -30, 11, 30, 10), box_building(1, 30, -31, 32, -28, 5),
                     box_building(2, 30, 28, 32, 31, 5)};
  const Camera c{.position = {0, 0, 1.7}, .hfov = kPi / 2, .vfov = kPi / 3};
  EXPECT_EQ(make_method("oh_is", scene)->cull(c).pvs, std::vector<ObjectId>{0});
  scene.buildings.erase(scene.buildings.begin());
  EXPECT_EQ(make_method("oh_is", scene)->cull(c).pvs, (std::vector<ObjectId>{1, 2})) << "both straddle a screen edge";
}

TEST(ImageSpaceHorizon, OccludersInFrontOfTheNearPlaneAreNotUsed) {
  Camera c{.position = {0, 0, 1.7}, .hfov = kPi / 2, .vfov = kPi / 3};
  c.near = 2.0;
  auto pvs_behind = [&](double wall_from, double wall_to) {
    Scene scene;
    scene.buildings = {box_building(0, wall_from, -20, wall_to, 20, 30), box_building(1, 40, -2, 45, 2, 10)};
    return make_method("oh_is", scene)->cull(c).pvs;
  };
  EXPECT_EQ(pvs_behind(1.0, 1.5), std::vector<ObjectId>{1}) << "wall wholly in front of the near plane (clipped)";
  EXPECT_EQ(pvs_behind(1.5, 3.0), (std::vector<ObjectId>{0, 1})) << "wall reaching in front of the near plane";
  EXPECT_EQ(pvs_behind(3.0, 3.5), std::vector<ObjectId>{0}) << "wall wholly beyond the near plane";
}

TEST(ImageSpaceHorizon, ClaimsLevelAndOmnidirectionalCamerasOnly) {
  Scene scene;
  scene.buildings = {box_building(0, 10, -2, 12, 2, 8)};
  auto method = make_method("oh_is", scene);
  EXPECT_FALSE(method->claims_conservative());
  Camera c{.position = {0, 0, 1.7}};
  EXPECT_TRUE(method->claims_conservative_for(c));
  c.pitch = 1e-6;
  EXPECT_FALSE(method->claims_conservative_for(c));
  c.pitch = 0.0, c.roll = -1e-6;
  EXPECT_FALSE(method->claims_conservative_for(c));
  c.hfov = kTwoPi;
  EXPECT_TRUE(method->claims_conservative_for(c));
  EXPECT_TRUE(make_method("oh_os_conservative", scene)->claims_conservative_for(c));
}

// 360 degrees has no view plane: OH(IS) is view-volume culling then. Extreme orientations and
// fields of view never crash.
TEST(ImageSpaceHorizon, OmnidirectionalAndExtremeCamerasAreHandled) {
  Scene scene;
  scene.buildings = {box_building(0, 10, -2, 12, 2, 8), box_building(1, -12, -2, -10, 2, 8), box_building(2, 30, -1, 32, 1, 4),
                     box_building(3, -2, -2, 2, 2, 3)};
  Camera c{.position = {0, 0, 10}, .hfov = kTwoPi, .vfov = kPi / 2};
  auto method = make_method("oh_is", scene);
  const CullResult r = method->cull(c);
  EXPECT_EQ(r.pvs, make_method("frustum", scene)->cull(c).pvs);
  EXPECT_EQ(r.stats.horizon_nodes, 0u);
  for (double pitch : {-kPi / 2, kPi / 2, -1.0})
    for (double hfov : {generators::radians(0.01), kPi / 2, generators::radians(179.0)}) {
      c.pitch = pitch, c.hfov = hfov, c.vfov = hfov / 2;
      const std::vector<ObjectId> pvs = method->cull(c).pvs, in_view = make_method("frustum", scene)->cull(c).pvs;
      EXPECT_TRUE(std::includes(in_view.begin(), in_view.end(), pvs.begin(), pvs.end()));
    }
}

// The design's numerical extremes, for level cameras (the ones OH(IS) claims): millimetre slabs
// and a 10 km wall, an occluder exactly at eye height, touching and collinear walls, a 2 mm
// sliver, a 0.0001-degree view, an eye on a wall, on a corner and inside a building, a slab
// reaching in front of the near plane. The oracle samples at its default density (2 m; the 10 km
// wall makes denser sampling slow).
TEST(ImageSpaceHorizon, LevelCameraNumericalExtremes) {
  Building sliver, slab;
  sliver.id = 5, sliver.height = 20, sliver.footprint = {{10, 0}, {30, 0.001}, {10, 0.002}};
  slab.id = 6, slab.height = 10, slab.footprint = {{0.05, -0.02}, {3, 2.93}, {2.999, 2.931}, {0.049, -0.019}};
  validate_and_finish(sliver);
  validate_and_finish(slab);
  Scene s;
  s.buildings = {box_building(0, 10, -0.0005, 10.001, 3, 20), box_building(1, 30, -5000, 40, 5000, 30),
                 box_building(2, 20, -1, 22, 1, 1.7), box_building(3, 60, -2, 64, 2, 50), box_building(4, 20, 1, 22, 4, 1.7),
                 sliver, slab, box_building(7, 20, 8, 21, 12, 10), box_building(8, -10, 5, -5, 10, 12)};
  const double tiny = 1e-4 * kPi / 180;
  std::vector<Camera> cameras;
  for (double yaw : {0.0, 0.1, 0.45, 0.6, kPi / 2, std::nextafter(kTwoPi, 0.0)})
    for (double z : {1.7, 35.0, 80.0})
      for (double hfov : {kPi / 2, tiny, kTwoPi}) cameras.push_back({.position = {0, 0, z}, .yaw = yaw, .hfov = hfov, .vfov = std::min(hfov, kPi / 3)});
  for (Vec3 eye : {Vec3{-7, 5, 1.7}, Vec3{-10, 5, 1.7}, Vec3{22, 1, 1.7}, Vec3{-7.5, 7.5, 1.7}})  // on a wall, a corner, a low roof, inside
    for (double yaw : {0.0, kPi / 2, kPi, 3 * kPi / 2}) cameras.push_back({.position = eye, .yaw = yaw});
  Camera deep_near{.position = {0, 0, 1.7}, .yaw = 0.45, .hfov = 1.2, .vfov = 0.8};
  deep_near.near = 0.5;
  cameras.push_back(deep_near);
  const oracle::Oracle truth(s);
  auto oh_is = make_method("oh_is", s);
  for (const Camera& c : cameras)
    EXPECT_EQ(oh_is_misses(truth, *oh_is, c, {}).description, "") << "camera " << camera_to_json_text(c);
  const std::vector<ObjectId> street_view = oh_is->cull(cameras.front()).pvs;  // level, east, 90 degrees
  // The tower behind the 10 km wall stays in the PVS: a shadow is merged only once the sweep has
  // passed its CVP's farthest point ("update OH at its maximum distance"), 5 km away here.
  EXPECT_TRUE(std::binary_search(street_view.begin(), street_view.end(), 3u));
}

}  // namespace
}  // namespace cullcheck
