#include "core/formats/polygon_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>
#include <list>

namespace cullcheck::formats {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
struct FaceInfo {
  int nesting = -1;
  bool inside() const { return nesting % 2 == 1; }
};
// A vertex's info: its index into `vertices` plus one; 0 (the default: CGAL leaves a plain
// integer uninitialised) marks one the triangulation made.
struct Index {
  std::size_t plus_one = 0;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using Fb = CGAL::Constrained_triangulation_face_base_2<Kernel, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: crossing constraints are split at their (rounded) crossing.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

// Faces reached from `start` without crossing a constraint get `level`; the constrained edges
// met lead to the next level (CGAL's polygon-with-holes recipe: odd levels are inside).
void mark(Cdt& cdt, Cdt::Face_handle start, int level, std::list<Cdt::Edge>& border) {
  if (start->info().nesting != -1) return;
  std::list<Cdt::Face_handle> queue{start};
  while (!queue.empty()) {
    Cdt::Face_handle f = queue.front();
    queue.pop_front();
    if (f->info().nesting != -1) continue;
    f->info().nesting = level;
    for (int i = 0; i < 3; ++i) {
      const Cdt::Edge e(f, i);
      Cdt::Face_handle n = f->neighbor(i);
      if (n->info().nesting != -1) continue;
      if (cdt.is_constrained(e)) border.push_back(e);
      else queue.push_back(n);
    }
  }
}

}  // namespace

std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(std::vector<Vec3>& vertices,
                                                              const std::vector<std::vector<std::size_t>>& rings) {
  std::vector<std::array<std::uint32_t, 3>> out;
  if (rings.empty() || rings[0].size() < 3) return out;
  // Newell's normal of the outer ring: its direction is the way the ring turns.
  Vec3 normal{0, 0, 0};
  const std::vector<std::size_t>& outer = rings[0];
  for (std::size_t i = 0; i < outer.size(); ++i) {
    const Vec3 a = vertices[outer[i]], b = vertices[outer[(i + 1) % outer.size()]];
    normal.x += (a.y - b.y) * (a.z + b.z);
    normal.y += (a.z - b.z) * (a.x + b.x);
    normal.z += (a.x - b.x) * (a.y + b.y);
  }
  const double length = std::sqrt(normal.x * normal.x + normal.y * normal.y + normal.z * normal.z);
  if (!(length > 1e-12)) return out;
  // Drop the axis the normal points along most; the other two are the plane's coordinates.
  const double ax = std::abs(normal.x), ay = std::abs(normal.y), az = std::abs(normal.z);
  const int drop = az >= ax && az >= ay ? 2 : (ay >= ax ? 1 : 0);
  auto project = [drop](Vec3 p) {
    return drop == 2 ? Kernel::Point_2(p.x, p.y) : drop == 1 ? Kernel::Point_2(p.z, p.x) : Kernel::Point_2(p.y, p.z);
  };
  const Vec3 anchor = vertices[outer[0]];
  auto lift = [&](const Kernel::Point_2& q) {  // back onto the polygon's plane
    const double u = q.x(), v = q.y();
    Vec3 p;
    if (drop == 2) p = {u, v, anchor.z - (normal.x * (u - anchor.x) + normal.y * (v - anchor.y)) / normal.z};
    else if (drop == 1) p = {v, anchor.y - (normal.z * (u - anchor.z) + normal.x * (v - anchor.x)) / normal.y, u};
    else p = {anchor.x - (normal.y * (u - anchor.y) + normal.z * (v - anchor.z)) / normal.x, u, v};
    return p;
  };
  Cdt cdt;
  for (const std::vector<std::size_t>& ring : rings) {
    if (ring.size() < 2) continue;
    std::vector<Cdt::Vertex_handle> handles;
    for (std::size_t i : ring) {
      Cdt::Vertex_handle h = cdt.insert(project(vertices[i]));
      if (h->info().plus_one == 0) h->info().plus_one = i + 1;  // a point given twice keeps its first index
      handles.push_back(h);
    }
    for (std::size_t k = 0; k < handles.size(); ++k) {
      const Cdt::Vertex_handle a = handles[k], b = handles[(k + 1) % handles.size()];
      if (a != b) cdt.insert_constraint(a, b);
    }
  }
  if (cdt.dimension() < 2) return out;
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info().nesting = -1;
  std::list<Cdt::Edge> border;
  mark(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) mark(cdt, n, e.first->info().nesting + 1, border);
  }
  const Vec3 unit{normal.x / length, normal.y / length, normal.z / length};
  for (Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (!f->info().inside()) continue;
    std::array<std::uint32_t, 3> t{};
    for (int i = 0; i < 3; ++i) {
      Cdt::Vertex_handle v = f->vertex(i);
      if (v->info().plus_one == 0) {
        vertices.push_back(lift(v->point()));
        v->info().plus_one = vertices.size();
      }
      t[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(v->info().plus_one - 1);
    }
    const Vec3 a = vertices[t[0]], b = vertices[t[1]], c = vertices[t[2]];
    if (dot(cross(b - a, c - a), unit) < 0) std::swap(t[1], t[2]);
    out.push_back(t);
  }
  return out;
}

}  // namespace cullcheck::formats
