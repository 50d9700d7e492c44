#include "engine/slice_wise/slice_rectangle.hpp"

#include <algorithm>
#include <array>

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

// Per side of axis a and width w: the largest k such that the form (w side slices, lowest k
// horizontal slices) drops no kept triangle. A kept triangle wholly within the w side slices
// bounds k by its last horizontal slice (k <= zlast keeps it); non-increasing in w.
std::array<std::vector<std::size_t>, 2> side_bounds(const SliceWiseObject& object, const std::vector<char>& keep, int a,
                                                    std::size_t n, std::size_t nz) {
  std::array<std::vector<std::size_t>, 2> bound{std::vector<std::size_t>(n + 1, nz), std::vector<std::size_t>(n + 1, nz)};
  for (std::size_t t = 0; t < keep.size(); ++t) {
    if (!keep[t]) continue;
    const auto& r = object.ranges[t];
    const std::size_t first = r[2 * a], last = r[2 * a + 1], zlast = r[5];
    if (last >= n || zlast >= nz) continue;
    bound[0][last + 1] = std::min(bound[0][last + 1], zlast);
    bound[1][n - first] = std::min(bound[1][n - first], zlast);
  }
  for (auto& b : bound)
    for (std::size_t w = 1; w <= n; ++w) b[w] = std::min(b[w], b[w - 1]);
  return bound;
}

// Both vertical axes at once: (wx side slices of x) or (wy side slices of y), by the lowest k
// horizontal slices, k the smaller of the two sides' bounds. The triangles dropped are those of
// the x form plus those of the y form less those in both, counted with one 3-D prefix table per
// pair of sides: c[wx][wy][k] = triangles within wx x-side slices, wy y-side slices, below k.
void consider_both_axes(SliceChoice& best, const SliceWiseObject& object,
                        const std::array<std::array<std::vector<std::size_t>, 2>, 2>& bounds, std::size_t nz) {
  const std::size_t nx = object.slices.axes[0].count(), ny = object.slices.axes[1].count();
  const std::size_t sy = nz + 1, sx = (ny + 1) * sy;
  std::vector<std::uint32_t> c((nx + 1) * sx);
  for (int side_x = 0; side_x < 2; ++side_x)
    for (int side_y = 0; side_y < 2; ++side_y) {
      const auto& bx = bounds[0][static_cast<std::size_t>(side_x)];
      const auto& by = bounds[1][static_cast<std::size_t>(side_y)];
      if (bx[1] == 0 || by[1] == 0) continue;  // neither side can drop anything on one axis
      std::fill(c.begin(), c.end(), 0u);
      for (const auto& r : object.ranges) {
        if (r[1] >= nx || r[3] >= ny || r[5] >= nz) continue;
        const std::size_t wx = side_x == 0 ? r[1] + 1u : nx - r[0], wy = side_y == 0 ? r[3] + 1u : ny - r[2];
        ++c[wx * sx + wy * sy + r[5] + 1];
      }
      // Cumulative on each axis in turn.
      for (std::size_t i = 1; i <= nx; ++i)
        for (std::size_t j = 0; j < sx; ++j) c[i * sx + j] += c[(i - 1) * sx + j];
      for (std::size_t i = 0; i <= nx; ++i)
        for (std::size_t j = 1; j <= ny; ++j)
          for (std::size_t k = 0; k <= nz; ++k) c[i * sx + j * sy + k] += c[i * sx + (j - 1) * sy + k];
      for (std::size_t i = 0; i <= nx; ++i)
        for (std::size_t j = 0; j <= ny; ++j)
          for (std::size_t k = 1; k <= nz; ++k) c[i * sx + j * sy + k] += c[i * sx + j * sy + k - 1];
      for (std::size_t wx = 1; wx <= nx && bx[wx] > 0; ++wx)
        for (std::size_t wy = 1; wy <= ny && by[wy] > 0; ++wy) {
          const std::size_t k = std::min(bx[wx], by[wy]);
          const std::size_t dropped = c[wx * sx + ny * sy + k] + c[nx * sx + wy * sy + k] - c[wx * sx + wy * sy + k];
          if (dropped <= best.dropped) continue;
          best.dropped = dropped;
          VisibilityIndices v = all_visible(object.slices);
          v.x = static_cast<std::int8_t>(side_x == 0 || wx == nx ? -static_cast<int>(wx) : static_cast<int>(nx - wx - 1));
          v.y = static_cast<std::int8_t>(side_y == 0 || wy == ny ? -static_cast<int>(wy) : static_cast<int>(ny - wy - 1));
          v.z = static_cast<std::int8_t>(k);
          v.work_axis = kBothVerticalAxes;
          best.indices = v;
          best.form = VisibleForm::two_sided;
        }
    }
}

}  // namespace

std::string_view visible_form_name(VisibleForm f) {
  switch (f) {
    case VisibleForm::complete: return "complete";
    case VisibleForm::l_shaped: return "l_shaped";
    case VisibleForm::vertical: return "vertical";
    case VisibleForm::horizontal: return "horizontal";
    case VisibleForm::two_sided: return "two_sided";
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

SliceChoice best_form_keeping(const SliceWiseObject& object, const std::vector<char>& keep, bool both_axes) {
  SliceChoice best;
  best.indices = all_visible(object.slices);
  const std::size_t nz = object.slices.axes[2].count();
  if (nz == 0 || keep.size() != object.ranges.size()) return best;
  std::array<std::array<std::vector<std::size_t>, 2>, 2> bounds;  // [axis][side]
  for (int a = 0; a < 2; ++a) {
    const std::size_t n = object.slices.axes[static_cast<std::size_t>(a)].count();
    if (n == 0) continue;
    const FormCounts counts = form_counts(object, a, n, nz);
    bounds[a] = side_bounds(object, keep, a, n, nz);
    for (int side = 0; side < 2; ++side)
      for (std::size_t w = 1; w <= n && bounds[a][side][w] > 0; ++w)
        consider(best, object, counts, a, side, n, nz, w, bounds[a][side][w]);
  }
  if (both_axes && !bounds[0][0].empty() && !bounds[1][0].empty()) consider_both_axes(best, object, bounds, nz);
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
