// The guarded ΔH's region certificate (engine/delta_horizon/motion_region.hpp) decides each
// building from the region's geometry alone: which quadtree it sweeps through, and so which
// cells and buildings happen to lie between two decisions, must not change its classes. Until
// each decision saw exactly the grown shadows keyed below it, a sharper cell test (the height
// split) left 2 of 49 buildings of the default city's first region uncertain instead of
// certainly visible.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <iostream>
#include <vector>

#include "engine/delta_horizon/motion_region.hpp"
#include "engine/spatial/quadtree.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "properties/property_run.hpp"

namespace cullcheck {
namespace {

struct Classes {
  std::vector<std::uint32_t> visible, swept;
  std::uint64_t uncertain = 0;
};

Classes certify_with(const Scene& scene, std::uint32_t leaf_size, const MotionRegion& region, std::uint32_t bins = 1024) {
  const Quadtree tree(scene, leaf_size);
  RegionCertificate certificate(scene, tree, bins);
  CullStatistics stats;
  certificate.certify(region, stats);
  return {certificate.visible(), certificate.swept(), certificate.uncertain_count()};
}

TEST(RegionCertificate, ClassesDoNotDependOnTheQuadtree) {
  int decided = 0;
  const PropertyOutcome outcome = run_property("RegionCertificate.ClassesDoNotDependOnTheQuadtree", 60, true, [&] {
    const generators::SceneSpec spec = *rc::gen::oneOf(generators::rcgen::occluded_manhattan_spec(), generators::rcgen::scene_spec());
    const Scene scene = generators::scene_of(spec);
    const Camera camera = *generators::rcgen::street_camera(scene);
    const double radius = *rc::gen::element(0.25, 0.5, 1.0, 2.0);
    const MotionRegion region{camera, radius, 0.5, 0.05};
    const Classes one = certify_with(scene, 1, region);
    for (std::uint32_t leaf : {4u, 8u, 64u}) {
      const Classes other = certify_with(scene, leaf, region);
      RC_ASSERT(other.visible == one.visible);
      RC_ASSERT(other.swept == one.swept);
      RC_ASSERT(other.uncertain == one.uncertain);
    }
    decided += !one.visible.empty() && one.uncertain > 0;
  });
  EXPECT_TRUE(outcome.held);
  std::cerr << "cases with both certainly visible and uncertain buildings: " << decided << " of " << outcome.cases << "\n";
  EXPECT_GE(decided, outcome.cases / 4) << "too few cases decided anything (the hard case: visible and uncertain together)";
}

// The default city's first street-walk region (the main job's walk, path seed 1), as measured
// when the decision rule changed.
TEST(RegionCertificate, DefaultCityFirstRegionPinned) {
  const Scene scene = generators::make_city("default", 1, nlohmann::json::object());
  const CameraPath walk = generators::make_camera_path("street_walk", scene, 1, {{"frames", 300}});
  const MotionRegion region{walk.frames.front(), 0.5, 0.5, 0.05};
  const Classes c = certify_with(scene, 8, region, 4096);  // the guarded ΔH's default options
  // 49 / 49 / 94 with one box a cell and the earlier rule; 47 / 51 / 94 with the height split
  // and the earlier rule.
  EXPECT_EQ(c.visible.size(), 50u);
  EXPECT_EQ(c.uncertain, 48u);
  EXPECT_EQ(c.swept.size(), 94u);
}

}  // namespace
}  // namespace cullcheck

namespace cullcheck {
namespace {

// meets_every_box (the from-region sweeps skip may_meet when it holds): whenever it holds for an
// extent, may_meet holds for every box inside it, drawn down to boxes at the extent's far corner
// and around the eye; it holds for a city-sized extent under the default far plane (counted),
// and not once the far plane comes within twice the far corner's L1 distance, nor for a camera
// that is not all-round.
TEST(MeetsEveryBox, ImpliesMayMeetForEveryBoxInside) {
  int held = 0, refused = 0;
  const PropertyOutcome outcome = run_property("MeetsEveryBox.ImpliesMayMeetForEveryBoxInside", 300, true, [&] {
    auto coordinate = [] { return *rc::gen::inRange(-2000000, 2000000) / 1000.0; };
    Box3 extent;
    for (int k = 0; k < 2; ++k) extent.extend({coordinate(), coordinate(), *rc::gen::inRange(-5000, 80000) / 1000.0});
    Camera camera;
    camera.hfov = kTwoPi;
    camera.position = {coordinate(), coordinate(), *rc::gen::inRange(0, 3000) / 1000.0};
    camera.far = *rc::gen::element(100000.0, 10000.0, 3000.0, 500.0);
    const double reach = *rc::gen::element(0.0, 1.4142135623730951, 50.0);
    const ViewVolume volume(camera);
    if (!meets_every_box(volume, extent, reach)) {
      ++refused;
      return;
    }
    ++held;
    for (int b = 0; b < 20; ++b) {
      auto inside = [&](double lo, double hi) { return lo + (hi - lo) * (*rc::gen::inRange(0, 1001) / 1000.0); };
      Box3 box;
      const bool corner = b == 0;
      box.extend({corner ? extent.lo.x : inside(extent.lo.x, extent.hi.x), corner ? extent.lo.y : inside(extent.lo.y, extent.hi.y),
                  corner ? extent.lo.z : inside(extent.lo.z, extent.hi.z)});
      box.extend({corner ? extent.lo.x : inside(extent.lo.x, extent.hi.x), corner ? extent.lo.y : inside(extent.lo.y, extent.hi.y),
                  corner ? extent.lo.z : inside(extent.lo.z, extent.hi.z)});
      RC_ASSERT(may_meet(volume, box, reach, 0.0));
    }
  });
  ASSERT_TRUE(outcome.held);
  if (reproducing()) return;
  EXPECT_GE(held, outcome.cases / 10);
  EXPECT_GE(refused, outcome.cases / 10);

  // A 4 km city under the default 100 km far plane, an eye inside it: holds.
  Camera camera;
  camera.hfov = kTwoPi;
  camera.position = {100.0, 200.0, 1.7};
  Box3 city;
  city.extend({-2000.0, -2000.0, 0.0});
  city.extend({2000.0, 2000.0, 120.0});
  EXPECT_TRUE(meets_every_box(ViewVolume(camera), city, 1.4142135623730951));
  // The far plane within twice the far corner's L1 distance (2,100 + 2,200 + 118.3 m): not.
  camera.far = 8000.0;
  EXPECT_FALSE(meets_every_box(ViewVolume(camera), city, 1.4142135623730951));
  camera.far = 9000.0;
  EXPECT_TRUE(meets_every_box(ViewVolume(camera), city, 1.4142135623730951));
  // A frustum, or a negative reach: never.
  camera.hfov = 1.2;
  EXPECT_FALSE(meets_every_box(ViewVolume(camera), city, 1.4142135623730951));
  camera.hfov = kTwoPi;
  EXPECT_FALSE(meets_every_box(ViewVolume(camera), city, -1.0));
}

}  // namespace
}  // namespace cullcheck
