// Where a camera may stand: point-in-footprint and clearance queries over a scene's buildings.
//
// Camera generators must never put the eye inside a building (a viewpoint inside a prism makes
// every occlusion claim vacuous, and is a separate, deliberate extreme case in the tests).
// Footprints are closed sets here: a point on a wall counts as inside, so "open" is strict.
#pragma once

#include <vector>

#include "core/scene.hpp"
#include "generators/box_grid.hpp"

namespace cullcheck::generators {

// Closed point-in-polygon test (boundary counts as inside); the ring may be non-convex.
bool point_in_footprint(const std::vector<Vec2>& ring, Vec2 p);
// Plan-view distance from p to the closed footprint: 0 when p is inside or on the boundary.
double distance_to_footprint(const std::vector<Vec2>& ring, Vec2 p);

// Queries over one scene; keeps a reference, so the scene must outlive it.
class OpenSpace {
 public:
  explicit OpenSpace(const Scene& scene);

  // True if p lies in some building's closed prism (footprint, 0 <= z <= height).
  bool inside_building(Vec3 p) const;
  // True if no footprint lies within `clearance` of p in the plan view.
  bool is_open(Vec2 p, double clearance) const;
  // Highest roof among buildings whose footprint lies within `radius` of p (0 if none).
  double roof_height_near(Vec2 p, double radius) const;
  // A point in the open near p: p itself if open, else the first open point met walking in
  // +x steps of `step` (always found: beyond the scene's bounds everything is open).
  Vec2 nudge_to_open(Vec2 p, double clearance, double step = 0.25) const;

  const Scene& scene() const { return *scene_; }
  Box3 bounds() const { return bounds_; }

 private:
  const Scene* scene_;
  Box3 bounds_;
  BoxGrid grid_;
};

}  // namespace cullcheck::generators
