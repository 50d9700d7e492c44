// The VbAoI server's sight filter (engine/vbaoi/sight_filter.hpp): hand-made walls pin what it
// hides and what it lets through, and on generated cities every disc it calls hidden is held to
// the oracle's line of sight (each random case names its seed: rerun the test to replay it).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/random.hpp"
#include "core/scene_io.hpp"
#include "engine/vbaoi/sight_filter.hpp"
#include "generators/city.hpp"
#include "generators/open_space.hpp"
#include "oracle/ray_oracle.hpp"

namespace cullcheck {
namespace {

constexpr double kEye = 1.7;

Scene scene_of(std::vector<Building> buildings) {
  Scene scene;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    buildings[i].id = static_cast<ObjectId>(i);
    scene.buildings.push_back(std::move(buildings[i]));
  }
  return scene;
}

Vec2 toward(Vec2 from, double degrees, double distance) {
  const double a = degrees * kPi / 180.0;
  return {from.x + distance * std::cos(a), from.y + distance * std::sin(a)};
}

// One wall across the line of sight: it hides a disc wholly inside its shadow, not one beside it
// or one whose edge rays pass its end. The wall [10, 12] x [-5, 5] spans +-26.57 degrees from the
// origin, so a disc 40 m away is hidden up to a radius of 40 sin(26.57 deg) = 17.9 m.
TEST(SightFilter, AWallHidesWhatLiesWhollyInItsShadow) {
  const Scene scene = scene_of({box_building(0, 10, -5, 12, 5, 10)});
  vbaoi::SightFilter filter(scene, kEye);
  EXPECT_TRUE(filter.hidden({0, 0}, {20, 0}, 0.0));
  EXPECT_TRUE(filter.hidden({0, 0}, {20, 0}, 0.5));
  EXPECT_TRUE(filter.hidden({0, 0}, {40, 0}, 17.0));
  EXPECT_FALSE(filter.hidden({0, 0}, {40, 0}, 18.5));  // its edge rays pass the wall's ends
  EXPECT_FALSE(filter.hidden({0, 0}, {20, 12}, 0.5));  // beside the wall
  EXPECT_FALSE(filter.hidden({0, 0}, {20, 0}, 8.5));   // the disc reaches in front of the wall
  EXPECT_FALSE(filter.hidden({0, 0}, {9, 0}, 0.5));    // in front of it
  EXPECT_TRUE(filter.hidden({20, 0}, {0, 0}, 0.5));    // and the other way round
  EXPECT_GT(filter.prisms_tested(), 0u);
}

// Only prisms that stand across eye height occlude: one lower than the eyes does not.
TEST(SightFilter, EyesSeeOverALowWall) {
  const Scene scene = scene_of({box_building(0, 10, -5, 12, 5, 1.2)});
  vbaoi::SightFilter filter(scene, kEye);
  EXPECT_FALSE(filter.hidden({0, 0}, {20, 0}, 0.0));
  vbaoi::SightFilter low_eyes(scene, 1.0);
  EXPECT_TRUE(low_eyes.hidden({0, 0}, {20, 0}, 0.0));
}

// A gap between two walls lets the sight line through; two prisms that together cover the
// directions towards the disc hide it where neither does alone. Seen from (0, 1), the walls
// [10, 12] x [-5, 0] and [10, 12] x [0, 5] overlap in direction between -5.71 and -4.76 degrees;
// a disc at -5.2 degrees whose directions span +-0.7 degrees needs both.
TEST(SightFilter, PrismsCoverTogetherButNotThroughAGap) {
  {
    const Scene gap = scene_of({box_building(0, 10, -5, 12, -0.25, 10), box_building(1, 10, 0.25, 12, 5, 10)});
    vbaoi::SightFilter filter(gap, kEye);
    EXPECT_FALSE(filter.hidden({0, 0}, {20, 0}, 0.0));
    EXPECT_TRUE(filter.hidden({0, 0}, {20, 3}, 0.1));
  }
  const Vec2 eye{0, 1};
  const Vec2 target = toward(eye, -5.2, 20);
  const double radius = 20 * std::sin(0.7 * kPi / 180.0);
  const Building lower = box_building(0, 10, -5, 12, 0, 10), upper = box_building(1, 10, 0, 12, 5, 10);
  vbaoi::SightFilter both(scene_of({lower, upper}), kEye);
  EXPECT_TRUE(both.hidden(eye, target, radius));
  vbaoi::SightFilter lower_only(scene_of({lower}), kEye);
  EXPECT_FALSE(lower_only.hidden(eye, target, radius));
  vbaoi::SightFilter upper_only(scene_of({upper}), kEye);
  EXPECT_FALSE(upper_only.hidden(eye, target, radius));
}

// A building that reaches behind the eye (the eye stands beside its wall) still blocks the sight
// lines that cross it ahead: only its part in front of the eye is used.
TEST(SightFilter, ABuildingBesideTheEyeBlocksAhead) {
  const Scene scene = scene_of({box_building(0, -10, 2, 30, 10, 20)});
  vbaoi::SightFilter filter(scene, kEye);
  EXPECT_TRUE(filter.hidden({0, 0}, {20, 20}, 0.5));
  EXPECT_FALSE(filter.hidden({0, 0}, {20, -20}, 0.5));
  EXPECT_FALSE(filter.hidden({0, 0}, {40, 1}, 0.5));  // along the wall, clear of it
}

// Kept counterexample (the 1,000-client run of the main job's city, tick 153, clients 417 and
// 752): a sight line 1,114 m long cuts the corner of building 9932 by 2.6e-6 m, and the oracle,
// which casts in single precision, sees past it (in this city; in a scene of that building
// alone it does not: at this depth the answer is rounding's). Without the wall margin the filter called it hidden
// and dropped a visible update.
TEST(SightFilter, KeptCounterexampleASightLineThatCutsACornerByMicrometres) {
  const Scene scene = generators::make_city("manhattan", 1, {{"blocks_x", 41}, {"blocks_y", 41}});
  const Vec2 a{-526.86713212892562, 1882.8376697369104}, b{587.94464520151962, 1873.9822759577628};
  const oracle::RayOracle truth(scene);
  ASSERT_TRUE(truth.line_of_sight({a.x, a.y, kEye}, {b.x, b.y, kEye}));
  vbaoi::SightFilter filter(scene, kEye);
  EXPECT_FALSE(filter.hidden(a, b, 0.0));
  EXPECT_FALSE(filter.hidden(b, a, 0.0));
}

// Bad numbers are never "hidden".
TEST(SightFilter, NonFiniteOrDegenerateQueriesAreNotHidden) {
  const Scene scene = scene_of({box_building(0, 10, -5, 12, 5, 10)});
  vbaoi::SightFilter filter(scene, kEye);
  EXPECT_FALSE(filter.hidden({0, 0}, {0, 0}, 0.0));
  EXPECT_FALSE(filter.hidden({0, 0}, {20, 0}, NAN));
  EXPECT_FALSE(filter.hidden({0, 0}, {20, 0}, -1.0));
  EXPECT_FALSE(filter.hidden({0, 0}, {NAN, 0}, 0.0));
  EXPECT_FALSE(filter.hidden({0, 0}, {INFINITY, 0}, 0.0));
  vbaoi::SightFilter empty(Scene{}, kEye);
  EXPECT_FALSE(empty.hidden({0, 0}, {20, 0}, 0.0));
}

// Generated cities: eye pairs in the open, discs of random radius; wherever the filter says
// hidden, no point of the disc (its centre, 16 points on its rim and 16 inside) sees the eye by
// the oracle. The hard case is counted: hidden discs, and sight lines the filter let through
// that the oracle found blocked (its price), besides the visible ones.
TEST(SightFilter, EveryDiscItHidesIsHiddenFromTheOracle) {
  std::uint64_t hidden = 0, passed_blocked = 0, passed_visible = 0, points = 0;
  for (const auto& [generator, params] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"manhattan", {{"blocks_x", 6}, {"blocks_y", 6}}},
           {"irregular", {{"count", 80}, {"area_size", 400}}},
           {"scatter", {{"count", 60}, {"area_size", 300}, {"thin_fraction", 0.5}}}}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Scene scene = generators::make_city(generator, seed, params);
      const generators::OpenSpace open(scene);
      const oracle::RayOracle truth(scene);
      vbaoi::SightFilter filter(scene, kEye);
      const Box2 box = scene.bounds().plan();
      Random rng(seed * 7919 + 11);
      auto open_point = [&] {
        for (;;) {
          const Vec2 p{rng.uniform_real(box.lo.x, box.hi.x), rng.uniform_real(box.lo.y, box.hi.y)};
          if (open.is_open(p, 0.05)) return p;
        }
      };
      for (int pair = 0; pair < 400; ++pair) {
        const Vec2 from = open_point(), to = open_point();
        const double radius = rng.bernoulli(0.3) ? 0.0 : rng.uniform_real(0.0, 3.0);
        const bool says_hidden = filter.hidden(from, to, radius);
        if (!says_hidden) {
          (truth.line_of_sight({from.x, from.y, kEye}, {to.x, to.y, kEye}) ? passed_visible : passed_blocked) += 1;
          continue;
        }
        ++hidden;
        for (int k = 0; k < 33; ++k) {
          const double a = kTwoPi * k / 16.0;
          const double r = k == 0 ? 0.0 : k <= 16 ? radius : radius * rng.uniform01();
          const Vec2 q{to.x + r * std::cos(a), to.y + r * std::sin(a)};
          if (!open.is_open(q, 0.0)) continue;  // inside a building: nothing to see from there
          ++points;
          ASSERT_FALSE(truth.line_of_sight({from.x, from.y, kEye}, {q.x, q.y, kEye}))
              << generator << " seed " << seed << " (" << params.dump() << "): the filter hid the disc of radius " << radius
              << " around (" << to.x << ", " << to.y << ") from (" << from.x << ", " << from.y << "), but (" << q.x << ", "
              << q.y << ") sees it; rerun this test to replay";
        }
      }
    }
  }
  std::printf("hidden discs %llu (%llu points checked), let through: %llu blocked by the oracle, %llu visible\n",
              static_cast<unsigned long long>(hidden), static_cast<unsigned long long>(points),
              static_cast<unsigned long long>(passed_blocked), static_cast<unsigned long long>(passed_visible));
  EXPECT_GT(hidden, 1000u);
  EXPECT_GT(passed_visible, 300u);
  // The filter's price: blocked sight lines it could not prove blocked, a small share of those it did.
  EXPECT_LT(passed_blocked * 5, hidden);
}

}  // namespace
}  // namespace cullcheck
