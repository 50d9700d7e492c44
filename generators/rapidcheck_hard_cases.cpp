// Bodies of the hard-case generators declared in rapidcheck_hard_cases.hpp (compiled once, as
// rapidcheck_gens.cpp explains).

#include "generators/rapidcheck_hard_cases.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

namespace cullcheck::generators::rcgen {

rc::Gen<SceneSpec> narrow_gap_manhattan_spec() {
  using detail::int_in;
  return detail::spec_of(
      "manhattan", rc::gen::map(rc::gen::tuple(int_in(1, 4), int_in(1, 4), int_in(2, 6), int_in(20, 60), int_in(6, 16),
                                               int_in(2, 500), int_in(0, 5), int_in(0, 30)),
                                [](const std::tuple<int, int, int, int, int, int, int, int>& t) {
                                  const auto [bx, by, lots, block, street, setback_mm, jitter, thin] = t;
                                  return nlohmann::json{{"blocks_x", bx},
                                                        {"blocks_y", by},
                                                        {"buildings_per_block", lots},
                                                        {"block_size", block},
                                                        {"street_width", street},
                                                        {"setback", setback_mm / 1000.0},
                                                        {"width_jitter", jitter / 100.0},
                                                        {"thin_fraction", thin / 100.0}};
                                }));
}

rc::Gen<SceneSpec> narrow_gap_scatter_spec() {
  using detail::int_in;
  return detail::spec_of("scatter", rc::gen::map(rc::gen::tuple(int_in(4, 20), int_in(50, 150), int_in(1, 10), int_in(0, 40)),
                                                 [](const std::tuple<int, int, int, int>& t) {
                                                   const auto [count, area, gap_dm, thin] = t;
                                                   return nlohmann::json{{"count", count},
                                                                         {"area_size", area},
                                                                         {"max_size", std::min(30, area / 3)},
                                                                         {"min_gap", gap_dm / 10.0},
                                                                         {"thin_fraction", thin / 100.0}};
                                                 }));
}

rc::Gen<SceneSpec> facade_scatter_spec() {
  using detail::int_in;
  return detail::spec_of("scatter", rc::gen::map(rc::gen::tuple(int_in(12, 30), int_in(50, 90), int_in(3, 30), int_in(30, 70)),
                                                 [](const std::tuple<int, int, int, int>& t) {
                                                   const auto [count, area, gap_dm, thin] = t;
                                                   return nlohmann::json{{"count", count},
                                                                         {"area_size", area},
                                                                         {"max_size", 40},
                                                                         {"min_height", 1.0},
                                                                         {"max_height", 40.0},
                                                                         {"min_gap", gap_dm / 10.0},
                                                                         {"thin_fraction", thin / 100.0}};
                                                 }));
}

rc::Gen<SceneSpec> small_building_scatter_spec() {
  using detail::int_in;
  return detail::spec_of("scatter", rc::gen::map(rc::gen::tuple(int_in(4, 20), int_in(40, 160), int_in(0, 50)),
                                                 [](const std::tuple<int, int, int>& t) {
                                                   const auto [count, area, thin] = t;
                                                   return nlohmann::json{{"count", count},
                                                                         {"area_size", area},
                                                                         {"min_size", 2.0},
                                                                         {"max_size", 12.0},
                                                                         {"min_height", 3.0},
                                                                         {"max_height", 30.0},
                                                                         {"thin_fraction", thin / 100.0}};
                                                 }));
}

rc::Gen<SceneSpec> hard_scene_spec() {
  return rc::gen::weightedOneOf<SceneSpec>({{3, occluded_manhattan_spec()},
                                            {3, narrow_gap_manhattan_spec()},
                                            {1, narrow_gap_scatter_spec()},
                                            {2, scene_spec()}});
}

namespace detail {

// Plan centre of a building's bounding box.
Vec2 centre_of(const Building& b) { return {(b.bounds.lo.x + b.bounds.hi.x) / 2, (b.bounds.lo.y + b.bounds.hi.y) / 2}; }

}  // namespace detail

rc::Gen<Camera> aimed_into_the_city(const Scene& scene, rc::Gen<Camera> cameras) {
  if (scene.buildings.empty()) return cameras;
  const auto shared = std::make_shared<const detail::SharedScene>(scene);
  return rc::gen::mapcat(std::move(cameras), [shared](const Camera& c) {
    const int last = static_cast<int>(shared->scene.buildings.size()) - 1;
    return rc::gen::map(rc::gen::tuple(detail::int_in(0, last), detail::signed_grid(200, radians(0.1))),
                        [shared, c](const std::tuple<int, double>& t) {
                          Camera out = c;
                          if (out.omnidirectional()) return out;
                          const Building& b = shared->scene.buildings[static_cast<std::size_t>(std::get<0>(t))];
                          const Vec2 d = detail::centre_of(b) - plan(c.position);
                          if (length(d) < 1e-6) return out;
                          out.yaw = wrap_azimuth(azimuth_of(d) + std::get<1>(t));
                          const double above = c.position.z - b.height / 2;
                          if (above > b.height) out.pitch = std::clamp(-std::atan2(above, length(d)) + std::get<1>(t), -kPi / 2, kPi / 2);
                          return out;
                        });
  });
}

rc::Gen<Camera> wall_camera(const Scene& scene) {
  using detail::int_in;
  if (scene.buildings.empty()) return street_camera(scene);
  const auto shared = std::make_shared<const detail::SharedScene>(scene);
  const int last = static_cast<int>(scene.buildings.size()) - 1;
  // 0: along the wall one way, 1: the other way, 2: away from it, 3: at it, 4: a drawn yaw.
  const auto facing = rc::gen::weightedOneOf<int>(
      {{2, rc::gen::just(0)}, {2, rc::gen::just(1)}, {2, rc::gen::just(2)}, {1, rc::gen::just(3)}, {1, rc::gen::just(4)}});
  const auto slight = rc::gen::weightedOneOf<double>({{3, rc::gen::just(0.0)}, {1, detail::signed_grid(100, radians(0.1))}});
  return rc::gen::map(rc::gen::tuple(int_in(0, last), int_in(0, 1 << 20), int_in(0, 1000), int_in(10, 1000), int_in(1500, 2000),
                                     facing, yaw(), slight, field_of_view()),
                      [shared](const std::tuple<int, int, int, int, int, int, double, double, FieldOfView>& t) {
                        const auto& [index, edge_pick, along, out_mm, z_mm, face, drawn_yaw, pitch, fov] = t;
                        const Building& b = shared->scene.buildings[static_cast<std::size_t>(index)];
                        const std::size_t n = b.footprint.size();
                        const std::size_t e = static_cast<std::size_t>(edge_pick) % n;
                        const Vec2 a = b.footprint[e], d = b.footprint[(e + 1) % n] - a;
                        const double len = length(d);
                        const Vec2 dir = len > 0 ? d * (1.0 / len) : Vec2{1, 0};
                        const Vec2 outward{dir.y, -dir.x};  // counter-clockwise ring: the outside is on the right
                        Vec2 p = a + d * (along / 1000.0) + outward * (out_mm / 1000.0);
                        if (!shared->open.is_open(p, 1e-4)) p = shared->open.nudge_to_open(p, 1e-4, 0.01);
                        Camera c;
                        c.position = {p.x, p.y, z_mm / 1000.0};
                        const double yaws[] = {azimuth_of(dir), azimuth_of(dir * -1.0), azimuth_of(outward),
                                               azimuth_of(outward * -1.0), drawn_yaw};
                        c.yaw = yaws[face];
                        c.pitch = pitch;
                        c.hfov = fov.hfov, c.vfov = fov.vfov;
                        return c;
                      });
}

rc::Gen<Camera> steep(rc::Gen<Camera> cameras) {
  using detail::int_in;
  const auto large = [](int max_tenths) {
    return rc::gen::map(rc::gen::tuple(int_in(300, max_tenths), rc::gen::arbitrary<bool>()),
                        [](const std::tuple<int, bool>& t) { return (std::get<1>(t) ? -1.0 : 1.0) * radians(std::get<0>(t) / 10.0); });
  };
  // 0: pitch only, 1: roll only, 2: both.
  return rc::gen::map(rc::gen::tuple(std::move(cameras), int_in(0, 2), large(900), large(1800)),
                      [](const std::tuple<Camera, int, double, double>& t) {
                        Camera c = std::get<0>(t);
                        const int which = std::get<1>(t);
                        if (which != 1) c.pitch = std::get<2>(t);
                        if (which != 0) c.roll = std::get<3>(t);
                        return c;
                      });
}

rc::Gen<Camera> hard_camera(const Scene& scene) {
  return rc::gen::weightedOneOf<Camera>({{3, aimed_into_the_city(scene, street_camera(scene))},
                                         {2, wall_camera(scene)},
                                         {2, steep(aimed_into_the_city(scene, street_camera(scene)))},
                                         {1, street_camera(scene)},
                                         {1, aimed_into_the_city(scene, rooftop_camera(scene))}});
}

rc::Gen<SceneCase> hard_scene_case(rc::Gen<SceneSpec> specs) {
  return rc::gen::mapcat(std::move(specs), [](const SceneSpec& spec) {
    const Scene scene = scene_of(spec);
    return rc::gen::map(hard_camera(scene), [spec](const Camera& c) { return SceneCase{spec, c}; });
  });
}

rc::Gen<SceneSpec> alley_manhattan_spec() {
  using detail::int_in;
  return detail::spec_of("manhattan",
                         rc::gen::map(rc::gen::tuple(int_in(2, 4), int_in(2, 4), int_in(2, 3), int_in(30, 60), int_in(6, 8), int_in(2, 100)),
                                      [](const std::tuple<int, int, int, int, int, int>& t) {
                                        const auto [bx, by, lots, block, street, setback_mm] = t;
                                        return nlohmann::json{{"blocks_x", bx},
                                                              {"blocks_y", by},
                                                              {"buildings_per_block", lots},
                                                              {"block_size", block},
                                                              {"street_width", street},
                                                              {"setback", setback_mm / 1000.0},
                                                              {"width_jitter", 0.0},
                                                              {"thin_fraction", 0.0}};
                                      }));
}

}  // namespace cullcheck::generators::rcgen
