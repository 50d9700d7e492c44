// The openings generator (generators/city.hpp: OpeningsParams): determinism, every feature kind
// with the defaults, facade walls that are closed meshes with holes (areas computed by hand),
// objects that a street-level eye sees only through an opening (by independent ray casting, not
// the generator's geometry), ids, the 1 mm grid, and shrinkable parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/openings_geometry.hpp"

namespace cullcheck::generators {
namespace {

using nlohmann::json;

double triangle_area(const MeshObject& m, const std::array<std::uint32_t, 3>& t) {
  return length(cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]])) / 2;
}

// V - E + F of a closed triangle mesh: 2 - 2g for a surface of genus g (a slab with g holes).
long euler_characteristic(const MeshObject& m) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  std::set<std::uint32_t> used;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
      used.insert(t[k]);
    }
  return static_cast<long>(used.size()) - static_cast<long>(edges.size()) + static_cast<long>(m.triangles.size());
}

TEST(OpeningsCity, IsDeterministic) {
  const std::string a = scene_to_json_text(make_city("openings", 5, nullptr));
  EXPECT_EQ(a, scene_to_json_text(make_city("openings", 5, nullptr)));
  EXPECT_NE(a, scene_to_json_text(make_city("openings", 6, nullptr)));
  // Provenance rebuilds it.
  const Scene s = make_city("openings", 5, nullptr);
  EXPECT_EQ(scene_to_json_text(make_city(s.provenance.generator, s.provenance.seed, json::parse(s.provenance.parameters_json))), a);
}

TEST(OpeningsCity, EveryFeatureKindAppearsWithTheDefaults) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const Scene s = make_city("openings", seed, nullptr);
    std::map<std::string, int> kinds;
    for (const MeshObject& m : s.meshes) ++kinds[m.name];
    EXPECT_GT(kinds["facade_wall"], 0) << "seed " << seed;
    EXPECT_GT(kinds["arcade"], 0) << "seed " << seed;
    EXPECT_EQ(kinds["bridge"], 2) << "seed " << seed;
    EXPECT_EQ(kinds.size(), 3u) << "seed " << seed;
    std::size_t low = 0, tall = 0;
    for (const Building& b : s.buildings) (b.height <= 2.5 ? low : tall) += 1;
    EXPECT_GE(tall, 9u * 8u) << "seed " << seed;  // cores and corners: 9 blocks x (4 + 4)
    EXPECT_EQ(low, static_cast<std::size_t>(kinds["facade_wall"] + kinds["arcade"])) << "one low building behind or under each";
    EXPECT_FALSE(s.prisms_only());
    // Ids 0..n-1 across buildings and meshes; every coordinate on the 1 mm grid.
    const std::vector<ObjectId> ids = s.ids();
    for (std::size_t i = 0; i < ids.size(); ++i) ASSERT_EQ(ids[i], i) << "seed " << seed;
    auto on_grid = [](double v) { return std::abs(v * 1000 - std::round(v * 1000)) < 1e-6; };
    for (const MeshObject& m : s.meshes)
      for (const Vec3& v : m.vertices) ASSERT_TRUE(on_grid(v.x) && on_grid(v.y) && on_grid(v.z)) << m.name;
    for (const Building& b : s.buildings) {
      ASSERT_TRUE(on_grid(b.height));
      for (Vec2 p : b.footprint) ASSERT_TRUE(on_grid(p.x) && on_grid(p.y));
    }
  }
}

// No two objects meet: buildings are plan-disjoint, and no mesh vertex lies in a building.
TEST(OpeningsCity, ObjectsDoNotMeet) {
  const Scene s = make_city("openings", 3, {{"blocks_x", 4}, {"blocks_y", 3}, {"bridge_count", 5}});
  for (std::size_t i = 0; i < s.buildings.size(); ++i)
    for (std::size_t j = i + 1; j < s.buildings.size(); ++j) {
      const Box3 &a = s.buildings[i].bounds, &b = s.buildings[j].bounds;
      EXPECT_TRUE(a.hi.x < b.lo.x || b.hi.x < a.lo.x || a.hi.y < b.lo.y || b.hi.y < a.lo.y)
          << s.buildings[i].id << " meets " << s.buildings[j].id;
    }
  for (const MeshObject& m : s.meshes)
    for (const Building& b : s.buildings)
      for (const Vec3& v : m.vertices)
        ASSERT_FALSE(v.x >= b.bounds.lo.x && v.x <= b.bounds.hi.x && v.y >= b.bounds.lo.y && v.y <= b.bounds.hi.y &&
                     v.z <= b.height)
            << m.name << " " << m.id << " reaches into building " << b.id;
}

// A 10 x 6 m wall, 0.3 m thick, with a door 1.2 x 2.2 m and a window 1.5 x 1.2 m. By hand:
// face 60 - 2.64 - 1.8 = 55.56 m2 on each side; reveals and sides 0.3 m times the region's
// boundary, 2 (10 + 6) + 2 * 2.2 (the door's jambs; its lintel replaces the foot it cuts) +
// 2 (1.5 + 1.2) (the window's four sides) = 41.8 m: 12.54 m2; in all 123.66 m2. One hole: genus 1.
TEST(OpeningsCity, FacadeWallAreaIsTheSlabLessItsOpenings) {
  const PlanFrame frame{0, 0, 1, 0};
  MeshObject m = facade_wall_mesh(frame, 0, 10000, 300, 6000, {{1000, 0, 2200, 2200}, {4000, 1000, 5500, 2200}});
  m.id = 1;
  validate_and_finish(m);
  EXPECT_TRUE(m.closed);
  double total = 0, street_side = 0;
  for (const auto& t : m.triangles) {
    const double a = triangle_area(m, t);
    total += a;
    const Vec3 n = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    if (n.y < 0 && std::abs(n.x) + std::abs(n.z) == 0 && m.vertices[t[0]].y == 0.0) street_side += a;
  }
  EXPECT_NEAR(street_side, 55.56, 1e-9);
  EXPECT_NEAR(total, 123.66, 1e-9);
  EXPECT_EQ(euler_characteristic(m), 0);  // genus 1: the window; the door is a notch
  EXPECT_EQ(m.bounds.lo.y, 0.0);
  EXPECT_EQ(m.bounds.hi.y, 0.3);
}

TEST(OpeningsCity, FacadeWallsAreClosedMeshesWithHoles) {
  const Scene s = make_city("openings", 1, nullptr);
  int walls = 0, with_windows = 0;
  for (const MeshObject& m : s.meshes) {
    EXPECT_TRUE(m.closed) << m.name << " " << m.id;
    if (m.name != "facade_wall") continue;
    ++walls;
    const long chi = euler_characteristic(m);
    EXPECT_EQ(chi % 2, 0);
    EXPECT_LE(chi, 2);
    with_windows += chi < 2;
  }
  EXPECT_EQ(walls, 7);
  EXPECT_GT(with_windows, 0);
}

// Segment-triangle intersection (Moeller-Trumbore), strictly inside the segment.
bool segment_hits(const MeshObject& m, Vec3 a, Vec3 b) {
  const Vec3 d = b - a;
  for (const auto& t : m.triangles) {
    const Vec3 p0 = m.vertices[t[0]], e1 = m.vertices[t[1]] - p0, e2 = m.vertices[t[2]] - p0;
    const Vec3 p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::abs(det) < 1e-15) continue;
    const Vec3 s = a - p0;
    const double u = dot(s, p) / det;
    if (u < 0 || u > 1) continue;
    const Vec3 q = cross(s, e1);
    const double v = dot(d, q) / det;
    if (v < 0 || u + v > 1) continue;
    const double tt = dot(e2, q) / det;
    if (tt > 1e-9 && tt < 1 - 1e-9) return true;
  }
  return false;
}

bool segment_meets_box(Vec3 a, Vec3 b, const Box3& box) {
  double t0 = 0, t1 = 1;
  const double o[3] = {a.x, a.y, a.z}, d[3] = {b.x - a.x, b.y - a.y, b.z - a.z};
  const double lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double u = (lo[k] - o[k]) / d[k], v = (hi[k] - o[k]) / d[k];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

// From street-level eyes in front of each facade wall, the low building behind it (generated
// right after it) is seen along some segments, and every such segment passes through the wall's
// box: a solid slab would hide it. The segments are checked against the wall's own triangles.
TEST(OpeningsCity, TheBuildingBehindAFacadeIsSeenOnlyThroughItsOpenings) {
  const Scene s = make_city("openings", 1, nullptr);
  int checked = 0;
  for (const MeshObject& wall : s.meshes) {
    if (wall.name != "facade_wall") continue;
    const Building* target = s.find(wall.id + 1);
    ASSERT_NE(target, nullptr);
    ASSERT_LT(target->height, wall.bounds.hi.z);
    const Box3 &w = wall.bounds, &t = target->bounds;
    const bool along_x = w.hi.x - w.lo.x > w.hi.y - w.lo.y;
    // The street side: away from the target, 4 m out.
    auto eye_at = [&](double s_along) {
      if (along_x) return Vec3{s_along, t.lo.y > w.hi.y ? w.lo.y - 4 : w.hi.y + 4, 1.7};
      return Vec3{t.lo.x > w.hi.x ? w.lo.x - 4 : w.hi.x + 4, s_along, 1.7};
    };
    const double lo = along_x ? w.lo.x : w.lo.y, hi = along_x ? w.hi.x : w.hi.y;
    int seen = 0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 1; j < 20; ++j)
        for (int k = 1; k < 4; ++k) {
          const Vec3 eye = eye_at(lo + (hi - lo) * i / 20);
          // Points on the target's face towards the wall.
          const double sp = (along_x ? t.lo.x + (t.hi.x - t.lo.x) * j / 20 : t.lo.y + (t.hi.y - t.lo.y) * j / 20);
          const double near_face = along_x ? (t.lo.y > w.hi.y ? t.lo.y : t.hi.y) : (t.lo.x > w.hi.x ? t.lo.x : t.hi.x);
          const Vec3 point = along_x ? Vec3{sp, near_face, t.hi.z * k / 4} : Vec3{near_face, sp, t.hi.z * k / 4};
          const bool through_slab = segment_meets_box(eye, point, w);
          ASSERT_TRUE(through_slab) << "a street-level sight line passes around or over the wall " << wall.id;
          if (!segment_hits(wall, eye, point)) ++seen;
        }
    EXPECT_GT(seen, 0) << "nothing of building " << target->id << " shows through wall " << wall.id;
    ++checked;
  }
  EXPECT_EQ(checked, 7);
}

TEST(OpeningsCity, ShrinksToOneBlockAndValidatesItsParameters) {
  const Scene one = make_city("openings", 2, {{"blocks_x", 1}, {"blocks_y", 1}});
  EXPECT_GE(one.buildings.size(), 8u);  // core lots and corners
  for (const MeshObject& m : one.meshes) EXPECT_NE(m.name, "bridge");  // no street between two blocks
  const Scene walls_only =
      make_city("openings", 2, {{"blocks_x", 1}, {"blocks_y", 1}, {"arcade_weight", 0.0}, {"plain_weight", 0.0}});
  EXPECT_EQ(walls_only.meshes.size(), 4u);
  auto field_of = [](const json& params) {
    try {
      (void)make_city("openings", 1, params);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of({{"frontage_depth", 1.0}}), "frontage_depth");
  EXPECT_EQ(field_of({{"block_size", 20.0}}), "block_size");
  EXPECT_EQ(field_of({{"target_min_height", 7.0}}), "target_min_height");
  EXPECT_EQ(field_of({{"wall_max_thickness", 0.1}}), "wall_max_thickness");
  EXPECT_EQ(field_of({{"facade_weight", 0.0}, {"arcade_weight", 0.0}, {"plain_weight", 0.0}}), "plain_weight");
  EXPECT_EQ(field_of({{"no_such_thing", 1}}), "no_such_thing");
  EXPECT_EQ(field_of({{"bridge_count", 0}}), "(accepted)");
}

TEST(OpeningsCity, StreetWalksFollowItsStreets) {
  const Scene s = make_city("openings", 1, nullptr);
  StreetWalkParams walk;
  walk.frames = 200;
  const CameraPath path = street_walk(s, walk, 3);
  ASSERT_EQ(path.frames.size(), 200u);
  for (const Camera& c : path.frames)
    for (const Building& b : s.buildings) ASSERT_FALSE(b.bounds.plan().contains(plan(c.position))) << "inside " << b.id;
}

}  // namespace
}  // namespace cullcheck::generators
