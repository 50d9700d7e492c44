// Claims ledger entries for the incremental occlusion horizon ΔH (thesis ch. 3.1.3):
//  - "thesis-3.1.3-delta-h-lateral": the published ΔH is conservative along any walk. A seeded
//    search of lateral steps past buildings, steps wider than a building, turns across the
//    azimuth wrap and stops refutes it (Fig. 3.10), with a replay command;
//  - "delta-h-guarded-equals-oh-os": the guarded ΔH gives full OH(OS)'s PVS at every frame of
//    the same paths (so it is as conservative as OH(OS)).
#pragma once

#include <vector>

#include "reports/claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> check_delta_horizon_claims(const ClaimSearchOptions& options);

}  // namespace cullcheck
