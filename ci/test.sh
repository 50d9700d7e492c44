#!/usr/bin/env bash
# README command (2): install, configure, build, run every test with CTest.
# CULLCHECK_RC_BUDGET=N multiplies the property-test budgets (default 1, the CI budget).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
cmake --preset default
cmake --build --preset default -j "$(nproc)"
ctest --preset default -j "$(nproc)"
