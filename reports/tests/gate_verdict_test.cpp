// The gate's verdict (reports/gate_verdict.hpp) from verifications built by hand: which checks a
// run gets, their outcomes, messages and replays, the totals and the exit code.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reports/gate_verdict.hpp"
#include "subjects/protocol.hpp"
#include "subjects/subject_error.hpp"

namespace cullcheck {
namespace {

using Outcome = GateCheck::Outcome;

Violation violation(const std::string& replay) {
  Violation v;
  v.replay = replay;
  return v;
}

// A conservative run with two checked frames and nothing wrong; cull_ms 1000 + 500 = 1.5 s.
MethodRun conservative_run(const std::string& method) {
  MethodRun r;
  r.method = method;
  r.claims_conservative = true;
  r.cull_ms = {1000, 500};
  r.pvs_size = {6, 6};
  r.checked_pvs_size = {6, 6};
  r.witnessed_size = {4, 5};
  return r;
}

// An approximate run with a budget of 40 misdrawn pixels and three checked frames.
MethodRun approximate_run(const std::string& method) {
  MethodRun r;
  r.method = method;
  r.pixel_error_budget = 40;
  r.cull_ms = {250};
  r.checked_pvs_size = {3, 3, 3};
  r.witnessed_size = {3, 3, 3};
  r.misdrawn_pixels = {95, 60, 3};
  return r;
}

const GateCheck& only_check(const GateVerdict& v) {
  EXPECT_EQ(v.checks.size(), 1u);
  return v.checks.at(0);
}

TEST(GateVerdict, CleanConservativeRunPasses) {
  PathVerification v;
  v.runs.push_back(conservative_run("oh_os_conservative"));
  const GateVerdict g = gate_verdict(v, "--seed 1");
  EXPECT_EQ(g.scene, "--seed 1");
  const GateCheck& c = only_check(g);
  EXPECT_EQ(c.method, "oh_os_conservative");
  EXPECT_EQ(c.check, "conservative");
  EXPECT_EQ(c.outcome, Outcome::passed);
  EXPECT_EQ(c.message, "");
  EXPECT_DOUBLE_EQ(c.seconds, 1.5);
  EXPECT_TRUE(g.passed());
  EXPECT_EQ(g.exit_code(), 0);
}

TEST(GateVerdict, ConservativeRunWithViolationsFailsWithItsReplays) {
  PathVerification v;
  MethodRun r = conservative_run("oh_os_conservative");
  r.violation_count = 3;  // three objects over two frames; the first two kept in full
  r.frames_with_violations = 2;
  r.violations = {violation("cullcheck verify --a"), violation("cullcheck verify --b")};
  v.runs.push_back(r);
  const GateVerdict g = gate_verdict(v, "--seed 1");
  const GateCheck& c = only_check(g);
  EXPECT_EQ(c.check, "conservative");
  EXPECT_EQ(c.outcome, Outcome::failed);
  EXPECT_EQ(c.message, "culled 3 objects the oracle saw, over 2 frames");
  EXPECT_EQ(c.replays, (std::vector<std::string>{"cullcheck verify --a", "cullcheck verify --b"}));
  EXPECT_EQ(g.conservative_violations, 3u);
  EXPECT_FALSE(g.passed());
  EXPECT_EQ(g.exit_code(), 1);
  // One of each: the singular.
  v.runs[0].violation_count = 1, v.runs[0].frames_with_violations = 1;
  EXPECT_EQ(only_check(gate_verdict(v, "")).message, "culled 1 object the oracle saw, over 1 frame");
}

TEST(GateVerdict, MisdrawnPixelsAloneFailAConservativeRun) {
  PathVerification v;
  MethodRun r = conservative_run("frustum");
  r.misdrawn_pixels = {17, 0};
  r.misdrawn_total = 17;
  v.runs.push_back(r);
  GateVerdict g = gate_verdict(v, "");
  EXPECT_EQ(only_check(g).outcome, Outcome::failed);
  EXPECT_EQ(only_check(g).message, "culled 0 objects the oracle saw, over 0 frames; 17 misdrawn pixels");
  EXPECT_EQ(g.conservative_violations, 0u);
  EXPECT_EQ(g.conservative_misdrawn_pixels, 17u);
  EXPECT_EQ(g.exit_code(), 1);
  v.runs[0].misdrawn_total = 1;
  EXPECT_EQ(only_check(gate_verdict(v, "")).message, "culled 0 objects the oracle saw, over 0 frames; 1 misdrawn pixel");
}

TEST(GateVerdict, ApproximateRunOverBudgetFailsPixelBudget) {
  PathVerification v;
  MethodRun r = approximate_run("wang_image_space");
  r.frames_over_budget = 2;  // 95 and 60 > 40
  r.most_misdrawn = 95;
  r.over_budget = {violation("cullcheck verify --f0"), violation("cullcheck verify --f1")};
  v.runs.push_back(r);
  const GateVerdict g = gate_verdict(v, "");
  const GateCheck& c = only_check(g);  // no conservative check: it does not claim it
  EXPECT_EQ(c.check, "pixel_budget");
  EXPECT_EQ(c.outcome, Outcome::failed);
  EXPECT_EQ(c.message, "2 frames above the budget of 40 misdrawn pixels (worst 95)");
  EXPECT_EQ(c.replays, (std::vector<std::string>{"cullcheck verify --f0", "cullcheck verify --f1"}));
  EXPECT_DOUBLE_EQ(c.seconds, 0.25);
  EXPECT_EQ(g.frames_over_budget, 2u);
  EXPECT_EQ(g.exit_code(), 1);
}

TEST(GateVerdict, ApproximateRunWithinBudgetPassesAndUncheckedIsSkipped) {
  PathVerification v;
  v.runs.push_back(approximate_run("wang_image_space"));
  EXPECT_EQ(only_check(gate_verdict(v, "")).outcome, Outcome::passed);
  v.runs[0].misdrawn_pixels.clear();
  const GateVerdict g = gate_verdict(v, "");
  EXPECT_EQ(only_check(g).outcome, Outcome::skipped);
  EXPECT_EQ(only_check(g).message, "the pixel oracle checked no frame");
  EXPECT_TRUE(g.passed());
  EXPECT_EQ(g.exit_code(), 0);
}

TEST(GateVerdict, MaxOverestimation) {
  PathVerification v;
  MethodRun r = conservative_run("frustum");
  r.checked_pvs_size = {10, 20};  // mean 15
  r.witnessed_size = {5, 5};      // mean 5: ratio 3
  v.runs.push_back(r);
  GateThresholds limit;
  limit.max_overestimation = 2.0;
  GateVerdict g = gate_verdict(v, "", limit);
  ASSERT_EQ(g.checks.size(), 2u);  // conservative, then overestimation
  EXPECT_EQ(g.checks[0].check, "conservative");
  EXPECT_EQ(g.checks[0].outcome, Outcome::passed);
  EXPECT_EQ(g.checks[1].check, "overestimation");
  EXPECT_EQ(g.checks[1].outcome, Outcome::failed);
  EXPECT_EQ(g.checks[1].message, "PVS / witnessed = 3.000 over the checked frames, above the limit 2.000");
  EXPECT_EQ(g.overestimation_failures, 1u);
  EXPECT_EQ(g.exit_code(), 1);
  // A ratio equal to the limit passes: 15 / 5 = 3 <= 3.
  limit.max_overestimation = 3.0;
  g = gate_verdict(v, "", limit);
  EXPECT_EQ(g.checks[1].outcome, Outcome::passed);
  EXPECT_EQ(g.overestimation_failures, 0u);
  // Without the threshold there is no such check.
  EXPECT_EQ(gate_verdict(v, "").checks.size(), 1u);
}

TEST(GateVerdict, AbortedOutsideRunIsAnAnswersErrorAndExitCode2) {
  PathVerification v;
  MethodRun subject = conservative_run("subject:culler");
  subject.outside = true;
  subject.violation_count = 2;  // it failed the conservative check too, before it crashed
  subject.frames_with_violations = 1;
  v.runs.push_back(subject);
  MethodRun other = conservative_run("oh_os_conservative");
  other.violation_count = 1;
  other.frames_with_violations = 1;
  v.runs.push_back(other);
  v.aborted = Abort{"subject:culler", 3, "crashed", "subject 'culler' at frame 3: crashed: closed its output"};
  const GateVerdict g = gate_verdict(v, "");
  ASSERT_EQ(g.checks.size(), 3u);  // subject: conservative, answers; other: conservative
  EXPECT_EQ(g.checks[0].check, "conservative");
  EXPECT_EQ(g.checks[0].outcome, Outcome::failed);
  EXPECT_EQ(g.checks[1].method, "subject:culler");
  EXPECT_EQ(g.checks[1].check, "answers");
  EXPECT_EQ(g.checks[1].outcome, Outcome::error);
  EXPECT_EQ(g.checks[1].message, "subject 'culler' at frame 3: crashed: closed its output");
  EXPECT_EQ(g.checks[2].method, "oh_os_conservative");
  EXPECT_EQ(g.checks[2].outcome, Outcome::failed);
  EXPECT_TRUE(g.subject_failed);
  EXPECT_EQ(g.conservative_violations, 3u);
  EXPECT_FALSE(g.passed());
  EXPECT_EQ(g.exit_code(), 2);  // bad input beats a failed gate
}

TEST(GateVerdict, AbortDuringTheHandshakeAddsAnAnswersError) {
  PathVerification v;
  v.runs.push_back(conservative_run("oh_os_conservative"));
  v.aborted = Abort{"subject:culler", -1, "timed out", "subject 'culler' during the handshake: timed out: ..."};
  const GateVerdict g = gate_verdict(v, "");
  ASSERT_EQ(g.checks.size(), 2u);
  EXPECT_EQ(g.checks[1].method, "subject:culler");
  EXPECT_EQ(g.checks[1].check, "answers");
  EXPECT_EQ(g.checks[1].outcome, Outcome::error);
  EXPECT_EQ(g.checks[1].seconds, 0.0);
  EXPECT_TRUE(g.subject_failed);
  EXPECT_EQ(g.exit_code(), 2);
}

TEST(GateVerdict, OutsideRunThatAnsweredPassesAndSaysWhatItSkipped) {
  PathVerification v;
  MethodRun r = conservative_run("subject:culler");
  r.outside = true;
  r.frames_skipped = 2;
  r.skip_reason = "orthographic camera: not listed";
  v.runs.push_back(r);
  const GateVerdict g = gate_verdict(v, "");
  ASSERT_EQ(g.checks.size(), 2u);
  EXPECT_EQ(g.checks[1].check, "answers");
  EXPECT_EQ(g.checks[1].outcome, Outcome::passed);
  EXPECT_EQ(g.checks[1].message, "2 frames skipped: orthographic camera: not listed");
  EXPECT_FALSE(g.subject_failed);
  EXPECT_EQ(g.exit_code(), 0);
}

TEST(GateVerdict, SectionViolationsFail) {
  PathVerification v;
  v.runs.push_back(conservative_run("oh_os_conservative"));
  GateVerdict g = gate_verdict(v, "", {}, 4);
  ASSERT_EQ(g.checks.size(), 2u);
  EXPECT_EQ(g.checks[1].method, "sections");
  EXPECT_EQ(g.checks[1].check, "conservative");
  EXPECT_EQ(g.checks[1].outcome, Outcome::failed);
  EXPECT_EQ(g.checks[1].message,
            "4 conservative violations in table_4_1, view_cells or vbaoi (see those sections' replays)");
  EXPECT_EQ(g.section_violations, 4u);
  EXPECT_EQ(g.conservative_violations, 0u);  // counted apart
  EXPECT_EQ(g.exit_code(), 1);
  g = gate_verdict(v, "", {}, 1);
  EXPECT_EQ(g.checks[1].message, "1 conservative violation in table_4_1, view_cells or vbaoi (see those sections' replays)");
  EXPECT_EQ(gate_verdict(v, "", {}, 0).checks.size(), 1u);
}

TEST(GateVerdict, RegionRunsGetTheConservativeCheck) {
  PathVerification v;
  RegionRun r;
  r.method = "shrinking";
  r.claims_conservative = true;
  r.compute_ms = {250, 250};
  r.violation_count = 2;
  r.violations = {violation("cullcheck region --x")};
  v.regions.push_back(r);
  RegionRun unclaimed = r;
  unclaimed.method = "former_shrinking";
  unclaimed.claims_conservative = false;  // no claim, no check
  v.regions.push_back(unclaimed);
  const GateVerdict g = gate_verdict(v, "");
  const GateCheck& c = only_check(g);
  EXPECT_EQ(c.method, "region:shrinking");
  EXPECT_EQ(c.check, "conservative");
  EXPECT_EQ(c.outcome, Outcome::failed);
  EXPECT_EQ(c.message, "culled 2 objects the oracle saw from an eye of its disc");
  EXPECT_EQ(c.replays, (std::vector<std::string>{"cullcheck region --x"}));
  EXPECT_DOUBLE_EQ(c.seconds, 0.5);
  EXPECT_EQ(g.conservative_violations, 2u);
  EXPECT_EQ(g.exit_code(), 1);
}

TEST(GateVerdict, RunWithNoCheckedFrameIsSkipped) {
  PathVerification v;
  MethodRun r = conservative_run("oh_os_conservative");
  r.checked_pvs_size.clear();
  r.witnessed_size.clear();
  v.runs.push_back(r);
  const GateVerdict g = gate_verdict(v, "");
  EXPECT_EQ(only_check(g).outcome, Outcome::skipped);
  EXPECT_EQ(only_check(g).message, "no frame was checked by the oracle");
  EXPECT_TRUE(g.passed());  // skipped is not a failure
  EXPECT_EQ(g.exit_code(), 0);
}

// A path on which the oracle saw nothing proves nothing: with require_witnessed it is bad input
// (exit 2) even though the conservative check passes; without it, and when something was seen,
// the verdict is unchanged.
TEST(GateVerdict, PathThatSeesNothingIsRefusedWhenRequired) {
  PathVerification v;
  MethodRun r = conservative_run("subject:cull-all");
  r.pvs_size = {0, 0};
  r.checked_pvs_size = {0, 0};
  r.witnessed_size = {0, 0};
  v.runs.push_back(r);
  GateThresholds require;
  require.require_witnessed = true;
  const GateVerdict g = gate_verdict(v, "", require);
  ASSERT_EQ(g.checks.size(), 2u);
  EXPECT_EQ(g.checks[0].outcome, Outcome::passed);  // nothing seen, nothing missed
  EXPECT_EQ(g.checks[1].method, "path");
  EXPECT_EQ(g.checks[1].check, "witnessed");
  EXPECT_EQ(g.checks[1].outcome, Outcome::error);
  EXPECT_EQ(g.checks[1].message,
            "the oracle saw no object at any of the 2 checked frames: a culler that culls everything would pass this "
            "path; choose a path that looks at the scene");
  EXPECT_TRUE(g.nothing_witnessed);
  EXPECT_FALSE(g.passed());
  EXPECT_EQ(g.exit_code(), 2);
  EXPECT_EQ(gate_verdict(v, "").exit_code(), 0);  // not required: the fuzzer's empty views are fine
  v.runs[0].witnessed_size = {0, 1};
  EXPECT_EQ(gate_verdict(v, "", require).checks.size(), 1u);
  EXPECT_EQ(gate_verdict(v, "", require).exit_code(), 0);
}

// Regression test of a bug it found, since fixed (root cause in subjects/protocol.cpp's excerpt(), see ParseVisible.GarbageExcerptIsValidUtf8):
// a subject whose garbage line holds bytes that are not UTF-8 aborts the run with that text in
// Abort::message; the verdict's JSON then cannot be written (nlohmann::json's dump() throws
// type_error 316), so the gate cannot write report.json and exits as an internal error, not 2.
// Seen end to end: a subject that answers a frame with the bytes FF FE makes `cullcheck gate
// --subject ... -o r.json --junit r.xml` print "internal error: [json.exception.type_error.316]
// invalid UTF-8 byte ..." and exit 3, writing neither file.
TEST(GateVerdict, SubjectGarbageThatIsNotUtf8StillGivesAWritableVerdict) {
  std::string message;
  try {
    (void)protocol::parse_visible(std::string("\xff\xfe not JSON"), "subject 'x'", 0, {1});
  } catch (const SubjectError& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty());
  PathVerification v;
  MethodRun r = conservative_run("subject:x");
  r.outside = true;
  v.runs.push_back(r);
  v.aborted = Abort{"subject:x", 0, "garbage", message};
  const GateVerdict g = gate_verdict(v, "");
  EXPECT_EQ(g.exit_code(), 2);
  EXPECT_NO_THROW((void)g.to_json().dump());
}

TEST(GateVerdict, ToJson) {
  PathVerification v;
  MethodRun r = conservative_run("oh_os_conservative");
  r.violation_count = 1;
  r.frames_with_violations = 1;
  r.violations = {violation("cullcheck verify --a")};
  v.runs.push_back(r);
  MethodRun clean = conservative_run("frustum");
  v.runs.push_back(clean);
  const nlohmann::json j = gate_verdict(v, "", {}, 0).to_json();
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "conservative_violations": 1, "conservative_misdrawn_pixels": 0, "section_violations": 0,
    "frames_over_pixel_budget": 0, "overestimation_failures": 0, "subject_failed": false,
    "nothing_witnessed": false, "checks": [
      {"method": "oh_os_conservative", "check": "conservative", "outcome": "failed",
       "message": "culled 1 object the oracle saw, over 1 frame", "replays": ["cullcheck verify --a"]},
      {"method": "frustum", "check": "conservative", "outcome": "passed"}],
    "passed": false, "exit_code": 1})");
  EXPECT_EQ(j, expected) << j.dump(2);
}

}  // namespace
}  // namespace cullcheck
