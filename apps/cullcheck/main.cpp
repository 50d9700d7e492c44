// cullcheck: the command-line program. Thin: it parses flags and calls the libraries.
//
// Exit codes: 0 success; 1 a method that claims to be conservative culled something the oracle
// saw (the CI gate); 2 bad input (one line on stderr naming the object and field); 3 an
// internal error (a bug: please report it with the command line).
#include <CLI/CLI.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/view_cell.hpp"
#include "engine/vbaoi/navigation_graph.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/navigable_regions.hpp"
#include "oracle/oracle.hpp"
#include "oracle/ray_oracle.hpp"
#include "reports/claims.hpp"
#include "reports/delta_claims.hpp"
#include "reports/shrinking_claims.hpp"
#include "reports/region_sweep.hpp"
#include "reports/view_cells.hpp"
#include "reports/table_4_1.hpp"
#include "reports/scaling.hpp"
#include "reports/report.hpp"
#include "reports/vbaoi.hpp"
#include "reports/verification.hpp"

namespace cc = cullcheck;

namespace {

constexpr int kExitGateFailed = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitInternalError = 3;

struct SceneFlags {
  cc::SceneSource source;
  void add(CLI::App& app) {
    app.add_option("--generator", source.generator, "City generator (manhattan, plaza, default, scatter, irregular, thesis, kept)")
        ->capture_default_str();
    app.add_option("--seed", source.seed, "Generator seed")->capture_default_str();
    app.add_option("--params", source.parameters_json, "Generator parameters as JSON, overlaid on its defaults")
        ->capture_default_str();
    app.add_option("--scene", source.file, "Read the scene from this JSON file instead of generating it");
  }
};

struct PathFlags {
  std::string kind = "street_walk";
  std::uint64_t seed = 1;
  std::string params = "{}";
  std::string file;
  void add(CLI::App& app, int default_frames) {
    params = nlohmann::json{{"frames", default_frames}}.dump();
    app.add_option("--path-kind", kind, "Camera path generator (street_walk, fly_through, moves)")->capture_default_str();
    app.add_option("--path-seed", seed, "Camera path seed")->capture_default_str();
    app.add_option("--path-params", params, "Camera path parameters as JSON")->capture_default_str();
    app.add_option("--path", file, "Read the camera path from this JSON file instead");
  }
  // The flags that rebuild this path, for replay commands.
  std::string replay_flags() const {
    if (!file.empty()) return "--path " + cc::shell_quote(file);
    return "--path-kind " + kind + " --path-seed " + std::to_string(seed) + " --path-params " + cc::shell_quote(params);
  }
  cc::CameraPath load(const cc::Scene& scene) const {
    if (!file.empty()) return cc::path_from_json_text(cc::read_text_file(file));
    return cc::generators::make_camera_path(kind, scene, seed, parse_json(params, "path-params"));
  }
  static nlohmann::json parse_json(const std::string& text, const std::string& field) {
    try {
      return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
      throw cc::InputError("command line", field, std::string("is not valid JSON: ") + e.what());
    }
  }
};

struct SamplingFlags {
  cc::oracle::SamplingOptions sampling;
  void add(CLI::App& app) {
    app.add_option("--spacing", sampling.spacing_m, "Oracle: surface sample spacing in metres")->capture_default_str();
    app.add_option("--face-grid", sampling.face_grid, "Oracle: least grid intervals per face")->capture_default_str();
    app.add_option("--frustum-resolution", sampling.frustum_resolution, "Oracle: stratified rays per image row")
        ->capture_default_str();
  }
};

// The engine's tuning knobs, the same on every subcommand that runs methods.
struct MethodFlags {
  cc::MethodOptions options;
  void add(CLI::App& app) {
    app.add_option("--horizon-bins", options.horizon_bins, "Occlusion horizon bins over 360 degrees (power of two)")
        ->capture_default_str();
    app.add_option("--leaf-size", options.quadtree_leaf_size, "Most buildings in a quadtree leaf")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1000000u));
    app.add_option("--delta-radius", options.delta_radius,
                   "Guarded ΔH: plan radius (m) of the motion region a certificate covers")
        ->capture_default_str()
        ->check(CLI::Range(1e-6, 1e4));
    app.add_option("--delta-height", options.delta_height, "Guarded ΔH: height range (m) of the motion region")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e4));
    app.add_option("--delta-turn", options.delta_turn, "Guarded ΔH: turn (rad, |Δyaw|+|Δpitch|+|Δroll|) the region allows")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1.5));
  }
};

// `region --from` and `cell --from`: the oracle's view from one eye (camera JSON) against a
// from-region PVS, into out["from"]; the gate's exit code when a method that claims to be
// conservative missed what it saw, else 0 (also when no eye was given).
int check_from(const cc::Scene& scene, const std::string& from_json, const cc::oracle::SamplingOptions& sampling,
               const std::vector<cc::ObjectId>& pvs, const cc::RegionCullingMethod& method, nlohmann::json& out) {
  if (from_json.empty()) return 0;
  cc::oracle::OracleOptions options;
  options.sampling = sampling;
  const cc::oracle::OracleAnswer seen =
      cc::oracle::Oracle(scene).visible_set(cc::camera_from_json_text(from_json, "from"), options);
  const std::vector<cc::ObjectId> missed = cc::missing_from(seen.visible, pvs);
  out["from"] = {{"oracle_model", seen.model}, {"witnessed", seen.visible.size()}, {"missed", missed}};
  return !missed.empty() && method.claims_conservative() ? kExitGateFailed : 0;
}

// From-region methods along a path (thesis ch. 4): which, and the region each PVS serves.
struct RegionFlags {
  std::string methods;
  double radius = std::sqrt(2.0);
  double turn = 0.0;
  std::string placement = "eye";
  void add(CLI::App& app, const std::string& default_methods) {
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
};

std::vector<std::string> parse_methods(const std::string& list,
                                       const std::vector<std::string>& names = cc::method_names()) {
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
      throw cc::InputError("command line", "method", "unknown method '" + m + "' (known: " + known + ", all)");
    }
  }
  return out;
}

nlohmann::json pvs_json(const cc::CullResult& r) {
  return {{"pvs", r.pvs},
          {"pvs_size", r.pvs.size()},
          {"cells_tested", r.stats.cells_tested},
          {"buildings_tested", r.stats.buildings_tested},
          {"horizon_nodes", r.stats.horizon_nodes},
          {"occluders_applied", r.stats.occluders_applied},
          {"cull_ms", r.stats.cull_ms}};
}

// VbAoI (issue 5): the graph's from-region method and the simulation's knobs.
struct VbaoiFlags {
  cc::VbaoiOptions options;
  std::string sampling = "boundary", symmetry = "intersection";
  // `prefix` keeps the names apart where other flags live (report: "vbaoi-").
  void add(CLI::App& app, const std::vector<std::uint32_t>& default_clients, const std::string& prefix = "") {
    const auto name = [&](const char* flag) { return "--" + prefix + flag; };
    options.client_counts = default_clients;
    // Results do not depend on the thread counts (nodes and rays are merged in order).
    options.graph.threads = std::max(1u, std::thread::hardware_concurrency());
    options.oracle_threads = static_cast<int>(options.graph.threads);
    app.add_option(name("cell-size"), options.regions.cell_size,
                   "Free-space cells (scenes without street cells): side of the grid no cell reaches across, metres")
        ->capture_default_str()
        ->check(CLI::Range(0.1, 1e5));
    app.add_option(name("cell-margin"), options.regions.margin,
                   "Free-space cells: open ground kept around the scene's bounds, metres")
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
  const cc::VbaoiOptions& resolved() {
    options.graph.sampling = cc::parse_cell_sampling(sampling);
    options.graph.symmetry = cc::parse_pvs_n_symmetry(symmetry);
    cc::vbaoi::validate(options.simulation);
    return options;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cullcheck: urban occlusion culling held to an oracle (Embree + CGAL) on seeded cities"};
  app.require_subcommand(1);

  // generate ---------------------------------------------------------------------------------
  CLI::App* generate = app.add_subcommand("generate", "Generate a city (JSON, optionally OBJ) and optionally a camera path");
  SceneFlags gen_scene;
  gen_scene.add(*generate);
  std::string gen_output = "scene.json", gen_obj, gen_path_output;
  PathFlags gen_path;
  gen_path.add(*generate, 300);
  generate->add_option("--output,-o", gen_output, "Scene JSON file to write")->capture_default_str();
  generate->add_option("--obj", gen_obj, "Also write the scene as Wavefront OBJ");
  generate->add_option("--path-output", gen_path_output, "Also write a camera path (see --path-kind) to this file");

  // cull -------------------------------------------------------------------------------------
  CLI::App* cull = app.add_subcommand("cull", "Run one engine method for a camera and print its PVS as JSON");
  SceneFlags cull_scene;
  cull_scene.add(*cull);
  MethodFlags cull_tuning;
  cull_tuning.add(*cull);
  std::string cull_method = "oh_os_conservative", cull_camera, cull_path;
  cull->add_option("--method", cull_method, "Engine method")->capture_default_str();
  auto* cull_camera_option = cull->add_option("--camera", cull_camera, "Camera as JSON (scene-local coordinates)");
  auto* cull_path_option = cull->add_option("--path", cull_path, "Camera path file: prints one JSON line per frame");
  cull_camera_option->excludes(cull_path_option);

  // verify -----------------------------------------------------------------------------------
  CLI::App* verify = app.add_subcommand("verify", "Hold methods to the oracle for one camera or a path; exit 1 on a violation");
  SceneFlags verify_scene;
  verify_scene.add(*verify);
  std::string verify_methods = "all", verify_camera;
  PathFlags verify_path;
  verify_path.add(*verify, 60);
  SamplingFlags verify_sampling;
  verify_sampling.add(*verify);
  MethodFlags verify_tuning;
  verify_tuning.add(*verify);
  verify->add_option("--method", verify_methods, "Comma-separated methods, or 'all'")->capture_default_str();
  verify->add_option("--camera", verify_camera, "One camera as JSON (instead of a path)");
  RegionFlags verify_regions;
  verify_regions.add(*verify, "none");

  // region -----------------------------------------------------------------------------------
  CLI::App* region = app.add_subcommand(
      "region", "PVS of a from-region method for the disc around a camera; with --from, hold it to the oracle there");
  SceneFlags region_scene;
  region_scene.add(*region);
  MethodFlags region_tuning;
  region_tuning.add(*region);
  SamplingFlags region_sampling;
  region_sampling.add(*region);
  std::string region_method = "shrink_adjustable_conservative", region_camera, region_from;
  double region_radius = std::sqrt(2.0), region_turn = 0.0;
  region->add_option("--method", region_method, "From-region method")->capture_default_str();
  region->add_option("--camera", region_camera, "The region's centre camera as JSON")->required();
  region->add_option("--radius", region_radius, "Disc radius (m)")->capture_default_str()->check(CLI::Range(0.0, 1e4));
  region->add_option("--turn", region_turn, "Turn (rad) allowed")->capture_default_str()->check(CLI::Range(0.0, 1.5));
  region->add_option("--from", region_from, "A viewpoint (camera JSON) of the region to check with the oracle");

  // cell -------------------------------------------------------------------------------------
  CLI::App* cell = app.add_subcommand(
      "cell", "From-region PVS of a view cell (a street cell or a given polygon) as the union of ε-disc PVSs at "
              "sample points; with --from, hold it to the oracle from that eye");
  SceneFlags cell_scene;
  cell_scene.add(*cell);
  MethodFlags cell_tuning;
  cell_tuning.add(*cell);
  SamplingFlags cell_oracle_sampling;
  cell_oracle_sampling.add(*cell);
  std::string cell_method = "shrink_adjustable_conservative", cell_ring, cell_sampling = "boundary", cell_from;
  std::int64_t cell_id = -1;
  double cell_epsilon = std::sqrt(2.0), cell_eye_height = 1.7;
  bool cell_no_carry = false, cell_nodes = false;
  std::vector<double> cell_to;
  cc::generators::FreeSpaceOptions cell_regions;
  cell->add_option("--method", cell_method, "From-region method for each sample's disc")->capture_default_str();
  cell->add_option("--cell", cell_id, "Navigable region id: a street cell of a Manhattan-family city, else a free-space cell "
                                      "(generators/navigable_regions.hpp)");
  cell->add_option("--ring", cell_ring, "Or the cell as a convex counter-clockwise polygon, JSON [[x,y],...]");
  cell->add_option("--cell-size", cell_regions.cell_size, "Free-space cells: side of the grid no cell reaches across, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1e5));
  cell->add_option("--cell-margin", cell_regions.margin, "Free-space cells: open ground kept around the scene's bounds, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e5));
  cell->add_option("--epsilon", cell_epsilon, "Disc radius ε (m); samples lie at most 2ε apart")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e4));
  cell->add_option("--sampling", cell_sampling, "boundary (as published) or tiled (hexagonal circle tiling)")->capture_default_str();
  cell->add_option("--eye-height", cell_eye_height, "Eye height (m) of every eye in the cell")->capture_default_str();
  cell->add_flag("--no-carry", cell_no_carry, "Test every building at every sample (no decisions carried between samples)");
  cell->add_option("--from", cell_from, "A viewpoint (camera JSON) to check the cell's PVS from with the oracle");
  cell->add_flag("--nodes", cell_nodes,
                 "Also the cell's PVSn (VbAoI, thesis ch. 5.1): the scene's navigable regions, extruded to eye height, "
                 "that the method does not hide (raw: before the graph makes PVSn symmetric)");
  cell->add_option("--to", cell_to, "With --nodes and --from: an avatar's eye X,Y (at eye height); checks the line of "
                                    "sight from --from's eye to it and that its region is in the PVSn")
      ->delimiter(',')
      ->expected(2);

  // vbaoi ------------------------------------------------------------------------------------
  CLI::App* vbaoi = app.add_subcommand(
      "vbaoi", "VbAoI (thesis ch. 5): build the navigable-region graph (PVSo, PVSn, SNs), simulate clients with VbAoI, "
               "broadcast, neighbours-only and circular AoI, check channel grouping against the oracle; exit 1 on a "
               "violation");
  SceneFlags vbaoi_scene;
  vbaoi_scene.add(*vbaoi);
  MethodFlags vbaoi_tuning;
  vbaoi_tuning.add(*vbaoi);
  VbaoiFlags vbaoi_flags;
  vbaoi_flags.add(*vbaoi, {10, 100});
  std::string vbaoi_output;
  vbaoi->add_option("--output,-o", vbaoi_output, "Also write the section as JSON to this file");

  // report -----------------------------------------------------------------------------------
  CLI::App* report = app.add_subcommand("report", "The main job: every method and the oracle along a path, the claims ledger, report.json");
  SceneFlags report_scene;
  report_scene.add(*report);
  PathFlags report_path;
  report_path.add(*report, 300);
  SamplingFlags report_sampling;
  report_sampling.add(*report);
  MethodFlags report_tuning;
  report_tuning.add(*report);
  std::string report_methods = "all", report_output = "report.json", benchmark_json;
  std::size_t oracle_stride = 5;  // the oracle costs ~0.3 s a frame on the default city
  RegionFlags report_regions;
  report_regions.add(*report, "all");
  std::vector<double> region_sweep_radii;
  report->add_option("--region-sweep", region_sweep_radii,
                     "Also run every region method along the path at each of these disc radii (m), e.g. "
                     "0.25,0.5,1,1.41,2,4: PVS size, frames each PVS serves and its cost, into report.json's \"region_sweep\"")
      ->delimiter(',')
      ->check(CLI::Range(1e-6, 1e4));
  cc::ClaimSearchOptions claim_options;
  report->add_option("--method", report_methods, "Comma-separated methods, or 'all'")->capture_default_str();
  report->add_option("--output,-o", report_output, "Report file to write")->capture_default_str();
  report->add_option("--oracle-stride", oracle_stride, "Check every n-th frame with the oracle")->capture_default_str();
  report->add_option("--claim-scenes", claim_options.scenes, "Scenes searched per claim")->capture_default_str();
  report->add_option("--claim-seed", claim_options.seed, "Seed of the claim search")->capture_default_str();
  std::vector<int> scaling_grids;
  int scaling_frames = 1000;
  report->add_option("--scaling-grids", scaling_grids,
                     "Also time the methods on thesis-layout cities of grid x grid buildings (e.g. 100,200,400,800: "
                     "10k to 640k) along a street walk, into report.json's \"scaling\"")
      ->delimiter(',')
      ->check(CLI::Range(1, 4000));
  report->add_option("--scaling-frames", scaling_frames, "Street-walk frames per city size for --scaling-grids")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  bool table_41 = false;
  report->add_flag("--table-4-1", table_41,
                   "Also reproduce thesis Table 4.1 on its plaza-crossing walk (Methods 1-3 at 60 and 90 degrees, "
                   "region radius --region-radius, oracle every --oracle-stride frames), into report.json's \"table_4_1\"");
  bool view_cells = false;
  cc::ViewCellOptions view_cell_options;
  std::string view_cell_sampling = "boundary,tiled";
  report->add_flag("--view-cells", view_cells,
                   "Also compute the from-region PVS of every navigable region (street or free-space cell) with each region "
                   "method and sampling, "
                   "hold some cells to the oracle, into report.json's \"view_cells\"");
  report->add_option("--view-cell-epsilon", view_cell_options.epsilon, "ε (m) of the view cells' sample discs")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 1e3));
  report->add_option("--view-cell-stride", view_cell_options.cell_stride, "Compute every n-th navigable region")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  report->add_option("--view-cell-oracle-cells", view_cell_options.oracle_cells, "Street cells held to the oracle")
      ->capture_default_str();
  report->add_option("--view-cell-sampling", view_cell_sampling, "Comma-separated: boundary, tiled")->capture_default_str();
  bool vbaoi_section = false;
  cc::SceneSource vbaoi_city{"manhattan", 1, R"({"blocks_x":41,"blocks_y":41})", ""};
  VbaoiFlags report_vbaoi;
  report->add_flag("--vbaoi", vbaoi_section,
                   "Also VbAoI (thesis ch. 5) on its own city (--vbaoi-generator/-seed/-params; default a 41 x 41-block "
                   "Manhattan grid of 10,086 buildings): the navigable-region graph, simulations of 10, 100 and 1,000 "
                   "clients against broadcast, neighbours-only and circular AoI, into report.json's \"vbaoi\"");
  report->add_option("--vbaoi-generator", vbaoi_city.generator, "Generator of the VbAoI city")->capture_default_str();
  report->add_option("--vbaoi-seed", vbaoi_city.seed, "Seed of the VbAoI city")->capture_default_str();
  report->add_option("--vbaoi-params", vbaoi_city.parameters_json, "Parameters (JSON) of the VbAoI city")->capture_default_str();
  report_vbaoi.add(*report, {10, 100, 1000}, "vbaoi-");
  report->add_option("--benchmark-json", benchmark_json,
                     "Fold this Google Benchmark JSON output (bench_culling --benchmark_format=json) into the report");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitBadInput;
  }

  try {
    if (*generate) {
      const cc::Scene scene = gen_scene.source.load();
      cc::write_scene_file(scene, gen_output);
      std::cout << "wrote " << gen_output << ": " << scene.buildings.size() << " buildings, " << scene.triangle_count()
                << " triangles\n";
      if (!gen_obj.empty()) {
        std::ostringstream obj;
        cc::write_obj(scene, obj);
        cc::write_text_file_atomically(gen_obj, obj.str());
        std::cout << "wrote " << gen_obj << "\n";
      }
      if (!gen_path_output.empty()) {
        const cc::CameraPath path = gen_path.load(scene);
        cc::write_text_file_atomically(gen_path_output, cc::path_to_json_text(path));
        std::cout << "wrote " << gen_path_output << ": " << path.frames.size() << " frames\n";
      }
      return 0;
    }
    if (*cull) {
      const cc::Scene scene = cull_scene.source.load();
      auto method = cc::make_method(cull_method, scene, cull_tuning.options);
      std::vector<cc::Camera> cameras;
      if (cull_camera.empty() && cull_path.empty())
        throw cc::InputError("command line", "camera", "give a camera (--camera JSON) or a path (--path FILE)");
      if (!cull_path.empty()) {
        cameras = cc::path_from_json_text(cc::read_text_file(cull_path)).frames;
      } else {
        cameras.push_back(cc::camera_from_json_text(cull_camera));
      }
      for (std::size_t frame = 0; frame < cameras.size(); ++frame) {
        nlohmann::json out = pvs_json(method->cull(cameras[frame]));
        out["method"] = cull_method;
        if (!cull_path.empty()) out["frame"] = frame;
        std::cout << out.dump() << "\n";
      }
      return 0;
    }
    if (*region) {
      const cc::Scene scene = region_scene.source.load();
      auto method = cc::make_region_method(region_method, scene, region_tuning.options);
      const cc::ViewRegion view_region{cc::camera_from_json_text(region_camera), region_radius, region_turn};
      const cc::CullResult r = method->cull_region(view_region);
      nlohmann::json out = pvs_json(r);
      out["method"] = region_method;
      out["radius"] = region_radius;
      out["turn"] = region_turn;
      const int exit_code = check_from(scene, region_from, region_sampling.sampling, r.pvs, *method, out);
      std::cout << out.dump() << "\n";
      return exit_code;
    }
    if (*cell) {
      const cc::Scene scene = cell_scene.source.load();
      cc::ViewCell view_cell{{}, cell_eye_height};
      if ((cell_id >= 0) == !cell_ring.empty())
        throw cc::InputError("cell", "--cell/--ring", "give exactly one of --cell ID and --ring POLYGON");
      std::vector<cc::NavigableRegion> regions;  // the cell's, and the passive targets of --nodes
      if (cell_id >= 0 || cell_nodes) regions = cc::generators::navigable_regions(scene, cell_regions);
      if (cell_id >= 0) {
        if (static_cast<std::size_t>(cell_id) >= regions.size())
          throw cc::InputError("cell", "--cell", "is " + std::to_string(cell_id) + ", the scene has " +
                                                     std::to_string(regions.size()) + " navigable regions (street cells or free-space cells)");
        view_cell.ring = regions[static_cast<std::size_t>(cell_id)].ring;
      } else {
        const nlohmann::json ring = PathFlags::parse_json(cell_ring, "ring");
        if (!ring.is_array()) throw cc::InputError("cell", "--ring", "must be a JSON array of [x, y] pairs");
        for (const auto& v : ring) {
          if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
            throw cc::InputError("cell", "--ring", "every vertex must be a pair of numbers [x, y]");
          view_cell.ring.push_back({v[0].get<double>(), v[1].get<double>()});
        }
      }
      auto method = cc::make_region_method(cell_method, scene, cell_tuning.options);
      const cc::CellSampling sampling = cc::parse_cell_sampling(cell_sampling);
      if (!cell_to.empty() && (!cell_nodes || cell_from.empty()))
        throw cc::InputError("cell", "--to", "needs --nodes and --from");
      if (cell_nodes) method->set_passive_targets(cc::navigable_region_targets(regions, cell_eye_height));
      const cc::ViewCellResult r =
          cc::ViewCellPvs(*method, scene, cell_nodes ? regions.size() : 0).compute(view_cell, cell_epsilon, sampling, !cell_no_carry);
      nlohmann::json out = {{"method", cell_method},      {"epsilon", cell_epsilon},
                            {"sampling", cell_sampling},  {"samples", r.samples},
                            {"pvs", r.pvs},               {"pvs_size", r.pvs.size()},
                            {"cull_ms", r.stats.cull_ms}, {"buildings_tested", r.stats.buildings_tested},
                            {"accepted_untested", r.stats.items_skipped}};
      int exit_code = check_from(scene, cell_from, cell_oracle_sampling.sampling, r.pvs, *method, out);
      if (cell_nodes) {
        out["pvs_n"] = r.passive;
        out["pvs_n_size"] = r.passive.size();
      }
      if (!cell_to.empty()) {
        const cc::Vec3 eye = cc::camera_from_json_text(cell_from, "from").position;
        const cc::Vec3 avatar{cell_to[0], cell_to[1], cell_eye_height};
        const std::int64_t node = cc::locate_region(regions, {avatar.x, avatar.y});
        const bool sight = cc::oracle::RayOracle(scene).line_of_sight(eye, avatar);
        const bool listed = node >= 0 && std::binary_search(r.passive.begin(), r.passive.end(), static_cast<cc::ObjectId>(node));
        out["to"] = {{"node", node}, {"line_of_sight", sight}, {"node_in_pvs_n", listed}};
        if (sight && node >= 0 && !listed && method->claims_conservative()) exit_code = kExitGateFailed;
      }
      std::cout << out.dump() << "\n";
      return exit_code;
    }
    if (*vbaoi) {
      const cc::Scene scene = vbaoi_scene.source.load();
      cc::VbaoiOptions options = vbaoi_flags.resolved();
      options.graph.method_options = vbaoi_tuning.options;
      const nlohmann::json section = cc::vbaoi_report(scene, vbaoi_scene.source, options);
      std::cout << cc::vbaoi_table(section);
      if (!vbaoi_output.empty()) cc::write_text_file_atomically(vbaoi_output, section.dump(2) + "\n");
      const std::size_t violations = cc::vbaoi_gate_violations(section);
      if (violations > 0)
        for (const auto& run : section["runs"]) std::cout << "replay: " << run["replay"].get<std::string>() << "\n";
      return violations == 0 ? 0 : kExitGateFailed;
    }
    if (*verify) {
      const cc::Scene scene = verify_scene.source.load();
      const std::vector<std::string> methods = parse_methods(verify_methods);
      cc::CameraPath path;
      if (!verify_camera.empty()) {
        path.kind = "single_camera";
        path.frames.push_back(cc::camera_from_json_text(verify_camera));
      } else {
        path = verify_path.load(scene);
      }
      cc::VerificationOptions options;
      options.oracle.sampling = verify_sampling.sampling;
      options.max_replays = 10;
      options.region_methods = parse_methods(verify_regions.methods, cc::region_method_names());
      options.region_radius = verify_regions.radius;
      options.region_turn = verify_regions.turn;
      options.region_on_tiling = verify_regions.placement == "tiling";
      if (verify_camera.empty()) options.path_replay_flags = verify_path.replay_flags();
      const cc::PathVerification v = cc::verify_path(scene, verify_scene.source, path, methods, verify_tuning.options, options);
      std::cout << cc::summary_table(v);
      for (const cc::MethodRun& r : v.runs)
        for (const cc::Violation& x : r.violations)
          std::cout << "violation: " << r.method << " culled building " << x.building << " at frame " << x.frame << " (oracle "
                    << x.model << (x.witness.empty() ? "" : ", witness " + x.witness) << ")\n  replay: " << x.replay << "\n";
      return cc::conservative_violations(v) == 0 ? 0 : kExitGateFailed;
    }
    if (*report) {
      const cc::Scene scene = report_scene.source.load();
      if (view_cells) {  // bad view-cell input fails before the long run, not after it
        view_cell_options.samplings.clear();
        for (std::size_t start = 0; start <= view_cell_sampling.size();) {  // comma-separated names
          const std::size_t comma = std::min(view_cell_sampling.find(',', start), view_cell_sampling.size());
          view_cell_options.samplings.push_back(cc::parse_cell_sampling(view_cell_sampling.substr(start, comma - start)));
          start = comma + 1;
        }
      }
      std::optional<cc::Scene> vbaoi_scene;  // bad VbAoI input fails before the long run too
      if (vbaoi_section) {
        report_vbaoi.resolved();
        report_vbaoi.options.graph.method_options = report_tuning.options;
        vbaoi_scene = vbaoi_city.load();
      }
      const cc::CameraPath path = report_path.load(scene);
      cc::VerificationOptions options;
      options.oracle.sampling = report_sampling.sampling;
      options.oracle_stride = oracle_stride;
      options.path_replay_flags = report_path.replay_flags();
      options.region_methods = parse_methods(report_regions.methods, cc::region_method_names());
      options.region_radius = report_regions.radius;
      options.region_turn = report_regions.turn;
      options.region_on_tiling = report_regions.placement == "tiling";
      const std::vector<std::string> methods = parse_methods(report_methods);
      std::cout << "scene: " << scene.provenance.generator << " seed " << scene.provenance.seed << ", "
                << scene.buildings.size() << " buildings; path: " << path.kind << ", " << path.frames.size() << " frames\n";
      const cc::PathVerification v = cc::verify_path(scene, report_scene.source, path, methods, report_tuning.options, options);
      claim_options.sampling = report_sampling.sampling;
      cc::ReportInputs in;
      in.method_options = report_tuning.options;
      in.scene = &scene;
      in.source = report_scene.source;
      in.path = &path;
      in.path_parameters_json = report_path.file.empty() ? report_path.params : "{}";
      in.verification = &v;
      in.claims = cc::check_shadow_elevation_rule(claim_options);
      for (cc::ClaimCheck& c : cc::check_image_space_pitch_roll(claim_options)) in.claims.push_back(std::move(c));
      for (cc::ClaimCheck& c : cc::check_delta_horizon_claims(claim_options)) in.claims.push_back(std::move(c));
      for (cc::ClaimCheck& c : cc::check_shrinking_claims(claim_options)) in.claims.push_back(std::move(c));
      nlohmann::json document = cc::build_report(in);
      if (!region_sweep_radii.empty()) {
        document["region_sweep"] =
            cc::region_radius_sweep(scene, path, options.region_methods.empty() ? cc::region_method_names() : options.region_methods,
                                    region_sweep_radii, report_regions.turn, options.region_on_tiling, report_tuning.options);
        std::cout << cc::region_sweep_table(document["region_sweep"]);
      }
      std::size_t section_violations = 0;
      if (table_41) {
        cc::Table41Options t;
        t.region_methods = options.region_methods;
        t.radius = report_regions.radius;
        t.oracle_stride = oracle_stride;
        t.oracle.sampling = report_sampling.sampling;
        document["table_4_1"] = cc::table_4_1(t, report_tuning.options);
        std::cout << cc::table_4_1_text(document["table_4_1"]);
        for (const auto& r : document["table_4_1"]["rows"])
          if (r.value("claims_conservative", true)) section_violations += r["violations"].get<std::size_t>();
      }
      if (view_cells) {
        view_cell_options.methods = options.region_methods.empty() ? cc::region_method_names() : options.region_methods;
        view_cell_options.oracle.sampling = report_sampling.sampling;
        document["view_cells"] = cc::view_cell_report(scene, report_scene.source, view_cell_options, report_tuning.options);
        std::cout << cc::view_cell_table(document["view_cells"]);
        for (const auto& r : document["view_cells"]["runs"])
          if (r["claims_conservative"].get<bool>()) section_violations += r["violations"].get<std::size_t>();
      }
      if (vbaoi_scene) {
        document["vbaoi"] = cc::vbaoi_report(*vbaoi_scene, vbaoi_city, report_vbaoi.options);
        std::cout << cc::vbaoi_table(document["vbaoi"]);
        section_violations += cc::vbaoi_gate_violations(document["vbaoi"]);
        for (cc::ClaimCheck& c : cc::vbaoi_claims(document["vbaoi"])) {
          document["claims"].push_back(cc::to_json(c));
          in.claims.push_back(std::move(c));
        }
      }
      if (!scaling_grids.empty()) {
        cc::ScalingOptions scaling;
        scaling.grids = scaling_grids;
        scaling.frames = scaling_frames;
        document["scaling"] = cc::run_scaling(scaling);
        std::cout << cc::scaling_table(document["scaling"]);
      }
      // The gate in the document says what the exit code says: sections' violations count too.
      document["gate"]["section_violations"] = section_violations;
      document["gate"]["passed"] = cc::conservative_violations(v) == 0 && section_violations == 0;
      if (!benchmark_json.empty())
        document["benchmarks"] = PathFlags::parse_json(cc::read_text_file(benchmark_json), "benchmark-json");
      cc::write_text_file_atomically(report_output, document.dump(2) + "\n");
      std::cout << cc::summary_table(v);
      for (const cc::ClaimCheck& c : in.claims) {
        std::cout << "claim " << c.id << ": " << (c.holds ? "holds" : "REFUTED") << " (" << c.frames_checked << " frames, "
                  << c.violations << " violations)\n";
        if (!c.holds) std::cout << "  counterexample: " << c.counterexample_replay << "\n";
      }
      std::cout << "wrote " << report_output << "\n";
      return cc::conservative_violations(v) == 0 && section_violations == 0 ? 0 : kExitGateFailed;
    }
  } catch (const cc::InputError& e) {
    std::cerr << "cullcheck: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "cullcheck: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "cullcheck: internal error: " << e.what() << "\n";
    return kExitInternalError;
  }
  return 0;
}
