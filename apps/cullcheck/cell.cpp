// cullcheck cell: the from-region PVS of a view cell (a navigable region or a given polygon) as
// the union of ε-disc PVSs at sample points; with --from, held to the oracle from that eye; with
// --nodes, also its PVSn (VbAoI), and with --to, a line of sight to an avatar checked against it.
// With --shard K/N, only the K-th of every N samples, into a file `cullcheck merge` joins
// (reports/cell_shards.hpp).
#include <iostream>
#include <memory>
#include <optional>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/navigable_region.hpp"
#include "core/scene_io.hpp"
#include "engine/vbaoi/navigation_graph.hpp"
#include "engine/shrinking/view_cell.hpp"
#include "generators/navigable_regions.hpp"
#include "oracle/ray_oracle.hpp"
#include "reports/report.hpp"

namespace cullcheck::cli {

Runner add_cell(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    MethodFlags tuning;
    SamplingFlags oracle_sampling;
    CoordinateFlags coordinates;
    std::string method = "shrink_adjustable_conservative", ring, sampling = "boundary", from, output;
    Shard shard;
    std::int64_t cell = -1;
    double epsilon = 1.4142135623730951, eye_height = 1.7;
    bool no_carry = false, nodes = false;
    std::vector<double> to;
    generators::FreeSpaceOptions regions;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "cell", "From-region PVS of a view cell (a street cell or a given polygon) as the union of ε-disc PVSs at "
              "sample points; with --from, hold it to the oracle from that eye");
  f->scene.add(*sub);
  f->tuning.add(*sub);
  f->oracle_sampling.add(*sub);
  sub->add_option("--method", f->method, "From-region method for each sample's disc")->capture_default_str();
  sub->add_option("--cell", f->cell,
                  "Navigable region id: a street cell of a Manhattan-family city, else a free-space cell "
                  "(generators/navigable_regions.hpp)");
  sub->add_option("--ring", f->ring, "Or the cell as a convex counter-clockwise polygon, JSON [[x,y],...]");
  sub->add_option("--cell-size", f->regions.cell_size, "Free-space cells: side of the grid no cell reaches across, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1e5));
  sub->add_option("--cell-margin", f->regions.margin, "Free-space cells: open ground kept around the scene's bounds, metres")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1e5));
  sub->add_option("--epsilon", f->epsilon, "Disc radius ε (m); samples lie at most 2ε apart")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e4));
  sub->add_option("--sampling", f->sampling, "boundary (as published) or tiled (hexagonal circle tiling)")->capture_default_str();
  sub->add_option("--eye-height", f->eye_height, "Eye height (m) of every eye in the cell")->capture_default_str();
  sub->add_flag("--no-carry", f->no_carry, "Test every building at every sample (no decisions carried between samples)");
  sub->add_option("--from", f->from, "A viewpoint (camera JSON) to check the cell's PVS from with the oracle");
  f->coordinates.add(*sub, "--from (--ring and --to are scene-local)");
  sub->add_flag("--nodes", f->nodes,
                "Also the cell's PVSn (VbAoI, thesis ch. 5.1): the scene's navigable regions, extruded to eye height, "
                "that the method does not hide (raw: before the graph makes PVSn symmetric)");
  sub->add_option("--to", f->to,
                  "With --nodes and --from: an avatar's eye X,Y (at eye height); checks the line of sight from --from's "
                  "eye to it and that its region is in the PVSn")
      ->delimiter(',')
      ->expected(2);
  add_shard_flag(*sub, f->shard,
                 "Compute shard K of N (e.g. 0/4) of the cell's samples: the n-th sample is shard n mod N's; merge the "
                 "shard files with `cullcheck merge` (needs --output; --from and --to check the merged cell)");
  sub->add_option("--output,-o", f->output, "Also write the result to this file (a shard file with --shard)");
  return [f] {
    if (!f->shard.whole()) {
      if (f->output.empty()) throw InputError("flag", "shard", "needs --output: the file `cullcheck merge` joins");
      if (!f->from.empty() || !f->to.empty())
        throw InputError("flag", "shard",
                         "cannot be given with --from or --to: a shard holds part of the cell; check the merged PVS "
                         "with `cullcheck gate --camera FROM --visible IDS`");
    }
    const Scene scene = f->scene.source.load();
    std::optional<Camera> from;
    if (!f->from.empty()) from = f->coordinates.camera(scene, f->from, "--from");
    ViewCell view_cell{{}, f->eye_height};
    if ((f->cell >= 0) == !f->ring.empty())
      throw InputError("cell", "--cell/--ring", "give exactly one of --cell ID and --ring POLYGON");
    std::vector<NavigableRegion> regions;  // the cell's, and the passive targets of --nodes
    if (f->cell >= 0 || f->nodes) regions = generators::navigable_regions(scene, f->regions);
    if (f->cell >= 0) {
      if (static_cast<std::size_t>(f->cell) >= regions.size())
        throw InputError("cell", "--cell",
                         "is " + std::to_string(f->cell) + ", the scene has " + std::to_string(regions.size()) +
                             " navigable regions (street cells or free-space cells)");
      view_cell.ring = regions[static_cast<std::size_t>(f->cell)].ring;
    } else {
      const nlohmann::json ring = parse_json_flag(f->ring, "ring");
      if (!ring.is_array()) throw InputError("cell", "--ring", "must be a JSON array of [x, y] pairs");
      for (const auto& v : ring) {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
          throw InputError("cell", "--ring", "every vertex must be a pair of numbers [x, y]");
        view_cell.ring.push_back({v[0].get<double>(), v[1].get<double>()});
      }
    }
    auto method = make_region_method(f->method, scene, f->tuning.options);
    const CellSampling sampling = parse_cell_sampling(f->sampling);
    if (!f->to.empty() && (!f->nodes || f->from.empty())) throw InputError("cell", "--to", "needs --nodes and --from");
    if (f->nodes) method->set_passive_targets(navigable_region_targets(regions, f->eye_height));
    const ViewCellResult r =
        ViewCellPvs(*method, scene, f->nodes ? regions.size() : 0).compute(view_cell, f->epsilon, sampling, !f->no_carry, {}, f->shard);
    nlohmann::json out = {{"method", f->method},        {"epsilon", f->epsilon},
                          {"sampling", f->sampling},    {"samples", r.samples},
                          {"pvs", r.pvs},               {"pvs_size", r.pvs.size()},
                          {"cull_ms", r.stats.cull_ms}, {"buildings_tested", r.stats.buildings_tested},
                          {"accepted_untested", r.stats.items_skipped}};
    int exit_code = check_from(scene, from, f->oracle_sampling.sampling, r.pvs, *method, out);
    if (f->nodes) {
      out["pvs_n"] = r.passive;
      out["pvs_n_size"] = r.passive.size();
    }
    if (!f->to.empty()) {
      const Vec3 eye = from->position;
      const Vec3 avatar{f->to[0], f->to[1], f->eye_height};
      const std::int64_t node = locate_region(regions, {avatar.x, avatar.y});
      const bool sight = oracle::RayOracle(scene).line_of_sight(eye, avatar);
      const bool listed = node >= 0 && std::binary_search(r.passive.begin(), r.passive.end(), static_cast<ObjectId>(node));
      out["to"] = {{"node", node}, {"line_of_sight", sight}, {"node_in_pvs_n", listed}};
      if (sight && node >= 0 && !listed && method->claims_conservative()) exit_code = kExitGateFailed;
    }
    if (!f->shard.whole()) {
      // What must be the same in every shard of one cell: everything that decides its samples and PVS.
      nlohmann::json cell_flags = f->cell >= 0 ? nlohmann::json{{"cell", f->cell}, {"cell_size", f->regions.cell_size}, {"cell_margin", f->regions.margin}}
                                               : nlohmann::json{{"ring", f->ring}};
      out["shard"] = {{"kind", "cell"},
                      {"index", f->shard.index},
                      {"count", f->shard.count},
                      {"cell_samples", r.cell_samples},
                      {"identity", {{"scene", f->scene.source.replay_flags()},
                                    {"cell", std::move(cell_flags)},
                                    {"method", f->method},
                                    {"method_options", method_options_json(f->tuning.options)},
                                    {"epsilon", f->epsilon},
                                    {"sampling", f->sampling},
                                    {"eye_height", f->eye_height},
                                    {"carry", !f->no_carry},
                                    {"nodes", f->nodes}}}};
    }
    if (!f->output.empty()) write_text_file_atomically(f->output, out.dump(2) + "\n");
    std::cout << out.dump() << "\n";
    return exit_code;
  };
}

}  // namespace cullcheck::cli
