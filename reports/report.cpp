#include "reports/report.hpp"

#include <sys/utsname.h>

#include <cstdio>
#include <thread>

#include "reports/statistics.hpp"

#ifndef CULLCHECK_BUILD_TYPE
#define CULLCHECK_BUILD_TYPE "unknown"
#endif

namespace cullcheck {
namespace {

nlohmann::json machine_json() {
  utsname u{};
  uname(&u);
  return {{"hardware_threads", std::thread::hardware_concurrency()},
          {"system", std::string(u.sysname) + " " + u.release},
          {"architecture", u.machine},
          {"compiler", std::string("g++ ") + __VERSION__},
          {"build_type", CULLCHECK_BUILD_TYPE}};
}

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

}  // namespace

std::uint64_t conservative_violations(const PathVerification& v) {
  std::uint64_t n = 0;
  for (const MethodRun& r : v.runs)
    if (r.claims_conservative) n += r.violation_count;
  return n;
}

nlohmann::json build_report(const ReportInputs& in) {
  using nlohmann::json;
  const Scene& scene = *in.scene;
  const PathVerification& v = *in.verification;
  json report;
  report["schema_version"] = kReportSchemaVersion;
  report["tool"] = {{"name", "cullcheck"}, {"version", "0.1.0"}};
  report["machine"] = machine_json();
  const Box3 b = scene.bounds();
  report["scene"] = {{"generator", scene.provenance.generator},
                     {"seed", scene.provenance.seed},
                     {"parameters", json::parse(scene.provenance.parameters_json)},
                     {"building_count", scene.buildings.size()},
                     {"triangle_count", scene.triangle_count()},
                     {"bounds", scene.buildings.empty() ? json(nullptr) : json{{"min", {b.lo.x, b.lo.y, b.lo.z}}, {"max", {b.hi.x, b.hi.y, b.hi.z}}}},
                     {"replay_flags", in.source.replay_flags()}};
  report["path"] = {{"kind", in.path->kind},
                    {"seed", in.path->seed},
                    {"parameters", json::parse(in.path_parameters_json)},
                    {"frames", in.path->frames.size()},
                    {"frames_per_second", in.path->frames_per_second}};
  const OracleSummary& o = v.oracle;
  json density;
  oracle::to_json(density, o.density);
  report["oracle"] = {{"frames_checked", o.frames_checked},
                      {"oracle_stride", o.oracle_stride},
                      {"frames_exact_2d", o.frames_exact_2d},
                      {"frames_ray_sampling", o.frames_ray_sampling},
                      {"density", density},
                      {"rays_cast", o.rays_cast},
                      {"seconds", o.seconds},
                      {"rays_per_second", ratio(static_cast<double>(o.rays_cast), o.sampling_seconds)},
                      {"bare_embree_rays_per_second", o.bare_embree_rays_per_second}};
  json runs = json::array();
  for (const MethodRun& r : v.runs) {
    const double frames = static_cast<double>(r.cull_ms.size());
    const double pvs_checked = mean(r.checked_pvs_size), witnessed = mean(r.witnessed_size);
    json violations = json::array();
    for (const Violation& x : r.violations)
      violations.push_back({{"frame", x.frame}, {"building", x.building}, {"model", x.model}, {"witness", x.witness}, {"replay", x.replay}});
    runs.push_back({{"method", r.method},
                    {"claims_conservative", r.claims_conservative},
                    {"parameters", {{"horizon_bins", in.method_options.horizon_bins}, {"quadtree_leaf_size", in.method_options.quadtree_leaf_size}}},
                    {"frames", r.cull_ms.size()},
                    {"cull_ms_median", median(r.cull_ms)},
                    {"cull_ms_p95", percentile(r.cull_ms, 95)},
                    {"cull_ms_mean", mean(r.cull_ms)},
                    {"pvs_mean", mean(r.pvs_size)},
                    {"pvs_mean_checked_frames", pvs_checked},
                    {"witnessed_mean", witnessed},
                    {"overestimation", ratio(pvs_checked, witnessed)},
                    {"cells_tested_mean", ratio(static_cast<double>(r.totals.cells_tested), frames)},
                    {"buildings_tested_mean", ratio(static_cast<double>(r.totals.buildings_tested), frames)},
                    {"horizon_nodes_mean", ratio(static_cast<double>(r.totals.horizon_nodes), frames)},
                    {"occluders_applied_mean", ratio(static_cast<double>(r.totals.occluders_applied), frames)},
                    {"violations", r.violation_count},
                    {"frames_with_violations", r.frames_with_violations},
                    {"violation_replays", violations}});
  }
  report["runs"] = runs;
  json claims = json::array();
  for (const ClaimCheck& c : in.claims) claims.push_back(to_json(c));
  report["claims"] = claims;
  report["gate"] = {{"conservative_violations", conservative_violations(v)},
                    {"passed", conservative_violations(v) == 0}};
  return report;
}

std::string summary_table(const PathVerification& v) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-20s %7s %9s %9s %9s %10s %8s %10s\n", "method", "frames", "ms_med", "ms_p95",
                "pvs_mean", "witnessed", "overest", "violations");
  out += line;
  for (const MethodRun& r : v.runs) {
    const double witnessed = mean(r.witnessed_size);
    std::snprintf(line, sizeof line, "%-20s %7zu %9.3f %9.3f %9.1f %10.1f %8.2f %10llu%s\n", r.method.c_str(),
                  r.cull_ms.size(), median(r.cull_ms), percentile(r.cull_ms, 95), mean(r.pvs_size), witnessed,
                  ratio(mean(r.checked_pvs_size), witnessed), static_cast<unsigned long long>(r.violation_count),
                  r.claims_conservative ? "" : " (not claimed conservative)");
    out += line;
  }
  return out;
}

}  // namespace cullcheck
