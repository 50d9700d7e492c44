// From-region PVSs of view cells (issue 4, thesis ch. 5.1): every navigable region of a scene (the
// street cells of a Manhattan-family city, else free-space cells: generators/navigable_regions.hpp),
// each method and sampling, the cost per cell and in total, the saving of carrying decisions
// between neighbouring samples, and the oracle's check from viewpoints inside some cells (corners,
// edge midpoints, an interior grid).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/shard.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/view_cell.hpp"
#include "oracle/oracle.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

struct ViewCellOptions {
  std::vector<std::string> methods;  // region methods
  std::vector<CellSampling> samplings{CellSampling::boundary, CellSampling::tiled};
  double epsilon = 1.4142135623730951;  // √2 m, as the thesis's walk
  double eye_height = 1.7;
  std::size_t cell_stride = 1;    // every k-th cell (1 = all navigable regions)
  std::size_t oracle_cells = 8;   // cells held to the oracle, spread over the city
  oracle::OracleOptions oracle;
  // Cells computed at once (0: every core), each thread with its own method; the report is the
  // same for any number (cells are independent, their rows are folded in cell order).
  unsigned threads = 0;
  Shard shard;  // compute only the cells this shard owns (the n-th computed cell is shard n mod N's)
};

// The eyes a cell's PVS is checked from: corners, edge midpoints, a 3 x 3 interior grid, all
// omnidirectional at the cell's eye height.
std::vector<Camera> cell_viewpoints(const ViewCell& cell, const Camera& clip = {});

// The command that recomputes one cell's PVS and checks it from `from` with the oracle.
std::string cell_replay_command(const SceneSource& source, const std::string& method, std::uint32_t cell, double epsilon,
                                CellSampling sampling, double eye_height, const Camera& from);

// The report's "view_cells" section ({"epsilon", "eye_height", "cells", "cells_computed", "runs":
// [{method, sampling, carry, ...}]}) in two steps: one row per computed cell and run (what a shard
// writes), then the section from the rows. merge_view_cell_rows joins the rows of a run's shards.
nlohmann::json view_cell_rows(const Scene& scene, const SceneSource& source, const ViewCellOptions& options,
                              const MethodOptions& method_options);
nlohmann::json view_cell_section(const nlohmann::json& rows);
nlohmann::json merge_view_cell_rows(const std::vector<nlohmann::json>& shards);
std::string view_cell_table(const nlohmann::json& report);

}  // namespace cullcheck
