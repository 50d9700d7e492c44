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
// Link target: cullcheck_generators_rc (cullcheck_generators + rapidcheck); the bodies are in
// rapidcheck_gens.cpp, compiled once.
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
rc::Gen<int> int_in(int lo, int hi);

// A value in [-max, max] on a grid of `unit`, shrinking towards 0 (magnitude, then sign).
rc::Gen<double> signed_grid(int max_units, double unit);

rc::Gen<std::uint64_t> seed();

rc::Gen<SceneSpec> spec_of(std::string generator, rc::Gen<nlohmann::json> params);

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
rc::Gen<SceneSpec> manhattan_spec();

// Larger grids where most of the city is hidden from the street (what incremental methods skip):
// 4-10 x 4-10 blocks of 2-4 lots, 20-50 m blocks, 6-14 m streets, up to 40% thin slabs.
rc::Gen<SceneSpec> occluded_manhattan_spec();

// 3-5 x 3-5 blocks with a one-block plaza and 0-4 kiosks (lower than the eye).
rc::Gen<SceneSpec> plaza_spec();

// 1-12 rotated rectangles in a 60-300 m square, up to 60% thin.
rc::Gen<SceneSpec> scatter_spec();

// 1-10 L/U/T/convex footprints in a 100-300 m square.
rc::Gen<SceneSpec> irregular_spec();

// 1-4 x 1-4 of the thesis's 46-triangle buildings.
rc::Gen<SceneSpec> thesis_spec();

// Any of the small generators above (shrinks towards manhattan).
rc::Gen<SceneSpec> scene_spec();

// 1-8 occluders in a 40-120 m square with heights in [min_height, max_height].
rc::Gen<SceneSpec> occluder_field_spec(double min_height, double max_height);
// Occluders entirely below the eye (0.2 m .. eye - 5 cm): the β_min case of thesis ch. 3.1.2,
// where a building's highest elevation seen from the eye is negative. Needs eye_height > 0.3.
rc::Gen<SceneSpec> low_occluder_spec(double eye_height);
// Occluders taller than the eye (eye + 0.5 m .. eye + 40 m).
rc::Gen<SceneSpec> tall_occluder_spec(double eye_height);

// --- Cameras ------------------------------------------------------------------------------------

struct FieldOfView {
  double hfov = kPi / 3;
  double vfov = kPi / 4;
};
inline void showValue(const FieldOfView& f, std::ostream& os) { os << "{hfov: " << f.hfov << ", vfov: " << f.vfov << "}"; }

// Ordinary 30-120 degrees (most often), narrow 1-5 degrees, or omnidirectional (hfov = 2*pi).
rc::Gen<FieldOfView> field_of_view();

// Azimuth in [0, 2*pi): on a 0.1-degree grid, or exactly one of the axis directions.
rc::Gen<double> yaw();

// Street level: eye 1.5-2 m, in the open (moved along +x out of any footprint it lands in),
// level or pitched by up to 10 degrees, roll 0 or up to 5 degrees.
rc::Gen<Camera> street_camera(const Scene& scene);

// Above every roof (1-200 m higher than the highest), anywhere over the scene, any pitch in
// [-90, 90] degrees (the extremes drawn on purpose) and any roll.
rc::Gen<Camera> rooftop_camera(const Scene& scene);

// Street level or above the rooftops.
rc::Gen<Camera> camera_in(const Scene& scene);

// A small scene and a camera in it; shrinks the scene first, then the camera.
rc::Gen<SceneCase> scene_case(rc::Gen<SceneSpec> specs = scene_spec());

}  // namespace cullcheck::generators::rcgen

namespace rc {
template <>
struct Arbitrary<cullcheck::generators::SceneSpec> {
  static Gen<cullcheck::generators::SceneSpec> arbitrary() { return cullcheck::generators::rcgen::scene_spec(); }
};
}  // namespace rc
