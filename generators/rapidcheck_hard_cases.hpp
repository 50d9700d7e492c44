// RapidCheck generators aimed at the cases culling methods get wrong (issue "Trust the gate"):
// sub-metre gaps between buildings, eyes within a metre of a wall, large pitch and roll at street
// level, eyes aimed into the city rather than anywhere, and large occluded Manhattan grids.
// The properties count how often their cases reach each of these (properties/case_coverage.hpp)
// and assert floors, so a change that stops reaching them fails a test instead of going unseen.
//
// Like rapidcheck_gens.hpp, scenes are SceneSpecs rebuilt by make_city (one replay command per
// case), and every draw shrinks: building indices towards 0, offsets towards the smallest.
//
// Link target: cullcheck_generators_rc.
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::generators::rcgen {

// --- Scenes with gaps narrower than 1 m ---------------------------------------------------------

// Manhattan blocks whose buildings nearly fill their lots: setback 2-500 mm and width jitter
// 0-5%, so neighbouring buildings of a block stand 4 mm to about 1 m apart (2 x setback plus
// the jitter); 1-4 x 1-4 blocks of 2-6 lots, 20-60 m blocks, 6-16 m streets, up to 30% slabs.
inline rc::Gen<SceneSpec> narrow_gap_manhattan_spec() {
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

// Rotated rectangles packed closely: 4-20 in a 50-150 m square, at least 0.1-1 m apart.
inline rc::Gen<SceneSpec> narrow_gap_scatter_spec() {
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

// Long slabs and blocks of every height packed closely (0.3-3 m apart): 8-25 rotated rectangles
// in a 50-120 m square, up to 40 m long, 30-70% thin, 1-40 m tall. Low buildings stand in front
// of the long facades of tall ones, which an eye looking along the facade sees obliquely (the
// occlusion horizon's merge delay, properties/grazing_horizon_cases.hpp).
inline rc::Gen<SceneSpec> facade_scatter_spec() {
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

// Small buildings (2-12 m) spread apart in a 40-160 m square, 3-30 m tall, up to half of them
// thin: a building near the eye is small enough that its shadow enters the horizon before the
// buildings behind it are tested (the near-plane guard, properties/grazing_horizon_cases.hpp).
inline rc::Gen<SceneSpec> small_building_scatter_spec() {
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

// The scenes of the hard-case properties: the large occluded Manhattan grids (most of the city
// hidden from the street), the narrow-gap cities, and the small scenes of every generator.
inline rc::Gen<SceneSpec> hard_scene_spec() {
  return rc::gen::weightedOneOf<SceneSpec>({{3, occluded_manhattan_spec()},
                                            {3, narrow_gap_manhattan_spec()},
                                            {1, narrow_gap_scatter_spec()},
                                            {2, scene_spec()}});
}

// --- Cameras ------------------------------------------------------------------------------------

namespace detail {

// Plan centre of a building's bounding box.
inline Vec2 centre_of(const Building& b) { return {(b.bounds.lo.x + b.bounds.hi.x) / 2, (b.bounds.lo.y + b.bounds.hi.y) / 2}; }

}  // namespace detail

// `cameras`, turned to look at a drawn building (yaw at its centre, off by up to ±20 degrees;
// from above the roofs, pitched down at it too), so the view runs into the city instead of out
// of it. Omnidirectional cameras are left as they are.
inline rc::Gen<Camera> aimed_into_the_city(const Scene& scene, rc::Gen<Camera> cameras) {
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

// An eye 1 cm to 1 m out from a drawn wall (outward along the wall's normal, 1.5-2 m up), looking
// along the wall, away from it, at it (the near plane may then lie beyond the wall: clipped
// geometry hides nothing) or anywhere. Falls back to the nearest open point when the spot lies
// in another building.
inline rc::Gen<Camera> wall_camera(const Scene& scene) {
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

// `cameras` pitched or rolled hard: pitch 30-90 degrees up or down, or roll 30-180 degrees
// either way, or both (the 6-DoF cases of thesis ch. 3.1.2 at street level, where occluders are
// near and the horizon is high).
inline rc::Gen<Camera> steep(rc::Gen<Camera> cameras) {
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

// The cameras of the hard-case properties: street level aimed into the city (most), hugging a
// wall, pitched or rolled hard at street level, anywhere at street level, above the roofs aimed
// down into the city.
inline rc::Gen<Camera> hard_camera(const Scene& scene) {
  return rc::gen::weightedOneOf<Camera>({{3, aimed_into_the_city(scene, street_camera(scene))},
                                         {2, wall_camera(scene)},
                                         {2, steep(aimed_into_the_city(scene, street_camera(scene)))},
                                         {1, street_camera(scene)},
                                         {1, aimed_into_the_city(scene, rooftop_camera(scene))}});
}

// A hard scene and a hard camera in it; shrinks the scene first, then the camera.
inline rc::Gen<SceneCase> hard_scene_case(rc::Gen<SceneSpec> specs = hard_scene_spec()) {
  return rc::gen::mapcat(std::move(specs), [](const SceneSpec& spec) {
    const Scene scene = scene_of(spec);
    return rc::gen::map(hard_camera(scene), [spec](const Camera& c) { return SceneCase{spec, c}; });
  });
}

// --- Alleys: narrow gaps that run through a whole block ---------------------------------------

// Manhattan blocks of 2-3 lots in one row, so the 4 mm to 20 cm gaps between neighbours (2 x
// setback, no jitter) run straight through the block, 30-60 m deep, beside narrow 6-8 m streets:
// from across the street, what stands beyond the block shows only down an alley, from a stretch
// of the street about as wide as the alley (the case view-cell boundary sampling must not leave
// uncovered). 2-4 x 2-4 blocks, no slabs.
inline rc::Gen<SceneSpec> alley_manhattan_spec() {
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
