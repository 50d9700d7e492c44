// From-region PVS by shadow shrinking (thesis ch. 4.1.2) held to the oracle: the PVS computed
// for the ε-disc around a camera (ViewRegion) must hold every building the oracle sees from any
// viewpoint of the disc, turned by up to the region's turn. Viewpoints: the centre, points on
// the boundary circle, one inside; orientations at the turn's extremes.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/scene_io.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/minkowski_shrinking.hpp"
#include "engine/shrinking/region_shrinking.hpp"
#include "generators/random.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "generators/rapidcheck_hard_cases.hpp"
#include "oracle/oracle.hpp"
#include "properties/method_options_gen.hpp"
#include "properties/property_oracle.hpp"
#include "properties/property_run.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;

struct RegionCase {
  generators::SceneCase scene_case;
  double radius = 0.0;
  double turn = 0.0;
  double phase = 0.0;  // where on the boundary the samples start
};

rc::Gen<RegionCase> region_case(rc::Gen<generators::SceneSpec> specs) {
  return rc::gen::map(rc::gen::tuple(rcgen::scene_case(std::move(specs)), rc::gen::element(0.05, 0.5, 2.0, 8.0),
                                     rc::gen::element(0.0, 0.05, 0.2), rc::gen::inRange(0, 360)),
                      [](const auto& t) {
                        return RegionCase{std::get<0>(t), std::get<1>(t), std::get<2>(t), std::get<3>(t) * kPi / 180};
                      });
}

// The viewpoints checked: centre; six on the boundary circle, turned alternately by ±turn; one
// halfway in. Omnidirectional cameras ignore the turn.
std::vector<Camera> sample_viewpoints(const RegionCase& r) {
  const Camera& c = r.scene_case.camera;
  std::vector<Camera> out{c};
  for (int k = 0; k < 7; ++k) {
    Camera v = c;
    const double angle = r.phase + k * kTwoPi / 6;
    const double reach = k < 6 ? r.radius : r.radius / 2;
    v.position = {c.position.x + reach * std::cos(angle), c.position.y + reach * std::sin(angle), c.position.z};
    if (!c.omnidirectional()) v.yaw = std::fmod(c.yaw + (k % 2 == 0 ? r.turn : -r.turn) + kTwoPi, kTwoPi);
    out.push_back(v);
  }
  return out;
}

// The first viewpoint from which the oracle sees a building the region's PVS lacks.
struct Miss {
  Camera viewpoint;
  ObjectId building = 0;
  std::string witness;
};
std::optional<Miss> region_miss(const std::string& method, const Scene& scene, const RegionCase& r,
                                const MethodOptions& options = {}) {
  auto engine = make_region_method(method, scene, options);
  const std::vector<ObjectId> pvs = engine->cull_region({r.scene_case.camera, r.radius, r.turn}).pvs;
  const oracle::Oracle truth(scene);
  for (const Camera& v : sample_viewpoints(r)) {
    oracle::OracleAnswer seen = truth.visible_set(v, property_oracle());
    if (const std::vector<ObjectId> missed = confirmed_misses(truth, seen, v, pvs); !missed.empty()) {
      const ObjectId id = missed.front();
      return Miss{v, id, seen.sampling ? oracle::describe(seen.sampling->witnesses.at(id)) : seen.model};
    }
  }
  return std::nullopt;
}

std::string describe(const RegionCase& r, const Miss& m, const std::string& method) {
  std::ostringstream out;
  std::string view = camera_to_json_text(m.viewpoint);
  if (!view.empty() && view.back() == '\n') view.pop_back();
  out << method << " (radius " << r.radius << " m, turn " << r.turn << " rad) around " << r.scene_case
      << " misses building " << m.building << " seen from " << view << ": " << m.witness;
  return out.str();
}

// Shrinking only takes occlusion away: a region's PVS holds the PVS OH(OS) computes at its centre
// (with the same shadow rule: published for the published shrinking, conservative otherwise).
RC_GTEST_PROP(RegionShrinking, RegionPvsHoldsTheCentresPvs, ()) {
  const RegionCase r = *region_case(rcgen::scene_spec());
  const Scene scene = generators::scene_of(r.scene_case.spec);
  RC_PRE(!scene.buildings.empty());
  for (const auto& [region_method, point_method] :
       {std::pair{"shrink_adjustable_thesis", "oh_os_thesis"}, std::pair{"shrink_adjustable_conservative", "oh_os_conservative"}}) {
    const std::vector<ObjectId> region_pvs =
        make_region_method(region_method, scene)->cull_region({r.scene_case.camera, r.radius, r.turn}).pvs;
    const std::vector<ObjectId> point_pvs = make_method(point_method, scene)->cull(r.scene_case.camera).pvs;
    std::vector<ObjectId> lost;
    std::set_difference(point_pvs.begin(), point_pvs.end(), region_pvs.begin(), region_pvs.end(), std::back_inserter(lost));
    if (!lost.empty())
      RC_FAIL(std::string(region_method) + " (radius " + std::to_string(r.radius) + ") lacks building " +
              std::to_string(lost.front()) + " that " + point_method + " keeps at the centre: " + [&] {
                std::ostringstream o;
                o << r.scene_case;
                return o.str();
              }());
  }
}

// The region methods that claim conservativeness over the disc, each held to the oracle by the
// same check (one property per method, so a failure names its method and shrinks on its own).
void holds_over_the_disc(const std::string& method) {
  const RegionCase r = *region_case(rcgen::scene_spec());
  const Scene scene = generators::scene_of(r.scene_case.spec);
  RC_PRE(!scene.buildings.empty());
  const auto miss = region_miss(method, scene, r);
  if (miss) RC_FAIL(describe(r, *miss, method));
}

RC_GTEST_PROP(RegionShrinking, FormerShrinkingHoldsOverTheDisc, ()) { holds_over_the_disc("shrink_former"); }
RC_GTEST_PROP(RegionShrinking, CertifiedShrinkingHoldsOverTheDisc, ()) {
  holds_over_the_disc("shrink_adjustable_conservative");
}
RC_GTEST_PROP(RegionShrinking, MinkowskiShrinkingHoldsOverTheDisc, ()) { holds_over_the_disc("shrink_minkowski"); }
RC_GTEST_PROP(RegionShrinking, CorrectedAdjustableShrinkingHoldsOverTheDisc, ()) {
  holds_over_the_disc("shrink_adjustable_corrected");
}

// The same over the hard cases (rapidcheck_hard_cases.hpp: occluded Manhattan grids, sub-metre
// gaps, eyes at walls, aimed and steep cameras), with the engine's options drawn over their range
// (method_options_gen.hpp) and the method drawn among those claiming the disc.
TEST(RegionShrinking, ConservativeRegionMethodsHoldOnHardCasesWithDrawnOptions) {
  const std::vector<std::string> methods{"shrink_former", "shrink_adjustable_conservative", "shrink_minkowski",
                                         "shrink_adjustable_corrected"};
  for (const std::string& m : methods) ASSERT_TRUE(make_region_method(m, Scene{})->claims_conservative()) << m;
  const auto hard_region_case = rc::gen::map(
      rc::gen::tuple(rcgen::hard_scene_case(), rc::gen::element(0.05, 0.5, 2.0, 8.0), rc::gen::element(0.0, 0.05, 0.2),
                     rc::gen::inRange(0, 360)),
      [](const auto& t) { return RegionCase{std::get<0>(t), std::get<1>(t), std::get<2>(t), std::get<3>(t) * kPi / 180}; });
  const PropertyOutcome run = run_property("region methods hold over the disc on hard cases with drawn options", 60, true, [&] {
    const RegionCase r = *hard_region_case;
    const std::string method = *rc::gen::elementOf(methods);
    const MethodOptions options = *method_options();
    const Scene scene = generators::scene_of(r.scene_case.spec);
    RC_PRE(!scene.buildings.empty());
    const auto miss = region_miss(method, scene, r, options);
    if (miss) RC_FAIL(describe(r, *miss, method) + " with " + option_flags(options));
  });
  EXPECT_TRUE(run.held) << "a region method misses a building the oracle sees (case above)";
}

// The buildings the target narrowing decides (target_span, engine/horizon/horizon_sweep.hpp):
// those the corrected and certified variants cull only because each target is tested by its span
// narrowed by asin(ε / R). The oracle, from the disc's viewpoints, must see none of them; the
// count shows the property reached the umbra's edges it is about (Manhattan grids and the hard
// cases, radii 0.5 to 8 m).
TEST(RegionShrinking, TargetNarrowingCullsOnlyWhatNoEyeOfTheDiscSees) {
  const auto narrowing_case = rc::gen::map(
      rc::gen::tuple(rc::gen::oneOf(rcgen::scene_case(rcgen::manhattan_spec()), rcgen::hard_scene_case()),
                     rc::gen::element(0.5, 1.41, 2.0, 8.0), rc::gen::element(0.0, 0.05), rc::gen::inRange(0, 360)),
      [](const auto& t) { return RegionCase{std::get<0>(t), std::get<1>(t), std::get<2>(t), std::get<3>(t) * kPi / 180}; });
  std::size_t cases = 0, deciding_cases = 0, decided = 0;
  const PropertyOutcome run = run_property("target narrowing culls only what no eye of the disc sees", 200, true, [&] {
    const RegionCase r = *narrowing_case;
    const Scene scene = generators::scene_of(r.scene_case.spec);
    RC_PRE(!scene.buildings.empty());
    const ViewRegion region{r.scene_case.camera, r.radius, r.turn};
    std::vector<ObjectId> culled_by_narrowing;
    auto pvs = [&](bool certified, bool narrow) -> std::vector<ObjectId> {
      if (certified) return CertifiedShadowShrinking(scene, MethodOptions{}, narrow).cull_region(region).pvs;
      return PublishedShadowShrinking(scene, MethodOptions{}, /*corrected=*/true, narrow).cull_region(region).pvs;
    };
    for (const bool certified : {false, true}) {
      const std::vector<ObjectId> with = pvs(certified, true), without = pvs(certified, false);
      // The narrowing only ever culls more.
      std::vector<ObjectId> added;
      std::set_difference(with.begin(), with.end(), without.begin(), without.end(), std::back_inserter(added));
      RC_ASSERT(added.empty());
      std::set_difference(without.begin(), without.end(), with.begin(), with.end(), std::back_inserter(culled_by_narrowing));
    }
    ++cases;
    std::sort(culled_by_narrowing.begin(), culled_by_narrowing.end());
    culled_by_narrowing.erase(std::unique(culled_by_narrowing.begin(), culled_by_narrowing.end()), culled_by_narrowing.end());
    if (culled_by_narrowing.empty()) return;
    ++deciding_cases;
    decided += culled_by_narrowing.size();
    const oracle::Oracle truth(scene);
    for (const Camera& v : sample_viewpoints(r)) {
      const oracle::OracleAnswer seen = truth.visible_set(v, property_oracle());
      for (ObjectId id : culled_by_narrowing)
        if (std::binary_search(seen.visible.begin(), seen.visible.end(), id)) {
          std::ostringstream what;
          what << "building " << id << ", culled only by the target narrowing (radius " << r.radius << " m) around "
               << r.scene_case << ", is seen from " << camera_to_json_text(v) << ": "
               << (seen.sampling ? oracle::describe(seen.sampling->witnesses.at(id)) : seen.model);
          RC_FAIL(what.str());
        }
    }
  });
  EXPECT_TRUE(run.held) << "the narrowing culls a building the oracle sees (case above)";
  std::cerr << "target narrowing: " << cases << " cases, " << deciding_cases << " where it culled something, " << decided
            << " buildings culled by it and seen from no viewpoint\n";
  if (run.held && !reproducing()) {
    EXPECT_GE(deciding_cases * 25, cases) << "the narrowing decided something in fewer than 1 case in 25";
    EXPECT_GE(decided, deciding_cases);
  }
}

// The claims ledger's counterexample to the first corrected variant (which dropped a shadow only
// when a tangent vertex lay within ε, as the published method does): a street wall reaching into
// the ε = 2 m disc between its tangent vertices hid a building from the centre that the disc's
// edge 2 m west sees. Asserted as properties, not as the building's id: the oracle sees from the
// edge a building OH(OS) culls at the centre (the case still tests something); every conservative
// region method keeps everything the oracle sees from the edge; the published method misses one
// of them, with a witness ray that replays.
TEST(RegionShrinking, WallReachingIntoTheDiscRegression) {
  const Scene scene = generators::make_city(
      "manhattan", 1020,
      {{"block_size", 39}, {"blocks_x", 6}, {"blocks_y", 5}, {"buildings_per_block", 3}, {"street_width", 10}, {"thin_fraction", 0.3}});
  Camera centre;
  centre.position = {-32.470363384499095, 102.36475659855616, 1.7};
  centre.yaw = 3.5878569354773195;
  centre.hfov = 1.5707963267948966;
  centre.vfov = 1.1780972450961724;
  Camera edge = centre;
  edge.position = {-34.46983129919285, 102.31862571833243, 1.7};
  const double radius = 2.0;
  ASSERT_LE(length(edge.position - centre.position), radius) << "the edge viewpoint lies in the disc";
  const oracle::Oracle truth(scene);
  const oracle::OracleAnswer seen = truth.visible_set(edge, property_oracle());
  const std::vector<ObjectId> point = make_method("oh_os_conservative", scene)->cull(centre).pvs;
  std::vector<ObjectId> hidden_from_centre;
  std::set_difference(seen.visible.begin(), seen.visible.end(), point.begin(), point.end(), std::back_inserter(hidden_from_centre));
  ASSERT_FALSE(hidden_from_centre.empty()) << "the oracle no longer sees from the edge anything OH(OS) culls at the centre";
  const ViewRegion region{centre, radius, 0.0};
  for (const std::string method : {"shrink_adjustable_corrected", "shrink_former", "shrink_adjustable_conservative"}) {
    const std::vector<ObjectId> pvs = make_region_method(method, scene)->cull_region(region).pvs;
    std::vector<ObjectId> missed;
    std::set_difference(seen.visible.begin(), seen.visible.end(), pvs.begin(), pvs.end(), std::back_inserter(missed));
    EXPECT_TRUE(missed.empty()) << method << " culls building " << missed.front() << ", seen from the edge";
  }
  const std::vector<ObjectId> published = make_region_method("shrink_adjustable_thesis", scene)->cull_region(region).pvs;
  std::vector<ObjectId> missed;
  std::set_difference(seen.visible.begin(), seen.visible.end(), published.begin(), published.end(), std::back_inserter(missed));
  ASSERT_FALSE(missed.empty()) << "the published method now keeps every building seen from the edge (was it changed?)";
  ASSERT_TRUE(seen.sampling.has_value()) << "ray sampling gives the witness ray (" << seen.model << ")";
  const oracle::WitnessRay& ray = seen.sampling->witnesses.at(missed.front());
  const oracle::RayOracle::Replay again = truth.rays().replay(ray, edge);
  EXPECT_EQ(again.hit, std::optional<ObjectId>(missed.front())) << oracle::describe(ray);
  EXPECT_TRUE(again.in_view_volume) << oracle::describe(ray);
}

// Footprint shrinking moves every edge inward by ε: a 10 m square becomes an 8 m one for ε = 1 m;
// a 1 m slab disappears for ε = 0.6 m; a sharp corner moves by more than ε (Fig. 4.3).
TEST(FootprintShrinking, MovesEdgesInwardAndDropsThinOccluders) {
  const auto square = shrink_convex_ring({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, 1.0);
  ASSERT_TRUE(square.has_value());
  double lo_x = 1e9, hi_x = -1e9, lo_y = 1e9, hi_y = -1e9;
  for (Vec2 p : *square) lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x), lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
  EXPECT_NEAR(lo_x, 1.0, 1e-12);
  EXPECT_NEAR(hi_x, 9.0, 1e-12);
  EXPECT_NEAR(lo_y, 1.0, 1e-12);
  EXPECT_NEAR(hi_y, 9.0, 1e-12);
  EXPECT_FALSE(shrink_convex_ring({{0, 0}, {20, 0}, {20, 1}, {0, 1}}, 0.6).has_value());
  const auto thin = shrink_convex_ring({{0, 0}, {20, 0}, {20, 1}, {0, 1}}, 0.4);
  ASSERT_TRUE(thin.has_value());
  // A 10-degree wedge: its tip moves by 1 / sin(5 degrees) = 11.5 m for ε = 1 m.
  const double tip_angle = 10.0 * kPi / 180;
  const std::vector<Vec2> wedge{{0, 0}, {100 * std::cos(tip_angle / 2), -100 * std::sin(tip_angle / 2)},
                                {100 * std::cos(tip_angle / 2), 100 * std::sin(tip_angle / 2)}};
  const auto shrunk = shrink_convex_ring(wedge, 1.0);
  ASSERT_TRUE(shrunk.has_value());
  double tip = 1e9;
  for (Vec2 p : *shrunk) tip = std::min(tip, p.x);
  EXPECT_NEAR(tip, 1.0 / std::sin(tip_angle / 2), 1e-9);
}


// What shrink_minkowski's preprocessing makes of the buildings of a few seeded cities
// (Manhattan: rectangles only; irregular: L/U/T footprints among convex ones), ε = 0.5 and 2 m.
// Asserted, as it holds by construction: each building is an occluder or is counted once among
// the reasons it is not, and on a Manhattan city (rectangles, so every wall moves exactly ε)
// Minkowski keeps as occluders exactly the buildings former shrinking does not make vanish.
// Figures, not checks (how the PVS sizes of the region methods compare; neither Minkowski ⊆
// former nor the reverse is guaranteed): report.json's region_sweep[] (`cullcheck report
// --region-sweep 0.5,2`), which gives every region method's pvs_mean against the point PVS and
// shrink_minkowski's occluder counts per ε.
TEST(RegionShrinking, MinkowskiOccludersAccountForEveryBuilding) {
  struct City {
    const char* generator;
    std::uint64_t seed;
    nlohmann::json params;
  };
  const std::vector<City> cities{
      {"manhattan", 11, {{"blocks_x", 4}, {"blocks_y", 4}, {"buildings_per_block", 4}, {"thin_fraction", 0.2}}},
      {"manhattan", 12, {{"blocks_x", 5}, {"blocks_y", 3}, {"buildings_per_block", 3}, {"street_width", 10}}},
      {"irregular", 21, {{"count", 40}, {"area_size", 250}}},
      {"irregular", 22, {{"count", 60}, {"area_size", 300}}},
      {"irregular", 23, {{"count", 30}, {"area_size", 160}}}};
  for (const double radius : {0.5, 2.0}) {
    std::size_t occluders = 0, dropped = 0;
    for (const City& city : cities) {
      const Scene scene = generators::make_city(city.generator, city.seed, city.params);
      const generators::OpenSpace open(scene);
      auto engine = make_region_method("shrink_minkowski", scene);
      generators::Random r = generators::Random::stream(city.seed, 0x3141, 0);
      const Box3 area = open.bounds();
      const Vec2 p = open.nudge_to_open({r.uniform_real(area.lo.x, area.hi.x), r.uniform_real(area.lo.y, area.hi.y)}, radius);
      Camera c;
      c.position = {p.x, p.y, 1.7};
      c.hfov = kTwoPi;
      c.vfov = kPi / 2;
      (void)engine->cull_region({c, radius, 0.0});  // preprocesses for this ε
      auto* minkowski = dynamic_cast<MinkowskiShrinking*>(engine.get());
      ASSERT_NE(minkowski, nullptr);
      const MinkowskiOccluderCounts& n = minkowski->occluder_counts();
      EXPECT_EQ(n.occluders + n.faces_removed + n.invalid_footprint + n.too_low, scene.buildings.size())
          << city.generator << " " << city.seed << " ε " << radius;
      occluders += n.occluders;
      dropped += n.faces_removed + n.invalid_footprint + n.too_low;
      if (std::string(city.generator) == "manhattan")
        for (const Building& b : scene.buildings) {
          const bool former_keeps = shrink_convex_ring(b.prisms.front().ring, radius).has_value() && b.height > radius;
          EXPECT_EQ(minkowski_occluder(b, radius).outcome == MinkowskiOutcome::occluder, former_keeps) << "building " << b.id;
        }
    }
    // Both outcomes occur, so both halves of the accounting were exercised.
    EXPECT_GT(occluders, 0u) << "ε " << radius;
    EXPECT_GT(dropped, 0u) << "ε " << radius;
  }
}

}  // namespace
}  // namespace cullcheck
