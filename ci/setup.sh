#!/usr/bin/env bash
# README command (1): install the Debian packages, configure, build, then run the main job on
# the built-in default city (generate it, run every engine method, run the oracle, print the
# summary table, write report.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
cmake --preset default
cmake --build --preset default -j "$(nproc)"
./build/apps/cullcheck/cullcheck report --output report.json
