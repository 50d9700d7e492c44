// Bodies of the RapidCheck generators declared in rapidcheck_gens.hpp. They live here, compiled
// once, because RapidCheck's combinators cost several seconds of compile time in every file
// that instantiates them (about 8 s a test file under gcc, 7 s under clang with sanitizers).

#include "generators/rapidcheck_gens.hpp"

#include <algorithm>
#include <memory>
#include <tuple>

namespace cullcheck::generators::rcgen {

namespace detail {

rc::Gen<int> int_in(int lo, int hi) { return rc::gen::inRange<int>(lo, hi + 1); }

rc::Gen<double> signed_grid(int max_units, double unit) {
  return rc::gen::map(rc::gen::tuple(int_in(0, max_units), rc::gen::arbitrary<bool>()),
                      [unit](const std::tuple<int, bool>& t) { return (std::get<1>(t) ? -1.0 : 1.0) * std::get<0>(t) * unit; });
}

rc::Gen<std::uint64_t> seed() { return rc::gen::arbitrary<std::uint64_t>(); }

rc::Gen<SceneSpec> spec_of(std::string generator, rc::Gen<nlohmann::json> params) {
  return rc::gen::map(rc::gen::tuple(seed(), std::move(params)), [generator](const std::tuple<std::uint64_t, nlohmann::json>& t) {
    return SceneSpec{generator, std::get<0>(t), std::get<1>(t)};
  });
}

}  // namespace detail

rc::Gen<SceneSpec> manhattan_spec() {
  using detail::int_in;
  return detail::spec_of(
      "manhattan", rc::gen::map(rc::gen::tuple(int_in(1, 4), int_in(1, 4), int_in(1, 4), int_in(20, 80), int_in(6, 20),
                                               int_in(0, 60), int_in(0, 30)),
                                [](const std::tuple<int, int, int, int, int, int, int>& t) {
                                  const auto [bx, by, lots, block, street, thin, tower] = t;
                                  return nlohmann::json{{"blocks_x", bx},        {"blocks_y", by},
                                                        {"buildings_per_block", lots}, {"block_size", block},
                                                        {"street_width", street},      {"thin_fraction", thin / 100.0},
                                                        {"tower_fraction", tower / 100.0}};
                                }));
}

rc::Gen<SceneSpec> occluded_manhattan_spec() {
  using detail::int_in;
  return detail::spec_of(
      "manhattan", rc::gen::map(rc::gen::tuple(int_in(4, 10), int_in(4, 10), int_in(2, 4), int_in(20, 50), int_in(6, 14),
                                               int_in(0, 40)),
                                [](const std::tuple<int, int, int, int, int, int>& t) {
                                  const auto [bx, by, lots, block, street, thin] = t;
                                  return nlohmann::json{{"blocks_x", bx},        {"blocks_y", by},
                                                        {"buildings_per_block", lots}, {"block_size", block},
                                                        {"street_width", street},      {"thin_fraction", thin / 100.0}};
                                }));
}

rc::Gen<SceneSpec> plaza_spec() {
  using detail::int_in;
  return detail::spec_of(
      "plaza", rc::gen::map(rc::gen::tuple(int_in(3, 5), int_in(3, 5), int_in(1, 4), int_in(0, 4), int_in(20, 60)),
                            [](const std::tuple<int, int, int, int, int>& t) {
                              const auto [bx, by, lots, kiosks, block] = t;
                              return nlohmann::json{{"blocks_x", bx},          {"blocks_y", by},
                                                    {"buildings_per_block", lots}, {"kiosk_count", kiosks},
                                                    {"plaza_blocks_x", 1},     {"plaza_blocks_y", 1},
                                                    {"block_size", block}};
                            }));
}

rc::Gen<SceneSpec> scatter_spec() {
  using detail::int_in;
  return detail::spec_of("scatter", rc::gen::map(rc::gen::tuple(int_in(1, 12), int_in(60, 300), int_in(0, 60)),
                                                 [](const std::tuple<int, int, int>& t) {
                                                   const auto [count, area, thin] = t;
                                                   return nlohmann::json{{"count", count},
                                                                         {"area_size", area},
                                                                         {"max_size", std::min(40, area / 3)},
                                                                         {"thin_fraction", thin / 100.0}};
                                                 }));
}

rc::Gen<SceneSpec> irregular_spec() {
  using detail::int_in;
  return detail::spec_of("irregular", rc::gen::map(rc::gen::tuple(int_in(1, 10), int_in(100, 300)),
                                                   [](const std::tuple<int, int>& t) {
                                                     const auto [count, area] = t;
                                                     return nlohmann::json{{"count", count}, {"area_size", area}};
                                                   }));
}

rc::Gen<SceneSpec> thesis_spec() {
  using detail::int_in;
  return detail::spec_of("thesis", rc::gen::map(rc::gen::tuple(int_in(1, 4), int_in(1, 4)), [](const std::tuple<int, int>& t) {
                           return nlohmann::json{{"grid_x", std::get<0>(t)}, {"grid_y", std::get<1>(t)}};
                         }));
}

rc::Gen<SceneSpec> scene_spec() {
  return rc::gen::oneOf(manhattan_spec(), plaza_spec(), scatter_spec(), irregular_spec(), thesis_spec());
}

rc::Gen<SceneSpec> occluder_field_spec(double min_height, double max_height) {
  using detail::int_in;
  return rc::gen::mapcat(rc::gen::element<std::string>("scatter", "irregular"), [=](const std::string& generator) {
    return detail::spec_of(generator, rc::gen::map(rc::gen::tuple(int_in(1, 8), int_in(40, 120)), [=](const std::tuple<int, int>& t) {
                             const auto [count, area] = t;
                             nlohmann::json p{{"count", count}, {"area_size", area}, {"min_height", min_height}, {"max_height", max_height}};
                             if (generator == "scatter") p["max_size"] = std::min(30, area / 3);
                             if (generator == "irregular") p["max_size"] = std::max(12, std::min(40, area / 3));
                             return p;
                           }));
  });
}

rc::Gen<SceneSpec> low_occluder_spec(double eye_height) { return occluder_field_spec(0.2, eye_height - 0.05); }

rc::Gen<SceneSpec> tall_occluder_spec(double eye_height) { return occluder_field_spec(eye_height + 0.5, eye_height + 40.0); }

rc::Gen<FieldOfView> field_of_view() {
  using detail::int_in;
  auto perspective = [](rc::Gen<int> tenths) {
    return rc::gen::map(rc::gen::tuple(std::move(tenths), int_in(50, 100)), [](const std::tuple<int, int>& t) {
      const double h = radians(std::get<0>(t) / 10.0);
      return FieldOfView{h, std::min(h * std::get<1>(t) / 100.0, radians(170))};
    });
  };
  return rc::gen::weightedOneOf<FieldOfView>({{6, perspective(int_in(300, 1200))},
                                              {2, perspective(int_in(10, 50))},
                                              {2, rc::gen::just(FieldOfView{kTwoPi, kPi / 2})}});
}

rc::Gen<double> yaw() {
  return rc::gen::weightedOneOf<double>({{4, rc::gen::map(detail::int_in(0, 3599), [](int t) { return radians(t / 10.0); })},
                                         {1, rc::gen::element(0.0, kPi / 2, kPi, 3 * kPi / 2)}});
}

rc::Gen<Camera> street_camera(const Scene& scene) {
  using detail::int_in;
  const auto shared = std::make_shared<const detail::SharedScene>(scene);
  auto slight = [](int max_tenths) {
    return rc::gen::weightedOneOf<double>({{3, rc::gen::just(0.0)}, {1, detail::signed_grid(max_tenths, radians(0.1))}});
  };
  return rc::gen::map(rc::gen::tuple(int_in(0, 10000), int_in(0, 10000), int_in(1500, 2000), yaw(), slight(100), slight(50),
                                     field_of_view()),
                      [shared](const std::tuple<int, int, int, double, double, double, FieldOfView>& t) {
                        const auto& [u, v, z_mm, yaw_angle, pitch, roll, fov] = t;
                        Box2 area = shared->scene.buildings.empty() ? Box2{{-50, -50}, {50, 50}} : shared->open.bounds().plan();
                        area = {{area.lo.x - 10, area.lo.y - 10}, {area.hi.x + 10, area.hi.y + 10}};
                        const Vec2 drawn{area.lo.x + (area.hi.x - area.lo.x) * u / 10000.0,
                                         area.lo.y + (area.hi.y - area.lo.y) * v / 10000.0};
                        Camera c;
                        const Vec2 p = shared->open.nudge_to_open(drawn, 0.05);
                        c.position = {p.x, p.y, z_mm / 1000.0};
                        c.yaw = yaw_angle, c.pitch = pitch, c.roll = roll;
                        c.hfov = fov.hfov, c.vfov = fov.vfov;
                        return c;
                      });
}

rc::Gen<Camera> rooftop_camera(const Scene& scene) {
  using detail::int_in;
  const auto shared = std::make_shared<const detail::SharedScene>(scene);
  const auto pitch = rc::gen::weightedOneOf<double>(
      {{4, detail::signed_grid(900, radians(0.1))}, {1, rc::gen::element(-kPi / 2, kPi / 2)}});
  return rc::gen::map(rc::gen::tuple(int_in(0, 10000), int_in(0, 10000), int_in(1, 200), yaw(), pitch,
                                     detail::signed_grid(1800, radians(0.1)), field_of_view()),
                      [shared](const std::tuple<int, int, int, double, double, double, FieldOfView>& t) {
                        const auto& [u, v, above, yaw_angle, pitch_angle, roll, fov] = t;
                        const bool empty = shared->scene.buildings.empty();
                        const Box3 b = shared->open.bounds();
                        const Box2 area = empty ? Box2{{-50, -50}, {50, 50}} : b.plan();
                        Camera c;
                        c.position = {area.lo.x + (area.hi.x - area.lo.x) * u / 10000.0,
                                      area.lo.y + (area.hi.y - area.lo.y) * v / 10000.0, (empty ? 0.0 : b.hi.z) + above};
                        c.yaw = yaw_angle;
                        c.pitch = std::clamp(pitch_angle, -kPi / 2, kPi / 2);
                        c.roll = roll;
                        c.hfov = fov.hfov, c.vfov = fov.vfov;
                        return c;
                      });
}

rc::Gen<Camera> camera_in(const Scene& scene) { return rc::gen::oneOf(street_camera(scene), rooftop_camera(scene)); }

rc::Gen<SceneCase> scene_case(rc::Gen<SceneSpec> specs) {
  return rc::gen::mapcat(std::move(specs), [](const SceneSpec& spec) {
    const Scene scene = scene_of(spec);
    return rc::gen::map(camera_in(scene), [spec](const Camera& c) { return SceneCase{spec, c}; });
  });
}

}  // namespace cullcheck::generators::rcgen
