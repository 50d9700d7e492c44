#include "engine/frustum/view_frustum_culling.hpp"

#include <algorithm>
#include <chrono>

namespace cullcheck {

ViewFrustumCulling::ViewFrustumCulling(const Scene& scene, const MethodOptions& options)
    : scene_(scene), quadtree_(scene, options.quadtree_leaf_size) {}

CullResult ViewFrustumCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  const ViewVolume volume(camera);
  const auto& cells = quadtree_.cells();
  const auto& order = quadtree_.buildings();
  std::vector<std::uint32_t> stack;
  if (!cells.empty() && cells[0].last > cells[0].first) stack.push_back(0);
  while (!stack.empty()) {
    const Quadtree::Cell& cell = cells[stack.back()];
    stack.pop_back();
    ++result.stats.cells_tested;
    if (!volume.may_intersect({{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}}))
      continue;
    if (!cell.leaf()) {
      for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c)
        if (cells[c].last > cells[c].first) stack.push_back(c);
      continue;
    }
    for (std::uint32_t i = cell.first; i < cell.last; ++i) {
      const Building& b = scene_.buildings[order[i]];
      ++result.stats.buildings_tested;
      if (volume.may_intersect(b.bounds)) result.pvs.push_back(b.id);
    }
  }
  for (const MeshObject& m : scene_.meshes) {
    ++result.stats.buildings_tested;
    if (volume.may_intersect(m.bounds)) result.pvs.push_back(m.id);
  }
  std::sort(result.pvs.begin(), result.pvs.end());
  result.stats.cull_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace cullcheck
