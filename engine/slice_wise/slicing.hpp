// Slice-wise structuring of objects (Yılmaz & Güdükbay, sections 3.2-3.3, Fig. 3-5).
//
// Each mesh object is subdivided uniformly over its bounding box; the occupied cells are
// combined into axis-aligned slices along each axis, and every triangle is listed in each slice
// it occupies on all three axes. A triangle occupies x-slice i exactly when its x-extent meets
// that slab (a triangle is connected, so every x in its extent is one of its points), so the
// slices are found from extents alone; slabs no triangle occupies are dropped.
//
// A view cell's visibility of an object is three signed bytes (Fig. 5), one per axis:
//   x, y (vertical slices): 0 ... n-1 from low to high coordinate;
//       +k  occluded from the high side: slices 0..k visible ("last visible slice", k >= 0);
//       -k  occluded from the low side: slices k..n-1 visible ("last invisible slice" k-1; stored
//           as -k with k >= 1 so that 0 stays "+0");
//   z (horizontal slices): k = the first visible slice, k..n-1 visible (n: none).
// An axis that is not occluded is +(n-1) (x, y) or 0 (z). The rendering set is the triangles in
// the visible slices of the chosen vertical axis (the maximally occluded one, Algorithm 3) or of
// the visible horizontal slices, each triangle once.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/scene.hpp"

namespace cullcheck::slice_wise {

struct SlicingOptions {
  int max_slices = 32;    // per axis (at most 127: indices are signed bytes)
  double slice_m = 2.0;   // target slab thickness, metres (fewer slabs for small objects); the paper makes
                          // its slices as wide as its view cells, and the default cell is 2 m
};

// One object's slices along one axis.
struct AxisSlices {
  double origin = 0.0, thickness = 1.0;       // slab i spans [origin + i t, origin + (i + 1) t] before dropping
  std::vector<std::uint32_t> slab;            // each kept slice's slab number, ascending
  std::vector<std::uint32_t> begin;           // CSR into triangles, size slices + 1
  std::vector<std::uint32_t> triangles;       // triangle indices of the object's mesh
  std::size_t count() const { return slab.size(); }
};

struct SlicedObject {
  ObjectId id = 0;
  std::array<AxisSlices, 3> axes;  // x, y, z
  std::size_t triangle_count = 0;
};

SlicedObject slice_object(const MeshObject& mesh, const SlicingOptions& options = {});

// The three stored bytes (Fig. 5) and which vertical axis the rendering uses (0: x, 1: y; 2: both,
// cullcheck's variant, slice_rectangle.hpp).
struct VisibilityIndices {
  std::int8_t x = 0, y = 0, z = 0;
  std::uint8_t work_axis = 0;
};
// "Everything visible" for an object.
VisibilityIndices all_visible(const SlicedObject& object);

// Whether slice `i` of `axis` is visible under `v`.
bool slice_visible(const SlicedObject& object, const VisibilityIndices& v, int axis, std::size_t i);
// The triangles to draw: those in a visible slice of v.work_axis or of z, sorted, each once. With
// work_axis 2, those in a visible slice of z or in a visible slice of both x and y (a triangle
// all of whose x slices or all of whose y slices are hidden, and all of whose z slices are, is
// dropped); with the other vertical index all visible this is the one-axis rule.
inline constexpr std::uint8_t kBothVerticalAxes = 2;
std::vector<std::uint32_t> rendering_set(const SlicedObject& object, const VisibilityIndices& v);

}  // namespace cullcheck::slice_wise
