#include "reports/polar_claims.hpp"

#include <chrono>
#include <cmath>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "core/random.hpp"
#include "core/replay_text.hpp"
#include "engine/polar_diagram/visibility_fan.hpp"
#include "generators/plan_scenes.hpp"
#include "generators/params_json.hpp"
#include "oracle/exact_2d.hpp"

namespace cullcheck {
std::vector<ClaimCheck> check_polar_claims(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ClaimCheck claim;
  claim.id = "ortega-polar-exact-2d";
  claim.source = "Ortega, Rueda & Feito, visibility map determination using angle preprocessing (section 4)";
  claim.statement =
      "from any point of a 2D scene of polygons, the fan of tangent rays over the polar diagrams finds exactly the visible "
      "objects (none missed, none hidden kept)";
  claim.method = "polar_diagram";
  std::vector<ClaimCheck> claims{claim};
  const int cameras = std::max(1, 4 * options.cameras_per_scene);
  search_scenes(options.scenes, options.threads, options.shard, {&claims[0]}, "claims search: polar diagrams against CGAL",
                [&](int index, std::vector<ClaimCheck>& partial) {
    generators::SlotCityParams p;
    p.slots_x = 3 + index % 3, p.slots_y = 3 + (index / 3) % 3;
    const std::uint64_t seed = options.seed * 1000 + static_cast<std::uint64_t>(index);
    const Scene scene = generators::slot_city(p, seed);
    const oracle::ExactVisibility2d exact(scene);
    const polar::VisibilityFan fan(scene);
    Random rng = Random::stream(options.seed, 0x901a7, static_cast<std::uint64_t>(index));
    ClaimCheck& c = partial[0];
    for (int k = 0; k < cameras; ++k) {
      Camera cam;
      const double w = p.slots_x * p.slot, h = p.slots_y * p.slot;
      const bool grid = rng.bernoulli(0.5);
      Vec2 eye{rng.uniform_real(-4, w + 4), rng.uniform_real(-4, h + 4)};
      if (grid) eye = {std::round(2 * eye.x) / 2, std::round(2 * eye.y) / 2};  // on many walls' lines
      cam.position = {eye.x, eye.y, 1.0};
      cam.yaw = rng.uniform_real(0, kTwoPi);
      cam.hfov = rng.bernoulli(0.25) ? kTwoPi : rng.uniform_real(0.02, 3.1);
      cam.vfov = 0.5, cam.near = 0.001, cam.far = 1e6;
      if (!fan.inside_frame(eye)) continue;
      oracle::Exact2dResult truth;
      try {
        truth = exact.visible(cam);
      } catch (const InputError&) {
        continue;  // the eye in or on a footprint
      }
      const std::vector<ObjectId> got = fan.visible(eye, polar::plan_wedge(cam)).visible;
      ++c.frames_checked;
      if (got == truth.visible) continue;
      ++c.violations;
      if (c.holds) {
        c.holds = false;
        c.counterexample_scene = index;
        c.counterexample_replay = "cullcheck gate --generator slot_city --seed " + std::to_string(seed) + " --params '" +
                                  generators::params_to_json(p).dump() + "' --camera " + camera_arg(cam) + " --method polar_diagram";
        c.counterexample_detail = "the fan saw " + ids_text(got) + ", CGAL's visibility polygon " + ids_text(truth.visible);
      }
    }
  });
  const double seconds = seconds_since(start);
  claims[0].search_seconds = seconds;
  return claims;
}

}  // namespace cullcheck
