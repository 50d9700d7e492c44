// cullcheck report: the main job. Every method and the oracle along a path, the claims ledger,
// optional sections (thesis Table 4.1, view cells, VbAoI, scaling, the ε sweep), report.json.
#include <algorithm>
#include <map>
#include <iostream>
#include <memory>
#include <optional>

#include <filesystem>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/page_writer.hpp"
#include "apps/cullcheck/subject_flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/scene_io.hpp"
#include "reports/claims.hpp"
#include "reports/delta_claims.hpp"
#include "reports/fuzzing.hpp"
#include "reports/subject_claims.hpp"
#include "reports/gate_verdict.hpp"
#include "reports/junit.hpp"
#include "reports/knob_sweep.hpp"
#include "reports/region_sweep.hpp"
#include "reports/report.hpp"
#include "reports/report_parts.hpp"
#include "reports/scaling.hpp"
#include "reports/speed_targets.hpp"
#include "reports/shrinking_claims.hpp"
#include "reports/online_claims.hpp"
#include "reports/online_culling.hpp"
#include "reports/frustum_claims.hpp"
#include "reports/radar_claims.hpp"
#include "reports/polar_claims.hpp"
#include "reports/polar_table.hpp"
#include "reports/slice_wise_table.hpp"
#include "reports/radar_table.hpp"
#include "reports/table_4_1.hpp"
#include "reports/vbaoi.hpp"
#include "reports/verification.hpp"
#include "reports/view_cells.hpp"

namespace cullcheck::cli {

Runner add_report(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    SamplingFlags sampling;
    MethodFlags tuning;
    bool online_table = false;
    OnlineTableOptions online_table_options;
    bool radar_table = false;
    RadarTableOptions radar_table_options;
    bool polar_table = false;
    PolarTableOptions polar_table_options;
    bool slice_table = false;
    SliceTableOptions slice_table_options;
    RegionFlags regions;
    std::string methods = "all", output = "report.json", benchmark_json, baseline, junit, html, map_method;
    std::optional<std::size_t> map_frame;
    Shard shard;
    std::size_t oracle_stride = 5;  // the main job (ci/setup.sh) checks every frame: about 0.06 s each on the default city
    std::vector<double> region_sweep_radii;
    std::vector<std::string> knob_sweeps;
    ClaimSearchOptions claim_options;
    std::vector<int> scaling_grids;
    int scaling_frames = 1000;
    bool table_41 = false, view_cells = false, vbaoi_section = false, no_pixels = false;
    SubjectFlags subjects;
    FuzzOptions fuzz, soak;
    std::string fuzz_out = "cullcheck-counterexample", soak_out = "cullcheck-soak-counterexample";
    ViewCellOptions view_cell_options;
    std::string view_cell_sampling = "boundary,tiled";
    SceneSource vbaoi_city{"manhattan", 1, R"({"blocks_x":41,"blocks_y":41})", ""};
    VbaoiFlags vbaoi;
  };
  auto f = std::make_shared<Flags>();
  f->soak.budget = 0;  // off unless asked for
  CLI::App* sub =
      app.add_subcommand("report", "The main job: every method and the oracle along a path, the claims ledger, report.json");
  f->scene.add(*sub);
  f->path.add(*sub, 300);
  f->sampling.add(*sub);
  f->tuning.add(*sub);
  f->regions.add(*sub, "all");
  f->subjects.add(*sub, /*inline_visible=*/false);
  sub->add_option("--fuzz-subject", f->fuzz.subject,
                  "Also fuzz this subject (like `cullcheck fuzz`), into report.json's \"fuzz\" and the claims ledger; its "
                  "counterexample goes to --fuzz-out");
  sub->add_option("--fuzz-budget", f->fuzz.budget, "Cases the fuzzed subject must pass")->capture_default_str();
  sub->add_option("--fuzz-seed", f->fuzz.seed, "Seed of the fuzzer's cases")->capture_default_str();
  sub->add_option("--fuzz-out", f->fuzz_out, "Folder for the fuzzer's minimal counterexample")->capture_default_str();
  sub->add_option("--soak-budget", f->soak.budget,
                  "Also fuzz every built-in conservative method in process for this many cases (like `cullcheck fuzz --method "
                  "conservative`), into report.json's \"soak\" and the claims ledger; 0: off")
      ->capture_default_str()
      ->check(CLI::Range(0, 10000000));
  sub->add_option("--soak-seed", f->soak.seed, "Seed of the soak's cases")->capture_default_str();
  sub->add_option("--soak-out", f->soak_out, "Folder for the soak's minimal counterexample")->capture_default_str();
  sub->add_option("--region-sweep", f->region_sweep_radii,
                     "Also run every region method along the path at each of these disc radii (m), e.g. "
                     "0.25,0.5,1,1.41,2,4: PVS size, frames each PVS serves and its cost, into report.json's \"region_sweep\"")
      ->delimiter(',')
      ->check(CLI::Range(1e-6, 1e4));
  sub->add_option("--knob-sweep", f->knob_sweeps,
                  "Also run the point methods a knob affects along the path at each value, held to this run's oracle at its "
                  "checked frames, e.g. horizon_bins=256,1024,4096 (repeatable; knobs: horizon_bins, quadtree_leaf_size, "
                  "delta_radius, delta_height, delta_turn): into report.json's \"knob_sweep\" and the page's Pareto plot");
  sub->add_option("--method", f->methods, "Comma-separated methods, or 'all'")->capture_default_str();
  sub->add_option("--output,-o", f->output, "Report file to write")->capture_default_str();
  add_shard_flag(*sub, f->shard,
                 "Run shard K of N (e.g. 0/4): the oracle's n-th checked frame, each claim search's n-th scene and the n-th "
                 "section asked for are shard n mod N's; every shard runs the methods along the whole path. The file it "
                 "writes is the report of its share; `cullcheck merge` joins the N files into the report of the whole run");
  sub->add_option("--html", f->html,
                  "Also write the report page: one self-contained HTML file (summary, claims ledger, plots, map) that opens "
                  "offline; `cullcheck html report.json` writes it later");
  sub->add_option("--map-method", f->map_method, "The method the page's map shows (default: the worst: the method that missed most)");
  sub->add_option("--map-frame", f->map_frame,
                  "The frame the page's map shows (a frame the oracle checks; default: the chosen method's worst checked frame)");
  sub->add_flag("--no-pixels", f->no_pixels, "Skip the pixel oracle (misdrawn pixels per method at every checked frame)");
  sub->add_option("--junit", f->junit, "Also write the gate's checks as JUnit XML (one test case per method and check)");
  sub->add_option("--oracle-stride", f->oracle_stride, "Check every n-th frame with the oracle")->capture_default_str();
  sub->add_option("--claim-scenes", f->claim_options.scenes, "Scenes searched per claim")->capture_default_str();
  sub->add_option("--claim-seed", f->claim_options.seed, "Seed of the claim search")->capture_default_str();
  sub->add_option("--claim-threads", f->claim_options.threads,
                  "Scenes of the claim search checked at once (0: every core); the ledger is the same for any number")
      ->capture_default_str()
      ->check(CLI::Range(0u, 256u));
  sub->add_option("--scaling-grids", f->scaling_grids,
                     "Also time the methods on thesis-layout cities of grid x grid buildings (e.g. 100,200,400,800: "
                     "10k to 640k) along a street walk, into report.json's \"scaling\"")
      ->delimiter(',')
      ->check(CLI::Range(1, 4000));
  sub->add_option("--scaling-frames", f->scaling_frames, "Street-walk frames per city size for --scaling-grids")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  sub->add_flag("--table-4-1", f->table_41,
                   "Also reproduce thesis Table 4.1 on its plaza-crossing walk (Methods 1-3 at 60 and 90 degrees, "
                   "region radius --region-radius, oracle every --oracle-stride frames), into report.json's \"table_4_1\"");
  sub->add_flag("--online-table", f->online_table,
                "Also measure on-line image-space culling as Wang et al. 2001 did: Table 1 on four cities (3.6k-436k polygons, "
                "--online-table-frames each), the Δ x s sweep, misdrawn pixels, a --online-long-frames walk and a dynamic walk, into "
                "report.json's \"online_culling\"");
  sub->add_option("--online-table-frames", f->online_table_options.frames, "Street-walk frames per city for --online-table")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--online-long-frames", f->online_table_options.long_frames, "Frames of --online-table's long walk (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 10000000));
  sub->add_option("--online-dynamic-every", f->online_table_options.dynamic_every,
                  "Frames between scene events of --online-table's dynamic walk (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000000));
  sub->add_option("--online-dynamic-churn", f->online_table_options.dynamic_churn,
                  "Share of the buildings vanishing at each event of the dynamic walk (and absent at its start)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.5));
  sub->add_option("--online-table-grids", f->online_table_options.grids,
                  "Cities of --online-table: blocks each way (20 lots a block; default 6,17,33,66); the sweeps use the third")
      ->delimiter(',')
      ->check(CLI::Range(1, 400));
  sub->add_flag("--polar-table", f->polar_table,
                "Also measure polar diagrams (Ortega et al.) against CGAL's exact visibility polygon: construction of the four "
                "diagrams on the default city and on a city like the paper's (600 non-convex buildings, 45,000 vertices), query "
                "time per frame along level walks (90 and 360 degrees) with both visible sets compared (a difference fails the "
                "gate), rays against 2k, query time by visible count; into report.json's \"polar_diagram\"");
  sub->add_option("--polar-frames", f->polar_table_options.frames, "Walk frames per city and view of --polar-table")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  sub->add_flag("--slice-table", f->slice_table,
                "Also measure slice-wise PVSs (Yilmaz & Gudukbay) as the paper's Tables 1-3 and Fig. 7 on the detailed default city "
                "(and --slice-cityjson): slicing, shrinking, Algorithms 1-3 per view cell of a street walk, triangles per frame "
                "against building-level culling, PVS storage, the premise of Fig. 2, and the oracle's per-triangle check from "
                "cell corners (a violation fails the gate); into report.json's \"slice_wise\"");
  sub->add_option("--slice-frames", f->slice_table_options.frames, "Walk frames per city of --slice-table")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  sub->add_option("--slice-cell", f->slice_table_options.cell_side, "View-cell side of --slice-table, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  sub->add_option("--slice-thickness", f->slice_table_options.slicing.slice_m,
                  "Target slice thickness of --slice-table, metres (the paper makes its slices as wide as its view cells, or "
                  "adapted to the buildings); an object needing more than --slice-max-slices on an axis gets thicker ones")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  sub->add_option("--slice-max-slices", f->slice_table_options.slicing.max_slices,
                  "Most slices per axis of an object in --slice-table (a larger object gets thicker slices on that axis; "
                  "indices are signed bytes)")
      ->capture_default_str()
      ->check(CLI::Range(1, 127));
  sub->add_option("--slice-oracle-cells", f->slice_table_options.oracle_cells,
                  "Cells of --slice-table checked by the oracle from their corners, edge midpoints and centre")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  sub->add_option("--slice-voxel", f->slice_table_options.voxel_m,
                  "Voxel side of --slice-table's voxel erosion, metres (a wall recedes by the cell's half-side and up to one voxel)")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 100.0));
  sub->add_option("--slice-zoom", f->slice_table_options.culling.zoom_resolution,
                  "Pixels per side of --slice-table's zoomed view on one candidate (finer: tighter, slower)")
      ->capture_default_str()
      ->check(CLI::Range(8, 4096));
  sub->add_option("--slice-delta", f->slice_table_options.culling.delta,
                  "Step of --slice-table's hidden heights (the paper's delta), metres")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 100.0));
  sub->add_option("--slice-oracle-eyes", f->slice_table_options.oracle_eyes_per_side,
                  "Eyes per side of each checked cell of --slice-table: an n x n grid with the cell's corners (3: corners, edge "
                  "midpoints and centre); denser grids witness more of what some eye of the cell sees")
      ->capture_default_str()
      ->check(CLI::Range(2, 33));
  sub->add_option("--slice-cityjson", f->slice_table_options.cityjson,
                  "A LoD2 CityJSON file measured by --slice-table too (each Building and BuildingPart a mesh)")
      ->check(CLI::ExistingFile);
  sub->add_flag("--slice-no-generated{false}", f->slice_table_options.generated,
                "Leave the generated detailed city out of --slice-table (measure --slice-cityjson alone)");
  sub->add_flag("--radar-table", f->radar_table,
                "Also measure radar echo over terrain as thesis ch. 3.3 did: Table 3.3 on a generated terrain of the thesis's size "
                "(--radar-grids, 60 and 360 degrees, both rules, the oracle's witnessed count), the same on --radar-dem, growth with "
                "terrain size, the 2 s rotation bar; echo PNGs beside the report; into report.json's \"radar_echo\"");
  sub->add_option("--radar-grids", f->radar_table_options.grids, "Grid sizes (cells each way) of --radar-table")
      ->delimiter(',')
      ->check(CLI::Range(1, 4096));
  sub->add_option("--radar-dem", f->radar_table_options.dem, "An elevation model (GeoTIFF, ESRI ASCII) --radar-table also measures, e.g. "
                  "../shared/data/real/dem_mt_rainier/; NoData filled");
  sub->add_option("--radar-height", f->radar_table_options.height, "The transmitter's mast for --radar-table, metres above ground")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10000.0));
  sub->add_option("--radar-repeats", f->radar_table_options.repeats, "Timed echoes per row of --radar-table (median, p95)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sub->add_option("--radar-terrain-shares", f->radar_table_options.size_shares,
                  "Shares of the thesis terrain's area timed for --radar-table's growth with terrain size")
      ->delimiter(',')
      ->check(CLI::Range(1e-6, 4.0));
  sub->add_flag("--view-cells", f->view_cells,
                   "Also compute the from-region PVS of every navigable region (street or free-space cell) with each region "
                   "method and sampling, "
                   "hold some cells to the oracle, into report.json's \"view_cells\"");
  sub->add_option("--view-cell-epsilon", f->view_cell_options.epsilon, "ε (m) of the view cells' sample discs")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 1e3));
  sub->add_option("--view-cell-stride", f->view_cell_options.cell_stride, "Compute every n-th navigable region")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  sub->add_option("--view-cell-oracle-cells", f->view_cell_options.oracle_cells, "Street cells held to the oracle")
      ->capture_default_str();
  sub->add_option("--view-cell-sampling", f->view_cell_sampling, "Comma-separated: boundary, tiled")->capture_default_str();
  sub->add_option("--view-cell-threads", f->view_cell_options.threads,
                  "View cells computed at once (0: every core); the section is the same for any number")
      ->capture_default_str()
      ->check(CLI::Range(0u, 256u));
  sub->add_flag("--vbaoi", f->vbaoi_section,
                   "Also VbAoI (thesis ch. 5) on its own city (--vbaoi-generator/-seed/-params; default a 41 x 41-block "
                   "Manhattan grid of 10,086 buildings): the navigable-region graph, simulations of 10, 100 and 1,000 "
                   "clients against broadcast, neighbours-only and circular AoI, into report.json's \"vbaoi\"");
  sub->add_option("--vbaoi-generator", f->vbaoi_city.generator, "Generator of the VbAoI city")->capture_default_str();
  sub->add_option("--vbaoi-seed", f->vbaoi_city.seed, "Seed of the VbAoI city")->capture_default_str();
  sub->add_option("--vbaoi-params", f->vbaoi_city.parameters_json, "Parameters (JSON) of the VbAoI city")->capture_default_str();
  f->vbaoi.add(*sub, {10, 100, 1000}, "vbaoi-");
  sub->add_option("--benchmark-json", f->benchmark_json,
                     "Fold this Google Benchmark JSON output (bench_culling --benchmark_format=json) into the report");
  sub->add_option("--baseline", f->baseline,
                  "An earlier report.json of the same command (e.g. from an earlier build): report.json's \"speed_targets\" "
                  "gives its figures as \"before\"")
      ->check(CLI::ExistingFile);
  return [f] {
    // Read before anything runs, so a bad baseline fails at once rather than after the run.
    const std::optional<nlohmann::json> baseline =
        f->baseline.empty() ? std::nullopt : std::optional<nlohmann::json>(parse_json_flag(read_text_file(f->baseline), "baseline"));
    formats::ImportReport imported;
    const Scene scene = f->scene.source.load(&imported);
    if (imported.features > 0) std::cout << "imported " << formats::footprint_import_summary(imported) << "\n";
    if (f->view_cells) {  // bad view-cell input fails before the long run, not after it
      f->view_cell_options.samplings.clear();
      for (std::size_t start = 0; start <= f->view_cell_sampling.size();) {  // comma-separated names
        const std::size_t comma = std::min(f->view_cell_sampling.find(',', start), f->view_cell_sampling.size());
        f->view_cell_options.samplings.push_back(parse_cell_sampling(f->view_cell_sampling.substr(start, comma - start)));
        start = comma + 1;
      }
    }
    std::vector<KnobSweep> sweeps;  // bad knob sweeps fail before the long run too
    for (const std::string& text : f->knob_sweeps) sweeps.push_back(parse_knob_sweep(text));
    std::optional<Scene> vbaoi_scene;  // bad VbAoI input fails before the long run too
    if (f->vbaoi_section) {
      f->vbaoi.resolved();
      f->vbaoi.options.graph.method_options = f->tuning.options;
      vbaoi_scene = f->vbaoi_city.load();
    }
    CoordinateConversion coordinates;
    const CameraPath path = f->path.load(scene, &coordinates);
    VerificationOptions options;
    options.oracle.sampling = f->sampling.sampling;
    options.oracle_stride = f->oracle_stride;
    options.pixels = !f->no_pixels;
    options.path_replay_flags = f->path.replay_flags() + f->tuning.replay_flags();
    options.snapshot_frame = f->map_frame;
    if (f->map_frame && *f->map_frame % std::max<std::size_t>(1, f->oracle_stride) != 0)
      throw InputError("flag", "map-frame", std::to_string(*f->map_frame) + " is not a frame the oracle checks (every " +
                                                std::to_string(f->oracle_stride) + "th from 0)");
    if (f->map_frame && *f->map_frame >= path.frames.size())
      throw InputError("flag", "map-frame", std::to_string(*f->map_frame) + " is past the path's last frame (" +
                                                std::to_string(path.frames.size() - 1) + ")");
    options.region_methods = parse_methods(f->regions.methods, region_method_names());
    options.region_radius = f->regions.radius;
    options.region_turn = f->regions.turn;
    options.region_on_tiling = f->regions.placement == "tiling";
    std::cout << "scene: " << scene.provenance.generator << " seed " << scene.provenance.seed << ", "
              << scene.buildings.size() << " buildings; path: " << path.kind << ", " << path.frames.size() << " frames\n";
    // The sections this run asks for, in report order: the j-th is shard j mod N's.
    std::vector<std::string> asked;
    const std::map<std::string, bool> wanted = {
        {"region_sweep", !f->region_sweep_radii.empty()}, {"table_4_1", f->table_41}, {"online_culling", f->online_table},
        {"radar_echo", f->radar_table}, {"polar_diagram", f->polar_table}, {"slice_wise", f->slice_table},
        {"vbaoi", vbaoi_scene.has_value()},                {"scaling", !f->scaling_grids.empty()}, {"fuzz", !f->fuzz.subject.empty()},
        {"soak", f->soak.budget > 0},                      {"benchmarks", !f->benchmark_json.empty()}};
    for (const std::string& name : report_section_names())
      if (wanted.at(name)) asked.push_back(name);
    auto mine = [&](const std::string& name) {
      const auto at = std::find(asked.begin(), asked.end(), name);
      return at != asked.end() && f->shard.owns(static_cast<std::size_t>(at - asked.begin()));
    };
    options.shard = f->shard;
    f->claim_options.shard = f->shard;
    ReportParts parts;
    parts.verification = f->subjects.verify(scene, f->scene.source, path, f->path.replay_flags() + f->tuning.replay_flags(), parse_methods(f->methods),
                                            f->tuning.options, options, /*require_any=*/false);
    const PathVerification& v = parts.verification;
    f->claim_options.sampling = f->sampling.sampling;
    ReportInputs in;
    in.scene = &scene;
    in.source = f->scene.source;
    in.import = imported;
    in.path = &path;
    in.path_parameters_json = f->path.file.empty() ? f->path.params : "{}";
    in.coordinates = coordinates;
    in.path_replay_flags = f->path.replay_flags() + f->tuning.replay_flags();
    parts.header = report_header(in);
    parts.method_options = f->tuning.options;
    parts.map_method = f->map_method;
    parts.map_frame = f->map_frame;
    for (auto search : {check_shadow_elevation_rule, check_image_space_pitch_roll, check_delta_horizon_claims, check_shrinking_claims,
                        check_online_claims, check_radar_claims, check_frustum_range_claims, check_polar_claims})
      for (ClaimCheck& c : search(f->claim_options)) parts.searched_claims.push_back(std::move(c));
    if (mine("region_sweep")) {
      parts.sections["region_sweep"] =
          region_radius_sweep(scene, path, options.region_methods.empty() ? region_method_names() : options.region_methods,
                              f->region_sweep_radii, f->regions.turn, options.region_on_tiling, f->tuning.options);
      std::cout << region_sweep_table(parts.sections["region_sweep"]);
    }
    if (!sweeps.empty()) {  // every shard: its checks are at its own checked frames
      parts.knob_rows = knob_sweep_rows(scene, path, parse_methods(f->methods), f->tuning.options, sweeps, v);
      std::cout << knob_sweep_table(knob_sweep_json(*parts.knob_rows));
    }
    if (mine("table_4_1")) {
      Table41Options t;
      t.region_methods = options.region_methods;
      t.radius = f->regions.radius;
      t.oracle_stride = f->oracle_stride;
      t.oracle.sampling = f->sampling.sampling;
      parts.sections["table_4_1"] = table_4_1(t, f->tuning.options);
      std::cout << table_4_1_text(parts.sections["table_4_1"]);
    }
    if (mine("online_culling")) {
      f->online_table_options.sweep_city = std::min<std::size_t>(2, f->online_table_options.grids.size() - 1);
      f->online_table_options.pixel_threads = f->sampling.sampling.threads;
      parts.sections["online_culling"] = online_culling_table(f->online_table_options, f->tuning.options);
      std::cout << online_culling_text(parts.sections["online_culling"]);
    }
    if (mine("radar_echo")) {
      const std::filesystem::path dir = std::filesystem::path(f->output).parent_path();
      f->radar_table_options.echo_prefix = (dir / "radar_echo").string();
      parts.sections["radar_echo"] = radar_table_3_3(f->radar_table_options);
      std::cout << radar_table_3_3_text(parts.sections["radar_echo"]);
    }
    if (mine("polar_diagram")) {
      parts.sections["polar_diagram"] = polar_diagram_table(f->polar_table_options);
      std::cout << polar_diagram_table_text(parts.sections["polar_diagram"]);
    }
    if (mine("slice_wise")) {
      parts.sections["slice_wise"] = slice_wise_table(f->slice_table_options);
      parts.section_claims["slice_wise"] = slice_wise_claims(parts.sections["slice_wise"]);
      std::cout << slice_wise_table_text(parts.sections["slice_wise"]);
    }
    if (f->view_cells) {  // every shard: its share of the cells
      f->view_cell_options.methods = options.region_methods.empty() ? region_method_names() : options.region_methods;
      f->view_cell_options.oracle.sampling = f->sampling.sampling;
      f->view_cell_options.shard = f->shard;
      parts.view_cell_rows = view_cell_rows(scene, f->scene.source, f->view_cell_options, f->tuning.options);
      std::cout << view_cell_table(view_cell_section(*parts.view_cell_rows));
    }
    if (mine("vbaoi")) {
      parts.sections["vbaoi"] = vbaoi_report(*vbaoi_scene, f->vbaoi_city, f->vbaoi.options);
      std::cout << vbaoi_table(parts.sections["vbaoi"]);
      parts.section_claims["vbaoi"] = vbaoi_claims(parts.sections["vbaoi"]);
    }
    if (mine("scaling")) {
      ScalingOptions scaling;
      scaling.grids = f->scaling_grids;
      scaling.frames = f->scaling_frames;
      parts.sections["scaling"] = run_scaling(scaling);
      std::cout << scaling_table(parts.sections["scaling"]);
    }
    if (mine("fuzz")) {
      f->fuzz.sampling = f->sampling.sampling;
      const FuzzResult fuzzed = fuzz_subject(f->fuzz);
      parts.sections["fuzz"] = fuzz_json(fuzzed);
      std::string replay;
      if (fuzzed.failure) {
        replay = write_counterexample(fuzzed, f->fuzz, f->fuzz_out);
        parts.sections["fuzz"]["counterexample"] = f->fuzz_out;
      }
      std::cout << fuzz_summary(fuzzed, f->fuzz_out);
      parts.section_claims["fuzz"] = {fuzz_claim(fuzzed, replay)};
    }
    if (mine("soak")) {
      f->soak.methods = conservative_method_names();
      f->soak.sampling = f->sampling.sampling;
      f->soak.pixels = false;
      const FuzzResult soaked = fuzz_subject(f->soak);
      parts.sections["soak"] = fuzz_json(soaked);
      std::string replay;
      if (soaked.failure) {
        replay = write_counterexample(soaked, f->soak, f->soak_out);
        parts.sections["soak"]["counterexample"] = f->soak_out;
      }
      std::cout << fuzz_summary(soaked, f->soak_out);
      parts.section_claims["soak"] = fuzz_claims(soaked, replay);
    }
    if (mine("benchmarks"))
      parts.sections["benchmarks"] = parse_json_flag(read_text_file(f->benchmark_json), "benchmark-json");
    // What the shards of one run share: merge refuses shards run with other flags.
    nlohmann::json density;
    oracle::to_json(density, options.oracle.sampling);
    parts.identity = {{"methods", f->methods},
                      {"oracle_stride", options.oracle_stride},
                      {"density", density},
                      {"pixels", options.pixels},
                      {"regions", {f->regions.methods, f->regions.radius, f->regions.turn, f->regions.placement}},
                      {"claims", {f->claim_options.seed, f->claim_options.scenes, f->claim_options.cameras_per_scene}},
                      {"sections", asked},
                      {"view_cells", f->view_cells ? nlohmann::json{f->view_cell_options.epsilon, f->view_cell_options.cell_stride,
                                                                     f->view_cell_options.oracle_cells, f->view_cell_sampling}
                                                   : nlohmann::json(nullptr)},
                      {"knob_sweeps", f->knob_sweeps},
                      {"region_sweep", f->region_sweep_radii},
                      {"max_replays", options.max_replays},
                      {"subjects", f->subjects.identity()}};
    const AssembledReport assembled = assemble_report(parts);
    nlohmann::json document = f->shard.whole() ? assembled.document : shard_document(assembled.document, parts, f->shard);
    if (f->shard.whole() && baseline) document["speed_targets"] = speed_targets(document, &*baseline);
    write_text_file_atomically(f->output, document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (!f->junit.empty()) write_text_file_atomically(f->junit, junit_xml({assembled.verdict}));
    if (!f->html.empty()) {
      if (const std::string problem = write_report_page(document, &scene, f->html, 900); !problem.empty())
        std::cerr << "cullcheck: the page has no map: " << problem << "\n";
      std::cout << "wrote " << f->html << "\n";
    }
    if (document.contains("map_problem")) std::cerr << "cullcheck: " << document["map_problem"].get<std::string>() << "\n";
    std::cout << coordinates_line(coordinates, f->path.source_name("")) << "\n" << summary_table(v);
    if (document.contains("speed_targets") && !document["speed_targets"]["rows"].empty())
      std::cout << speed_targets_text(document["speed_targets"]);
    for (const ClaimCheck& c : assembled.claims) {
      std::cout << "claim " << c.id << ": " << (c.holds ? "holds" : "REFUTED") << " (" << c.frames_checked << " frames, "
                << c.violations << " violations)\n";
      if (!c.holds) std::cout << "  counterexample: " << c.counterexample_replay << "\n";
    }
    if (!f->shard.whole()) {
      std::string ran;
      for (const auto& [name, section] : parts.sections.items()) ran += (ran.empty() ? "" : ", ") + name;
      std::cout << "shard " << f->shard.text() << ": " << v.oracle.frames_checked << " of the path's checked frames, sections: "
                << (ran.empty() ? "none" : ran) << "; join the shards with `cullcheck merge`\n";
    }
    std::cout << "wrote " << f->output << "\n";
    return assembled.verdict.exit_code();
  };
}

}  // namespace cullcheck::cli
