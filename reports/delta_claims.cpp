#include "reports/delta_claims.hpp"
#include "core/elapsed.hpp"
#include "core/progress.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>

#include "engine/method.hpp"
#include "generators/camera_moves.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/open_space.hpp"
#include "generators/random.hpp"
#include "oracle/oracle.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {
namespace {

using generators::Move;
using generators::MoveKind;

// Manhattan blocks with narrow streets and thin slabs: what a lateral step can uncover.
SceneSource lateral_move_scene(std::uint64_t seed, int index) {
  return seeded_street_city(seed, index, 0xDE17A, {2, 5, 1, 4, 20, 50, 6, 16, 0.5});
}

// 1-8 sideways steps (Fig. 3.10's case), from a pedestrian frame to past a building, with stops
// between some; nothing else moves, so a miss is the lateral failure itself.
std::vector<Move> search_moves(generators::Random& r) {
  std::vector<Move> moves(static_cast<std::size_t>(r.uniform_int(1, 8)));
  const double steps[] = {0.05, 0.5, 1.0, 2.0, 4.0, 8.0, 12.0};
  for (Move& m : moves) {
    if (r.uniform01() < 0.15) m = {MoveKind::stop, 0.0};
    else m = {r.bernoulli(0.5) ? MoveKind::left : MoveKind::right, steps[r.uniform_int(0, 6)]};
  }
  return moves;
}

std::string replay(const SceneSource& scene, const nlohmann::json& params, const std::string& method) {
  return "cullcheck verify " + scene.replay_flags() + " --path-kind moves --path-params " + shell_quote(params.dump()) +
         " --method " + method;
}

}  // namespace

std::vector<ClaimCheck> check_delta_horizon_claims(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ClaimCheck published, guarded;
  published.id = "thesis-3.1.3-delta-h-lateral";
  published.source = "thesis ch. 3.1.3 (steps 1-5), Fig. 3.10";
  published.statement =
      "ΔH as published (skip what lies behind the parts of the horizon that rose since the last frame) culls nothing "
      "visible when the viewer steps sideways";
  published.method = "delta_h_thesis";
  guarded.id = "delta-h-guarded-equals-oh-os";
  guarded.source = "cullcheck (guard for thesis ch. 3.1.3 / Fig. 3.10)";
  guarded.statement = "the guarded ΔH gives the PVS of full OH(OS) at every frame of the same paths";
  guarded.method = "delta_h_guarded";
  oracle::OracleOptions oracle_options;
  oracle_options.sampling = options.sampling;
  search_scenes(options.scenes, options.threads, options.shard, {&published, &guarded}, "claims search: ΔH from a lateral move",
                [&options, oracle_options = for_one_scene(oracle_options, options.threads, options.scenes)](int index, std::vector<ClaimCheck>& partial) {
    ClaimCheck& published = partial[0];
    ClaimCheck& guarded = partial[1];
    const SceneSource source = lateral_move_scene(options.seed, index);
    const Scene scene = source.load();
    if (scene.buildings.empty()) return;
    const generators::OpenSpace open(scene);
    const oracle::Oracle truth(scene);
    generators::Random r = generators::Random::stream(options.seed, 0xDE17B, static_cast<std::uint64_t>(index));
    const Box3 area = open.bounds();
    for (int k = 0; k < options.cameras_per_scene; ++k) {
      Camera c;
      const Vec2 p = open.nudge_to_open({r.uniform_real(area.lo.x, area.hi.x), r.uniform_real(area.lo.y, area.hi.y)}, 0.05);
      c.position = {p.x, p.y, 1.7};
      c.yaw = r.bernoulli(0.3) ? 0.0 : r.uniform_real(0.0, kTwoPi);  // yaw 0 sits on the azimuth wrap
      c.hfov = r.bernoulli(0.5) ? kPi / 6 : kPi / 2;
      c.vfov = c.hfov / 2;
      const std::vector<Move> moves = search_moves(r);
      const nlohmann::json params = generators::moves_params(c, moves);
      const CameraPath path = generators::path_of_moves(c, moves);
      auto full = make_method("oh_os_conservative", scene);
      auto thesis = make_method("delta_h_thesis", scene);
      auto fixed = make_method("delta_h_guarded", scene);
      for (std::size_t f = 0; f < path.frames.size(); ++f) {
        const std::vector<ObjectId> reference = full->cull(path.frames[f]).pvs;
        const std::vector<ObjectId> pvs = thesis->cull(path.frames[f]).pvs;
        ++published.frames_checked;
        ++guarded.frames_checked;
        if (fixed->cull(path.frames[f]).pvs != reference) {
          ++guarded.violations;
          if (guarded.holds) {
            guarded.holds = false;
            guarded.counterexample_replay = replay(source, params, "delta_h_guarded,oh_os_conservative");
            guarded.counterexample_detail = "frame " + std::to_string(f) + ": PVS differs from full OH(OS)";
          }
        }
        // Only where the published ΔH keeps less than OH(OS) (conservative) can it miss anything.
        std::vector<ObjectId> lacking;
        std::set_difference(reference.begin(), reference.end(), pvs.begin(), pvs.end(), std::back_inserter(lacking));
        if (lacking.empty()) continue;
        const oracle::OracleAnswer seen = truth.visible_set(path.frames[f], oracle_options);
        for (ObjectId id : lacking) {
          if (!std::binary_search(seen.visible.begin(), seen.visible.end(), id)) continue;
          ++published.violations;
          if (published.holds) {
            published.holds = false;
            published.counterexample_replay = replay(source, params, "delta_h_thesis");
            const Move& last = moves[f > 0 ? f - 1 : 0];
            published.counterexample_detail = "frame " + std::to_string(f) + " (after " + to_string(last.kind) + " " +
                                              std::to_string(last.amount) + "): building " +
                                              std::to_string(id) + " seen by the oracle (" + seen.model + ") but culled";
          }
        }
      }
    }
    });
  const double seconds = seconds_since(start);
  published.search_seconds = guarded.search_seconds = seconds;
  return {published, guarded};
}

}  // namespace cullcheck
