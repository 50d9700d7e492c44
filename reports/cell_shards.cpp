#include "reports/cell_shards.hpp"

#include <cstdint>
#include <set>

#include "core/errors.hpp"
#include "core/shard.hpp"
#include "reports/shard_merge.hpp"

namespace cullcheck {

nlohmann::json merge_cell_shards(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names) {
  using nlohmann::json;
  std::vector<std::string> ordered_names;
  const std::vector<const json*> shards = shards_in_order(documents, names, &ordered_names);
  const std::size_t cell_samples = (*shards[0])["shard"].at("cell_samples").get<std::size_t>();
  std::set<std::uint64_t> pvs, pvs_n;
  std::size_t samples = 0;
  std::uint64_t tested = 0, accepted = 0;
  double cull_ms = 0.0;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const json& d = *shards[k];
    const Shard shard{k, shards.size()};
    const std::size_t expected = shard.share(cell_samples);
    if (d["shard"].at("cell_samples").get<std::size_t>() != cell_samples || d.at("samples").get<std::size_t>() != expected)
      throw InputError(ordered_names[k], "samples",
                       "is " + d.at("samples").dump() + ", shard " + shard.text() + " of a cell of " + std::to_string(cell_samples) +
                           " samples computes " + std::to_string(expected));
    for (const json& id : d.at("pvs")) pvs.insert(id.get<std::uint64_t>());
    if (d.contains("pvs_n"))
      for (const json& id : d.at("pvs_n")) pvs_n.insert(id.get<std::uint64_t>());
    samples += expected;
    tested += d.at("buildings_tested").get<std::uint64_t>();
    accepted += d.at("accepted_untested").get<std::uint64_t>();
    cull_ms += d.at("cull_ms").get<double>();
  }
  json out = *shards[0];
  out.erase("shard");
  out["samples"] = samples;
  out["pvs"] = std::vector<std::uint64_t>(pvs.begin(), pvs.end());
  out["pvs_size"] = pvs.size();
  if (out.contains("pvs_n")) {
    out["pvs_n"] = std::vector<std::uint64_t>(pvs_n.begin(), pvs_n.end());
    out["pvs_n_size"] = pvs_n.size();
  }
  out["buildings_tested"] = tested;
  out["accepted_untested"] = accepted;
  out["cull_ms"] = cull_ms;
  return out;
}

}  // namespace cullcheck
