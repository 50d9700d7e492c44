// RapidCheck generators for properties (design: "Generators compose; failures shrink").
//
// A generated scene is never built by RapidCheck's own randomness: RapidCheck draws a SceneSpec
// (generator name, 64-bit seed, a few small size parameters) and the scene is made by the same
// seeded generator the CLI runs (make_city). So every counterexample is printable as one replay
// command (replay_args), and shrinking works on the spec: fewer blocks, fewer lots, fewer
// buildings, no thin slabs, a smaller seed - a failure shrinks towards a small city.
//
// Cameras are drawn for a given scene: at street level (eye 1.5-2 m, in the open, level or
// slightly pitched), above the rooftops (any pitch in [-90, 90] degrees, any roll), with narrow
// (1-5 degree), ordinary (30-120 degree) or omnidirectional (360 degree) fields of view, and the
// exact azimuths 0, pi/2, pi, 3pi/2 drawn on purpose (wrap-around cases). Angles shrink towards
// 0 and fields of view towards the ordinary ones.
//
// Link target: cullcheck_generators_rc (cullcheck_generators + rapidcheck).
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <tuple>

#include "core/camera.hpp"
#include "core/scene_io.hpp"
#include "generators/angles.hpp"
#include "generators/city.hpp"
#include "generators/open_space.hpp"

namespace cullcheck::generators {

// What to build: make_city(generator, seed, params).
struct SceneSpec {
  std::string generator = "manhattan";
  std::uint64_t seed = 0;
  nlohmann::json params = nlohmann::json::object();
};

inline Scene scene_of(const SceneSpec& spec) { return make_city(spec.generator, spec.seed, spec.params); }

// Command-line flags that rebuild the scene, e.g.
//   --generator manhattan --seed 12 --params '{"blocks_x":2,"blocks_y":1}'
inline std::string replay_args(const SceneSpec& spec) {
  return "--generator " + spec.generator + " --seed " + std::to_string(spec.seed) + " --params '" + spec.params.dump() + "'";
}

inline std::ostream& operator<<(std::ostream& os, const SceneSpec& spec) { return os << replay_args(spec); }
// Found by argument-dependent lookup from rc::show, for counterexample printing.
inline void showValue(const SceneSpec& spec, std::ostream& os) { os << replay_args(spec); }

// A scene together with one camera in it.
struct SceneCase {
  SceneSpec spec;
  Camera camera;
};
inline std::ostream& operator<<(std::ostream& os, const SceneCase& c) {
  std::string cam = camera_to_json_text(c.camera);
  if (!cam.empty() && cam.back() == '\n') cam.pop_back();
  return os << replay_args(c.spec) << " --camera '" << cam << "'";
}
inline void showValue(const SceneCase& c, std::ostream& os) { os << c; }

}  // namespace cullcheck::generators

namespace cullcheck {
// Cameras print as the JSON the CLI reads (camera_from_json_text). Declared in cullcheck, the
// namespace of Camera, so that rc::show finds it by argument-dependent lookup.
inline void showValue(const Camera& camera, std::ostream& os) {
  std::string text = camera_to_json_text(camera);
  if (!text.empty() && text.back() == '\n') text.pop_back();
  os << text;
}
}  // namespace cullcheck

namespace cullcheck::generators::rcgen {

namespace detail {

// Integer in [lo, hi] (inclusive), shrinking towards lo.
inline rc::Gen<int> int_in(int lo, int hi) { return rc::gen::inRange<int>(lo, hi + 1); }

// A value in [-max, max] on a grid of `unit`, shrinking towards 0 (magnitude, then sign).
inline rc::Gen<double> signed_grid(int max_units, double unit) {
  return rc::gen::map(rc::gen::tuple(int_in(0, max_units), rc::gen::arbitrary<bool>()),
                      [unit](const std::tuple<int, bool>& t) { return (std::get<1>(t) ? -1.0 : 1.0) * std::get<0>(t) * unit; });
}

inline rc::Gen<std::uint64_t> seed() { return rc::gen::arbitrary<std::uint64_t>(); }

inline rc::Gen<SceneSpec> spec_of(std::string generator, rc::Gen<nlohmann::json> params) {
  return rc::gen::map(rc::gen::tuple(seed(), std::move(params)), [generator](const std::tuple<std::uint64_t, nlohmann::json>& t) {
    return SceneSpec{generator, std::get<0>(t), std::get<1>(t)};
  });
}

// A scene copied into shared storage with its open-space index, so camera generators can be
// copied freely by RapidCheck without holding a reference to the caller's scene.
struct SharedScene {
  explicit SharedScene(Scene s) : scene(std::move(s)), open(scene) {}
  Scene scene;
  OpenSpace open;
};

}  // namespace detail

// --- Scenes: small versions of each generator -------------------------------------------------

// 1-4 x 1-4 blocks of 1-4 lots, 20-80 m blocks, 6-20 m streets, up to 60% thin slabs.
inline rc::Gen<SceneSpec> manhattan_spec() {
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

// Larger grids where most of the city is hidden from the street (what incremental methods skip):
// 4-10 x 4-10 blocks of 2-4 lots, 20-50 m blocks, 6-14 m streets, up to 40% thin slabs.
inline rc::Gen<SceneSpec> occluded_manhattan_spec() {
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

// 3-5 x 3-5 blocks with a one-block plaza and 0-4 kiosks (lower than the eye).
inline rc::Gen<SceneSpec> plaza_spec() {
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

// 1-12 rotated rectangles in a 60-300 m square, up to 60% thin.
inline rc::Gen<SceneSpec> scatter_spec() {
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

// 1-10 L/U/T/convex footprints in a 100-300 m square.
inline rc::Gen<SceneSpec> irregular_spec() {
  using detail::int_in;
  return detail::spec_of("irregular", rc::gen::map(rc::gen::tuple(int_in(1, 10), int_in(100, 300)),
                                                   [](const std::tuple<int, int>& t) {
                                                     const auto [count, area] = t;
                                                     return nlohmann::json{{"count", count}, {"area_size", area}};
                                                   }));
}

// 1-4 x 1-4 of the thesis's 46-triangle buildings.
inline rc::Gen<SceneSpec> thesis_spec() {
  using detail::int_in;
  return detail::spec_of("thesis", rc::gen::map(rc::gen::tuple(int_in(1, 4), int_in(1, 4)), [](const std::tuple<int, int>& t) {
                           return nlohmann::json{{"grid_x", std::get<0>(t)}, {"grid_y", std::get<1>(t)}};
                         }));
}

// Any of the small generators above (shrinks towards manhattan).
inline rc::Gen<SceneSpec> scene_spec() {
  return rc::gen::oneOf(manhattan_spec(), plaza_spec(), scatter_spec(), irregular_spec(), thesis_spec());
}

// 1-8 occluders in a 40-120 m square with heights in [min_height, max_height].
inline rc::Gen<SceneSpec> occluder_field_spec(double min_height, double max_height) {
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
// Occluders entirely below the eye (0.2 m .. eye - 5 cm): the β_min case of thesis ch. 3.1.2,
// where a building's highest elevation seen from the eye is negative. Needs eye_height > 0.3.
inline rc::Gen<SceneSpec> low_occluder_spec(double eye_height) { return occluder_field_spec(0.2, eye_height - 0.05); }
// Occluders taller than the eye (eye + 0.5 m .. eye + 40 m).
inline rc::Gen<SceneSpec> tall_occluder_spec(double eye_height) { return occluder_field_spec(eye_height + 0.5, eye_height + 40.0); }

// --- Cameras ------------------------------------------------------------------------------------

struct FieldOfView {
  double hfov = kPi / 3;
  double vfov = kPi / 4;
};
inline void showValue(const FieldOfView& f, std::ostream& os) { os << "{hfov: " << f.hfov << ", vfov: " << f.vfov << "}"; }

// Ordinary 30-120 degrees (most often), narrow 1-5 degrees, or omnidirectional (hfov = 2*pi).
inline rc::Gen<FieldOfView> field_of_view() {
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

// Azimuth in [0, 2*pi): on a 0.1-degree grid, or exactly one of the axis directions.
inline rc::Gen<double> yaw() {
  return rc::gen::weightedOneOf<double>({{4, rc::gen::map(detail::int_in(0, 3599), [](int t) { return radians(t / 10.0); })},
                                         {1, rc::gen::element(0.0, kPi / 2, kPi, 3 * kPi / 2)}});
}

// Street level: eye 1.5-2 m, in the open (moved along +x out of any footprint it lands in),
// level or pitched by up to 10 degrees, roll 0 or up to 5 degrees.
inline rc::Gen<Camera> street_camera(const Scene& scene) {
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

// Above every roof (1-200 m higher than the highest), anywhere over the scene, any pitch in
// [-90, 90] degrees (the extremes drawn on purpose) and any roll.
inline rc::Gen<Camera> rooftop_camera(const Scene& scene) {
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

// Street level or above the rooftops.
inline rc::Gen<Camera> camera_in(const Scene& scene) { return rc::gen::oneOf(street_camera(scene), rooftop_camera(scene)); }

// A small scene and a camera in it; shrinks the scene first, then the camera.
inline rc::Gen<SceneCase> scene_case(rc::Gen<SceneSpec> specs = scene_spec()) {
  return rc::gen::mapcat(std::move(specs), [](const SceneSpec& spec) {
    const Scene scene = scene_of(spec);
    return rc::gen::map(camera_in(scene), [spec](const Camera& c) { return SceneCase{spec, c}; });
  });
}

}  // namespace cullcheck::generators::rcgen

namespace rc {
template <>
struct Arbitrary<cullcheck::generators::SceneSpec> {
  static Gen<cullcheck::generators::SceneSpec> arbitrary() { return cullcheck::generators::rcgen::scene_spec(); }
};
}  // namespace rc
