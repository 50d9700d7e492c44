// The check every hard-case property makes: what the oracle sees from a viewpoint, the PVS
// holds. Returns the first building the oracle sees and the PVS lacks, with its witness (one that
// stands re-cast in double precision: property_oracle.hpp's confirmed_misses).
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "oracle/oracle.hpp"
#include "properties/property_oracle.hpp"

namespace cullcheck::properties {

struct OracleMiss {
  ObjectId building = 0;
  std::string witness;  // the witness ray, or the exact model's name
};

// The same for an oracle answer the caller already has (`seen`, at `viewpoint`).
inline std::optional<OracleMiss> oracle_miss(const oracle::Oracle& truth, oracle::OracleAnswer& seen, const Camera& viewpoint,
                                             const std::vector<ObjectId>& pvs) {
  const std::vector<ObjectId> missed = confirmed_misses(truth, seen, viewpoint, pvs);
  if (missed.empty()) return std::nullopt;
  const ObjectId id = missed.front();
  return OracleMiss{id, seen.sampling ? oracle::describe(seen.sampling->witnesses.at(id)) : seen.model};
}

inline std::optional<OracleMiss> oracle_miss(const oracle::Oracle& truth, const Camera& viewpoint,
                                             const std::vector<ObjectId>& pvs) {
  oracle::OracleAnswer seen = truth.visible_set(viewpoint, property_oracle());
  return oracle_miss(truth, seen, viewpoint, pvs);
}

}  // namespace cullcheck::properties
