// Slice-wise from-region culling (engine/slice_wise/cell_culling.hpp, Yılmaz & Güdükbay §4.2) is
// conservative at slice granularity: every triangle the oracle witnesses from any eye of a view
// cell (its corners, edge midpoints and a point inside) belongs to an object of the cell's PVS and
// lies in a slice its three indices keep. Over seeded detailed cities, cells on the streets, and
// over the real LoD2 district of The Hague, cells on a free-space walk.
// The property must reach objects the indices cut (count them) and must fail for a straw man
// whose occluders are not shrunk by the cell's ε.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <map>
#include <string>
#include <sstream>

#include "core/formats/footprint_formats.hpp"
#include "engine/slice_wise/cell_culling.hpp"
#include "generators/camera_paths.hpp"
#include "generators/detailed_buildings.hpp"
#include "oracle/oracle.hpp"
#include "oracle/witness_cover.hpp"
#include "properties/property_run.hpp"
#include "reports/report_parts.hpp"
#include "reports/slice_wise_table.hpp"

namespace cullcheck::slice_wise {
namespace {

struct Counts {
  std::size_t cases = 0, eyes = 0, witnessed_triangles = 0, witnessed_in_cut_objects = 0, cut_objects = 0;
  std::size_t drawn_by_another = 0;  // credited to a dropped face at a point a kept face draws (oracle/witness_cover.hpp)
  std::size_t violations = 0;
  std::size_t kept_eroded_jointly = 0;  // PVS objects eroded with touching neighbours (voxel_erosion.hpp)
  std::size_t two_sided = 0;            // PVS objects cut on both vertical axes at once
  std::size_t witnessed_in_two_sided = 0;
  std::map<std::string, std::size_t> configurations;
};

// The eyes a cell is checked from: corners, edge midpoints, one drawn point inside.
std::vector<Vec3> cell_eyes(Vec3 centre, double side, double u, double v) {
  const double h = side / 2;
  std::vector<Vec3> eyes;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      if (i != 0 || j != 0) eyes.push_back({centre.x + i * h, centre.y + j * h, centre.z});
  eyes.push_back({centre.x + (2 * u - 1) * h, centre.y + (2 * v - 1) * h, centre.z});
  return eyes;
}

// Culls the cell at `centre` and checks every triangle the oracle witnesses from its eyes.
void check_cell(Counts& counts, const oracle::Oracle& truth, const SliceWiseScene& prepared,
                bool self_occlusion, Vec3 centre, double side, double u, double v) {
  CellCullingOptions co;
  co.self_occlusion = self_occlusion;
  // As the report runs them: the corrected occluders with a rectangle on both vertical axes.
  co.both_vertical_axes = prepared.options().shrinking == Shrinking::voxel_erosion;
  CellCuller culler(prepared, co);
  ++counts.configurations[std::string(shrinking_name(prepared.options().shrinking)) + (co.self_occlusion ? "+self" : "")];
  const CellPvs pvs = culler.cull(centre);
  // What the indices keep, per object id: nothing (absent), or the triangles kept.
  std::map<ObjectId, std::vector<char>> kept;
  std::map<ObjectId, bool> cut;  // the indices drop part of the object
  std::map<ObjectId, bool> two_sided;
  for (const ObjectVisibility& ov : pvs.visible) {
    const SliceWiseObject& o = prepared.objects()[ov.object];
    two_sided.emplace(o.id, ov.choice.form == VisibleForm::two_sided);
    counts.two_sided += ov.choice.form == VisibleForm::two_sided;
    std::vector<char> k(o.triangles(), 0);
    for (std::uint32_t t : rendering_set(o.slices, ov.indices)) k[t] = 1;
    kept.emplace(o.id, std::move(k));
    cut.emplace(o.id, ov.choice.dropped > 0);
    counts.cut_objects += ov.choice.dropped > 0;
    counts.kept_eroded_jointly += o.eroded_with > 1;
  }

  oracle::SamplingOptions sampling;
  sampling.spacing_m = 3.0;
  sampling.frustum_resolution = 128;
  sampling.threads = 1;
  const oracle::TriangleMesh& mesh = truth.rays().mesh();
  for (const Vec3& eye : cell_eyes(centre, side, u, v)) {
    Camera cam;
    cam.position = eye;
    cam.hfov = kTwoPi;
    oracle::TriangleWitnesses witnessed;
    truth.rays().witness(cam, sampling, nullptr, &witnessed);
    ++counts.eyes;
    for (const auto& [prim, ray] : witnessed) {
      const std::uint32_t owner = mesh.owner_index[prim];
      const ObjectId id = mesh.object_ids[owner];
      const std::uint32_t local = prim - mesh.first_triangle[owner];
      ++counts.witnessed_triangles;
      const auto it = kept.find(id);
      counts.witnessed_in_cut_objects += it != kept.end() && cut.at(id);
      counts.witnessed_in_two_sided += it != kept.end() && two_sided.at(id);
      const oracle::WitnessVerdict verdict = oracle::witness_verdict(mesh, prim, ray, it == kept.end() ? nullptr : &it->second);
      if (verdict == oracle::WitnessVerdict::drawn) continue;
      if (verdict == oracle::WitnessVerdict::drawn_by_another) {
        ++counts.drawn_by_another;
        continue;
      }
      ++counts.violations;
      // A witness must stand re-cast in double precision (the oracle casts in single).
      const auto replayed = truth.rays().replay(ray, cam);
      RC_LOG() << "from (" << eye.x << ", " << eye.y << ", " << eye.z << "): object " << id << " triangle " << local
               << (it == kept.end() ? " (object culled)" : " (slice culled)") << "; ray " << oracle::describe(ray)
               << "; replayed hit " << (replayed.hit ? std::to_string(*replayed.hit) : "none") << "\n";
      RC_FAIL("a witnessed triangle lies in no kept slice");
    }
  }
  ++counts.cases;
}

// One case: a seeded detailed city, a cell centred on a frame of a street walk, one of the three
// configurations the report runs (as published; voxel-eroded occluders; with self-occlusion).
// `shrink_epsilon_share` scales what the occluders are shrunk by (1: the cell's ε; less for the
// straw man).
void check_case(Counts& counts, double shrink_epsilon_share) {
  const int configuration = *rc::gen::element(0, 1, 2);
  const std::uint64_t seed = *rc::gen::inRange<std::uint64_t>(0, 1u << 20);
  const int frame = *rc::gen::inRange(0, 120);
  const double u = *rc::gen::inRange(0, 1001) / 1000.0, v = *rc::gen::inRange(0, 1001) / 1000.0;
  generators::DetailedCityParams p;
  p.layout.blocks_x = 2, p.layout.blocks_y = 2;
  p.max_triangles = 3000;
  const Scene scene = generators::detailed_city(p, seed);
  generators::StreetWalkParams walk;
  walk.frames = 121;
  const CameraPath path = generators::street_walk(p.layout, walk, seed);
  const double side = 2.0, epsilon = side / std::sqrt(2.0);
  const Vec3 centre = path.frames[static_cast<std::size_t>(frame)].position;
  std::ostringstream replay;
  replay << "detailed city 2 x 2 blocks, max_triangles 3000, seed " << seed << "; cell side " << side << " at ("
         << centre.x << ", " << centre.y << ", " << centre.z << ") = street walk frame " << frame << "; configuration "
         << configuration;
  RC_LOG() << replay.str() << "\n";

  SliceSceneOptions so;
  so.epsilon = epsilon * shrink_epsilon_share;
  so.threads = 1;
  so.shrinking = configuration == 0 ? Shrinking::minkowski_mesh : Shrinking::voxel_erosion;
  const SliceWiseScene prepared(scene, so);
  const oracle::Oracle truth(scene);
  check_cell(counts, truth, prepared, configuration == 2, centre, side, u, v);
}

// The real LoD2 district (The Hague, each building with its parts one object), prepared once per
// shrinking; cells centred on the frames of a free-space walk laid out on its footprints.
struct Hague {
  static constexpr const char* kFile = CULLCHECK_SHARED_DATA "/real/denhaag_lod2/DenHaag_01.city.json";
  Scene scene;
  CameraPath walk;
  std::unique_ptr<oracle::Oracle> truth;
  std::unique_ptr<SliceWiseScene> published, eroded;
  Hague() {
    formats::FootprintOptions fo;
    fo.cityjson_buildings = true;
    scene = formats::read_cityjson(kFile, fo);
    const Scene footprints = formats::read_cityjson(kFile);
    generators::StreetWalkParams w;
    w.frames = 600;
    walk = generators::free_space_walk(footprints, w, 1);
    const Vec2 shift = footprints.origin - scene.origin;
    for (Camera& c : walk.frames) c.position.x += shift.x, c.position.y += shift.y;
    truth = std::make_unique<oracle::Oracle>(scene);
    SliceSceneOptions so;
    so.shrinking = Shrinking::minkowski_mesh;
    published = std::make_unique<SliceWiseScene>(scene, so);
    so.shrinking = Shrinking::voxel_erosion;
    eroded = std::make_unique<SliceWiseScene>(scene, so);
  }
};

void check_hague_case(const Hague& city, Counts& counts) {
  const int configuration = *rc::gen::element(0, 1, 2);
  const int frame = *rc::gen::inRange(0, static_cast<int>(city.walk.frames.size()));
  const double u = *rc::gen::inRange(0, 1001) / 1000.0, v = *rc::gen::inRange(0, 1001) / 1000.0;
  const Vec3 centre = city.walk.frames[static_cast<std::size_t>(frame)].position;
  RC_LOG() << "The Hague LoD2 (DenHaag_01.city.json, buildings), free-space walk seed 1 of 600 frames, frame " << frame
           << " as the centre of a 2 m cell; configuration " << configuration << "\n";
  check_cell(counts, *city.truth, configuration == 0 ? *city.published : *city.eroded, configuration == 2,
             centre, 2.0, u, v);
}

TEST(SliceWiseCulling, EveryWitnessedTriangleLiesInAKeptSlice) {
  Counts counts;
  const PropertyOutcome outcome = run_property("slice-wise-conservative", 15, true, [&] { check_case(counts, 1.0); });
  std::cerr << "cases " << counts.cases << ", eyes " << counts.eyes << ", witnessed triangles " << counts.witnessed_triangles
            << " (" << counts.witnessed_in_cut_objects << " in objects the indices cut), objects cut "
            << counts.cut_objects << " (" << counts.two_sided << " on both vertical axes, " << counts.witnessed_in_two_sided
            << " witnessed triangles in those), witnesses of dropped faces drawn by a kept one " << counts.drawn_by_another << "; configurations:";
  for (const auto& [name, n] : counts.configurations) std::cerr << " " << name << " " << n;
  std::cerr << "\n";
  EXPECT_TRUE(outcome.held);
  EXPECT_EQ(counts.configurations.size(), 3u) << "every configuration reached";
  EXPECT_GT(counts.cut_objects, counts.cases) << "the property must reach objects whose slices are dropped";
  EXPECT_GT(counts.witnessed_in_cut_objects, 100u);
  EXPECT_GT(counts.witnessed_in_two_sided, 100u) << "the property must reach objects cut on both vertical axes";
}

TEST(SliceWiseCulling, EveryWitnessedTriangleOfTheRealLod2DistrictLiesInAKeptSlice) {
  if (!std::filesystem::exists(Hague::kFile)) GTEST_FAIL() << "the real data is missing: " << Hague::kFile;
  const Hague city;
  Counts counts;
  const PropertyOutcome outcome = run_property("slice-wise-conservative-lod2", 12, true, [&] { check_hague_case(city, counts); });
  std::cerr << "The Hague: cases " << counts.cases << ", eyes " << counts.eyes << ", witnessed triangles "
            << counts.witnessed_triangles << " (" << counts.witnessed_in_cut_objects << " in objects the indices cut), objects cut "
            << counts.cut_objects << " (" << counts.two_sided << " on both vertical axes, " << counts.witnessed_in_two_sided
            << " witnessed triangles in those), witnesses of dropped faces drawn by a kept one " << counts.drawn_by_another
            << ", PVS objects eroded with their neighbours " << counts.kept_eroded_jointly << "; configurations:";
  for (const auto& [name, n] : counts.configurations) std::cerr << " " << name << " " << n;
  std::cerr << "\n";
  EXPECT_TRUE(outcome.held);
  EXPECT_EQ(counts.configurations.size(), 3u) << "every configuration reached";
  EXPECT_GT(counts.cut_objects, counts.cases) << "the property must reach buildings whose slices are dropped";
  EXPECT_GT(counts.witnessed_in_cut_objects, 100u);
  EXPECT_GT(counts.witnessed_in_two_sided, 100u) << "the property must reach buildings cut on both vertical axes";
  // Row houses: the eroded scene erodes buildings that share walls as one solid each row.
  std::size_t jointly = 0;
  for (const SliceWiseObject& o : city.eroded->objects()) jointly += o.eroded_with > 1;
  EXPECT_EQ(jointly, 574u);
  EXPECT_GT(counts.kept_eroded_jointly, counts.cases) << "the property must reach cells among rows eroded as one";
}

TEST(SliceWiseCulling, OccludersNotShrunkByTheCellFailTheProperty) {
  Counts counts;
  const PropertyOutcome outcome =
      run_property("slice-wise-unshrunk-straw-man", 30, false, [&] { check_case(counts, 0.01); }, true);
  EXPECT_FALSE(outcome.held) << "occluders shrunk by 1% of ε must be caught from the cell's corners";
}

// The report splits what the indices keep beyond the best form by kind of object; on a small
// detailed city the kinds add up to the totals, each keeps at least its best form, and their
// shares of the gap sum to one.
TEST(SliceWiseTable, TheGapToTheBestFormAddsUpOverItsKinds) {
  SliceTableOptions o;
  o.detailed.layout.blocks_x = 3, o.detailed.layout.blocks_y = 3;
  o.detailed.max_triangles = 3000;
  o.frames = 200;
  o.oracle_cells = 2;
  o.runs = {{Shrinking::voxel_erosion, true, true}};
  const nlohmann::json table = slice_wise_table(o);
  const nlohmann::json& bound = table["cities"][0]["runs"][0]["bound"];
  ASSERT_EQ(bound["gap_by_kind"].size(), 5u);
  double indices = 0, best = 0, share = 0, objects = 0;
  for (const nlohmann::json& g : bound["gap_by_kind"]) {
    EXPECT_GE(g["kept_by_indices"].get<double>(), g["kept_by_best_form"].get<double>()) << g.dump();
    indices += g["kept_by_indices"].get<double>(), best += g["kept_by_best_form"].get<double>();
    share += g["share_of_gap"].get<double>(), objects += g["objects"].get<double>();
    if (g["kind"] == "unwitnessed") {
      EXPECT_EQ(g["kept_by_best_form"].get<double>(), 0.0) << "nothing witnessed, nothing to keep";
    }
  }
  EXPECT_GT(objects, 0.0);
  EXPECT_DOUBLE_EQ(indices, bound["kept_by_indices"].get<double>());
  EXPECT_DOUBLE_EQ(best, bound["kept_by_best_form"].get<double>());
  ASSERT_GT(indices, best) << "the indices keep more than the best form on this city";
  EXPECT_NEAR(share, 1.0, 1e-9);
  EXPECT_EQ(slice_table_violations(table), 0u);
}

TEST(SliceWiseTable, RefusesAnOracleOfOneEyePerSide) {
  SliceTableOptions o;
  o.oracle_eyes_per_side = 1;
  EXPECT_THROW(slice_wise_table(o), std::invalid_argument);
}

// The report's section feeds the gate and the ledger: a violation in any run fails both.
TEST(SliceWiseTable, AViolationFailsTheGateAndRefutesTheClaim) {
  using nlohmann::json;
  auto run = [](const char* shrinking, bool self, std::uint64_t violations, double share) {
    json examples = json::array();
    if (violations > 0) examples.push_back({{"eye", {1, 2, 1.7}}, {"object", 7}, {"triangle", 12}});
    return json{{"shrinking", shrinking},
                {"self_occlusion", self},
                {"table_3", {{"slice_over_building", share}}},
                {"oracle", {{"eyes", 9}, {"violations", violations}, {"seconds", 1.0}, {"examples", examples}}}};
  };
  json doc;
  doc["slice_wise"] = {{"replay", "cullcheck report --slice-table"},
                       {"cities", json::array({{{"city", "detailed"},
                                                {"runs", json::array({run("minkowski_mesh", false, 0, 0.96),
                                                                      run("voxel_erosion", false, 2, 0.5),
                                                                      run("voxel_erosion", true, 0, 0.49)})}}})}};
  EXPECT_EQ(section_gate_violations(doc), 2u);
  const std::vector<ClaimCheck> claims = slice_wise_claims(doc["slice_wise"]);
  ASSERT_EQ(claims.size(), 3u);
  EXPECT_EQ(claims[0].id, "yilmaz-slice-conservative");
  EXPECT_TRUE(claims[0].holds);
  EXPECT_EQ(claims[0].frames_checked, 9u);
  EXPECT_EQ(claims[1].id, "cullcheck-slice-voxel-erosion");
  EXPECT_FALSE(claims[1].holds);
  EXPECT_EQ(claims[1].violations, 2u);
  EXPECT_EQ(claims[1].counterexample_replay, "cullcheck report --slice-table");
  EXPECT_EQ(claims[2].id, "yilmaz-slice-half-of-building-level");
  EXPECT_FALSE(claims[2].holds) << "96% of the building-level triangles is not about half";
  doc["slice_wise"]["cities"][0]["runs"][1]["oracle"]["violations"] = 0;
  EXPECT_EQ(section_gate_violations(doc), 0u);
}

}  // namespace
}  // namespace cullcheck::slice_wise
