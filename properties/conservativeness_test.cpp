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

#include <array>
#include <cstdio>
#include <vector>

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
  oracle::OracleAnswer seen = truth.visible_set(c.camera, property_oracle());
  const CullResult culled = method->cull(c.camera);
  const std::vector<ObjectId> missed = confirmed_misses(truth, seen, c.camera, culled.pvs);
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

// Runs the conservativeness property of `method` over `cases` (hard ones by default,
// rapidcheck_hard_cases.hpp) and prints how many reached each hard case.
HardCaseCoverage coverage_run(const std::string& method, int cases, const std::string& what = "hard cases",
                              rc::Gen<generators::SceneCase> (*gen)() = [] { return rcgen::hard_scene_case(); }) {
  HardCaseCoverage coverage;
  const PropertyOutcome run = run_property("conservativeness of " + method + " on " + what, cases, true, [&] {
    check_conservative(method, *gen(), *method_options(), &coverage);
  });
  EXPECT_TRUE(run.held) << method << " hides a building the oracle sees (case and replay line above)";
  std::printf("%s\n", coverage.summary(method + " (" + what + ")").c_str());
  return coverage;
}

// Measured at the CI seed (300 cases of OH(OS)): culls beyond the frustum 49.3%, gap < 1 m 11.0%,
// eye at a wall 39.3%, steep 25.7% (ΔH 60/13/43/23%, frustum culling -/11/41/30%, 100 cases
// each). The lowest over seeds 1-5 and all three runs: 43%, 4%, 36%, 14%. The floors sit below
// those: the gap is the rarest (only the oracle's first witness ray of each building is measured,
// and a building seen through a gap is often seen some other way first).
constexpr std::array<double, 4> kFloors{0.28, 0.03, 0.22, 0.10};

// The hard cases whose share is below its floor (frustum culling has no horizon: its first
// feature is not asked of it).
std::vector<HardCase> below_floors(const HardCaseCoverage& coverage, bool horizon = true) {
  std::vector<HardCase> out;
  for (int k = horizon ? 0 : 1; k < 4; ++k)
    if (coverage.share(HardCase(k)) < kFloors[k]) out.push_back(HardCase(k));
  return out;
}

// A reproduce= run checks one case: no shares then.
void expect_floors(const HardCaseCoverage& coverage, bool horizon = true) {
  if (reproducing()) return;
  for (HardCase k : below_floors(coverage, horizon))
    ADD_FAILURE() << kHardCaseNames[int(k)] << " below its floor of " << 100 * kFloors[int(k)] << "%: " << coverage.summary("these");
}

TEST(Conservativeness, ObjectSpaceHorizonReachesTheHardCases) { expect_floors(coverage_run("oh_os_conservative", 300)); }

TEST(Conservativeness, GuardedDeltaHorizonReachesTheHardCases) { expect_floors(coverage_run("delta_h_guarded", 100)); }

TEST(Conservativeness, FrustumReachesTheHardCases) { expect_floors(coverage_run("frustum", 100), false); }

// The floors have teeth: the ordinary generated cases (rcgen::scene_case, which the properties
// above this section use) fall below them, the reason the hard cases exist. Measured at the CI
// seed: see the printed line.
TEST(Conservativeness, OrdinaryCasesFallBelowTheFloors) {
  if (reproducing()) GTEST_SKIP() << "RC_PARAMS reproduces one property";
  const HardCaseCoverage c = coverage_run("oh_os_conservative", 100, "ordinary cases", [] { return rcgen::scene_case(); });
  const std::vector<HardCase> below = below_floors(c);
  EXPECT_FALSE(below.empty()) << "the ordinary cases now reach every hard case: " << c.summary("these");
  for (HardCase k : below) std::printf("  below the floor: %s\n", kHardCaseNames[int(k)]);
}

}  // namespace
}  // namespace cullcheck
