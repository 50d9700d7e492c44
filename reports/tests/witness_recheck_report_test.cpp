// Violations pass through the double-precision witness re-check (oracle/witness_recheck.hpp)
// before they count, and report.json says how many witnesses were checked and dropped, per
// method and for the oracle. A method that culls everything misses every witnessed object.
#include <gtest/gtest.h>

#include "core/scene_io.hpp"
#include "reports/report.hpp"
#include "reports/verification.hpp"

namespace cullcheck {
namespace {

class CullsEverything : public CullingMethod {
 public:
  explicit CullsEverything(std::string name) : name_(std::move(name)) {}
  std::string name() const override { return name_; }
  bool claims_conservative() const override { return true; }
  CullResult cull(const Camera&) override { return {}; }

 private:
  std::string name_;
};

struct RecheckRun {
  Scene scene;
  CameraPath path;
  PathVerification verification;
};

// Two buildings in front of a level street-level camera, two frames, two methods that cull both.
RecheckRun run(bool allow_exact_2d) {
  RecheckRun r;
  r.scene.buildings = {box_building(1, 20, -12, 24, -2, 30), box_building(2, 20, 2, 24, 12, 30)};
  Camera c;
  c.position = {0, 0, 1.7};
  c.hfov = 100 * kPi / 180, c.vfov = 60 * kPi / 180;
  r.path.kind = "hand";
  r.path.frames = {c, c};
  r.path.frames[1].position.x = 1.0;
  std::vector<MethodUnderTest> methods;
  for (const char* name : {"culls_everything_a", "culls_everything_b"}) {
    MethodUnderTest m;
    m.method = std::make_unique<CullsEverything>(name);
    m.replay = [](std::size_t, const Camera&) { return std::string("replay"); };
    methods.push_back(std::move(m));
  }
  VerificationOptions options;
  options.oracle.allow_exact_2d = allow_exact_2d;
  options.oracle.sampling.threads = 1;
  r.verification = verify_path(r.scene, SceneSource{}, r.path, methods, {}, options);
  return r;
}

TEST(WitnessRecheckReport, EveryViolationsWitnessIsCheckedOnceAndCountedPerMethod) {
  const RecheckRun r = run(/*allow_exact_2d=*/false);
  ASSERT_EQ(r.verification.runs.size(), 2u);
  for (const MethodRun& m : r.verification.runs) {
    EXPECT_EQ(m.violation_count, 4u) << m.method;  // two buildings, two frames
    EXPECT_EQ(m.witness_recheck, (oracle::WitnessRecheckCounts{4, 0})) << m.method;
  }
  // The oracle re-casts each witness once per frame, however many methods culled it.
  EXPECT_EQ(r.verification.oracle.witness_recheck, (oracle::WitnessRecheckCounts{4, 0}));
  EXPECT_GT(r.verification.oracle.grazing_rays, 0u);

  ReportInputs in;
  in.scene = &r.scene;
  in.path = &r.path;
  in.verification = &r.verification;
  const nlohmann::json report = build_report(in);
  for (const auto& m : report["runs"]) {
    EXPECT_EQ(m["witness_recheck"]["checked"], 4) << m["method"];
    EXPECT_EQ(m["witness_recheck"]["dropped"], 0) << m["method"];
  }
  EXPECT_EQ(report["oracle"]["witness_recheck"]["checked"], 4);
  EXPECT_EQ(report["oracle"]["witness_recheck"]["dropped"], 0);
  EXPECT_EQ(report["oracle"]["grazing_rays"], r.verification.oracle.grazing_rays);
}

TEST(WitnessRecheckReport, ExactPlanViewViolationsHaveNoRayToRecheck) {
  const RecheckRun r = run(/*allow_exact_2d=*/true);
  ASSERT_EQ(r.verification.oracle.frames_exact_2d, 2u);
  for (const MethodRun& m : r.verification.runs) {
    EXPECT_EQ(m.violation_count, 4u) << m.method;
    EXPECT_EQ(m.witness_recheck, (oracle::WitnessRecheckCounts{0, 0})) << m.method;
  }
}

}  // namespace
}  // namespace cullcheck
