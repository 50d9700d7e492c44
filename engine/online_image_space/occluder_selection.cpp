#include "engine/online_image_space/occluder_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace cullcheck::online {
namespace {

struct Queued {
  double phi;
  std::int32_t node;
  bool operator>(const Queued& o) const { return phi > o.phi || (phi == o.phi && node > o.node); }
};

class Coverage {
 public:
  Coverage(const ImagePlane& plane, int grid) : plane_(plane), grid_(std::max(1, grid)), cells_(std::size_t(grid_) * std::size_t(grid_), 0.0) {}

  // min C over the cells under the box's centre and its diagonal's ends (0 when none projects).
  double least(const Box3& box) const {
    const Vec3 samples[3] = {(box.lo + box.hi) * 0.5, box.lo, box.hi};
    double least = std::numeric_limits<double>::infinity();
    for (const Vec3& s : samples) {
      int cx, cy;
      if (cell_of(s, cx, cy)) least = std::min(least, cells_[std::size_t(cy) * std::size_t(grid_) + std::size_t(cx)]);
    }
    return std::isfinite(least) ? least : 0.0;
  }

  // Spreads `count` polygons over the cells the box's projection covers.
  void add(const Box3& box, double count) {
    double x_lo = plane_.width(), x_hi = 0.0, y_lo = plane_.height(), y_hi = 0.0;
    bool behind = false;
    for (int k = 0; k < 8 && !behind; ++k) {
      const Vec3 c = plane_.to_camera({k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z});
      if (c.z < plane_.near()) {
        behind = true;
        break;
      }
      const ViewPoint p = plane_.project(c);
      x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x), y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
    }
    if (behind) x_lo = 0, y_lo = 0, x_hi = plane_.width(), y_hi = plane_.height();
    if (x_hi < 0 || y_hi < 0 || x_lo > plane_.width() || y_lo > plane_.height()) return;
    const double cw = double(plane_.width()) / grid_, ch = double(plane_.height()) / grid_, last = grid_ - 1;
    // Clamped as doubles before the conversion: projections can lie far off the image.
    const int cx0 = int(std::clamp(x_lo / cw, 0.0, last)), cx1 = int(std::clamp(x_hi / cw, 0.0, last));
    const int cy0 = int(std::clamp(y_lo / ch, 0.0, last)), cy1 = int(std::clamp(y_hi / ch, 0.0, last));
    const double share = count / double((cx1 - cx0 + 1) * (cy1 - cy0 + 1));
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx) cells_[std::size_t(cy) * std::size_t(grid_) + std::size_t(cx)] += share;
  }

 private:
  bool cell_of(Vec3 p, int& cx, int& cy) const {
    const Vec3 c = plane_.to_camera(p);
    if (c.z < plane_.near()) return false;
    const ViewPoint v = plane_.project(c);
    if (!(v.x >= 0 && v.x < plane_.width() && v.y >= 0 && v.y < plane_.height())) return false;
    cx = std::min(grid_ - 1, int(v.x * grid_ / plane_.width()));
    cy = std::min(grid_ - 1, int(v.y * grid_ / plane_.height()));
    return true;
  }

  const ImagePlane& plane_;
  int grid_;
  std::vector<double> cells_;
};

void collect(const PolygonKdTree& tree, std::int32_t n, std::vector<std::uint32_t>& out) {
  const auto& node = tree.nodes()[std::size_t(n)];
  if (node.count == 0) return;
  if (node.leaf()) {
    out.insert(out.end(), node.polygons.begin(), node.polygons.end());
    return;
  }
  collect(tree, node.child[0], out), collect(tree, node.child[1], out);
}

}  // namespace

double min_distance(Vec3 p, const Box3& b) {
  const double dx = std::max({b.lo.x - p.x, 0.0, p.x - b.hi.x});
  const double dy = std::max({b.lo.y - p.y, 0.0, p.y - b.hi.y});
  const double dz = std::max({b.lo.z - p.z, 0.0, p.z - b.hi.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

OccluderSelection select_occluders(const PolygonKdTree& tree, const ScenePolygons& polygons, const ImagePlane& plane,
                                   const ViewVolume& volume, const SelectionParameters& p) {
  OccluderSelection out;
  out.nearest = std::numeric_limits<double>::infinity();
  if (tree.nodes().empty() || p.occluders == 0) return out;
  Coverage coverage(plane, p.coverage_grid);
  const Vec3 eye = plane.eye();
  const auto phi = [&](std::int32_t n) {
    const double d = min_distance(eye, tree.nodes()[std::size_t(n)].box);
    return p.priority == OccluderPriority::distance ? d : (1.0 + coverage.least(tree.nodes()[std::size_t(n)].box)) * d;
  };
  std::priority_queue<Queued, std::vector<Queued>, std::greater<>> queue;
  queue.push({phi(0), 0});
  while (!queue.empty() && out.polygons.size() < p.occluders) {
    const Queued top = queue.top();
    queue.pop();
    const auto& node = tree.nodes()[std::size_t(top.node)];
    ++out.nodes_visited;
    if (node.count == 0 || !volume.may_intersect(node.box)) continue;
    if (p.priority == OccluderPriority::coverage) {
      const double now = phi(top.node);
      if (now > top.phi && !queue.empty() && queue.top().phi < now) {  // stale: covered since it was queued
        queue.push({now, top.node});
        continue;
      }
    }
    const double distance = min_distance(eye, node.box);
    if ((node.leaf() || node.count <= p.node_polygons) && distance >= p.min_distance) {
      const std::size_t before = out.polygons.size();
      collect(tree, top.node, out.polygons);
      for (std::size_t i = before; i < out.polygons.size(); ++i) out.nearest = std::min(out.nearest, min_distance(eye, polygons.box[out.polygons[i]]));
      if (p.priority == OccluderPriority::coverage) coverage.add(node.box, double(node.count));
    } else if (!node.leaf()) {
      for (std::int32_t c : node.child) queue.push({phi(c), c});
    }
  }
  std::sort(out.polygons.begin(), out.polygons.end());
  return out;
}

}  // namespace cullcheck::online
