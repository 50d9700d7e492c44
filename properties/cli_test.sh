#!/usr/bin/env bash
# End-to-end checks of the `cullcheck` program: every subcommand runs, bad input gives one clear
# line and exit 2, a failed run never clobbers a file already written, output is deterministic,
# cameras in world and scene-local coordinates, and every way the gate fails (exit 1 with a replay
# that fails again the same way, 2, 3).
# Usage: cli_test.sh /path/to/cullcheck BUILD_DIR SOURCE_DIR
#   (BUILD_DIR holds examples/subjects/*; SOURCE_DIR the repository, for the Python subjects)
set -u
cc="$1"
build="${2:-$(dirname "$cc")/../..}"
source_dir="${3:-$(dirname "$0")/..}"
subjects="$build/examples/subjects"
misbehaving="python3 $source_dir/properties/subjects/misbehaving_subject.py"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passes=0
# A sanitizer build (the sanitize preset) runs several times slower and reserves terabytes of
# shadow memory.
sanitized=0
grep -aq -e __asan_init -e __tsan_init -e __msan_init -e AddressSanitizer -e ThreadSanitizer "$cc" && sanitized=1
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

json_field() {  # file python-expression-on-d
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"
}

for sub in generate cull verify report region cell vbaoi gate fuzz html merge radar; do expect_exit 0 "$sub --help" "$cc" "$sub" --help; done

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
# Speed targets against a baseline report: its figures as "before"; a baseline that is not JSON is
# refused before the run, and nothing is written.
expect_exit 0 "report with a baseline" "$cc" report --scene "$work/a.json" --path "$work/path.json" \
  --method oh_os_conservative --claim-scenes 0 --baseline "$work/sweep.json" -o "$work/against.json"
[ "$(json_field "$work/against.json" "[r['id'] for r in d['speed_targets']['rows'] if 'before' in r]")" = "['oh_os_tests_over_exact_traversal', 'oracle_vs_bare_packets']" ] &&
  pass || fail "report --baseline: the OH(OS) and oracle rows have no figure before"
grep -q "oracle_vs_bare_packets" "$work/out" && pass || fail "report --baseline: no speed-targets table printed"
printf 'not json' >"$work/not-a-report.json"
expect_exit 2 "report: baseline not JSON" "$cc" report --scene "$work/a.json" --path "$work/path.json" \
  --method oh_os_conservative --claim-scenes 0 --baseline "$work/not-a-report.json" -o "$work/never.json"
expect_error_names "report: baseline not JSON" "baseline"
[ -e "$work/never.json" ] && fail "report: a report was written despite a bad baseline" || pass
# A horizon resolution the engine cannot take is refused by the flag, before any run.
expect_exit 2 "horizon bins not a power of two" "$cc" verify --generator manhattan --params '{"blocks_x":1,"blocks_y":1}' \
  --path-params '{"frames":1}' --horizon-bins 1000
expect_error_names "horizon bins not a power of two" "must be a power of two from 4"
# Progress: on a terminal (script(1) gives the run one) a run over 2 s (80 frames: about 4 s) shows its stage and how
# far it is on stderr; with --quiet, or when stderr is not a terminal, nothing.
# Under the sanitizers 20 frames already run well over 2 s (80 took about 20 s each, three times).
progress_frames=80
[ "$sanitized" = 1 ] && progress_frames=20
long_run=("$cc" verify --generator default --path-params "{\"frames\":$progress_frames}" --method oh_os_conservative)
script -qec "${long_run[*]@Q}" /dev/null >"$work/tty.out" 2>&1
grep -q "methods and the oracle along the path: [0-9]*/$progress_frames frames ([0-9]*%), [0-9]* s, about [0-9]* s left" "$work/tty.out" && pass || fail "progress: nothing shown on a terminal"
script -qec "${long_run[*]@Q} --quiet" /dev/null >"$work/tty-quiet.out" 2>&1
grep -q "along the path:" "$work/tty-quiet.out" && fail "progress: shown with --quiet" || pass
"${long_run[@]}" >/dev/null 2>"$work/not-tty.err"
grep -q "along the path:" "$work/not-tty.err" && fail "progress: shown when stderr is not a terminal" || pass
# The report page from a report of a scene file: drawn again by `cullcheck html` (the map's scene
# rebuilt from the report's replay flags); a report whose scene is gone still gets its page, exit 2.
expect_exit 0 "html of a report" "$cc" html "$work/sweep.json" -o "$work/sweep.html"
grep -q '<img id="map-image"' "$work/sweep.html" && pass || fail "html: the page has no map"
grep -q 'id="plot-region-sweep"' "$work/sweep.html" && pass || fail "html: the page has no radius-sweep plot"
cp "$work/a.json" "$work/moved.json"
sed "s|$work/a.json|$work/gone.json|g" "$work/sweep.json" >"$work/gone-report.json"
expect_exit 2 "html: the report's scene is gone" "$cc" html "$work/gone-report.json" -o "$work/gone.html"
expect_error_names "html: the report's scene is gone" "the page has no map"
grep -q "No map drawn" "$work/gone.html" && pass || fail "html: the page of a report whose scene is gone was not written"
expect_exit 0 "html: the scene given again" "$cc" html "$work/gone-report.json" -o "$work/given.html" --scene "$work/moved.json"
grep -q '<img id="map-image"' "$work/given.html" && pass || fail "html: --scene did not replace the report's scene"
expect_exit 2 "html: not a report" "$cc" html "$work/a.json" -o "$work/not.html"
expect_error_names "html: not a report" "not a report written by cullcheck"
expect_exit 2 "html: no such file" "$cc" html "$work/none.json"
[ -e "$work/not.html" ] && fail "html: a page was written for a file that is not a report" || pass
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
# --hold-conservative holds a method to a claim the engine does not gate: the ledger's replay of
# range detection as published (the fuzzer's shrunk case: a wall beside the eye in a 1-degree
# view) fails with it and passes without; the fuzzer finds such a case on its own.
rdt_case=(--generator scatter --seed 0 --params '{"area_size":60,"count":1,"max_size":20,"thin_fraction":0.0}'
  --camera '{"far":100000.0,"hfov":0.017453292519943295,"near":0.01,"pitch":0.0,"position":[-4.894,15.4535,1.7],"roll":0.0,"vfov":0.008726646259971648,"yaw":4.71238898038469}')
expect_exit 1 "gate --hold-conservative refutes rdt" "$cc" gate "${rdt_case[@]}" --method rdt --hold-conservative -o "$work/rdt-gate.json"
grep -q "replay: cullcheck verify .* --method rdt .*--hold-conservative" "$work/out" && pass || fail "rdt's replay lacks --hold-conservative"
expect_exit 0 "gate without it reports rdt, not gated" "$cc" gate "${rdt_case[@]}" --method rdt -o "$work/rdt-gate.json"
expect_exit 0 "gate passes rdt_corrected there" "$cc" gate "${rdt_case[@]}" --method rdt_corrected,radar_frustum --hold-conservative -o "$work/rdt-gate.json"
expect_exit 1 "fuzz finds rdt's counterexample" "$cc" fuzz --method rdt --hold-conservative --budget 200 --no-pixels -o "$work/rdt-fuzz"
grep -q "rdt: conservative: culled" "$work/out" && pass || fail "fuzz printed no rdt failure"


# ---- The gate for outside subjects (README "The subject protocol") ----------------------------
small=(--generator manhattan --seed 5 --params '{"blocks_x":2,"blocks_y":2}')
walk=(--path-params '{"frames":12}')
# A generated scene timeline (path parameter "timeline"): verify applies it, and --path-output
# writes its events; out of range it is refused, naming the field.
expect_exit 0 "verify with a generated timeline" "$cc" verify --generator manhattan --params '{"blocks_x":2,"blocks_y":2}' \
  --path-params '{"frames":40,"timeline":{"every":10,"churn":0.2}}' --method online_is_guarded,oh_os_conservative
expect_exit 0 "generate a path with a timeline" "$cc" generate --generator manhattan --params '{"blocks_x":2,"blocks_y":2}' \
  -o "$work/tl.json" --path-params '{"frames":40,"timeline":{"every":10,"churn":0.2}}' --path-output "$work/tl-path.json"
[ "$(json_field "$work/tl-path.json" "[e['frame'] for e in d['events']]")" = "[10, 20, 30]" ] && pass || fail "generate: the path's timeline was not written"
expect_exit 2 "timeline out of range" "$cc" verify --generator manhattan --params '{"blocks_x":1,"blocks_y":1}' \
  --path-params '{"frames":4,"timeline":{"every":0}}'
expect_error_names "timeline out of range" "every"
# The first violation printed, as "METHOD OBJECT FRAME" (gate says "object", verify "building").
first_miss() {
  sed -n 's/^violation: \([^ ]*\) culled [a-z]* \([0-9]*\) at frame \([0-9]*\) .*/\1 \2 \3/p' "$1" | head -1
}
# Runs the replay line printed under the first violation in $work/out: it must hold `text`, exit 1
# and report the same first miss (method, object, frame).
expect_replay_fails_the_same() {  # description text-the-replay-must-hold
  local what=$1 must=$2 miss replay got out=()
  miss=$(first_miss "$work/out")
  replay=$(grep -m1 "^  replay: cullcheck " "$work/out" | sed 's/^ *replay: cullcheck //')
  if [ -z "$miss" ] || [ -z "$replay" ]; then fail "$what: no violation with a replay line"; return; fi
  case "$replay" in *"$must"*) pass ;; *) fail "$what: the replay lacks '$must': $replay" ;; esac
  case "$replay" in gate*) out=(-o "$work/replay.json") ;; esac
  eval "\"$cc\" $replay \"\${out[@]}\"" >"$work/replay.out" 2>"$work/replay.err"
  got=$?
  [ "$got" -eq 1 ] && pass || { fail "$what: the replay exits $got, not 1: cullcheck $replay"; sed 's/^/  | /' "$work/replay.err" | head -3; }
  [ "$(first_miss "$work/replay.out")" = "$miss" ] && pass || fail "$what: the replay's first miss is '$(first_miss "$work/replay.out")', not '$miss'"
}
# A built-in method wrapped as a subject passes, with the PVS of the same method in-process at every frame.
expect_exit 0 "gate: built-in method over the protocol" "$cc" gate "${small[@]}" "${walk[@]}" \
  --subject "$subjects/builtin_subject" --method oh_os_conservative -o "$work/g.json" --junit "$work/g.xml"
[ "$(json_field "$work/g.json" "d['runs'][1]['frames_pvs_equal_to']['oh_os_conservative']")" = 12 ] && pass \
  || fail "gate: the protocol changed the built-in method's PVS"
[ "$(json_field "$work/g.json" "d['runs'][1]['violations'] == d['runs'][0]['violations'] and d['runs'][1]['pvs_mean'] == d['runs'][0]['pvs_mean']")" = True ] \
  && pass || fail "gate: the protocol changed the built-in method's violations or PVS sizes"
[ "$(json_field "$work/g.json" "d['runs'][1]['pixels']['misdrawn_pixels']")" = 0 ] && pass || fail "gate: a conservative subject misdrew pixels"
grep -q '<testsuites' "$work/g.xml" && ! grep -q '<failure' "$work/g.xml" && pass || fail "gate: JUnit of a passing run"
# The README's minimal subjects (C++ and Python) pass and cull exactly what frustum culling culls.
expect_exit 0 "gate: minimal C++ subject" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$subjects/minimal_subject" \
  --method frustum -o "$work/g.json"
[ "$(json_field "$work/g.json" "d['runs'][1]['frames_pvs_equal_to']['frustum']")" = 12 ] && pass || fail "gate: minimal subject != frustum"
expect_exit 0 "gate: minimal Python subject" "$cc" gate "${small[@]}" "${walk[@]}" \
  --subject "python3 $source_dir/examples/subjects/minimal_subject.py" -o "$work/g.json"
# A miss fails the gate (exit 1) with a replay line that fails again on its own.
expect_exit 1 "gate: a subject that culls what is visible" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving cull-all 4" \
  -o "$work/g.json" --junit "$work/g.xml"
grep -q "culled object .* at frame 4" "$work/out" && pass || fail "gate: the miss does not name frame 4"
grep -q '<failure message="culled' "$work/g.xml" && pass || fail "gate: JUnit lacks the failure"
[ "$(first_miss "$work/out")" = "subject:misbehaving-cull-all 2 4" ] && pass || fail "gate: cull-all 4: first miss '$(first_miss "$work/out")'"
expect_replay_fails_the_same "gate: a subject that culls what is visible" "--frame 4"
# Subjects that crash, hang or lie: exit 2, one line naming the frame and the fault, the report of
# the frames before it written.
for case in "crash 3|crashed|3" "segfault 2|signal 11|2" "hang 1|timed out|1" "garbage 2|garbage|2" \
            "wrong-frame 2|answered frame 3, expected 2|2" "unknown-id 1|object 99999999 is not in the scene|1"; do
  IFS='|' read -r mode text frame <<<"$case"
  expect_exit 2 "gate: subject $mode" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving $mode" --timeout 2 -o "$work/m.json"
  expect_error_names "gate: subject $mode" "at frame $frame: .*$text"
  [ "$(json_field "$work/m.json" "d['frames_run'], d['aborted']['frame']")" = "$frame $frame" ] && pass \
    || fail "gate: subject $mode: the report does not keep the $frame frames before the fault"
done
expect_exit 2 "gate: a ready message without claims" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving bad-ready" -o "$work/m.json"
expect_error_names "gate: bad ready" "during the handshake: protocol violation"
expect_exit 2 "gate: a program that is not there" "$cc" gate "${small[@]}" --subject "$work/no-such-program" -o "$work/m.json"
expect_error_names "gate: missing program" "status 127"
# Straw men: culling nothing passes the conservative check, and the over-estimation limit catches it.
expect_exit 0 "gate: a subject that culls nothing is conservative" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving everything"
expect_exit 1 "gate: --max-overestimation catches a subject that culls nothing" "$cc" gate "${small[@]}" "${walk[@]}" \
  --subject "$misbehaving everything" --max-overestimation 3
# A path on which the oracle sees nothing proves nothing: a subject that culls everything would
# pass it. Refused (exit 2) by default; --allow-empty-path accepts it. (This street walk of a
# 3 x 3 city runs along the outer ring facing away from the city.)
away=(--generator manhattan --seed 7 --params '{"blocks_x":3,"blocks_y":3}' --path-seed 2 --path-params '{"frames":30}')
expect_exit 2 "gate: a path that sees nothing" "$cc" gate "${away[@]}" --subject "$misbehaving cull-all 0" -o "$work/e.json"
expect_error_names "gate: a path that sees nothing" "the oracle saw no object at any of the 30 checked frames"
[ "$(json_field "$work/e.json" "d['gate']['nothing_witnessed']")" = True ] && pass || fail "gate: report lacks nothing_witnessed"
expect_exit 0 "gate: --allow-empty-path" "$cc" gate "${away[@]}" --subject "$misbehaving cull-all 0" --allow-empty-path -o "$work/e.json"
# An approximate subject is judged by its pixel budget.
expect_exit 1 "gate: approximate subject over its budget" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving approximate 100"
grep -q "over budget: .* misdrawn pixels (budget 100)" "$work/out" && pass || fail "gate: no over-budget line"
# Recorded visible sets: cull's per-frame output is a valid file; a tampered one fails.
"$cc" generate "${small[@]}" -o "$work/s.json" --path-output "$work/p.json" --path-params '{"frames":6}' >/dev/null
"$cc" cull --scene "$work/s.json" --path "$work/p.json" --method frustum | sed 's/"pvs":/"ids":/' >"$work/rec.jsonl"
# cull --recorded writes the file itself, with a ready line carrying the method's claim.
"$cc" cull --scene "$work/s.json" --path "$work/p.json" --method oh_os_conservative --recorded "$work/rec-oh.jsonl" >/dev/null
head -1 "$work/rec-oh.jsonl" | grep -q '"claims":"conservative"' && pass || fail "cull --recorded: no conservative ready line"
expect_exit 0 "gate --pvs from cull --recorded" "$cc" gate --scene "$work/s.json" --path "$work/p.json" --pvs "$work/rec-oh.jsonl" -o "$work/r.json"
[ "$(json_field "$work/r.json" "d['runs'][0]['method']")" = "recorded:oh_os_conservative" ] && pass || fail "cull --recorded: the gate did not name the method"
expect_exit 0 "gate --pvs" "$cc" gate --scene "$work/s.json" --path "$work/p.json" --pvs "$work/rec.jsonl" -o "$work/r.json"
sed '3s/"ids":\[[0-9,]*\]/"ids":[]/' "$work/rec.jsonl" >"$work/rec-miss.jsonl"
expect_exit 1 "gate --pvs with a missing object" "$cc" gate --scene "$work/s.json" --path "$work/p.json" --pvs "$work/rec-miss.jsonl" \
  -o "$work/r.json"
grep -q "replay: cullcheck gate --scene .* --frame 2 --pvs " "$work/out" && pass || fail "gate --pvs: replay does not name frame 2"
head -3 "$work/rec.jsonl" >"$work/rec-short.jsonl"
expect_exit 2 "gate --pvs with missing frames" "$cc" gate --scene "$work/s.json" --path "$work/p.json" --pvs "$work/rec-short.jsonl" \
  -o "$work/r.json"
expect_error_names "gate --pvs with missing frames" "at frame 3: protocol violation: holds no line for this frame"
# One camera's visible set given inline.
expect_exit 1 "gate --visible []" "$cc" gate --scene "$work/s.json" --camera "$camera" --visible '[]' -o "$work/r.json"
expect_exit 2 "gate --visible without a camera" "$cc" gate --scene "$work/s.json" --visible '[]'
expect_exit 2 "gate with nothing to check" "$cc" gate --scene "$work/s.json"
expect_error_names "gate with nothing to check" "nothing to check"
# Orthographic cameras: subjects and frustum culling take them, horizon methods skip them (counted).
expect_exit 0 "gate: orthographic camera" "$cc" gate --scene "$work/s.json" --method frustum,oh_os_conservative \
  --subject "$subjects/minimal_subject" --camera '{"position":[0,0,150],"pitch":-1.5707963267948966,"projection":"orthographic","ortho_width":120,"ortho_height":90}' \
  -o "$work/o.json"
[ "$(json_field "$work/o.json" "d['runs'][1]['frames_skipped'], d['runs'][2]['frames_pvs_equal_to']['frustum']")" = "1 1" ] && pass \
  || fail "gate: orthographic camera: horizon method not skipped, or the subject differs from frustum culling"

# Mesh scenes: frustum culling (by planes and by ranges), on-line image-space culling (it works on
# polygons) and subjects run, 2.5D methods are skipped with a reason.
expect_exit 0 "gate on a mesh scene" "$cc" gate --generator openings --params '{"blocks_x":1,"blocks_y":2}' \
  --path-params '{"frames":4}' --method all --subject "$subjects/minimal_subject" -o "$work/mesh.json"
[ "$(json_field "$work/mesh.json" "len(d['skipped_methods']), [r['method'] for r in d['runs']]")" = "6 ['frustum', 'rdt', 'rdt_corrected', 'radar_frustum', 'online_is', 'online_is_guarded', 'subject:minimal-box']" ] \
  && pass || fail "gate on a mesh scene: expected frustum, rdt(_corrected), radar_frustum, online_is(_guarded) and the subject to run, six 2.5D methods skipped"
# Point and region methods alike say why they were skipped (6 point methods, 5 region methods).
expect_exit 0 "verify on a mesh scene with region methods" "$cc" verify --generator openings --params '{"blocks_x":1,"blocks_y":1}' \
  --path-params '{"frames":2}' --region-method all
[ "$(grep -c '^skipped ' "$work/out")" = 11 ] && pass || fail "verify on a mesh scene: not every skipped method is named"
"$cc" generate --generator openings --params '{"blocks_x":1,"blocks_y":1}' -o "$work/op.json" --glb "$work/op.glb" --obj "$work/op.obj" >/dev/null
expect_exit 0 "gate reads a .glb scene" "$cc" gate --scene "$work/op.glb" --camera "$camera" --subject "$subjects/minimal_subject" \
  --method frustum -o "$work/glb.json"
[ "$(json_field "$work/glb.json" "d['scene']['mesh_count'] > 0 and d['runs'][1]['frames_pvs_equal_to']['frustum'] == 1")" = True ] \
  && pass || fail "gate --scene .glb: meshes lost, or the subject differs from frustum culling"

# ---- World and scene-local coordinates (core/coordinates.hpp) --------------------------------
# The small city moved 5,000 km east and 3,000 km north is rebased on load (origin [5000001,
# 3000000]: the whole-metre centre). Its walk in world coordinates, said by the file, by
# --coordinates or relative to another origin, checks exactly the cameras of the scene-local walk;
# read as local (a file that does not say) it would see nothing, so it is refused, not passed.
"$cc" generate "${small[@]}" -o "$work/near.json" --path-output "$work/near-walk.json" --path-params '{"frames":8}' >/dev/null
python3 - "$work" <<'EOF'
import json, sys
w = sys.argv[1] + "/"
s = json.load(open(w + "near.json"))
for b in s["buildings"]:
    b["footprint"] = [[x + 5000000, y + 3000000] for x, y in b["footprint"]]
json.dump(s, open(w + "far.json", "w"))
p = json.load(open(w + "near-walk.json"))
relative = dict(p, origin=[5000000, 3000000])  # local to another origin
json.dump(relative, open(w + "far-relative.json", "w"))
for f in p["frames"]:
    f["position"][0] += 5000000
    f["position"][1] += 3000000
del p["coordinates"], p["origin"]
json.dump(p, open(w + "far-world-undeclared.json", "w"))
json.dump(dict(p, coordinates="world"), open(w + "far-world.json", "w"))
EOF
far=(--scene "$work/far.json")
"$cc" generate "${far[@]}" --path "$work/far-world.json" -o "$work/far-again.json" --path-output "$work/far-local.json" >/dev/null
[ "$(json_field "$work/far-local.json" "d['coordinates'], d['origin'], d['frames'][0]['position'][:2]")" = \
  "local [5000001.0, 3000000.0] [-1.0, 18.082906308583915]" ] && pass || fail "generate: the world walk is not written scene-local with its origin"
expect_exit 0 "gate: world walk on a rebased scene" "$cc" gate "${far[@]}" --path "$work/far-world.json" --method frustum,oh_os_conservative \
  --subject "$subjects/minimal_subject" -o "$work/fw.json"
grep -q "^coordinates: scene-local metres, world = local + origin \[5000001.0, 3000000.0\]; .*far-world.json given in world coordinates (said by the file), converted to scene-local" \
  "$work/out" && pass || fail "gate: the output does not print the origin and the walk's frame"
[ "$(json_field "$work/fw.json" "d['scene']['origin'], d['path']['coordinates']['given'], d['path']['coordinates']['converted_to_local'], d['runs'][2]['frames_pvs_equal_to']['frustum'], d['runs'][0]['witnessed_mean']")" = \
  "[5000001.0, 3000000.0] world True 8 5.0" ] && pass || fail "gate: report.json of the world walk (origin, frame, subject = frustum, something seen)"
expect_exit 0 "gate: the same walk scene-local" "$cc" gate "${far[@]}" --path "$work/far-local.json" --method frustum,oh_os_conservative \
  --subject "$subjects/minimal_subject" -o "$work/fl.json"
strip_run() { json_field "$1" "[{k: ({f: x for f, x in v.items() if 'ms' not in f} if k == 'per_frame' else v) for k, v in r.items() if 'ms' not in k and 'seconds' not in k and 'ns_per' not in k and k != 'protocol'} for r in d['runs']], d['oracle']['rays_cast']"; }
[ "$(strip_run "$work/fw.json")" = "$(strip_run "$work/fl.json")" ] && pass || fail "gate: the world walk and the local walk gave different runs"
# Per frame, the same PVS whichever way the frame is said.
"$cc" cull "${far[@]}" --path "$work/far-local.json" --method oh_os_conservative | sed 's/"cull_ms":[0-9.e-]*//' >"$work/cl.txt"
for how in "far-world.json" "far-world-undeclared.json --coordinates world" "far-relative.json"; do
  eval "\"$cc\" cull \"\${far[@]}\" --method oh_os_conservative --path \"$work/\"$how" | sed 's/"cull_ms":[0-9.e-]*//' >"$work/cw.txt"
  [ "$(wc -l <"$work/cw.txt")" -eq 8 ] && cmp -s "$work/cl.txt" "$work/cw.txt" && pass || fail "cull --path $how: not the local walk's PVSs"
done
# Read as local, the world walk lies 5,000 km from the scene: refused (exit 2), naming the file,
# the first eye, the bounds and the origin. (Before, a subject that culls everything passed here.)
expect_exit 2 "gate: world walk read as local" "$cc" gate "${far[@]}" --path "$work/far-world-undeclared.json" \
  --subject "$misbehaving cull-all 0" -o "$work/m.json"
expect_error_names "gate: world walk read as local" \
  "far-world-undeclared.json: field 'frames\[0\].position': every eye of the path (8 frames) lies outside the scene's plan bounds grown by 1000.0 m, so it would see nothing: the first is at \[5000000.0, 3000018.08290630[0-9]*, 1.7\] scene-local, the bounds are x \[-85.6[0-9]*, 85.5[0-9]*\], y \[-85.7[0-9]*, 85.9[0-9]*\] scene-local, the origin is \[5000001.0, 3000000.0\]"
# Said to be world, the same subject is caught: exit 1, and its replay (which keeps
# --coordinates) fails again at the same frame with the same object.
expect_exit 1 "gate: culling everything on the world walk" "$cc" gate "${far[@]}" --path "$work/far-world-undeclared.json" --coordinates world \
  --subject "$misbehaving cull-all 0" -o "$work/m.json"
expect_replay_fails_the_same "gate: culling everything on the world walk" "--coordinates world --frame 0"
expect_exit 2 "gate: file and flag disagree" "$cc" gate "${far[@]}" --path "$work/far-world.json" --coordinates local --method frustum
expect_error_names "gate: file and flag disagree" "far-world.json: field 'coordinates': says world but --coordinates says local"
expect_exit 2 "gate: --coordinates on a generated path" "$cc" gate "${far[@]}" --coordinates world --method frustum
expect_error_names "gate: --coordinates on a generated path" "generated paths are scene-local"
# One camera: world when it says so (the walk's first eye), refused when it does not.
world_eye='{"position":[5000000,3000018.082906308583915,1.7],"yaw":-1.4,"coordinates":"world"}'
expect_exit 0 "cull: a world camera" "$cc" cull "${far[@]}" --method frustum --camera "$world_eye"
grep -q '"pvs_size":[1-9]' "$work/out" && pass || fail "cull: a world camera sees nothing"
expect_exit 2 "cull: a world camera read as local" "$cc" cull "${far[@]}" --method frustum --camera "${world_eye/,\"coordinates\":\"world\"/}"
expect_error_names "cull: a world camera read as local" "^cullcheck: --camera: field 'position': the eye lies outside"
expect_exit 2 "verify: a world --camera and --coordinates local" "$cc" verify "${far[@]}" --method frustum --camera "$world_eye" --coordinates local
expect_error_names "verify: a world --camera and --coordinates local" "says world but --coordinates says local"

# ---- Every way the gate fails (README "Exit codes") --------------------------------------------
# Exit 1 when a conservative culler misses, whatever form it takes: each miss below is pinned
# (the first violation printed: who, which object, which frame), and the replay line printed
# under it must fail again the same way on its own.
# A recorded file that drops one visible object (building 6, seen at frame 2) from one frame.
python3 - "$work" <<'EOF'
import json, sys
w = sys.argv[1] + "/"
lines = open(w + "rec.jsonl").read().splitlines()
frame = json.loads(lines[2])
assert frame["frame"] == 2 and 6 in frame["ids"], frame
frame["ids"].remove(6)
lines[2] = json.dumps(frame)
open(w + "rec-drop.jsonl", "w").write("\n".join(lines) + "\n")
EOF
expect_exit 1 "gate --pvs without one visible object" "$cc" gate --scene "$work/s.json" --path "$work/p.json" --pvs "$work/rec-drop.jsonl" \
  -o "$work/r.json"
[ "$(first_miss "$work/out") $(grep -c '^violation:' "$work/out")" = "recorded:rec-drop.jsonl 6 2 1" ] && pass \
  || fail "gate --pvs: expected exactly one miss, building 6 at frame 2; got '$(first_miss "$work/out")'"
expect_replay_fails_the_same "gate --pvs without one visible object" "--frame 2 --pvs "
# One camera's visible set without one visible object (building 9, frustum culling keeps it).
"$cc" cull --scene "$work/s.json" --method frustum --camera "$camera" >"$work/cam.txt"
ids=$(python3 -c "import json,sys; print(json.dumps(json.load(open(sys.argv[1]))['pvs']))" "$work/cam.txt")
expect_exit 0 "gate --visible: frustum culling's set" "$cc" gate --scene "$work/s.json" --camera "$camera" --visible "$ids" -o "$work/r.json"
ids_less=$(python3 -c "import json,sys; v=json.loads(sys.argv[1]); v.remove(9); print(json.dumps(v))" "$ids")
expect_exit 1 "gate --visible without one visible object" "$cc" gate --scene "$work/s.json" --camera "$camera" --visible "$ids_less" -o "$work/r.json"
[ "$(first_miss "$work/out")" = "recorded:visible 9 0" ] && pass || fail "gate --visible: expected the miss of building 9, got '$(first_miss "$work/out")'"
expect_replay_fails_the_same "gate --visible without one visible object" "--visible '"
# Subjects handed the right scene but reading it wrong: every box 40 m east of where it is (an
# off-by-a-block offset); the scene-local boxes taken for world ones (moved by the origin) on the
# far scene; the boxes of another export of the city, whose ids run the other way.
expect_exit 1 "gate: a subject that shifts the boxes" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving shift 40" -o "$work/m.json"
[ "$(first_miss "$work/out")" = "subject:misbehaving-shift 7 0" ] && pass || fail "gate: shift 40: first miss '$(first_miss "$work/out")'"
expect_replay_fails_the_same "gate: a subject that shifts the boxes" "--frame 0"
expect_exit 1 "gate: a subject that adds the origin" "$cc" gate "${far[@]}" --path "$work/far-world.json" --subject "$misbehaving shift origin" \
  -o "$work/m.json"
[ "$(first_miss "$work/out")" = "subject:misbehaving-shift 2 0" ] && pass || fail "gate: shift origin: first miss '$(first_miss "$work/out")'"
expect_replay_fails_the_same "gate: a subject that adds the origin" "--path '$work/far-world.json' --frame 0"
python3 -c "
import json, sys
s = json.load(open(sys.argv[1]))
ids = sorted(b['id'] for b in s['buildings'])
for b in s['buildings']:
    b['id'] = ids[-1 - ids.index(b['id'])]
json.dump(s, open(sys.argv[2], 'w'))" "$work/near.json" "$work/renumbered.json"
expect_exit 1 "gate: a subject that reads another scene" "$cc" gate "${small[@]}" "${walk[@]}" --subject "$misbehaving scene $work/renumbered.json" \
  -o "$work/m.json"
[ "$(first_miss "$work/out")" = "subject:misbehaving-scene 2 0" ] && pass || fail "gate: another scene: first miss '$(first_miss "$work/out")'"
expect_replay_fails_the_same "gate: a subject that reads another scene" "--frame 0"
# Exit 2 when the gate cannot run: an unusable TMPDIR is named (it was exit 3).
TMPDIR="$work/no-such-dir" expect_exit 2 "gate: unusable TMPDIR" "$cc" gate "${small[@]}" --subject "$subjects/minimal_subject" -o "$work/m.json"
expect_error_names "gate: unusable TMPDIR" "TMPDIR $work/no-such-dir: field '(folder)': cannot hold a temporary folder"
# Exit 3 when no verdict was reached: out of memory under a 500 MB address-space limit (the city
# of 6,000,000 buildings needs gigabytes, the small one is generated within it; the gate fails
# while generating, before the oracle's threads exist), and the report already there is left as
# it was. Sanitizer builds reserve terabytes of shadow memory and cannot run under ulimit -v, so
# they skip it.
if [ "$sanitized" = 1 ]; then
  echo "cli_test: skipped the out-of-memory case (sanitizer build)"
else
  echo '{"kept":true}' >"$work/kept.json"
  expect_exit 0 "generate within 500 MB" bash -c 'ulimit -v 500000 && exec "$@"' _ "$cc" generate "${small[@]}" -o "$work/m.json"
  expect_exit 3 "gate out of memory" bash -c 'ulimit -v 500000 && exec "$@"' _ "$cc" gate --generator manhattan \
    --params '{"blocks_x":1000,"blocks_y":1000}' --method frustum -o "$work/kept.json"
  expect_error_names "gate out of memory" "^cullcheck: internal error: out of memory (std::bad_alloc): no verdict was reached$"
  [ "$(cat "$work/kept.json")" = '{"kept":true}' ] && pass || fail "gate out of memory: the report already there was changed"
fi

# ---- Fuzzing an outside program ----------------------------------------------------------------
# The buggy example culler is found and shrunk by the fuzzer on its own; its counterexample
# folder replays the failure.
expect_exit 1 "fuzz finds the buggy culler" "$cc" fuzz --subject "$subjects/buggy_sphere_subject" --budget 200 --seed 1 \
  --out "$work/cex" -o "$work/fuzz.json"
for f in scene.json scene.glb path.json replay.sh map.png frame.png case.json; do
  [ -s "$work/cex/$f" ] && pass || fail "fuzz: counterexample lacks $f"
done
# Shrunk: fewer objects than the first failing case (or one), at most two frames.
[ "$(json_field "$work/cex/case.json" "(d['failure']['objects'] < d['failure']['first_failure_objects'] or d['failure']['objects'] == 1) and d['failure']['frames'] <= 2 and d['shrinks_accepted'] > 0")" = True ] \
  && pass || fail "fuzz: the counterexample was not shrunk"
PATH="$(dirname "$cc"):$PATH" sh "$work/cex/replay.sh" >/dev/null 2>&1
[ $? -eq 1 ] && pass || fail "fuzz: replay.sh does not reproduce the failure"
# Its path says its frame, so --coordinates world cannot misread it.
[ "$(json_field "$work/cex/path.json" "d['coordinates'] == 'local' and d['origin'] == [0, 0]")" = True ] \
  && pass || fail "fuzz: the counterexample's path.json does not say it is scene-local"
# A culler that takes bounding boxes as solid occluders is wrong only where an object does not
# fill its box: through a door or window, under an arcade, past an L-shaped building.
expect_exit 1 "fuzz finds the box-occluder culler" "$cc" fuzz --subject "$subjects/box_occluder_subject" --budget 200 --seed 2 \
  --out "$work/cex-box"
[ -s "$work/cex-box/map.png" ] && pass || fail "fuzz: the box-occluder counterexample has no map"
expect_exit 0 "fuzz passes a correct subject" "$cc" fuzz --subject "$subjects/builtin_subject frustum" --budget 25 --seed 2 \
  --out "$work/cex2" -o "$work/fuzz2.json"
[ "$(json_field "$work/fuzz2.json" "d['cases'] == 25 and d['cases_by_path_kind'].get('viewport_edge', 0) > 0 and d['cases_by_path_kind'].get('orthographic', 0) > 0")" = True ] \
  && pass || fail "fuzz: did not run 25 cases reaching viewport-edge and orthographic cameras"
expect_exit 2 "fuzz: a subject that cannot start" "$cc" fuzz --subject "$work/no-such-program" --budget 2

# ---- Radar echo over terrain (thesis ch. 3.3) -------------------------------------------------
# The conservative rule holds the oracle (exit 0); the published rule misses a witnessed triangle
# on the kept counterexample (exit 1, and its replay line fails again); echo PNGs are written.
small_terrain='{"nx":9,"ny":9,"spacing":20,"relief":100}'
expect_exit 0 "radar: the conservative rule" "$cc" radar --terrain-params "$small_terrain" --terrain-seed 2 --height 50 --grid 2 \
  --rule conservative --echo "$work/echo" -o "$work/radar.json"
for f in echo_oracle.png echo_conservative.png echo_diff_conservative.png; do
  [ -s "$work/$f" ] && pass || fail "radar: $f not written"
done
[ "$(json_field "$work/radar.json" "d['rules'][0]['missed'] == 0 and d['oracle']['witnessed'] > 0 and d['rules'][0]['visible'] >= d['oracle']['witnessed']")" = True ] \
  && pass || fail "radar: the conservative run's JSON does not show 0 missed of a witnessed set"
expect_exit 1 "radar: the thesis rule misses" "$cc" radar --terrain-params "$small_terrain" --terrain-seed 2 --height 50 --grid 2 --rule thesis
replay=$(sed -n 's/^replay: cullcheck //p' "$work/out")
eval "\"\$cc\" $replay" >/dev/null 2>&1
[ $? -eq 1 ] && pass || fail "radar: the printed replay ($replay) does not fail again"
expect_exit 2 "radar: unknown rule" "$cc" radar --terrain-params "$small_terrain" --rule optimistic
expect_error_names "radar: unknown rule" "'optimistic' is none of"
expect_exit 2 "radar: transmitter off the terrain" "$cc" radar --terrain-params "$small_terrain" --at 1000,0
expect_error_names "radar: transmitter off the terrain" "off the terrain"
expect_exit 2 "radar: bad terrain parameter" "$cc" radar --terrain-params '{"nx":1}'
expect_error_names "radar: bad terrain parameter" "nx"
expect_exit 2 "radar: a missing elevation model" "$cc" radar --dem "$work/none.tif"
# A city standing on the terrain (--with-city and the scene flags the other subcommands take);
# one that does not fit on it is refused naming the building.
expect_exit 0 "radar: a city on the terrain" "$cc" radar --terrain-params '{"nx":33,"ny":33,"spacing":10,"relief":40}' --with-city \
  --generator manhattan --seed 2 --params '{"blocks_x":2,"blocks_y":2,"block_size":40}' --height 5 --grid 8 --rule conservative -o "$work/radar_city.json"
[ "$(json_field "$work/radar_city.json" "d['buildings']['count'] > 0 and d['rules'][0]['missed'] == 0 and '--with-city --generator manhattan' in d['replay']")" = True ] \
  && pass || fail "radar: the city run's JSON lacks its buildings, misses, or its replay lacks the city"
expect_exit 2 "radar: a city larger than the terrain" "$cc" radar --terrain-params "$small_terrain" --with-city --generator manhattan \
  --params '{"blocks_x":4,"blocks_y":4}'
expect_error_names "radar: a city larger than the terrain" "field 'footprint'"
expect_exit 0 "radar: a region echo for a moving mast" "$cc" radar --terrain-params "$small_terrain" --terrain-seed 2 --height 50 --grid 2 \
  --rule conservative --region 30 --region-rim 3 -o "$work/radar_region.json"
[ "$(json_field "$work/radar_region.json" "d['region']['missed'] == 0 and d['region']['samples'] >= 4 and d['region']['visible'] >= d['rules'][0]['visible'] and '--region 30 --region-rim 3' in d['replay']")" = True ] \
  && pass || fail "radar: the region run's JSON lacks its samples, misses, or its replay lacks the region"
expect_exit 2 "radar: a region without the oracle" "$cc" radar --terrain-params "$small_terrain" --region 30 --no-oracle
expect_error_names "radar: a region without the oracle" "region"
expect_exit 2 "radar: a malformed grid" "$cc" radar --terrain-params "$small_terrain" --grid 3,x
expect_error_names "radar: a malformed grid" "grid"

echo "cli_test: $passes passed, $failures failed"
[ "$failures" -eq 0 ]
