// Exact plan-view visibility (design: "Oracle", CGAL angular geometry).
//
// From the eye's plan position, the visibility polygon among all footprints is computed with
// exact predicates and exact constructions (CGAL Epeck: the arrangement of every footprint edge
// plus a bounding box, CGAL::Triangular_expansion_visibility_2, regularized). A building is
// VISIBLE when the directions from the eye that reach it first form a set of positive angle
// inside the horizontal view wedge [yaw - hfov/2, yaw + hfov/2] (the whole circle for an
// omnidirectional camera): some visible edge of the visibility polygon lies on its footprint
// boundary, is not seen edge-on (eye, ends not collinear), and keeps a piece of positive length
// after exact clipping against the wedge's two half-planes. Walls seen exactly edge-on and
// single grazing directions do not count (regularized visibility).
//
// The 2D model ignores near and far (it assumes far lies beyond the scene) and height. It is
// the exact 3D visible set only when `exact_2d_applies` holds; see there for why the design's
// "every building taller than the eye and a level camera" is not enough on its own.
//
// CGAL is confined to exact_2d.cpp; this header only sees doubles.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck::oracle {

struct VisibleExtent2d {
  double angular_extent = 0.0;    // radians: total angle of directions reaching the building first
  double largest_interval = 0.0;  // radians: the widest contiguous such interval
};

struct Exact2dResult {
  std::vector<ObjectId> visible;                  // sorted ids
  std::map<ObjectId, VisibleExtent2d> extents;    // one entry per visible building
  std::size_t visibility_polygon_edges = 0;
  double elapsed_seconds = 0.0;
};

// Whether the plan-view visible set equals the true 3D visible set for this camera, and if not,
// why (one line naming the first object or field that prevents it).
struct Exact2dApplicability {
  bool applies = false;
  std::string reason;
};
// The conditions (each is needed by the argument in exact_2d.cpp):
//  0. the scene is 2.5D (no mesh objects) and the camera is not orthographic;
//  1. the camera is level (pitch = roll = 0) or omnidirectional;
//  2. every building is taller than the eye, and the eye is strictly outside every footprint;
//  3. far lies beyond the scene (every building's box is within the far bound) and, for a
//     perspective camera, near is nearer than any building within the wedge;
//  4. nothing can be seen over a building: every building lower than the tallest satisfies
//     height >= eye height + (farthest plan distance to it) * tan(vfov / 2). A rising ray
//     that passes over a lower building can hit a taller one behind it, which the plan view
//     calls hidden. Omnidirectional cameras look straight up, so they need equal heights.
Exact2dApplicability check_exact_2d(const Scene& scene, const Camera& camera);
bool exact_2d_applies(const Scene& scene, const Camera& camera);

// Built once per scene (arrangement and constrained triangulation); queried per camera.
class ExactVisibility2d {
 public:
  explicit ExactVisibility2d(const Scene& scene);  // the Scene must outlive this object
  ~ExactVisibility2d();
  ExactVisibility2d(const ExactVisibility2d&) = delete;
  ExactVisibility2d& operator=(const ExactVisibility2d&) = delete;

  // Throws InputError if the camera is not level (and not omnidirectional), a building is not
  // taller than the eye, or the eye is inside or on a building's footprint.
  Exact2dResult visible(const Camera& camera) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-shot convenience: builds the structure and queries it once.
Exact2dResult exact_visible_2d(const Scene& scene, const Camera& camera);

}  // namespace cullcheck::oracle
