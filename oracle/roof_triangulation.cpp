// The roof triangulation with CGAL (the oracle's second CGAL translation unit; see the header).
#include "oracle/roof_triangulation.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <deque>
#include <stdexcept>
#include <string>

namespace cullcheck::oracle {
namespace {

// Exact predicates on the footprint's doubles; no constructions are ever needed, because the
// constraints (the footprint's edges) meet only at shared vertices: any other intersection throws.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;  // footprint index
using FaceInfo = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;                 // nesting level
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;

// Nesting levels by flood fill from the infinite face: crossing a constrained edge (a footprint
// edge) goes one level deeper. Level 1 is inside the footprint.
void mark_nesting_levels(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<std::pair<Cdt::Face_handle, int>> borders{{cdt.infinite_face(), 0}};
  while (!borders.empty()) {
    const auto [start, level] = borders.front();
    borders.pop_front();
    if (start->info() != -1) continue;
    std::deque<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained({f, i}))
          borders.emplace_back(n, level + 1);
        else
          queue.push_back(n);
      }
    }
  }
}

}  // namespace

std::vector<std::array<std::uint32_t, 3>> triangulate_roof(const std::vector<Vec2>& footprint) {
  const std::size_t n = footprint.size();
  if (n < 3) throw std::invalid_argument("roof triangulation: a footprint needs at least 3 vertices, got " + std::to_string(n));
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  handles.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    handles.push_back(cdt.insert({footprint[k].x, footprint[k].y}));
    handles.back()->info() = std::uint32_t(k);
  }
  if (cdt.number_of_vertices() != n)
    throw std::invalid_argument("roof triangulation: the footprint repeats a vertex");
  try {
    for (std::size_t k = 0; k < n; ++k) cdt.insert_constraint(handles[k], handles[(k + 1) % n]);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    throw std::invalid_argument("roof triangulation: the footprint's edges cross or touch (not a simple polygon)");
  }
  mark_nesting_levels(cdt);
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if (f->info() == 1) triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  if (triangles.size() != n - 2)
    throw std::invalid_argument("roof triangulation: " + std::to_string(triangles.size()) + " triangles inside a footprint of " +
                                std::to_string(n) + " vertices (a simple polygon has n - 2): not a simple polygon");
  return triangles;
}

}  // namespace cullcheck::oracle
