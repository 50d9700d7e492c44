#include "reports/online_culling.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <set>

#include "engine/online_image_space/online_culling.hpp"
#include "core/elapsed.hpp"
#include "engine/online_image_space/scene_polygons.hpp"
#include "core/scene_timeline.hpp"
#include "generators/camera_paths.hpp"
#include "generators/scene_timeline_gen.hpp"
#include "generators/city.hpp"
#include "oracle/oracle.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;

nlohmann::json city_params(int grid) {
  return {{"blocks_x", grid}, {"blocks_y", grid}, {"plaza_blocks_x", 0}, {"plaza_blocks_y", 0}, {"kiosk_count", 0}};
}

// Misdrawn pixels of `pvs` (sorted): pixels whose full-scene object it lacks (pixel_oracle.hpp
// shows these are exactly the pixels where the PVS-only image differs).
std::uint64_t misdrawn(const oracle::IdImage& full, const std::vector<ObjectId>& pvs) {
  std::uint64_t n = 0;
  ObjectId last = oracle::kNoObject;
  bool last_in = true;
  for (ObjectId id : full.ids) {
    if (id == oracle::kNoObject) continue;
    if (id != last) last = id, last_in = std::binary_search(pvs.begin(), pvs.end(), id);
    n += last_in ? 0 : 1;
  }
  return n;
}

// One method along one walk.
struct Track {
  std::string method;
  std::unique_ptr<CullingMethod> owned;
  std::function<std::unique_ptr<CullingMethod>(const Scene&)> rebuild;  // for a scene change it cannot follow
  OnlineImageSpaceCulling* online = nullptr;  // when it is one
  json parameters = json::object();
  std::vector<double> ms, critical_ms, other_ms, sent, in_frustum, cr_v, cr_o, objects, pixels;
  std::vector<double> select_ms, draw_ms, shrink_ms, hierarchy_ms, mark_ms;
  std::vector<double> update_ms;  // per scene event: updated in place, or rebuilt
  std::map<std::string, std::size_t> critical_reasons;
  std::size_t error_frames = 0;
  double most = 0;
};

Track online_track(const Scene& scene, OnlineImageSpaceCulling::Variant variant, const OnlineCullingOptions& o) {
  Track t;
  auto m = std::make_unique<OnlineImageSpaceCulling>(scene, variant, o);
  m->measure_frustum(true);
  t.online = m.get();
  t.method = m->name();
  t.parameters = {{"shrink_pixels", o.shrink_pixels}, {"mask_size", o.mask_size}, {"leaf_size", o.leaf_size},
                  {"min_distance", o.min_distance}, {"max_speed", o.max_speed}, {"occluders", o.occluders},
                  {"critical_turn", o.critical_turn}, {"ground_occluder", o.ground_occluder}};
  t.owned = std::move(m);
  t.rebuild = [variant, o](const Scene& present) { return std::make_unique<OnlineImageSpaceCulling>(present, variant, o); };
  return t;
}

// Runs every track along `path`, one full-scene id buffer per frame shared by all. A path with
// a scene timeline changes the scene at its events: on-line culling updates its kd-tree in place,
// the other tracks, frustum counting and the oracle are rebuilt on the present scene.
void run_tracks(const Scene& scene, const CameraPath& path, std::vector<Track>& tracks, int threads, bool pixels = true) {
  if (!path.events.empty()) validate_timeline(path, scene, path.frames.size());
  const std::vector<std::uint32_t> polygons_of = [&] {
    const online::ScenePolygons p = online::scene_polygons(scene);
    std::vector<std::uint32_t> count(p.ids.size(), 0);
    for (std::uint32_t o : p.object) ++count[o];
    return count;
  }();
  std::vector<std::uint32_t> by_id;  // polygons per object id
  const std::vector<ObjectId> ids = scene.ids();
  for (std::size_t i = 0; i < scene.buildings.size(); ++i) {
    if (by_id.size() <= scene.buildings[i].id) by_id.resize(scene.buildings[i].id + 1, 0);
    by_id[scene.buildings[i].id] = polygons_of[i];
  }
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    if (by_id.size() <= scene.meshes[i].id) by_id.resize(scene.meshes[i].id + 1, 0);
    by_id[scene.meshes[i].id] = polygons_of[scene.buildings.size() + i];
  }
  double total = 0;
  for (std::uint32_t c : polygons_of) total += c;
  std::unique_ptr<oracle::Oracle> truth = pixels ? std::make_unique<oracle::Oracle>(scene) : nullptr;
  auto frustum = make_method("frustum", scene);
  PresentScenes presents(scene);
  std::size_t next_event = 0;
  const auto change = [&](const std::vector<ObjectId>& appear, const std::vector<ObjectId>& vanish) {
    const Scene& present = presents.apply(appear, vanish);  // rebuilt methods and the oracle refer to it
    for (Track& t : tracks) {
      const auto t0 = std::chrono::steady_clock::now();
      if (!t.owned->update_scene(present, appear, vanish)) t.owned = t.rebuild(present);
      t.update_ms.push_back(ms_since(t0));
    }
    frustum = make_method("frustum", present);
    if (truth) truth = std::make_unique<oracle::Oracle>(present);
  };
  if (const std::set<ObjectId> start = absent_at_start(path); !start.empty()) {
    change({}, std::vector<ObjectId>(start.begin(), start.end()));
    for (Track& t : tracks) t.update_ms.clear();  // the start state is no event
  }
  for (std::size_t f = 0; f < path.frames.size(); ++f) {
    const Camera& camera = path.frames[f];
    if (next_event < path.events.size() && path.events[next_event].frame == f) {
      change(path.events[next_event].appear, path.events[next_event].vanish);
      ++next_event;
    }
    double in_view = 0;
    for (ObjectId id : frustum->cull(camera).pvs) in_view += by_id[id];
    std::optional<oracle::IdImage> full;
    if (truth) full = truth->pixels().render(camera, nullptr, threads);
    for (Track& t : tracks) {
      t.owned->set_frame(f, double(f) / path.frames_per_second);
      const CullResult r = t.owned->cull(camera);
      t.ms.push_back(r.stats.cull_ms);
      t.objects.push_back(double(r.pvs.size()));
      double sent = 0;
      if (t.online) {
        const OnlineFrame& of = t.online->last_frame();
        sent = double(of.polygons_sent);
        in_view = double(of.polygons_in_frustum);  // the same count, from the method's own boxes
        (of.critical != CriticalReason::none ? t.critical_ms : t.other_ms).push_back(r.stats.cull_ms);
        if (of.critical != CriticalReason::none) ++t.critical_reasons[to_string(of.critical)];
        if (of.critical != CriticalReason::none) {
          t.select_ms.push_back(of.select_ms), t.draw_ms.push_back(of.draw_ms), t.shrink_ms.push_back(of.shrink_ms);
          t.hierarchy_ms.push_back(of.hierarchy_ms), t.mark_ms.push_back(of.mark_ms);
        }
      } else {
        for (ObjectId id : r.pvs) sent += by_id[id];
      }
      t.sent.push_back(sent);
      t.in_frustum.push_back(in_view);
      t.cr_v.push_back(in_view > 0 ? std::max(0.0, in_view - sent) / in_view : 0.0);
      t.cr_o.push_back(total > 0 ? (total - sent) / total : 0.0);
      if (full) {
        const double m = double(misdrawn(*full, r.pvs));
        t.pixels.push_back(m);
        t.error_frames += m > 0 ? 1 : 0;
        t.most = std::max(t.most, m);
      }
    }
  }
}

json track_row(const Track& t, const Track* oh, const Track* frustum) {
  json row = {{"method", t.method},
              {"parameters", t.parameters},
              {"frames", t.ms.size()},
              {"cull_ms_median", median(t.ms)},
              {"cull_ms_p95", percentile(t.ms, 95)},
              {"cull_ms_mean", mean(t.ms)},
              {"polygons_sent_mean", mean(t.sent)},
              {"polygons_in_frustum_mean", mean(t.in_frustum)},
              {"cr_v_mean", mean(t.cr_v)},
              {"cr_o_mean", mean(t.cr_o)},
              {"pvs_objects_mean", mean(t.objects)},
              {"misdrawn_pixels", std::accumulate(t.pixels.begin(), t.pixels.end(), 0.0)},
              {"misdrawn_pixels_mean", mean(t.pixels)},
              {"error_frames", t.error_frames},
              {"most_misdrawn_in_a_frame", t.most}};
  if (t.online) {
    row["critical_frames"] = t.critical_ms.size();
    row["critical_ms_median"] = median(t.critical_ms);
    row["critical_ms_p95"] = percentile(t.critical_ms, 95);
    row["other_ms_median"] = median(t.other_ms);
    row["other_ms_p95"] = percentile(t.other_ms, 95);
    row["marking_ms_mean"] = {{"select_occluders", mean(t.select_ms)}, {"draw_occluders", mean(t.draw_ms)}, {"shrink", mean(t.shrink_ms)},
                              {"hierarchy", mean(t.hierarchy_ms)}, {"mark_tree", mean(t.mark_ms)}};
  }
  if (!t.update_ms.empty())
    row["scene_events"] = {{"count", t.update_ms.size()}, {"update_ms_median", median(t.update_ms)},
                           {"update_ms_max", *std::max_element(t.update_ms.begin(), t.update_ms.end())},
                           {"in_place", t.online != nullptr}};
  if (t.online) row["critical_reasons"] = t.critical_reasons;
  if (oh && oh != &t) {
    row["time_median_over_oh_os"] = median(t.ms) / std::max(1e-9, median(oh->ms));
    row["polygons_sent_over_oh_os"] = mean(t.sent) / std::max(1e-9, mean(oh->sent));
  }
  if (frustum && frustum != &t) {
    row["time_median_over_frustum"] = median(t.ms) / std::max(1e-9, median(frustum->ms));
    row["polygons_sent_over_frustum"] = mean(t.sent) / std::max(1e-9, mean(frustum->sent));
  }
  return row;
}

Track builtin_track(const Scene& scene, const std::string& name, const MethodOptions& o) {
  Track t;
  t.method = name;
  t.owned = make_method(name, scene, o);
  t.rebuild = [name, o](const Scene& present) { return make_method(name, present, o); };
  return t;
}

}  // namespace

json online_culling_table(const OnlineTableOptions& options, const MethodOptions& method_options) {
  json out;
  out["paper"] = {{"table_1_polygons", {3657, 27437, 109748, 438992}},
                  {"table_1_fps", {{"hardware_only", {328.57, 9.26, 1.86, 0.43}}, {"view_frustum", {58.93, 14.78, 3.26, 1.17}},
                                   {"ours", {56.63, 41.27, 38.53, 20.13}}}},
                  {"long_walk", {{"frames", 11558}, {"error_frames", 158}, {"shrink_pixels", 6}}}};
  generators::StreetWalkParams walk;
  walk.frames = options.frames;
  json table = json::array();
  Scene sweep_scene;
  for (std::size_t c = 0; c < options.grids.size(); ++c) {
    const Scene scene = generators::make_city("default", options.seed, city_params(options.grids[c]));
    const CameraPath path = generators::street_walk(scene, walk, options.seed);
    std::vector<Track> tracks;
    tracks.push_back(builtin_track(scene, "frustum", method_options));
    tracks.push_back(builtin_track(scene, "oh_os_conservative", method_options));
    tracks.push_back(online_track(scene, OnlineImageSpaceCulling::Variant::published, method_options.online));
    tracks.push_back(online_track(scene, OnlineImageSpaceCulling::Variant::guarded, method_options.online));
    const std::size_t polygons = tracks[2].online->polygon_count();
    run_tracks(scene, path, tracks, options.pixel_threads);
    json rows = json::array();
    for (const Track& t : tracks) rows.push_back(track_row(t, &tracks[1], &tracks[0]));
    json city = {{"grid", options.grids[c]}, {"buildings", scene.buildings.size()}, {"polygons", polygons},
                 {"frames", path.frames.size()}, {"rows", rows}};
    // Fig. 14: CR_v and CR_o of online_is along the walk.
    city["fig_14"] = {{"cr_v", tracks[2].cr_v}, {"cr_o", tracks[2].cr_o}};
    table.push_back(city);
    if (c == options.sweep_city) sweep_scene = scene;
    std::fprintf(stderr, "online culling: city of %zu polygons done\n", polygons);
  }
  out["table_1"] = table;
  if (options.sweep_city >= options.grids.size()) return out;

  // Fig. 11 / 12 and the trade: Δ x s on the sweep city, one walk.
  const CameraPath path = generators::street_walk(sweep_scene, walk, options.seed);
  std::vector<Track> tracks;
  tracks.push_back(builtin_track(sweep_scene, "frustum", method_options));
  tracks.push_back(builtin_track(sweep_scene, "oh_os_conservative", method_options));
  std::size_t fig_12 = 0;
  for (int s : options.mask_sizes)
    for (int d : options.deltas) {
      OnlineCullingOptions o = method_options.online;
      o.mask_size = s;
      o.shrink_pixels = d;
      if (s == method_options.online.mask_size && d == 6) fig_12 = tracks.size();
      tracks.push_back(online_track(sweep_scene, OnlineImageSpaceCulling::Variant::published, o));
    }
  for (int d : options.deltas) {
    OnlineCullingOptions o = method_options.online;
    o.shrink_pixels = d;
    tracks.push_back(online_track(sweep_scene, OnlineImageSpaceCulling::Variant::guarded, o));
  }
  run_tracks(sweep_scene, path, tracks, options.pixel_threads);
  json sweep = json::array();
  for (const Track& t : tracks) sweep.push_back(track_row(t, &tracks[1], &tracks[0]));
  out["delta_sweep"] = {{"city_grid", options.grids[options.sweep_city]}, {"frames", path.frames.size()}, {"rows", sweep}};
  if (fig_12 > 0) out["fig_12_misdrawn_per_frame"] = {{"method", "online_is"}, {"shrink_pixels", 6}, {"pixels", tracks[fig_12].pixels}};
  // The trade, plot-ready: (time median, misdrawn pixels per frame) per online configuration.
  json trade = json::array();
  for (const Track& t : tracks)
    trade.push_back({{"method", t.method}, {"shrink_pixels", t.parameters.value("shrink_pixels", json())},
                     {"mask_size", t.parameters.value("mask_size", json())}, {"cull_ms_median", median(t.ms)},
                     {"cull_ms_p95", percentile(t.ms, 95)}, {"misdrawn_pixels_mean", mean(t.pixels)},
                     {"error_frames", t.error_frames}, {"polygons_sent_mean", mean(t.sent)}});
  out["trade"] = trade;
  std::fprintf(stderr, "online culling: sweep done\n");

  // The long walk at the defaults (Δ = 6 unless the knobs say otherwise).
  if (options.long_frames > 0) {
    generators::StreetWalkParams long_walk;
    long_walk.frames = options.long_frames;
    const CameraPath long_path = generators::street_walk(sweep_scene, long_walk, options.seed);
    std::vector<Track> two;
    two.push_back(online_track(sweep_scene, OnlineImageSpaceCulling::Variant::published, method_options.online));
    two.push_back(online_track(sweep_scene, OnlineImageSpaceCulling::Variant::guarded, method_options.online));
    run_tracks(sweep_scene, long_path, two, options.pixel_threads);
    json rows = json::array();
    for (const Track& t : two) {
      json r = track_row(t, nullptr, nullptr);
      std::vector<json> frames;
      for (std::size_t f = 0; f < t.pixels.size(); ++f)
        if (t.pixels[f] > 0) frames.push_back({{"frame", f}, {"misdrawn_pixels", t.pixels[f]}});
      r["error_frame_list"] = frames;
      rows.push_back(r);
    }
    out["long_walk"] = {{"frames", long_path.frames.size()}, {"rows", rows}};
  }

  // Section 6: the same walk while buildings vanish and come back (a seeded scene timeline).
  if (options.dynamic_every > 0) {
    CameraPath dynamic_path = path;
    generators::TimelineParams timeline;
    timeline.every = options.dynamic_every;
    timeline.churn = options.dynamic_churn;
    timeline.late = options.dynamic_churn;
    dynamic_path.events = generators::scene_timeline(sweep_scene, dynamic_path.frames.size(), timeline, options.seed);
    std::vector<Track> four;
    four.push_back(builtin_track(sweep_scene, "frustum", method_options));
    four.push_back(builtin_track(sweep_scene, "oh_os_conservative", method_options));
    four.push_back(online_track(sweep_scene, OnlineImageSpaceCulling::Variant::published, method_options.online));
    four.push_back(online_track(sweep_scene, OnlineImageSpaceCulling::Variant::guarded, method_options.online));
    run_tracks(sweep_scene, dynamic_path, four, options.pixel_threads);
    json rows = json::array();
    for (const Track& t : four) rows.push_back(track_row(t, &four[1], &four[0]));
    out["dynamic_walk"] = {{"city_grid", options.grids[options.sweep_city]}, {"frames", dynamic_path.frames.size()},
                           {"timeline", {{"every", timeline.every}, {"churn", timeline.churn}, {"late", timeline.late}}},
                           {"events", dynamic_path.events.size()}, {"rows", rows}};
    std::fprintf(stderr, "online culling: dynamic walk done\n");
  }
  return out;
}

std::string online_culling_text(const json& t) {
  std::string out = "On-line image-space culling (Wang et al. 2001), Table 1 in kind:\n";
  char line[320];
  std::snprintf(line, sizeof line, "%9s %-18s %8s %8s %9s %9s %10s %6s %6s %8s %7s %8s\n", "polygons", "method", "ms_med", "ms_p95", "crit_med",
                "other_med", "sent", "CR_v", "CR_o", "x_OH_t", "errfr", "misdrawn");
  out += line;
  for (const json& city : t.value("table_1", json::array()))
    for (const json& r : city["rows"]) {
      std::snprintf(line, sizeof line, "%9zu %-18s %8.3f %8.3f %9.3f %9.3f %10.0f %6.3f %6.3f %8.2f %7zu %8.0f\n",
                    city["polygons"].get<std::size_t>(), r["method"].get<std::string>().c_str(), r["cull_ms_median"].get<double>(),
                    r["cull_ms_p95"].get<double>(), r.value("critical_ms_median", 0.0), r.value("other_ms_median", 0.0),
                    r["polygons_sent_mean"].get<double>(), r["cr_v_mean"].get<double>(), r["cr_o_mean"].get<double>(),
                    r.value("time_median_over_oh_os", 1.0), r["error_frames"].get<std::size_t>(), r["misdrawn_pixels"].get<double>());
      out += line;
    }
  if (t.contains("delta_sweep")) {
    out += "Δ sweep and the trade (city of grid " + std::to_string(t["delta_sweep"]["city_grid"].get<int>()) + "):\n";
    std::snprintf(line, sizeof line, "%-18s %5s %5s %8s %8s %10s %6s %7s %10s\n", "method", "Δ", "s", "ms_med", "ms_p95", "sent", "crit",
                  "errfr", "px/frame");
    out += line;
    for (const json& r : t["delta_sweep"]["rows"]) {
      const json& p = r["parameters"];
      std::snprintf(line, sizeof line, "%-18s %5s %5s %8.3f %8.3f %10.0f %6zu %7zu %10.3f\n", r["method"].get<std::string>().c_str(),
                    p.contains("shrink_pixels") ? std::to_string(p["shrink_pixels"].get<int>()).c_str() : "-",
                    p.contains("mask_size") ? std::to_string(p["mask_size"].get<int>()).c_str() : "-", r["cull_ms_median"].get<double>(),
                    r["cull_ms_p95"].get<double>(), r["polygons_sent_mean"].get<double>(), r.value("critical_frames", std::size_t(0)),
                    r["error_frames"].get<std::size_t>(), r["misdrawn_pixels_mean"].get<double>());
      out += line;
    }
  }
  if (t.contains("long_walk"))
    for (const json& r : t["long_walk"]["rows"]) {
      std::snprintf(line, sizeof line, "long walk, %s: errors in %zu of %zu frames (paper: 158 of 11,558 at Δ = 6); at most %.0f pixels\n",
                    r["method"].get<std::string>().c_str(), r["error_frames"].get<std::size_t>(), t["long_walk"]["frames"].get<std::size_t>(),
                    r["most_misdrawn_in_a_frame"].get<double>());
      out += line;
    }
  if (t.contains("dynamic_walk")) {
    const json& d = t["dynamic_walk"];
    out += "Dynamic walk (" + std::to_string(d["events"].get<std::size_t>()) + " scene events, " +
           d["timeline"].dump() + "):\n";
    std::snprintf(line, sizeof line, "%-18s %8s %8s %10s %10s %10s %7s %8s\n", "method", "ms_med", "ms_p95", "sent", "upd_med", "upd_max",
                  "errfr", "misdrawn");
    out += line;
    for (const json& r : d["rows"]) {
      const json& e = r.value("scene_events", json::object());
      std::snprintf(line, sizeof line, "%-18s %8.3f %8.3f %10.0f %10.3f %10.3f %7zu %8.0f\n", r["method"].get<std::string>().c_str(),
                    r["cull_ms_median"].get<double>(), r["cull_ms_p95"].get<double>(), r["polygons_sent_mean"].get<double>(),
                    e.value("update_ms_median", 0.0), e.value("update_ms_max", 0.0), r["error_frames"].get<std::size_t>(),
                    r["misdrawn_pixels"].get<double>());
      out += line;
    }
  }
  return out;
}

}  // namespace cullcheck
