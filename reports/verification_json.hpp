// A PathVerification as JSON, losslessly (every field, doubles written so they read back equal):
// what a shard file carries so `cullcheck merge` can rebuild the run's results without the scene.
#pragma once

#include <nlohmann/json.hpp>

#include "reports/claims.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

nlohmann::json verification_to_json(const PathVerification& v);
// Throws InputError (object `what`) when a field is missing or of the wrong type.
PathVerification verification_from_json(const nlohmann::json& j, const std::string& what);

// A claim with its search's raw result (the lowest refuting scene), and back.
nlohmann::json claim_to_raw_json(const ClaimCheck& c);
ClaimCheck claim_from_raw_json(const nlohmann::json& j, const std::string& what);

}  // namespace cullcheck
