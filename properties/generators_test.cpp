// Tests of the seeded generators (generators/): determinism, validity, no overlaps, JSON round
// trips, the thesis testbed's counts, camera-path invariants, and the RapidCheck generators.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "core/scene_timeline.hpp"
#include "generators/angles.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/open_space.hpp"
#include "generators/random.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::generators {
namespace {

using nlohmann::json;

// Small versions of every generator, so a test can afford several seeds of each.
std::vector<SceneSpec> small_specs(std::uint64_t seed) {
  return {{"manhattan", seed, {{"blocks_x", 3}, {"blocks_y", 2}, {"buildings_per_block", 5}, {"thin_fraction", 0.4}}},
          {"plaza", seed, {{"blocks_x", 4}, {"blocks_y", 4}}},
          {"scatter", seed, {{"count", 120}, {"area_size", 400}}},
          {"irregular", seed, {{"count", 100}, {"area_size", 500}}},
          {"thesis", seed, {{"grid_x", 20}, {"grid_y", 20}}}};
}

// --- Independent geometry for the checks (deliberately not the generators' own helpers) ------

int orient(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}

bool segments_meet(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  auto within = [](Vec2 p, Vec2 q, Vec2 r) {
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) ||
         (o4 == 0 && within(c, d, b));
}

bool strictly_inside(const std::vector<Vec2>& ring, Vec2 p) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2 a = ring[j], b = ring[i];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
  }
  return inside;
}

// Closed footprints meet if an edge of one meets an edge of the other, or one contains the other.
bool footprints_meet(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (segments_meet(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return true;
  return strictly_inside(b, a[0]) || strictly_inside(a, b[0]);
}

// Sweep over x-sorted bounding boxes, exact test for boxes that overlap. Returns the first pair.
std::optional<std::pair<ObjectId, ObjectId>> find_overlap(const Scene& scene) {
  std::vector<const Building*> order;
  for (const Building& b : scene.buildings) order.push_back(&b);
  std::sort(order.begin(), order.end(), [](auto* a, auto* b) { return a->bounds.lo.x < b->bounds.lo.x; });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && order[j]->bounds.lo.x <= order[i]->bounds.hi.x; ++j) {
      const Box3 &a = order[i]->bounds, &b = order[j]->bounds;
      if (a.lo.y > b.hi.y || b.lo.y > a.hi.y) continue;
      if (footprints_meet(order[i]->footprint, order[j]->footprint)) return std::pair{order[i]->id, order[j]->id};
    }
  return std::nullopt;
}

// Every building: ids 0..n-1 in order, valid by the loader's rules, prisms that are convex and
// tile the footprint's area, bounds from 0 to the height.
void expect_valid_buildings(const Scene& scene) {
  for (std::size_t i = 0; i < scene.buildings.size(); ++i) {
    const Building& b = scene.buildings[i];
    ASSERT_EQ(b.id, i);
    Building copy{b.id, b.footprint, b.height, {}, {}};
    ASSERT_NO_THROW(validate_and_finish(copy)) << "building " << b.id;
    ASSERT_EQ(copy.footprint, b.footprint) << "generated footprints are already normalised";
    ASSERT_FALSE(b.prisms.empty()) << "building " << b.id;
    double area = 0;
    for (const ConvexVerticalPrism& p : b.prisms) {
      ASSERT_TRUE(is_convex(p.ring)) << "building " << b.id;
      ASSERT_EQ(p.height, b.height);
      area += signed_area(p.ring);
    }
    EXPECT_NEAR(area, signed_area(b.footprint), 1e-6 * std::max(1.0, signed_area(b.footprint))) << "building " << b.id;
    EXPECT_GT(signed_area(b.footprint), 0.0);
    EXPECT_EQ(b.bounds.lo.z, 0.0);
    EXPECT_EQ(b.bounds.hi.z, b.height);
  }
}

// --- The PRNG -------------------------------------------------------------------------------------

TEST(Random, RangesAndIndependentStreams) {
  // The engine's literal outputs are pinned in generators/tests/pinned_streams_test.cpp.
  Random r2(1);
  int hits[10] = {};
  for (int i = 0; i < 10000; ++i) {
    const double u = r2.uniform_real(-3.0, 5.0);
    ASSERT_GE(u, -3.0);
    ASSERT_LT(u, 5.0);
    const auto k = r2.uniform_int(-2, 7);
    ASSERT_GE(k, -2);
    ASSERT_LE(k, 7);
    ++hits[k + 2];
  }
  // Every value of the range is drawn, about equally often (1,000 expected each; 4.7 standard
  // deviations either side, so a fair draw fails this once in a million seeds, and this seed is fixed).
  for (int v = 0; v < 10; ++v) {
    EXPECT_GT(hits[v], 860) << "value " << v - 2;
    EXPECT_LT(hits[v], 1140) << "value " << v - 2;
  }
  EXPECT_EQ(r2.uniform_int(4, 4), 4);
  // Streams keyed by position differ from each other and from the plain seed.
  EXPECT_NE(Random::stream(7, 1, 0, 0).next_u64(), Random::stream(7, 1, 1, 0).next_u64());
  EXPECT_NE(Random::stream(7, 1, 0, 1).next_u64(), Random::stream(7, 1, 1, 0).next_u64());
  EXPECT_NE(Random::stream(7, 0, 0, 0).next_u64(), Random(7).next_u64());
}

TEST(Random, PinnedSceneText) {
  // A tiny scene's exact text, pinned so that any change of the PRNG, distributions or layout
  // that would break replay of recorded seeds shows up here first, readably (the digests of
  // larger scenes: generators/tests/pinned_streams_test.cpp).
  const Scene s = make_city("manhattan", 42, {{"blocks_x", 1}, {"blocks_y", 1}, {"buildings_per_block", 1}});
  ASSERT_EQ(s.buildings.size(), 1u);
  const std::string pinned =
      R"({"building_count":1,"buildings":[{"footprint":[[-29.714,-37.377],[29.825,-37.377],[29.825,20.035],[-29.714,20.035]],)"
      R"("height":9.346,"id":0}],"format":"cullcheck-scene","provenance":{"generator":"manhattan","parameters":{)"
      R"("block_size":80.0,"blocks_x":1,"blocks_y":1,"buildings_per_block":1,"kiosk_count":0,"kiosk_max_height":1.5,)"
      R"("kiosk_max_size":4.0,"kiosk_min_height":1.0,"kiosk_min_size":1.5,"max_height":40.0,"min_height":8.0,)"
      R"("plaza_blocks_x":0,"plaza_blocks_y":0,"setback":1.0,"street_width":16.0,"thin_fraction":0.1,"thin_max_width":2.0,)"
      R"("thin_min_width":0.5,"tower_fraction":0.05,"tower_max_height":150.0,"tower_min_height":60.0,"width_jitter":0.3},)"
      R"("seed":42},"version":1})"
      "\n";
  EXPECT_EQ(scene_to_json_text(s), pinned)
      << "the generator's output changed: every stored replay of a manhattan scene is now invalid";
  // All coordinates on the 1 mm grid.
  for (Vec2 p : s.buildings[0].footprint) {
    EXPECT_EQ(p.x, std::round(p.x * 1000) / 1000);
    EXPECT_EQ(p.y, std::round(p.y * 1000) / 1000);
  }
}

// --- Cities -------------------------------------------------------------------------------------

TEST(Cities, SameSeedGivesByteIdenticalScenes) {
  for (std::uint64_t seed : {0ULL, 1ULL, 987654321ULL}) {
    for (const SceneSpec& spec : small_specs(seed)) {
      const std::string a = scene_to_json_text(scene_of(spec));
      const std::string b = scene_to_json_text(scene_of(spec));
      EXPECT_EQ(a, b) << replay_args(spec);
    }
  }
  EXPECT_EQ(scene_to_json_text(default_city(5)), scene_to_json_text(make_city("default", 5, json::object())));
}

TEST(Cities, DifferentSeedsGiveDifferentScenes) {
  const auto a = small_specs(1), b = small_specs(2);
  for (std::size_t i = 0; i < a.size(); ++i)
    EXPECT_NE(scene_to_json_text(scene_of(a[i])), scene_to_json_text(scene_of(b[i]))) << a[i].generator;
}

TEST(Cities, BuildingsAreValidAndNeverOverlap) {
  for (std::uint64_t seed : {3ULL, 17ULL, 2024ULL}) {
    for (const SceneSpec& spec : small_specs(seed)) {
      SCOPED_TRACE(replay_args(spec));
      const Scene scene = scene_of(spec);
      ASSERT_FALSE(scene.buildings.empty());
      expect_valid_buildings(scene);
      const auto overlap = find_overlap(scene);
      EXPECT_FALSE(overlap) << "buildings " << overlap->first << " and " << overlap->second << " meet";
    }
  }
}

TEST(Cities, JsonRoundTripIsIdentical) {
  for (const SceneSpec& spec : small_specs(77)) {
    SCOPED_TRACE(replay_args(spec));
    const Scene scene = scene_of(spec);
    const std::string text = scene_to_json_text(scene);
    const Scene back = scene_from_json_text(text);
    EXPECT_EQ(scene_to_json_text(back), text);
    ASSERT_EQ(back.buildings.size(), scene.buildings.size());
    EXPECT_EQ(back.provenance.generator, spec.generator);
    EXPECT_EQ(back.provenance.seed, spec.seed);
    // The stored parameters rebuild the same scene.
    const Scene rebuilt = make_city(back.provenance.generator, back.provenance.seed, json::parse(back.provenance.parameters_json));
    EXPECT_EQ(scene_to_json_text(rebuilt), text);
  }
}

TEST(Cities, DefaultCityHasPlazaKiosksAndThinBuildings) {
  const Scene scene = default_city(1);  // its generation time: BM_GenerateDefaultCity (bench_culling)
  EXPECT_GE(scene.buildings.size(), 2000u);
  EXPECT_LE(scene.buildings.size(), 4000u);
  expect_valid_buildings(scene);
  EXPECT_FALSE(find_overlap(scene));
  std::size_t thin = 0, low = 0;
  for (const Building& b : scene.buildings) {
    const Box2 box = b.bounds.plan();
    if (std::min(box.hi.x - box.lo.x, box.hi.y - box.lo.y) <= 2.0) ++thin;
    if (b.height < 1.7) ++low;
  }
  EXPECT_GT(thin, 100u);
  EXPECT_EQ(low, 8u) << "the kiosks in the plaza are the only objects below eye height";
  // The plaza: the middle of the city is open.
  const OpenSpace open(scene);
  EXPECT_TRUE(open.is_open({0.0, 0.0}, 5.0));
}

TEST(Cities, ManhattanHasTowersAndStaysInsideLots) {
  ManhattanParams p;
  p.tower_fraction = 0.3;
  const Scene scene = manhattan_city(p, 9);
  ASSERT_EQ(scene.buildings.size(), static_cast<std::size_t>(p.blocks_x * p.blocks_y * p.buildings_per_block));
  double top = 0;
  for (const Building& b : scene.buildings) top = std::max(top, b.height);
  EXPECT_GE(top, p.tower_min_height);
  EXPECT_LE(top, p.tower_max_height);
}

TEST(Cities, IrregularCityHasNonConvexFootprints) {
  const Scene scene = make_city("irregular", 5, {{"count", 200}});
  std::size_t non_convex = 0, rotated = 0;
  for (const Building& b : scene.buildings) {
    if (!is_convex(b.footprint)) ++non_convex;
    const Vec2 e = b.footprint[1] - b.footprint[0];
    if (e.x != 0.0 && e.y != 0.0) ++rotated;
  }
  EXPECT_GT(non_convex, 50u);
  EXPECT_GT(rotated, 50u);
  EXPECT_GT(scene.buildings.size(), 150u);
}

TEST(Cities, ThesisTestbedHas160000BuildingsOf46Triangles) {
  const Scene scene = thesis_city(ThesisParams{}, 1);  // its generation time: BM_GenerateThesisCity (bench_culling)
  ASSERT_EQ(scene.buildings.size(), 160000u);
  EXPECT_EQ(scene.triangle_count(), 7'360'000u);
  for (const Building& b : scene.buildings) {
    ASSERT_EQ(b.triangle_count(), 46u);
    ASSERT_EQ(b.prisms.size(), 1u) << "convex: one CVP, no partition";
  }
  // Spot-check the no-overlap property on the small version (the full one is a regular grid).
  const Scene small = make_city("thesis", 1, {{"grid_x", 20}, {"grid_y", 20}});
  EXPECT_EQ(small.buildings.size(), 400u);
  EXPECT_FALSE(find_overlap(small));
}

TEST(Cities, BadParametersAreTypedErrors) {
  auto expect_error = [](const std::string& gen, const json& params, const std::string& field) {
    try {
      make_city(gen, 1, params);
      ADD_FAILURE() << "no error for " << gen << " " << params.dump();
    } catch (const InputError& e) {
      EXPECT_EQ(e.object(), "generator") << e.what();
      EXPECT_EQ(e.field(), field) << e.what();
    }
  };
  expect_error("nonesuch", json::object(), "name");
  expect_error("manhattan", {{"blocks_x", 0}}, "blocks_x");
  expect_error("manhattan", {{"blocks_x", 2.5}}, "blocks_x");
  expect_error("manhattan", {{"blokcs_x", 2}}, "blokcs_x");
  expect_error("manhattan", {{"street_width", "wide"}}, "street_width");
  expect_error("manhattan", {{"max_height", 1.0}}, "max_height");
  expect_error("manhattan", {{"buildings_per_block", 5000}}, "buildings_per_block");
  expect_error("manhattan", {{"blocks_x", 10000}, {"blocks_y", 10000}, {"buildings_per_block", 1000}}, "buildings_per_block");
  expect_error("manhattan", {{"kiosk_count", 3}}, "kiosk_count");
  expect_error("plaza", {{"plaza_blocks_x", 0}, {"plaza_blocks_y", 0}, {"kiosk_count", 0}}, "plaza_blocks_x");
  expect_error("scatter", {{"min_size", -1}}, "min_size");
  expect_error("irregular", {{"min_size", 2}}, "min_size");
  expect_error("thesis", {{"corner_radius", 11}}, "corner_radius");
  expect_error("thesis", {{"grid_x", 5000}, {"grid_y", 5000}}, "grid_y");
  expect_error("default", json::array(), "params");
  EXPECT_NO_THROW(make_city("scatter", 1, nullptr));
  expect_error("kept", {{"case", "no_such_case"}}, "case");
  expect_error("kept", {{"case", 3}}, "case");
  EXPECT_NO_THROW(make_city("kept", 0, {{"case", "slab_across_the_disc"}}));
  expect_error("slot_city", {{"slots_x", 0}}, "slots_x");
  expect_error("star_block_city", {{"street", 80}}, "street");
  EXPECT_EQ(city_generator_names().size(), 11u);
}

// --- Camera paths ---------------------------------------------------------------------------------

// A small grid with short blocks, so long walks turn at many crossings.
ManhattanParams walk_city() {
  ManhattanParams p;
  p.blocks_x = 4, p.blocks_y = 3, p.block_size = 30, p.street_width = 12, p.buildings_per_block = 4;
  p.plaza_blocks_x = 1, p.plaza_blocks_y = 1, p.kiosk_count = 3;
  return p;
}

// What a pedestrian walk must be frame by frame (asserted here), and what it did (counted):
// valid cameras at the eye height, never inside a building and `margin` clear of every wall,
// each frame standing or moving exactly one step (at most one with `cut_steps`: a free-space walk
// stops short at the bends of its route), the view turning less than 0.25 rad a frame.
struct WalkCounts {
  int moving = 0, still = 0, lateral = 0, backward = 0, turning = 0, wraps = 0;
};
WalkCounts check_walk(const CameraPath& path, const OpenSpace& open, const StreetWalkParams& walk, bool cut_steps = false) {
  const double step = walk.walking_speed / walk.frames_per_second;
  WalkCounts n;
  EXPECT_EQ(path.frames.size(), static_cast<std::size_t>(walk.frames));
  EXPECT_EQ(path.kind, "street_walk");
  EXPECT_EQ(path.frames_per_second, walk.frames_per_second);
  for (std::size_t i = 0; i < path.frames.size(); ++i) {
    const Camera& c = path.frames[i];
    EXPECT_NO_THROW(validate(c));
    EXPECT_EQ(c.position.z, walk.eye_height);
    EXPECT_TRUE(c.yaw >= 0.0 && c.yaw < kTwoPi) << "frame " << i;
    if (open.inside_building(c.position) || !open.is_open(plan(c.position), walk.street_margin - 1e-6)) {
      ADD_FAILURE() << "frame " << i << " is inside a building or nearer a wall than the margin";
      return n;
    }
    if (i == 0) continue;
    const Camera& prev = path.frames[i - 1];
    const Vec2 d = plan(c.position) - plan(prev.position);
    const double dist = length(d);
    if (dist == 0.0) {
      ++n.still;
    } else {
      if (cut_steps) EXPECT_LE(dist, step + 1e-9) << "frame " << i;
      else EXPECT_NEAR(dist, step, 1e-9) << "frame " << i;
      ++n.moving;
      const Vec2 forward{std::cos(c.yaw), std::sin(c.yaw)};
      if (std::abs(dot(d, forward)) < 1e-9) ++n.lateral;
      if (dot(d, forward) < -0.9 * step) ++n.backward;
    }
    const double turn = shortest_turn(prev.yaw, c.yaw);
    EXPECT_LT(std::abs(turn), 0.25) << "yaw jumps at frame " << i;
    if (turn != 0.0) ++n.turning;
    if (std::abs(c.yaw - prev.yaw) > kPi) ++n.wraps;  // crossed the 0 / 2*pi seam
  }
  return n;
}

TEST(StreetWalk, StepsAreWalkingSpeedTurnsAreSmoothEyeStaysInTheStreet) {
  const ManhattanParams city = walk_city();
  StreetWalkParams walk;
  walk.frames = 6000;
  int wraps = 0;
  for (std::uint64_t seed : {1ULL, 2ULL, 3ULL, 4ULL}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = plaza_city(city, seed);
    const WalkCounts n = check_walk(street_walk(city, walk, seed), OpenSpace(scene), walk);
    EXPECT_GT(n.moving, 3000);
    EXPECT_GT(n.still, 100);
    EXPECT_GT(n.lateral, 50) << "sideways steps";
    EXPECT_GT(n.backward, 50);
    EXPECT_GT(n.turning, 100);
    wraps += n.wraps;
  }
  EXPECT_GT(wraps, 0) << "some turn crosses the azimuth wrap";
}

// Scenes without a street grid (irregular and scatter cities, imported ones) are walked through
// their free-space cells (free_space_walk.cpp), with the same segments and the same guarantees.
TEST(StreetWalk, FreeSpaceWalkOnScenesWithoutAGrid) {
  StreetWalkParams walk;
  walk.frames = 3000;
  for (const auto& [generator, seed] : std::vector<std::pair<std::string, std::uint64_t>>{{"irregular", 5}, {"scatter", 2}}) {
    SCOPED_TRACE(generator);
    const Scene scene = make_city(generator, seed, {{"count", 150}});
    const CameraPath path = street_walk(scene, walk, 7);
    const WalkCounts n = check_walk(path, OpenSpace(scene), walk, /*cut_steps=*/true);
    EXPECT_GT(n.moving, 1500);
    EXPECT_GT(n.still, 50);
    EXPECT_GT(n.lateral, 20) << "sideways steps";
    EXPECT_GT(n.backward, 20);
    EXPECT_GT(n.turning, 100);
    // Deterministic, and a different seed walks elsewhere.
    EXPECT_EQ(path_to_json_text(path), path_to_json_text(free_space_walk(scene, walk, 7)));
    EXPECT_NE(path_to_json_text(path), path_to_json_text(street_walk(scene, walk, 8)));
  }
}

TEST(StreetWalk, DeterministicRoundTripsAndReadsStreetsFromTheScene) {
  const Scene scene = default_city(3);
  StreetWalkParams walk;
  const CameraPath a = street_walk(scene, walk, 11);
  const CameraPath b = street_walk(default_city_params(), walk, 11);
  EXPECT_EQ(path_to_json_text(a), path_to_json_text(b));
  EXPECT_NE(path_to_json_text(a), path_to_json_text(street_walk(scene, walk, 12)));
  const CameraPath back = path_from_json_text(path_to_json_text(a));
  EXPECT_EQ(path_to_json_text(back), path_to_json_text(a));
  const OpenSpace open(scene);
  for (const Camera& c : a.frames) ASSERT_FALSE(open.inside_building(c.position));
  // A scene with no open ground to walk on.
  Scene closed;
  closed.buildings = {box_building(0, 0, 0, 100, 100, 10)};
  StreetWalkParams wide = walk;
  wide.street_margin = 200;
  EXPECT_THROW(street_walk(closed, wide, 1), InputError);
  EXPECT_THROW(make_camera_path("street_walk", scene, 1, {{"frames", 0}}), InputError);
  EXPECT_THROW(make_camera_path("teleport", scene, 1, json::object()), InputError);
  EXPECT_EQ(make_camera_path("street_walk", scene, 11, json::object()).frames.size(), 1800u);
}

// A path's "timeline" parameter: events every `every` frames, each bringing back what the last
// one removed and removing a fresh `churn` share; `late` objects absent from the start. Pinned,
// valid against the scene, carried by the path JSON, and refused out of range.
TEST(SceneTimeline, SeededEventsEveryFewFramesThatUndoTheLastOne) {
  const Scene scene = make_city("manhattan", 3, {{"blocks_x", 3}, {"blocks_y", 3}});
  ASSERT_EQ(scene.buildings.size(), 54u);
  const json params = {{"frames", 100}, {"timeline", {{"every", 30}, {"churn", 0.1}, {"late", 0.05}}}};
  const CameraPath path = make_camera_path("street_walk", scene, 5, params);
  ASSERT_EQ(path.frames.size(), 100u);
  ASSERT_EQ(path.events.size(), 3u);
  EXPECT_EQ(path.events[0].frame, 30u);
  EXPECT_EQ(path.events[2].frame, 90u);
  EXPECT_EQ(path.events[0].appear, (std::vector<ObjectId>{50, 51, 53}));  // the late 5% of 54, rounded up
  EXPECT_EQ(path.events[0].vanish, (std::vector<ObjectId>{10, 11, 26, 29, 47}));  // 10% of the 51 present
  for (std::size_t e = 1; e < path.events.size(); ++e) EXPECT_EQ(path.events[e].appear, path.events[e - 1].vanish);
  EXPECT_NO_THROW(validate_timeline(path, scene, path.frames.size()));
  EXPECT_EQ(make_camera_path("street_walk", scene, 5, params).events, path.events);
  EXPECT_NE(make_camera_path("street_walk", scene, 6, params).events, path.events);
  EXPECT_EQ(path_from_json_text(path_to_json_text(path)).events, path.events);
  EXPECT_TRUE(make_camera_path("street_walk", scene, 5, {{"frames", 20}, {"timeline", {{"every", 30}}}}).events.empty());
  EXPECT_THROW(make_camera_path("street_walk", scene, 5, {{"timeline", {{"every", 0}}}}), InputError);
  EXPECT_THROW(make_camera_path("street_walk", scene, 5, {{"timeline", {{"churn", 0.9}}}}), InputError);
  EXPECT_THROW(make_camera_path("street_walk", scene, 5, {{"timeline", {{"gone", 1}}}}), InputError);
}

// The thesis testbed's streets coincide with a Manhattan grid of its blocks, so the street walk
// (Table 3.2's setting) runs on it and never enters a building.
TEST(StreetWalk, RunsInTheThesisCityStreets) {
  const Scene scene = make_city("thesis", 2, {{"grid_x", 20}, {"grid_y", 15}});
  const CameraPath path = make_camera_path("street_walk", scene, 4, {{"frames", 3000}});
  ASSERT_EQ(path.frames.size(), 3000u);
  const OpenSpace open(scene);
  for (const Camera& c : path.frames) ASSERT_TRUE(open.is_open(plan(c.position), 0.5)) << c.position.x << ", " << c.position.y;
  EXPECT_FALSE(thesis_street_grid(ThesisParams{.grid_x = 21}));  // not whole blocks: no street grid
}

TEST(FlyThrough, SixDofAboveRoofsWithDipsNeverInsideABuilding) {
  for (const SceneSpec& spec : {SceneSpec{"default", 4, json::object()}, SceneSpec{"irregular", 4, {{"count", 150}}}}) {
    SCOPED_TRACE(replay_args(spec));
    const Scene scene = scene_of(spec);
    const OpenSpace open(scene);
    FlyThroughParams fly;
    fly.frames = 3000;
    fly.dip_fraction = 0.5;
    const CameraPath path = fly_through(scene, fly, 8);
    ASSERT_EQ(path.frames.size(), 3000u);
    EXPECT_EQ(path_to_json_text(path), path_to_json_text(fly_through(scene, fly, 8)));
    const double top = scene.bounds().hi.z;
    double min_pitch = 0, max_z = 0, min_z = 1e9, max_roll = 0;
    for (std::size_t i = 0; i < path.frames.size(); ++i) {
      const Camera& c = path.frames[i];
      ASSERT_NO_THROW(validate(c));
      ASSERT_FALSE(open.inside_building(c.position)) << "frame " << i;
      min_pitch = std::min(min_pitch, c.pitch), max_roll = std::max(max_roll, std::abs(c.roll));
      max_z = std::max(max_z, c.position.z), min_z = std::min(min_z, c.position.z);
      if (i == 0) continue;
      const Camera& prev = path.frames[i - 1];
      EXPECT_LE(length(plan(c.position) - plan(prev.position)), fly.cruise_speed / fly.frames_per_second * 1.05) << i;
      EXPECT_LT(std::abs(shortest_turn(prev.yaw, c.yaw)), 0.2) << i;
      EXPECT_LT(std::abs(c.pitch - prev.pitch), 0.2) << i;
      EXPECT_LT(std::abs(c.roll - prev.roll), 0.2) << i;
    }
    EXPECT_LE(min_pitch, radians(-79.9));
    EXPECT_GT(max_roll, radians(10));
    EXPECT_GT(max_z, top);
    EXPECT_LT(min_z, 5.0) << "dips to street level";
  }
}

// --- RapidCheck generators ------------------------------------------------------------------------

RC_GTEST_PROP(RapidCheckGenerators, SpecsBuildValidSmallScenes, (const SceneSpec& spec)) {
  const Scene scene = scene_of(spec);
  RC_ASSERT(!scene.buildings.empty());
  RC_ASSERT(scene.buildings.size() <= 100u);
  for (std::size_t i = 0; i < scene.buildings.size(); ++i) {
    const Building& b = scene.buildings[i];
    RC_ASSERT(b.id == i);
    RC_ASSERT(!b.prisms.empty());
    Building copy{b.id, b.footprint, b.height, {}, {}};
    validate_and_finish(copy);
  }
  RC_ASSERT(!find_overlap(scene));
  const std::string text = scene_to_json_text(scene);
  RC_ASSERT(scene_to_json_text(scene_from_json_text(text)) == text);
  RC_ASSERT(replay_args(spec).find("--seed " + std::to_string(spec.seed)) != std::string::npos);
}

RC_GTEST_PROP(RapidCheckGenerators, CamerasAreValidAndOutsideBuildings, ()) {
  const SceneCase c = *rcgen::scene_case();
  const Scene scene = scene_of(c.spec);
  const OpenSpace open(scene);
  validate(c.camera);
  RC_ASSERT(!open.inside_building(c.camera.position));
  const bool street = c.camera.position.z <= 2.0;
  if (!street) RC_ASSERT(c.camera.position.z > scene.bounds().hi.z);
  if (street) RC_ASSERT(c.camera.position.z >= 1.5);
  RC_TAG(street ? "street" : "rooftop", c.camera.omnidirectional() ? "360" : (c.camera.hfov < radians(6) ? "narrow" : "ordinary"));
}

RC_GTEST_PROP(RapidCheckGenerators, LowAndTallOccludersStraddleTheEye, ()) {
  const double eye = 1.7;
  const Scene low = scene_of(*rcgen::low_occluder_spec(eye));
  const Scene tall = scene_of(*rcgen::tall_occluder_spec(eye));
  RC_ASSERT(!low.buildings.empty());
  RC_ASSERT(!tall.buildings.empty());
  for (const Building& b : low.buildings) RC_ASSERT(b.height < eye);
  for (const Building& b : tall.buildings) RC_ASSERT(b.height > eye);
}

RC_GTEST_PROP(RapidCheckGenerators, StreetWalksStayInTheStreetsOfAnySmallGrid, ()) {
  const SceneSpec spec = *rc::gen::oneOf(rcgen::manhattan_spec(), rcgen::plaza_spec());
  const std::uint64_t walk_seed = *rc::gen::arbitrary<std::uint64_t>();
  const Scene scene = scene_of(spec);
  const OpenSpace open(scene);
  StreetWalkParams walk;
  walk.frames = 900;
  const CameraPath path = street_walk(scene, walk, walk_seed);
  RC_ASSERT(path.frames.size() == 900u);
  for (std::size_t i = 0; i < path.frames.size(); ++i) {
    RC_ASSERT(!open.inside_building(path.frames[i].position));
    if (i == 0) continue;
    const double d = length(plan(path.frames[i].position) - plan(path.frames[i - 1].position));
    RC_ASSERT(d == 0.0 || std::abs(d - walk.walking_speed / walk.frames_per_second) < 1e-9);
  }
}

// Shrinking a spec never grows the city: every immediate shrink of a Manhattan spec has at
// most as many buildings (blocks_x * blocks_y * buildings_per_block) as the original.
TEST(RapidCheckGenerators, ShrinkingMakesCitiesSmaller) {
  auto buildings = [](const SceneSpec& s) {
    return s.params.at("blocks_x").get<int>() * s.params.at("blocks_y").get<int>() * s.params.at("buildings_per_block").get<int>();
  };
  for (int trial = 0; trial < 20; ++trial) {
    const auto shrinkable = rcgen::manhattan_spec()(rc::Random(static_cast<std::uint64_t>(trial)), 100);
    const SceneSpec original = shrinkable.value();
    auto shrinks = shrinkable.shrinks();
    int seen = 0;
    while (auto next = shrinks.next()) {
      ASSERT_LE(buildings(next->value()), buildings(original)) << replay_args(original);
      ++seen;
    }
    if (buildings(original) > 1) {
      EXPECT_GT(seen, 0);
    }
  }
}

TEST(RapidCheckGenerators, CounterexamplesPrintAsReplayCommands) {
  const SceneSpec spec{"manhattan", 12, {{"blocks_x", 2}}};
  EXPECT_EQ(rc::toString(spec), "--generator manhattan --seed 12 --params '{\"blocks_x\":2}'");
  Camera cam;
  EXPECT_NE(rc::toString(cam).find("\"position\""), std::string::npos);
  EXPECT_NE(rc::toString(SceneCase{spec, cam}).find("--camera '"), std::string::npos);
}

// The Table 4.1 walk: east along the street south of the plaza, across it diagonally, then north;
// frames 2 m apart, turns in steps of at most 7 degrees, every camera in the open.
TEST(CameraPaths, PlazaCrossingFollowsTheThesisWalk) {
  const Scene scene = make_city("plaza", 1, nlohmann::json::parse(R"({"blocks_x":11,"blocks_y":10,"block_size":40,
      "street_width":10,"buildings_per_block":4,"plaza_blocks_x":3,"plaza_blocks_y":2,"kiosk_count":0})"));
  const CameraPath path = make_camera_path("plaza_crossing", scene, 1, nlohmann::json::object());
  ASSERT_GT(path.frames.size(), 100u);
  const OpenSpace open(scene);
  double first_turn = 0.0;
  for (std::size_t i = 1; i < path.frames.size(); ++i) {
    const Camera& a = path.frames[i - 1];
    const Camera& b = path.frames[i];
    const double step = length(plan(b.position) - plan(a.position));
    const double turn = std::abs(shortest_turn(a.yaw, b.yaw));
    EXPECT_LE(step, 2.0 + 1e-9) << "frame " << i;
    EXPECT_LE(turn, radians(7.0) + 1e-12) << "frame " << i;
    EXPECT_TRUE(step == 0.0 || turn == 0.0) << "frame " << i << " moves and turns at once";
    EXPECT_FALSE(open.inside_building(b.position)) << "frame " << i;
    if (first_turn == 0.0 && turn > 0.0) first_turn = b.yaw;
  }
  EXPECT_EQ(path.frames.front().yaw, 0.0);
  // Diagonal of a 3 x 2-block plaza at 50 m pitch: atan(100 / 150) = 33.7 degrees; then north.
  EXPECT_NEAR(path.frames.back().yaw, kPi / 2, 1e-12);
  double diagonal = 0.0;
  for (const Camera& c : path.frames)
    if (std::abs(c.yaw - std::atan2(100.0, 150.0)) < 1e-9) diagonal = c.yaw;
  EXPECT_NEAR(diagonal, std::atan2(100.0, 150.0), 1e-9);
  EXPECT_THROW(make_camera_path("plaza_crossing", make_city("manhattan", 1, nlohmann::json::object()), 1, {}), InputError);
  EXPECT_THROW(make_camera_path("plaza_crossing", scene, 1, {{"step_m", 0.0}}), InputError);
}

}  // namespace
}  // namespace cullcheck::generators
