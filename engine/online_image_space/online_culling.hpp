// On-line image-space occlusion culling (Wang, Agarwal & Har-Peled 2001): a kd-tree over the
// scene's polygons (section 4); at critical frames, occluders chosen by coverage (5.3), their
// depth image eroded by Δ + 1 pixels into hierarchical max-depth masks (5.2, 5.4), and every
// kd-tree node behind the masks stamped with t + δ/V, where δ comes from Eq. (1) for the nearest
// occluder (5.1, 5.5); at every frame, the polygons in the view frustum whose nodes carry no
// live stamp are sent (II.2). An object is in the PVS when one of its polygons is sent.
//
// Claims: NOT conservative, by design: the paper shrinks the union of the occluders'
// projections, which can open a leak (Fig. 5); errors are judged in misdrawn pixels against the
// full scene (oracle/pixel_oracle.hpp), within the budget the options give.
//
// Variants:
//  - online_is: as published. δ = 2 Δ D / (s tan(θ/2)) (Eq. 1 as printed; θ the horizontal
//    field of view), critical frames exactly when (i) the clock reaches the stamp, (ii) the view
//    direction turns more than critical_turn from the critical frame's, (iii) an occluder is
//    deleted; stamps of earlier critical frames stay in force until they expire.
//  - online_is_guarded: δ = D sin(Δ ω), with ω the smallest angle a mask pixel subtends (a
//    point at distance >= D moves by at most asin(δ / D) as the eye moves by δ, and Δ pixels
//    subtend at least Δ ω anywhere on the image; Eq. (1) as printed is larger than that whenever
//    the field of view is under 90 degrees), and a critical frame as soon as the eye leaves
//    B_δ of the critical frame's eye, whatever the clock says, so a walker faster than V cannot
//    outrun the stamps; only the latest critical frame's stamps are in force.
//
// Dynamic scenes (section 6, "lazy"): insert_object adds an object's polygons to the kd-tree
// (the nodes on their way lose their stamps, so nothing new is hidden untested); erase_object
// removes them, and when one of them served as an occluder since the stamps were last cleared,
// every stamp is dropped and the next query is a critical frame (iii).
//
// Time comes from set_frame (seconds along the path). A query without set_frame starts a new
// path: every stamp is dropped and the frame is critical.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/method.hpp"
#include "engine/online_image_space/occluder_selection.hpp"
#include "engine/online_image_space/polygon_kd_tree.hpp"
#include "engine/online_image_space/scene_polygons.hpp"

namespace cullcheck {

enum class CriticalReason : std::uint8_t { none, first, expired, turned, occluder_deleted, left_ball };
std::string to_string(CriticalReason reason);

// What one query did, for the report's Table 1 and Fig. 10 breakdown.
struct OnlineFrame {
  CriticalReason critical = CriticalReason::none;
  double time = 0.0;             // seconds along the path
  // Fig. 10's five sub-steps of a marking operation (milliseconds; 0 on other frames).
  double select_ms = 0.0, draw_ms = 0.0, shrink_ms = 0.0, hierarchy_ms = 0.0, mark_ms = 0.0;
  double send_ms = 0.0;          // II.2: frustum and stamps over the tree
  std::uint64_t occluder_polygons = 0;
  std::uint64_t mask_pixels = 0;       // covered pixels of M_0
  std::uint64_t nodes_marked = 0;
  double nearest_occluder = 0.0;       // metres
  double delta = 0.0;                  // δ, metres
  double stamp = 0.0;                  // t + δ / V given at this critical frame
  std::uint64_t polygons_sent = 0;
  std::uint64_t polygons_in_frustum = 0;  // only with measure_frustum (CR_v's denominator)
};

class OnlineImageSpaceCulling final : public CullingMethod {
 public:
  enum class Variant : std::uint8_t { published, guarded };
  OnlineImageSpaceCulling(const Scene& scene, Variant variant, const OnlineCullingOptions& options = {});

  std::string name() const override { return variant_ == Variant::published ? "online_is" : "online_is_guarded"; }
  bool claims_conservative() const override { return false; }
  bool incremental() const override { return true; }
  std::optional<std::uint64_t> pixel_error_budget() const override { return options_.pixel_budget; }
  std::string unsupported_camera(const Camera& camera) const override;
  void set_frame(std::size_t frame, double time_seconds) override;
  CullResult cull(const Camera& camera) override;

  // Section 6. insert_object throws std::invalid_argument when the id is already in the scene;
  // erase_object when it is not.
  void insert_object(const Building& building);
  void insert_object(const MeshObject& mesh);
  void erase_object(ObjectId id);
  bool update_scene(const Scene& present, const std::vector<ObjectId>& appeared, const std::vector<ObjectId>& vanished) override;

  // δ for an occluder at `distance` under this variant's reading of Eq. (1).
  double delta_for(const Camera& camera, double distance) const;
  const OnlineFrame& last_frame() const { return last_; }
  // Also count the polygons in the view frustum each query (outside the timed part).
  void measure_frustum(bool on) { measure_frustum_ = on; }
  std::size_t polygon_count() const { return polygons_.size(); }
  const online::PolygonKdTree& tree() const { return tree_; }
  const online::ScenePolygons& polygons() const { return polygons_; }  // every polygon ever inserted (tree().alive says which are in)

 private:
  void mark(const Camera& camera, OnlineFrame& frame);
  void clear_stamps();
  void add_object(ObjectId id, const std::function<void(std::uint32_t)>& append);

  Variant variant_;
  OnlineCullingOptions options_;
  online::ScenePolygons polygons_;
  online::PolygonKdTree tree_;
  double time_ = 0.0;
  bool told_time_ = false;
  bool anchored_ = false;
  Camera anchor_;         // the last critical frame's camera
  double anchor_delta_ = 0.0;
  double anchor_stamp_ = 0.0;
  std::vector<std::uint32_t> object_frame_;  // last query each object was sent in (dedup)
  std::unordered_map<ObjectId, std::uint32_t> object_index_;  // id -> index into polygons_.ids
  std::vector<char> alive_object_;
  std::vector<std::uint32_t> object_first_;  // object o's polygons are [object_first_[o], object_first_[o + 1])
  std::vector<char> occluder_;   // per polygon: drawn into a mask since the stamps were last cleared
  bool occluder_deleted_ = false;
  std::uint32_t query_ = 0;
  bool measure_frustum_ = false;
  OnlineFrame last_;
};

}  // namespace cullcheck
