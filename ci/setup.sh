#!/usr/bin/env bash
# README command (1): install the Debian packages, configure, build, then run the main job on
# the built-in default city (generate it, run every engine method, run the oracle, print the
# summary table, write report.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
cmake --preset default
cmake --build --preset default -j "$(nproc)"
# Also thesis Table 4.1 on its plaza walk, the view-cell PVSs of every 10th street cell, and VbAoI
# on its own 10,086-building city with 10, 100 and 1,000 clients.
./build/apps/cullcheck/cullcheck report --table-4-1 --view-cells --view-cell-stride 10 --view-cell-oracle-cells 3 \
  --vbaoi --output report.json
