#include "reports/online_claims.hpp"

#include <algorithm>
#include <chrono>
#include <iterator>

#include "core/elapsed.hpp"
#include "core/replay_text.hpp"
#include "engine/online_image_space/online_culling.hpp"
#include "generators/camera_moves.hpp"
#include "generators/open_space.hpp"
#include "generators/random.hpp"
#include "reports/verification.hpp"

namespace cullcheck {
namespace {

using generators::Move;
using generators::MoveKind;

struct Configuration {
  OnlineImageSpaceCulling::Variant variant;
  OnlineCullingOptions options;
  std::string flags;  // the --online-* flags that give `options`
};

// V = 1 mm/s: the stamps outlive the two frames, so the step, not the clock, is what is tested.
Configuration single_occluder(OnlineImageSpaceCulling::Variant variant) {
  Configuration c{variant, {}, "--online-occluders 1 --online-leaf-size 1 --online-min-distance 5 --online-max-speed 0.001 --online-ground 0"};
  c.options.occluders = 1;
  c.options.leaf_size = 1;
  c.options.min_distance = 5;
  c.options.max_speed = 0.001;
  c.options.ground_occluder = false;
  return c;
}
Configuration union_of_occluders() {
  Configuration c{OnlineImageSpaceCulling::Variant::guarded, {}, "--online-leaf-size 1 --online-min-distance 5 --online-max-speed 0.001"};
  c.options.leaf_size = 1;
  c.options.min_distance = 5;
  c.options.max_speed = 0.001;
  return c;
}

}  // namespace

std::vector<ClaimCheck> check_online_claims(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ClaimCheck published, corrected, union_leak;
  published.id = "wang-2001-eq-1-single-occluder";
  published.source = "Wang, Agarwal & Har-Peled 2001, section 5.1, Eq. (1)";
  published.statement =
      "shrinking one occluder's image by Δ pixels (plus one for partly covered pixels) keeps every point it hides hidden "
      "from every viewpoint within δ = 2ΔD / (s tan(θ/2)) of the eye (D the occluder's distance, s the mask width, θ the "
      "field of view)";
  published.method = "online_is";
  corrected.id = "cullcheck-eq-1-corrected-single-occluder";
  corrected.source = "cullcheck (Eq. (1) re-derived: δ = D sin(Δω), ω the smallest angle of a mask pixel)";
  corrected.statement = "the same with δ = D sin(Δω): Δ pixels subtend at least Δω anywhere on the mask, and a point at "
                        "distance >= D turns by at most asin(δ/D) as the eye moves by δ";
  corrected.method = "online_is_guarded";
  union_leak.id = "wang-2001-union-shrinking";
  union_leak.source = "Wang, Agarwal & Har-Peled 2001, section 5.2, Fig. 5";
  union_leak.statement =
      "eroding the union of many occluders' images (not each occluder's) is still conservative over B_δ(v) with the "
      "corrected δ. The paper says it is not: shrinking the union closes the slit two overlapping occluders leave (Fig. "
      "5), so a counterexample is the leak it predicts";
  union_leak.method = "online_is_guarded";
  const std::vector<std::pair<ClaimCheck*, Configuration>> configurations = {
      {&published, single_occluder(OnlineImageSpaceCulling::Variant::published)},
      {&corrected, single_occluder(OnlineImageSpaceCulling::Variant::guarded)},
      {&union_leak, union_of_occluders()}};
  oracle::OracleOptions oracle_options;
  oracle_options.sampling = options.sampling;
  search_scenes(options.scenes, options.threads, options.shard, {&published, &corrected, &union_leak},
                "claims search: on-line image-space culling, a step within δ",
                [&, oracle_options = for_one_scene(oracle_options, options.threads, options.scenes)](int index, std::vector<ClaimCheck>& partial) {
    const SceneSource source = seeded_street_city(options.seed, index, 0x0A11E, {2, 5, 1, 4, 20, 50, 6, 16, 0.3});
    const Scene scene = source.load();
    if (scene.buildings.empty()) return;
    const generators::OpenSpace open(scene);
    const oracle::Oracle truth(scene);
    auto frustum = make_method("frustum", scene);
    generators::Random r = generators::Random::stream(options.seed, 0x0A11F, static_cast<std::uint64_t>(index));
    const Box3 area = open.bounds();
    for (int k = 0; k < options.cameras_per_scene; ++k) {
      Camera c;
      const Vec2 p = open.nudge_to_open({r.uniform_real(area.lo.x, area.hi.x), r.uniform_real(area.lo.y, area.hi.y)}, 0.05);
      c.position = {p.x, p.y, 1.7};
      c.yaw = r.uniform_real(0.0, kTwoPi);
      const double fovs[] = {kPi / 6, kPi / 3, kPi / 2};
      c.hfov = fovs[r.uniform_int(0, 2)];
      c.vfov = c.hfov * 0.75;
      const bool left = r.bernoulli(0.5);
      const double share = r.uniform_real(0.5, 0.99);  // of δ
      for (std::size_t i = 0; i < configurations.size(); ++i) {
        ClaimCheck& claim = partial[i];
        const Configuration& config = configurations[i].second;
        OnlineImageSpaceCulling method(scene, config.variant, config.options);
        method.set_frame(0, 0.0);
        method.cull(c);
        const double delta = method.last_frame().delta;
        if (method.last_frame().occluder_polygons == 0 || !(delta > 0)) continue;
        const std::vector<Move> moves = {{left ? MoveKind::left : MoveKind::right, share * delta}};
        const Camera moved = generators::apply_move(c, moves[0]);
        method.set_frame(1, 1.0 / 30.0);
        const std::vector<ObjectId> pvs = method.cull(moved).pvs;
        ++claim.frames_checked;
        const std::vector<ObjectId> lacking = missing_from(frustum->cull(moved).pvs, pvs);
        if (lacking.empty()) continue;
        oracle::OracleAnswer seen = truth.visible_set(moved, oracle_options);
        std::vector<ObjectId> missed = missing_from(seen.visible, pvs);
        // As the gate counts: a ray-sampling witness must stand re-cast in double precision.
        if (seen.sampling) std::erase_if(missed, [&](ObjectId id) { return !truth.confirm_witness(seen, id, moved).stands(); });
        claim.violations += missed.size();
        if (missed.empty() || !claim.holds) continue;
        claim.holds = false;
        claim.counterexample_replay = "cullcheck verify " + source.replay_flags() + " --path-kind moves --path-params " +
                                      shell_quote(generators::moves_params(c, moves).dump()) + " --method " + claim.method + " " +
                                      config.flags + "   # violation at frame 1";
        claim.counterexample_detail = "a step of " + std::to_string(share * delta) + " m (" + std::to_string(share) + " δ, δ = " +
                                      std::to_string(delta) + " m for the nearest occluder at " +
                                      std::to_string(method.last_frame().nearest_occluder) + " m): building " +
                                      std::to_string(missed.front()) + " seen by the oracle (" + seen.model + ") but culled" +
                                      (seen.sampling ? ": " + oracle::describe(seen.sampling->witnesses.at(missed.front())) : "");
      }
    }
  });
  const double seconds = seconds_since(start);
  published.search_seconds = corrected.search_seconds = union_leak.search_seconds = seconds;
  return {published, corrected, union_leak};
}

}  // namespace cullcheck
