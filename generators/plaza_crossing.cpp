// The thesis's Table 4.1 walk on a plaza city ("plaza_crossing"; thesis ch. 4.2): a long street
// east to the plaza's south-west corner, the plaza crossed diagonally to its north-east corner,
// a left turn into the street that leaves that corner northwards, and along it. The diagonal
// runs between street centre lines (the thesis walks 162 of its square's 170 m diagonal; here
// the whole of it, so that the walk ends in the street). One frame per
// step (the thesis computes a PVS every 2 m and uses it for 30 frames), turns in steps of at
// most `turn_step_deg` (it recomputes when the view turns by more than 7 degrees). The street
// legs are cut where the city ends. With 50 m block pitch and a 3 x 2-block plaza the diagonal
// is 180 m and the second turn 56.3 degrees (thesis: 170 m, 56 degrees).
#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "generators/angles.hpp"
#include "generators/camera_paths.hpp"
#include "generators/manhattan_layout.hpp"
#include "generators/param_checks.hpp"

namespace cullcheck::generators {

void validate(const PlazaCrossingParams& p) {
  const ParamChecks check("path", "plaza_crossing");
  check.above("step_m", p.step_m, 0.0, 1.0e4);
  check.above("turn_step_deg", p.turn_step_deg, 0.0, 180.0);
  check.in_range("first_street_m", p.first_street_m, 0.0, 1.0e6);
  check.in_range("second_street_m", p.second_street_m, 0.0, 1.0e6);
  check.above("eye_height", p.eye_height, 0.0, 1.0e4);
  if (!(p.hfov_deg > 0.0 && p.hfov_deg < 180.0)) check.fail("hfov_deg", "must lie in (0, 180)");
  if (!(p.vfov_deg > 0.0 && p.vfov_deg < 180.0)) check.fail("vfov_deg", "must lie in (0, 180)");
}

CameraPath plaza_crossing(const Scene& scene, const PlazaCrossingParams& p) {
  validate(p);
  const auto city = manhattan_params_of(scene);
  if (!city || city->plaza_blocks_x <= 0 || city->plaza_blocks_y <= 0)
    throw InputError("path", "kind", "plaza_crossing needs a scene from the plaza or default generator (a city with a plaza)");
  const ManhattanLayout layout = manhattan_layout(*city);
  const Box2 extent = layout.extent();
  const Vec2 south_west{layout.street_x(layout.plaza_x0), layout.street_y(layout.plaza_y0)};
  const Vec2 north_east{layout.street_x(layout.plaza_x1), layout.street_y(layout.plaza_y1)};
  const Vec2 start{std::max(extent.lo.x + p.step_m, south_west.x - p.first_street_m), south_west.y};
  const Vec2 diagonal = north_east - south_west;
  const Vec2 finish{north_east.x, std::min(extent.hi.y - p.step_m, north_east.y + p.second_street_m)};

  CameraPath path;
  path.kind = "plaza_crossing";
  path.frames_per_second = 1.0;  // one frame per step
  Camera camera;
  camera.hfov = radians(p.hfov_deg);
  camera.vfov = radians(p.vfov_deg);
  camera.position = {start.x, start.y, p.eye_height};
  camera.yaw = 0.0;
  auto walk_to = [&](Vec2 to) {
    const Vec2 from = plan(camera.position);
    const double length_m = length(to - from);
    const int steps = static_cast<int>(std::ceil(length_m / p.step_m - 1e-9));
    for (int i = 1; i <= steps; ++i) {
      const Vec2 q = from + (to - from) * (std::min(1.0, i * p.step_m / length_m));
      camera.position = {q.x, q.y, p.eye_height};
      path.frames.push_back(camera);
    }
  };
  auto turn_to = [&](double yaw) {
    const double total = shortest_turn(camera.yaw, yaw);
    const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(total) / radians(p.turn_step_deg) - 1e-9)));
    const double from = camera.yaw;
    for (int i = 1; i <= steps; ++i) {
      camera.yaw = wrap_azimuth(from + total * i / steps);
      path.frames.push_back(camera);
    }
  };
  path.frames.push_back(camera);
  walk_to(south_west);
  turn_to(azimuth_of(diagonal));
  walk_to(north_east);
  turn_to(kPi / 2);
  walk_to(finish);
  return path;
}

}  // namespace cullcheck::generators
