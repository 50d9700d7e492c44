#include "reports/knob_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "core/errors.hpp"
#include "core/progress.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

struct Knob {
  const char* name;
  bool integer;
  std::vector<std::string> methods;
};

const std::vector<Knob>& knobs() {
  static const std::vector<Knob> all = {
      {"horizon_bins", true, {"oh_is", "oh_os_thesis", "oh_os_conservative", "delta_h_thesis", "delta_h_guarded"}},
      {"quadtree_leaf_size", true, {"frustum", "oh_is", "oh_os_thesis", "oh_os_conservative", "delta_h_thesis", "delta_h_guarded"}},
      {"delta_radius", false, {"delta_h_guarded"}},
      {"delta_height", false, {"delta_h_guarded"}},
      {"delta_turn", false, {"delta_h_guarded"}}};
  return all;
}

const Knob* find_knob(const std::string& name) {
  for (const Knob& k : knobs())
    if (name == k.name) return &k;
  return nullptr;
}

double knob_value(const MethodOptions& o, const std::string& knob) {
  if (knob == "horizon_bins") return o.horizon_bins;
  if (knob == "quadtree_leaf_size") return o.quadtree_leaf_size;
  if (knob == "delta_radius") return o.delta_radius;
  if (knob == "delta_height") return o.delta_height;
  return o.delta_turn;
}

}  // namespace

KnobSweep parse_knob_sweep(const std::string& text) {
  const std::size_t eq = text.find('=');
  std::string names;
  for (const Knob& k : knobs()) names += (names.empty() ? "" : ", ") + std::string(k.name);
  const Knob* knob = eq == std::string::npos ? nullptr : find_knob(text.substr(0, eq));
  if (!knob) throw InputError("flag", "knob-sweep", "'" + text + "' is not KNOB=V1,V2,... with KNOB one of " + names);
  KnobSweep out{knob->name, {}};
  for (std::size_t start = eq + 1; start <= text.size();) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    std::size_t used = 0;
    double v = NAN;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(v) || v <= 0.0)
      throw InputError("flag", "knob-sweep", out.knob + ": '" + item + "' is not a positive number");
    if (knob->integer && (v != std::floor(v) || v > 1000000.0))
      throw InputError("flag", "knob-sweep", out.knob + ": '" + item + "' is not a whole number from 1 to 1000000");
    // The horizons take a power of two from 4 (OH(IS)'s least) up; asked here, not after the run.
    if (out.knob == "horizon_bins" && (v < 4.0 || (std::uint32_t(v) & (std::uint32_t(v) - 1)) != 0))
      throw InputError("flag", "knob-sweep", "horizon_bins: '" + item + "' is not a power of two from 4 to 524288");
    if (out.knob == "delta_turn" && v > 1.5) throw InputError("flag", "knob-sweep", "delta_turn: '" + item + "' is above 1.5 rad");
    out.values.push_back(v);
    start = comma + 1;
  }
  return out;
}

std::vector<std::string> methods_affected_by(const std::string& knob) {
  const Knob* k = find_knob(knob);
  return k ? k->methods : std::vector<std::string>{};
}

MethodOptions with_knob(MethodOptions o, const std::string& knob, double value) {
  if (knob == "horizon_bins") o.horizon_bins = std::uint32_t(value);
  else if (knob == "quadtree_leaf_size") o.quadtree_leaf_size = std::uint32_t(value);
  else if (knob == "delta_radius") o.delta_radius = value;
  else if (knob == "delta_height") o.delta_height = value;
  else if (knob == "delta_turn") o.delta_turn = value;
  return o;
}

std::vector<KnobRow> knob_sweep_rows(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                                     const MethodOptions& options, const std::vector<KnobSweep>& sweeps, const PathVerification& main) {
  std::vector<KnobRow> rows;
  // What the main run's oracle saw, by frame number.
  std::vector<const std::vector<ObjectId>*> seen_at(path.frames.size(), nullptr);
  for (std::size_t k = 0; k < main.checked_frames.size(); ++k)
    if (main.checked_frames[k] < seen_at.size()) seen_at[main.checked_frames[k]] = &main.checked_visible[k];
  const double frame_seconds = path.frames_per_second > 0 ? 1.0 / path.frames_per_second : 0.0;
  std::size_t runs = 0;
  for (const KnobSweep& sweep : sweeps)
    for (const std::string& m : methods_affected_by(sweep.knob))
      runs += std::count(methods.begin(), methods.end(), m) > 0 ? sweep.values.size() : 0;
  Progress progress("knob sweep", runs * path.frames.size(), "frames");
  for (const KnobSweep& sweep : sweeps)
    for (double value : sweep.values)
      for (const std::string& name : methods_affected_by(sweep.knob)) {
        if (std::find(methods.begin(), methods.end(), name) == methods.end()) continue;
        if (!method_unavailable_reason(name, scene).empty()) continue;
        const auto method = make_method(name, scene, with_knob(options, sweep.knob, value));
        KnobRow row;
        row.knob = sweep.knob;
        row.value = value;
        row.method = name;
        row.run_setting = value == knob_value(options, sweep.knob);
        for (std::size_t f = 0; f < path.frames.size(); ++f, progress.advance()) {
          const Camera& camera = path.frames[f];
          if (!method->unsupported_camera(camera).empty()) continue;
          method->set_frame(f, double(f) * frame_seconds);
          const CullResult r = method->cull(camera);
          row.cull_ms.push_back(r.stats.cull_ms);
          row.pvs.push_back(double(r.pvs.size()));
          if (!seen_at[f]) continue;
          row.checked_frames.push_back(f);
          row.checked_pvs.push_back(double(r.pvs.size()));
          row.witnessed.push_back(double(seen_at[f]->size()));
          for (ObjectId id : *seen_at[f]) row.misses += std::binary_search(r.pvs.begin(), r.pvs.end(), id) ? 0 : 1;
        }
        rows.push_back(std::move(row));
      }
  return rows;
}

nlohmann::json knob_sweep_json(const std::vector<KnobRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const KnobRow& row : rows) {
    const double w = mean(row.witnessed);
    out.push_back({{"knob", row.knob},
                   {"value", row.value},
                   {"method", row.method},
                   {"run_setting", row.run_setting},
                   {"frames", row.cull_ms.size()},
                   {"cull_ms_median", median(row.cull_ms)},
                   {"cull_ms_p95", percentile(row.cull_ms, 95)},
                   {"pvs_mean", mean(row.pvs)},
                   {"pvs_mean_checked_frames", mean(row.checked_pvs)},
                   {"witnessed_mean", w},
                   {"overestimation", w > 0 ? mean(row.checked_pvs) / w : 0.0},
                   {"misses", row.misses}});
  }
  return out;
}

nlohmann::json knob_sweep(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                          const MethodOptions& options, const std::vector<KnobSweep>& sweeps, const PathVerification& main) {
  return knob_sweep_json(knob_sweep_rows(scene, path, methods, options, sweeps, main));
}

nlohmann::json knob_row_to_raw_json(const KnobRow& r) {
  return {{"knob", r.knob},       {"method", r.method},       {"value", r.value},         {"run_setting", r.run_setting},
          {"cull_ms", r.cull_ms}, {"pvs", r.pvs},             {"checked_frames", r.checked_frames},
          {"checked_pvs", r.checked_pvs}, {"witnessed", r.witnessed}, {"misses", r.misses}};
}

KnobRow knob_row_from_raw_json(const nlohmann::json& j, const std::string& what) {
  KnobRow r;
  try {
    r.knob = j.at("knob").get<std::string>();
    r.method = j.at("method").get<std::string>();
    r.value = j.at("value").get<double>();
    r.run_setting = j.at("run_setting").get<bool>();
    r.cull_ms = j.at("cull_ms").get<std::vector<double>>();
    r.pvs = j.at("pvs").get<std::vector<double>>();
    r.checked_frames = j.at("checked_frames").get<std::vector<std::size_t>>();
    r.checked_pvs = j.at("checked_pvs").get<std::vector<double>>();
    r.witnessed = j.at("witnessed").get<std::vector<double>>();
    r.misses = j.at("misses").get<std::uint64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(what, "", std::string("is not a knob-sweep row: ") + e.what());
  }
  if (r.checked_pvs.size() != r.checked_frames.size() || r.witnessed.size() != r.checked_frames.size())
    throw InputError(what, "checked_frames", "has not one PVS and one witnessed size per checked frame");
  return r;
}

std::string knob_sweep_table(const nlohmann::json& rows) {
  std::string out = "knob sweep (PVS held to the main run's oracle at its checked frames):\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-20s %10s %-20s %9s %9s %8s %7s\n", "knob", "value", "method", "ms_med", "pvs_mean", "overest",
                "misses");
  out += line;
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "  %-20s %10g %-20s %9.3f %9.1f %8.2f %7llu%s\n", r["knob"].get<std::string>().c_str(),
                  r["value"].get<double>(), r["method"].get<std::string>().c_str(), r["cull_ms_median"].get<double>(),
                  r["pvs_mean"].get<double>(), r["overestimation"].get<double>(),
                  static_cast<unsigned long long>(r["misses"].get<std::uint64_t>()), r["run_setting"].get<bool>() ? "  (the run's)" : "");
    out += line;
  }
  return out;
}

}  // namespace cullcheck
