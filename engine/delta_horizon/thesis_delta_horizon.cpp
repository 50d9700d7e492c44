#include "engine/delta_horizon/thesis_delta_horizon.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/elapsed.hpp"
#include "engine/horizon/horizon_sweep.hpp"

namespace cullcheck {

ThesisDeltaHorizonCulling::ThesisDeltaHorizonCulling(const Scene& scene, const MethodOptions& options)
    : scene_(scene),
      quadtree_(scene, options.quadtree_leaf_size),
      horizon_(options.horizon_bins),
      delta_(options.horizon_bins),
      tested_at_(scene.buildings.size(), 0) {}

CullResult ThesisDeltaHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  CullStatistics& stats = result.stats;
  const ViewVolume volume(camera);
  const Vec3 eye = camera.position;
  const Vec2 e = plan(eye);
  const double unclipped = unclipped_distance(camera);
  if (++frame_ == 0) {  // stamp wrap-around: forget every stamp
    std::fill(tested_at_.begin(), tested_at_.end(), 0);
    frame_ = 1;
  }
  std::vector<std::uint32_t> front;
  std::vector<std::optional<ConvexSpan>> spans;
  QuadHeap<SweepItem> sweep;
  ShadowQueue pending;
  // Both sweeps test a building the same way, against H(t+1) (step 2) or ΔH (steps 4-5); a
  // visible one joins the PVS and queues its shadows.
  auto test_building = [&](const SweepItem& item, OcclusionHorizon& against) {
    const Building& building = scene_.buildings[item.index];
    ++stats.buildings_tested;
    tested_at_[item.index] = frame_;
    front.push_back(item.index);
    if (!volume.may_intersect(building.bounds) || box_hidden(against, building.bounds.plan(), building.height, eye) ||
        !prisms_visible(against, building, eye, spans))
      return;
    result.pvs.push_back(building.id);
    queue_shadows(pending, ShadowRule::conservative, building, eye, item.distance, unclipped, spans);
  };

  // Step 2: H(t+1) from the buildings in front of H(t), front to back.
  horizon_.reset();
  horizon_.restrict_to(azimuth_coverage(camera));
  horizon_.take_node_visits();
  for (std::uint32_t b : front_) sweep.push({min_distance(e, scene_.buildings[b].bounds.plan()), true, b});
  while (!sweep.empty()) {
    const SweepItem item = sweep.top();
    sweep.pop();
    pending.merge_nearer_than(item.distance, horizon_, stats);
    test_building(item, horizon_);
  }
  pending.merge_all(horizon_, stats);

  // Step 3: ΔH = H(t+1) - H(t): +inf where H rose (or stayed), H(t+1) in the openings. Before
  // the first frame H(t) is +inf everywhere, so everything is an opening: a full OH(OS) sweep.
  std::vector<double> delta = horizon_.bin_values();
  if (!previous_.empty())
    for (std::size_t i = 0; i < delta.size(); ++i)
      if (delta[i] >= previous_[i]) delta[i] = std::numeric_limits<double>::infinity();
  delta_.assign(delta);

  // Steps 4-5: the quadtree front to back against ΔH; what shows through the openings joins the
  // PVS and raises both H(t+1) and ΔH.
  const auto& cells = quadtree_.cells();
  if (!cells.empty() && cells[0].last > cells[0].first) sweep.push({min_distance(e, cells[0].bounds), false, 0});
  while (!sweep.empty()) {
    const SweepItem item = sweep.top();
    sweep.pop();
    pending.merge_nearer_than(item.distance, horizon_, stats, &delta_);
    if (!item.is_building) {
      const Quadtree::Cell& cell = cells[item.index];
      ++stats.cells_tested;
      const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
      if (!volume.may_intersect(box) || cell_hidden(delta_, cell, eye)) continue;
      quadtree_.for_each_child(
          cell, [&](std::uint32_t c) { sweep.push({min_distance(e, cells[c].bounds), false, c}); },
          [&](std::uint32_t b) {
            if (tested_at_[b] != frame_) sweep.push({min_distance(e, scene_.buildings[b].bounds.plan()), true, b});
          });
      continue;
    }
    test_building(item, delta_);
  }
  pending.merge_all(horizon_, stats, &delta_);

  previous_ = horizon_.bin_values();
  front_ = std::move(front);
  stats.horizon_nodes = horizon_.take_node_visits() + delta_.take_node_visits();
  std::sort(result.pvs.begin(), result.pvs.end());
  stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
