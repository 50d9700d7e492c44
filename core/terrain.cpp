#include "core/terrain.hpp"

#include <cmath>
#include <limits>

#include "core/errors.hpp"

namespace cullcheck {

std::array<std::size_t, 3> Terrain::triangle_vertices(std::size_t t) const {
  const std::size_t c = t / 2;
  const std::uint32_t i = std::uint32_t(c % (nx - 1)), j = std::uint32_t(c / (nx - 1));
  const std::size_t v00 = index(i, j), v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
  if (t % 2 == 0) return {v00, v10, v11};
  return {v00, v11, v01};
}

std::array<Vec3, 3> Terrain::triangle(std::size_t t) const {
  const auto v = triangle_vertices(t);
  std::array<Vec3, 3> out;
  for (int k = 0; k < 3; ++k)
    out[k] = {corner.x + double(v[k] % nx) * dx, corner.y + double(v[k] / nx) * dy, z[v[k]]};
  return out;
}

bool Terrain::triangle_present(std::size_t t) const {
  if (hole.empty()) return true;
  for (std::size_t v : triangle_vertices(t))
    if (hole[v]) return false;
  return true;
}

std::size_t Terrain::present_triangle_count() const {
  if (hole.empty()) return triangle_count();
  std::size_t n = 0;
  for (std::size_t t = 0; t < triangle_count(); ++t) n += triangle_present(t) ? 1 : 0;
  return n;
}

Box3 Terrain::bounds() const {
  Box3 b;
  double lo = +HUGE_VAL, hi = -HUGE_VAL;
  for (std::size_t v = 0; v < z.size(); ++v) {
    if (is_hole(v)) continue;
    lo = std::min(lo, z[v]);
    hi = std::max(hi, z[v]);
  }
  b.extend({corner.x, corner.y, lo});
  b.extend({corner.x + (nx - 1) * dx, corner.y + (ny - 1) * dy, hi});
  return b;
}

double Terrain::height_at(Vec2 p) const {
  const double u = (p.x - corner.x) / dx, w = (p.y - corner.y) / dy;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(u >= 0.0 && w >= 0.0 && u <= nx - 1 && w <= ny - 1)) return nan;
  const std::uint32_t i = std::min(std::uint32_t(u), nx - 2), j = std::min(std::uint32_t(w), ny - 2);
  const double fu = u - i, fw = w - j;
  const std::size_t v00 = index(i, j), v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
  // South-east half when fu >= fw (below the diagonal), north-west half otherwise.
  const std::size_t t = 2 * (std::size_t(j) * (nx - 1) + i) + (fu >= fw ? 0 : 1);
  if (!triangle_present(t)) return nan;
  if (fu >= fw) return z[v00] + fu * (z[v10] - z[v00]) + fw * (z[v11] - z[v10]);
  return z[v00] + fw * (z[v01] - z[v00]) + fu * (z[v11] - z[v01]);
}

void validate(const Terrain& t, const std::string& where) {
  if (t.nx < 2 || t.ny < 2)
    throw InputError(where, "size", "a terrain needs at least 2 x 2 vertices, not " + std::to_string(t.nx) + " x " + std::to_string(t.ny));
  if (!(t.dx > 0.0) || !(t.dy > 0.0) || !std::isfinite(t.dx) || !std::isfinite(t.dy))
    throw InputError(where, "spacing", "the vertex spacing must be positive and finite");
  if (!std::isfinite(t.corner.x) || !std::isfinite(t.corner.y)) throw InputError(where, "corner", "not a finite point");
  if (t.z.size() != t.vertex_count())
    throw InputError(where, "heights", std::to_string(t.z.size()) + " heights for " + std::to_string(t.vertex_count()) + " vertices");
  if (!t.hole.empty() && t.hole.size() != t.vertex_count())
    throw InputError(where, "holes", std::to_string(t.hole.size()) + " hole flags for " + std::to_string(t.vertex_count()) + " vertices");
  std::size_t filled = 0;
  for (std::size_t v = 0; v < t.z.size(); ++v) {
    if (t.is_hole(v)) continue;
    if (!std::isfinite(t.z[v]))
      throw InputError(where, "heights", "vertex (" + std::to_string(v % t.nx) + ", " + std::to_string(v / t.nx) + ") has no finite height");
    ++filled;
  }
  if (filled == 0) throw InputError(where, "heights", "every vertex is a hole");
}

}  // namespace cullcheck
