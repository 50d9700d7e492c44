#!/usr/bin/env bash
# README command (2): install, configure, build, run every test with CTest; then the same tests
# again under AddressSanitizer + UndefinedBehaviorSanitizer (clang-14, the "sanitize" preset,
# build-sanitize/, no benchmarks), with the libFuzzer harnesses of every reader (fuzz/).
# CULLCHECK_RC_BUDGET=N multiplies the property-test budgets (default 1, the CI budget).
# CULLCHECK_FUZZ_SECONDS=N fuzzes each reader for N seconds (default 5).
# CULLCHECK_SKIP_SANITIZE=1 stops after the default build's tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
cmake --preset default
cmake --build --preset default -j "$(nproc)"
ctest --preset default -j "$(nproc)"
[ "${CULLCHECK_SKIP_SANITIZE:-0}" = 1 ] && exit 0
cmake --preset sanitize
cmake --build --preset sanitize -j "$(nproc)"
ctest --preset sanitize -j "$(nproc)"
