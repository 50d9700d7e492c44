// The precision the properties hold each point method to (conservativeness alone passes a
// method that culls nothing). Measured over occluded street-level cases (large Manhattan grids,
// level eyes aimed into the city: straw_man_test.cpp), as
//  - over-estimation: Σ|PVS| / Σ|oracle-witnessed| over the cases, at most max_overestimation;
//  - culling beyond the frustum: the share of cases whose PVS lacks a building the frustum PVS
//    keeps, at least min_share_beyond_frustum (0 for frustum culling, which claims none).
// The bounds are the measured figures (CI seed and seeds 1-6, printed by the test) with a margin
// of about a third of the worst, so they fail when a method loses much of its culling, not on a
// rotated seed's noise (CULLCHECK_SEED, property_main.cpp).
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

namespace cullcheck {

struct PrecisionClaim {
  double max_overestimation = 0.0;
  double min_share_beyond_frustum = 0.0;
};

// nullopt for methods without a precision claim here.
inline std::optional<PrecisionClaim> precision_claim(std::string_view method) {
  // The horizon methods on level cameras (OH(IS)'s claim holds there), 4096 bins. Measured at the
  // CI seed over 119 cases: over-estimation 1.40 (OH(OS), both ΔH on one frame) and 1.60
  // (OH(IS)); culling beyond the frustum in 93.3% and 91.6% of the cases. Over seeds 1-6 the
  // worst were 1.46 and 1.73, and 94.2%.
  if (method == "oh_os_conservative" || method == "oh_os_thesis" || method == "delta_h_guarded" ||
      method == "delta_h_thesis" || method == "oh_is")
    return PrecisionClaim{2.4, 0.6};
  // Measured 5.71 at the CI seed, 5.30-7.44 over seeds 1-6 (a PVS of every building: 18.4 at the
  // CI seed, 16.3-21.3 over seeds 1-6).
  if (method == "frustum") return PrecisionClaim{11.0, 0.0};
  return std::nullopt;
}

// What a method did over the precision cases.
struct PrecisionTally {
  std::size_t cases = 0;           // cases where the oracle saw something
  std::size_t pvs_total = 0;       // Σ|PVS|
  std::size_t seen_total = 0;      // Σ|oracle-witnessed|
  std::size_t beyond_frustum = 0;  // cases whose PVS lacks a building the frustum PVS keeps

  double overestimation() const { return seen_total ? double(pvs_total) / double(seen_total) : 0.0; }
  double share_beyond_frustum() const { return cases ? double(beyond_frustum) / double(cases) : 0.0; }
  std::string summary() const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu cases, PVS %zu vs witnessed %zu: over-estimation %.2f, culls beyond the frustum in %.1f%%",
                  cases, pvs_total, seen_total, overestimation(), 100.0 * share_beyond_frustum());
    return buf;
  }
};

// Empty when `t` meets `claim`, else what it misses.
inline std::string precision_shortfall(const PrecisionTally& t, const PrecisionClaim& claim) {
  char buf[200];
  if (t.overestimation() > claim.max_overestimation) {
    std::snprintf(buf, sizeof buf, "over-estimation %.2f exceeds the claimed %.2f", t.overestimation(), claim.max_overestimation);
    return buf;
  }
  if (t.share_beyond_frustum() < claim.min_share_beyond_frustum) {
    std::snprintf(buf, sizeof buf, "culls beyond the frustum in %.1f%% of occluded cases, below the claimed %.1f%%",
                  100.0 * t.share_beyond_frustum(), 100.0 * claim.min_share_beyond_frustum);
    return buf;
  }
  return "";
}

}  // namespace cullcheck
