// Joining `cullcheck cell --shard K/N` files: each shard computed the n-th samples of one view
// cell with n mod N = K, so the cell's PVS (and PVSn) is the union of theirs. The merged result
// is what the unsharded `cell` prints, but for the work counts (`buildings_tested`,
// `accepted_untested`: a shard carries decisions only between its own samples) and `cull_ms`,
// which are the shards' sums.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cullcheck {

// Throws InputError naming the file when the files are not every shard of one cell run (see
// shards_in_order), or a shard's sample count is not its share of the cell's.
nlohmann::json merge_cell_shards(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names);

}  // namespace cullcheck
