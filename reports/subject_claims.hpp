// The claims ledger's entries for outside subjects: what each declared (conservative, or
// approximate within a pixel budget) and whether the oracle confirms it, with the replay of the
// first counterexample.
#pragma once

#include <vector>

#include "reports/claims.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

std::vector<ClaimCheck> subject_claims(const PathVerification& v);

}  // namespace cullcheck
