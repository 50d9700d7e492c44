// The 2D kd-tree of section 4 (Wang, Agarwal & Har-Peled 2001): built on the anchor points p_Δ
// (the xy-projection of the bottom-left corner of each polygon's box), each node with the 3D box
// B_τ of the polygons whose anchors it holds, the number of (live) polygons below it, and the
// time stamp until which it is known occluded (section 5.5). A node is a leaf when it holds at
// most ρ polygons; a leaf stores its polygons, interior nodes none, so the size is O(n).
//
// Splitter: the median anchor along the longer side of the anchors' extent ("bisect the points").
// Dynamic scenes (section 6): insertion descends by the splitters to a leaf, grows the boxes on
// its way, drops their time stamps (a grown box was never tested against a mask; a stamp moves
// down to the child off the way, whose box did not grow) and splits a
// leaf that reaches 2ρ + 1 polygons; deletion is lazy, removing the polygon
// from its leaf and the counts but leaving the boxes as they were (still bounding, only looser).
// Leaves keep their polygons sorted, so a tree does not depend on the standard library's sort.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/online_image_space/scene_polygons.hpp"

namespace cullcheck::online {

class PolygonKdTree {
 public:
  struct Node {
    Box3 box;                    // B_τ: bounds every polygon stored below (after deletions, loosely)
    std::uint32_t count = 0;     // live polygons below
    std::int32_t child[2] = {-1, -1};
    std::int32_t parent = -1;
    int axis = 0;                // 0: x, 1: y; anchors with coordinate < split go to child[0]
    double split = 0.0;
    std::vector<std::uint32_t> polygons;  // leaves only, ascending
    double stamp = -std::numeric_limits<double>::infinity();  // occluded while time < stamp
    bool leaf() const { return child[0] < 0; }
  };

  // Every polygon of `polygons` (which must outlive the tree) goes in.
  PolygonKdTree(const ScenePolygons& polygons, std::uint32_t leaf_size);

  const std::vector<Node>& nodes() const { return nodes_; }
  std::vector<Node>& nodes() { return nodes_; }
  std::uint32_t leaf_size() const { return leaf_size_; }
  bool alive(std::uint32_t polygon) const { return polygon < leaf_of_.size() && leaf_of_[polygon] >= 0; }

  // Section 6. `polygon` must be an index of the polygon set not yet in the tree.
  void insert(std::uint32_t polygon);
  void erase(std::uint32_t polygon);

 private:
  // Builds the subtree of items[begin, end) into node `reuse` (a new node when -1); returns it.
  std::int32_t build(std::vector<std::uint32_t>& items, std::size_t begin, std::size_t end, std::int32_t parent,
                     std::int32_t reuse = -1);

  const ScenePolygons& polygons_;
  std::uint32_t leaf_size_;
  std::vector<Node> nodes_;
  std::vector<std::int32_t> leaf_of_;  // the leaf holding each polygon, -1 when not in the tree
};

}  // namespace cullcheck::online
