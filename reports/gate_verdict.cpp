#include "reports/gate_verdict.hpp"

#include <numeric>

#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

std::string count_text(std::uint64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

double total(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

}  // namespace

bool GateVerdict::passed() const {
  for (const GateCheck& c : checks)
    if (c.outcome == GateCheck::Outcome::failed || c.outcome == GateCheck::Outcome::error) return false;
  return true;
}

int GateVerdict::exit_code() const {
  if (subject_failed || nothing_witnessed) return 2;
  return passed() ? 0 : 1;
}

nlohmann::json GateVerdict::to_json() const {
  nlohmann::json checks_json = nlohmann::json::array();
  for (const GateCheck& c : checks) {
    static const char* names[] = {"passed", "failed", "error", "skipped"};
    nlohmann::json j = {{"method", c.method}, {"check", c.check}, {"outcome", names[static_cast<int>(c.outcome)]}};
    if (!c.message.empty()) j["message"] = c.message;
    if (!c.replays.empty()) j["replays"] = c.replays;
    checks_json.push_back(std::move(j));
  }
  return {{"conservative_violations", conservative_violations},
          {"conservative_misdrawn_pixels", conservative_misdrawn_pixels},
          {"section_violations", section_violations},
          {"frames_over_pixel_budget", frames_over_budget},
          {"overestimation_failures", overestimation_failures},
          {"subject_failed", subject_failed},
          {"nothing_witnessed", nothing_witnessed},
          {"checks", std::move(checks_json)},
          {"passed", passed()},
          {"exit_code", exit_code()}};
}

GateVerdict gate_verdict(const PathVerification& v, const std::string& scene, const GateThresholds& thresholds,
                         std::uint64_t section_violations) {
  GateVerdict out;
  out.scene = scene;
  using Outcome = GateCheck::Outcome;
  for (const MethodRun& r : v.runs) {
    const double seconds = total(r.cull_ms) / 1000.0;
    if (r.claims_conservative) {
      GateCheck c{r.method, "conservative", Outcome::passed, "", {}, seconds};
      out.conservative_violations += r.violation_count;
      out.conservative_misdrawn_pixels += r.misdrawn_total;
      if (r.violation_count > 0 || r.misdrawn_total > 0) {
        c.outcome = Outcome::failed;
        c.message = "culled " + count_text(r.violation_count, "object", "objects") + " the oracle saw, over " +
                    count_text(r.frames_with_violations, "frame", "frames");
        if (r.misdrawn_total > 0) c.message += "; " + count_text(r.misdrawn_total, "misdrawn pixel", "misdrawn pixels");
        for (const Violation& x : r.violations) c.replays.push_back(x.replay);
      } else if (r.witnessed_size.empty()) {
        c.outcome = Outcome::skipped;
        c.message = "no frame was checked by the oracle";
      }
      out.checks.push_back(std::move(c));
    }
    if (r.pixel_error_budget) {
      GateCheck c{r.method, "pixel_budget", Outcome::passed, "", {}, seconds};
      out.frames_over_budget += r.frames_over_budget;
      if (r.frames_over_budget > 0) {
        c.outcome = Outcome::failed;
        c.message = count_text(r.frames_over_budget, "frame", "frames") + " above the budget of " +
                    std::to_string(*r.pixel_error_budget) + " misdrawn pixels (worst " + std::to_string(r.most_misdrawn) + ")";
        for (const Violation& x : r.over_budget) c.replays.push_back(x.replay);
      } else if (r.misdrawn_pixels.empty()) {
        c.outcome = Outcome::skipped;
        c.message = "the pixel oracle checked no frame";
      }
      out.checks.push_back(std::move(c));
    }
    if (thresholds.max_overestimation) {
      GateCheck c{r.method, "overestimation", Outcome::passed, "", {}, seconds};
      const double witnessed = mean(r.witnessed_size);
      const double ratio = witnessed > 0 ? mean(r.checked_pvs_size) / witnessed : 0.0;
      if (ratio > *thresholds.max_overestimation) {
        ++out.overestimation_failures;
        c.outcome = Outcome::failed;
        char text[160];
        std::snprintf(text, sizeof text, "PVS / witnessed = %.3f over the checked frames, above the limit %.3f", ratio,
                      *thresholds.max_overestimation);
        c.message = text;
      }
      out.checks.push_back(std::move(c));
    }
    if (r.outside) {
      GateCheck c{r.method, "answers", Outcome::passed, "", {}, seconds};
      if (v.aborted && v.aborted->method == r.method) {
        c.outcome = Outcome::error;
        c.message = v.aborted->message;
        out.subject_failed = true;
      } else if (r.frames_skipped > 0) {
        c.message = count_text(r.frames_skipped, "frame", "frames") + " skipped: " + r.skip_reason;
      }
      out.checks.push_back(std::move(c));
    }
  }
  if (v.aborted && !out.subject_failed) {  // failed before its run existed (the handshake)
    out.subject_failed = true;
    out.checks.push_back({v.aborted->method, "answers", Outcome::error, v.aborted->message, {}, 0.0});
  }
  for (const RegionRun& r : v.regions) {
    if (!r.claims_conservative) continue;
    GateCheck c{"region:" + r.method, "conservative", Outcome::passed, "", {}, total(r.compute_ms) / 1000.0};
    out.conservative_violations += r.violation_count;
    if (r.violation_count > 0) {
      c.outcome = Outcome::failed;
      c.message = "culled " + count_text(r.violation_count, "object", "objects") + " the oracle saw from an eye of its disc";
      for (const Violation& x : r.violations) c.replays.push_back(x.replay);
    }
    out.checks.push_back(std::move(c));
  }
  if (thresholds.require_witnessed) {
    // Every run is checked at the same frames against the same oracle: the first run with
    // checked frames says what the oracle saw.
    for (const MethodRun& r : v.runs) {
      if (r.witnessed_size.empty()) continue;
      if (total(r.witnessed_size) == 0.0) {
        out.nothing_witnessed = true;
        out.checks.push_back({"path", "witnessed", Outcome::error,
                              "the oracle saw no object at any of the " + count_text(r.witnessed_size.size(), "checked frame", "checked frames") +
                                  ": a culler that culls everything would pass this path; choose a path that looks at the scene",
                              {},
                              0.0});
      }
      break;
    }
  }
  out.section_violations = section_violations;
  if (section_violations > 0)
    out.checks.push_back({"sections", "conservative", Outcome::failed,
                          count_text(section_violations, "conservative violation", "conservative violations") +
                              " in table_4_1, view_cells or vbaoi (see those sections' replays)",
                          {},
                          0.0});
  return out;
}

}  // namespace cullcheck
