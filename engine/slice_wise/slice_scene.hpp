// What the slice-wise culling prepares once per scene and view-cell size (Yılmaz & Güdükbay
// Fig. 8, the preprocessing boxes): each object sliced (slicing.hpp), each object's shrunk
// occluder, and a quadtree over the objects' ground boxes for the coarse culling.
//
// Two ways to shrink (both conservative: the occluder lies inside the object eroded by the cell):
//  - minkowski_mesh, as published (engine/shrinking/minkowski_mesh.hpp): vertices moved by
//    δ = ε / sin(α/2), colliding faces dropped;
//  - voxel_erosion, the corrected variant (voxel_erosion.hpp): the closed solid eroded on a voxel
//    grid and kept as boxes, because the published rule drops nearly every face of a facade whose
//    relief is shallower than ε. An object whose mesh is not closed falls back to minkowski_mesh.
//    Objects that lie against one another (a row of houses) are eroded as one solid, each keeping
//    the boxes inside its own solids.
//
// Objects are the scene's mesh objects followed by its buildings; a building (a 2.5D prism) is
// sliced and shrunk as its closed mesh (minkowski_mesh.hpp's building_mesh), so every object has
// slices, although only mesh objects have triangles the oracle names one by one.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/scene.hpp"
#include "engine/shrinking/minkowski_mesh.hpp"
#include "engine/slice_wise/slicing.hpp"

namespace cullcheck::slice_wise {

enum class Shrinking { minkowski_mesh, voxel_erosion };
std::string_view shrinking_name(Shrinking s);
Shrinking parse_shrinking(std::string_view name);  // std::invalid_argument naming the accepted values

struct SliceWiseObject {
  ObjectId id = 0;
  bool is_mesh = true;          // Scene::meshes[scene_index], else Scene::buildings[scene_index]
  std::size_t scene_index = 0;
  Box3 box;                     // of its triangles
  SlicedObject slices;
  // Per triangle, its slice index ranges: x first/last, y first/last, z first/last.
  std::vector<std::array<std::uint8_t, 6>> ranges;
  // Per axis and slice: the box of the slice's triangles cut to its slab (what Algorithm 2 tests:
  // every triangle of the slice lies in it, and it leaves out the empty parts of the object's box).
  std::array<std::vector<Box3>, 3> slice_boxes;
  TriangleMesh occluder;        // shrunk by ε; may be empty (every face dropped)
  Box3 occluder_box;            // of the occluder's kept triangles
  MeshShrinkStatistics shrink;  // minkowski_mesh
  Shrinking shrunk_by = Shrinking::minkowski_mesh;
  std::size_t occluder_boxes = 0;  // voxel_erosion
  std::uint32_t eroded_with = 1;   // objects in the solid it was eroded as (touching neighbours)
  // Closed, every solid wound outward (checked by voxel_erosion): a face turned away from an eye
  // outside the object is hidden from it by the object itself.
  bool outward_solids = false;
  double shrink_seconds = 0.0;
  std::size_t triangles() const { return slices.triangle_count; }
};

// A quadtree over the objects' plan boxes: each node's box (3D) holds every object below it.
struct ObjectTree {
  struct Node {
    Box3 box;
    std::uint32_t first_child = 0;  // children first_child .. first_child + child_count - 1
    std::uint32_t child_count = 0;  // 0 for a leaf
    std::uint32_t first = 0, last = 0;  // objects order[first, last)
  };
  std::vector<Node> nodes;           // nodes[0] is the root
  std::vector<std::uint32_t> order;  // object indices
};
ObjectTree build_object_tree(const std::vector<Box3>& boxes, std::uint32_t leaf_size = 8);

struct SliceSceneOptions {
  double epsilon = 1.4142135623730951;  // the view cell's largest distance from its centre
  Shrinking shrinking = Shrinking::minkowski_mesh;
  // voxel_erosion's grid. A wall recedes by the cell's half-side and by up to one voxel more (the
  // voxels it passes through count as outside): 0.25 m loses half of what 0.5 m did, for about
  // 8 times the voxels and 3 times the boxes.
  double voxel_m = 0.25;
  // What voxel_erosion erodes by. `square`: the view cell itself, the axis-aligned square of
  // half-side ε/√2 at eye height (eyes move on a plane, so walls recede by s/2, roofs not at all:
  // the Minkowski difference O ⊖ cell on which Theorem 1's proof rests). `ball`: the ball of
  // radius ε (a cube of half-side ε on the grid), for eyes that also move up and down; the
  // published minkowski_mesh always shrinks by the ball.
  enum class Element { square, ball };
  Element erosion_element = Element::square;
  // voxel_erosion: closed objects that lie against one another (shared party walls) eroded as
  // one solid, so that no slot opens between neighbours; a group whose joint grid would exceed
  // max_joint_voxels is eroded object by object.
  bool erode_touching = true;
  std::size_t max_joint_voxels = 50'000'000;
  SlicingOptions slicing;
  unsigned threads = 0;  // for shrinking and slicing (0: every core); the result does not depend on it
};

class SliceWiseScene {
 public:
  // Throws std::invalid_argument on a bad option.
  SliceWiseScene(const Scene& scene, const SliceSceneOptions& options);
  const std::vector<SliceWiseObject>& objects() const { return objects_; }
  const ObjectTree& tree() const { return tree_; }
  const SliceSceneOptions& options() const { return options_; }
  const Scene& scene() const { return scene_; }
  double slicing_seconds() const { return slicing_seconds_; }
  double shrinking_seconds() const { return shrinking_seconds_; }  // wall time, all objects

 private:
  const Scene& scene_;
  SliceSceneOptions options_;
  std::vector<SliceWiseObject> objects_;
  ObjectTree tree_;
  double slicing_seconds_ = 0.0, shrinking_seconds_ = 0.0;
};

// A building's closed mesh as a mesh object (the form slicing takes): building_mesh's walls and
// roof, and a floor.
MeshObject building_as_mesh(const Building& building);

}  // namespace cullcheck::slice_wise
