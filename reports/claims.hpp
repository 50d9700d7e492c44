// The claims ledger (design: "Reports"): each paper claim checked so far, whether the oracle
// confirms it, and for a refuted claim the replay command of a counterexample.
//
// Claims are checked by a deterministic, budgeted search over generated scenes and cameras
// (seeded: the same budget and seed find the same counterexample on every machine).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <functional>
#include <string>
#include <vector>

#include "core/shard.hpp"
#include "oracle/oracle.hpp"
#include "oracle/sampling.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

struct ClaimSearchOptions {
  std::uint64_t seed = 1;
  int scenes = 12;             // generated scenes searched
  int cameras_per_scene = 16;  // rooftop cameras per scene; 4x as many near-roof ones, half as many fly-through frames
  oracle::SamplingOptions sampling;
  unsigned threads = 0;        // scenes searched at once; 0: every core. The ledger is the same for any number.
  Shard shard;                 // search only the scenes whose index is this shard's (core/shard.hpp)
};

struct ClaimCheck {
  std::string id;         // e.g. "thesis-3.1.2-shadow-elevation-rule"
  std::string source;     // paper and section
  std::string statement;  // the claim, in our words
  std::string method;     // the engine method that embodies it
  bool holds = true;
  std::uint64_t frames_checked = 0;
  std::uint64_t violations = 0;
  std::string counterexample_replay;  // empty when the claim held
  std::string counterexample_detail;
  double search_seconds = 0.0;
  // The scene (search_scenes' index) the counterexample came from, -1 for none: shards of a
  // search keep the counterexample of the lowest one (merge_claims).
  int counterexample_scene = -1;
};

nlohmann::json to_json(const ClaimCheck& claim);

// A claim search over scenes 0 .. scenes - 1 on `threads` threads (0: every core): search(index,
// partial) checks one scene into `partial`, copies of `claims` with no result yet (same order).
// The partials are folded into `claims` in scene order: frames and violations added, a refuted
// claim's counterexample the one of the lowest scene that refuted it. So the ledger is what one
// thread searching the scenes in order writes, for any number of threads. The oracle's own
// threads are 1 within a search on more than one thread (`threaded` says which).
// The oracle's options within one scene of search_scenes: its own threads 1 when scenes run at once.
oracle::OracleOptions for_one_scene(oracle::OracleOptions options, unsigned threads, int scenes);
// Only the scenes `shard` owns are searched (the others add nothing).
void search_scenes(int scenes, unsigned threads, const Shard& shard, const std::vector<ClaimCheck*>& claims, const std::string& stage,
                   const std::function<void(int index, std::vector<ClaimCheck>& partial)>& search);

// A seeded Manhattan city for a claim search: sizes drawn (in this order) from the ranges by the
// stream (seed, tag, index), scene seed seed * 1000 + index.
struct StreetCityRanges {
  int min_blocks, max_blocks, min_lots, max_lots, min_block, max_block, min_street, max_street;
  double thin_fraction;
};

SceneSource seeded_street_city(std::uint64_t seed, int index, std::uint64_t tag, const StreetCityRanges& ranges);

// The shadow-elevation rule of thesis ch. 3.1.2 (β_min from the two tangent vertices) against
// the far-chain bound, over scenes with occluders below and above the eye (plazas with kiosks,
// low and tall buildings) and cameras from street level to above the rooftops.
std::vector<ClaimCheck> check_shadow_elevation_rule(const ClaimSearchOptions& options);

// OH(IS), Downs et al.'s horizon built in the view plane (thesis ch. 3.1.1, Fig. 3.3), over the
// same scenes: street-level and rooftop cameras, each once pitched and/or rolled and once level.
// Two checks: "downs-oh-is-pitch-roll" (the view-plane horizon stays conservative under pitch and
// roll; refuted with a replay when the oracle sees a building it culled from a tilted camera) and
// "downs-oh-is-level-cameras" (conservative for level cameras, its 4-DoF claim; expected to hold).
std::vector<ClaimCheck> check_image_space_pitch_roll(const ClaimSearchOptions& options);

}  // namespace cullcheck
