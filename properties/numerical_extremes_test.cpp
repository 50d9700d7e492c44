// Numerical extremes (design: "Numerical extremes (each a test)"): each case runs every method
// claimed conservative and holds it to the oracle; none may crash, none may cull what the
// oracle sees. Float versus double: the engine and the CGAL exact plan view compute in double
// (exact predicates and constructions for CGAL), the Embree oracle in float relative to a
// whole-metre origin near the scene's centre (oracle/mesh.hpp); the UTM city below goes
// through both paths, before and after rebasing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"
#include "core/random.hpp"
#include "core/scene_io.hpp"
#include "engine/method.hpp"
#include "generators/city.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {
namespace {

Camera camera_at(Vec3 eye, double yaw, double pitch = 0.0, double hfov = kPi / 2, double vfov = kPi / 3) {
  Camera c;
  c.position = eye;
  c.yaw = yaw;
  c.pitch = pitch;
  c.hfov = hfov;
  c.vfov = vfov;
  return c;
}

// Holds every conservative method to the oracle; returns the oracle's set for further checks.
std::vector<ObjectId> expect_conservative(const Scene& scene, const Camera& camera, const std::string& label) {
  const oracle::Oracle truth(scene);
  oracle::OracleOptions options;
  options.sampling.spacing_m = 0.5;
  const oracle::OracleAnswer seen = truth.visible_set(camera, options);
  for (const std::string& name : method_names()) {
    auto method = make_method(name, scene);
    if (!method->unsupported_camera(camera).empty()) continue;  // frustum culling by ranges refuses 360-degree views
    if (!method->claims_conservative_for(camera)) continue;     // OH(IS): level cameras; polar diagrams: the exact plan view
    const CullResult r = method->cull(camera);
    for (ObjectId id : seen.visible)
      EXPECT_TRUE(std::binary_search(r.pvs.begin(), r.pvs.end(), id))
          << label << ": " << name << " culled building " << id << " which the oracle sees; camera "
          << camera_to_json_text(camera);
  }
  return seen.visible;
}

// A street with buildings on both sides and a row behind, used by several cases.
Scene street(double offset_x = 0.0, double offset_y = 0.0) {
  Scene s;
  ObjectId id = 0;
  for (int i = 0; i < 6; ++i) {
    const double x = offset_x + i * 12.0;
    s.buildings.push_back(box_building(id++, x, offset_y + 8, x + 10, offset_y + 20, 6.0 + 3 * (i % 3)));
    s.buildings.push_back(box_building(id++, x, offset_y - 20, x + 10, offset_y - 8, 15.0 - 2 * (i % 4)));
    s.buildings.push_back(box_building(id++, x + 2, offset_y + 26, x + 8, offset_y + 30, 25.0));
  }
  return s;
}

TEST(NumericalExtremes, CoordinatesOffsetByTenMillionMetres) {
  Scene far = street(1.0e7, 1.0e7);
  far = scene_from_json_text(scene_to_json_text(far));  // loading rebases it
  ASSERT_GT(std::abs(far.origin.x), 1e6);
  const Scene near = street();
  for (double yaw : {0.0, 0.4, kPi}) {
    const Vec3 eye_far{1.0e7 + 5 - far.origin.x, 1.0e7 - far.origin.y, 1.7};
    const auto seen_far = expect_conservative(far, camera_at(eye_far, yaw), "offset 1e7");
    const auto seen_near = expect_conservative(near, camera_at({5, 0, 1.7}, yaw), "at origin");
    EXPECT_EQ(seen_far, seen_near) << "yaw " << yaw;
    EXPECT_EQ(make_method("oh_os_conservative", far)->cull(camera_at(eye_far, yaw)).pvs,
              make_method("oh_os_conservative", near)->cull(camera_at({5, 0, 1.7}, yaw)).pvs);
  }
}

TEST(NumericalExtremes, OneMillimetreAndTenKilometreBuildings) {
  Scene s;
  s.buildings = {box_building(0, 10, -0.0005, 10.001, 3, 20),    // 1 mm thin slab
                 box_building(1, 30, -5000, 40, 5000, 30),       // 10 km long wall
                 box_building(2, 20, -1, 22, 1, 4), box_building(3, 60, -2, 64, 2, 50)};
  for (double yaw : {0.0, 0.1, -0.1 + kTwoPi})
    for (double z : {1.7, 35.0, 80.0}) expect_conservative(s, camera_at({0, 0, z}, yaw, z > 30 ? -0.4 : 0.0), "mm and km");
}

TEST(NumericalExtremes, OccluderExactlyAtEyeHeight) {
  Scene s;
  s.buildings = {box_building(0, 10, -5, 11, 5, 1.7), box_building(1, 20, -1, 21, 1, 1.7), box_building(2, 30, -1, 31, 1, 1.0),
                 box_building(3, 40, -1, 41, 1, 2.5)};
  const auto seen = expect_conservative(s, camera_at({0, 0, 1.7}, 0.0), "eye height");
  EXPECT_TRUE(std::binary_search(seen.begin(), seen.end(), 3u));  // shows above the eye-height wall
}

TEST(NumericalExtremes, ViewpointOnAWallOnACornerAndInsideABuilding) {
  const Scene s = street();
  const Vec3 on_wall{5, 8, 1.7}, on_corner{0, 8, 1.7}, inside{5, 14, 1.7};
  for (const Vec3& eye : {on_wall, on_corner, inside})
    for (double yaw : {0.0, kPi / 2, kPi, 3 * kPi / 2}) expect_conservative(s, camera_at(eye, yaw), "eye on or in a building");
}

TEST(NumericalExtremes, AzimuthExactlyZeroPiAndJustBelowTwoPi) {
  Scene s;
  // Buildings straddling azimuth 0 (east), at π (west), and at the wrap from both sides.
  s.buildings = {box_building(0, 10, -2, 12, 2, 10), box_building(1, 30, -6, 32, 6, 20), box_building(2, -12, -2, -10, 2, 10),
                 box_building(3, -32, -6, -30, 6, 20), box_building(4, 20, -0.5, 21, 0.0, 30), box_building(5, 20, 0.0, 21, 0.5, 30)};
  for (double yaw : {0.0, kPi, std::nextafter(kTwoPi, 0.0), kPi / 2})
    for (double hfov : {kPi / 2, kTwoPi}) expect_conservative(s, camera_at({0, 0, 1.7}, yaw, 0.0, hfov), "azimuth wrap");
}

TEST(NumericalExtremes, CollinearAndTouchingWalls) {
  Scene s;
  s.buildings = {box_building(0, 10, -5, 12, 0, 10), box_building(1, 10, 0, 12, 5, 10),  // share the wall y = 0
                 box_building(2, 12, -5, 14, 5, 8),                           // touches both
                 box_building(3, 20, -0.5, 21, 0.5, 30),                      // behind the seam
                 box_building(4, 10, 5, 12, 10, 12)};                         // collinear with 0 and 1
  for (double y : {0.0, 1e-9, -1e-9, 5.0}) expect_conservative(s, camera_at({0, y, 1.7}, 0.0), "touching walls");
}

TEST(NumericalExtremes, SliverFootprintsWorkAndZeroAreaIsRefused) {
  Scene s;
  Building sliver;
  sliver.id = 0;
  sliver.height = 20;
  sliver.footprint = {{10, 0}, {30, 0.001}, {10, 0.002}};  // 20 m long, 2 mm wide triangle
  validate_and_finish(sliver);
  s.buildings = {sliver, box_building(1, 40, -1, 41, 1, 5)};
  expect_conservative(s, camera_at({0, 0.001, 1.7}, 0.0), "sliver");
  expect_conservative(s, camera_at({0, 10, 1.7}, -kPi / 4), "sliver, oblique");
  Building flat;
  flat.id = 2;
  flat.height = 5;
  flat.footprint = {{0, 0}, {1, 1}, {2, 2}};
  EXPECT_THROW(validate_and_finish(flat), InputError);
}

TEST(NumericalExtremes, FieldOfViewNearZeroAndFullCircle) {
  const Scene s = street();
  const double tiny = 1e-4 * kPi / 180;  // 0.0001 degrees
  expect_conservative(s, camera_at({5, 0, 1.7}, 0.0, 0.0, tiny, tiny), "fov 0.0001 degrees");
  expect_conservative(s, camera_at({5, 0, 1.7}, kPi / 2, 0.0, tiny, tiny), "fov 0.0001 degrees at a wall");
  expect_conservative(s, camera_at({5, 0, 1.7}, 0.0, 0.0, kTwoPi), "fov 360 degrees");
  expect_conservative(s, camera_at({5, 0, 40.0}, 0.0, 0.0, kTwoPi), "fov 360 degrees above the roofs");
  EXPECT_THROW(validate(camera_at({5, 0, 1.7}, 0.0, 0.0, kPi)), InputError);  // 180: neither kind
}

TEST(NumericalExtremes, PitchPlusMinusNinetyDegrees) {
  const Scene s = street();
  for (double pitch : {kPi / 2, -kPi / 2})
    for (double roll : {0.0, 1.0})
      for (double z : {1.7, 40.0}) {
        Camera c = camera_at({5, 0, z}, 0.3, pitch);
        c.roll = roll;
        expect_conservative(s, c, "pitch +-90");
      }
}

// Geometry nearer than the near plane is clipped and hides nothing: a thin slab running away
// from the eye, whose first half metre is clipped, must not hide what is seen past its clipped
// end (found by hand; the engine now skips occluders that may reach in front of the near plane).
TEST(NumericalExtremes, OccluderReachingInFrontOfTheNearPlane) {
  Scene s;
  Building slab;
  slab.id = 0;
  slab.height = 10;
  slab.footprint = {{0.05, -0.02}, {3, 2.93}, {2.999, 2.931}, {0.049, -0.019}};
  validate_and_finish(slab);
  s.buildings = {slab, box_building(1, 20, 8, 21, 12, 10)};
  for (double yaw : {0.45, 0.6}) {
    Camera c = camera_at({0, 0, 1.7}, yaw, 0.0, 1.2, 0.8);
    c.near = 0.5;
    const auto seen = expect_conservative(s, c, "near-plane clipping");
    EXPECT_TRUE(std::binary_search(seen.begin(), seen.end(), 1u));
  }
}


// ---------------------------------------------------------------------------------------------
// A 10 km x 10 km city at UTM coordinates: easting 5e5, northing 5e6, where a user's city in a
// UTM zone lies. The generated city (centred on the origin) is translated there. `world` keeps
// those coordinates (origin 0, nothing rebased: the engine and CGAL compute on 5e6-sized doubles,
// the Embree oracle on floats relative to its own whole-metre origin); `local` is the same scene
// rebased as a loaded file is (rebase_if_far: coordinates within 5.1 km of 0). The shift is a
// whole number of metres within a factor of two of every coordinate, so rebasing is exact
// (Sterbenz): both are the same geometry, and every answer must agree, the oracle's and each
// conservative method's PVS, which must hold the oracle's visible set in both.
//
// At CI budget the pinned cases below run (eyes at the city's edge, outside it, at its corner and
// inside; at street level, where the plan view is exact, and above the roofs, where Embree
// samples); CULLCHECK_RC_BUDGET=N adds 8 (N - 1) seeded cases, and CULLCHECK_UTM_CASE=i runs
// seeded case i alone (the replay every failure prints).
namespace utm {

constexpr Vec2 kOffset{5.0e5, 5.0e6};
// Manhattan grid: 23 x 23 blocks of 400 m, 40 m streets around and between: 10.16 km across.
constexpr int kBlocks = 23;
constexpr double kBlock = 400.0, kStreet = 40.0;
constexpr double kExtent = kBlocks * kBlock + (kBlocks + 1) * kStreet;
constexpr double kEye = 1.7;
constexpr double kRegionRadius = 0.5;

// Centre line of street k (0 .. kBlocks) in the generated city's coordinates.
double street_line(int k) { return -kExtent / 2 + kStreet / 2 + k * (kBlock + kStreet); }

struct City {
  std::string label;
  std::uint64_t seed = 0;
  nlohmann::json params;
  Scene world, local;
  std::string file;  // for CLI replays: world coordinates, which loading rebases to `local`
  std::unique_ptr<oracle::Oracle> world_truth, local_truth;
};

// `uniform`: every building 20 m (taller than the eye, none seen over another: the plan view is
// the 3D truth at street level, so the oracle is CGAL's exact 2D). `varied`: 8-40 m with towers
// to 150 m (the Embree oracle everywhere).
std::unique_ptr<City> make(const std::string& label, bool uniform) {
  auto c = std::make_unique<City>();
  c->label = label;
  c->seed = uniform ? 5 : 6;
  c->params = {{"blocks_x", kBlocks}, {"blocks_y", kBlocks}, {"block_size", kBlock}, {"street_width", kStreet},
               {"buildings_per_block", 6}, {"thin_fraction", 0.1}};
  if (uniform) c->params.update({{"min_height", 20.0}, {"max_height", 20.0}, {"tower_fraction", 0.0}});
  c->world = generators::make_city("manhattan", c->seed, c->params);
  for (Building& b : c->world.buildings) {
    for (Vec2& p : b.footprint) p = p + kOffset;
    validate_and_finish(b);
  }
  c->local = c->world;
  rebase_if_far(c->local);
  c->file = ::testing::TempDir() + "numerical_extremes_utm_" + label + ".json";
  write_scene_file(c->local, c->file);
  c->world_truth = std::make_unique<oracle::Oracle>(c->world);
  c->local_truth = std::make_unique<oracle::Oracle>(c->local);
  return c;
}
const City& uniform_city() {
  static const std::unique_ptr<City> c = make("uniform", true);
  return *c;
}
const City& varied_city() {
  static const std::unique_ptr<City> c = make("varied", false);
  return *c;
}

// The oracle's density: buildings here are 60-400 m wide, so surface samples every 8 m (at
// least a 4 x 4 grid per face), one thread (results do not depend on it).
oracle::OracleOptions density() {
  oracle::OracleOptions o;
  o.sampling.spacing_m = 8.0;
  o.sampling.frustum_resolution = 128;
  o.sampling.threads = 1;
  return o;
}

std::string camera_text(const Camera& c) {
  std::string t = camera_to_json_text(c);
  if (!t.empty() && t.back() == '\n') t.pop_back();
  return t;
}

// One frame's answers: the oracle's, and the PVS of every method that claims conservativeness
// for this camera (point methods by name, region methods as "region:NAME" over a 0.5 m disc
// centred on the camera, which the oracle's eye lies in).
struct Answers {
  oracle::OracleAnswer seen;
  std::map<std::string, std::vector<ObjectId>> pvs;
};
Answers answer(const Scene& scene, const oracle::Oracle& truth, const Camera& camera) {
  Answers a;
  a.seen = truth.visible_set(camera, density());
  for (const std::string& name : method_names()) {
    auto method = make_method(name, scene);
    if (!method->unsupported_camera(camera).empty() || !method->claims_conservative_for(camera)) continue;
    a.pvs[name] = method->cull(camera).pvs;
  }
  for (const std::string& name : region_method_names()) {
    auto method = make_region_method(name, scene);
    if (!method->claims_conservative()) continue;
    a.pvs["region:" + name] = method->cull_region({camera, kRegionRadius, 0.0}).pvs;
  }
  return a;
}

struct Case {
  Case() = default;
  Case(std::string label_, Vec2 at_, double z_ = kEye, double yaw_ = 0.0, double pitch_ = 0.0, double hfov_ = kPi / 2,
       double far_ = 1.0e5)
      : label(std::move(label_)), at(at_), z(z_), yaw(yaw_), pitch(pitch_), hfov(hfov_), far(far_) {}

  std::string label;
  Vec2 at;  // in the generated city's coordinates (world = at + kOffset)
  double z = kEye, yaw = 0.0, pitch = 0.0, hfov = kPi / 2;
  double far = 1.0e5;  // beyond the city unless a case says otherwise
  double near = 0.1;
  std::optional<Vec2> world_at;  // instead of `at`: a world position (beside_wall)
};

Camera world_camera(const Case& k) {
  Camera c;
  c.position = k.world_at ? Vec3{k.world_at->x, k.world_at->y, k.z} : Vec3{k.at.x + kOffset.x, k.at.y + kOffset.y, k.z};
  c.yaw = k.yaw;
  c.pitch = k.pitch;
  c.hfov = k.hfov;
  c.vfov = k.hfov >= kTwoPi ? kPi / 2 : k.hfov * 0.6;
  c.far = k.far;
  c.near = k.near;
  return c;
}

// Checks one case in both frames; returns the oracle's model (for the caller to pin) and the
// size of its visible set. `replay` is the one command that reruns the case.
std::pair<std::string, std::size_t> check(const City& city, const Case& k, const std::string& replay) {
  const Camera in_world = world_camera(k);
  Camera in_local = in_world;
  in_local.position = {in_world.position.x - city.local.origin.x, in_world.position.y - city.local.origin.y, in_world.position.z};
  // Exact (Sterbenz), so the two cameras stand at the same point of the same geometry.
  EXPECT_EQ(in_local.position.x + city.local.origin.x, in_world.position.x);
  EXPECT_EQ(in_local.position.y + city.local.origin.y, in_world.position.y);
  const Answers w = answer(city.world, *city.world_truth, in_world), l = answer(city.local, *city.local_truth, in_local);
  // The failure's replays: this test's case, and the CLI on the rebased scene (the file holds
  // world coordinates, loading rebases them; the camera is scene-local).
  const std::string where = city.label + " city, " + k.label + ", camera (local) " + camera_text(in_local) +
                            "\n  replay: " + replay + "\n  or: build/apps/cullcheck/cullcheck verify --scene " + city.file +
                            " --camera '" + camera_text(in_local) + "' --spacing 8 --frustum-resolution 128";
  auto with_method = [&](const std::string& name) {
    if (name.rfind("region:", 0) == 0)
      return where + " --method frustum --region-method " + name.substr(7) + " --region-radius " + std::to_string(kRegionRadius);
    return where + " --method " + name;
  };
  EXPECT_EQ(w.seen.model, l.seen.model) << where;
  EXPECT_EQ(w.seen.visible, l.seen.visible) << "the oracle's visible set changed with rebasing: " << where;
  EXPECT_EQ(w.pvs.size(), l.pvs.size()) << where;
  for (const auto& [name, pvs] : l.pvs) {
    const auto other = w.pvs.find(name);
    if (other == w.pvs.end()) continue;
    EXPECT_EQ(other->second, pvs) << name << "'s PVS changed with rebasing: " << with_method(name);
    for (const auto* frame : {&w, &l}) {
      const auto& held = frame->pvs.at(name);
      for (ObjectId id : frame->seen.visible) {
        if (std::binary_search(held.begin(), held.end(), id)) continue;
        std::string witness;
        if (frame->seen.sampling && frame->seen.sampling->witnesses.count(id))
          witness = ", witness " + oracle::describe(frame->seen.sampling->witnesses.at(id));
        ADD_FAILURE() << name << " culled building " << id << " which the oracle (" << frame->seen.model << witness << ") sees, "
                      << (frame == &w ? "un-rebased" : "rebased") << ": " << with_method(name);
      }
    }
  }
  return {l.seen.model, l.seen.visible.size()};
}

// A world position `gap` metres outside wall `edge` of building `index` (world coordinates), at
// fraction `t` along it: where the eye is nearly on a wall, spans are widest and the rounding of
// 5e6-sized coordinates over the distance is largest. Buildings stand at least 2 m apart, so a
// gap below that is outside every footprint.
Vec2 beside_wall(const City& city, std::size_t index, std::size_t edge, double t, double gap) {
  const std::vector<Vec2>& ring = city.world.buildings.at(index).footprint;
  const Vec2 p = ring[edge % ring.size()], q = ring[(edge + 1) % ring.size()], d = q - p;
  const Vec2 outward = Vec2{d.y, -d.x} * (1.0 / length(d));  // right of a counter-clockwise edge
  return p + d * t + outward * gap;
}

std::string pinned_replay() { return "build/properties/numerical_extremes_test --gtest_filter=NumericalExtremes.UtmCity*"; }

}  // namespace utm

TEST(NumericalExtremes, UtmCityIsTranslatedAndRebasedExactly) {
  const utm::City& city = utm::uniform_city();
  EXPECT_EQ(city.world.origin, (Vec2{0.0, 0.0}));
  EXPECT_EQ(city.local.origin, (Vec2{5.0e5, 5.0e6}));  // the city is centred on its generated origin
  ASSERT_EQ(city.world.buildings.size(), city.local.buildings.size());
  EXPECT_EQ(city.world.buildings.size(), 3174u);  // 23 x 23 blocks x 6 lots
  const Box2 world = city.world.bounds().plan(), local = city.local.bounds().plan();
  EXPECT_NEAR(world.hi.x - world.lo.x, 10'000, 200);
  EXPECT_NEAR(world.hi.y - world.lo.y, 10'000, 200);
  EXPECT_GT(world.lo.y, 4.99e6);
  EXPECT_LT(std::max(std::abs(local.lo.x), std::abs(local.hi.x)), 5100.0);
  for (std::size_t i = 0; i < city.world.buildings.size(); ++i)
    for (std::size_t v = 0; v < city.world.buildings[i].footprint.size(); ++v) {
      const Vec2 a = city.world.buildings[i].footprint[v], b = city.local.buildings[i].footprint[v];
      ASSERT_EQ(b + city.local.origin, a) << "building " << i << " vertex " << v << ": rebasing is not exact";
    }
}

// Street level in the uniform city: CGAL's exact plan view is the oracle (double, exact).
TEST(NumericalExtremes, UtmCityAtStreetLevelHeldToTheExactPlanView) {
  using utm::street_line;
  const utm::City& city = utm::uniform_city();
  const std::vector<utm::Case> cases{
      {"west edge street looking north", {street_line(0), street_line(5) + 100}, utm::kEye, kPi / 2},
      {"west edge looking east down a 10 km street", {street_line(0), street_line(8)}, utm::kEye, 0.0},
      {"outside the city looking in", {-utm::kExtent / 2 - 50, 130}, utm::kEye, 0.1},
      {"city corner looking in", {street_line(utm::kBlocks), street_line(utm::kBlocks)}, utm::kEye, 5 * kPi / 4},
      {"inside, 360 degrees", {street_line(11), street_line(12)}, utm::kEye, 0.0, 0.0, kTwoPi},
      {"inside, mid-street", {street_line(12), street_line(12) + 150}, utm::kEye, 3 * kPi / 2 - 0.2},
      {"1 cm from a wall at the city's edge, looking along it", {}, utm::kEye, 0.0},
      {"1 mm from a wall inside, looking past its corner", {}, utm::kEye, 0.0},
  };
  // The exact plan view's visible counts, pinned (the city is seeded, the plan view exact).
  const std::vector<std::size_t> expected_seen{16, 47, 3, 47, 99, 23, 2, 3};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    utm::Case k = cases[i];
    if (i == 6) {  // building 0 stands in the south-west corner block; its first edge faces south
      k.world_at = utm::beside_wall(city, 0, 0, 0.5, 0.01);
      k.yaw = 0.02;
      k.near = 1e-4;  // nearer than the wall, so that the plan view is still the truth
    } else if (i == 7) {
      k.world_at = utm::beside_wall(city, city.world.buildings.size() / 2, 1, 0.999, 0.001);
      k.yaw = kPi / 2 + 0.3;
      k.near = 1e-4;
    }
    const auto [model, seen] = utm::check(city, k, utm::pinned_replay());
    EXPECT_EQ(model, oracle::kModelExact2d) << k.label;
    EXPECT_EQ(seen, expected_seen[i]) << k.label;
  }
}

// Above the roofs (uniform city) and at street level among varied heights: Embree (float) is the
// oracle. (Some far planes are a few km, not beyond the city: the oracle samples every object in
// the view volume, and 3 million rays a case would not fit the CI budget.)
TEST(NumericalExtremes, UtmCityHeldToEmbreeAboveRoofsAndAmongVariedHeights) {
  using utm::street_line;
  const std::vector<utm::Case> above{
      {"inside, above the roofs, looking down", {street_line(11), street_line(11)}, 45.0, 0.7, -0.3, kPi / 2, 2000.0},
      {"beyond the west edge, above the roofs", {-utm::kExtent / 2 - 20, 0.0}, 60.0, 0.0, -0.2, kPi / 2, 3000.0},
  };
  for (const utm::Case& k : above) {
    const auto [model, seen] = utm::check(utm::uniform_city(), k, utm::pinned_replay());
    EXPECT_EQ(model, oracle::kModelRaySampling3d) << k.label;
    EXPECT_GT(seen, 0u) << k.label;
  }
  const std::vector<utm::Case> street{
      {"west edge street looking north", {street_line(0), street_line(5) + 100}, utm::kEye, kPi / 2, 0.0, kPi / 2, 4000.0},
      {"inside, 360 degrees", {street_line(11), street_line(12)}, utm::kEye, 0.0, 0.0, kTwoPi, 3000.0},
      {"city corner looking in", {street_line(utm::kBlocks), street_line(utm::kBlocks)}, utm::kEye, 5 * kPi / 4, 0.0,
       kPi / 2, 4000.0},
  };
  for (const utm::Case& k : street) {
    const auto [model, seen] = utm::check(utm::varied_city(), k, utm::pinned_replay());
    EXPECT_EQ(model, oracle::kModelRaySampling3d) << k.label;
    EXPECT_GT(seen, 0u) << k.label;
  }
}

// Guarded ΔH at UTM scale: along a walk (lateral steps past the buildings) it gives OH(OS)'s
// PVS at every frame, in both frames of coordinates, and the two frames agree.
TEST(NumericalExtremes, UtmCityGuardedDeltaHorizonEqualsFullHorizonAlongAWalk) {
  const utm::City& city = utm::varied_city();
  for (const Scene* scene : {&city.world, &city.local}) {
    const Vec2 shift = scene == &city.world ? utm::kOffset : utm::kOffset - city.local.origin;
    auto guarded = make_method("delta_h_guarded", *scene), full = make_method("oh_os_conservative", *scene);
    std::uint64_t fires = 0;
    for (int frame = 0; frame < 40; ++frame) {
      Camera c;
      c.position = {utm::street_line(3) + shift.x + 0.3 * frame, utm::street_line(0) + 60 + shift.y + 0.05 * frame, utm::kEye};
      c.yaw = kPi / 2 + 0.001 * frame;
      c.hfov = kPi / 2;
      c.vfov = kPi / 3;
      const CullResult g = guarded->cull(c);
      fires += g.stats.guard_fires;
      ASSERT_EQ(g.pvs, full->cull(c).pvs) << (scene == &city.world ? "un-rebased" : "rebased") << " frame " << frame
                                          << " camera " << utm::camera_text(c) << "; replay: " << utm::pinned_replay();
    }
    EXPECT_GT(fires, 1u);  // the walk leaves motion regions: re-anchoring is exercised too
  }
}

// Seeded cases: CULLCHECK_RC_BUDGET=N runs 8 (N - 1) of them, CULLCHECK_UTM_CASE=i runs case i.
TEST(NumericalExtremes, UtmCitySeededCases) {
  long budget = 1;
  if (const char* b = std::getenv("CULLCHECK_RC_BUDGET")) budget = std::max(1L, std::strtol(b, nullptr, 10));
  long first = 0, count = 8 * (budget - 1);
  if (const char* only = std::getenv("CULLCHECK_UTM_CASE")) first = std::strtol(only, nullptr, 10), count = 1;
  if (count == 0) GTEST_SKIP() << "long mode: CULLCHECK_RC_BUDGET=N (N > 1) or CULLCHECK_UTM_CASE=i";
  for (long i = first; i < first + count; ++i) {
    Random r = Random::stream(20261201, static_cast<std::uint64_t>(i));
    const bool uniform = r.uniform01() < 0.5;
    const bool along_x = r.uniform01() < 0.5;
    const int street = static_cast<int>(r.uniform01() * (utm::kBlocks + 1));
    const double along = (r.uniform01() - 0.5) * (utm::kExtent + 200.0);  // may leave the city at either end
    const double across = (r.uniform01() - 0.5) * (utm::kStreet - 4.0);
    utm::Case k;
    k.label = "seeded case " + std::to_string(i);
    k.at = along_x ? Vec2{along, utm::street_line(street) + across} : Vec2{utm::street_line(street) + across, along};
    k.yaw = r.uniform01() * kTwoPi;
    const double kind = r.uniform01();
    if (kind < 0.25) k.hfov = kTwoPi;
    if (r.uniform01() < 0.3) k.z = 30.0 + 40.0 * r.uniform01(), k.pitch = -0.5 * r.uniform01();
    const utm::City& city = uniform ? utm::uniform_city() : utm::varied_city();
    if (r.uniform01() < 0.3) {  // nearly on a wall: 1 mm to 10 cm away
      const auto b = static_cast<std::size_t>(r.uniform01() * static_cast<double>(city.world.buildings.size()));
      const auto edge = static_cast<std::size_t>(r.uniform01() * 4.0);
      // Distance before position: the order gcc gave when both draws were arguments of one call.
      const double gap = std::pow(10.0, -3.0 + 2.0 * r.uniform01());
      const double along_wall = r.uniform01();
      k.world_at = utm::beside_wall(city, b, edge, along_wall, gap);
    }
    const std::string replay = "CULLCHECK_UTM_CASE=" + std::to_string(i) +
                               " build/properties/numerical_extremes_test --gtest_filter=NumericalExtremes.UtmCitySeededCases";
    SCOPED_TRACE(k.label + "; replay: " + replay);
    utm::check(city, k, replay);
  }
}

}  // namespace
}  // namespace cullcheck
