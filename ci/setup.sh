#!/usr/bin/env bash
# README command (1): install the Debian packages, configure, build, then run the main job on
# the built-in default city (generate it, run every engine method, run the oracle, print the
# summary table, write report.json).
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
cmake --preset default
cmake --build --preset default -j "$(nproc)"
# Also thesis Table 4.1 on its plaza walk, the view-cell PVSs of every 10th street cell, VbAoI
# on its own 10,086-building city with 10, 100 and 1,000 clients, a built-in method run through
# the subject protocol beside itself (the same PVS at every frame), and the fuzzer on the buggy
# example subject (its shrunk counterexample in cullcheck-counterexample/; a finding about the
# example, reported in report.json's "fuzz" and the claims ledger, not a failure of the gate),
# and a short soak of the built-in conservative methods (report.json's "soak"); the report page
# report.html (reports/html/: opens offline) and its screenshot, with the region radius sweep
# and the knobs' sweeps on its Pareto plot; thesis Table 3.3 in kind (radar echo over a generated
# terrain of the thesis's size, and over the Rainier elevation model when ../shared/data holds it),
# its echo PNGs beside report.json; polar diagrams (Ortega et al.) against CGAL's exact
# visibility polygon on the default city and on a city like the paper's; the methods on a
# 300-frame street walk of the 160,000-building thesis city (report.json's "scaling", from which
# speed_targets reads the guarded ΔH's speed over OH(OS)).
radar_dem=()
rainier=../shared/data/real/dem_mt_rainier/mt_rainier_90m.tif
[ -f "$rainier" ] && radar_dem=(--radar-dem "$rainier")
./build/apps/cullcheck/cullcheck report --table-4-1 --view-cells --view-cell-stride 10 --view-cell-oracle-cells 3 \
  --vbaoi --subject build/examples/subjects/builtin_subject \
  --fuzz-subject build/examples/subjects/buggy_sphere_subject --fuzz-budget 200 --fuzz-seed 1 --soak-budget 2000 \
  --region-sweep 0.5,1,1.41,2,4 --knob-sweep horizon_bins=1024,4096,16384 --knob-sweep quadtree_leaf_size=2,8,32 \
  --knob-sweep delta_radius=0.05,0.25,0.5 --scaling-grids 400 --scaling-frames 300 --radar-table "${radar_dem[@]}" --polar-table --slice-table --slice-frames 300 --slice-oracle-cells 2 \
  --oracle-stride 1 --output report.json --html report.html
# The page's screenshot beside it (headless Chromium; the browser test keeps one of a short run too).
chromium --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --hide-scrollbars --window-size=1280,2400 \
  --screenshot="$PWD/report-page.png" "file://$PWD/report.html" 2>/dev/null >/dev/null && echo "wrote report-page.png"
