#include "reports/view_cells.hpp"
#include "core/progress.hpp"

#include <algorithm>
#include <sstream>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "engine/shrinking/circle_tiling.hpp"
#include "generators/open_space.hpp"
#include "generators/navigable_regions.hpp"
#include "reports/statistics.hpp"
#include "reports/verification.hpp"

namespace cullcheck {
namespace {

// Cells spread over the city: every k-th, k chosen so that about `n` are picked.
std::vector<std::size_t> spread(std::size_t total, std::size_t n) {
  std::vector<std::size_t> out;
  if (n == 0 || total == 0) return out;
  const std::size_t step = std::max<std::size_t>(1, total / n);
  for (std::size_t i = step / 2; i < total && out.size() < n; i += step) out.push_back(i);
  return out;
}

}  // namespace

std::vector<Camera> cell_viewpoints(const ViewCell& cell, const Camera& clip) {
  std::vector<Vec2> points;
  const auto& r = cell.ring;
  Vec2 centroid{};
  for (std::size_t i = 0; i < r.size(); ++i) {
    points.push_back(r[i]);
    points.push_back((r[i] + r[(i + 1) % r.size()]) * 0.5);
    centroid = centroid + r[i] * (1.0 / static_cast<double>(r.size()));
  }
  // Interior grid: the centroid and points a quarter and half of the way towards each corner.
  points.push_back(centroid);
  for (std::size_t i = 0; i < r.size(); ++i) points.push_back(centroid + (r[i] - centroid) * 0.5);
  for (std::size_t i = 0; i < r.size(); ++i) points.push_back(centroid + ((r[i] + r[(i + 1) % r.size()]) * 0.5 - centroid) * 0.75);
  std::vector<Camera> out;
  for (Vec2 p : points) {
    Camera c = clip;
    c.hfov = kTwoPi;
    c.yaw = c.pitch = c.roll = 0.0;
    c.position = {p.x, p.y, cell.eye_height};
    out.push_back(c);
  }
  return out;
}

std::string cell_replay_command(const SceneSource& source, const std::string& method, std::uint32_t cell, double epsilon,
                                CellSampling sampling, double eye_height, const Camera& from) {
  return "cullcheck cell " + source.replay_flags() + " --method " + method + " --cell " + std::to_string(cell) +
         " --epsilon " + round_trip_text(epsilon) + " --sampling " + std::string(cell_sampling_name(sampling)) + " --eye-height " +
         round_trip_text(eye_height) + " --from " + camera_arg(from);
}

nlohmann::json view_cell_report(const Scene& scene, const SceneSource& source, const ViewCellOptions& options,
                                const MethodOptions& method_options) {
  const std::vector<NavigableRegion> regions = generators::navigable_regions(scene);
  const auto cells = &regions;
  std::vector<std::size_t> chosen;
  for (std::size_t c = 0; c < cells->size(); c += std::max<std::size_t>(1, options.cell_stride)) chosen.push_back(c);
  const std::vector<std::size_t> checked = spread(chosen.size(), options.oracle_cells);

  // The oracle's answers, once per viewpoint of each checked cell, shared by every run.
  const oracle::Oracle truth(scene);
  const generators::OpenSpace open(scene);
  std::vector<std::vector<std::pair<Camera, oracle::OracleAnswer>>> answers;
  double oracle_seconds = 0.0;
  for (std::size_t k : checked) {
    answers.emplace_back();
    for (const Camera& v : cell_viewpoints({(*cells)[chosen[k]].ring, options.eye_height})) {
      if (open.inside_building(v.position)) continue;
      answers.back().emplace_back(v, truth.visible_set(v, options.oracle));
      oracle_seconds += answers.back().back().second.elapsed_seconds;
    }
  }

  nlohmann::json report = {{"epsilon", options.epsilon},          {"eye_height", options.eye_height},
                           {"buildings", scene.buildings.size()}, {"cells", cells->size()},
                           {"cells_computed", chosen.size()},     {"cells_checked_by_oracle", checked.size()},
                           {"oracle_seconds", oracle_seconds},    {"runs", nlohmann::json::array()}};
  for (const std::string& name : options.methods)
    for (CellSampling sampling : options.samplings) {
      auto method = make_region_method(name, scene, method_options);
      ViewCellPvs cells_pvs(*method, scene);
      std::vector<double> carried_ms, plain_ms, pvs, samples;
      std::uint64_t carried_tests = 0, plain_tests = 0, skipped = 0;
      std::size_t unions_differ = 0, violations = 0, viewpoints = 0;
      nlohmann::json first = nlohmann::json::array();
      std::size_t next_checked = 0;
      Progress progress("view cells: " + name + " (" + std::string(cell_sampling_name(sampling)) + ")", chosen.size(), "cells");
      for (std::size_t k = 0; k < chosen.size(); ++k, progress.advance()) {
        const ViewCell cell{(*cells)[chosen[k]].ring, options.eye_height};
        const ViewCellResult plain = cells_pvs.compute(cell, options.epsilon, sampling, /*carry=*/false);
        plain_ms.push_back(plain.stats.cull_ms);
        plain_tests += plain.stats.buildings_tested;
        ViewCellResult used = plain;
        if (method->carries_known()) {
          used = cells_pvs.compute(cell, options.epsilon, sampling, /*carry=*/true);
          unions_differ += used.pvs != plain.pvs ? 1 : 0;
        }
        carried_ms.push_back(used.stats.cull_ms);
        carried_tests += used.stats.buildings_tested;
        skipped += used.stats.items_skipped;
        pvs.push_back(static_cast<double>(used.pvs.size()));
        samples.push_back(static_cast<double>(used.samples));
        if (next_checked < checked.size() && checked[next_checked] == k) {
          for (const auto& [v, seen] : answers[next_checked]) {
            ++viewpoints;
            for (ObjectId id : missing_from(seen.visible, used.pvs)) {
              ++violations;
              if (first.size() < 5)
                first.push_back({{"cell", chosen[k]},
                                 {"building", id},
                                 {"witness", seen.sampling ? oracle::describe(seen.sampling->witnesses.at(id)) : seen.model},
                                 {"replay", cell_replay_command(source, name, static_cast<std::uint32_t>(chosen[k]),
                                                                options.epsilon, sampling, options.eye_height, v)}});
            }
          }
          ++next_checked;
        }
      }
      auto sum = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) s += x;
        return s;
      };
      report["runs"].push_back({{"method", name},
                                {"sampling", cell_sampling_name(sampling)},
                                {"claims_conservative", method->claims_conservative()},
                                {"carries", method->carries_known()},
                                {"samples_mean", mean(samples)},
                                {"ms_per_cell_median", median(carried_ms)},
                                {"ms_per_cell_p95", percentile(carried_ms, 95.0)},
                                {"ms_per_cell_mean", mean(carried_ms)},
                                {"total_seconds", sum(carried_ms) / 1000.0},
                                {"uncarried_ms_per_cell_median", median(plain_ms)},
                                {"uncarried_total_seconds", sum(plain_ms) / 1000.0},
                                {"carry_speedup", sum(carried_ms) > 0.0 ? sum(plain_ms) / sum(carried_ms) : 1.0},
                                {"buildings_tested_per_cell", static_cast<double>(carried_tests) / std::max<double>(1, chosen.size())},
                                {"uncarried_buildings_tested_per_cell", static_cast<double>(plain_tests) / std::max<double>(1, chosen.size())},
                                {"accepted_untested_per_cell", static_cast<double>(skipped) / std::max<double>(1, chosen.size())},
                                {"cells_where_carrying_changed_the_pvs", unions_differ},
                                {"pvs_mean", mean(pvs)},
                                {"pvs_max", pvs.empty() ? 0.0 : *std::max_element(pvs.begin(), pvs.end())},
                                {"oracle_viewpoints", viewpoints},
                                {"violations", violations},
                                {"first_violations", first}});
    }
  return report;
}

std::string view_cell_table(const nlohmann::json& report) {
  std::ostringstream out;
  out << "view cells: " << report["cells_computed"].get<std::size_t>() << " of " << report["cells"].get<std::size_t>()
      << " cells, " << report["buildings"].get<std::size_t>() << " buildings, eps " << report["epsilon"].get<double>()
      << " m, " << report["cells_checked_by_oracle"].get<std::size_t>() << " cells held to the oracle\n";
  char line[256];
  std::snprintf(line, sizeof line, "%-32s %-8s %8s %9s %9s %9s %9s %8s %6s %5s\n", "method", "sampling", "samples",
                "ms/cell", "total_s", "uncarried", "speedup", "pvs", "views", "viol");
  out << line;
  for (const auto& r : report["runs"]) {
    std::snprintf(line, sizeof line, "%-32s %-8s %8.1f %9.2f %9.2f %9.2f %9.2f %8.1f %6zu %5zu\n",
                  r["method"].get<std::string>().c_str(), r["sampling"].get<std::string>().c_str(),
                  r["samples_mean"].get<double>(), r["ms_per_cell_median"].get<double>(), r["total_seconds"].get<double>(),
                  r["uncarried_total_seconds"].get<double>(), r["carry_speedup"].get<double>(), r["pvs_mean"].get<double>(),
                  r["oracle_viewpoints"].get<std::size_t>(), r["violations"].get<std::size_t>());
    out << line;
  }
  return out.str();
}

}  // namespace cullcheck
