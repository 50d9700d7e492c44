// The fewest tests a front-to-back traversal of a quadtree needs to output a given PVS, even with
// exact tests (issue 17: OH(OS)'s cost against a bound one can defend).
//
// A top-down traversal outputs a building only from a leaf it entered, and enters a cell only
// after testing it. Entering a cell means deciding each of its non-empty children (or, for a
// leaf, each of its buildings), so each of them costs a test; a perfect test then enters exactly
// the cells whose subtree holds a building of the PVS and stops at every other child. The bound
// counts those tests: the root, every non-empty child of an entered inner cell, every building of
// an entered leaf. Any method that sweeps this quadtree (OH(OS), the from-region sweeps) makes
// at least these tests for its own PVS; what it makes beyond them went into cells that passed
// their test but led to nothing it keeps.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/scene.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

struct TraversalBound {
  std::uint64_t cells = 0;      // cells an exact traversal tests (root included)
  std::uint64_t buildings = 0;  // buildings it tests in the leaves it enters
  std::uint64_t total() const { return cells + buildings; }
};

// Counts the bound frame after frame for one quadtree and the scene it was built on (both must
// outlive it; std::invalid_argument when the quadtree holds another number of buildings). A PVS
// costs its size times the tree's depth plus the cells entered, not a pass over the city.
class ExactTraversal {
 public:
  ExactTraversal(const Quadtree& quadtree, const Scene& scene);
  const Quadtree& quadtree() const { return quadtree_; }
  // `pvs`: building ids, any order; std::invalid_argument for an id the scene lacks.
  TraversalBound tests_for(const std::vector<ObjectId>& pvs);

 private:
  void enter(std::uint32_t cell, TraversalBound& bound) const;
  const Quadtree& quadtree_;
  std::vector<std::pair<ObjectId, std::uint32_t>> index_of_;  // (id, scene index), sorted
  std::vector<std::uint32_t> leaf_of_;  // scene building index -> its leaf
  std::vector<std::uint32_t> parent_;   // cell -> parent (the root's is itself)
  std::vector<char> holds_;             // per cell, during a count: its subtree holds a PVS building
  std::vector<std::uint32_t> marked_;   // the cells marked, to clear them afterwards
};

// One count, for a single PVS.
TraversalBound top_down_test_bound(const Quadtree& quadtree, const Scene& scene, const std::vector<ObjectId>& pvs);

}  // namespace cullcheck
