// Algorithm 3 (Yılmaz & Güdükbay §4.2.3, Fig. 19): from the occlusion Algorithm 2 measured, one
// rectangle of hidden slices per object, stored as the three indices of Fig. 5.
//
// Algorithm 2 gives, for each vertical slice of an axis, the height up to which it is hidden
// (from the object's bottom), and for each horizontal slice whether it is hidden whole. In the
// grid of (vertical slice i, horizontal slice j) a cell is hidden when slice i is hidden above
// the top of slab j, or slice j is hidden whole. The rectangle is w vertical slices taken from
// one side (low or high coordinate) by the lowest kz horizontal slices, every cell of it hidden;
// the rendering set (slicing.hpp) then drops exactly the triangles whose slices all lie inside
// it: vertical slices all among the w, horizontal slices all below kz.
//
// The paper picks the maximally occluded axis by its percentage of occlusion and then the largest
// rectangle; here every axis, side and width is tried and the one that drops the most triangles
// wins (ties: x before y, low side before high, narrower first), which is what the rendered
// triangle count rewards. Forms (Fig. 2): L-shaped (a rectangle short of both the full width and
// the full height), vertical (full height), horizontal (full width).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/slice_wise/slice_scene.hpp"
#include "engine/slice_wise/slicing.hpp"

namespace cullcheck::slice_wise {

// two_sided: cullcheck's variant, a rectangle on each vertical axis (best_form_keeping).
enum class VisibleForm : std::uint8_t { complete, l_shaped, vertical, horizontal, two_sided };
std::string_view visible_form_name(VisibleForm f);

struct SliceOcclusion {
  std::array<std::vector<double>, 2> hidden_height;  // per x and y slice: metres above box.lo.z hidden
  std::vector<char> z_hidden;                        // per horizontal slice: hidden whole
};

struct SliceChoice {
  VisibilityIndices indices;  // all_visible when nothing can be dropped
  VisibleForm form = VisibleForm::complete;
  std::size_t dropped = 0;       // triangles the indices drop
  // Triangles whose every (vertical slice, horizontal slice) cell is hidden, on the better
  // vertical axis: what a per-cell PVS would drop. dropped <= cell_dropped; the difference is
  // the tightness Algorithm 3 gives up for three bytes.
  std::size_t cell_dropped = 0;
  bool any_hidden_cell = false;  // Algorithm 2 found some part hidden (a partially visible object)
};

SliceChoice choose_slices(const SliceWiseObject& object, const SliceOcclusion& occlusion);

// The top of horizontal slice j, in metres above the object's bottom (SliceOcclusion's heights),
// and the slack hidden heights are compared with (a slice hidden to the object's top is measured
// as the box's height, and a slab's top is recomputed from its origin and thickness).
double horizontal_slice_top(const SliceWiseObject& object, std::size_t j);
inline constexpr double kHeightSlack = 1e-9;

// The form that drops the most triangles while keeping every triangle marked in `keep` (per
// triangle of the object): what three bytes could do at best if the visible triangles were known,
// e.g. the oracle's witnessed ones. Measures the representation apart from the queries. Its
// cell_dropped: the triangles none of whose cells (on the better vertical axis) holds a kept
// triangle, what a per-cell record could drop; equal to `dropped` when the kept triangles fit
// one form (Fig. 2's premise).
//
// With both_axes (cullcheck's variant, not the paper's): the three bytes also hold a rectangle on
// each vertical axis at once, from a side of x and a side of y, sharing the z index, drawn by
// rendering_set's work axis 2. The paper draws from the maximally occluded axis only, so a
// building seen across a corner keeps one of its two far walls; the same three bytes can drop
// both. Every pair of rectangles is tried (3-D prefix counts per pair of sides).
SliceChoice best_form_keeping(const SliceWiseObject& object, const std::vector<char>& keep, bool both_axes = false);

}  // namespace cullcheck::slice_wise
