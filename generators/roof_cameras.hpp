// Cameras a little above a building's roof, in front of one of its longest sides and facing it.
// The roof then spans a wide angle below the eye, where its far wall is nearer than its end
// corners: the case that separates the thesis's shadow-elevation rule (ch. 3.1.2) from a
// conservative one. Used by the claims search and the shadow-rule property.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "generators/open_space.hpp"

namespace cullcheck::generators {

// `side` (+1 or -1) picks which long side; the eye stands `gap` metres off it and `above`
// metres over the roof, lifted 1 m over any roof it would stand in; 90 x 60 degree view.
inline Camera roof_facing_camera(const OpenSpace& open, const Building& b, double side, double gap, double above) {
  const Box2 box = b.bounds.plan();
  const Vec2 centre = box.center();
  const double wx = box.hi.x - box.lo.x, wy = box.hi.y - box.lo.y;
  const Vec2 away = wx > wy ? Vec2{0.0, side} : Vec2{side, 0.0};
  const double distance = std::min(wx, wy) / 2 + gap;
  Camera c;
  c.position = {centre.x + away.x * distance, centre.y + away.y * distance, b.height + above};
  if (open.inside_building(c.position)) c.position.z = open.roof_height_near(plan(c.position), 0.0) + 1.0;
  c.yaw = azimuth_of(centre - plan(c.position));
  c.pitch = -std::atan2(c.position.z, distance + 10.0);
  c.hfov = kPi / 2;
  c.vfov = kPi / 3;
  return c;
}

}  // namespace cullcheck::generators
