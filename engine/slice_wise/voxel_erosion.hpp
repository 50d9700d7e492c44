// A shrunk occluder that survives facade relief: the object's solid eroded by the view cell on a voxel grid
// (erosion by a structuring element, the generalisation of occluder shrinking the slice-wise paper
// cites as Décoret et al. [16]), kept as a few boxes.
//
// Why not only the paper's vertex shrinking (engine/shrinking/minkowski_mesh.hpp): it moves every
// vertex by δ = ε / sin(α/2) and drops faces whose movement volumes collide. On a facade whose
// relief is shallower than ε (window recesses of 0.3 m against ε = 1.41 m for a 2 m cell), the
// jambs, sills and wall strips between windows all collide, and the published rule drops nearly
// every face (99% of the detailed city's): the occluders become sieves. The exact Minkowski
// difference simply flattens such relief; this is a conservative approximation of it.
//
// Construction, every step conservative (the result lies inside O ⊖ H, H the element box):
//  1. Inside voxels: a voxel (side r) no boundary triangle touches (a separating-axis test, the
//     box widened by 1e-9 m; floor triangles, on the object's lowest plane, do not count: they
//     bound the lowest voxels from below only, where the ground is; nor do faces between two of
//     the object's solids, solid_parts.hpp) lies wholly inside or wholly outside the union of the
//     mesh's closed solids; it is inside when a point of it is inside one solid, by the parity of
//     the crossings of a vertical line through the column with that solid's non-vertical
//     triangles (the centre's line, else one of three others inside the column). A column where
//     every such line passes within 1e-9 of a triangle's edge, or crosses a solid an odd number
//     of times, is taken as wholly outside.
//  2. Erosion by a box of half-sides h (the structuring element; see erode_closed_mesh): a voxel
//     is kept when every voxel within ceil(h / r) steps on each axis is inside. Below the
//     object's lowest point counts as solid: eyes stand on the ground, so nothing is seen from
//     below it (the paper's Fig. 16 leaves ground vertices at the ground for the same reason).
//  3. Boxes: the kept voxels merged greedily (runs along x, widened along y, then raised along z).
//  4. Each box pushed out face by face as far as the box grown by the element meets no boundary
//     face (clipped exactly to the grown box's cross-section), 1e-9 m short, and no further than
//     its mesh's bounds: what the voxels the boundary passes through lost comes back, and an
//     axis-aligned solid is eroded exactly (a block's walls recede by h, not h plus a voxel).
// Only for closed meshes (MeshObject::closed): parity means nothing on an open surface.
#pragma once

#include <cstddef>
#include <vector>

#include "core/scene.hpp"
#include "engine/shrinking/minkowski_mesh.hpp"

namespace cullcheck::slice_wise {

struct VoxelErosion {
  std::vector<Box3> boxes;
  std::size_t voxels = 0, inside = 0, kept = 0;
  std::size_t ambiguous_columns = 0;  // taken as outside
  std::size_t solids = 0;              // closed solids the mesh is made of (solid_parts.hpp)
  std::size_t interior_triangles = 0;  // faces between two of them: not the union's boundary
  std::size_t partly_interior_triangles = 0;  // faces partly so: only the rest is boundary
  bool outward = false;  // every solid wound outward (positive signed volume)
  // Eroding several meshes as one (erode_closed_meshes): per box, the mesh it belongs to (the one
  // with a solid holding its voxels' centres), and per mesh whether its own solids are all outward.
  std::vector<std::uint32_t> box_owner;
  std::vector<std::uint8_t> outward_of;
};

// Erodes by the box [-h.x, h.x] x [-h.y, h.y] x [-h.z, h.z] (a cube of half-side ε holds the
// ball of radius ε; a square view cell of half-side s/2 at eye height is the box (s/2, s/2, 0)).
// Throws std::invalid_argument unless r is positive and finite and h's sides finite and not
// negative, or when the grid would exceed `max_voxels`.
VoxelErosion erode_closed_mesh(const MeshObject& mesh, Vec3 h, double voxel_m, std::size_t max_voxels = 50'000'000);

// Closed meshes that lie against one another (a row of houses sharing party walls, solid_parts.hpp's
// touching_pairs) eroded as the union of their solids, then the kept voxels handed back to the mesh
// each one's centre lies in (boxes merge within one mesh only). Each mesh eroded on its own recedes
// from every party wall, so a row of houses becomes blocks with a slot of 2 h.x between
// neighbours, through which a whole district behind them is seen; the union has no slot there.
// Every box still lies inside the union eroded by the element, which is all Theorem 1 asks of an
// occluder: it hides a point only where the solids hide it from every eye of the cell.
VoxelErosion erode_closed_meshes(const std::vector<const MeshObject*>& meshes, Vec3 h, double voxel_m,
                                 std::size_t max_voxels = 50'000'000);

// The boxes as one triangle mesh (12 triangles a box, outward).
TriangleMesh boxes_mesh(const std::vector<Box3>& boxes);

}  // namespace cullcheck::slice_wise
