#include "reports/view_cells.hpp"
#include "core/parallel_indices.hpp"
#include "core/progress.hpp"

#include <algorithm>
#include <map>
#include <memory>
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

namespace {

// One cell of one run: the union computed without and with carried decisions, and the oracle's
// check when the cell is one of those held to it.
nlohmann::json cell_row(RegionCullingMethod& method, ViewCellPvs& cells_pvs, const ViewCell& cell, std::size_t k, std::size_t id,
                        const ViewCellOptions& options, CellSampling sampling, const SceneSource& source,
                        const std::vector<std::pair<Camera, oracle::OracleAnswer>>* answers) {
  const ViewCellResult plain = cells_pvs.compute(cell, options.epsilon, sampling, /*carry=*/false);
  ViewCellResult used = plain;
  bool differ = false;
  if (method.carries_known()) {
    used = cells_pvs.compute(cell, options.epsilon, sampling, /*carry=*/true);
    differ = used.pvs != plain.pvs;
  }
  nlohmann::json row = {{"k", k},
                        {"plain_ms", plain.stats.cull_ms},
                        {"plain_tests", plain.stats.buildings_tested},
                        {"carried_ms", used.stats.cull_ms},
                        {"carried_tests", used.stats.buildings_tested},
                        {"skipped", used.stats.items_skipped},
                        {"pvs", used.pvs.size()},
                        {"samples", used.samples},
                        {"differ", differ},
                        {"viewpoints", 0},
                        {"violations", 0},
                        {"first", nlohmann::json::array()}};
  if (!answers) return row;
  for (const auto& [v, seen] : *answers) {
    row["viewpoints"] = row["viewpoints"].get<std::size_t>() + 1;
    for (ObjectId id_seen : missing_from(seen.visible, used.pvs)) {
      row["violations"] = row["violations"].get<std::size_t>() + 1;
      if (row["first"].size() < 5)
        row["first"].push_back({{"cell", id},
                                {"building", id_seen},
                                {"witness", seen.sampling ? oracle::describe(seen.sampling->witnesses.at(id_seen)) : seen.model},
                                {"replay", cell_replay_command(source, method.name(), static_cast<std::uint32_t>(id), options.epsilon,
                                                               sampling, options.eye_height, v)}});
    }
  }
  return row;
}

}  // namespace

nlohmann::json view_cell_rows(const Scene& scene, const SceneSource& source, const ViewCellOptions& options,
                              const MethodOptions& method_options) {
  const std::vector<NavigableRegion> regions = generators::navigable_regions(scene);
  std::vector<std::size_t> chosen;
  for (std::size_t c = 0; c < regions.size(); c += std::max<std::size_t>(1, options.cell_stride)) chosen.push_back(c);
  std::vector<std::size_t> mine;  // indices into `chosen` this shard computes
  for (std::size_t k = 0; k < chosen.size(); ++k)
    if (options.shard.owns(k)) mine.push_back(k);
  const std::vector<std::size_t> checked = spread(chosen.size(), options.oracle_cells);

  // The oracle's answers, once per viewpoint of each checked cell this shard computes, shared by every run.
  const oracle::Oracle truth(scene);
  const generators::OpenSpace open(scene);
  std::map<std::size_t, std::vector<std::pair<Camera, oracle::OracleAnswer>>> answers;
  double oracle_seconds = 0.0;
  for (std::size_t k : checked) {
    if (!options.shard.owns(k)) continue;
    auto& list = answers[k];
    for (const Camera& v : cell_viewpoints({regions[chosen[k]].ring, options.eye_height})) {
      if (open.inside_building(v.position)) continue;
      list.emplace_back(v, truth.visible_set(v, options.oracle));
      oracle_seconds += list.back().second.elapsed_seconds;
    }
  }

  nlohmann::json out = {{"epsilon", options.epsilon},          {"eye_height", options.eye_height},
                        {"buildings", scene.buildings.size()}, {"cells", regions.size()},
                        {"cells_computed", chosen.size()},     {"cells_checked_by_oracle", checked.size()},
                        {"oracle_seconds", oracle_seconds},    {"runs", nlohmann::json::array()}};
  for (const std::string& name : options.methods)
    for (CellSampling sampling : options.samplings) {
      std::vector<nlohmann::json> rows(mine.size());
      Progress progress("view cells: " + name + " (" + std::string(cell_sampling_name(sampling)) + ")", mine.size(), "cells");
      for_each_index(mine.size(), options.threads, [&] {
        // Each thread its own method: region methods keep per-query state.
        auto method = std::shared_ptr<RegionCullingMethod>(make_region_method(name, scene, method_options));
        auto cells_pvs = std::make_shared<ViewCellPvs>(*method, scene);
        return [&, method, cells_pvs](std::size_t i) {
          const std::size_t k = mine[i];
          const auto found = answers.find(k);
          rows[i] = cell_row(*method, *cells_pvs, {regions[chosen[k]].ring, options.eye_height}, k, chosen[k], options, sampling,
                             source, found == answers.end() ? nullptr : &found->second);
          progress.advance();
        };
      });
      const auto probe = make_region_method(name, scene, method_options);
      out["runs"].push_back({{"method", name},
                             {"sampling", cell_sampling_name(sampling)},
                             {"claims_conservative", probe->claims_conservative()},
                             {"carries", probe->carries_known()},
                             {"rows", rows}});
    }
  return out;
}

nlohmann::json merge_view_cell_rows(const std::vector<nlohmann::json>& shards) {
  if (shards.empty()) throw InputError("view_cells", "", "no shards");
  nlohmann::json out = shards[0];
  out["oracle_seconds"] = 0.0;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const nlohmann::json& shard = shards[s];
    for (const char* key : {"epsilon", "eye_height", "buildings", "cells", "cells_computed", "cells_checked_by_oracle"})
      if (shard.at(key) != out.at(key))
        throw InputError("shard " + std::to_string(s), std::string("view_cells.") + key, "differs from shard 0's");
    if (shard.at("runs").size() != out.at("runs").size())
      throw InputError("shard " + std::to_string(s), "view_cells.runs", "has other runs than shard 0");
    out["oracle_seconds"] = out["oracle_seconds"].get<double>() + shard.at("oracle_seconds").get<double>();
  }
  for (std::size_t r = 0; r < out["runs"].size(); ++r) {
    std::vector<nlohmann::json> rows;
    for (const nlohmann::json& shard : shards)
      for (const nlohmann::json& row : shard["runs"][r].at("rows")) rows.push_back(row);
    std::stable_sort(rows.begin(), rows.end(),
                     [](const nlohmann::json& a, const nlohmann::json& b) { return a.at("k").get<std::size_t>() < b.at("k").get<std::size_t>(); });
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (rows[i]["k"].get<std::size_t>() != i)
        throw InputError("view_cells", "rows", "cell " + std::to_string(i) + " is missing or given twice among the shards");
    out["runs"][r]["rows"] = rows;
  }
  return out;
}

nlohmann::json view_cell_section(const nlohmann::json& raw) {
  nlohmann::json report = raw;
  report["runs"] = nlohmann::json::array();
  const double cells = std::max<double>(1, raw["cells_computed"].get<double>());
  for (const nlohmann::json& run : raw["runs"]) {
    std::vector<double> carried_ms, plain_ms, pvs, samples;
    std::uint64_t carried_tests = 0, plain_tests = 0, skipped = 0;
    std::size_t unions_differ = 0, violations = 0, viewpoints = 0;
    nlohmann::json first = nlohmann::json::array();
    for (const nlohmann::json& row : run["rows"]) {
      plain_ms.push_back(row["plain_ms"].get<double>());
      carried_ms.push_back(row["carried_ms"].get<double>());
      plain_tests += row["plain_tests"].get<std::uint64_t>();
      carried_tests += row["carried_tests"].get<std::uint64_t>();
      skipped += row["skipped"].get<std::uint64_t>();
      pvs.push_back(row["pvs"].get<double>());
      samples.push_back(row["samples"].get<double>());
      unions_differ += row["differ"].get<bool>() ? 1 : 0;
      viewpoints += row["viewpoints"].get<std::size_t>();
      violations += row["violations"].get<std::size_t>();
      for (const nlohmann::json& v : row["first"])
        if (first.size() < 5) first.push_back(v);
    }
    auto sum = [](const std::vector<double>& v) {
      double s = 0.0;
      for (double x : v) s += x;
      return s;
    };
    report["runs"].push_back({{"method", run["method"]},
                              {"sampling", run["sampling"]},
                              {"claims_conservative", run["claims_conservative"]},
                              {"carries", run["carries"]},
                              {"samples_mean", mean(samples)},
                              {"ms_per_cell_median", median(carried_ms)},
                              {"ms_per_cell_p95", percentile(carried_ms, 95.0)},
                              {"ms_per_cell_mean", mean(carried_ms)},
                              {"total_seconds", sum(carried_ms) / 1000.0},
                              {"uncarried_ms_per_cell_median", median(plain_ms)},
                              {"uncarried_total_seconds", sum(plain_ms) / 1000.0},
                              {"carry_speedup", sum(carried_ms) > 0.0 ? sum(plain_ms) / sum(carried_ms) : 1.0},
                              {"buildings_tested_per_cell", static_cast<double>(carried_tests) / cells},
                              {"uncarried_buildings_tested_per_cell", static_cast<double>(plain_tests) / cells},
                              {"accepted_untested_per_cell", static_cast<double>(skipped) / cells},
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
