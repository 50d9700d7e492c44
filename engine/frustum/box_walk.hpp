// The frustum methods' walk over a scene's bounding boxes: the quadtree's cells front to back
// (a cell outside drops its subtree), the buildings of the leaves kept, then every mesh object's
// box; the PVS sorted, the cells and objects tested counted. The box test is the method's: the
// six planes (view_frustum_culling.hpp) or the camera-space ranges (range_detection.hpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/scene.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

// keep_cell(box) and keep_object(box, index): true when the box may meet the view; `index` is a
// building's index in scene.buildings, or -1 for a mesh object.
template <class KeepCell, class KeepObject>
void walk_boxes(const Quadtree& quadtree, const Scene& scene, KeepCell&& keep_cell, KeepObject&& keep_object, CullResult& result) {
  const auto& cells = quadtree.cells();
  const auto& order = quadtree.buildings();
  std::vector<std::uint32_t> stack;
  if (!cells.empty() && cells[0].last > cells[0].first) stack.push_back(0);
  while (!stack.empty()) {
    const Quadtree::Cell& cell = cells[stack.back()];
    stack.pop_back();
    ++result.stats.cells_tested;
    if (!keep_cell(Box3{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}})) continue;
    if (!cell.leaf()) {
      for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c)
        if (cells[c].last > cells[c].first) stack.push_back(c);
      continue;
    }
    for (std::uint32_t i = cell.first; i < cell.last; ++i) {
      const Building& b = scene.buildings[order[i]];
      ++result.stats.buildings_tested;
      if (keep_object(b.bounds, static_cast<std::int64_t>(order[i]))) result.pvs.push_back(b.id);
    }
  }
  for (const MeshObject& m : scene.meshes) {
    ++result.stats.buildings_tested;
    if (keep_object(m.bounds, std::int64_t{-1})) result.pvs.push_back(m.id);
  }
  std::sort(result.pvs.begin(), result.pvs.end());
}

}  // namespace cullcheck
