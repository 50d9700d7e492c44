// The oracle's density for properties: coarser than the report's (cases are many), still dense
// enough that a culled visible building is very likely witnessed; one thread per case.
// Replays of property failures name the same density: --spacing 3 --frustum-resolution 128.
#pragma once

#include <algorithm>
#include <vector>

#include "oracle/oracle.hpp"

namespace cullcheck {

inline oracle::OracleOptions property_oracle() {
  oracle::OracleOptions o;
  o.sampling.spacing_m = 3.0;
  o.sampling.frustum_resolution = 128;
  o.sampling.threads = 1;
  return o;
}

// What the oracle saw and `pvs` (sorted) lacks, as the gate counts it: a ray-sampling witness must
// stand re-cast in double precision (Oracle::confirm_witness; the oracle casts in single precision),
// so a rounding artefact of the oracle's fails no property. The exact 2D model's misses all count.
// Dropped witnesses are counted in answer.witness_recheck.
inline std::vector<ObjectId> confirmed_misses(const oracle::Oracle& truth, oracle::OracleAnswer& answer, const Camera& camera,
                                              const std::vector<ObjectId>& pvs) {
  std::vector<ObjectId> missed;
  std::set_difference(answer.visible.begin(), answer.visible.end(), pvs.begin(), pvs.end(), std::back_inserter(missed));
  if (answer.sampling)
    std::erase_if(missed, [&](ObjectId id) { return !truth.confirm_witness(answer, id, camera).stands(); });
  return missed;
}

}  // namespace cullcheck
