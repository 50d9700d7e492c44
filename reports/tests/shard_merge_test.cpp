// Runs split over shards (core/shard.hpp) and joined again (shard_merge.hpp, report_parts.hpp):
// four shards of a run, each written as its file and read back, merge into the report of the
// unsharded run, timings aside; each shard checks exactly its share; merge refuses files that
// are not the shards of one run.
#include "reports/shard_merge.hpp"

#include <gtest/gtest.h>

#include "reports/tests/synthetic_search.hpp"

#include <functional>

#include "core/errors.hpp"
#include "core/shard.hpp"
#include "generators/camera_paths.hpp"
#include "reports/report.hpp"
#include "reports/report_parts.hpp"
#include "reports/verification_json.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;

// Claims conservativeness and drops every other building of the frustum PVS: violations, a
// worst frame and misdrawn pixels to merge.
class DropsHalf final : public CullingMethod {
 public:
  explicit DropsHalf(const Scene& scene) : frustum_(make_method("frustum", scene)) {}
  std::string name() const override { return "drops_half"; }
  bool claims_conservative() const override { return true; }
  CullResult cull(const Camera& camera) override {
    CullResult r = frustum_->cull(camera);
    std::vector<ObjectId> half;
    for (std::size_t k = 0; k < r.pvs.size(); k += 2) half.push_back(r.pvs[k]);
    r.pvs = half;
    return r;
  }

 private:
  std::unique_ptr<CullingMethod> frustum_;
};

// Scene i checks i + 1 frames; scenes 3 and 5 refute the claim (synthetic_search.hpp).
constexpr auto synthetic = testing::synthetic_search;

class ShardedRun : public ::testing::Test {
 protected:
  SceneSource source{"manhattan", 7, R"({"blocks_x":4,"blocks_y":4})", ""};
  Scene scene = source.load();
  CameraPath path = generators::make_camera_path("street_walk", scene, 2, {{"frames", 30}});

  // One run, or shard `shard` of it, as its parts.
  ReportParts run(const Shard& shard) const {
    VerificationOptions options;
    options.oracle_stride = 3;
    options.measure_bare_embree = false;
    options.pixels = true;
    options.region_methods = {"shrink_minkowski"};
    options.shard = shard;
    std::vector<MethodUnderTest> methods = builtin_methods(scene, source, {"frustum", "oh_os_conservative", "delta_h_guarded"}, {}, options);
    methods.push_back({std::make_unique<DropsHalf>(scene), [](std::size_t f, const Camera&) { return "replay " + std::to_string(f); }});
    ReportParts parts;
    parts.verification = verify_path(scene, source, path, methods, {}, options);
    ReportInputs in;
    in.scene = &scene;
    in.source = source;
    in.path = &path;
    parts.header = report_header(in);
    ClaimCheck c;
    c.id = "synthetic";
    search_scenes(7, 2, shard, {&c}, "test", synthetic);
    parts.searched_claims = {c};
    parts.knob_rows = knob_sweep_rows(scene, path, {"oh_os_conservative"}, {}, {{"horizon_bins", {256, 4096}}}, parts.verification);
    if (shard.owns(1)) {  // the second section asked for
      parts.sections["table_4_1"] = {{"rows", json::array({{{"violations", 2}, {"claims_conservative", true}}})}};
      ClaimCheck t;
      t.id = "table-claim";
      parts.section_claims["table_4_1"] = {t};
    }
    parts.identity = {{"flags", "the same"}};
    return parts;
  }
  // The four shard files' JSON, as `cullcheck report --shard k/4` writes them.
  std::vector<json> shard_files() const {
    std::vector<json> files;
    for (std::size_t k = 0; k < 4; ++k) {
      const ReportParts parts = run({k, 4});
      files.push_back(json::parse(shard_document(assemble_report(parts).document, parts, {k, 4}).dump()));
    }
    return files;
  }
  static std::string merge_error(const std::vector<json>& files) {
    try {
      merge_shard_documents(files, {"a.json", "b.json", "c.json", "d.json"});
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(ShardedRun, FourMergedShardsAreTheReportOfOneRun) {
  const AssembledReport one = assemble_report(run({}));
  std::vector<json> files = shard_files();
  std::swap(files[0], files[2]);  // any order
  const AssembledReport merged = assemble_report(merge_shard_documents(files, {"c", "b", "a", "d"}));
  EXPECT_EQ(without_timings(merged.document), without_timings(one.document))
      << "one:\n" << without_timings(one.document).dump(1).substr(0, 3000) << "\nmerged:\n" << without_timings(merged.document).dump(1).substr(0, 3000);
  // What the run found, pinned: ten checked frames, the straw man's violations, the claims.
  EXPECT_EQ(one.document["oracle"]["frames_checked"], 10);
  const json& straw = one.document["runs"][3];
  ASSERT_EQ(straw["method"], "drops_half");
  EXPECT_GT(straw["violations"].get<int>(), 10) << straw.dump();
  ASSERT_EQ(straw["violation_replays"].size(), 5u);
  EXPECT_EQ(straw["violation_replays"][0]["frame"], 0) << "the first violations are kept, whichever shard found them";
  EXPECT_EQ(one.document["gate"]["passed"], false);
  ASSERT_EQ(merged.claims.size(), 2u);  // the search's, then the section's
  EXPECT_EQ(merged.claims[0].frames_checked, 28u);
  EXPECT_EQ(merged.claims[0].counterexample_replay, "replay scene 3") << "the lowest refuting scene's, found by shard 3";
  EXPECT_EQ(merged.claims[1].id, "table-claim");
  EXPECT_EQ(merged.verdict.section_violations, 2u);
  EXPECT_EQ(merged.document["knob_sweep"][0]["misses"], one.document["knob_sweep"][0]["misses"]);
}

TEST_F(ShardedRun, EachShardChecksItsShareOfTheCheckedFrames) {
  const ReportParts one = run({1, 4});
  // Checked frames 0, 3, ..., 27 are the 0th to 9th; shard 1 of 4 has the 1st, 5th and 9th.
  EXPECT_EQ(one.verification.checked_frames, (std::vector<std::size_t>{3, 15, 27}));
  EXPECT_EQ(one.verification.runs[0].cull_ms.size(), 30u) << "every shard runs the methods along the whole path";
  EXPECT_EQ(one.searched_claims[0].frames_checked, 2u + 6u) << "scenes 1 and 5";
  EXPECT_EQ(one.searched_claims[0].counterexample_scene, 5);
  EXPECT_TRUE(one.sections.contains("table_4_1"));
  EXPECT_FALSE(run({2, 4}).sections.contains("table_4_1"));
}

TEST_F(ShardedRun, AVerificationReadsBackAsItWasWritten) {
  const PathVerification v = run({}).verification;
  const json once = verification_to_json(v);
  EXPECT_EQ(verification_to_json(verification_from_json(json::parse(once.dump()), "test")), once);
}

TEST_F(ShardedRun, MergeRefusesFilesThatAreNotTheShardsOfOneRun) {
  const std::vector<json> files = shard_files();
  EXPECT_NE(merge_error({files[0], files[1], files[2]}).find("every shard of the run is needed"), std::string::npos);
  EXPECT_NE(merge_error({files[0], files[1], files[1], files[3]}).find("shard 1 is given twice"), std::string::npos);
  std::vector<json> other = files;
  other[2]["shard"]["identity"]["flags"] = "others";
  EXPECT_NE(merge_error(other).find("in 'flags': the shards were run with other flags"), std::string::npos);
  other = files;
  other[3]["scene"]["seed"] = 8;
  EXPECT_NE(merge_error(other).find("not a shard of the same run"), std::string::npos);
  other = files;
  other[1]["shard"]["verification"]["runs"][1]["pvs_size"][4] = 1e6;
  EXPECT_NE(merge_error(other).find("not deterministic"), std::string::npos);
  other = files;
  other[1]["shard"]["verification"]["checked_frames"][0] = 0;
  EXPECT_NE(merge_error(other).find("frame 0 is not in shard 1/4's share"), std::string::npos);
  other = files;
  other[0].erase("shard");
  EXPECT_NE(merge_error(other).find("not a shard file"), std::string::npos);
}

// What "timings aside" drops, pinned: timed keys and how the run was spread (threads), at any depth.
TEST(WithoutTimings, DropsTimedKeysAndThreadsOnly) {
  const nlohmann::json report = nlohmann::json::parse(R"({
    "machine": {"hardware_threads": 8}, "pvs": 3, "cull_ms": 1.5, "ms_per_cell": 2,
    "graph": {"threads": 2, "build_seconds": 4, "nodes": 10, "rays_per_second": 9, "speedup": 1.6},
    "runs": [{"method": "frustum", "cull_ms_median": 0.3, "violations": 0}]})");
  EXPECT_EQ(without_timings(report), nlohmann::json::parse(R"({
    "pvs": 3, "graph": {"nodes": 10}, "runs": [{"method": "frustum", "violations": 0}]})"));
}

TEST(ShardFlag, ReadsKOfN) {
  EXPECT_EQ(parse_shard("2/4"), (Shard{2, 4}));
  EXPECT_EQ(parse_shard("0/1"), (Shard{0, 1}));
  for (const char* bad : {"4/4", "1/0", "-1/4", "a/b", "3", "1/4/2", "", "1 /4"})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
  EXPECT_EQ((Shard{1, 4}).share(10), 3u);
  EXPECT_EQ((Shard{3, 4}).share(10), 2u);
}

}  // namespace
}  // namespace cullcheck
