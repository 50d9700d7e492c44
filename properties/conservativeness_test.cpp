// Conservativeness (design: "Properties"): for every method that claims it, the buildings the
// oracle sees are a subset of the PVS — over generated scenes (all generators, small, and the
// large occluded Manhattan grids), cameras at street level and above the rooftops, pitch and
// roll, narrow, ordinary and 360-degree fields of view, occluders below and above the eye, and
// engine options drawn over their whole range (method_options_gen.hpp). A failure logs the
// `cullcheck verify` command that replays it; RapidCheck shrinks it to a small city first.
//
// The hard-case properties also count how many of their cases reach what breaks culling
// (case_coverage.hpp: culling beyond the frustum, sub-metre gaps, eyes at walls, steep cameras)
// and assert each share is above a floor, so that a generator change that stops reaching them
// fails here instead of leaving a property that passes because it never looks.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdio>

#include "engine/method.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "generators/rapidcheck_hard_cases.hpp"
#include "oracle/oracle.hpp"
#include "properties/case_coverage.hpp"
#include "properties/method_options_gen.hpp"
#include "properties/property_oracle.hpp"
#include "properties/property_run.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;

// Checks one case; with `coverage`, also classifies it (the horizon's PVS against the frustum's).
void check_conservative(const std::string& method_name, const generators::SceneCase& c, const MethodOptions& options,
                        HardCaseCoverage* coverage = nullptr) {
  const Scene scene = generators::scene_of(c.spec);
  RC_PRE(!scene.buildings.empty());
  auto method = make_method(method_name, scene, options);
  RC_ASSERT(method->claims_conservative());
  const oracle::Oracle truth(scene);
  const oracle::OracleAnswer seen = truth.visible_set(c.camera, property_oracle());
  const CullResult culled = method->cull(c.camera);
  std::vector<ObjectId> missed;
  std::set_difference(seen.visible.begin(), seen.visible.end(), culled.pvs.begin(), culled.pvs.end(),
                      std::back_inserter(missed));
  if (!missed.empty()) {
    RC_LOG() << "replay: cullcheck verify " << c << " --method " << method_name << " " << option_flags(options)
             << " --spacing 3 --frustum-resolution 128\n";
    RC_LOG() << "building " << missed.front() << " seen by the oracle (" << seen.model << ")";
    if (seen.sampling) RC_LOG() << ": " << oracle::describe(seen.sampling->witnesses.at(missed.front()));
    RC_LOG() << "\n";
  }
  RC_ASSERT(missed.empty());
  if (coverage) {
    const bool horizon = method_name != "frustum";
    const std::vector<ObjectId> frustum = horizon ? make_method("frustum", scene, options)->cull(c.camera).pvs : culled.pvs;
    coverage->add(hard_case_features(scene, c.camera, seen, horizon ? &culled.pvs : nullptr, &frustum));
  }
}

RC_GTEST_PROP(Conservativeness, FrustumOnGeneratedScenes, ()) {
  check_conservative("frustum", *rcgen::scene_case(), *method_options());
}

RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonOnGeneratedScenes, ()) {
  check_conservative("oh_os_conservative", *rcgen::scene_case(), *method_options());
}

RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonWithOccludersBelowTheEye, ()) {
  check_conservative("oh_os_conservative", *rcgen::scene_case(rcgen::low_occluder_spec(1.7)), *method_options());
}

RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonWithOccludersAboveTheEye, ()) {
  check_conservative("oh_os_conservative", *rcgen::scene_case(rcgen::tall_occluder_spec(1.7)), *method_options());
}

// Near planes from 1 cm to 5 m: clipped geometry hides nothing, so what reaches in front of the
// near plane must not be used as an occluder.
RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonWithDeepNearPlanes, ()) {
  generators::SceneCase c = *rcgen::scene_case();
  c.camera.near = *rc::gen::element(0.01, 0.5, 2.0, 5.0);
  c.camera.far = std::max(c.camera.far, c.camera.near * 2);
  check_conservative("oh_os_conservative", c, *method_options());
}

// --- Hard cases, counted ------------------------------------------------------------------------

// Runs the conservativeness property of `method` over the hard cases (rapidcheck_hard_cases.hpp)
// and prints how many reached each hard case.
HardCaseCoverage hard_case_run(const std::string& method, int cases) {
  HardCaseCoverage coverage;
  const PropertyOutcome run = run_property("conservativeness of " + method + " on hard cases", cases, true, [&] {
    check_conservative(method, *rcgen::hard_scene_case(), *method_options(), &coverage);
  });
  EXPECT_TRUE(run.held) << method << " hides a building the oracle sees (case and replay line above)";
  std::printf("%s\n", coverage.summary(method).c_str());
  return coverage;
}

// Floors: the shares measured at the CI seed (printed by the tests, README) less about a third,
// so that they fail when a generator change stops reaching a case, not on the seed's noise.
// A reproduce= run checks one case: no shares then.
void expect_floor(const HardCaseCoverage& coverage, HardCase k, double floor) {
  if (reproducing()) return;
  EXPECT_GE(coverage.share(k), floor) << kHardCaseNames[int(k)] << ": " << coverage.summary("these");
}

// Measured at the CI seed (300 cases of OH(OS)): culls beyond the frustum 49.3%, gap < 1 m 11.0%,
// eye at a wall 39.3%, steep 25.7% (ΔH 60/13/43/23%, frustum culling -/11/41/30%, 100 cases
// each). The lowest over seeds 1-5 and all three runs: 43%, 4%, 36%, 14%. The floors sit below
// those: the gap is the rarest (only the oracle's first witness ray of each building is measured,
// and a building seen through a gap is often seen some other way first).
constexpr double kFloorBeyondFrustum = 0.28, kFloorNarrowGap = 0.03, kFloorNearWall = 0.22, kFloorSteep = 0.10;

TEST(Conservativeness, ObjectSpaceHorizonReachesTheHardCases) {
  const HardCaseCoverage c = hard_case_run("oh_os_conservative", 300);
  expect_floor(c, HardCase::horizon_beyond_frustum, kFloorBeyondFrustum);
  expect_floor(c, HardCase::narrow_gap, kFloorNarrowGap);
  expect_floor(c, HardCase::eye_near_wall, kFloorNearWall);
  expect_floor(c, HardCase::steep, kFloorSteep);
}

TEST(Conservativeness, GuardedDeltaHorizonReachesTheHardCases) {
  const HardCaseCoverage c = hard_case_run("delta_h_guarded", 100);
  expect_floor(c, HardCase::horizon_beyond_frustum, kFloorBeyondFrustum);
  expect_floor(c, HardCase::narrow_gap, kFloorNarrowGap);
  expect_floor(c, HardCase::eye_near_wall, kFloorNearWall);
  expect_floor(c, HardCase::steep, kFloorSteep);
}

TEST(Conservativeness, FrustumReachesTheHardCases) {
  const HardCaseCoverage c = hard_case_run("frustum", 100);
  expect_floor(c, HardCase::narrow_gap, kFloorNarrowGap);
  expect_floor(c, HardCase::eye_near_wall, kFloorNearWall);
  expect_floor(c, HardCase::steep, kFloorSteep);
}

}  // namespace
}  // namespace cullcheck
