#include "engine/slice_wise/slicing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cullcheck::slice_wise {
namespace {

double coordinate(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

AxisSlices slice_axis(const MeshObject& mesh, int axis, const SlicingOptions& o) {
  AxisSlices s;
  const double lo = coordinate(mesh.bounds.lo, axis), hi = coordinate(mesh.bounds.hi, axis);
  const double extent = hi - lo;
  const int slabs = extent > 0 ? std::clamp(static_cast<int>(std::ceil(extent / o.slice_m)), 1, o.max_slices) : 1;
  s.origin = lo;
  s.thickness = extent > 0 ? extent / slabs : 1.0;
  // Each triangle in every slab whose closed range meets its extent.
  std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(slabs));
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    double a = HUGE_VAL, b = -HUGE_VAL;
    for (std::uint32_t k : mesh.triangles[t]) {
      const double c = coordinate(mesh.vertices[k], axis);
      a = std::min(a, c), b = std::max(b, c);
    }
    const double first = std::ceil((a - lo) / s.thickness) - 1, last = std::floor((b - lo) / s.thickness);
    const int i0 = static_cast<int>(std::clamp(first, 0.0, slabs - 1.0)), i1 = static_cast<int>(std::clamp(last, 0.0, slabs - 1.0));
    for (int i = i0; i <= i1; ++i) members[static_cast<std::size_t>(i)].push_back(t);
  }
  s.begin.push_back(0);
  for (int i = 0; i < slabs; ++i) {
    const auto& m = members[static_cast<std::size_t>(i)];
    if (m.empty()) continue;  // no triangle occupies this slab: no slice
    s.slab.push_back(static_cast<std::uint32_t>(i));
    s.triangles.insert(s.triangles.end(), m.begin(), m.end());
    s.begin.push_back(static_cast<std::uint32_t>(s.triangles.size()));
  }
  return s;
}

}  // namespace

SlicedObject slice_object(const MeshObject& mesh, const SlicingOptions& options) {
  if (options.max_slices < 1 || options.max_slices > 127)
    throw std::invalid_argument("slice_object: max_slices must lie in [1, 127] (indices are signed bytes)");
  if (!(options.slice_m > 0)) throw std::invalid_argument("slice_object: slice_m must be positive");
  SlicedObject o;
  o.id = mesh.id;
  o.triangle_count = mesh.triangles.size();
  for (int a = 0; a < 3; ++a) o.axes[static_cast<std::size_t>(a)] = slice_axis(mesh, a, options);
  return o;
}

VisibilityIndices all_visible(const SlicedObject& object) {
  VisibilityIndices v;
  v.x = static_cast<std::int8_t>(std::max<std::size_t>(object.axes[0].count(), 1) - 1);
  v.y = static_cast<std::int8_t>(std::max<std::size_t>(object.axes[1].count(), 1) - 1);
  v.z = 0;
  return v;
}

bool slice_visible(const SlicedObject& /*object*/, const VisibilityIndices& v, int axis, std::size_t i) {
  if (axis == 2) return static_cast<int>(i) >= v.z;
  const int index = axis == 0 ? v.x : v.y;
  return index >= 0 ? static_cast<int>(i) <= index : static_cast<int>(i) >= -index;
}

std::vector<std::uint32_t> rendering_set(const SlicedObject& object, const VisibilityIndices& v) {
  // Bit a set: the triangle is in a visible slice of axis a.
  std::vector<std::uint8_t> in_visible(object.triangle_count, 0);
  for (int axis = 0; axis < 3; ++axis) {
    if (axis < 2 && v.work_axis != kBothVerticalAxes && axis != v.work_axis) continue;
    const AxisSlices& s = object.axes[static_cast<std::size_t>(axis)];
    for (std::size_t i = 0; i < s.count(); ++i) {
      if (!slice_visible(object, v, axis, i)) continue;
      for (std::uint32_t k = s.begin[i]; k < s.begin[i + 1]; ++k) in_visible[s.triangles[k]] |= std::uint8_t(1u << axis);
    }
  }
  const std::uint8_t vertical = v.work_axis == kBothVerticalAxes ? 3 : std::uint8_t(1u << v.work_axis);
  std::vector<std::uint32_t> out;
  for (std::uint32_t t = 0; t < in_visible.size(); ++t)
    if ((in_visible[t] & 4) || (in_visible[t] & vertical) == vertical) out.push_back(t);
  return out;
}

}  // namespace cullcheck::slice_wise
