// The claims ledger's entries for on-line image-space culling (Wang, Agarwal & Har-Peled 2001,
// section 5.1-5.2), each searched with the real method along two-frame walks (a critical frame
// at v, then a sideways step to v' inside B_δ(v) before the stamp expires) and judged by the
// oracle at v'; a counterexample replays as `cullcheck verify ... --path-kind moves`:
//  - wang-2001-eq-1-single-occluder: Eq. (1) as printed, δ = 2 Δ D / (s tan(θ/2)): the image of
//    ONE occluder polygon (R = 1, ρ = 1, no ground) eroded by Δ (+1) hides nothing visible from
//    any viewpoint of B_δ(v) (online_is);
//  - cullcheck-eq-1-corrected-single-occluder: the same with δ = D sin(Δ ω) (online_is_guarded);
//  - wang-2001-union-shrinking: the same guarded method with its full occluder set (R = 1500):
//    eroding the UNION of the projections is conservative over B_δ(v). The paper says it is not
//    (Fig. 5: a slit two occluders leave between them is closed by shrinking their union), so a
//    counterexample here is the leak it predicts, found by search and kept as a replay.
#pragma once

#include <vector>

#include "reports/claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> check_online_claims(const ClaimSearchOptions& options);

}  // namespace cullcheck
