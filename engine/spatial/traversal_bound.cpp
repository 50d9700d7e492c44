#include "engine/spatial/traversal_bound.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace cullcheck {
namespace {

struct Counter {
  const Quadtree& quadtree;
  const std::vector<char>& kept;  // by scene building index
  TraversalBound bound;

  bool holds(const Quadtree::Cell& cell) const {
    const auto& order = quadtree.buildings();
    for (std::uint32_t i = cell.first; i < cell.last; ++i)
      if (kept[order[i]]) return true;
    return false;
  }
  // `cell` was tested and holds a kept building: count what entering it tests.
  void enter(const Quadtree::Cell& cell) {
    if (cell.leaf()) {
      bound.buildings += cell.last - cell.first;
      return;
    }
    const auto& cells = quadtree.cells();
    for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c) {
      if (cells[c].last == cells[c].first) continue;
      ++bound.cells;
      if (holds(cells[c])) enter(cells[c]);
    }
  }
};

}  // namespace

TraversalBound top_down_test_bound(const Quadtree& quadtree, const Scene& scene, const std::vector<ObjectId>& pvs) {
  if (quadtree.buildings().size() != scene.buildings.size())
    throw std::invalid_argument("traversal bound: the quadtree holds " + std::to_string(quadtree.buildings().size()) +
                                " buildings, the scene " + std::to_string(scene.buildings.size()) + ": not built on it");
  std::vector<std::pair<ObjectId, std::uint32_t>> index_of;
  index_of.reserve(scene.buildings.size());
  for (std::uint32_t b = 0; b < scene.buildings.size(); ++b) index_of.emplace_back(scene.buildings[b].id, b);
  std::sort(index_of.begin(), index_of.end());
  std::vector<char> kept(scene.buildings.size(), 0);
  for (ObjectId id : pvs) {
    const auto it = std::lower_bound(index_of.begin(), index_of.end(), std::pair<ObjectId, std::uint32_t>{id, 0});
    if (it == index_of.end() || it->first != id)
      throw std::invalid_argument("traversal bound: PVS id " + std::to_string(id) + " is not a building of the scene");
    for (auto same = it; same != index_of.end() && same->first == id; ++same) kept[same->second] = 1;
  }
  Counter counter{quadtree, kept, {}};
  const auto& cells = quadtree.cells();
  if (cells.empty() || cells[0].last == cells[0].first) return counter.bound;
  counter.bound.cells = 1;  // the root is tested whatever it holds
  if (counter.holds(cells[0])) counter.enter(cells[0]);
  return counter.bound;
}

}  // namespace cullcheck
