#include "reports/subject_claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> subject_claims(const PathVerification& v) {
  std::vector<ClaimCheck> out;
  for (const MethodRun& r : v.runs) {
    if (!r.outside) continue;
    ClaimCheck c;
    c.method = r.method;
    c.source = "declared by the subject (its ready message, or the recorded PVS file's header / --claims)";
    c.frames_checked = r.witnessed_size.size();
    if (r.claims_conservative) {
      c.id = r.method + "-conservative";
      c.statement = "never culls an object the oracle sees (0 misdrawn pixels)";
      c.violations = r.violation_count + r.misdrawn_total;
      c.holds = r.violation_count == 0 && r.misdrawn_total == 0;
      if (!r.violations.empty()) {
        c.counterexample_replay = r.violations.front().replay;
        c.counterexample_detail = "frame " + std::to_string(r.violations.front().frame) + ": culled object " +
                                  std::to_string(r.violations.front().building) + " (oracle " + r.violations.front().model + ")";
      }
    } else if (r.pixel_error_budget) {
      c.id = r.method + "-pixel-budget";
      c.statement = "misdraws at most " + std::to_string(*r.pixel_error_budget) + " pixels in any frame";
      c.frames_checked = r.misdrawn_pixels.size();
      c.violations = r.frames_over_budget;
      c.holds = r.frames_over_budget == 0;
      if (!r.over_budget.empty()) {
        c.counterexample_replay = r.over_budget.front().replay;
        c.counterexample_detail = "frame " + std::to_string(r.over_budget.front().frame) + ": " + r.over_budget.front().witness;
      }
    } else {
      continue;
    }
    if (v.aborted && v.aborted->method == r.method) {
      c.holds = false;
      c.counterexample_detail = v.aborted->message;
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace cullcheck
