#include "reports/shrinking_claims.hpp"
#include "core/elapsed.hpp"
#include "core/progress.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>

#include "core/scene_io.hpp"
#include "engine/method.hpp"
#include "generators/kept_cases.hpp"
#include "generators/open_space.hpp"
#include "generators/random.hpp"
#include "oracle/oracle.hpp"
#include "reports/scene_source.hpp"
#include "reports/verification.hpp"

namespace cullcheck {
namespace {

// Manhattan blocks with narrow streets and thin slabs, where a disc can reach across a street.
SceneSource search_scene(std::uint64_t seed, int index) {
  return seeded_street_city(seed, index, 0x5A41C, {3, 6, 2, 4, 20, 40, 6, 14, 0.3});
}

struct Variant {
  ClaimCheck claim;
  std::string method;
  bool open_discs_only;
};

}  // namespace

std::vector<ClaimCheck> check_shrinking_claims(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Variant> variants(5);
  auto set = [](Variant& v, const char* id, const char* source, const char* statement, const char* method, bool open) {
    v.claim.id = id;
    v.claim.source = source;
    v.claim.statement = statement;
    v.claim.method = method;
    v.method = method;
    v.open_discs_only = open;
  };
  set(variants[0], "thesis-4.1.2-adjustable-shrinking", "thesis ch. 4.1.2, Eq. 1-16, Fig. 4.4-4.6",
      "a PVS computed with occluder shadows shrunk by Eq. 4-16 holds everything visible from any viewpoint of the "
      "ε-disc", "shrink_adjustable_thesis", false);
  set(variants[1], "thesis-4.1.2-adjustable-shrinking-open-disc", "thesis ch. 4.1.2, Eq. 1-16",
      "the same, for discs that lie in open ground (a walker's region)", "shrink_adjustable_thesis", true);
  set(variants[2], "wonka-former-shrinking", "thesis ch. 4.1.1 (Wonka et al.)",
      "a PVS computed with occluders shrunk by ε holds everything visible from any viewpoint of the ε-disc",
      "shrink_former", false);
  set(variants[3], "cullcheck-certified-shrinking", "cullcheck (region certificate, engine/delta_horizon/)",
      "the certified region PVS holds everything visible from any viewpoint of the ε-disc",
      "shrink_adjustable_conservative", false);
  set(variants[4], "cullcheck-corrected-adjustable-shrinking", "cullcheck (thesis Eq. 4-16 corrected, region_shrinking.hpp)",
      "the published method with the conservative shadow rule, Eq. 13-14 with h_C - h_X and shadows merged 2ε late holds "
      "everything visible from any viewpoint of the ε-disc",
      "shrink_adjustable_corrected", false);
  oracle::OracleOptions oracle_options;
  oracle_options.sampling = options.sampling;
  // The kept counterexamples first (generators/kept_cases.hpp): small hand-built scenes a seeded
  // street city never builds (a planter 1 m from the eye), each with the viewpoint that refutes.
  // They are shard 0's (a counterexample found here is the search's first: its scene is -1).
  for (const std::string& name : options.shard.index == 0 ? generators::kept_case_names() : std::vector<std::string>{}) {
    const generators::KeptRegionQuery q = generators::kept_region_query(name);
    SceneSource source;
    source.generator = "kept";
    source.seed = 0;
    source.parameters_json = nlohmann::json{{"case", name}}.dump();
    const Scene scene = source.load();
    const oracle::OracleAnswer seen = oracle::Oracle(scene).visible_set(q.from, oracle_options);
    for (Variant& variant : variants) {
      if (variant.open_discs_only && !q.disc_in_open_ground) continue;
      ++variant.claim.frames_checked;
      const std::vector<ObjectId> pvs = make_region_method(variant.method, scene)->cull_region({q.centre, q.radius, 0.0}).pvs;
      for (ObjectId id : missing_from(seen.visible, pvs)) {
        ++variant.claim.violations;
        if (!variant.claim.holds) continue;
        variant.claim.holds = false;
        variant.claim.counterexample_replay = region_replay_command(source, variant.method, q.centre, q.radius, 0.0, q.from);
        variant.claim.counterexample_detail = "building " + std::to_string(id) + " seen by the oracle (" + seen.model +
                                              ") from the disc's edge, ε = " + round_trip_text(q.radius) +
                                              " m, kept case '" + name + "'" +
                                              (q.disc_in_open_ground ? " (open disc)" : " (the disc crosses a building)");
      }
    }
  }
  const double radii[] = {0.5, 2.0, 8.0};
  std::vector<ClaimCheck*> claims;
  for (Variant& v : variants) claims.push_back(&v.claim);
  search_scenes(options.scenes, options.threads, options.shard, claims, "claims search: region shrinking",
                [&options, &variants, &radii, oracle_options = for_one_scene(oracle_options, options.threads, options.scenes)](
                    int index, std::vector<ClaimCheck>& partial) {
    const SceneSource source = search_scene(options.seed, index);
    const Scene scene = source.load();
    if (scene.buildings.empty()) return;
    const generators::OpenSpace open(scene);
    const oracle::Oracle truth(scene);
    auto point = make_method("oh_os_conservative", scene);
    std::vector<std::unique_ptr<RegionCullingMethod>> engines;
    for (const Variant& v : variants) engines.push_back(make_region_method(v.method, scene));
    generators::Random r = generators::Random::stream(options.seed, 0x5A41D, static_cast<std::uint64_t>(index));
    const Box3 area = open.bounds();
    for (int k = 0; k < options.cameras_per_scene; ++k) {
      Camera centre;
      const Vec2 p = open.nudge_to_open({r.uniform_real(area.lo.x, area.hi.x), r.uniform_real(area.lo.y, area.hi.y)}, 0.05);
      centre.position = {p.x, p.y, 1.7};
      centre.yaw = r.uniform_real(0.0, kTwoPi);
      centre.hfov = r.bernoulli(0.3) ? kTwoPi : (r.bernoulli(0.5) ? kPi / 3 : kPi / 2);
      centre.vfov = centre.omnidirectional() ? kPi / 2 : centre.hfov * 0.75;
      const double radius = radii[r.uniform_int(0, 2)];
      const double phase = r.uniform_real(0.0, kTwoPi);
      std::vector<Camera> viewpoints;
      bool open_disc = true;
      for (int j = 0; j < 24; ++j) {
        const double a = phase + j * kTwoPi / 24;
        const Vec2 q{p.x + radius * std::cos(a), p.y + radius * std::sin(a)};
        open_disc = open_disc && open.is_open(q, 0.1) && open.is_open(p + (q - p) * 0.5, 0.1);
        if (j % 3 == 0) {
          Camera v = centre;
          v.position = {q.x, q.y, centre.position.z};
          viewpoints.push_back(v);
        }
      }
      for (std::size_t m = 0; m < variants.size(); ++m) {
        const Variant& variant = variants[m];
        ClaimCheck& claim = partial[m];
        if (variant.open_discs_only && !open_disc) continue;
        const ViewRegion region{centre, radius, 0.0};
        const std::vector<ObjectId> pvs = engines[m]->cull_region(region).pvs;
        for (const Camera& v : viewpoints) {
          ++claim.frames_checked;
          const std::vector<ObjectId> kept = point->cull(v).pvs;
          std::vector<ObjectId> lacking;
          std::set_difference(kept.begin(), kept.end(), pvs.begin(), pvs.end(), std::back_inserter(lacking));
          if (lacking.empty()) continue;
          const oracle::OracleAnswer seen = truth.visible_set(v, oracle_options);
          for (ObjectId id : lacking) {
            if (!std::binary_search(seen.visible.begin(), seen.visible.end(), id)) continue;
            ++claim.violations;
            if (!claim.holds) continue;
            claim.holds = false;
            claim.counterexample_replay = region_replay_command(source, variant.method, centre, radius, 0.0, v);
            claim.counterexample_detail = "building " + std::to_string(id) + " seen by the oracle (" + seen.model +
                                                  ") from the disc's edge, ε = " + std::to_string(radius) + " m" +
                                                  (open_disc ? " (open disc)" : " (the disc touches a building)");
          }
        }
      }
    }
    });
  const double seconds = seconds_since(start);
  std::vector<ClaimCheck> out;
  for (Variant& v : variants) {
    v.claim.search_seconds = seconds;
    out.push_back(v.claim);
  }
  return out;
}

}  // namespace cullcheck
