#include "engine/slice_wise/slice_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "core/elapsed.hpp"
#include "core/parallel_indices.hpp"
#include "engine/slice_wise/solid_parts.hpp"
#include "engine/slice_wise/voxel_erosion.hpp"

namespace cullcheck::slice_wise {
namespace {

using Clock = std::chrono::steady_clock;

Box3 box_of(const TriangleMesh& m) {
  Box3 b;
  for (const auto& t : m.triangles)
    for (std::uint32_t v : t) b.extend(m.vertices[v]);
  return b;
}

void fill_slice_boxes(SliceWiseObject& o, const MeshObject& m) {
  for (std::size_t a = 0; a < 3; ++a) {
    const AxisSlices& s = o.slices.axes[a];
    auto& boxes = o.slice_boxes[a];
    boxes.assign(s.count(), Box3{});
    for (std::size_t i = 0; i < s.count(); ++i) {
      Box3& b = boxes[i];
      for (std::uint32_t k = s.begin[i]; k < s.begin[i + 1]; ++k)
        for (std::uint32_t v : m.triangles[s.triangles[k]]) b.extend(m.vertices[v]);
      const double lo = s.origin + s.slab[i] * s.thickness, hi = s.origin + (s.slab[i] + 1.0) * s.thickness;
      double& blo = a == 0 ? b.lo.x : a == 1 ? b.lo.y : b.lo.z;
      double& bhi = a == 0 ? b.hi.x : a == 1 ? b.hi.y : b.hi.z;
      blo = std::max(blo, lo), bhi = std::min(bhi, hi);
    }
  }
}

void fill_ranges(SliceWiseObject& o) {
  o.ranges.assign(o.slices.triangle_count, {255, 0, 255, 0, 255, 0});
  for (std::size_t a = 0; a < 3; ++a) {
    const AxisSlices& s = o.slices.axes[a];
    for (std::size_t i = 0; i < s.count(); ++i)
      for (std::uint32_t k = s.begin[i]; k < s.begin[i + 1]; ++k) {
        auto& r = o.ranges[s.triangles[k]];
        r[2 * a] = std::min<std::uint8_t>(r[2 * a], static_cast<std::uint8_t>(i));
        r[2 * a + 1] = std::max<std::uint8_t>(r[2 * a + 1], static_cast<std::uint8_t>(i));
      }
  }
}

void build_node(ObjectTree& tree, std::uint32_t node, const std::vector<Box3>& boxes, std::uint32_t leaf_size,
                int depth) {
  ObjectTree::Node n = tree.nodes[node];
  Box3 box;
  double cx0 = HUGE_VAL, cx1 = -HUGE_VAL, cy0 = HUGE_VAL, cy1 = -HUGE_VAL;
  for (std::uint32_t k = n.first; k < n.last; ++k) {
    const Box3& b = boxes[tree.order[k]];
    box.extend(b.lo), box.extend(b.hi);
    const double cx = 0.5 * (b.lo.x + b.hi.x), cy = 0.5 * (b.lo.y + b.hi.y);
    cx0 = std::min(cx0, cx), cx1 = std::max(cx1, cx), cy0 = std::min(cy0, cy), cy1 = std::max(cy1, cy);
  }
  tree.nodes[node].box = box;
  if (n.last - n.first <= leaf_size || depth >= 24 || (cx0 == cx1 && cy0 == cy1)) return;
  // Four quadrants about the middle of the objects' centres; empty quadrants get no node.
  const double mx = 0.5 * (cx0 + cx1), my = 0.5 * (cy0 + cy1);
  auto quadrant = [&](std::uint32_t o) {
    const Box3& b = boxes[o];
    return (0.5 * (b.lo.x + b.hi.x) > mx ? 1 : 0) + (0.5 * (b.lo.y + b.hi.y) > my ? 2 : 0);
  };
  std::stable_sort(tree.order.begin() + n.first, tree.order.begin() + n.last,
                   [&](std::uint32_t a, std::uint32_t b) { return quadrant(a) < quadrant(b); });
  const auto first_child = static_cast<std::uint32_t>(tree.nodes.size());
  std::uint32_t begin = n.first;
  for (int q = 0; q < 4; ++q) {
    std::uint32_t end = begin;
    while (end < n.last && quadrant(tree.order[end]) == q) ++end;
    if (end > begin) {
      ObjectTree::Node child;
      child.first = begin, child.last = end;
      tree.nodes.push_back(child);
    }
    begin = end;
  }
  tree.nodes[node].first_child = first_child;
  tree.nodes[node].child_count = static_cast<std::uint32_t>(tree.nodes.size()) - first_child;
  for (std::uint32_t c = 0; c < tree.nodes[node].child_count; ++c) build_node(tree, first_child + c, boxes, leaf_size, depth + 1);
}

}  // namespace

ObjectTree build_object_tree(const std::vector<Box3>& boxes, std::uint32_t leaf_size) {
  ObjectTree tree;
  tree.order.resize(boxes.size());
  for (std::uint32_t i = 0; i < boxes.size(); ++i) tree.order[i] = i;
  ObjectTree::Node root;
  root.last = static_cast<std::uint32_t>(boxes.size());
  tree.nodes.push_back(root);
  build_node(tree, 0, boxes, std::max<std::uint32_t>(leaf_size, 1), 0);
  return tree;
}

std::string_view shrinking_name(Shrinking s) { return s == Shrinking::minkowski_mesh ? "minkowski_mesh" : "voxel_erosion"; }

Shrinking parse_shrinking(std::string_view name) {
  if (name == "minkowski_mesh") return Shrinking::minkowski_mesh;
  if (name == "voxel_erosion") return Shrinking::voxel_erosion;
  throw std::invalid_argument("unknown shrinking '" + std::string(name) + "' (minkowski_mesh or voxel_erosion)");
}

MeshObject building_as_mesh(const Building& building) {
  const TriangleMesh t = building_mesh(building);
  MeshObject m;
  m.id = building.id;
  m.vertices = t.vertices;
  m.triangles = t.triangles;
  // The floor (building_mesh has none): the roof's fans at the ground, turned over, so that the
  // mesh is closed (voxel erosion needs an inside).
  const auto n = static_cast<std::uint32_t>(building.footprint.size());
  for (std::size_t k = 2 * n; k < t.triangles.size(); ++k) {
    const auto& r = t.triangles[k];
    m.triangles.push_back({r[0] - n, r[2] - n, r[1] - n});
  }
  finish_mesh(m);
  return m;
}

SliceWiseScene::SliceWiseScene(const Scene& scene, const SliceSceneOptions& options) : scene_(scene), options_(options) {
  if (!(options.epsilon > 0) || !std::isfinite(options.epsilon))
    throw std::invalid_argument("slice-wise: epsilon must be positive and finite");
  if (!(options.voxel_m > 0) || !std::isfinite(options.voxel_m))
    throw std::invalid_argument("slice-wise: voxel_m must be positive and finite");
  const std::size_t n = scene.meshes.size() + scene.buildings.size();
  objects_.resize(n);
  std::vector<MeshObject> converted(scene.buildings.size());  // the buildings as closed meshes
  auto mesh_of = [&](std::size_t i) -> const MeshObject& {
    return i < scene.meshes.size() ? scene.meshes[i] : converted[i - scene.meshes.size()];
  };
  std::vector<double> slice_time(n, 0.0);
  const auto start = Clock::now();
  for_each_index(n, options.threads, [&] {
    return [&](std::size_t i) {
      SliceWiseObject& o = objects_[i];
      const bool mesh = i < scene.meshes.size();
      if (!mesh) converted[i - scene.meshes.size()] = building_as_mesh(scene.buildings[i - scene.meshes.size()]);
      const MeshObject& m = mesh_of(i);
      o.id = m.id, o.is_mesh = mesh, o.scene_index = mesh ? i : i - scene.meshes.size();
      o.box = m.bounds;
      const auto t = Clock::now();
      o.slices = slice_object(m, options.slicing);
      fill_ranges(o);
      fill_slice_boxes(o, m);
      slice_time[i] = seconds_since(t);
    };
  });

  // Shrinking, in groups: closed meshes that lie against one another are eroded as one solid
  // (voxel_erosion.hpp's erode_closed_meshes), everything else on its own.
  const bool voxels = options.shrinking == Shrinking::voxel_erosion;
  std::vector<std::vector<std::uint32_t>> groups;
  {
    std::vector<std::uint32_t> closed;  // object indices
    for (std::uint32_t i = 0; i < n; ++i)
      if (voxels && mesh_of(i).closed) closed.push_back(i);
    std::vector<std::uint32_t> root(n);
    std::iota(root.begin(), root.end(), 0u);
    auto find = [&](std::uint32_t v) {
      while (root[v] != v) v = root[v] = root[root[v]];
      return v;
    };
    if (options.erode_touching && closed.size() > 1) {
      std::vector<const MeshObject*> meshes;
      for (std::uint32_t i : closed) meshes.push_back(&mesh_of(i));
      for (const auto& [a, b] : touching_pairs(meshes)) {
        const std::uint32_t ra = find(closed[a]), rb = find(closed[b]);
        root[std::max(ra, rb)] = std::min(ra, rb);  // the lowest index is a group's root
      }
    }
    std::vector<std::uint32_t> group_of(n, UINT32_MAX);
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t r = find(i);
      if (group_of[r] == UINT32_MAX) group_of[r] = static_cast<std::uint32_t>(groups.size()), groups.emplace_back();
      groups[group_of[r]].push_back(i);
    }
  }
  const double e = options.epsilon, s = e / std::sqrt(2.0);
  const Vec3 element = options.erosion_element == SliceSceneOptions::Element::square ? Vec3{s, s, 0} : Vec3{e, e, e};
  // An object's occluder from its eroded boxes (alone or in a group of `with` objects).
  auto take_eroded = [&](SliceWiseObject& o, const std::vector<Box3>& boxes, bool outward, std::size_t with) {
    o.occluder = boxes_mesh(boxes);
    o.occluder_boxes = boxes.size();
    o.outward_solids = outward;
    o.shrunk_by = Shrinking::voxel_erosion;
    o.eroded_with = static_cast<std::uint32_t>(with);
    o.occluder_box = box_of(o.occluder);
  };
  auto erode_alone = [&](std::uint32_t i) {
    SliceWiseObject& o = objects_[i];
    const MeshObject& m = mesh_of(i);
    if (voxels && m.closed) {
      const VoxelErosion eroded = erode_closed_mesh(m, element, options.voxel_m);
      take_eroded(o, eroded.boxes, eroded.outward, 1);
      return;
    }
    TriangleMesh plain;
    plain.vertices = m.vertices;
    plain.triangles = m.triangles;
    ShrunkMesh shrunk = shrink_mesh(plain, options.epsilon, m.bounds.lo.z);
    o.occluder = std::move(shrunk.mesh);
    o.shrink = shrunk.stats;
    o.occluder_box = box_of(o.occluder);
  };
  for_each_index(groups.size(), options.threads, [&] {
    return [&](std::size_t g) {
      const auto t = Clock::now();
      const std::vector<std::uint32_t>& members = groups[g];
      Box3 joint;
      for (std::uint32_t i : members) joint.extend(mesh_of(i).bounds.lo), joint.extend(mesh_of(i).bounds.hi);
      const Vec3 extent = joint.hi - joint.lo;
      const double cells = std::ceil(extent.x / options.voxel_m) * std::ceil(extent.y / options.voxel_m) * std::ceil(extent.z / options.voxel_m);
      if (members.size() == 1 || !(cells <= double(options.max_joint_voxels))) {
        for (std::uint32_t i : members) {
          const auto ti = Clock::now();
          erode_alone(i);
          objects_[i].shrink_seconds = seconds_since(ti);
        }
        return;
      }
      std::vector<const MeshObject*> meshes;
      for (std::uint32_t i : members) meshes.push_back(&mesh_of(i));
      const VoxelErosion eroded = erode_closed_meshes(meshes, element, options.voxel_m, options.max_joint_voxels);
      std::vector<std::vector<Box3>> own(members.size());
      for (std::size_t b = 0; b < eroded.boxes.size(); ++b) own[eroded.box_owner[b]].push_back(eroded.boxes[b]);
      const double share = seconds_since(t) / double(members.size());
      for (std::size_t q = 0; q < members.size(); ++q) {
        SliceWiseObject& o = objects_[members[q]];
        take_eroded(o, own[q], eroded.outward_of[q] != 0, members.size());
        o.shrink_seconds = share;
      }
    };
  });
  for (double t : slice_time) slicing_seconds_ += t;
  shrinking_seconds_ = seconds_since(start);
  std::vector<Box3> boxes;
  for (const SliceWiseObject& o : objects_) boxes.push_back(o.box);
  tree_ = build_object_tree(boxes);
}

}  // namespace cullcheck::slice_wise
