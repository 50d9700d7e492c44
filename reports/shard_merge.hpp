// Joining the results of a run's shards (core/shard.hpp) into the results of the unsharded run.
// Every shard ran the methods along the whole path, so what is per frame (times, PVS sizes,
// comparisons with the reference) is taken from shard 0, after checking the others agree on
// everything but times; what is per checked frame (the oracle's, the pixel oracle's, violations,
// the map's frame) is interleaved by frame number, and counts are added. The result is what one
// run writes, timings aside: the violations kept are the first ones, the snapshot the worst
// (earliest of equals), a claim's counterexample the one of the lowest scene.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reports/claims.hpp"
#include "reports/knob_sweep.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

// N shard files (their JSON, named for errors) in shard order: each holds "shard" with an index
// and a count, the count is N, each index comes once, and all have shard 0's "shard.identity".
// Throws InputError naming the file otherwise.
std::vector<const nlohmann::json*> shards_in_order(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names,
                                                   std::vector<std::string>* names_in_order = nullptr);
// The first key whose value differs between two objects ("" when none), for errors that say what differs.
std::string first_difference(const nlohmann::json& a, const nlohmann::json& b);

// `shards[k]` is shard k of shards.size(), run with the same options. Throws InputError when
// they cannot be one run's shards (different methods or frames, a PVS that differs between them:
// a method that is not deterministic, or checked frames that are not the shard's share).
PathVerification merge_verifications(const std::vector<PathVerification>& shards, std::size_t max_replays);
// The same claims searched by each shard, in the same order.
std::vector<ClaimCheck> merge_claims(const std::vector<std::vector<ClaimCheck>>& shards);
// The same knob-sweep rows from each shard, in the same order.
std::vector<KnobRow> merge_knob_rows(const std::vector<std::vector<KnobRow>>& shards);

}  // namespace cullcheck
