#!/usr/bin/env bash
# README command (2): install, configure, build, run every test with CTest; then the same tests
# again under AddressSanitizer + UndefinedBehaviorSanitizer (clang-14, the "sanitize" preset,
# build-sanitize/, no benchmarks), with the libFuzzer harnesses of every reader (fuzz/).
# CULLCHECK_RC_BUDGET=N multiplies the property-test budgets (default 1, the CI budget); with
# N > 1 every property binary is split into 2 x nproc CTest tests (GoogleTest shards,
# properties/CMakeLists.txt) so that the long run uses every core; CULLCHECK_PROPERTY_SHARDS=M
# chooses M instead (1: unsharded).
# CULLCHECK_FUZZ_SECONDS=N fuzzes each reader for N seconds (default 5).
# CULLCHECK_SKIP_SANITIZE=1 stops after the default build's tests.
# The sanitizer run looks for memory and undefined-behaviour errors on the code paths the default
# run has already held to the properties, so its property tests run half the cases
# (CULLCHECK_SANITIZE_RC_BUDGET, default half of CULLCHECK_RC_BUDGET; the whole budget: set it
# equal). Every test still runs, and every hard-case floor still applies.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
budget=${CULLCHECK_RC_BUDGET:-1}
shards=1
[[ "$budget" =~ ^[0-9]+$ ]] && [ "$budget" -gt 1 ] && shards=$((2 * $(nproc)))
shards=${CULLCHECK_PROPERTY_SHARDS:-$shards}
cmake --preset default -DCULLCHECK_PROPERTY_SHARDS="$shards"
cmake --build --preset default -j "$(nproc)"
ctest --preset default -j "$(nproc)"
[ "${CULLCHECK_SKIP_SANITIZE:-0}" = 1 ] && exit 0
cmake --preset sanitize -DCULLCHECK_PROPERTY_SHARDS="$shards"
cmake --build --preset sanitize -j "$(nproc)"
sanitize_budget=${CULLCHECK_SANITIZE_RC_BUDGET:-$(awk -v b="$budget" 'BEGIN { print b / 2 }')}
CULLCHECK_RC_BUDGET=$sanitize_budget ctest --preset sanitize -j "$(nproc)"
