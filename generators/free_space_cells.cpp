// Free-space cells (navigable_regions.hpp): CGAL's constrained Delaunay triangulation of the open
// ground, its open triangles merged into convex cells. The only CGAL translation unit of
// generators/ (its own object library, like core/convex_partition.cpp).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "core/errors.hpp"
#include "generators/navigable_regions.hpp"
#include "generators/open_space.hpp"
#include "generators/street_cells.hpp"

namespace cullcheck::generators {
namespace {

// Exact predicates: orientation tests (triangulation, convexity of merged cells) are decided
// exactly on the double coordinates. Constructions are inexact, but the only constructed points
// are crossings of footprints that overlap, which generated scenes never have.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, CGAL::Triangulation_face_base_with_info_2<std::size_t, Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>,
                                                       CGAL::Exact_predicates_tag>;
using Point = Kernel::Point_2;
using Ring = std::vector<std::size_t>;  // vertex indices, counter-clockwise
constexpr std::size_t kClosed = ~std::size_t{0};  // a face that is not open ground

// A triangulation edge between two open triangles: a candidate for merging their cells.
struct InnerEdge {
  double length;
  std::size_t u, v;  // u -> v runs counter-clockwise around face a
  std::size_t a, b;  // face indices, a < b
};

std::size_t find(std::vector<std::size_t>& parent, std::size_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// `ring` rotated so that it starts at vertex `first` (its smallest by default).
Ring rotated_to(Ring ring, std::size_t first) {
  std::rotate(ring.begin(), std::find(ring.begin(), ring.end(), first), ring.end());
  return ring;
}
Ring canonical(Ring ring) { return rotated_to(ring, *std::min_element(ring.begin(), ring.end())); }

}  // namespace

std::vector<NavigableRegion> free_space_cells(const Scene& scene, const FreeSpaceOptions& options) {
  if (!std::isfinite(options.margin) || options.margin < 0.0 || options.margin > 1e5)
    throw InputError("navigable regions", "margin", "must be in [0, 100000] metres");
  if (!std::isfinite(options.cell_size) || options.cell_size < 0.1)
    throw InputError("navigable regions", "cell_size", "must be at least 0.1 metres and finite");
  Box2 area;
  area.extend(Vec2{0.0, 0.0});
  if (!scene.buildings.empty()) area = scene.bounds().plan();
  area.lo = area.lo - Vec2{options.margin, options.margin};
  area.hi = area.hi + Vec2{options.margin, options.margin};
  if (!(area.hi.x > area.lo.x && area.hi.y > area.lo.y))
    throw InputError("navigable regions", "margin", "must be positive around an empty scene");

  // Constraints inserted one by one in scene order: the triangulation depends only on the scene.
  Cdt cdt;
  auto add_ring = [&](const std::vector<Vec2>& ring) {
    std::vector<Cdt::Vertex_handle> vs;
    for (Vec2 p : ring) vs.push_back(cdt.insert(Point(p.x, p.y)));
    for (std::size_t i = 0; i < vs.size(); ++i)
      if (vs[i] != vs[(i + 1) % vs.size()]) cdt.insert_constraint(vs[i], vs[(i + 1) % vs.size()]);
  };
  add_ring({area.lo, {area.hi.x, area.lo.y}, area.hi, {area.lo.x, area.hi.y}});
  for (const Building& b : scene.buildings) add_ring(b.footprint);
  // Grid lines every cell_size, as constraints: no cell is merged across one, so every cell fits
  // in a grid square (open ground far from buildings becomes the squares themselves).
  const double squares = std::ceil((area.hi.x - area.lo.x) / options.cell_size) * std::ceil((area.hi.y - area.lo.y) / options.cell_size);
  if (squares > 1e6)
    throw InputError("navigable regions", "cell_size", "makes a grid of " + std::to_string(static_cast<long long>(squares)) +
                                                             " squares over the scene, more than 1000000");
  for (int k = 1; area.lo.x + k * options.cell_size < area.hi.x; ++k)
    cdt.insert_constraint(Point(area.lo.x + k * options.cell_size, area.lo.y), Point(area.lo.x + k * options.cell_size, area.hi.y));
  for (int k = 1; area.lo.y + k * options.cell_size < area.hi.y; ++k)
    cdt.insert_constraint(Point(area.lo.x, area.lo.y + k * options.cell_size), Point(area.hi.x, area.lo.y + k * options.cell_size));

  // Vertices numbered in (x, y) order, so that nothing depends on CGAL's storage order.
  std::vector<Cdt::Vertex_handle> vertices;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) vertices.push_back(v);
  std::sort(vertices.begin(), vertices.end(), [](const auto& p, const auto& q) { return p->point() < q->point(); });
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    vertices[i]->info() = i;
    points.push_back({vertices[i]->point().x(), vertices[i]->point().y()});
  }

  // Open triangles: centroid inside the area and in no footprint (a triangle never crosses a
  // wall, so its centroid decides it). Numbered by their canonical rings, again for order.
  const OpenSpace open(scene);
  std::vector<std::pair<Ring, Cdt::Face_handle>> open_faces;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    f->info() = kClosed;
    const Ring ring{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    const Vec2 c = (points[ring[0]] + points[ring[1]] + points[ring[2]]) * (1.0 / 3.0);
    const bool in_area = c.x > area.lo.x && c.x < area.hi.x && c.y > area.lo.y && c.y < area.hi.y;
    if (in_area && !open.inside_building({c.x, c.y, 0.0})) open_faces.emplace_back(canonical(ring), f);
  }
  std::sort(open_faces.begin(), open_faces.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  std::vector<Ring> cells;
  for (auto& [ring, f] : open_faces) {
    f->info() = cells.size();
    cells.push_back(ring);
  }

  std::vector<InnerEdge> edges;
  for (const auto& [ring, f] : open_faces)
    for (int i = 0; i < 3; ++i) {
      const Cdt::Face_handle g = f->neighbor(i);
      if (cdt.is_infinite(g) || g->info() == kClosed || f->is_constrained(i) || f->info() > g->info()) continue;
      const std::size_t u = f->vertex(Cdt::ccw(i))->info(), v = f->vertex(Cdt::cw(i))->info();
      edges.push_back({length(points[v] - points[u]), u, v, f->info(), g->info()});
    }
  // Longest shared edges first: merging across them gives fat cells. (Grid lines and walls are
  // constrained edges, never candidates.)
  std::sort(edges.begin(), edges.end(), [](const InnerEdge& p, const InnerEdge& q) {
    return std::tie(q.length, p.u, p.v) < std::tie(p.length, q.u, q.v);
  });

  auto left_turn = [&](std::size_t p, std::size_t q, std::size_t r) {
    return CGAL::orientation(Point(points[p].x, points[p].y), Point(points[q].x, points[q].y),
                             Point(points[r].x, points[r].y)) == CGAL::LEFT_TURN;
  };
  std::vector<std::size_t> parent(cells.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (const InnerEdge& e : edges) {
    const std::size_t a = find(parent, e.a), b = find(parent, e.b);
    // Two triangles of one convex cell never share an unmerged edge (the third triangle around
    // their common vertex would make that vertex reflex), so a != b; kept as a guard.
    if (a == b) continue;
    // a runs ... u v ..., b runs ... v u ...: the union runs v ..(a).. u ..(b).. back to v.
    const Ring ra = rotated_to(cells[a], e.v), rb = rotated_to(cells[b], e.u);
    Ring merged(ra);
    merged.insert(merged.end(), rb.begin() + 1, rb.end() - 1);
    // Strictly convex at the two joints (u and v): no collinear vertex enters a ring.
    const std::size_t n = merged.size(), ju = ra.size() - 1;
    if (!left_turn(merged[ju - 1], merged[ju], merged[ju + 1]) || !left_turn(merged[n - 1], merged[0], merged[1])) continue;
    parent[b] = a;
    cells[a] = std::move(merged);
  }

  // The surviving cells, ordered by their canonical rings; neighbours across unmerged edges.
  std::vector<std::size_t> roots;
  for (std::size_t f = 0; f < cells.size(); ++f)
    if (find(parent, f) == f) {
      cells[f] = canonical(cells[f]);
      roots.push_back(f);
    }
  std::sort(roots.begin(), roots.end(), [&](std::size_t p, std::size_t q) { return cells[p] < cells[q]; });
  std::vector<std::uint32_t> id_of(cells.size());
  std::vector<NavigableRegion> out(roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) {
    id_of[roots[i]] = static_cast<std::uint32_t>(i);
    out[i].id = static_cast<std::uint32_t>(i);
    out[i].kind = "free";
    for (std::size_t v : cells[roots[i]]) out[i].ring.push_back(points[v]);
  }
  for (const InnerEdge& e : edges) {
    const std::uint32_t a = id_of[find(parent, e.a)], b = id_of[find(parent, e.b)];
    if (a == b) continue;
    out[a].neighbours.push_back(b);
    out[b].neighbours.push_back(a);
  }
  for (NavigableRegion& r : out) {
    std::sort(r.neighbours.begin(), r.neighbours.end());
    r.neighbours.erase(std::unique(r.neighbours.begin(), r.neighbours.end()), r.neighbours.end());
  }
  return out;
}

std::vector<NavigableRegion> navigable_regions(const Scene& scene, const FreeSpaceOptions& options) {
  if (auto cells = street_cells_of(scene)) return std::move(*cells);
  return free_space_cells(scene, options);
}

}  // namespace cullcheck::generators
