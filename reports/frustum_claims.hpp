// The claims ledger's entries for frustum culling by ranges (engine/frustum/range_detection.hpp),
// each checked by the fuzzer (reports/fuzzing.hpp) holding the method to conservativeness
// (`cullcheck fuzz --method NAME --hold-conservative`): small seeded scenes and the camera paths
// frustum culling gets wrong (viewport edges, near planes, lateral moves past thin buildings,
// pitch and roll), a failure shrunk to a minimal case:
//  - sunar-rdt-outside-only: range detection as published (front test, sphere, the eight corners
//    with OUTSIDE / INSIDE / INTERSECT) drops only what lies outside the view frustum;
//  - cullcheck-rdt-corrected: the corrected rule (sphere by r / cos, a box outside one range);
//  - placeres-radar-frustum: the radar approach, bounding spheres against the ranges.
// The search is ClaimSearchOptions::scenes x cameras_per_scene cases per method, seeded by its
// seed; a refutation replays as `cullcheck gate ... --method NAME --hold-conservative`.
#pragma once

#include <vector>

#include "reports/claims.hpp"

namespace cullcheck {

std::vector<ClaimCheck> check_frustum_range_claims(const ClaimSearchOptions& options);

}  // namespace cullcheck
