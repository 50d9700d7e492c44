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
#include <vector>

#include "core/scene.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

struct TraversalBound {
  std::uint64_t cells = 0;      // cells an exact traversal tests (root included)
  std::uint64_t buildings = 0;  // buildings it tests in the leaves it enters
  std::uint64_t total() const { return cells + buildings; }
};

// `quadtree` must be built on `scene`; `pvs`: building ids, any order. std::invalid_argument for an
// id the scene lacks or a quadtree of another size.
TraversalBound top_down_test_bound(const Quadtree& quadtree, const Scene& scene, const std::vector<ObjectId>& pvs);

}  // namespace cullcheck
