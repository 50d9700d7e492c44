// The claims ledger's entry for polar diagrams (Ortega, Rueda and Feito, section 4): the fan of
// rays finds exactly the visible set of a 2D scene (every visible object, and nothing hidden).
// Checked against CGAL's exact visibility polygon (oracle/exact_2d.hpp) over seeded slot cities
// (generators/plan_scenes.hpp: shared and collinear walls, T-junctions, pockets, stars) from eyes
// on the half-metre grid and anywhere, all round and in wedges. A counterexample replays as
// `cullcheck gate --generator slot_city ... --method polar_diagram` (the gate holds the method to
// the ray oracle where the plan view is exact, as it is in a slot city from an eye below the roofs).
#pragma once

#include <vector>

#include "reports/claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> check_polar_claims(const ClaimSearchOptions& options);

}  // namespace cullcheck
