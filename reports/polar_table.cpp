#include "reports/polar_table.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "engine/polar_diagram/polar_diagram.hpp"
#include "engine/polar_diagram/visibility_fan.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/plan_scenes.hpp"
#include "oracle/exact_2d.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

template <class F>
double median_ms(int repeats, F&& build) {
  std::vector<double> t;
  for (int i = 0; i < std::max(1, repeats); ++i) {
    const auto start = Clock::now();
    build();
    t.push_back(ms_since(start));
  }
  return median(t);
}

// One walk, one view: fan against CGAL frame by frame.
json walk_row(const Scene& scene, const polar::VisibilityFan& fan, const oracle::ExactVisibility2d& exact,
              const std::vector<Camera>& frames, double hfov_deg) {
  std::vector<double> fan_ms, cgal_ms, rays_per_2k;
  std::uint64_t compared = 0, skipped = 0, mismatches = 0, rays = 0, visible = 0, edges = 0, splits = 0;
  json first_mismatch;
  for (Camera c : frames) {
    c.pitch = c.roll = 0.0;
    c.hfov = hfov_deg >= 360 ? kTwoPi : hfov_deg * kPi / 180;
    auto start = Clock::now();
    oracle::Exact2dResult truth;
    try {
      truth = exact.visible(c);
    } catch (const InputError&) {
      ++skipped;  // the eye in or on a footprint, or a building not taller than the eye
      continue;
    }
    cgal_ms.push_back(ms_since(start));
    start = Clock::now();
    const polar::FanResult got = fan.visible(plan(c.position), polar::plan_wedge(c));
    fan_ms.push_back(ms_since(start));
    ++compared;
    if (got.visible != truth.visible) {
      if (mismatches++ == 0)
        first_mismatch = {{"camera", {c.position.x, c.position.y, c.position.z, c.yaw, c.hfov}},
                          {"fan", got.visible.size()}, {"cgal", truth.visible.size()}};
    }
    rays += got.stats.rays;
    visible += got.visible.size();
    edges += got.visible_edges.size();
    splits += got.stats.wedge_splits;
    if (!got.visible.empty()) rays_per_2k.push_back(static_cast<double>(got.stats.rays) / (2.0 * static_cast<double>(got.visible.size())));
  }
  const double n = std::max<double>(1.0, static_cast<double>(compared));
  json row = {{"scene", scene.provenance.generator},
              {"hfov_deg", hfov_deg},
              {"frames_compared", compared},
              {"frames_skipped", skipped},
              {"mismatches", mismatches},
              {"fan_ms_median", median(fan_ms)},
              {"fan_ms_p95", percentile(fan_ms, 95)},
              {"cgal_ms_median", median(cgal_ms)},
              {"cgal_ms_p95", percentile(cgal_ms, 95)},
              {"cgal_over_fan_median", median(fan_ms) > 0 ? median(cgal_ms) / median(fan_ms) : 0.0},
              {"visible_mean", static_cast<double>(visible) / n},
              {"visible_edges_mean", static_cast<double>(edges) / n},
              {"rays_mean", static_cast<double>(rays) / n},
              {"rays_per_2k_median", median(rays_per_2k)},
              {"rays_per_2k_p95", percentile(rays_per_2k, 95)},
              {"wedge_splits_mean", static_cast<double>(splits) / n}};
  if (mismatches) row["first_mismatch"] = first_mismatch;
  return row;
}

json city_rows(const Scene& built, const std::vector<Camera>& frames, const PolarTableOptions& o, json& growth) {
  // Both sides work on footprints alone; CGAL's side refuses a building not taller than the
  // eye on principle (the default city has kiosks), so every building is raised to 100 m here.
  Scene scene = built;
  for (Building& b : scene.buildings) b.height = std::max(b.height, 100.0);
  const std::vector<Vec2> vertices = polar::footprint_vertices(scene);
  json city = {{"scene", scene.provenance.generator}, {"buildings", scene.buildings.size()}, {"vertices", vertices.size()}};
  city["diagrams_ms"] = median_ms(o.build_repeats, [&] { const polar::PolarDiagrams d(vertices); });
  city["one_diagram_ms"] = median_ms(o.build_repeats, [&] { const polar::PolarDiagram d(vertices, polar::DiagramKind::east_plus); });
  city["fan_build_ms"] = median_ms(o.build_repeats, [&] { const polar::VisibilityFan f(scene); });
  const polar::VisibilityFan fan(scene);
  const auto cgal_start = Clock::now();  // CGAL's build is timed once, on the structure the walks use
  const oracle::ExactVisibility2d exact(scene);
  city["cgal_build_ms"] = ms_since(cgal_start);
  city["walks"] = json::array({walk_row(scene, fan, exact, frames, 90), walk_row(scene, fan, exact, frames, 360)});
  // Query time against k at fixed n: the same eyes with views of 10 to 360 degrees.
  struct Sample {
    std::size_t k;
    double ms;
    std::uint64_t rays;
  };
  std::vector<Sample> samples;
  for (std::size_t i = 0; i < frames.size(); i += 4)
    for (double deg : {10.0, 30.0, 90.0, 180.0, 360.0}) {
      Camera c = frames[i];
      c.pitch = c.roll = 0.0;
      c.hfov = deg >= 360 ? kTwoPi : deg * kPi / 180;
      const auto start = Clock::now();
      const polar::FanResult r = fan.visible(plan(c.position), polar::plan_wedge(c));
      samples.push_back({r.visible.size(), ms_since(start), r.stats.rays});
    }
  const std::size_t bins[][2] = {{0, 0}, {1, 5}, {6, 10}, {11, 20}, {21, 40}, {41, 80}, {81, 160}, {161, 320}, {321, 1u << 30}};
  json table = json::array();
  for (const auto& bin : bins) {
    std::vector<double> ms, rays;
    for (const Sample& s : samples)
      if (s.k >= bin[0] && s.k <= bin[1]) ms.push_back(s.ms), rays.push_back(static_cast<double>(s.rays));
    if (ms.empty()) continue;
    table.push_back({{"k_from", bin[0]}, {"k_to", bin[1]}, {"queries", ms.size()}, {"fan_ms_median", median(ms)}, {"rays_median", median(rays)}});
  }
  growth[scene.provenance.generator] = table;
  return city;
}

}  // namespace

json polar_diagram_table(const PolarTableOptions& o) {
  json out = {{"frames", o.frames}, {"seed", o.seed}, {"cities", json::array()}, {"k_growth", json::object()}};
  generators::StreetWalkParams walk;
  walk.frames = o.frames;
  const Scene city = generators::default_city(o.seed);
  out["cities"].push_back(city_rows(city, generators::street_walk(city, walk, o.seed).frames, o, out["k_growth"]));
  const Scene paper = generators::star_block_city({}, o.seed);
  const std::vector<Camera> frames = generators::star_block_walk({}, o.frames);
  out["cities"].push_back(city_rows(paper, frames, o, out["k_growth"]));
  return out;
}

std::uint64_t polar_table_mismatches(const json& table) {
  std::uint64_t n = 0;
  if (table.contains("cities"))
    for (const json& c : table["cities"])
      for (const json& w : c["walks"]) n += w.value("mismatches", std::uint64_t{0});
  return n;
}

std::string polar_diagram_table_text(const json& t) {
  std::ostringstream s;
  char line[512];
  s << "Polar diagrams (Ortega et al.) against CGAL's exact visibility polygon\n";
  for (const json& c : t["cities"]) {
    std::snprintf(line, sizeof line, "  %s: %d buildings, %d vertices; four diagrams %.1f ms (one %.1f ms), fan grids %.1f ms, CGAL %.1f ms\n",
                  c["scene"].get<std::string>().c_str(), c["buildings"].get<int>(), c["vertices"].get<int>(), c["diagrams_ms"].get<double>(),
                  c["one_diagram_ms"].get<double>(), c["fan_build_ms"].get<double>(), c["cgal_build_ms"].get<double>());
    s << line;
    for (const json& w : c["walks"]) {
      std::snprintf(line, sizeof line,
                    "    %3.0f deg: %d frames (%d skipped), %d mismatches; fan %.3f ms (p95 %.3f), CGAL %.3f ms (p95 %.3f): %.1fx; "
                    "k %.1f, edges %.1f, rays %.1f (%.2f x 2k median)\n",
                    w["hfov_deg"].get<double>(), w["frames_compared"].get<int>(), w["frames_skipped"].get<int>(), w["mismatches"].get<int>(),
                    w["fan_ms_median"].get<double>(), w["fan_ms_p95"].get<double>(), w["cgal_ms_median"].get<double>(),
                    w["cgal_ms_p95"].get<double>(), w["cgal_over_fan_median"].get<double>(), w["visible_mean"].get<double>(),
                    w["visible_edges_mean"].get<double>(), w["rays_mean"].get<double>(), w["rays_per_2k_median"].get<double>());
      s << line;
    }
  }
  for (const auto& [scene, bins] : t["k_growth"].items()) {
    s << "  query time by visible count k (" << scene << "):";
    for (const json& b : bins) {
      std::snprintf(line, sizeof line, " k %zu-%zu: %.3f ms;", b["k_from"].get<std::size_t>(), b["k_to"].get<std::size_t>(),
                    b["fan_ms_median"].get<double>());
      s << line;
    }
    s << "\n";
  }
  return s.str();
}

}  // namespace cullcheck
