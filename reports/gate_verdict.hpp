// The gate's verdict (README "Exit codes"), computed from a verification, so it is testable
// without the CLI: one check per method and kind of check, each passed, failed, in error or
// skipped, with the replay lines that reproduce a failure. report.json's "gate" and the JUnit
// file (reports/junit.hpp) are both written from it.
//
// Checks, per run:
//  - conservative: a method that claims conservativeness culled nothing the oracle saw (no
//    violation, and no misdrawn pixel when the pixel oracle ran);
//  - pixel_budget: an approximate method stayed within its misdrawn pixels per frame;
//  - overestimation: PVS / witnessed stayed within GateThresholds::max_overestimation (when set:
//    catches a culler that culls nothing, which the conservative check cannot);
//  - answers: an outside subject answered every frame (an error when it crashed, hung or lied);
//  - witnessed (with GateThresholds::require_witnessed, once per verification): the oracle saw
//    some object at some checked frame. A path that sees nothing proves nothing: a culler that
//    culls everything passes it. It is bad input (an error, exit 2), not a failed culler.
// Region runs get the conservative check; the report's sections (Table 4.1, view cells, VbAoI)
// one check for their conservative violations.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "reports/verification.hpp"

namespace cullcheck {

struct GateThresholds {
  std::optional<double> max_overestimation;
  bool require_witnessed = false;
};

struct GateCheck {
  enum class Outcome { passed, failed, error, skipped };
  std::string method;
  std::string check;  // conservative, pixel_budget, overestimation, answers, sections, witnessed
  Outcome outcome = Outcome::passed;
  std::string message;               // what failed, or why it was skipped
  std::vector<std::string> replays;  // commands that reproduce a failure
  double seconds = 0.0;              // time the method spent (culling), for JUnit's time attribute
};

struct GateVerdict {
  std::string scene;  // the scene's replay flags, naming the suite
  std::vector<GateCheck> checks;
  std::uint64_t conservative_violations = 0;  // point and region runs that claim conservativeness
  std::uint64_t conservative_misdrawn_pixels = 0;
  std::uint64_t section_violations = 0;
  std::size_t frames_over_budget = 0;
  std::size_t overestimation_failures = 0;
  bool subject_failed = false;  // an outside subject crashed, hung or lied (exit 2)
  bool nothing_witnessed = false;  // require_witnessed, and the oracle saw nothing (exit 2)

  bool passed() const;
  // 0 passed; 1 the gate failed; 2 a subject failed or the path saw nothing (bad input),
  // whatever else happened.
  int exit_code() const;
  nlohmann::json to_json() const;
};

GateVerdict gate_verdict(const PathVerification& v, const std::string& scene, const GateThresholds& thresholds = {},
                         std::uint64_t section_violations = 0);

}  // namespace cullcheck
