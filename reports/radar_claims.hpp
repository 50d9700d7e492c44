// The claims ledger's entries for radar echo over terrain (thesis ch. 3.3.2), searched over
// seeded generated terrains (fractal, ridged, terraces, flat; some with NoData holes, some with a
// small city standing on them), each with
// transmitters anywhere, on a vertex and on the highest crest, 2 m to 500 m above the ground,
// grids from 1 x 1 to 24 x 24 cells and sectors; every rule held to the terrain oracle:
//  - thesis-3.3-radar-echo: the published rule "finds all visible primitives";
//  - thesis-3.3-c2-cell-bound, -vertex-test, -beta-min-shadow, -immediate-merge: each of its four
//    choices alone, the other three conservative (so a refutation names the choice that loses
//    triangles; β_min was examined for prisms in ch. 3.1.2, not for triangles);
//  - cullcheck-radar-conservative: the conservative rule (engine/radar/radar_echo.hpp).
// A counterexample replays as `cullcheck radar ... --rule NAME`.
#pragma once

#include <vector>

#include "reports/claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> check_radar_claims(const ClaimSearchOptions& options);

}  // namespace cullcheck
