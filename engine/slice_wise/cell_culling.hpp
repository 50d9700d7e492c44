// From-region slice-wise culling of one view cell (Yılmaz & Güdükbay §4.2, Algorithms 1 and 2;
// Algorithm 3 is slice_rectangle.hpp).
//
// The cell is a square of side s at a fixed eye height (ground navigation, as the paper's walks);
// every eye in it lies within ε = s / √2 of the centre, and the occluders are shrunk by ε
// (slice_scene.hpp), so visibility computed from the centre against the shrunk occluders holds
// for every eye of the cell (Theorem 1). The queries are occlusion_buffer.hpp's exact-coverage
// tests, so "hidden" means hidden from the centre for every ray, not for sampled ones.
//
// Algorithm 1, coarse: a cube map at the centre (the paper's four 90-degree sections, plus up and
// down so that no direction is left out); the quadtree's blocks front to back, a block whose box
// is hidden in every face skipped whole; each object of a visible block tested by its box, and if
// visible, its shrunk occluder drawn (so later, farther blocks meet the occluders in front of
// them: occluders that are themselves hidden are never drawn, which changes nothing).
// Then each candidate on its own: a view zoomed on its box (the paper's zoomed query; when the box
// is too near or spans too wide an angle to zoom on, six cube faces at the zoomed resolution,
// hidden only where hidden in each), every
// other object's shrunk occluder in that view drawn front to back (again skipping hidden ones and
// those wholly behind the candidate), the box tested, and if visible, Algorithm 2: each vertical
// slice's hidden height (boxes of height Δ, 2Δ, ... from the bottom; found by bisection, since a
// taller box is hidden only if a lower one is) and each horizontal slice tested whole. A slice's
// box is the box of its own triangles cut to its slab (slice_scene.hpp), which holds every
// triangle of the slice and leaves out the empty parts of the object's box (beside a tower, above
// a podium).
//
// Deviation, stated: the paper's loop tests heights k Δ while k Δ <= the slice's height, so a slice
// whose height is not a multiple of Δ is never hidden whole; here the last height is the slice's
// own, so a slice hidden to its top is invisible.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/slice_wise/occlusion_buffer.hpp"
#include "engine/slice_wise/slice_rectangle.hpp"
#include "engine/slice_wise/slice_scene.hpp"

namespace cullcheck::slice_wise {

struct CellCullingOptions {
  double delta = 1.0;         // Δ, metres: the step of the vertical slices' hidden heights
  int cube_resolution = 256;  // pixels per cube face side (coarse culling)
  int zoom_resolution = 128;  // pixels per side of the zoomed view on one candidate
  double near = 0.05;         // metres
  bool slices = true;         // false: building-level culling (stop after the candidate's box test)
  // Whether a candidate's own shrunk occluder is drawn when its slices are tested. The paper tests
  // an object "against the shrunk versions of all other objects"; an object's own shrunk solid
  // hides its far side just as validly (Theorem 1 holds for any occluder that does not contain
  // the target point, and a surface point is never inside its own shrunk solid).
  bool self_occlusion = false;
  // With self_occlusion, the faces of a closed, outward-wound object turned away from every eye of
  // the cell are left out of its slices' queries when the cell lies outside the object's box: the
  // object itself hides them from every eye (exactly, not through its shrunk solid), and the
  // faces left are grouped by where they stand, so that the far slices' boxes do not reach round
  // to the walls facing the cell. Each group's hidden height is then found on its own, which
  // says per triangle whether it is hidden (every cell of it hidden by its own group, or by a
  // horizontal slice); Algorithm 3 picks the best form keeping every triangle not shown hidden,
  // which drops at least what the rectangle of hidden cells drops: a long triangle whose visible
  // part keeps it no longer keeps the far cells it reaches into. The turned-away faces are
  // dropped whatever surrounds them; a ray can meet one only where it grazes the edge it shares
  // with a facing face, which draws that point (oracle/witness_cover.hpp).
  bool turned_away_faces = true;
  // cullcheck's variant of Algorithm 3 (slice_rectangle.hpp best_form_keeping): a rectangle of
  // hidden slices on each vertical axis at once, in the same three bytes. The paper draws from the
  // maximally occluded axis only.
  bool both_vertical_axes = false;
};

struct ObjectVisibility {
  std::uint32_t object = 0;   // index into SliceWiseScene::objects()
  VisibilityIndices indices;  // what the cell stores (3 bytes, Fig. 5)
  SliceChoice choice;
  bool zoom_refused = false;  // too close or too wide to zoom on: tested in six cube faces instead
};

// The cost of one cell (what it decided is CellPvs::visible and each one's SliceChoice).
struct CellStatistics {
  std::size_t coarse_blocks_hidden = 0;  // quadtree blocks the cube map hid whole
  std::size_t coarse_candidates = 0;     // objects whose box the cube map did not hide
  std::size_t queries = 0;               // box tests of candidates, slices and heights in zoomed views
  std::size_t occluders_drawn = 0;       // occluder meshes drawn, cube and zoomed views together
  std::size_t triangles_drawn = 0;
  double coarse_ms = 0.0, fine_ms = 0.0;
};

struct CellPvs {
  std::vector<ObjectVisibility> visible;  // ascending object index
  CellStatistics stats;
};

// Throws std::invalid_argument on a bad option.
void validate(const CellCullingOptions& o);

// Reusable buffers: one per thread.
class CellCuller {
 public:
  CellCuller(const SliceWiseScene& scene, const CellCullingOptions& options);
  // The PVS of the cell whose centre (at eye height) is `centre`.
  CellPvs cull(Vec3 centre);

 private:
  bool cube_hidden(const Box3& box);
  // Hidden in every face of a cube map at the eye (every direction is in some face's image).
  bool hidden_in_cube(std::array<OcclusionBuffer, 6>& faces, const Box3& box) const;
  void draw_cube(const TriangleMesh& occluder, const Box3& box);
  void draw_zoomed(OcclusionBuffer& view, std::uint32_t candidate, double farthest, CellStatistics& stats);
  bool zoom_hidden(const Box3& box, CellStatistics& stats);

  const SliceWiseScene& scene_;
  CellCullingOptions options_;
  Vec3 eye_;
  std::array<OcclusionBuffer, 6> cube_;
  std::array<OcclusionBuffer, 6> zoom_;  // one zoomed view, or six cube faces when zooming is refused
  int zoom_views_ = 1;
};

}  // namespace cullcheck::slice_wise
