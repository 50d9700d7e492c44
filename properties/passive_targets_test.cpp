// Passive targets' two paths (engine/shrinking/passive_targets.hpp): for an eye at the height
// every target reaches (the VbAoI graph's case), the order-free test, which keeps only each bin's
// nearest positive shadow, must give the sweep's answer and test counts. Drawn over street
// cities, eyes on a cell's boundary (perspective or all-round), known sets and shadow logs that
// include shadows placed exactly at a target's distance (not merged before its test: the merge
// takes shadows strictly nearer) and one step before it (merged), plus flat, negative, infinite
// and NaN slopes.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/shrinking/passive_targets.hpp"
#include "engine/vbaoi/navigation_graph.hpp"
#include "generators/navigable_regions.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "properties/property_run.hpp"

namespace cullcheck {
namespace {

constexpr double kEyeHeight = 1.7;

TEST(PassiveTargets, OrderFreePathEqualsTheSweep) {
  int some_hidden = 0, ties_decided = 0;
  const PropertyOutcome run = run_property("PassiveTargets order-free path equals the sweep", 400, true, [&] {
    const auto seed = *rc::gen::inRange<std::uint64_t>(0, 1000);
    const int bx = *rc::gen::inRange(1, 4), by = *rc::gen::inRange(1, 4);
    const Scene city = generators::scene_of({"manhattan", seed, {{"blocks_x", bx}, {"blocks_y", by}}});
    const std::vector<NavigableRegion> regions = generators::navigable_regions(city);
    RC_PRE(!regions.empty());
    const Scene scene = navigable_region_targets(regions, kEyeHeight);
    MethodOptions options;
    options.quadtree_leaf_size = *rc::gen::element(1u, 4u, 8u);
    options.horizon_bins = *rc::gen::element(256u, 4096u);
    PassiveTargets targets(scene, options);

    // An eye on some cell's boundary, as the view cells' samples lie.
    const NavigableRegion& cell = regions[*rc::gen::inRange<std::size_t>(0, regions.size())];
    const std::size_t k = *rc::gen::inRange<std::size_t>(0, cell.ring.size());
    const double t = *rc::gen::inRange(0, 1001) / 1000.0;
    const Vec2 a = cell.ring[k], b = cell.ring[(k + 1) % cell.ring.size()];
    const Vec2 e = a + (b - a) * t;
    Camera camera;
    camera.position = {e.x, e.y, kEyeHeight};
    if (*rc::gen::inRange(0, 3) == 0) {
      camera.hfov = *rc::gen::inRange(30, 150) * kPi / 180.0;
      camera.vfov = camera.hfov / 2;
      camera.yaw = *rc::gen::inRange(0, 360) * kPi / 180.0;
    } else {
      camera.hfov = kTwoPi;
    }
    const ViewRegion region{camera, *rc::gen::element(0.5, 1.4142135623730951, 3.0), *rc::gen::element(0.0, 0.1)};

    // Shadows: anywhere, or over one target's span at exactly its distance or one step before.
    std::vector<Shadow> shadows;
    std::vector<std::size_t> at_tie;  // indices of shadows placed exactly at a target's distance
    const int count = *rc::gen::inRange(0, 160);
    for (int i = 0; i < count; ++i) {
      const int kind = *rc::gen::inRange(0, 4);
      if (kind < 2) {
        const double begin = *rc::gen::inRange(0, 6283) / 1000.0;
        const double width = *rc::gen::inRange(0, 1500) / 1000.0;
        const double slope = *rc::gen::element(-0.5, 0.0, 0.3, 2.0, HUGE_VAL, std::numeric_limits<double>::quiet_NaN());
        shadows.push_back({*rc::gen::inRange(0, 400000) / 1000.0, {begin, begin + width}, slope});
        continue;
      }
      const Building& target = scene.buildings[*rc::gen::inRange<std::size_t>(0, scene.buildings.size())];
      const auto span = box_span(target.bounds.plan(), e);
      if (!span) continue;
      const double d = min_distance(e, target.bounds.plan());
      if (kind == 2) at_tie.push_back(shadows.size());
      const double farthest = kind == 2 ? d : std::nextafter(d, -HUGE_VAL);
      shadows.push_back({farthest, {span->span.begin - 0.01, span->span.end + 0.01}, 0.5});
    }
    std::vector<char> known(scene.buildings.size(), 0);
    const bool with_known = *rc::gen::arbitrary<bool>();
    if (with_known)
      for (char& c : known) c = *rc::gen::inRange(0, 4) == 0;

    CullStatistics fast_stats, sweep_stats, unused;
    const std::vector<ObjectId> fast = targets.visible(region, shadows, with_known ? &known : nullptr, fast_stats);
    const std::vector<ObjectId> swept = targets.visible_by_sweep(region, shadows, with_known ? &known : nullptr, sweep_stats);
    RC_ASSERT(fast == swept);
    RC_ASSERT(fast_stats.cells_tested == sweep_stats.cells_tested);
    RC_ASSERT(fast_stats.buildings_tested == sweep_stats.buildings_tested);

    // The hard cases reached: something hidden, and ties that decided (moved one step nearer,
    // they hide more).
    if (targets.visible_by_sweep(region, {}, with_known ? &known : nullptr, unused).size() > fast.size()) ++some_hidden;
    std::vector<Shadow> moved = shadows;
    for (std::size_t i : at_tie) moved[i].farthest = std::nextafter(moved[i].farthest, -HUGE_VAL);
    if (targets.visible_by_sweep(region, moved, with_known ? &known : nullptr, unused) != swept) ++ties_decided;
  });
  ASSERT_TRUE(run.held);
  if (reproducing()) return;
  std::cerr << "cases " << run.cases << ", some target hidden " << some_hidden << ", ties decided " << ties_decided << "\n";
  EXPECT_GE(some_hidden, run.cases / 3);
  EXPECT_GE(ties_decided, run.cases / 20);
}

// Targets not at the eye's height take the sweep (no order-free argument there): the same answer
// as visible_by_sweep, and a shadow below the eye hides a lower target, which the order-free
// test, reading only positive shadows, could not.
TEST(PassiveTargets, EyeAboveTheTargetsTakesTheSweep) {
  const Scene city = generators::scene_of({"manhattan", 5, {{"blocks_x", 2}, {"blocks_y", 2}}});
  const std::vector<NavigableRegion> regions = generators::navigable_regions(city);
  ASSERT_FALSE(regions.empty());
  const Scene scene = navigable_region_targets(regions, kEyeHeight);
  PassiveTargets targets(scene, MethodOptions{});
  const Building& target = scene.buildings.back();
  Camera camera;
  camera.hfov = kTwoPi;
  const Vec2 far_corner = target.bounds.plan().hi + Vec2{30.0, 30.0};
  camera.position = {far_corner.x, far_corner.y, kEyeHeight + 1.0};
  const ViewRegion region{camera, 1.0, 0.0};
  const Vec2 e = plan(camera.position);
  const auto span = box_span(target.bounds.plan(), e);
  ASSERT_TRUE(span);
  // Below the eye, yet above the target's highest slope (1 m down over its farthest distance).
  const double d = min_distance(e, target.bounds.plan()), far = max_distance(e, target.bounds.plan());
  const std::vector<Shadow> shadows{{d / 2, {span->span.begin - 0.01, span->span.end + 0.01}, -0.9 / far}};
  CullStatistics a, b;
  const std::vector<ObjectId> seen = targets.visible(region, shadows, nullptr, a);
  EXPECT_EQ(seen, targets.visible_by_sweep(region, shadows, nullptr, b));
  EXPECT_FALSE(std::binary_search(seen.begin(), seen.end(), target.id));
  EXPECT_EQ(a.buildings_tested, b.buildings_tested);
}

}  // namespace
}  // namespace cullcheck
