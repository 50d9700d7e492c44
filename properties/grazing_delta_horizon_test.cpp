// The guarded ΔH held to the oracle at every frame of short paths that start at a grazing eye
// (properties/grazing_cameras.hpp: a far silhouette vertex just beside or behind a near one) and
// then step sideways by less than, about, and more than the guard's radius, turn by less and more
// than its turn, step forward or back and rise. Inside the motion region the PVS comes from the
// region certificate (engine/delta_horizon/motion_region.hpp), so these are the moves where its
// shrunk spans and elevations, its merge delay, its grown items and the guard itself decide what
// a step uncovers (ci/mutants/run.sh weakens each; these properties must fail). The method runs
// with the options the CLI and `builtin_subject delta_h_guarded` use. A failure prints the
// `cullcheck verify` line that replays the path.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <sstream>

#include "engine/method.hpp"
#include "generators/camera_moves.hpp"
#include "generators/camera_paths.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "generators/rapidcheck_hard_cases.hpp"
#include "generators/rapidcheck_moves.hpp"
#include "properties/grazing_cameras.hpp"
#include "properties/grazing_horizon_cases.hpp"
#include "properties/grazing_oracle.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;
using generators::Move;
using generators::MoveKind;

// Moves scaled to the guard (MethodOptions: 0.5 m plan radius, 0.5 m height, 0.05 rad turn):
// sideways steps from 5 cm to 1.5 m, turns from 0.01 to 0.6 rad, short forward and back steps
// and rises; 1-6 of them.
rc::Gen<Move> guard_scale_move() {
  const auto step = rc::gen::element(0.05, 0.1, 0.2, 0.3, 0.45, 0.7, 1.5);
  const auto turn = rc::gen::element(0.01, 0.03, 0.045, 0.1, 0.3, 0.6);
  auto signed_turn = rc::gen::map(rc::gen::tuple(turn, rc::gen::arbitrary<bool>()), [](const std::tuple<double, bool>& t) {
    return Move{MoveKind::turn, std::get<1>(t) ? -std::get<0>(t) : std::get<0>(t)};
  });
  auto along = [step](MoveKind k) { return rc::gen::map(step, [k](double a) { return Move{k, a}; }); };
  return rc::gen::weightedOneOf<Move>({{4, along(MoveKind::left)},
                                       {4, along(MoveKind::right)},
                                       {3, std::move(signed_turn)},
                                       {1, along(MoveKind::forward)},
                                       {1, along(MoveKind::backward)},
                                       {1, rc::gen::map(rc::gen::element(0.2, 0.45, 0.8), [](double a) { return Move{MoveKind::rise, a}; })}});
}

rc::Gen<std::vector<Move>> guard_scale_moves() {
  return rc::gen::mapcat(rc::gen::inRange(1, 7), [](int n) { return rc::gen::container<std::vector<Move>>(n, guard_scale_move()); });
}

// The guarded ΔH along the "moves" path `params` in `scene` (from `spec`), held to the oracle at
// every frame; `seen_at(f, visible)` is given the oracle's visible set at each frame it checks.
// With `open`, stops at the first frame whose eye is inside a building (a step into a wall:
// nothing to hold from there on).
void hold_along_path(const generators::SceneSpec& spec, const Scene& scene, const nlohmann::json& params,
                     const generators::OpenSpace* open,
                     const std::function<void(std::size_t, const std::vector<ObjectId>&)>& seen_at = {}) {
  const CameraPath path = generators::make_camera_path("moves", scene, 0, params);
  auto method = make_method("delta_h_guarded", scene);
  const oracle::Oracle truth(scene);
  for (std::size_t f = 0; f < path.frames.size(); ++f) {
    const Camera& camera = path.frames[f];
    const std::vector<ObjectId> pvs = method->cull(camera).pvs;
    if (open && open->inside_building(camera.position)) break;
    oracle::OracleAnswer seen = truth.visible_set(camera, property_oracle());
    if (seen_at) seen_at(f, seen.visible);
    if (const auto miss = properties::oracle_miss(truth, seen, camera, pvs)) {
      std::ostringstream replay;
      replay << "replay: cullcheck verify " << generators::replay_args(spec) << " --path-kind moves --path-params '"
             << params.dump() << "' --method delta_h_guarded --spacing 3 --frustum-resolution 128";
      RC_FAIL("frame " + std::to_string(f) + ": delta_h_guarded culls building " + std::to_string(miss->building) +
              " the oracle sees (" + miss->witness + ")\n" + replay.str());
    }
  }
}

// The guarded ΔH along `moves` from the grazing eye of `draw`, held to the oracle at every frame.
void holds_along_moves(properties::GrazingDraw draw, const std::vector<Move>& moves) {
  const generators::SceneSpec spec =
      *rc::gen::oneOf(rcgen::manhattan_spec(), rcgen::scatter_spec(), rcgen::irregular_spec(), rcgen::tall_occluder_spec(1.7));
  const Scene scene = generators::scene_of(spec);
  RC_PRE(!scene.buildings.empty());
  const generators::OpenSpace open(scene);
  draw.near = 0.1;  // the near plane is OH(OS)'s business (grazing_horizon_test)
  const properties::Grazing g = properties::grazing_camera(scene, open, draw);
  RC_TAG(g.usable ? "grazing start" : "no usable start");
  if (!g.usable) return;
  hold_along_path(spec, scene, generators::moves_params(g.camera, moves), &open);
}

RC_GTEST_PROP(GrazingEyes, GuardedDeltaHorizonKeepsWhatAStepUncovers, ()) {
  properties::GrazingDraw draw = *properties::grazing_draw();
  // b hidden by a fraction of the guard's radius (a step of that much uncovers it), or by a bin.
  if (*rc::gen::arbitrary<bool>()) draw.offset_metres = -0.5 * *rc::gen::element(0.5, 0.1, 0.3, 0.7, 0.9, 1.5);
  holds_along_moves(draw, *guard_scale_moves());
}

// A far roof just under a near building's shadow line at its farther tangent vertex
// (grazing_cameras.hpp, heights 4-7), then one rise or step back within the guard's height and
// radius: the far roof comes up over the near one while the carried-over certificate holds.
RC_GTEST_PROP(GrazingEyes, GuardedDeltaHorizonKeepsARoofARiseUncovers, ()) {
  properties::GrazingDraw draw = *properties::grazing_draw();
  draw.height = *rc::gen::inRange(4, 8);
  draw.offset_bins = -*rc::gen::inRange(0, 40) * 0.5;
  draw.offset_metres.reset();
  const Move move = *rc::gen::oneOf(
      rc::gen::map(rc::gen::element(0.45, 0.3, 0.2, 0.1), [](double a) { return Move{MoveKind::rise, a}; }),
      rc::gen::map(rc::gen::element(0.45, 0.2), [](double a) { return Move{MoveKind::backward, a}; }));
  holds_along_moves(draw, {move});
}

// A far roof 0.1-0.45 m of eye height under a near roof's shadow line, the eye 1-5 m beyond the
// near CVP's silhouette vertex and the far CVP at least 6 times farther (grazing_horizon_cases.hpp),
// then one rise by 0.45-0.49 m (within the guard's height), half the time followed by a step back
// of 0.45 m (within its radius): the far roof comes up over the near one, which the certificate
// made at the first frame must allow for (its shrunk shadows take the lowest elevation over the
// region). Counts the cases where the oracle sees the far building at the last frame but not at
// the first (the moves uncovered it) and asserts a floor of 5% (about 12% at the CI seed).
TEST(GrazingEyes, GuardedDeltaHorizonKeepsAFarRoofARiseLiftsOverANearOne) {
  std::size_t cases = 0, uncovered = 0;
  const bool held = rc::check("delta_h_guarded keeps a far roof a rise lifts over a near one", [&] {
    const generators::SceneSpec spec = *rc::gen::oneOf(rcgen::tall_occluder_spec(1.7), rcgen::manhattan_spec(), rcgen::scatter_spec());
    const Scene scene = generators::scene_of(spec);
    RC_PRE(!scene.buildings.empty());
    const generators::OpenSpace open(scene);
    const properties::GrazingDraw draw = *properties::far_roof_draw();
    properties::Grazing g = properties::far_roof_camera(scene, open, draw);
    const double lower = *rc::gen::element(0.05, 0.1, 0.15);
    const double rise = *rc::gen::element(0.49, 0.45);
    const bool back_too = *rc::gen::arbitrary<bool>();
    ++cases;
    g.camera.position.z -= lower;
    if (!g.usable || !(g.camera.position.z > 0.05)) return;
    std::vector<Move> moves{{MoveKind::rise, rise}};
    if (back_too) moves.push_back({MoveKind::backward, 0.45});
    std::vector<bool> target_seen;
    hold_along_path(spec, scene, generators::moves_params(g.camera, moves), nullptr,
                    [&](std::size_t, const std::vector<ObjectId>& seen) {
                      target_seen.push_back(std::binary_search(seen.begin(), seen.end(), g.target));
                    });
    const bool up = !target_seen.front() && target_seen.back();
    RC_TAG(up ? "the rise uncovers the far roof" : "no roof uncovered");
    uncovered += up;
  });
  EXPECT_TRUE(held);
  std::printf("far roof uncovered by the rise: %zu of %zu cases\n", uncovered, cases);
  EXPECT_GE(20 * uncovered, cases) << "cases where the rise uncovers the far roof";
}

// A low building wholly in front of a taller building's long facade, seen from nearer the tall
// one (grazing_horizon_cases.hpp, as for OH(OS)), then a stop or a sideways step of 0.3 m: the
// certificate made at the first frame may let the tall one's shrunk shadow hide what the sweep
// reaches only once it has passed the tall one's farthest point (+ 2ε), not its nearest. Counts
// the cases where the oracle sees the low building at the first frame and asserts a floor of 5%
// (about 12% at the CI seed).
TEST(GrazingEyes, GuardedDeltaHorizonKeepsALowBuildingBeforeADeepFacade) {
  std::size_t cases = 0, reached = 0;
  const bool held = rc::check("delta_h_guarded keeps a low building before a deep facade", [&] {
    const generators::SceneSpec spec = *rcgen::facade_scatter_spec();
    const Scene scene = generators::scene_of(spec);
    RC_PRE(!scene.buildings.empty());
    const generators::OpenSpace open(scene);
    const properties::FacadeDraw draw = *properties::facade_draw();
    const Move move = *rc::gen::element(Move{MoveKind::stop, 0.0}, Move{MoveKind::left, 0.3}, Move{MoveKind::right, 0.3});
    const properties::FacadeCase c = properties::before_a_deep_facade(scene, open, draw);
    ++cases;
    RC_TAG(c.reached ? "low building before a facade" : "no such pair");
    if (!c.reached) return;
    hold_along_path(spec, scene, generators::moves_params(c.grazing.camera, {move}), &open,
                    [&](std::size_t f, const std::vector<ObjectId>& seen) {
                      if (f == 0) reached += std::binary_search(seen.begin(), seen.end(), c.grazing.target);
                    });
  });
  EXPECT_TRUE(held);
  std::printf("low building before a deep facade, seen by the oracle: %zu of %zu cases\n", reached, cases);
  EXPECT_GE(20 * reached, cases) << "cases that reached a low building seen before a deep facade";
}

}  // namespace
}  // namespace cullcheck
