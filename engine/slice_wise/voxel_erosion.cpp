#include "engine/slice_wise/voxel_erosion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/slice_wise/solid_parts.hpp"

namespace cullcheck::slice_wise {
namespace {

constexpr double kWiden = 1e-9;  // metres: voxels are widened by this for the touch test

// Whether convex planar polygon `poly` meets the box of centre `m` and half-sides `h` (separating
// axes: the box's three, the polygon's normal, each edge crossed with each box axis).
bool polygon_meets_box(Vec3 m, Vec3 h, const Vec3* poly, std::size_t n) {
  auto separated = [&](Vec3 axis) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (std::size_t k = 0; k < n; ++k) {
      const double p = dot(axis, poly[k] - m);
      lo = std::min(lo, p), hi = std::max(hi, p);
    }
    const double r = h.x * std::abs(axis.x) + h.y * std::abs(axis.y) + h.z * std::abs(axis.z);
    return lo > r || hi < -r;
  };
  const Vec3 units[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Vec3& u : units)
    if (separated(u)) return false;
  Vec3 normal;  // Newell's: robust when three points in a row are collinear
  for (std::size_t k = 0; k < n; ++k) normal = normal + cross(poly[k] - m, poly[(k + 1) % n] - m);
  if (separated(normal)) return false;
  for (const Vec3& u : units)
    for (std::size_t k = 0; k < n; ++k)
      if (separated(cross(u, poly[(k + 1) % n] - poly[k]))) return false;
  return true;
}

double orient(Vec2 a, Vec2 b, Vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

double& coord(Vec3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }
double coord(const Vec3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

// The part of convex polygon `poly` with lo <= p[axis] <= hi (Sutherland-Hodgman, two planes).
void clip_slab(std::vector<Vec3>& poly, int axis, double lo, double hi, std::vector<Vec3>& scratch) {
  for (int side = 0; side < 2 && !poly.empty(); ++side) {
    auto inside = [&](const Vec3& p) { return side == 0 ? coord(p, axis) >= lo : coord(p, axis) <= hi; };
    const double plane = side == 0 ? lo : hi;
    scratch.clear();
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec3 &p = poly[k], &q = poly[(k + 1) % poly.size()];
      const bool pin = inside(p), qin = inside(q);
      if (pin) scratch.push_back(p);
      if (pin != qin) {
        const double t = (plane - coord(p, axis)) / (coord(q, axis) - coord(p, axis));
        Vec3 x = p + (q - p) * t;
        coord(x, axis) = plane;
        scratch.push_back(x);
      }
    }
    poly.swap(scratch);
  }
}

// 4. Each box pushed out, face by face (up, down, then the four sides), until the box grown by the
// element would meet the boundary: the voxels a boundary face passes through were all taken as
// outside, which loses up to a voxel at every wall and roof, and under a floor above the object's
// lowest point (a part standing higher on sloping ground). The floor on the lowest plane is not a
// boundary here: below it is the ground, so a box on it is not pushed down. Pushing the
// face on +a to `limit` is conservative when the open prism beyond the grown box's face,
// (face + h_a, limit + h_a) times the grown box's cross-section, holds no point of a boundary
// polygon: it adjoins the grown box, which lies inside the solid, so it lies inside too. The
// cross-section is shrunk by 1e-9 m, so faces that only touch its rim do not block, and a face
// stops 1e-9 m short of its limit. A box stays within the bounds of its own mesh (`within`, by
// box_owner): across a party wall the union goes on, but the neighbour's side is its own to cover.
void push_out(std::vector<Box3>& boxes, const std::vector<std::uint32_t>& box_owner, const std::vector<Box3>& within,
              const std::vector<std::vector<Vec3>>& boundary, Vec3 h) {
  constexpr double kTol = 1e-9;
  std::vector<Box3> bounds(boundary.size());
  for (std::size_t k = 0; k < boundary.size(); ++k)
    for (const Vec3& v : boundary[k]) bounds[k].extend(v);
  const double half[3] = {h.x, h.y, h.z};
  std::vector<Vec3> poly, scratch;
  for (std::size_t bi = 0; bi < boxes.size(); ++bi)
    for (const auto& [axis, up] : {std::pair{2, true}, {2, false}, {0, true}, {0, false}, {1, true}, {1, false}}) {
      Box3& b = boxes[bi];
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const double ulo = coord(b.lo, u) - half[u] + kTol, uhi = coord(b.hi, u) + half[u] - kTol;
      const double vlo = coord(b.lo, v) - half[v] + kTol, vhi = coord(b.hi, v) + half[v] - kTol;
      const double reach = up ? coord(b.hi, axis) + half[axis] : coord(b.lo, axis) - half[axis];  // the grown face
      double limit = up ? HUGE_VAL : -HUGE_VAL;  // how far the grown face may go
      for (std::size_t k = 0; k < boundary.size(); ++k) {
        const Box3& pb = bounds[k];
        if (coord(pb.hi, u) <= ulo || coord(pb.lo, u) >= uhi || coord(pb.hi, v) <= vlo || coord(pb.lo, v) >= vhi) continue;
        if (up ? coord(pb.hi, axis) <= reach + kTol : coord(pb.lo, axis) >= reach - kTol) continue;  // wholly behind
        poly = boundary[k];
        clip_slab(poly, u, ulo, uhi, scratch);
        clip_slab(poly, v, vlo, vhi, scratch);
        if (poly.empty()) continue;
        double lo_a = HUGE_VAL, hi_a = -HUGE_VAL;
        for (const Vec3& p : poly) lo_a = std::min(lo_a, coord(p, axis)), hi_a = std::max(hi_a, coord(p, axis));
        if (up ? hi_a <= reach + kTol : lo_a >= reach - kTol) continue;
        limit = up ? std::min(limit, std::max(lo_a, reach)) : std::max(limit, std::min(hi_a, reach));
      }
      if (!std::isfinite(limit)) continue;  // nothing bounds it: leave it (a closed solid always does)
      const Box3& own = within[box_owner[bi]];
      double& face = up ? coord(b.hi, axis) : coord(b.lo, axis);
      // kTol short of the limit, so that rounding leaves the grown box inside.
      face = up ? std::max(face, std::min(limit - half[axis] - kTol, coord(own.hi, axis)))
                : std::min(face, std::max(limit + half[axis] + kTol, coord(own.lo, axis)));
    }
}

// Erodes `m`, the concatenation of one or more meshes: mesh q holds triangles first[q] .. first[q + 1] - 1
// (first ends with the triangle count) and is closed when closed[q].
VoxelErosion erode(const MeshObject& m, const std::vector<std::uint32_t>& first, const std::vector<std::uint8_t>& closed, Vec3 h,
                   double r, std::size_t max_voxels) {
  for (double a : {h.x, h.y, h.z})
    if (!(a >= 0) || !std::isfinite(a)) throw std::invalid_argument("voxel erosion: the element's half-sides must be finite and not negative");
  if (!(r > 0) || !std::isfinite(r)) throw std::invalid_argument("voxel erosion: voxel size must be positive and finite");
  VoxelErosion out;
  if (m.triangles.empty()) return out;
  const Vec3 lo = m.bounds.lo, hi = m.bounds.hi;
  auto cells = [&](double extent) { return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(extent / r))); };
  const std::size_t nx = cells(hi.x - lo.x), ny = cells(hi.y - lo.y), nz = cells(hi.z - lo.z);
  if (!(double(nx) * double(ny) * double(nz) <= double(max_voxels)))
    throw std::invalid_argument("voxel erosion: object " + std::to_string(m.id) + " needs more than " + std::to_string(max_voxels) + " voxels");
  out.voxels = nx * ny * nz;
  auto at = [&](std::size_t i, std::size_t j, std::size_t k) { return (k * ny + j) * nx + i; };
  auto index_range = [&](double a, double b, double origin, std::size_t n, std::size_t& first, std::size_t& last) {
    const double f = std::floor((a - origin) / r), l = std::floor((b - origin) / r);
    if (l < 0 || f > double(n) - 1) return false;
    first = static_cast<std::size_t>(std::max(f, 0.0)), last = static_cast<std::size_t>(std::min(l, double(n) - 1));
    return true;
  };

  // 1a. Voxels some triangle of the union's boundary touches (faces between two solids of the
  // object are inside it).
  const SolidParts parts = solid_parts(m);
  out.solids = parts.parts, out.interior_triangles = parts.interior_count, out.partly_interior_triangles = parts.partly_count;
  const std::size_t meshes = first.size() - 1;
  std::vector<std::uint32_t> mesh_of_part(parts.parts, 0);  // a solid's vertices are one mesh's
  for (std::uint32_t q = 0; q < meshes; ++q)
    for (std::uint32_t t = first[q]; t < first[q + 1]; ++t) mesh_of_part[parts.part_of[t]] = q;
  {
    std::vector<double> volume(parts.parts, 0.0);  // six times each solid's signed volume
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const auto& tri = m.triangles[t];
      const Vec3 a = m.vertices[tri[0]] - lo, b = m.vertices[tri[1]] - lo, c = m.vertices[tri[2]] - lo;
      volume[parts.part_of[t]] += dot(a, cross(b, c));
    }
    out.outward_of.assign(closed.begin(), closed.end());
    for (std::uint32_t p = 0; p < parts.parts; ++p)
      if (!(volume[p] > 0)) out.outward_of[mesh_of_part[p]] = 0;
    out.outward = std::all_of(out.outward_of.begin(), out.outward_of.end(), [](std::uint8_t o) { return o != 0; });
  }
  std::vector<std::uint8_t> touched(out.voxels, 0);
  const Vec3 half{r / 2 + kWiden, r / 2 + kWiden, r / 2 + kWiden};
  // Marks the voxels convex polygon `poly` (n points) touches.
  auto touch = [&](const Vec3* poly, std::size_t n) {
    Box3 b;
    for (std::size_t k = 0; k < n; ++k) b.extend(poly[k]);
    std::size_t i0, i1, j0, j1, k0, k1;
    if (!index_range(b.lo.x - kWiden, b.hi.x + kWiden, lo.x, nx, i0, i1) || !index_range(b.lo.y - kWiden, b.hi.y + kWiden, lo.y, ny, j0, j1) ||
        !index_range(b.lo.z - kWiden, b.hi.z + kWiden, lo.z, nz, k0, k1))
      return;
    for (std::size_t k = k0; k <= k1; ++k)
      for (std::size_t j = j0; j <= j1; ++j)
        for (std::size_t i = i0; i <= i1; ++i) {
          const std::size_t v = at(i, j, k);
          if (touched[v]) continue;
          const Vec3 centre{lo.x + (double(i) + 0.5) * r, lo.y + (double(j) + 0.5) * r, lo.z + (double(k) + 0.5) * r};
          if (polygon_meets_box(centre, half, poly, n)) touched[v] = 1;
        }
  };
  std::vector<std::vector<Vec3>> boundary;  // the union's boundary as convex polygons, the floor left out
  for (std::uint32_t ti = 0; ti < m.triangles.size(); ++ti) {
    const auto& t = m.triangles[ti];
    const Vec3 corners[3] = {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
    // The floor (on the object's lowest plane) only bounds voxels from below, where the ground is.
    if (corners[0].z == lo.z && corners[1].z == lo.z && corners[2].z == lo.z) continue;
    if (parts.cover[ti] == SolidParts::interior) continue;
    if (parts.cover[ti] == SolidParts::partly) {
      for (const auto& piece : parts.boundary_pieces.at(ti)) touch(piece.data(), piece.size()), boundary.push_back(piece);
      continue;
    }
    touch(corners, 3);
    boundary.push_back({corners[0], corners[1], corners[2]});
  }

  // 1b. Parity along a vertical line through each column, solid by solid: a point is inside the
  // union when it is inside one of them. An untouched voxel is wholly inside or outside, so any
  // line through the column decides it: the centre's first, then a few others when the centre's
  // passes near an edge (the diagonal of a square roof does, for every column on it).
  std::vector<std::vector<std::uint32_t>> column_triangles(nx * ny);
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    const Vec3 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    if (orient({a.x, a.y}, {b.x, b.y}, {c.x, c.y}) == 0.0) continue;  // vertical: no vertical line crosses it
    const double x0 = std::min({a.x, b.x, c.x}), x1 = std::max({a.x, b.x, c.x});
    const double y0 = std::min({a.y, b.y, c.y}), y1 = std::max({a.y, b.y, c.y});
    const double fi = std::ceil((x0 - lo.x) / r - 1), li = std::floor((x1 - lo.x) / r);  // columns its plan box meets
    const double fj = std::ceil((y0 - lo.y) / r - 1), lj = std::floor((y1 - lo.y) / r);
    for (double j = std::max(fj, 0.0); j <= std::min(lj, double(ny) - 1); ++j)
      for (double i = std::max(fi, 0.0); i <= std::min(li, double(nx) - 1); ++i)
        column_triangles[static_cast<std::size_t>(j) * nx + static_cast<std::size_t>(i)].push_back(t);
  }
  std::vector<std::uint8_t> solid(out.voxels, 0);
  std::vector<std::uint32_t> owner(meshes > 1 ? out.voxels : 0, 0);  // the mesh of the first solid holding it
  std::vector<std::vector<double>> crossings(std::max<std::uint32_t>(parts.parts, 1));
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      // Where the line crosses each solid; false when it passes within 1e-9 of an edge (in
      // barycentric terms) or crosses a solid an odd number of times.
      auto cross_at = [&](Vec2 p) {
        for (auto& c : crossings) c.clear();
        for (std::uint32_t t : column_triangles[j * nx + i]) {
          const Vec3 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
          const Vec2 pa{a.x, a.y}, pb{b.x, b.y}, pc{c.x, c.y};
          const double area = orient(pa, pb, pc);
          const double w0 = orient(pb, pc, p) / area, w1 = orient(pc, pa, p) / area, w2 = orient(pa, pb, p) / area;
          if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;  // outside in plan
          if (w0 <= 1e-9 || w1 <= 1e-9 || w2 <= 1e-9) return false;
          crossings[parts.part_of[t]].push_back(w0 * a.z + w1 * b.z + w2 * c.z);
        }
        for (const auto& c : crossings)
          if (c.size() % 2 == 1) return false;
        return true;
      };
      static constexpr double kOffsets[4][2] = {{0, 0}, {0.213, 0.131}, {-0.177, 0.229}, {0.151, -0.239}};  // of r
      bool decided = false;
      for (const auto& d : kOffsets)
        if ((decided = cross_at({lo.x + (double(i) + 0.5 + d[0]) * r, lo.y + (double(j) + 0.5 + d[1]) * r}))) break;
      if (!decided) {
        ++out.ambiguous_columns;
        continue;
      }
      for (auto& c : crossings) std::sort(c.begin(), c.end());
      for (std::size_t k = 0; k < nz; ++k) {
        const std::size_t v = at(i, j, k);
        if (touched[v]) continue;
        const double z = lo.z + (double(k) + 0.5) * r;
        for (std::uint32_t p = 0; p < crossings.size(); ++p) {
          const auto& c = crossings[p];
          if ((std::upper_bound(c.begin(), c.end(), z) - c.begin()) % 2 == 0) continue;
          solid[v] = 1, ++out.inside;
          if (meshes > 1) owner[v] = mesh_of_part[p];
          break;
        }
      }
    }

  // 2. Erosion by the box of half-sides ceil(h / r) voxels, one axis at a time (outside the grid:
  // empty, below it: ground, solid).
  std::vector<std::uint8_t> next(out.voxels, 0);
  auto erode_axis = [&](double half_side, std::size_t n, std::size_t stride_count, auto&& index, bool ground_below) {
    const long e = static_cast<long>(std::ceil(half_side / r));
    if (e == 0) return;
    std::vector<int> prefix(n + 1);
    for (std::size_t s = 0; s < stride_count; ++s) {
      prefix[0] = 0;
      for (std::size_t q = 0; q < n; ++q) prefix[q + 1] = prefix[q] + solid[index(s, q)];
      for (std::size_t q = 0; q < n; ++q) {
        const long from = long(q) - e, to = long(q) + e;
        bool keep = to < long(n) && (from >= 0 || ground_below);
        if (keep) {
          const std::size_t f = static_cast<std::size_t>(std::max(from, 0L)), t = static_cast<std::size_t>(to);
          keep = prefix[t + 1] - prefix[f] == int(t + 1 - f);
        }
        next[index(s, q)] = keep ? 1 : 0;
      }
    }
    solid.swap(next);
  };
  erode_axis(h.x, nx, ny * nz, [&](std::size_t s, std::size_t q) { return s * nx + q; }, false);
  erode_axis(h.y, ny, nx * nz, [&](std::size_t s, std::size_t q) { return at(s % nx, q, s / nx); }, false);
  erode_axis(h.z, nz, nx * ny, [&](std::size_t s, std::size_t q) { return at(s % nx, s / nx, q); }, true);

  // 3. Boxes.
  std::vector<std::uint8_t> used(out.voxels, 0);
  std::uint32_t mesh = 0;  // of the box being grown: boxes merge within one mesh
  auto free_voxel = [&](std::size_t i, std::size_t j, std::size_t k) {
    const std::size_t v = at(i, j, k);
    return solid[v] && !used[v] && (meshes == 1 || owner[v] == mesh);
  };
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        if (meshes > 1) mesh = owner[at(i, j, k)];
        if (!free_voxel(i, j, k)) continue;
        std::size_t i1 = i, j1 = j, k1 = k;
        while (i1 + 1 < nx && free_voxel(i1 + 1, j, k)) ++i1;
        auto row_free = [&](std::size_t jj, std::size_t kk) {
          for (std::size_t ii = i; ii <= i1; ++ii)
            if (!free_voxel(ii, jj, kk)) return false;
          return true;
        };
        while (j1 + 1 < ny && row_free(j1 + 1, k)) ++j1;
        auto layer_free = [&](std::size_t kk) {
          for (std::size_t jj = j; jj <= j1; ++jj)
            if (!row_free(jj, kk)) return false;
          return true;
        };
        while (k1 + 1 < nz && layer_free(k1 + 1)) ++k1;
        for (std::size_t kk = k; kk <= k1; ++kk)
          for (std::size_t jj = j; jj <= j1; ++jj)
            for (std::size_t ii = i; ii <= i1; ++ii) used[at(ii, jj, kk)] = 1;
        out.kept += (i1 - i + 1) * (j1 - j + 1) * (k1 - k + 1);
        out.boxes.push_back({{lo.x + double(i) * r, lo.y + double(j) * r, lo.z + double(k) * r},
                             {lo.x + double(i1 + 1) * r, lo.y + double(j1 + 1) * r, lo.z + double(k1 + 1) * r}});
        out.box_owner.push_back(mesh);
      }
  std::vector<Box3> mesh_bounds(meshes);
  for (std::uint32_t q = 0; q < meshes; ++q)
    for (std::uint32_t t = first[q]; t < first[q + 1]; ++t)
      for (std::uint32_t v : m.triangles[t]) mesh_bounds[q].extend(m.vertices[v]);
  push_out(out.boxes, out.box_owner, mesh_bounds, boundary, h);
  return out;
}

}  // namespace

VoxelErosion erode_closed_mesh(const MeshObject& m, Vec3 h, double r, std::size_t max_voxels) {
  return erode(m, {0, static_cast<std::uint32_t>(m.triangles.size())}, {static_cast<std::uint8_t>(m.closed)}, h, r, max_voxels);
}

VoxelErosion erode_closed_meshes(const std::vector<const MeshObject*>& meshes, Vec3 h, double r, std::size_t max_voxels) {
  MeshObject joint;
  std::vector<std::uint32_t> first{0};
  std::vector<std::uint8_t> closed;
  for (const MeshObject* m : meshes) {
    const auto base = static_cast<std::uint32_t>(joint.vertices.size());
    joint.vertices.insert(joint.vertices.end(), m->vertices.begin(), m->vertices.end());
    for (const auto& t : m->triangles) joint.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    joint.bounds.extend(m->bounds.lo), joint.bounds.extend(m->bounds.hi);
    first.push_back(static_cast<std::uint32_t>(joint.triangles.size()));
    closed.push_back(m->closed);
  }
  if (meshes.empty()) return {};
  joint.id = meshes.front()->id;
  return erode(joint, first, closed, h, r, max_voxels);
}

TriangleMesh boxes_mesh(const std::vector<Box3>& boxes) {
  TriangleMesh mesh;
  // Corner c has bit 0 for x, 1 for y, 2 for z; faces counter-clockwise seen from outside.
  static constexpr std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const Box3& b : boxes) {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (int c = 0; c < 8; ++c) mesh.vertices.push_back({(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z});
    for (const auto& f : faces) {
      mesh.triangles.push_back({base + f[0], base + f[1], base + f[2]});
      mesh.triangles.push_back({base + f[0], base + f[2], base + f[3]});
    }
  }
  return mesh;
}

}  // namespace cullcheck::slice_wise
