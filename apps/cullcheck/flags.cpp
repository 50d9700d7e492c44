#include "apps/cullcheck/flags.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <sstream>
#include <thread>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "engine/shrinking/view_cell.hpp"
#include "engine/vbaoi/navigation_graph.hpp"
#include "generators/camera_paths.hpp"
#include "oracle/oracle.hpp"
#include "reports/verification.hpp"

namespace cullcheck::cli {

void SceneFlags::add(CLI::App& app) {
  app.add_option("--generator", source.generator,
                 "City generator (manhattan, plaza, default, scatter, irregular, thesis, openings, kept)")
      ->capture_default_str();
  app.add_option("--seed", source.seed, "Generator seed")->capture_default_str();
  app.add_option("--params", source.parameters_json, "Generator parameters as JSON, overlaid on its defaults")
      ->capture_default_str();
  app.add_option("--scene", source.file,
                 "Read the scene from this file instead of generating it: cullcheck scene JSON, glTF 2.0 (.glb, .gltf), OBJ, "
                 "or building footprints with heights: GeoJSON (.geojson) or CityJSON (.json, .city.json; see --height-attribute, "
                 "--storeys-attribute, --crs)");
  const std::map<std::string, formats::IdSource> id_sources{{"node", formats::IdSource::node}, {"mesh", formats::IdSource::mesh}};
  app.add_option("--mesh-ids", source.mesh_ids, "glTF scenes: one object per node (node, the default) or per glTF mesh (mesh)")
      ->transform(CLI::CheckedTransformer(id_sources, CLI::ignore_case).description(""))
      ->type_name("node|mesh");
  const std::map<std::string, formats::UpAxis> axes{{"y", formats::UpAxis::y}, {"z", formats::UpAxis::z}};
  app.add_option("--obj-up", source.obj_up, "OBJ scenes: the file's up axis, y or z (default z)")
      ->transform(CLI::CheckedTransformer(axes, CLI::ignore_case).description(""))
      ->type_name("y|z");
  formats::FootprintOptions& f = source.footprints;
  app.add_option("--height-attribute", f.height_attribute,
                 "Footprint files (GeoJSON): the property holding a building's height in metres (default: height)");
  app.add_option("--storeys-attribute", f.storeys_attribute,
                 "Footprint files: the property holding a storey count instead, times --storey-height");
  app.add_option("--storey-height", f.storey_height, "Footprint files: metres a storey")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 1e3));
  app.add_option("--missing-height", f.missing_height,
                 "Footprint files: height (m) for a feature without a usable one (default: skip it; the import counts it)")
      ->check(CLI::Range(1e-3, 1e4));
  app.add_option("--crs", f.crs,
                 "Footprint files: the coordinates' CRS (e.g. EPSG:26919), overriding the file's; local = plan metres as "
                 "they are (default: the file's crs member, else WGS84 longitude/latitude)");
  app.add_flag("--cityjson-meshes", f.cityjson_meshes,
               "CityJSON: keep each Building and BuildingPart as a mesh object (its highest-LoD surfaces, triangulated) "
               "instead of a footprint prism: the oracle, frustum culling and subjects see the LoD2 shapes, 2.5D methods are "
               "skipped");
  app.add_flag("--cityjson-buildings", f.cityjson_buildings,
               "CityJSON: as --cityjson-meshes, but a Building and its BuildingParts make one mesh object (the building's)");
}

void CoordinateFlags::add(CLI::App& app, const std::string& applies_to) {
  app.add_option("--coordinates", frame,
                 "Frame of " + applies_to +
                     " JSON that does not say its own (a file's \"coordinates\": \"world\"|\"local\" is read as it "
                     "says; a flag that contradicts it is an error): local = scene-local metres, the default, as "
                     "cullcheck writes them; world = local + the scene's origin (far scenes are rebased on load; the "
                     "origin is printed). An input whose every eye lies outside the scene's bounds grown by "
                     "max(1 km, its size) is refused")
      ->check(CLI::IsMember({"world", "local"}).description(""))
      ->type_name("world|local");
}

std::optional<CoordinateFrame> CoordinateFlags::fallback() const {
  if (frame.empty()) return std::nullopt;
  return parse_coordinate_frame(frame);
}

CoordinateConversion CoordinateFlags::localise(CameraPath& path, const Scene& scene, const std::string& file) const {
  CoordinateConversion how = to_scene_local(path, scene, fallback(), file);
  require_an_eye_near_the_scene(path, scene, how, file);
  return how;
}

Camera CoordinateFlags::camera(const Scene& scene, const std::string& json, const std::string& flag, CoordinateConversion* how) const {
  CameraPath one = single_camera_from_json_text(json, flag);
  const CoordinateConversion c = localise(one, scene, flag);
  if (how) *how = c;
  return one.frames.front();
}

std::string CoordinateFlags::replay_flag() const { return frame.empty() ? "" : " --coordinates " + frame; }

void PathFlags::add(CLI::App& app, int default_frames) {
  params = nlohmann::json{{"frames", default_frames}}.dump();
  app.add_option("--path-kind", kind, "Camera path generator (street_walk, fly_through, moves)")->capture_default_str();
  app.add_option("--path-seed", seed, "Camera path seed")->capture_default_str();
  app.add_option("--path-params", params, "Camera path parameters as JSON")->capture_default_str();
  app.add_option("--path", file, "Read the camera path from this JSON file instead (see --coordinates)");
  coordinates.add(app, "--path and --camera");
}

std::string PathFlags::replay_flags() const {
  if (!file.empty()) return "--path " + shell_quote(file) + coordinates.replay_flag();
  return "--path-kind " + kind + " --path-seed " + std::to_string(seed) + " --path-params " + shell_quote(params);
}

CameraPath PathFlags::load(const Scene& scene, CoordinateConversion* how) const {
  if (!file.empty()) {
    CameraPath path = read_path_file(file);
    const CoordinateConversion c = coordinates.localise(path, scene, file);
    if (how) *how = c;
    return path;
  }
  if (!coordinates.frame.empty())
    throw InputError("command line", "--coordinates", "applies to cameras read from JSON (--path, --camera); generated paths are scene-local");
  CameraPath path = generators::make_camera_path(kind, scene, seed, parse_json_flag(params, "path-params"));
  path.coordinates = CoordinateFrame::local;
  path.origin = scene.origin;
  if (how) *how = CoordinateConversion{CoordinateFrame::local, "generator", scene.origin, std::nullopt, false};
  return path;
}

CameraPath PathFlags::load(const Scene& scene, const std::string& camera_json, CoordinateConversion* how) const {
  if (camera_json.empty()) return load(scene, how);
  CameraPath path = single_camera_from_json_text(camera_json, "--camera");
  const CoordinateConversion c = coordinates.localise(path, scene, "--camera");
  if (how) *how = c;
  return path;
}

std::string PathFlags::source_name(const std::string& camera_json) const {
  if (!camera_json.empty()) return "--camera";
  if (!file.empty()) return file;
  return "the " + kind + " path";
}

void add_shard_flag(CLI::App& app, Shard& shard, const std::string& what) {
  app.add_option_function<std::string>("--shard", [&shard](const std::string& text) { shard = parse_shard(text); }, what)
      ->type_name("K/N")
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              parse_shard(text);
              return std::string();
            } catch (const InputError& e) {
              return e.problem();
            }
          },
          "K/N"));
}

nlohmann::json parse_json_flag(const std::string& text, const std::string& field) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError("command line", field, std::string("is not valid JSON: ") + e.what());
  }
}

void SamplingFlags::add(CLI::App& app) {
  app.add_option("--spacing", sampling.spacing_m, "Oracle: surface sample spacing in metres")->capture_default_str();
  app.add_option("--face-grid", sampling.face_grid, "Oracle: least grid intervals per face")->capture_default_str();
  app.add_option("--frustum-resolution", sampling.frustum_resolution, "Oracle: stratified rays per image row")
      ->capture_default_str();
  app.add_flag("--oracle-every-ray{false}", sampling.stop_when_witnessed,
               "Oracle: cast every surface-sample ray, also those of objects already witnessed (default: stop at an object's "
               "kept witnesses)");
  sampling.threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 1024u));
  app.add_option("--oracle-threads", sampling.threads,
                 "Oracle: threads casting rays (default: every core); its answers are the same for any number")
      ->check(CLI::Range(1, 1024));
}

void MethodFlags::add(CLI::App& app) {
  app.add_option("--horizon-bins", options.horizon_bins, "Occlusion horizon bins over 360 degrees (power of two)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](const std::string& text) {
            // What the horizons take (occlusion_horizon.cpp; OH(IS) needs at least 4), said before any run.
            const unsigned long v = std::strtoul(text.c_str(), nullptr, 10);
            return v >= 4 && v <= (1ul << 22) && (v & (v - 1)) == 0 ? std::string() : "must be a power of two from 4 to 4194304";
          },
          "POWER_OF_TWO"));
  app.add_option("--leaf-size", options.quadtree_leaf_size, "Most buildings in a quadtree leaf")
      ->capture_default_str()
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--delta-radius", options.delta_radius, "Guarded ΔH: plan radius (m) of the motion region a certificate covers")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e4));
  app.add_option("--delta-height", options.delta_height, "Guarded ΔH: height range (m) of the motion region")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e4));
  app.add_option("--delta-turn", options.delta_turn, "Guarded ΔH: turn (rad, |Δyaw|+|Δpitch|+|Δroll|) the region allows")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.5));
  app.add_flag("--delta-no-prefetch{false}", options.delta_prefetch,
               "Guarded ΔH: certify the next motion region on the critical path, not ahead on a second thread (same PVS)");
  OnlineCullingOptions& o = options.online;
  app.add_option("--online-shrink", o.shrink_pixels, "On-line image-space culling: Δ, pixels the occluders' image is eroded by (plus one)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  app.add_option("--online-mask-size", o.mask_size, "On-line image-space culling: s, mask pixels across the horizontal field of view")
      ->capture_default_str()
      ->check(CLI::Range(4, 2048));
  app.add_option("--online-leaf-size", o.leaf_size, "On-line image-space culling: ρ, most polygons in a kd-tree leaf")
      ->capture_default_str()
      ->check(CLI::Range(1u, 1000000u));
  app.add_option("--online-min-distance", o.min_distance, "On-line image-space culling: D, no occluder nearer than this (m)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--online-max-speed", o.max_speed, "On-line image-space culling: V, the walker's greatest speed (m/s); stamps last δ/V")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e6));
  app.add_option("--online-occluders", o.occluders, "On-line image-space culling: R, occluder polygons per critical frame")
      ->capture_default_str()
      ->check(CLI::Range(0u, 100000000u));
  app.add_option("--online-mask-block", o.mask_block, "On-line image-space culling: b, each coarser mask pixel covers b x b finer ones")
      ->capture_default_str()
      ->check(CLI::Range(2, 64));
  app.add_option("--online-mask-levels", o.mask_levels, "On-line image-space culling: coarser masks above M_0 (-1: down to one pixel)")
      ->capture_default_str()
      ->check(CLI::Range(-1, 64));
  app.add_option("--online-priority", online_priority, "On-line image-space culling: occluder priority φ, coverage (x distance) or distance")
      ->capture_default_str()
      ->check(CLI::IsMember({"coverage", "distance"}))
      ->each([&o](const std::string& v) { o.coverage_priority = v == "coverage"; });
  app.add_option("--online-turn", o.critical_turn, "On-line image-space culling: radians the view may turn before a critical frame")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--online-ground", o.ground_occluder, "On-line image-space culling: draw the ground plane into the occluders' image (1/0)")
      ->capture_default_str();
  app.add_option("--online-pixel-budget", o.pixel_budget, "On-line image-space culling: misdrawn pixels per frame it claims at most")
      ->capture_default_str();
}

std::string MethodFlags::replay_flags() const {
  const MethodOptions d;
  const OnlineCullingOptions& o = options.online;
  const OnlineCullingOptions& od = d.online;
  std::ostringstream out;
  // Doubles as JSON writes them: the shortest text that reads back to the same value.
  const auto text = [](double v) { return nlohmann::json(v).dump(); };
  if (options.horizon_bins != d.horizon_bins) out << " --horizon-bins " << options.horizon_bins;
  if (options.quadtree_leaf_size != d.quadtree_leaf_size) out << " --leaf-size " << options.quadtree_leaf_size;
  if (options.delta_radius != d.delta_radius) out << " --delta-radius " << text(options.delta_radius);
  if (options.delta_height != d.delta_height) out << " --delta-height " << text(options.delta_height);
  if (options.delta_turn != d.delta_turn) out << " --delta-turn " << text(options.delta_turn);
  if (options.delta_prefetch != d.delta_prefetch) out << " --delta-no-prefetch";
  if (o.shrink_pixels != od.shrink_pixels) out << " --online-shrink " << o.shrink_pixels;
  if (o.mask_size != od.mask_size) out << " --online-mask-size " << o.mask_size;
  if (o.leaf_size != od.leaf_size) out << " --online-leaf-size " << o.leaf_size;
  if (o.min_distance != od.min_distance) out << " --online-min-distance " << text(o.min_distance);
  if (o.max_speed != od.max_speed) out << " --online-max-speed " << text(o.max_speed);
  if (o.occluders != od.occluders) out << " --online-occluders " << o.occluders;
  if (o.mask_block != od.mask_block) out << " --online-mask-block " << o.mask_block;
  if (o.mask_levels != od.mask_levels) out << " --online-mask-levels " << o.mask_levels;
  if (o.coverage_priority != od.coverage_priority) out << " --online-priority " << (o.coverage_priority ? "coverage" : "distance");
  if (o.critical_turn != od.critical_turn) out << " --online-turn " << text(o.critical_turn);
  if (o.ground_occluder != od.ground_occluder) out << " --online-ground " << (o.ground_occluder ? 1 : 0);
  if (o.pixel_budget != od.pixel_budget) out << " --online-pixel-budget " << o.pixel_budget;
  return out.str();
}

void RegionFlags::add(CLI::App& app, const std::string& default_methods) {
  app.add_option("--region-placement", placement,
                 "Where a new disc is centred when the walker leaves the old one: 'eye' (at the walker) or 'tiling' "
                 "(the nearest centre of the hexagonal circle tiling, thesis Fig. 4.9d)")
      ->capture_default_str()
      ->check(CLI::IsMember({"eye", "tiling"}));
  methods = default_methods;
  app.add_option("--region-method", methods,
                 "From-region methods, comma-separated, 'all' or 'none': each PVS serves the frames that stay in its region")
      ->capture_default_str();
  app.add_option("--region-radius", radius, "Radius (m) of a from-region PVS's disc (ε)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e4));
  app.add_option("--region-turn", turn, "Turn (rad) a from-region PVS allows")->capture_default_str()->check(CLI::Range(0.0, 1.5));
}

void VbaoiFlags::add(CLI::App& app, const std::vector<std::uint32_t>& default_clients, const std::string& prefix) {
  const auto name = [&](const char* flag) { return "--" + prefix + flag; };
  options.client_counts = default_clients;
  // Results do not depend on the thread counts (nodes and rays are merged in order).
  options.graph.threads = std::max(1u, std::thread::hardware_concurrency());
  options.oracle_threads = static_cast<int>(options.graph.threads);
  app.add_option(name("cell-size"), options.regions.cell_size,
                 "Free-space cells (scenes without street cells): side of the grid no cell reaches across, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1e5));
  app.add_option(name("cell-margin"), options.regions.margin, "Free-space cells: open ground kept around the scene's bounds, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e5));
  app.add_option(name("graph-method"), options.graph.method,
                 "From-region method for each node's PVSo and PVSn (one that tests passive targets)")
      ->capture_default_str();
  app.add_option(name("epsilon"), options.graph.epsilon, "ε (m) of the view-cell samples' discs")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 1e3));
  app.add_option(name("eye-height"), options.graph.eye_height, "Eye height (m) of every client and of the view cells' eyes")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 1e3));
  app.add_option(name("graph-sampling"), sampling, "View-cell sampling: boundary or tiled")->capture_default_str();
  app.add_option(name("pvs-n-symmetry"), symmetry,
                 "An entry only one side's PVSn lists: dropped (intersection: each side alone is conservative) or "
                 "mirrored (union)")
      ->capture_default_str();
  app.add_option(name("graph-threads"), options.graph.threads, "Threads computing the graph's nodes")
      ->capture_default_str()
      ->check(CLI::Range(1u, 256u));
  app.add_option(name("clients"), options.client_counts, "Client counts, comma-separated (one simulation each)")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(1u, 100000u));
  auto& s = options.simulation;
  app.add_option(name("sim-seed"), s.seed, "Simulation seed (walks, join times, network draws)")->capture_default_str();
  app.add_option(name("duration"), s.duration, "Simulated seconds")->capture_default_str();
  app.add_option(name("tick"), s.tick, "Seconds between pose updates")->capture_default_str();
  app.add_option(name("latency"), s.latency, "One-way latency (s) client <-> server")->capture_default_str();
  app.add_option(name("jitter"), s.jitter, "Extra latency, uniform in [0, jitter) seconds")->capture_default_str();
  app.add_option(name("loss"), s.loss, "Probability that a message is lost")->capture_default_str();
  app.add_option(name("retry-timeout"), s.retry_timeout, "Seconds before an unanswered control message is resent")
      ->capture_default_str();
  app.add_option(name("join-window"), s.join_window, "Clients join at seeded times in [0, join window) seconds")
      ->capture_default_str();
  app.add_option(name("speed-min"), s.speed_min, "Slowest walking speed, m/s")->capture_default_str();
  app.add_option(name("speed-max"), s.speed_max, "Fastest walking speed, m/s")->capture_default_str();
  app.add_option(name("circular-radii"), s.circular_radii, "Radii (m) of the circular-AoI baselines, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option(name("check-stride"), s.check_stride, "Check line of sight at every n-th tick")->capture_default_str();
  app.add_option(name("oracle-threads"), options.oracle_threads, "Threads casting line-of-sight rays")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
}

const VbaoiOptions& VbaoiFlags::resolved() {
  options.graph.sampling = parse_cell_sampling(sampling);
  options.graph.symmetry = parse_pvs_n_symmetry(symmetry);
  vbaoi::validate(options.simulation);
  return options;
}

std::vector<std::string> parse_methods(const std::string& list, const std::vector<std::string>& names) {
  if (list == "all") return names;
  if (list.empty() || list == "none") return {};
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = list.find(',', start);
    out.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  for (const auto& m : out) {
    if (std::find(names.begin(), names.end(), m) == names.end()) {
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
      throw InputError("command line", "method", "unknown method '" + m + "' (known: " + known + ", all)");
    }
  }
  return out;
}

nlohmann::json pvs_json(const CullResult& r) {
  return {{"pvs", r.pvs},
          {"pvs_size", r.pvs.size()},
          {"cells_tested", r.stats.cells_tested},
          {"buildings_tested", r.stats.buildings_tested},
          {"horizon_nodes", r.stats.horizon_nodes},
          {"occluders_applied", r.stats.occluders_applied},
          {"cull_ms", r.stats.cull_ms}};
}

int check_from(const Scene& scene, const std::optional<Camera>& from, const oracle::SamplingOptions& sampling,
               const std::vector<ObjectId>& pvs, const RegionCullingMethod& method, nlohmann::json& out) {
  if (!from) return 0;
  oracle::OracleOptions options;
  options.sampling = sampling;
  const oracle::OracleAnswer seen = oracle::Oracle(scene).visible_set(*from, options);
  const std::vector<ObjectId> missed = missing_from(seen.visible, pvs);
  out["from"] = {{"oracle_model", seen.model}, {"witnessed", seen.visible.size()}, {"missed", missed}};
  return !missed.empty() && method.claims_conservative() ? kExitGateFailed : 0;
}

}  // namespace cullcheck::cli
