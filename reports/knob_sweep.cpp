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

nlohmann::json knob_sweep(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                          const MethodOptions& options, const std::vector<KnobSweep>& sweeps, const PathVerification& main) {
  nlohmann::json rows = nlohmann::json::array();
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
        std::vector<double> ms, pvs, checked_pvs, witnessed;
        std::uint64_t misses = 0;
        for (std::size_t f = 0; f < path.frames.size(); ++f, progress.advance()) {
          const Camera& camera = path.frames[f];
          if (!method->unsupported_camera(camera).empty()) continue;
          method->set_frame(f, double(f) * frame_seconds);
          const CullResult r = method->cull(camera);
          ms.push_back(r.stats.cull_ms);
          pvs.push_back(double(r.pvs.size()));
          if (!seen_at[f]) continue;
          checked_pvs.push_back(double(r.pvs.size()));
          witnessed.push_back(double(seen_at[f]->size()));
          for (ObjectId id : *seen_at[f]) misses += std::binary_search(r.pvs.begin(), r.pvs.end(), id) ? 0 : 1;
        }
        const double w = mean(witnessed);
        rows.push_back({{"knob", sweep.knob},
                        {"value", value},
                        {"method", name},
                        {"run_setting", value == knob_value(options, sweep.knob)},
                        {"frames", ms.size()},
                        {"cull_ms_median", median(ms)},
                        {"cull_ms_p95", percentile(ms, 95)},
                        {"pvs_mean", mean(pvs)},
                        {"pvs_mean_checked_frames", mean(checked_pvs)},
                        {"witnessed_mean", w},
                        {"overestimation", w > 0 ? mean(checked_pvs) / w : 0.0},
                        {"misses", misses}});
      }
  return rows;
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
