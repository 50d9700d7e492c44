#include "engine/online_image_space/online_culling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/elapsed.hpp"
#include "engine/online_image_space/occlusion_mask.hpp"

namespace cullcheck {
namespace {

using Clock = std::chrono::steady_clock;

// Angle between two cameras' view directions plus their difference in roll.
double turn_between(const Camera& a, const Camera& b) {
  const CameraBasis ba = basis_of(a), bb = basis_of(b);
  return std::acos(std::clamp(dot(ba.forward, bb.forward), -1.0, 1.0)) + std::abs(a.roll - b.roll);
}

void check(const OnlineCullingOptions& o) {
  const auto bad = [](const std::string& what) { return std::invalid_argument("online image-space culling: " + what); };
  if (o.shrink_pixels < 0 || o.shrink_pixels > 1000) throw bad("shrink_pixels (Δ) must be 0..1000");
  if (o.mask_size < 4 || o.mask_size > 2048) throw bad("mask_size (s) must be 4..2048");
  if (o.leaf_size < 1) throw bad("leaf_size (ρ) must be at least 1");
  if (!(o.min_distance >= 0.0) || !std::isfinite(o.min_distance)) throw bad("min_distance (D) must be a finite distance >= 0");
  if (!(o.max_speed > 0.0) || !std::isfinite(o.max_speed)) throw bad("max_speed (V) must be a finite speed > 0");
  if (o.mask_block < 2 || o.mask_block > 64) throw bad("mask_block (b) must be 2..64");
  if (o.mask_levels < -1 || o.mask_levels > 64) throw bad("mask_levels must be -1 (all) or 0..64");
  if (o.coverage_grid < 1 || o.coverage_grid > 1024) throw bad("coverage_grid must be 1..1024");
  if (!(o.critical_turn >= 0.0)) throw bad("critical_turn must be >= 0 radians");
}

// The camera whose frustum the clip region covers (image_plane.hpp): fields of view widened by
// the turn allowance on every side, each half-angle capped at 80 degrees like the plane's.
Camera widened(const Camera& camera, double turn) {
  Camera wide = camera;
  const double cap = 80.0 * kPi / 180.0;
  wide.hfov = 2 * std::min(cap, camera.hfov / 2 + turn);
  wide.vfov = 2 * std::min(cap, camera.vfov / 2 + turn);
  return wide;
}

}  // namespace

std::string to_string(CriticalReason reason) {
  switch (reason) {
    case CriticalReason::none: return "none";
    case CriticalReason::first: return "first";
    case CriticalReason::expired: return "expired";
    case CriticalReason::turned: return "turned";
    case CriticalReason::occluder_deleted: return "occluder_deleted";
    case CriticalReason::left_ball: return "left_ball";
  }
  return "?";
}

OnlineImageSpaceCulling::OnlineImageSpaceCulling(const Scene& scene, Variant variant, const OnlineCullingOptions& options)
    : variant_(variant), options_((check(options), options)), polygons_(online::scene_polygons(scene)),
      tree_(polygons_, options.leaf_size), object_frame_(polygons_.ids.size(), 0), alive_object_(polygons_.ids.size(), 1),
      occluder_(polygons_.size(), 0) {
  for (std::uint32_t i = 0; i < polygons_.ids.size(); ++i) object_index_[polygons_.ids[i]] = i;
  // scene_polygons appends each object's polygons in object order, so they are contiguous.
  object_first_.assign(polygons_.ids.size() + 1, static_cast<std::uint32_t>(polygons_.size()));
  for (auto p = static_cast<std::uint32_t>(polygons_.size()); p-- > 0;) object_first_[polygons_.object[p]] = p;
  for (std::size_t o = polygons_.ids.size(); o-- > 0;) object_first_[o] = std::min(object_first_[o], object_first_[o + 1]);
}

void OnlineImageSpaceCulling::add_object(ObjectId id, const std::function<void(std::uint32_t)>& append) {
  if (const auto at = object_index_.find(id); at != object_index_.end() && alive_object_[at->second])
    throw std::invalid_argument(name() + ": insert_object: object " + std::to_string(id) + " is already in the scene");
  const auto index = static_cast<std::uint32_t>(polygons_.ids.size());
  const std::size_t first = polygons_.size();
  append(index);
  polygons_.ids.push_back(id);
  object_index_[id] = index;
  object_frame_.push_back(0);
  alive_object_.push_back(1);
  occluder_.resize(polygons_.size(), 0);
  object_first_.push_back(static_cast<std::uint32_t>(polygons_.size()));
  for (std::size_t p = first; p < polygons_.size(); ++p) tree_.insert(static_cast<std::uint32_t>(p));
}

void OnlineImageSpaceCulling::insert_object(const Building& building) {
  add_object(building.id, [&](std::uint32_t index) { online::append_building(building, index, polygons_); });
}

void OnlineImageSpaceCulling::insert_object(const MeshObject& mesh) {
  add_object(mesh.id, [&](std::uint32_t index) { online::append_mesh(mesh, index, polygons_); });
}

bool OnlineImageSpaceCulling::update_scene(const Scene& present, const std::vector<ObjectId>& appeared,
                                           const std::vector<ObjectId>& vanished) {
  for (ObjectId id : vanished) erase_object(id);
  for (ObjectId id : appeared) {
    if (const Building* b = present.find(id)) insert_object(*b);
    else if (const MeshObject* m = present.find_mesh(id)) insert_object(*m);
    else throw std::invalid_argument(name() + ": update_scene: appeared object " + std::to_string(id) + " is not in the present scene");
  }
  return true;
}

void OnlineImageSpaceCulling::erase_object(ObjectId id) {
  const auto at = object_index_.find(id);
  if (at == object_index_.end() || !alive_object_[at->second])
    throw std::invalid_argument(name() + ": erase_object: object " + std::to_string(id) + " is not in the scene");
  alive_object_[at->second] = 0;
  for (std::uint32_t p = object_first_[at->second]; p < object_first_[at->second + 1]; ++p) {
    if (!tree_.alive(p)) continue;
    tree_.erase(p);
    occluder_deleted_ = occluder_deleted_ || occluder_[p];
  }
}

std::string OnlineImageSpaceCulling::unsupported_camera(const Camera& camera) const {
  if (camera.orthographic() || camera.omnidirectional())
    return name() + " draws its occlusion masks on a perspective image plane; it takes perspective cameras only";
  if (camera.hfov > 170.0 * kPi / 180.0 || camera.vfov > 170.0 * kPi / 180.0)
    return name() + " needs fields of view up to 170 degrees for a planar mask";
  return "";
}

void OnlineImageSpaceCulling::set_frame(std::size_t /*frame*/, double time_seconds) {
  time_ = time_seconds;
  told_time_ = true;
}

double OnlineImageSpaceCulling::delta_for(const Camera& camera, double distance) const {
  const double shrink = options_.shrink_pixels;
  if (variant_ == Variant::published)  // Eq. (1) as printed
    return 2.0 * shrink * distance / (options_.mask_size * std::tan(camera.hfov / 2));
  const online::ImagePlane plane(camera, options_.mask_size, options_.critical_turn, options_.shrink_pixels + 1);
  return distance * std::sin(std::min(kPi / 2, shrink * plane.smallest_pixel_angle()));
}

void OnlineImageSpaceCulling::clear_stamps() {
  for (auto& node : tree_.nodes()) node.stamp = -std::numeric_limits<double>::infinity();
  std::fill(occluder_.begin(), occluder_.end(), 0);
}

void OnlineImageSpaceCulling::mark(const Camera& camera, OnlineFrame& frame) {
  const ViewVolume volume(widened(camera, options_.critical_turn));
  const online::ImagePlane plane(camera, options_.mask_size, options_.critical_turn, options_.shrink_pixels + 1);
  auto start = Clock::now();
  online::SelectionParameters selection;
  selection.occluders = options_.occluders;
  selection.min_distance = options_.min_distance;
  selection.node_polygons = options_.leaf_size;
  selection.priority = options_.coverage_priority ? online::OccluderPriority::coverage : online::OccluderPriority::distance;
  selection.coverage_grid = options_.coverage_grid;
  const online::OccluderSelection chosen = online::select_occluders(tree_, polygons_, plane, volume, selection);
  frame.select_ms = ms_since(start);
  frame.occluder_polygons = chosen.polygons.size();
  start = Clock::now();
  online::DepthImage depth(plane);
  for (std::uint32_t p : chosen.polygons) depth.draw(polygons_.polygon(p), polygons_.vertex_count(p)), occluder_[p] = 1;
  if (options_.ground_occluder) depth.draw_ground(camera.far);
  frame.draw_ms = ms_since(start);
  anchor_ = camera;
  anchored_ = true;
  if (chosen.polygons.empty()) {  // nothing to hide behind: no stamps, critical again next frame
    anchor_delta_ = 0.0;
    anchor_stamp_ = time_;
    frame.stamp = time_;
    return;
  }
  start = Clock::now();
  online::OcclusionMask mask(plane, depth, options_.shrink_pixels);
  frame.shrink_ms = ms_since(start);
  start = Clock::now();
  mask.build_hierarchy(options_.mask_block, options_.mask_levels);
  frame.hierarchy_ms = ms_since(start);
  frame.mask_pixels = mask.covered_pixels();
  frame.nearest_occluder = chosen.nearest;
  frame.delta = delta_for(camera, chosen.nearest);
  frame.stamp = time_ + frame.delta / options_.max_speed;
  anchor_delta_ = frame.delta;
  anchor_stamp_ = frame.stamp;
  start = Clock::now();
  // Section 5.5: top-down; a node whose box is behind the masks takes the stamp and its subtree
  // is done; otherwise its children are tried, down to the leaves (which hold at most ρ).
  std::vector<std::int32_t> stack{0};
  auto& nodes = tree_.nodes();
  while (!stack.empty()) {
    auto& node = nodes[std::size_t(stack.back())];
    stack.pop_back();
    if (node.count == 0 || node.stamp > frame.stamp || !volume.may_intersect(node.box)) continue;
    if (mask.occluded(node.box)) {
      node.stamp = frame.stamp;
      ++frame.nodes_marked;
      continue;
    }
    if (!node.leaf()) stack.push_back(node.child[1]), stack.push_back(node.child[0]);
  }
  frame.mark_ms = ms_since(start);
}

CullResult OnlineImageSpaceCulling::cull(const Camera& camera) {
  const auto start = Clock::now();
  CullResult result;
  OnlineFrame frame;
  if (!told_time_) {  // a query outside a path: start afresh
    clear_stamps();
    anchored_ = false;
    time_ = 0.0;
  }
  told_time_ = false;
  frame.time = time_;
  const ViewVolume volume(camera);
  if (!anchored_) frame.critical = CriticalReason::first;
  else if (occluder_deleted_) frame.critical = CriticalReason::occluder_deleted;  // (iii)
  else if (variant_ == Variant::guarded && length(camera.position - anchor_.position) > anchor_delta_) frame.critical = CriticalReason::left_ball;
  else if (time_ >= anchor_stamp_) frame.critical = CriticalReason::expired;
  else if (turn_between(camera, anchor_) > options_.critical_turn) frame.critical = CriticalReason::turned;
  if (occluder_deleted_) {  // stamps made with it may hide what it no longer hides
    clear_stamps();
    occluder_deleted_ = false;
  }
  if (frame.critical != CriticalReason::none) {
    // The guarded variant keeps only the newest marking: an older one's ball may no longer hold the eye.
    if (variant_ == Variant::guarded) clear_stamps();
    mark(camera, frame);
    result.stats.guard_fires = 1;
    result.stats.occluders_applied = frame.occluder_polygons;
  }
  const auto send_start = Clock::now();
  ++query_;
  std::vector<std::int32_t> stack{0};
  const auto& nodes = tree_.nodes();
  while (!nodes.empty() && !stack.empty()) {
    const auto& node = nodes[std::size_t(stack.back())];
    stack.pop_back();
    ++result.stats.cells_tested;
    if (node.count == 0) continue;
    if (node.stamp >= time_) {  // "sent when its stamp is less than the current time" (II.2)
      result.stats.items_skipped += node.count;
      continue;
    }
    if (!volume.may_intersect(node.box)) continue;
    if (!node.leaf()) {
      stack.push_back(node.child[1]), stack.push_back(node.child[0]);
      continue;
    }
    for (std::uint32_t p : node.polygons) {
      ++result.stats.buildings_tested;
      if (!volume.may_intersect(polygons_.box[p])) continue;
      ++frame.polygons_sent;
      const std::uint32_t object = polygons_.object[p];
      if (object_frame_[object] != query_) object_frame_[object] = query_, result.pvs.push_back(polygons_.ids[object]);
    }
  }
  std::sort(result.pvs.begin(), result.pvs.end());
  frame.send_ms = ms_since(send_start);
  result.stats.cull_ms = ms_since(start);
  if (measure_frustum_)
    for (std::size_t p = 0; p < polygons_.size(); ++p)
      if (tree_.alive(std::uint32_t(p)) && volume.may_intersect(polygons_.box[p])) ++frame.polygons_in_frustum;
  last_ = frame;
  return result;
}

}  // namespace cullcheck
