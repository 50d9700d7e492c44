#include "engine/slice_wise/cell_culling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <stdexcept>

#include "core/elapsed.hpp"

namespace cullcheck::slice_wise {
namespace {

using Clock = std::chrono::steady_clock;

double distance_to(Vec3 p, const Box3& b) {
  const double dx = std::max({b.lo.x - p.x, 0.0, p.x - b.hi.x});
  const double dy = std::max({b.lo.y - p.y, 0.0, p.y - b.hi.y});
  const double dz = std::max({b.lo.z - p.z, 0.0, p.z - b.hi.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

bool empty(const Box3& b) { return !(b.lo.x <= b.hi.x); }

// Front to back over the tree: on_node(node) says whether to open a node (or, at a leaf, to visit
// its objects); on_object(object) is called for its objects, nearest first.
template <class OnNode, class OnObject>
void front_to_back(const ObjectTree& tree, const std::vector<SliceWiseObject>& objects, Vec3 eye, OnNode&& on_node,
                   OnObject&& on_object) {
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  queue.emplace(distance_to(eye, tree.nodes[0].box), 0u);
  std::vector<Item> leaf;
  while (!queue.empty()) {
    const std::uint32_t n = queue.top().second;
    queue.pop();
    const ObjectTree::Node& node = tree.nodes[n];
    if (node.last == node.first || !on_node(node)) continue;
    if (node.child_count > 0) {
      for (std::uint32_t c = 0; c < node.child_count; ++c)
        queue.emplace(distance_to(eye, tree.nodes[node.first_child + c].box), node.first_child + c);
      continue;
    }
    leaf.clear();
    for (std::uint32_t k = node.first; k < node.last; ++k)
      leaf.emplace_back(distance_to(eye, objects[tree.order[k]].box), tree.order[k]);
    std::sort(leaf.begin(), leaf.end());
    for (const auto& [d, o] : leaf) on_object(o);
  }
}

// Per triangle of `m`: whether it may be turned to some eye of the cell (the square of half-side h
// around `centre` at its height). A face of an outward-wound closed solid turned away from an
// eye outside it is hidden from that eye by the solid: the ray is inside the solid just before
// it, so it crossed the solid's boundary earlier. Eyes in the face's plane (1e-6 m) count as
// turned to it, and so does a degenerate face.
std::vector<char> faces_turned_to_cell(const MeshObject& m, Vec3 centre, double h) {
  std::vector<char> out(m.triangles.size(), 1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Vec3 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    const Vec3 n = cross(b - a, c - a);
    const double len = length(n);
    if (!(len > 0)) continue;
    double most = -HUGE_VAL;
    for (double dx : {-h, h})
      for (double dy : {-h, h}) most = std::max(most, dot(n, Vec3{centre.x + dx, centre.y + dy, centre.z} - a) / len);
    out[t] = most > -1e-6;
  }
  return out;
}

// What a query must find hidden for slice i of axis a to be hidden: its slab box, or, when the
// faces turned away from the cell are left out (`facing` not empty), the boxes of the others cut
// to the slab, grouped by the slice of the next horizontal axis (both, for a horizontal slice)
// where each begins, so that the faces at opposite walls do not share one box. None: hidden.
struct SlicePart {
  int key = 0;  // part_key of its triangles
  Box3 box;
};

int part_key(const std::array<std::uint8_t, 6>& r, std::size_t a) { return a == 0 ? r[2] : a == 1 ? r[0] : r[0] * 256 + r[2]; }

std::vector<SlicePart> slice_parts(const SliceWiseObject& o, const MeshObject& m, std::size_t a, std::size_t i,
                                   const std::vector<char>& facing) {
  const Box3& slab = o.slice_boxes[a][i];
  if (facing.empty()) return {{0, slab}};
  std::map<int, Box3> groups;
  const AxisSlices& s = o.slices.axes[a];
  for (std::uint32_t k = s.begin[i]; k < s.begin[i + 1]; ++k) {
    const std::uint32_t t = s.triangles[k];
    if (!facing[t]) continue;
    Box3& g = groups[part_key(o.ranges[t], a)];
    for (std::uint32_t v : m.triangles[t]) g.extend(m.vertices[v]);
  }
  std::vector<SlicePart> out;
  for (auto& [key, g] : groups) {
    g.lo = {std::max(g.lo.x, slab.lo.x), std::max(g.lo.y, slab.lo.y), std::max(g.lo.z, slab.lo.z)};
    g.hi = {std::min(g.hi.x, slab.hi.x), std::min(g.hi.y, slab.hi.y), std::min(g.hi.z, slab.hi.z)};
    out.push_back({key, g});
  }
  return out;
}

// With the parts' own hidden heights known (metres above the object's bottom, per vertical axis,
// slice and part key), the facing triangles that are hidden at every point: each of its cells
// (vertical slice i, horizontal slice j) hidden by its part of slice i up to the cell's top (or
// its own), or by horizontal slice j whole. Turned-away faces are hidden by the object itself.
// A triangle is dropped when either vertical axis shows it hidden; a form that keeps every
// triangle left keeps every visible one.
// Without `facing` (empty), every triangle faces the cell and each slice is one part, its hidden
// height the slice's own (`slice_height`).
std::vector<char> possibly_visible(const SliceWiseObject& o, const MeshObject& m, const std::vector<char>& facing,
                                   const std::array<std::vector<std::map<int, double>>, 2>& part_height,
                                   const SliceOcclusion& slice_height) {
  const std::vector<char>& z_hidden = slice_height.z_hidden;
  const std::size_t nz = o.slices.axes[2].count();
  std::vector<char> keep(o.ranges.size(), 0);
  for (std::size_t t = 0; t < keep.size(); ++t) {
    if (!facing.empty() && !facing[t]) continue;
    const auto& r = o.ranges[t];
    double top_t = -std::numeric_limits<double>::infinity();
    for (std::uint32_t v : m.triangles[t]) top_t = std::max(top_t, m.vertices[v].z);
    top_t -= o.box.lo.z;
    bool hidden = false;
    for (std::size_t a = 0; a < 2 && !hidden; ++a) {
      bool all = true;
      for (std::size_t i = r[2 * a]; i <= r[2 * a + 1] && all; ++i) {
        double h = -1.0;
        if (facing.empty()) {
          if (i < slice_height.hidden_height[a].size()) h = slice_height.hidden_height[a][i];
        } else if (i < part_height[a].size()) {
          const auto it = part_height[a][i].find(part_key(r, a));
          if (it != part_height[a][i].end()) h = it->second;
        }
        for (std::size_t j = r[4]; j <= r[5] && all; ++j) {
          if (j < z_hidden.size() && z_hidden[j]) continue;
          const double top = j < nz ? std::min(top_t, horizontal_slice_top(o, j)) : top_t;
          all = h + kHeightSlack >= top;
        }
      }
      hidden = all;
    }
    keep[t] = !hidden;
  }
  return keep;
}

}  // namespace

void validate(const CellCullingOptions& o) {
  if (!(o.delta > 0) || !std::isfinite(o.delta)) throw std::invalid_argument("slice-wise: delta must be positive and finite");
  if (o.cube_resolution < 8 || o.cube_resolution > 4096)
    throw std::invalid_argument("slice-wise: cube_resolution must lie in [8, 4096]");
  if (o.zoom_resolution < 8 || o.zoom_resolution > 4096)
    throw std::invalid_argument("slice-wise: zoom_resolution must lie in [8, 4096]");
  if (!(o.near > 0) || !(o.near < 1)) throw std::invalid_argument("slice-wise: near must lie in (0, 1) metres");
}

CellCuller::CellCuller(const SliceWiseScene& scene, const CellCullingOptions& options) : scene_(scene), options_(options) {
  validate(options);
}

bool CellCuller::cube_hidden(const Box3& box) { return hidden_in_cube(cube_, box); }

bool CellCuller::hidden_in_cube(std::array<OcclusionBuffer, 6>& faces, const Box3& box) const {
  // Points within `near` of the eye on every axis lie in no face's image: such a box stays.
  const double r = options_.near * 1.001;
  if (box.lo.x <= eye_.x + r && box.hi.x >= eye_.x - r && box.lo.y <= eye_.y + r && box.hi.y >= eye_.y - r &&
      box.lo.z <= eye_.z + r && box.hi.z >= eye_.z - r)
    return false;
  for (OcclusionBuffer& face : faces)
    if (face.test_box(box).visible) return false;
  return true;
}

void CellCuller::draw_cube(const TriangleMesh& occluder, const Box3& box) {
  for (OcclusionBuffer& face : cube_) {
    if (!face.locate_box(box).in_image) continue;
    for (const auto& t : occluder.triangles)
      face.draw_triangle(occluder.vertices[t[0]], occluder.vertices[t[1]], occluder.vertices[t[2]]);
  }
}

void CellCuller::draw_zoomed(OcclusionBuffer& view, std::uint32_t candidate, double farthest, CellStatistics& stats) {
  const auto& objects = scene_.objects();
  // Whether something in `box` may stand in front of part of the candidate in this view.
  auto may_occlude = [&](const Box3& box) {
    if (empty(box)) return false;
    const BoxVisibility where = view.locate_box(box);
    if (!where.in_image || where.nearest >= farthest) return false;
    return view.test_box(box).visible;
  };
  front_to_back(
      scene_.tree(), objects, eye_, [&](const ObjectTree::Node& node) { return may_occlude(node.box); },
      [&](std::uint32_t o) {
        if (o == candidate && !options_.self_occlusion) return;
        const SliceWiseObject& obj = objects[o];
        if (!may_occlude(obj.occluder_box)) return;
        ++stats.occluders_drawn;
        stats.triangles_drawn += obj.occluder.triangles.size();
        for (const auto& t : obj.occluder.triangles)
          view.draw_triangle(obj.occluder.vertices[t[0]], obj.occluder.vertices[t[1]], obj.occluder.vertices[t[2]]);
      });
}

bool CellCuller::zoom_hidden(const Box3& box, CellStatistics& stats) {
  ++stats.queries;
  if (zoom_views_ == 1) {
    const BoxVisibility r = zoom_[0].test_box(box);
    return !r.visible && !r.crosses_near && !r.beyond_image;
  }
  return hidden_in_cube(zoom_, box);
}

CellPvs CellCuller::cull(Vec3 centre) {
  CellPvs out;
  CellStatistics& stats = out.stats;
  eye_ = centre;
  const auto& objects = scene_.objects();
  const auto views = cube_views(centre, options_.cube_resolution, options_.near);
  for (std::size_t k = 0; k < 6; ++k) cube_[k].reset(views[k]);

  // Algorithm 1, coarse: blocks and boxes against the cube map, drawing what stays.
  auto start = Clock::now();
  std::vector<std::uint32_t> candidates;
  front_to_back(
      scene_.tree(), objects, eye_,
      [&](const ObjectTree::Node& node) {
        if (!cube_hidden(node.box)) return true;
        ++stats.coarse_blocks_hidden;
        return false;
      },
      [&](std::uint32_t o) {
        const SliceWiseObject& obj = objects[o];
        if (cube_hidden(obj.box)) return;
        candidates.push_back(o);
        if (empty(obj.occluder_box)) return;
        ++stats.occluders_drawn;
        stats.triangles_drawn += obj.occluder.triangles.size();
        draw_cube(obj.occluder, obj.occluder_box);
      });
  std::sort(candidates.begin(), candidates.end());
  stats.coarse_candidates = candidates.size();
  stats.coarse_ms = ms_since(start);

  // Each candidate zoomed: its box, then Algorithm 2 on its slices, then Algorithm 3.
  start = Clock::now();
  for (std::uint32_t c : candidates) {
    const SliceWiseObject& obj = objects[c];
    ObjectVisibility v;
    v.object = c;
    v.indices = all_visible(obj.slices);
    const auto view = zoomed_view(centre, obj.box, options_.zoom_resolution, options_.near);
    if (view) {
      zoom_[0].reset(*view);
      zoom_views_ = 1;
    } else {
      v.zoom_refused = true;
      const auto faces = cube_views(centre, options_.zoom_resolution, options_.near);
      for (std::size_t k = 0; k < 6; ++k) zoom_[k].reset(faces[k]);
      zoom_views_ = 6;
    }
    {
      for (int k = 0; k < zoom_views_; ++k) {
        const BoxVisibility where = zoom_[static_cast<std::size_t>(k)].locate_box(obj.box);
        if (where.in_image) draw_zoomed(zoom_[static_cast<std::size_t>(k)], c, where.farthest, stats);
      }
      if (zoom_hidden(obj.box, stats)) continue;
      if (options_.slices) {
        SliceOcclusion occ;
        const double height = obj.box.hi.z - obj.box.lo.z;
        const int steps = height > 0 ? static_cast<int>(std::ceil(height / options_.delta)) : 0;
        // With self-occlusion, an outward-wound closed object's faces turned away from the whole
        // cell hide behind the object itself (faces_turned_to_cell) when the cell lies outside it.
        const double h = scene_.options().epsilon / std::sqrt(2.0);
        const bool cell_outside = centre.z < obj.box.lo.z || centre.z > obj.box.hi.z || centre.x + h < obj.box.lo.x ||
                                  centre.x - h > obj.box.hi.x || centre.y + h < obj.box.lo.y || centre.y - h > obj.box.hi.y;
        const MeshObject* mesh = obj.is_mesh ? &scene_.scene().meshes[obj.scene_index] : nullptr;
        std::vector<char> facing;
        if (options_.self_occlusion && options_.turned_away_faces && mesh && obj.outward_solids && cell_outside) facing = faces_turned_to_cell(*mesh, centre, h);
        // Per vertical axis, slice and part: the height up to which the part is hidden.
        std::array<std::vector<std::map<int, double>>, 2> part_height;
        for (std::size_t a = 0; a < 2; ++a) {
          const AxisSlices& s = obj.slices.axes[a];
          part_height[a].resize(s.count());
          for (std::size_t i = 0; i < s.count(); ++i) {
            const std::vector<SlicePart> parts = mesh ? slice_parts(obj, *mesh, a, i, facing) : std::vector<SlicePart>{{0, obj.slice_boxes[a][i]}};
            auto hidden_to = [&](Box3 b, int k) {
              if (k < steps) b.hi.z = std::min(b.hi.z, obj.box.lo.z + k * options_.delta);
              return b.hi.z < b.lo.z || zoom_hidden(b, stats);  // nothing of the part that low: hidden
            };
            // Largest k whose box is hidden (0: none), by bisection: per part when the facing
            // triangles are known (each part's height says which of its triangles are hidden),
            // else for the slice at once (it is hidden to k when every part is).
            auto bisect = [&](auto&& hidden_at) {
              int lo_k = 0, hi_k = steps;
              while (lo_k < hi_k) {
                const int mid = (lo_k + hi_k + 1) / 2;
                if (hidden_at(mid)) lo_k = mid;
                else hi_k = mid - 1;
              }
              return lo_k >= steps ? height : lo_k * options_.delta;
            };
            double slice_height = height;
            if (!facing.empty()) {
              for (const SlicePart& p : parts) {
                const double h = bisect([&](int k) { return hidden_to(p.box, k); });
                part_height[a][i][p.key] = h;
                slice_height = std::min(slice_height, h);
              }
            } else {
              slice_height = bisect([&](int k) {
                return std::all_of(parts.begin(), parts.end(), [&](const SlicePart& p) { return hidden_to(p.box, k); });
              });
            }
            occ.hidden_height[a].push_back(slice_height);
          }
        }
        for (std::size_t j = 0; j < obj.slices.axes[2].count(); ++j) {
          const std::vector<SlicePart> parts = mesh ? slice_parts(obj, *mesh, 2, j, facing) : std::vector<SlicePart>{{0, obj.slice_boxes[2][j]}};
          occ.z_hidden.push_back(std::all_of(parts.begin(), parts.end(), [&](const SlicePart& p) { return zoom_hidden(p.box, stats); }) ? 1 : 0);
        }
        v.choice = choose_slices(obj, occ);
        if (mesh && (!facing.empty() || options_.both_vertical_axes)) {
          // Algorithm 3 over triangles: the best form keeping every triangle not shown hidden
          // drops at least what the rectangle of hidden cells drops (its triangles are all shown
          // hidden), more where a long triangle's visible part kept a cell it reaches into.
          const std::vector<char> keep = possibly_visible(obj, *mesh, facing, part_height, occ);
          SliceChoice by_triangle = best_form_keeping(obj, keep, options_.both_vertical_axes);
          if (by_triangle.dropped > v.choice.dropped) {
            by_triangle.any_hidden_cell = true;
            by_triangle.cell_dropped = std::max(v.choice.cell_dropped, static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 0)));
            v.choice = by_triangle;
          }
        }
        v.indices = v.choice.indices;
      }
    }
    out.visible.push_back(v);
  }
  stats.fine_ms = ms_since(start);
  return out;
}

}  // namespace cullcheck::slice_wise
