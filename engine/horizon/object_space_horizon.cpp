#include "engine/horizon/object_space_horizon.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>
#include <queue>


namespace cullcheck {
namespace {

// One entry of the front-to-back sweep: a quadtree cell or a building, keyed by its nearest plan
// distance; ties broken by kind and index so that the order is deterministic.
struct SweepItem {
  double distance;
  bool is_building;
  std::uint32_t index;  // cell index, or scene building index
  bool operator>(const SweepItem& o) const {
    if (distance != o.distance) return distance > o.distance;
    if (is_building != o.is_building) return is_building > o.is_building;
    return index > o.index;
  }
};

// A shadow waiting until the sweep passes the CVP's farthest point.
struct PendingShadow {
  double farthest;
  AzimuthSpan span;
  double slope;
  std::uint64_t order;  // insertion order, for a deterministic tie-break
  bool operator>(const PendingShadow& o) const {
    return farthest != o.farthest ? farthest > o.farthest : order > o.order;
  }
};

template <class T>
using MinQueue = std::priority_queue<T, std::vector<T>, std::greater<T>>;

}  // namespace

ObjectSpaceHorizonCulling::ObjectSpaceHorizonCulling(const Scene& scene, ShadowRule rule, const MethodOptions& options)
    : scene_(scene), rule_(rule), quadtree_(scene, options.quadtree_leaf_size), horizon_(options.horizon_bins) {}

std::string ObjectSpaceHorizonCulling::name() const {
  return rule_ == ShadowRule::thesis ? "oh_os_thesis" : "oh_os_conservative";
}

double ObjectSpaceHorizonCulling::shadow_slope(const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span) const {
  const Vec2 e = plan(eye);
  const double rise = prism.height - eye.z;
  if (rule_ == ShadowRule::thesis || rise >= 0.0) {
    const double d1 = length(prism.ring[span.first_tangent] - e);
    const double d2 = length(prism.ring[span.last_tangent] - e);
    return std::min(rise / d1, rise / d2);
  }
  return rise / min_far_chain_distance(prism.ring, e);
}

CullResult ObjectSpaceHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  CullStatistics& stats = result.stats;
  const ViewVolume volume(camera);
  const Vec3 eye = camera.position;
  const Vec2 e = plan(eye);
  // Geometry nearer than the near plane is clipped and hides nothing. A point of the view
  // volume lies at least `near` deep, so at least near / cos(corner angle) from the eye; a CVP
  // whose plan distance is below that may be partly clipped and is not used as an occluder.
  const double unclipped_distance =
      camera.omnidirectional()
          ? 0.0
          : camera.near * std::sqrt(1.0 + std::pow(std::tan(camera.hfov / 2), 2) + std::pow(std::tan(camera.vfov / 2), 2));
  horizon_.reset();
  horizon_.restrict_to(azimuth_coverage(camera));
  horizon_.take_node_visits();

  MinQueue<SweepItem> sweep;
  MinQueue<PendingShadow> pending;
  std::uint64_t shadow_order = 0;
  std::vector<std::optional<ConvexSpan>> spans;
  const auto& cells = quadtree_.cells();
  const auto& order = quadtree_.buildings();
  if (!cells.empty() && cells[0].last > cells[0].first) sweep.push({min_distance(e, cells[0].bounds), false, 0});

  // Hidden: outside the azimuth span's horizon. Boxes that contain the eye cannot be culled.
  auto hidden_box = [&](const Box2& box, double top) {
    const auto span = box_span(box, e);
    if (!span) return false;
    return horizon_.hides(span->span, max_slope(top, eye.z, min_distance(e, box), max_distance(e, box)));
  };

  while (!sweep.empty()) {
    const SweepItem item = sweep.top();
    sweep.pop();
    // Merge every shadow whose prism lies wholly nearer than this item.
    while (!pending.empty() && pending.top().farthest < item.distance) {
      horizon_.raise(pending.top().span, pending.top().slope);
      ++stats.occluders_applied;
      pending.pop();
    }
    if (!item.is_building) {
      const Quadtree::Cell& cell = cells[item.index];
      ++stats.cells_tested;
      const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
      if (!volume.may_intersect(box) || hidden_box(cell.bounds, cell.max_height)) continue;
      if (cell.leaf()) {
        for (std::uint32_t i = cell.first; i < cell.last; ++i)
          sweep.push({min_distance(e, scene_.buildings[order[i]].bounds.plan()), true, order[i]});
      } else {
        for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c)
          if (cells[c].last > cells[c].first) sweep.push({min_distance(e, cells[c].bounds), false, c});
      }
      continue;
    }
    const Building& building = scene_.buildings[item.index];
    ++stats.buildings_tested;
    if (!volume.may_intersect(building.bounds) || hidden_box(building.bounds.plan(), building.height)) continue;
    // The bounding box is visible; the building is hidden only if every CVP is. Spans are kept
    // for the shadows of a visible building.
    spans.clear();
    bool visible = false;
    for (const ConvexVerticalPrism& prism : building.prisms) {
      spans.push_back(convex_span(prism.ring, e));
      const auto& span = spans.back();
      visible = visible || !span ||
                !horizon_.hides(span->span, max_slope(prism.height, eye.z, min_boundary_distance(prism.ring, e),
                                                      max_vertex_distance(prism.ring, e)));
    }
    if (!visible) continue;
    result.pvs.push_back(building.id);
    const bool may_be_clipped = item.distance < unclipped_distance;  // item.distance: nearest point of its box
    for (std::size_t p = 0; p < building.prisms.size(); ++p) {
      const ConvexVerticalPrism& prism = building.prisms[p];
      // An eye inside or on a CVP gets no span: such a CVP cannot occlude.
      if (!spans[p] || (may_be_clipped && min_boundary_distance(prism.ring, e) < unclipped_distance)) continue;
      pending.push({max_vertex_distance(prism.ring, e), spans[p]->span, shadow_slope(prism, eye, *spans[p]), shadow_order++});
    }
  }
  std::sort(result.pvs.begin(), result.pvs.end());
  stats.horizon_nodes = horizon_.take_node_visits();
  stats.cull_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace cullcheck
