#include "engine/spatial/traversal_bound.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cullcheck {

ExactTraversal::ExactTraversal(const Quadtree& quadtree, const Scene& scene) : quadtree_(quadtree) {
  if (quadtree.buildings().size() != scene.buildings.size())
    throw std::invalid_argument("traversal bound: the quadtree holds " + std::to_string(quadtree.buildings().size()) +
                                " buildings, the scene " + std::to_string(scene.buildings.size()) + ": not built on it");
  index_of_.reserve(scene.buildings.size());
  for (std::uint32_t b = 0; b < scene.buildings.size(); ++b) index_of_.emplace_back(scene.buildings[b].id, b);
  std::sort(index_of_.begin(), index_of_.end());
  const auto& cells = quadtree.cells();
  const auto& order = quadtree.buildings();
  leaf_of_.assign(scene.buildings.size(), 0);
  parent_.assign(cells.size(), 0);
  holds_.assign(cells.size(), 0);
  for (std::uint32_t c = 0; c < cells.size(); ++c) {
    if (cells[c].leaf()) {
      for (std::uint32_t i = cells[c].first; i < cells[c].last; ++i) leaf_of_[order[i]] = c;
      continue;
    }
    for (std::uint32_t k = cells[c].first_child; k < cells[c].first_child + 4; ++k) parent_[k] = c;
  }
}

void ExactTraversal::enter(std::uint32_t cell, TraversalBound& bound) const {
  const auto& cells = quadtree_.cells();
  const Quadtree::Cell& c = cells[cell];
  if (c.leaf()) {
    bound.buildings += c.last - c.first;
    return;
  }
  for (std::uint32_t k = c.first_child; k < c.first_child + 4; ++k) {
    if (cells[k].last == cells[k].first) continue;
    ++bound.cells;
    if (holds_[k]) enter(k, bound);
  }
}

TraversalBound ExactTraversal::tests_for(const std::vector<ObjectId>& pvs) {
  TraversalBound bound;
  const auto& cells = quadtree_.cells();
  if (cells.empty() || cells[0].last == cells[0].first) {
    if (!pvs.empty()) throw std::invalid_argument("traversal bound: a PVS of an empty city");
    return bound;
  }
  // Mark the cells on the way from each PVS building's leaf up to the root.
  for (ObjectId id : pvs) {
    auto it = std::lower_bound(index_of_.begin(), index_of_.end(), std::pair<ObjectId, std::uint32_t>{id, 0});
    if (it == index_of_.end() || it->first != id) {
      for (std::uint32_t c : marked_) holds_[c] = 0;
      marked_.clear();
      throw std::invalid_argument("traversal bound: PVS id " + std::to_string(id) + " is not a building of the scene");
    }
    for (; it != index_of_.end() && it->first == id; ++it)
      for (std::uint32_t c = leaf_of_[it->second]; !holds_[c]; c = parent_[c]) {
        holds_[c] = 1;
        marked_.push_back(c);
        if (c == 0) break;
      }
  }
  bound.cells = 1;  // the root is tested whatever it holds
  if (holds_[0]) enter(0, bound);
  for (std::uint32_t c : marked_) holds_[c] = 0;
  marked_.clear();
  return bound;
}

TraversalBound top_down_test_bound(const Quadtree& quadtree, const Scene& scene, const std::vector<ObjectId>& pvs) {
  return ExactTraversal(quadtree, scene).tests_for(pvs);
}

}  // namespace cullcheck
