#!/usr/bin/env bash
# End-to-end checks of the `cullcheck` program: every subcommand runs, bad input gives one clear
# line and exit 2, a failed run never clobbers a file already written, output is deterministic.
# Usage: cli_test.sh /path/to/cullcheck
set -u
cc="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
pass() { passes=$((passes + 1)); }
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

expect_exit() {  # expected-code description command...
  local want=$1 what=$2
  shift 2
  "$@" >"$work/out" 2>"$work/err"
  local got=$?
  if [ "$got" -ne "$want" ]; then
    fail "$what: exit $got, expected $want"; sed 's/^/  | /' "$work/err" | head -5
  else
    pass
  fi
}

expect_error_names() {  # description text-that-must-appear
  if grep -q -- "$2" "$work/err"; then pass; else fail "$1: stderr lacks '$2'"; sed 's/^/  | /' "$work/err" | head -3; fi
}

for sub in generate cull verify report region cell vbaoi; do expect_exit 0 "$sub --help" "$cc" "$sub" --help; done

# generate: deterministic bytes, OBJ and path outputs.
expect_exit 0 "generate" "$cc" generate --generator manhattan --seed 5 --params '{"blocks_x":2,"blocks_y":2}' \
  -o "$work/a.json" --obj "$work/a.obj" --path-output "$work/path.json"
expect_exit 0 "generate again" "$cc" generate --generator manhattan --seed 5 --params '{"blocks_x":2,"blocks_y":2}' -o "$work/b.json"
if cmp -s "$work/a.json" "$work/b.json"; then pass; else fail "same seed gave different scene files"; fi
[ -s "$work/a.obj" ] && pass || fail "no OBJ written"
[ -s "$work/path.json" ] && pass || fail "no path written"

# cull and verify on the written scene.
camera='{"position":[0,0,1.7],"yaw":0.3,"hfov":1.2,"vfov":0.8}'
expect_exit 0 "cull" "$cc" cull --scene "$work/a.json" --method oh_os_conservative --camera "$camera"
grep -q '"pvs"' "$work/out" && pass || fail "cull printed no pvs"
expect_exit 0 "verify a camera" "$cc" verify --scene "$work/a.json" --camera "$camera"
expect_exit 0 "verify a path" "$cc" verify --scene "$work/a.json" --path "$work/path.json" --method oh_os_conservative,frustum

# Bad input: exit 2, one line naming object and field.
printf '{"format":"cullcheck-scene","version":1,"buildings":[{"id":3,"height":-1,"footprint":[[0,0],[1,0],[1,1]]}]}' >"$work/bad.json"
expect_exit 2 "negative height" "$cc" cull --scene "$work/bad.json" --camera "$camera"
expect_error_names "negative height" "building 3: field 'height'"
printf '{"format":"cullcheck-scene","version":1,"buildings":[{"id":4,"height":5,"footprint":[[0,0],[NaN,0],[1,1]]}]}' >"$work/nan.json"
expect_exit 2 "NaN coordinate" "$cc" cull --scene "$work/nan.json" --camera "$camera"
expect_error_names "NaN coordinate" "is not valid JSON"
expect_exit 2 "missing file" "$cc" cull --scene "$work/nope.json" --camera "$camera"
expect_error_names "missing file" "cannot be opened"
expect_exit 2 "camera below ground" "$cc" cull --scene "$work/a.json" --camera '{"position":[0,0,-2]}'
expect_error_names "camera below ground" "position.z"
expect_exit 2 "unknown method" "$cc" cull --scene "$work/a.json" --method nonsense --camera "$camera"
expect_error_names "unknown method" "unknown method 'nonsense'"
expect_exit 0 "region PVS held to the oracle" "$cc" region --scene "$work/a.json" --method shrink_former --camera "$camera" \
  --radius 1 --from "$camera"
grep -q '"missed":\[\]' "$work/out" && pass || fail "region: the centre's own view misses a building"
expect_exit 0 "verify with region methods" "$cc" verify --scene "$work/a.json" --path "$work/path.json" \
  --method oh_os_conservative --region-method all --region-radius 2
grep -q "region shrink_former (radius 2.00 m)" "$work/out" && pass || fail "verify: no region summary"
expect_exit 0 "report with a region radius sweep" "$cc" report --scene "$work/a.json" --path "$work/path.json" \
  --method oh_os_conservative --claim-scenes 1 --region-sweep 0.5,2 -o "$work/sweep.json"
grep -q '"region_sweep"' "$work/sweep.json" && pass || fail "report: no region_sweep in report.json"
expect_exit 2 "unknown region method" "$cc" region --scene "$work/a.json" --method nonsense --camera "$camera"
expect_error_names "unknown region method" "unknown region method 'nonsense'"
expect_exit 2 "unknown region method in verify" "$cc" verify --scene "$work/a.json" --camera "$camera" --region-method nonsense
expect_error_names "unknown region method in verify" "unknown method 'nonsense'"
# View cells: a street cell's PVS, the same with a given polygon, bad cells named.
expect_exit 0 "cell" "$cc" cell --generator manhattan --seed 3 --params '{"blocks_x":2,"blocks_y":2}' --cell 4 \
  --method shrink_former --sampling tiled --epsilon 2
grep -q '"samples"' "$work/out" && pass || fail "cell: no samples in the output"
expect_exit 0 "cell from a polygon, checked from inside" "$cc" cell --generator manhattan --seed 3 \
  --params '{"blocks_x":2,"blocks_y":2}' --ring '[[-8,-8],[8,-8],[8,8],[-8,8]]' --method shrink_adjustable_corrected \
  --from '{"position":[2,3,1.7],"hfov":6.283185307179586}'
grep -q '"missed":\[\]' "$work/out" && pass || fail "cell: a conservative cell PVS misses a building from inside"
expect_exit 2 "cell out of range" "$cc" cell --generator manhattan --params '{"blocks_x":2,"blocks_y":2}' --cell 999
expect_error_names "cell out of range" "navigable regions"
expect_exit 2 "clockwise cell" "$cc" cell --generator manhattan --ring '[[0,0],[0,5],[5,5],[5,0]]'
expect_error_names "clockwise cell" "counter-clockwise"
expect_exit 2 "cell sampling" "$cc" cell --generator manhattan --cell 1 --sampling everywhere
expect_error_names "cell sampling" "boundary, tiled"
expect_exit 0 "view cells of free-space cells" "$cc" report --generator scatter --params '{"count":5,"area_size":100}' \
  --path-kind fly_through --path-params '{"frames":2}' --claim-scenes 1 --method frustum --region-method shrink_former \
  --view-cells --view-cell-sampling boundary --view-cell-stride 7 --view-cell-oracle-cells 1 -o "$work/vc.json"
grep -q '"view_cells"' "$work/vc.json" && pass || fail "view cells of a scatter city: no view_cells section"
expect_exit 2 "view-cell sampling" "$cc" report --generator default --path-params '{"frames":2}' --claim-scenes 1 \
  --view-cells --view-cell-sampling boundary,nowhere -o "$work/vc.json"
expect_error_names "view-cell sampling" "unknown view-cell sampling 'nowhere'"
expect_exit 0 "kept counterexample replays" "$cc" region --generator kept --params '{"case":"low_planter"}' \
  --method shrink_adjustable_thesis --camera '{"position":[0,0,1.7],"hfov":6.283185307179586}' --radius 0.5 \
  --from '{"position":[0.5,0,1.7],"hfov":6.283185307179586}'
grep -q '"missed":\[1\]' "$work/out" && pass || fail "kept case: the published equations no longer miss the kerb stone"

expect_exit 2 "unknown generator" "$cc" generate --generator moon -o "$work/c.json"
expect_error_names "unknown generator" "generator"
expect_exit 2 "bad generator parameter" "$cc" generate --generator manhattan --params '{"blocks_x":-4}' -o "$work/c.json"
expect_error_names "bad generator parameter" "blocks_x"
expect_exit 2 "unknown flag" "$cc" cull --frobnicate

# A failed generate leaves an existing file untouched.
cp "$work/a.json" "$work/keep.json"
expect_exit 2 "failed generate" "$cc" generate --generator manhattan --params '{"blocks_x":0}' -o "$work/keep.json"
if cmp -s "$work/a.json" "$work/keep.json"; then pass; else fail "a failed run changed an existing file"; fi
# An unwritable destination is an error naming the file, not a crash.
expect_exit 2 "unwritable output" "$cc" generate --generator manhattan --params '{"blocks_x":1,"blocks_y":1}' -o "$work/no/such/dir/x.json"
expect_error_names "unwritable output" "cannot be opened for writing"

# VbAoI: a street city and a free-space (irregular) city, the gate's zero, the baselines' misses,
# one seed one run, bad input named before the graph is built.
vb_city=(--generator manhattan --seed 3 --params '{"blocks_x":2,"blocks_y":2,"block_size":40,"street_width":10}')
expect_exit 0 "vbaoi" "$cc" vbaoi "${vb_city[@]}" --clients 5,20 --duration 5 -o "$work/vb.json"
grep -q "neighbours" "$work/out" && pass || fail "vbaoi: no neighbours baseline in the table"
# Exit 0 is the gate's zero for a conservative graph method: no grouping violation, no missed update.
grep -q '"invariant_violations": 0' "$work/vb.json" && pass || fail "vbaoi: graph invariants broken"
[ "$(grep -c '"replay": "cullcheck vbaoi' "$work/vb.json")" -eq 2 ] && pass || fail "vbaoi: a run lacks its replay line"
expect_exit 0 "vbaoi again" "$cc" vbaoi "${vb_city[@]}" --clients 5,20 --duration 5 -o "$work/vb2.json"
# Timings (fields named *_ms* or *seconds*, and the objects under them) and thread counts aside.
strip_timings() { sed -e '/_ms": {/,/}/d' "$1" | grep -v -e '_ms' -e 'seconds' -e '"threads"'; }
if diff <(strip_timings "$work/vb.json") <(strip_timings "$work/vb2.json") >/dev/null; then pass; else fail "vbaoi: same seed, different section"; fi
expect_exit 0 "vbaoi on free-space cells" "$cc" vbaoi --generator irregular --seed 2 --params '{"count":6,"area_size":120}' \
  --clients 8 --duration 4 --loss 0.1
expect_exit 0 "cell PVSn from an eye" "$cc" cell "${vb_city[@]}" --cell 0 --method shrink_former --nodes \
  --from '{"position":[-45,-45,1.7],"hfov":6.283185307179586}' --to -45,40
grep -q '"node_in_pvs_n":true' "$work/out" && pass || fail "cell --nodes: a street's far end is not in the crossing's PVSn"
expect_exit 0 "cell on a free-space grid of its own" "$cc" cell --generator irregular --seed 2 --params '{"count":6,"area_size":120}' \
  --cell 3 --cell-size 40 --method shrink_former --nodes
grep -q '"pvs_n":\[' "$work/out" && pass || fail "cell --nodes printed no PVSn"
expect_exit 2 "vbaoi loss" "$cc" vbaoi "${vb_city[@]}" --loss 2
expect_error_names "vbaoi loss" "loss"
expect_exit 2 "vbaoi method" "$cc" vbaoi "${vb_city[@]}" --graph-method shrink_adjustable_conservative
expect_error_names "vbaoi method" "cannot test passive targets"
expect_exit 2 "vbaoi clients" "$cc" vbaoi "${vb_city[@]}" --clients 0
expect_exit 2 "vbaoi retry" "$cc" vbaoi "${vb_city[@]}" --latency 0.5 --retry-timeout 0.2
expect_error_names "vbaoi retry" "retry_timeout"
expect_exit 2 "cell --to alone" "$cc" cell "${vb_city[@]}" --cell 0 --to 1,2
expect_error_names "cell --to alone" "needs --nodes and --from"
expect_exit 2 "report vbaoi city" "$cc" report --generator manhattan --params '{"blocks_x":1,"blocks_y":1}' \
  --path-params '{"frames":2}' --claim-scenes 1 --vbaoi --vbaoi-generator moon -o "$work/vb3.json"
expect_error_names "report vbaoi city" "generator"

# The CI gate: a refuted method's violation is reported with a replay line.
printf '{"format":"cullcheck-scene","version":1,"buildings":[{"id":0,"height":10,"footprint":[[20,-20],[21,-20],[21,20],[20,20]]},{"id":1,"height":1,"footprint":[[40,-0.5],[41,-0.5],[41,0.5],[40,0.5]]}]}' >"$work/slab.json"
expect_exit 0 "published rule is reported, not gated" "$cc" verify --scene "$work/slab.json" --method oh_os_thesis \
  --camera '{"position":[0,0,30],"pitch":-0.6,"hfov":1.047,"vfov":0.785}'
grep -q "replay: cullcheck verify --scene" "$work/out" && pass || fail "violation printed no replay line"

echo "cli_test: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
