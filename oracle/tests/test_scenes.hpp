// Small hand-built scenes and seeded random cities for the oracle's tests. The generators
// library is developed separately; these tests build their own scenes so that they depend on
// core/ and oracle/ only.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/scene_io.hpp"
#include "oracle/splitmix64.hpp"

namespace cullcheck::oracle::testing {

inline constexpr double kDeg = kPi / 180.0;

using cullcheck::box_building;

inline Building polygon_building(ObjectId id, std::vector<Vec2> ring, double height) {
  Building b;
  b.id = id;
  b.height = height;
  b.footprint = std::move(ring);
  validate_and_finish(b);
  return b;
}

inline Scene scene_of(std::vector<Building> buildings) {
  Scene s;
  s.provenance.generator = "oracle_test";
  s.buildings = std::move(buildings);
  return s;
}

inline Scene scene_of(std::vector<Building> buildings, std::vector<MeshObject> meshes) {
  Scene s = scene_of(std::move(buildings));
  s.meshes = std::move(meshes);
  return s;
}

inline MeshObject mesh_object(ObjectId id, std::vector<Vec3> vertices, std::vector<std::array<std::uint32_t, 3>> triangles) {
  MeshObject m;
  m.id = id;
  m.vertices = std::move(vertices);
  m.triangles = std::move(triangles);
  validate_and_finish(m);
  return m;
}

// A rectangular opening in a wall, in the wall's own coordinates: s along it, t up.
struct Opening {
  double s0, s1, t0, t1;
};

// A vertical wall as an open mesh (one sheet, seen from both sides): the points corner + along * s
// + (0, 0, t) for s in [0, width], t in [0, height], `along` a horizontal unit vector. With an
// opening, the wall is the frame around it: 8 triangles joining the outer and the inner corners
// (no T-junctions, so Embree's watertight test leaves no crack); without, 2 triangles.
inline MeshObject wall_mesh(ObjectId id, Vec3 corner, Vec3 along, double width, double height,
                            const Opening* opening = nullptr) {
  auto at = [&](double s, double t) { return corner + along * s + Vec3{0, 0, t}; };
  if (!opening) return mesh_object(id, {at(0, 0), at(width, 0), at(width, height), at(0, height)}, {{0, 1, 2}, {0, 2, 3}});
  const Opening& o = *opening;
  std::vector<Vec3> v = {at(0, 0),       at(width, 0),   at(width, height), at(0, height),
                         at(o.s0, o.t0), at(o.s1, o.t0), at(o.s1, o.t1),    at(o.s0, o.t1)};
  std::vector<std::array<std::uint32_t, 3>> t;
  for (std::uint32_t k = 0; k < 4; ++k) {
    const std::uint32_t k1 = (k + 1) % 4;
    t.push_back({k, k1, 4 + k1});
    t.push_back({k, 4 + k1, 4 + k});
  }
  return mesh_object(id, std::move(v), std::move(t));
}

inline Camera level_camera(Vec3 eye, double yaw, double hfov = 60 * kDeg, double vfov = 60 * kDeg) {
  Camera c;
  c.position = eye;
  c.yaw = yaw;
  c.hfov = hfov;
  c.vfov = vfov;
  return c;
}

// Eye at street level, looking east (+x), 60 x 60 degrees.
inline const Camera kStreetEast = level_camera({0, 0, 1.7}, 0.0);

// An orthographic camera: a width x height metre box around the view axis through `eye`.
inline Camera ortho_camera(Vec3 eye, double yaw, double pitch, double width, double height) {
  Camera c;
  c.position = eye;
  c.yaw = yaw;
  c.pitch = pitch;
  c.projection = Projection::orthographic;
  c.ortho_width = width;
  c.ortho_height = height;
  c.near = 0.0;
  c.far = 1000.0;
  return c;
}

inline Camera omni_camera(Vec3 eye) {
  Camera c;
  c.position = eye;
  c.hfov = kTwoPi;
  return c;
}

// A random city of non-overlapping rectangles (at least 1 m apart), all taller than the eye,
// and a level camera in free space whose view cannot pass over any building, so that the
// exact plan-view oracle applies. Three kinds, by seed % 3: perspective with heights rising
// with distance (seeing over is impossible because of the vertical fov), perspective with
// equal heights, and omnidirectional with equal heights.
struct RandomCity {
  Scene scene;
  Camera camera;
  std::string kind;
};

inline RandomCity random_city(std::uint64_t seed) {
  SplitMix64 rng(seed * 0x2545F4914F6CDD1DULL + 1);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.unit(); };
  RandomCity city;
  const int n = 30 + int(rng.next() % 71);
  const double half = 14.0 * std::sqrt(double(n));
  std::vector<Box2> boxes;
  for (int attempt = 0; attempt < 60 * n && int(boxes.size()) < n; ++attempt) {
    const double w = uniform(4, 25), d = uniform(4, 25);
    const Vec2 c{uniform(-half, half), uniform(-half, half)};
    const Box2 box{{c.x - w / 2, c.y - d / 2}, {c.x + w / 2, c.y + d / 2}};
    bool free = true;
    for (const Box2& o : boxes)
      free = free && (box.lo.x > o.hi.x + 1 || o.lo.x > box.hi.x + 1 || box.lo.y > o.hi.y + 1 || o.lo.y > box.hi.y + 1);
    if (free) boxes.push_back(box);
  }
  Vec2 eye;
  for (;;) {
    eye = {uniform(-half, half), uniform(-half, half)};
    bool clear = true;
    for (const Box2& b : boxes) clear = clear && min_distance(eye, b) >= 2.0;
    if (clear) break;
  }
  const double eye_z = uniform(1.5, 2.0);
  const int kind = int(seed % 3);
  // The level camera's draws one at a time: a call's arguments are evaluated in an unspecified
  // order (gcc right to left, clang left to right), and the city must not depend on the compiler.
  // gcc's order is kept: vfov, hfov, yaw.
  Camera camera = omni_camera({eye.x, eye.y, eye_z});
  if (kind != 2) {
    const double vfov = uniform(20, kind == 0 ? 60 : 90) * kDeg;
    const double hfov = uniform(40, 120) * kDeg;
    const double yaw = uniform(0, kTwoPi);
    camera = level_camera({eye.x, eye.y, eye_z}, yaw, hfov, vfov);
  }
  const double shared_height = uniform(15, 40);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box2& b = boxes[i];
    const double h = kind == 0 ? eye_z + max_distance(eye, b) * std::tan(camera.vfov / 2) + uniform(1, 40) : shared_height;
    city.scene.buildings.push_back(box_building(ObjectId(100 + i), b.lo.x, b.lo.y, b.hi.x, b.hi.y, h));
  }
  city.scene.provenance = {"oracle_test.random_city", seed, "{}"};
  city.camera = camera;
  city.kind = kind == 0 ? "perspective, heights rising with distance" : kind == 1 ? "perspective, equal heights" : "omnidirectional, equal heights";
  return city;
}

// A jittered 25 x 20 grid of 500 boxes, 30 m tall, 30 m apart: the exact 2D oracle's size test
// (Exact2d.FiveHundredBuildings...) and its benchmark (BM_Exact2dFiveHundredBuildings) use it.
inline Scene jittered_grid_500() {
  Scene scene;
  SplitMix64 rng(99);
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 20; ++j) {
      const double x = i * 30 + 8 * rng.unit(), y = j * 30 + 8 * rng.unit();
      // Drawn one per statement, y first: the order gcc gave when both draws were arguments.
      const double hi_y = y + 10 + 8 * rng.unit();
      const double hi_x = x + 10 + 8 * rng.unit();
      scene.buildings.push_back(box_building(ObjectId(i * 20 + j), x, y, hi_x, hi_y, 30));
    }
  return scene;
}
inline constexpr Vec3 kJitteredGridEye{372, 296, 1.7};

}  // namespace cullcheck::oracle::testing
