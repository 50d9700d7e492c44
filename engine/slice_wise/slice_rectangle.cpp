#include "engine/slice_wise/slice_rectangle.hpp"

#include <algorithm>

namespace cullcheck::slice_wise {
namespace {

// low[w][k]: triangles with every slice of axis a below w and every horizontal slice below k;
// high[w][k]: every slice of axis a among the last w. Row stride nz + 1.
struct FormCounts {
  std::vector<std::size_t> low, high;
  std::size_t stride = 0;
};

FormCounts form_counts(const SliceWiseObject& object, int a, std::size_t n, std::size_t nz) {
  FormCounts c;
  c.stride = nz + 1;
  c.low.assign((n + 1) * c.stride, 0), c.high.assign((n + 1) * c.stride, 0);
  for (const auto& r : object.ranges) {
    const std::size_t first = r[2 * a], last = r[2 * a + 1], zlast = r[5];
    if (last >= n || zlast >= nz) continue;  // in no slice (cannot happen for a sliced triangle)
    ++c.low[(last + 1) * c.stride + zlast + 1];
    ++c.high[(n - first) * c.stride + zlast + 1];
  }
  for (auto* t : {&c.low, &c.high})  // cumulative: counts with index < w and < k
    for (std::size_t w = 0; w <= n; ++w)
      for (std::size_t k = 0; k <= nz; ++k) {
        std::size_t& v = (*t)[w * c.stride + k];
        if (w > 0) v += (*t)[(w - 1) * c.stride + k];
        if (k > 0) v += (*t)[w * c.stride + k - 1];
        if (w > 0 && k > 0) v -= (*t)[(w - 1) * c.stride + k - 1];
      }
  return c;
}

// Keeps `best` when (axis a, side, w, k) drops more than it.
void consider(SliceChoice& best, const SliceWiseObject& object, const FormCounts& counts, int a, int side, std::size_t n,
              std::size_t nz, std::size_t w, std::size_t k) {
  const std::size_t dropped = (side == 0 ? counts.low : counts.high)[w * counts.stride + k];
  if (dropped <= best.dropped) return;
  best.dropped = dropped;
  VisibilityIndices v = all_visible(object.slices);
  const auto index = static_cast<std::int8_t>(side == 0 || w == n ? -static_cast<int>(w) : static_cast<int>(n - w - 1));
  (a == 0 ? v.x : v.y) = index;
  v.z = static_cast<std::int8_t>(k);
  v.work_axis = static_cast<std::uint8_t>(a);
  best.indices = v;
  best.form = w == n ? VisibleForm::horizontal : k == nz ? VisibleForm::vertical : VisibleForm::l_shaped;
}

}  // namespace

std::string_view visible_form_name(VisibleForm f) {
  switch (f) {
    case VisibleForm::complete: return "complete";
    case VisibleForm::l_shaped: return "l_shaped";
    case VisibleForm::vertical: return "vertical";
    case VisibleForm::horizontal: return "horizontal";
  }
  return "?";
}

double horizontal_slice_top(const SliceWiseObject& object, std::size_t j) {
  const AxisSlices& zs = object.slices.axes[2];
  return zs.origin + (zs.slab[j] + 1.0) * zs.thickness - object.box.lo.z;
}

SliceChoice choose_slices(const SliceWiseObject& object, const SliceOcclusion& occ) {
  SliceChoice best;
  best.indices = all_visible(object.slices);
  const AxisSlices& zs = object.slices.axes[2];
  const std::size_t nz = zs.count();
  if (nz == 0 || occ.z_hidden.size() != nz) return best;
  std::vector<double> top(nz);
  for (std::size_t j = 0; j < nz; ++j) top[j] = horizontal_slice_top(object, j);
  for (int a = 0; a < 2; ++a) {
    const std::size_t n = object.slices.axes[static_cast<std::size_t>(a)].count();
    const std::vector<double>& h = occ.hidden_height[static_cast<std::size_t>(a)];
    if (n == 0 || h.size() != n) continue;
    auto hidden = [&](std::size_t i, std::size_t j) { return occ.z_hidden[j] || h[i] + kHeightSlack >= top[j]; };
    std::vector<std::size_t> kz(n, nz);  // per vertical slice: its lowest horizontal slices hidden
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < nz; ++j)
        if (!hidden(i, j)) {
          kz[i] = j;
          break;
        }
      if (kz[i] > 0) best.any_hidden_cell = true;
    }
    const FormCounts counts = form_counts(object, a, n, nz);
    std::size_t cell_dropped = 0;
    for (const auto& r : object.ranges) {
      const std::size_t first = r[2 * a], last = r[2 * a + 1], zfirst = r[4], zlast = r[5];
      if (last >= n || zlast >= nz) continue;
      bool all = true;
      for (std::size_t i = first; i <= last && all; ++i)
        for (std::size_t j = zfirst; j <= zlast && all; ++j) all = hidden(i, j);
      cell_dropped += all;
    }
    best.cell_dropped = std::max(best.cell_dropped, cell_dropped);
    for (int side = 0; side < 2; ++side) {
      std::size_t k = nz;
      for (std::size_t w = 1; w <= n; ++w) {
        k = std::min(k, kz[side == 0 ? w - 1 : n - w]);
        if (k == 0) break;
        consider(best, object, counts, a, side, n, nz, w, k);
      }
    }
  }
  return best;
}

SliceChoice best_form_keeping(const SliceWiseObject& object, const std::vector<char>& keep) {
  SliceChoice best;
  best.indices = all_visible(object.slices);
  const std::size_t nz = object.slices.axes[2].count();
  if (nz == 0 || keep.size() != object.ranges.size()) return best;
  for (int a = 0; a < 2; ++a) {
    const std::size_t n = object.slices.axes[static_cast<std::size_t>(a)].count();
    if (n == 0) continue;
    const FormCounts counts = form_counts(object, a, n, nz);
    // Per w: the kept triangles wholly within the w side slices bound k by their last
    // horizontal slice (k <= zlast keeps them).
    std::vector<std::size_t> low_bound(n + 1, nz), high_bound(n + 1, nz);
    for (std::size_t t = 0; t < keep.size(); ++t) {
      if (!keep[t]) continue;
      const auto& r = object.ranges[t];
      const std::size_t first = r[2 * a], last = r[2 * a + 1], zlast = r[5];
      if (last >= n || zlast >= nz) continue;
      low_bound[last + 1] = std::min(low_bound[last + 1], zlast);
      high_bound[n - first] = std::min(high_bound[n - first], zlast);
    }
    for (int side = 0; side < 2; ++side) {
      const std::vector<std::size_t>& bound = side == 0 ? low_bound : high_bound;
      std::size_t k = nz;
      for (std::size_t w = 1; w <= n; ++w) {
        k = std::min(k, bound[w]);
        if (k == 0) break;
        consider(best, object, counts, a, side, n, nz, w, k);
      }
    }
  }
  // What a per-cell record could drop: on the better vertical axis, the triangles none of whose
  // (vertical slice, horizontal slice) cells holds a kept triangle.
  for (int a = 0; a < 2; ++a) {
    const std::size_t n = object.slices.axes[static_cast<std::size_t>(a)].count();
    std::vector<char> seen(n * nz, 0);
    auto cells_of = [&](std::size_t t, auto&& visit) {
      const auto& r = object.ranges[t];
      for (std::size_t i = r[2 * a]; i <= r[2 * a + 1] && i < n; ++i)
        for (std::size_t j = r[4]; j <= r[5] && j < nz; ++j)
          if (!visit(i * nz + j)) return false;
      return true;
    };
    for (std::size_t t = 0; t < keep.size(); ++t)
      if (keep[t]) cells_of(t, [&](std::size_t c) { return seen[c] = 1, true; });
    std::size_t dropped = 0;
    for (std::size_t t = 0; t < keep.size(); ++t)
      dropped += !keep[t] && cells_of(t, [&](std::size_t c) { return !seen[c]; });
    best.cell_dropped = std::max(best.cell_dropped, dropped);
  }
  best.cell_dropped = std::max(best.cell_dropped, best.dropped);
  return best;
}

}  // namespace cullcheck::slice_wise
