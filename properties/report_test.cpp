// report.json: the fields the schema promises are present, methods claimed conservative have
// no violations on a generated city and path, the claims ledger refutes the published shadow
// rule with a replay and confirms the corrected one, and two runs give the same document once
// the timing fields are set aside (design: "Determinism").
#include <gtest/gtest.h>

#include "generators/camera_paths.hpp"
#include "reports/report.hpp"

namespace cullcheck {
namespace {

struct SmallRun {
  SceneSource source;
  Scene scene;
  CameraPath path;
  PathVerification verification;
  nlohmann::json report;
};

SmallRun small_run(const std::vector<ClaimCheck>& claims) {
  SmallRun r;
  r.source.generator = "plaza";
  r.source.seed = 3;
  r.source.parameters_json = R"({"blocks_x":4,"blocks_y":4,"plaza_blocks_x":2,"plaza_blocks_y":2,"kiosk_count":6})";
  r.scene = r.source.load();
  r.path = generators::make_camera_path("street_walk", r.scene, 9, {{"frames", 40}});
  VerificationOptions options;
  options.oracle.sampling.threads = 1;
  r.verification = verify_path(r.scene, r.source, r.path, method_names(), {}, options);
  ReportInputs in;
  in.scene = &r.scene;
  in.source = r.source;
  in.path = &r.path;
  in.verification = &r.verification;
  in.claims = claims;
  r.report = build_report(in);
  return r;
}

TEST(Report, CarriesTheSchemaFieldsAndPassesTheGate) {
  const SmallRun run = small_run({});
  const nlohmann::json& j = run.report;
  EXPECT_EQ(j["schema_version"], kReportSchemaVersion);
  EXPECT_EQ(j["scene"]["generator"], "plaza");
  EXPECT_EQ(j["scene"]["seed"], 3);
  EXPECT_EQ(j["scene"]["building_count"], run.scene.buildings.size());
  ASSERT_EQ(j["runs"].size(), method_names().size());
  for (const auto& m : j["runs"]) {
    for (const char* key : {"method", "frames", "cull_ms_median", "cull_ms_p95", "pvs_mean", "witnessed_mean",
                            "overestimation", "violations", "violation_replays"})
      EXPECT_TRUE(m.contains(key)) << m["method"] << " lacks " << key;
    EXPECT_EQ(m["frames"], 40);
    EXPECT_GT(m["witnessed_mean"].get<double>(), 0.0);
    // Range detection as published culls the quadtree's root whenever the eye is inside the
    // city's box (no corner of it in view): its PVS is empty along the walk, and reported so.
    if (m["method"] == "rdt") {
      EXPECT_EQ(m["pvs_mean"].get<double>(), 0.0);
      EXPECT_GT(m["violations"].get<int>(), 0);
      continue;
    }
    EXPECT_GE(m["overestimation"].get<double>(), 1.0) << m["method"];
    if (m["claims_conservative"].get<bool>()) {
      EXPECT_EQ(m["violations"], 0) << m["method"] << ": " << m["violation_replays"].dump();
    }
  }
  EXPECT_TRUE(j["gate"]["passed"].get<bool>());
  EXPECT_GT(j["oracle"]["rays_cast"].get<double>(), 0.0);
  EXPECT_TRUE(j["oracle"].contains("bare_embree_rays_per_second"));
}

TEST(Report, IsDeterministicApartFromTimings) {
  const SmallRun a = small_run({}), b = small_run({});
  EXPECT_EQ(without_timings(a.report).dump(), without_timings(b.report).dump());
}

TEST(Report, ClaimsLedgerRefutesThePublishedShadowRuleAndKeepsTheCorrection) {
  const std::vector<ClaimCheck> claims = check_shadow_elevation_rule({});
  ASSERT_EQ(claims.size(), 2u);
  EXPECT_FALSE(claims[0].holds) << "the default search no longer finds the published rule's counterexample";
  EXPECT_NE(claims[0].counterexample_replay.find("cullcheck verify --generator"), std::string::npos);
  EXPECT_NE(claims[0].counterexample_replay.find("--method oh_os_thesis"), std::string::npos);
  EXPECT_TRUE(claims[1].holds) << claims[1].counterexample_replay;
  EXPECT_EQ(claims[1].violations, 0u);
  EXPECT_EQ(claims[0].frames_checked, claims[1].frames_checked);
  const nlohmann::json j = small_run(claims).report;
  EXPECT_EQ(j["claims"][0]["holds"], false);
  EXPECT_TRUE(j["claims"][0]["counterexample"].contains("replay"));
}

}  // namespace
}  // namespace cullcheck
