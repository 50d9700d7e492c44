#include "reports/table_4_1.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <cmath>
#include <cstdio>

#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/open_space.hpp"
#include "reports/statistics.hpp"
#include "reports/verification.hpp"

namespace cullcheck {
namespace {

constexpr int kUnionRings = 4;  // OH(OS)'s union over the disc: 1 + 6 + 12 + 18 + 24 = 61 eyes

std::vector<std::string> narrow_region_names(const PathVerification& v) {
  std::vector<std::string> out;
  for (const RegionRun& r : v.regions) out.push_back(r.method);
  return out;
}

// The thesis's increases over Method 1 at 60° (Table 4.1), where it has a row for the method.
nlohmann::json thesis_increase(const std::string& method, int angle) {
  if (method == "oh_os_conservative") return angle == 60 ? 0.0 : 0.06;
  if (method == "shrink_former") return angle == 60 ? 0.68 : 0.75;
  if (method == "shrink_adjustable_thesis") return angle == 60 ? 0.17 : 0.24;
  return nullptr;
}

}  // namespace

nlohmann::json table_4_1(const Table41Options& options, const MethodOptions& method_options) {
  const Scene scene = generators::make_city(options.generator, options.seed, options.params);
  SceneSource source;
  source.generator = options.generator;
  source.seed = options.seed;
  source.parameters_json = options.params.dump();
  auto walk = [&](double hfov_deg) {
    return generators::make_camera_path("plaza_crossing", scene, 0, {{"hfov_deg", hfov_deg}});
  };
  const CameraPath at_60 = walk(60.0), at_90 = walk(90.0);

  VerificationOptions v;
  v.oracle = options.oracle;
  v.oracle_stride = options.oracle_stride;
  v.region_methods = options.region_methods.empty() ? region_method_names() : options.region_methods;
  v.region_radius = options.radius;
  v.path_replay_flags = "--path-kind plaza_crossing --path-params '{\"hfov_deg\":60}'";
  const PathVerification narrow = verify_path(scene, source, at_60, {"oh_os_conservative"}, method_options, v);
  v.region_turn = options.widen_deg * kPi / 180.0;
  const PathVerification widened = verify_path(scene, source, at_60, {"oh_os_conservative"}, method_options, v);
  v.region_methods.clear();
  v.path_replay_flags = "--path-kind plaza_crossing --path-params '{\"hfov_deg\":90}'";
  const PathVerification wide_point = verify_path(scene, source, at_90, {"oh_os_conservative"}, method_options, v);

  const double reference = mean(narrow.runs[0].pvs_size);
  nlohmann::json rows = nlohmann::json::array();
  auto point_row = [&](const MethodRun& r, int angle) {
    rows.push_back({{"method", r.method},
                    {"thesis_method", "Method 1 (no shrinking, PVS for the viewpoint)"},
                    {"viewing_angle", angle},
                    {"pvs_mean", mean(r.pvs_size)},
                    {"increase_over_method_1_at_60", mean(r.pvs_size) / reference - 1.0},
                    {"thesis_increase", thesis_increase(r.method, angle)},
                    {"witnessed_mean", mean(r.witnessed_size)},
                    {"violations", r.violation_count},
                    {"pvs_computed", r.pvs_size.size()},
                    {"frames_per_pvs", 1.0},
                    {"compute_ms_median", median(r.cull_ms)}});
  };
  auto region_row = [&](const RegionRun& r, int angle) {
    const std::string label = r.method == "shrink_former" ? "Method 2 (former shrinking)"
                              : r.method == "shrink_adjustable_thesis" ? "Method 3 (adjustable shrinking, as published)"
                                                                       : "Method 3 variant";
    rows.push_back({{"method", r.method},
                    {"thesis_method", label},
                    {"viewing_angle", angle},
                    {"claims_conservative", r.claims_conservative},
                    {"pvs_mean", mean(r.pvs_size)},
                    {"increase_over_method_1_at_60", mean(r.pvs_size) / reference - 1.0},
                    {"thesis_increase", thesis_increase(r.method, angle)},
                    {"witnessed_mean", mean(r.witnessed_size)},
                    {"violations", r.violation_count},
                    {"pvs_computed", r.compute_ms.size()},
                    {"frames_per_pvs", static_cast<double>(r.pvs_size.size()) / std::max<double>(1, r.compute_ms.size())},
                    {"compute_ms_median", median(r.compute_ms)}});
  };
  point_row(narrow.runs[0], 60);
  for (const RegionRun& r : narrow.regions) region_row(r, 60);
  point_row(wide_point.runs[0], 90);
  for (const RegionRun& r : widened.regions) region_row(r, 90);
  // The disc's witnessed union: a lower bound on any conservative region PVS at that frame.
  nlohmann::json disc = nlohmann::json::array();
  const oracle::Oracle truth(scene);
  const generators::OpenSpace open(scene);
  const std::size_t stride = std::max<std::size_t>(1, options.oracle_stride * options.disc_stride);
  // Where each method's over-estimate lies: PVS members that no eye of the disc witnessed, by
  // plan distance from the centre (the point method against its centre's witnesses).
  const std::vector<std::string> region_names = narrow_region_names(narrow);
  std::vector<std::unique_ptr<RegionCullingMethod>> engines;
  for (const std::string& name : region_names) engines.push_back(make_region_method(name, scene, method_options));
  auto point_engine = make_method("oh_os_conservative", scene, method_options);
  static constexpr double kBins[] = {50.0, 150.0, 400.0};
  auto bin_of = [&](ObjectId id, Vec2 eye) {
    const Box2 box = scene.find(id)->bounds.plan();
    const double d = length((box.lo + box.hi) * 0.5 - eye);
    std::size_t b = 0;
    while (b < 3 && d >= kBins[b]) ++b;
    return b;
  };
  // OH(OS)'s own floor: the union of its point PVS over eyes filling the disc (the centre and
  // hexagonal rings of 6, 12, 18 and 24 eyes at a quarter, half, three quarters and all of the
  // radius). A region method whose PVS holds OH(OS)'s at every eye of the disc cannot be below it;
  // with 61 eyes it is a sampled lower bound of that union (the oracle's union above bounds any
  // conservative method).
  std::vector<Vec2> union_offsets = {{0.0, 0.0}};
  for (int ring = 1; ring <= kUnionRings; ++ring)
    for (int k = 0; k < 6 * ring; ++k) {
      const double a = kTwoPi * k / (6.0 * ring), r = options.radius * ring / kUnionRings;
      union_offsets.push_back({r * std::cos(a), r * std::sin(a)});
    }
  // The oracle's 13 eyes: the centre, 8 on the rim and 4 at half the radius.
  std::vector<Vec2> witness_offsets;
  for (int k = 0; k < 13; ++k) {
    const double reach = k == 0 ? 0.0 : k <= 8 ? options.radius : options.radius / 2;
    const double a = k <= 8 ? (k - 1) * kPi / 4 : (k - 9) * kPi / 2 + kPi / 4;
    witness_offsets.push_back({reach * std::cos(a), reach * std::sin(a)});
  }
  for (const int angle : {60, 90}) {
    std::vector<double> unions, points, centres, oh_os_unions;
    std::vector<std::array<double, 5>> unwitnessed(engines.size() + 1, std::array<double, 5>{});  // 4 bins + total
    const std::vector<double> turns = angle == 60 ? std::vector<double>{0.0} : std::vector<double>{-1.0, 0.0, 1.0};
    // Every camera of the disc around c at `offsets` (those not inside a building), turned by each
    // of `turns`; `centre` is true for the first offset unturned.
    auto each_eye = [&](const Camera& c, const std::vector<Vec2>& offsets, auto&& f) {
      for (std::size_t k = 0; k < offsets.size(); ++k) {
        Camera v = c;
        v.position = {c.position.x + offsets[k].x, c.position.y + offsets[k].y, c.position.z};
        if (open.inside_building(v.position)) continue;
        for (const double turn : turns) {
          v.yaw = std::fmod(c.yaw + turn * options.widen_deg * kPi / 180.0 + kTwoPi, kTwoPi);
          f(v, k == 0 && turn == 0.0);
        }
      }
    };
    auto distinct = [](std::vector<ObjectId>& ids) {
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      return static_cast<double>(ids.size());
    };
    for (std::size_t f = 0; f < at_60.frames.size(); f += stride) {
      const Camera& c = at_60.frames[f];
      std::vector<ObjectId> seen;
      each_eye(c, witness_offsets, [&](const Camera& v, bool centre) {
        const oracle::OracleAnswer answer = truth.visible_set(v, options.oracle);
        if (centre) {
          centres.push_back(static_cast<double>(answer.visible.size()));
          if (angle == 60)
            for (ObjectId id : missing_from(point_engine->cull(c).pvs, answer.visible)) {
              unwitnessed.back()[bin_of(id, plan(c.position))] += 1;
              unwitnessed.back()[4] += 1;
            }
        }
        seen.insert(seen.end(), answer.visible.begin(), answer.visible.end());
      });
      unions.push_back(distinct(seen));
      std::vector<ObjectId> kept;
      each_eye(c, union_offsets, [&](const Camera& v, bool) {
        const std::vector<ObjectId> pvs = point_engine->cull(v).pvs;
        kept.insert(kept.end(), pvs.begin(), pvs.end());
      });
      oh_os_unions.push_back(distinct(kept));
      const double turn = angle == 60 ? 0.0 : options.widen_deg * kPi / 180.0;
      for (std::size_t m = 0; m < engines.size(); ++m)
        for (ObjectId id : missing_from(engines[m]->cull_region({c, options.radius, turn}).pvs, seen)) {
          unwitnessed[m][bin_of(id, plan(c.position))] += 1;
          unwitnessed[m][4] += 1;
        }
      points.push_back(narrow.runs[0].pvs_size[f]);
    }
    disc.push_back({{"viewing_angle", angle},
                    {"frames", unions.size()},
                    {"witnessed_union_mean", mean(unions)},
                    {"point_pvs_mean", mean(points)},
                    {"least_possible_increase", mean(unions) / mean(points) - 1.0},
                    {"oh_os_union_eyes", union_offsets.size()},
                    {"oh_os_union_mean", mean(oh_os_unions)},
                    {"oh_os_union_increase", mean(oh_os_unions) / mean(points) - 1.0},
                    {"witnessed_centre_mean", mean(centres)},
                    {"witnessed_increase", mean(unions) / mean(centres) - 1.0},
                    {"unwitnessed", [&] {
                       nlohmann::json rows = nlohmann::json::array();
                       const double n = std::max<double>(1, unions.size());
                       auto row = [&](const std::string& name, const std::array<double, 5>& u) {
                         rows.push_back({{"method", name},
                                         {"mean", u[4] / n},
                                         {"by_distance_m", {{"0-50", u[0] / n}, {"50-150", u[1] / n},
                                                            {"150-400", u[2] / n}, {"400+", u[3] / n}}}});
                       };
                       if (angle == 60) row("oh_os_conservative (point, against its centre)", unwitnessed.back());
                       for (std::size_t m = 0; m < engines.size(); ++m) row(region_names[m], unwitnessed[m]);
                       return rows;
                     }()}});
  }
  return {{"scene", {{"generator", options.generator}, {"seed", options.seed}, {"parameters", options.params},
                     {"buildings", scene.buildings.size()}}},
          {"path", {{"kind", "plaza_crossing"}, {"frames", at_60.frames.size()}}},
          {"radius", options.radius},
          {"widen_deg", options.widen_deg},
          {"oracle_frames", narrow.oracle.frames_checked},
          {"rows", rows},
          {"disc_witnessed", disc}};
}

std::string table_4_1_text(const nlohmann::json& table) {
  std::string out = "Table 4.1 (thesis ch. 4.2) on " + std::to_string(table["scene"]["buildings"].get<std::size_t>()) +
                    " buildings, " + std::to_string(table["path"]["frames"].get<std::size_t>()) +
                    " frames of the plaza crossing, eps " + std::to_string(table["radius"].get<double>()) + " m\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-32s %5s %8s %9s %9s %9s %6s %8s\n", "method", "angle", "pvs", "increase", "thesis",
                "witnessed", "viol", "pvs/walk");
  out += line;
  for (const auto& r : table["rows"]) {
    char thesis[16] = "-";
    if (!r["thesis_increase"].is_null()) std::snprintf(thesis, sizeof thesis, "%+.0f%%", 100 * r["thesis_increase"].get<double>());
    std::snprintf(line, sizeof line, "%-32s %5d %8.1f %+8.0f%% %9s %9.1f %6llu %8zu\n", r["method"].get<std::string>().c_str(),
                  r["viewing_angle"].get<int>(), r["pvs_mean"].get<double>(),
                  100 * r["increase_over_method_1_at_60"].get<double>(), thesis, r["witnessed_mean"].get<double>(),
                  static_cast<unsigned long long>(r["violations"].get<std::uint64_t>()), r["pvs_computed"].get<std::size_t>());
    out += line;
  }
  for (const auto& d : table["disc_witnessed"]) {
    for (const auto& u : d["unwitnessed"]) {
      std::snprintf(line, sizeof line, "  %d°: %-48s unwitnessed %5.1f  (0-50 m %4.1f, 50-150 m %4.1f, 150-400 m %4.1f, 400+ m %4.1f)\n",
                    d["viewing_angle"].get<int>(), u["method"].get<std::string>().c_str(), u["mean"].get<double>(),
                    u["by_distance_m"]["0-50"].get<double>(), u["by_distance_m"]["50-150"].get<double>(),
                    u["by_distance_m"]["150-400"].get<double>(), u["by_distance_m"]["400+"].get<double>());
      out += line;
    }
    std::snprintf(line, sizeof line,
                  "disc witnessed (%d°, %zu frames): union %.1f buildings (%+.0f%% over the %.1f witnessed at the centre), "
                  "point PVS %.1f: no conservative region PVS can be below %+.0f%%\n",
                  d["viewing_angle"].get<int>(), d["frames"].get<std::size_t>(), d["witnessed_union_mean"].get<double>(),
                  100 * d["witnessed_increase"].get<double>(), d["witnessed_centre_mean"].get<double>(),
                  d["point_pvs_mean"].get<double>(), 100 * d["least_possible_increase"].get<double>());
    out += line;
    std::snprintf(line, sizeof line,
                  "  OH(OS)'s point PVS over %zu eyes of the disc: union %.1f buildings (%+.1f%% over the point PVS): "
                  "the floor of a region PVS that keeps OH(OS)'s at every eye\n",
                  d["oh_os_union_eyes"].get<std::size_t>(), d["oh_os_union_mean"].get<double>(),
                  100 * d["oh_os_union_increase"].get<double>());
    out += line;
  }
  return out;
}

}  // namespace cullcheck
