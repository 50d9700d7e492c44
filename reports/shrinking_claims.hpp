// Claims ledger entries for from-region PVS by shrinking (thesis ch. 4.1): each variant's claim
// that its PVS holds every building visible from any viewpoint of the ε-disc, searched over
// seeded Manhattan cities with narrow streets and thin slabs, street-level cameras, ε from a
// pedestrian's step to wider than a street, viewpoints on the disc's edge and inside it:
//  - "thesis-4.1.2-adjustable-shrinking": the published Eq. 4-16 over any disc;
//  - "thesis-4.1.2-adjustable-shrinking-open-disc": the same, only discs that lie in open ground
//    (a walker's region: the disc touches no building);
//  - "wonka-former-shrinking" and "cullcheck-certified-shrinking": the other two variants.
// The oracle is asked only where a viewpoint's OH(OS) PVS holds a building the region PVS lacks.
#pragma once

#include <vector>

#include "reports/claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> check_shrinking_claims(const ClaimSearchOptions& options);

}  // namespace cullcheck
