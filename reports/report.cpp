#include "reports/report.hpp"

#include <sys/utsname.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <thread>

#include "reports/gate_verdict.hpp"
#include "reports/html/frame_map.hpp"
#include "reports/statistics.hpp"
#include "reports/test_costs.hpp"

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

// Thesis Table 3.2 b): culling-time speed-ups it reports (Pentium IV, its own OH(IS), OH(OS), ΔH).
struct PublishedSpeedup {
  const char* numerator;
  const char* denominator;
  double culling_time;
};
constexpr PublishedSpeedup kTable32[] = {{"oh_is", "oh_os_conservative", 2.34},
                                         {"oh_is", "delta_h_guarded", 21.54},
                                         {"oh_os_conservative", "delta_h_guarded", 9.18},
                                         {"oh_is", "delta_h_thesis", 21.54},
                                         {"oh_os_conservative", "delta_h_thesis", 9.18},
                                         {"frustum", "oh_os_conservative", 0.0}};

const MethodRun* find_run(const PathVerification& v, const std::string& method) {
  for (const MethodRun& r : v.runs)
    if (r.method == method) return &r;
  return nullptr;
}

}  // namespace

nlohmann::json speedups_json(const PathVerification& v) {
  nlohmann::json out = nlohmann::json::array();
  for (const PublishedSpeedup& s : kTable32) {
    const MethodRun* a = find_run(v, s.numerator);
    const MethodRun* b = find_run(v, s.denominator);
    if (!a || !b) continue;
    auto per_frame = [](const MethodRun& r, std::uint64_t total) {
      return r.cull_ms.empty() ? 0.0 : static_cast<double>(total) / static_cast<double>(r.cull_ms.size());
    };
    nlohmann::json row = {{"faster", s.denominator},
                          {"than", s.numerator},
                          {"cull_ms_median_ratio", ratio(median(a->cull_ms), median(b->cull_ms))},
                          {"cull_ms_p95_ratio", ratio(percentile(a->cull_ms, 95), percentile(b->cull_ms, 95))},
                          {"cull_ms_mean_ratio", ratio(mean(a->cull_ms), mean(b->cull_ms))},
                          {"cells_tested_ratio", ratio(per_frame(*a, a->totals.cells_tested), per_frame(*b, b->totals.cells_tested))},
                          {"horizon_nodes_ratio",
                           ratio(per_frame(*a, a->totals.horizon_nodes), per_frame(*b, b->totals.horizon_nodes))}};
    row["thesis_table_3_2_culling_time"] = s.culling_time > 0 ? nlohmann::json(s.culling_time) : nlohmann::json(nullptr);
    out.push_back(row);
  }
  return out;
}

std::uint64_t conservative_violations(const PathVerification& v) {
  std::uint64_t n = 0;
  for (const MethodRun& r : v.runs)
    if (r.claims_conservative) n += r.violation_count;
  for (const RegionRun& r : v.regions)
    if (r.claims_conservative) n += r.violation_count;
  return n;
}

nlohmann::json report_header(const ReportInputs& in) {
  using nlohmann::json;
  const Scene& scene = *in.scene;
  json report;
  report["schema_version"] = kReportSchemaVersion;
  report["tool"] = {{"name", "cullcheck"}, {"version", "0.1.0"}};
  report["machine"] = machine_json();
  const Box3 b = scene.bounds();
  report["scene"] = {{"generator", scene.provenance.generator},
                     {"seed", scene.provenance.seed},
                     {"parameters", json::parse(scene.provenance.parameters_json)},
                     {"building_count", scene.buildings.size()},
                     {"mesh_count", scene.meshes.size()},
                     {"model", scene.prisms_only() ? "2.5D: every object a vertical prism" : "mesh objects: not every object is a vertical prism"},
                     {"origin", {scene.origin.x, scene.origin.y}},
                     {"triangle_count", scene.triangle_count()},
                     {"bounds", scene.object_count() == 0 ? json(nullptr) : json{{"min", {b.lo.x, b.lo.y, b.lo.z}}, {"max", {b.hi.x, b.hi.y, b.hi.z}}}},
                     {"replay_flags", in.source.replay_flags()}};
  if (in.import && in.import->features > 0) {  // every feature of a footprint file accounted for
    const formats::ImportReport& r = *in.import;
    report["scene"]["import"] = {{"features", r.features},
                                 {"buildings", r.buildings},
                                 {"parts_split", r.parts_split},
                                 {"holes_filled", r.holes_filled},
                                 {"rings_repaired", r.rings_repaired},
                                 {"skipped_invalid", r.skipped_invalid},
                                 {"skipped_no_height", r.skipped_no_height},
                                 {"heights_defaulted", r.heights_defaulted},
                                 {"skipped_not_polygon", r.skipped_not_polygon},
                                 {"crs", r.crs},
                                 {"notes", r.notes}};
  }
  report["path"] = {{"kind", in.path->kind},
                    {"seed", in.path->seed},
                    {"parameters", json::parse(in.path_parameters_json)},
                    {"frames", in.path->frames.size()},
                    {"frames_per_second", in.path->frames_per_second},
                    {"replay_flags", in.path_replay_flags}};
  if (in.coordinates) {  // cameras are checked scene-local; this says what the input was
    const CoordinateConversion& c = *in.coordinates;
    report["path"]["coordinates"] = {{"given", frame_name(c.given)},
                                     {"decided_by", c.decided_by},
                                     {"converted_to_local", c.moved},
                                     {"rounding_m", c.rounding_m},
                                     {"origin", {c.origin.x, c.origin.y}}};
    if (c.declared_origin) report["path"]["coordinates"]["declared_origin"] = {c.declared_origin->x, c.declared_origin->y};
  }
  return report;
}

nlohmann::json build_report(const ReportInputs& in) { return report_results(in, report_header(in)); }

nlohmann::json report_results(const ReportInputs& in, nlohmann::json report) {
  using nlohmann::json;
  const PathVerification& v = *in.verification;
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
                      {"bare_embree_rays_per_second", o.bare_embree_rays_per_second},
                      {"bare_embree_packet_rays_per_second", o.bare_embree_packet_rays_per_second},
                      {"grazing_rays", o.grazing_rays},
                      {"rays_skipped", o.rays_skipped},
                      {"witness_recheck", {{"checked", o.witness_recheck.checked}, {"dropped", o.witness_recheck.dropped}}}};
  json runs = json::array();
  for (const MethodRun& r : v.runs) {
    const double frames = static_cast<double>(r.cull_ms.size());
    const double pvs_checked = mean(r.checked_pvs_size), witnessed = mean(r.witnessed_size);
    json violations = json::array();
    for (const Violation& x : r.violations)
      violations.push_back({{"frame", x.frame}, {"building", x.building}, {"model", x.model}, {"witness", x.witness}, {"replay", x.replay}});
    runs.push_back({{"method", r.method},
                    {"claims_conservative", r.claims_conservative},
                    {"parameters", method_options_json(in.method_options)},
                    {"frames", r.cull_ms.size()},
                    {"cull_ms_median", median(r.cull_ms)},
                    {"cull_ms_p95", percentile(r.cull_ms, 95)},
                    {"cull_ms_mean", mean(r.cull_ms)},
                    {"background_ms_mean", mean(r.background_ms)},
                    {"pvs_mean", mean(r.pvs_size)},
                    {"pvs_mean_checked_frames", pvs_checked},
                    {"witnessed_mean", witnessed},
                    {"overestimation", ratio(pvs_checked, witnessed)},
                    {"cells_tested_mean", ratio(static_cast<double>(r.totals.cells_tested), frames)},
                    {"buildings_tested_mean", ratio(static_cast<double>(r.totals.buildings_tested), frames)},
                    {"horizon_nodes_mean", ratio(static_cast<double>(r.totals.horizon_nodes), frames)},
                    {"occluders_applied_mean", ratio(static_cast<double>(r.totals.occluders_applied), frames)},
                    {"items_skipped_mean", ratio(static_cast<double>(r.totals.items_skipped), frames)},
                    {"guard_fires", r.totals.guard_fires},
                    {"bound_tests_per_object", ratio(static_cast<double>(r.totals.bound_tests),
                                                     static_cast<double>(r.totals.cells_tested + r.totals.buildings_tested))},
                    {"guard_fire_rate", ratio(static_cast<double>(r.totals.guard_fires), frames)},
                    {"tests_over_exact_traversal", tests_over_exact_traversal(r.totals)},
                    {"ns_per_test", ns_per_test(r.totals, mean(r.cull_ms) * frames)},
                    {"frames_pvs_differs_from_oh_os",
                     r.compared_with_reference ? nlohmann::json(r.frames_differing_from_reference) : nlohmann::json(nullptr)},
                    {"violations", r.violation_count},
                    {"frames_with_violations", r.frames_with_violations},
                    {"violation_replays", violations},
                    {"witness_recheck", {{"checked", r.witness_recheck.checked}, {"dropped", r.witness_recheck.dropped}}}});
    json& run = runs.back();
    // Per frame, for the page's curves: every answered frame, and the frames the oracle checked.
    run["per_frame"] = {{"frames", r.answered_frames},
                        {"cull_ms", r.cull_ms},
                        {"pvs", r.pvs_size},
                        {"checked_frames", r.checked_frames},
                        {"checked_pvs", r.checked_pvs_size},
                        {"witnessed", r.witnessed_size}};
    if (r.snapshot)
      run["worst_frame"] = {{"frame", r.snapshot->frame},
                            {"missed", r.snapshot->missed.size()},
                            {"overestimate", r.snapshot->overestimate},
                            {"chosen_frame", in.map_frame.has_value()}};
    run["outside"] = r.outside;
    run["frames_skipped"] = r.frames_skipped;
    if (r.frames_skipped > 0) run["skip_reason"] = r.skip_reason;
    if (r.pixel_error_budget) run["pixel_error_budget"] = *r.pixel_error_budget;
    if (r.outside) {
      const double protocol_seconds = std::accumulate(r.protocol_ms.begin(), r.protocol_ms.end(), 0.0) / 1000.0;
      run["protocol"] = {{"ms_median", median(r.protocol_ms)},
                         {"ms_p95", percentile(r.protocol_ms, 95)},
                         {"seconds", protocol_seconds},
                         {"oracle_seconds", o.seconds + v.pixels.seconds},
                         {"fraction_of_oracle_seconds", ratio(protocol_seconds, o.seconds + v.pixels.seconds)}};
      json equal = json::object();
      for (const auto& [method, frames] : r.frames_equal_to) equal[method] = frames;
      run["frames_pvs_equal_to"] = equal;
    }
    if (v.pixels.enabled) {
      json over = json::array();
      for (const Violation& x : r.over_budget)
        over.push_back({{"frame", x.frame}, {"worst_object", x.building}, {"replay", x.replay}});
      // Per checked frame, only those with an error (a conservative method's list is empty).
      json error_frames = json::array();
      for (std::size_t k = 0; k < r.misdrawn_pixels.size(); ++k)
        if (r.misdrawn_pixels[k] > 0)
          error_frames.push_back({{"frame", r.pixel_frames[k]}, {"misdrawn_pixels", static_cast<std::uint64_t>(r.misdrawn_pixels[k])},
                                  {"largest_blob", r.blob_per_frame[k]}});
      run["pixels"] = {{"frames_checked", r.misdrawn_pixels.size()},
                       {"per_error_frame", std::move(error_frames)},
                       {"misdrawn_pixels", r.misdrawn_total},
                       {"misdrawn_pixels_mean", mean(r.misdrawn_pixels)},
                       {"error_frames", r.error_frames},
                       {"largest_blob", r.largest_blob},
                       {"most_misdrawn_in_a_frame", r.most_misdrawn},
                       {"frames_over_budget", r.frames_over_budget},
                       {"over_budget_replays", over}};
    }
  }
  report["runs"] = runs;
  report["frames_run"] = v.frames_run;
  if (v.aborted)
    report["aborted"] = {{"method", v.aborted->method},
                         {"frame", v.aborted->frame < 0 ? json("handshake") : json(v.aborted->frame)},
                         {"kind", v.aborted->kind},
                         {"message", v.aborted->message}};
  json skipped = json::array();
  for (const auto& [method, why] : v.skipped_methods) skipped.push_back({{"method", method}, {"reason", why}});
  report["skipped_methods"] = skipped;
  report["pixel_oracle"] = {{"enabled", v.pixels.enabled},
                            {"frames_checked", v.pixels.frames},
                            {"rays", v.pixels.rays},
                            {"seconds", v.pixels.seconds},
                            {"rays_per_second", ratio(static_cast<double>(v.pixels.rays), v.pixels.seconds)}};
  report["speedups"] = speedups_json(v);
  json regions = json::array();
  for (const RegionRun& r : v.regions) {
    json violations = json::array();
    for (const Violation& x : r.violations)
      violations.push_back({{"frame", x.frame}, {"building", x.building}, {"model", x.model}, {"witness", x.witness}, {"replay", x.replay}});
    const double pvs = mean(r.pvs_size), point = mean(r.point_pvs_size);
    regions.push_back({{"method", r.method},
                       {"claims_conservative", r.claims_conservative},
                       {"radius", r.radius},
                       {"turn", r.turn},
                       {"placement", r.on_tiling ? "circle_tiling" : "at_eye"},
                       {"pvs_computed", r.compute_ms.size()},
                       {"frames_per_pvs", ratio(static_cast<double>(r.pvs_size.size()), static_cast<double>(r.compute_ms.size()))},
                       {"compute_ms_median", median(r.compute_ms)},
                       {"compute_ms_p95", percentile(r.compute_ms, 95)},
                       {"pvs_mean", pvs},
                       {"point_pvs_mean", r.point_pvs_size.empty() ? json(nullptr) : json(point)},
                       {"increase_over_point_pvs", r.point_pvs_size.empty() ? json(nullptr) : json(ratio(pvs, point) - 1.0)},
                       {"witnessed_mean", mean(r.witnessed_size)},
                       {"violations", r.violation_count},
                       {"frames_with_violations", r.frames_with_violations},
                       {"violation_replays", violations},
                       {"witness_recheck", {{"checked", r.witness_recheck.checked}, {"dropped", r.witness_recheck.dropped}}}});
  }
  report["regions"] = regions;
  const MethodRun* chosen = nullptr;
  try {
    chosen = html::choose_map_run(v, in.map_method, "oh_os_conservative");
  } catch (const std::invalid_argument& e) {  // a long run's report is never lost to a wrong map flag
    report["map_problem"] = e.what();
  }
  if (chosen) {
    std::string why = in.map_frame ? "the frame asked for" : "its worst checked frame";
    if (!in.map_method.empty()) why += ", the method asked for";
    else if (!chosen->snapshot->missed.empty()) why += "; the method whose worst frame missed most";
    else if (chosen->method == "oh_os_conservative") why += "; no method missed anything, so the reference method's largest over-estimate";
    else why += "; no method missed anything";
    report["map"] = html::map_json(*chosen, why);
  }
  json claims = json::array();
  for (const ClaimCheck& c : in.claims) claims.push_back(to_json(c));
  report["claims"] = claims;
  report["gate"] = gate_verdict(v, report["scene"]["replay_flags"].get<std::string>(), in.thresholds).to_json();
  return report;
}

nlohmann::json method_options_json(const MethodOptions& o) {
  return {{"horizon_bins", o.horizon_bins},
          {"quadtree_leaf_size", o.quadtree_leaf_size},
          {"delta_radius", o.delta_radius},
          {"delta_height", o.delta_height},
          {"delta_turn", o.delta_turn},
          {"delta_prefetch", o.delta_prefetch}};
}

nlohmann::json without_timings(const nlohmann::json& j) {
  if (j.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const nlohmann::json& x : j) out.push_back(without_timings(x));
    return out;
  }
  if (!j.is_object()) return j;
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [key, value] : j.items()) {
    const bool timed = key.find("_ms") != std::string::npos || key.rfind("ms_", 0) == 0 || key.find("seconds") != std::string::npos ||
                       key.find("per_second") != std::string::npos || key.find("ns_per_") != std::string::npos || key.find("speedup") != std::string::npos || key == "machine" ||
                       key == "threads" || key.find("peak_rss") != std::string::npos ||
                       key == "speed_targets";  // derived from timings (and from fields kept here)
    if (!timed) out[key] = without_timings(value);
  }
  return out;
}

std::string summary_table(const PathVerification& v) {
  std::string out;
  char line[512];
  int width = 20;  // the method column fits the longest name (outside subjects' names can be long)
  for (const MethodRun& r : v.runs) width = std::max(width, static_cast<int>(std::min<std::size_t>(r.method.size(), 60)));
  std::snprintf(line, sizeof line, "%-*s %7s %9s %9s %9s %10s %8s %10s\n", width, "method", "frames", "ms_med", "ms_p95",
                "pvs_mean", "witnessed", "overest", "violations");
  out += line;
  for (const MethodRun& r : v.runs) {
    const double witnessed = mean(r.witnessed_size);
    std::snprintf(line, sizeof line, "%-*s %7zu %9.3f %9.3f %9.1f %10.1f %8.2f %10llu%s\n", width, r.method.c_str(),
                  r.cull_ms.size(), median(r.cull_ms), percentile(r.cull_ms, 95), mean(r.pvs_size), witnessed,
                  ratio(mean(r.checked_pvs_size), witnessed), static_cast<unsigned long long>(r.violation_count),
                  r.claims_conservative ? "" : " (not claimed conservative)");
    out += line;
  }
  for (const RegionRun& r : v.regions) {
    const double point = mean(r.point_pvs_size);
    std::snprintf(line, sizeof line, "region %s (radius %.2f m): %zu PVS over %zu frames, PVS %.1f (%+.0f%% over the point PVS), %llu violations%s\n",
                  r.method.c_str(), r.radius, r.compute_ms.size(), r.pvs_size.size(), mean(r.pvs_size),
                  point > 0 ? (mean(r.pvs_size) / point - 1.0) * 100 : 0.0, static_cast<unsigned long long>(r.violation_count),
                  r.claims_conservative ? "" : " (not claimed conservative)");
    out += line;
  }
  // What did not run, and why: methods the scene rules out, frames a method does not take.
  for (const auto& [method, why] : v.skipped_methods) out += "skipped " + method + ": " + why + "\n";
  for (const MethodRun& r : v.runs)
    if (r.frames_skipped > 0) out += r.method + ": " + std::to_string(r.frames_skipped) + " frames skipped: " + r.skip_reason + "\n";
  // Incremental methods: how often their PVS matched the reference's, and how often the guard fired.
  for (const MethodRun& r : v.runs) {
    if (!r.compared_with_reference || r.method == "oh_os_conservative" || r.method.rfind("delta_h", 0) != 0) continue;
    std::snprintf(line, sizeof line, "%s: PVS equals oh_os_conservative's at %zu of %zu frames; guard fired %llu times\n",
                  r.method.c_str(), r.cull_ms.size() - r.frames_differing_from_reference, r.cull_ms.size(),
                  static_cast<unsigned long long>(r.totals.guard_fires));
    out += line;
  }
  return out;
}

}  // namespace cullcheck
