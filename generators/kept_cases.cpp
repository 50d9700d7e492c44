#include "generators/kept_cases.hpp"

#include <cmath>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "generators/params_json.hpp"

namespace cullcheck::generators {
namespace {

// The smallest refutation of thesis Eq. 4-16 with the disc crossing a building: a 30 m long,
// 0.3 m thin, 10 m high slab 2 m in front of the centre (its tangent vertices are its far ends,
// 15.1 m away, so Eq. 4-5 shrinks its shadow by only asin(3 / 15.1) = 11.5 degrees a side) and a
// 5 m building 17-21 m out behind it. ε = 3 m carries the disc through the slab: from (0, 3),
// between slab and building, the building is in plain view.
Scene slab_across_the_disc() {
  Scene s;
  s.buildings = {box_building(0, -15, 2, 15, 2.3, 10), box_building(1, -2, 17, 2, 21, 5)};
  return s;
}

// The refutation with the disc in open ground: a curved planter wall 1.3 m high (below a 1.7 m
// eye) on the circle of radius 1 m (±50 degrees, 21 vertices on the circle) and a 0.22 m kerb
// stone 2.2-2.4 m out behind it. ε = 0.5 m ends 0.14 m short of the planter. Eq. 13-14 as printed
// (h_C + h_X = 3.0 m where the geometry has h_C - h_X = 0.4 m) shrinks the planter's shadow to a
// slope of -0.596 from the centre; from the disc's edge the sight line over the planter's far edge
// falls at -0.8 and clears the stone (found by the from-region extremes, region_extremes_test).
Scene low_planter() {
  Building planter;
  planter.id = 0;
  planter.height = 1.3;
  const int n = 21;
  const double half = 50 * kPi / 180;
  for (int k = 0; k < n; ++k) {
    const double a = -half + 2 * half * k / (n - 1);
    planter.footprint.push_back({std::cos(a), std::sin(a)});
  }
  validate_and_finish(planter);
  Scene s;
  s.buildings = {planter, box_building(1, 2.2, -0.2, 2.4, 0.2, 0.22)};
  return s;
}

Camera level(Vec2 p, double yaw, double hfov) {
  Camera c;
  c.position = {p.x, p.y, 1.7};
  c.yaw = yaw;
  c.hfov = hfov;
  c.vfov = hfov >= kTwoPi ? kPi / 2 : hfov * 0.75;
  return c;
}

}  // namespace

const std::vector<std::string>& kept_case_names() {
  static const std::vector<std::string> names = {"low_planter", "slab_across_the_disc"};
  return names;
}

void validate(const KeptParams& p, const std::string& generator) {
  for (const std::string& n : kept_case_names())
    if (p.case_name == n) return;
  std::string known;
  for (const std::string& n : kept_case_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("generator", "case", generator + ": unknown case '" + p.case_name + "' (known: " + known + ")");
}

Scene kept_city(const KeptParams& p) {
  validate(p);
  Scene s = p.case_name == "low_planter" ? low_planter() : slab_across_the_disc();
  s.provenance = {"kept", 0, params_to_json(p).dump()};
  return s;
}

KeptRegionQuery kept_region_query(const std::string& case_name) {
  validate(KeptParams{case_name});
  KeptRegionQuery q;
  q.building = 1;
  if (case_name == "low_planter") {
    // Omnidirectional: a level frustum's lower plane would clip the planter and the stone.
    q.centre = level({0, 0}, 0.0, kTwoPi);
    q.radius = 0.5;
    q.from = level({0.5, 0}, 0.0, kTwoPi);
    q.disc_in_open_ground = true;
  } else {
    q.centre = level({0, 0}, kPi / 2, kPi / 2);
    q.radius = 3.0;
    q.from = level({0, 3}, kPi / 2, kPi / 2);
  }
  return q;
}

}  // namespace cullcheck::generators
