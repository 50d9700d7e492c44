#!/usr/bin/env bash
# Sharded runs end to end: `cullcheck report --shard K/4` four times and `cullcheck merge` write
# the report of one unsharded run (timings aside: report_same), with sections, the knob sweep,
# view cells and claim searches split between the shards; view cells on one and on two threads
# give the same section; the same for `verify --shard K/2 -o`; the merged
# exit code is the run's; bad shard flags and incomplete shard sets are refused with exit 2.
# Fuzzing too: `fuzz --shard K/3` and merge give the unsharded summary and the same shrunk case.
# And one view cell: `cell --shard K/3` and merge give the cell's PVS and PVSn.
# Usage: shard_cli_test.sh /path/to/cullcheck /path/to/report_same SUBJECTS_DIR
set -u
cc="$1"
same="$2"
subjects="$3"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
cd "$work" || exit 1

city=(--generator manhattan --params '{"blocks_x":6,"blocks_y":6}')
run=("${city[@]}" --seed 3 --path-params '{"frames":30}' --oracle-stride 3
  --view-cells --view-cell-sampling boundary --view-cell-stride 2 --view-cell-oracle-cells 3 --region-sweep 0.5,1 --claim-scenes 2
  --knob-sweep horizon_bins=1024,4096 --vbaoi --vbaoi-params '{"blocks_x":4,"blocks_y":4}' --vbaoi-clients 5 --soak-budget 8)
"$cc" -q report "${run[@]}" -o one.json >one.out 2>&1
one_exit=$?
for k in 0 1 2 3; do
  "$cc" -q report "${run[@]}" --shard "$k/4" -o "shard$k.json" >"shard$k.out" 2>&1 || true
  grep -q "^shard $k/4: " "shard$k.out" || fail "report --shard $k/4 did not say what it ran"
done
"$cc" merge shard2.json shard0.json shard3.json shard1.json -o merged.json --html merged.html >merge.out 2>&1
merge_exit=$?
[ "$merge_exit" -eq "$one_exit" ] || fail "merge exited $merge_exit, the unsharded run $one_exit"
"$same" one.json merged.json || fail "4 merged report shards differ from one run"
grep -q '"sections_run"' merged.json && fail "the merged report still holds shard data"
grep -q '<svg' merged.html || fail "merge --html wrote no page"
# The work was split: each shard checked 2 or 3 of the 10 checked frames and ran its own sections.
for k in 0 1 2 3; do
  checked=$(sed -n "s|^shard $k/4: \([0-9]*\) of the path's checked frames.*|\1|p" "shard$k.out")
  case "$checked" in 2|3) ;; *) fail "shard $k/4 checked $checked frames, not its 2 or 3 of 10" ;; esac
done
grep -q "sections: region_sweep" shard0.out || fail "the first section is not shard 0's"
grep -q "sections: vbaoi" shard1.out || fail "the second section is not shard 1's"
grep -q "sections: soak" shard2.out || fail "the third section is not shard 2's"
"$cc" -q report "${run[@]}" --view-cell-threads 1 -o one-thread.json >/dev/null 2>&1
"$same" one.json one-thread.json || fail "view cells on one thread differ from every core's"
# A shard's file is a report of its share: it differs from the whole run's.
"$same" one.json shard0.json >/dev/null && fail "a shard's report equals the whole run's"

# verify: the frames split in two.
vrun=(--generator manhattan --seed 3 --params '{"blocks_x":4,"blocks_y":4}' --path-params '{"frames":12}' --method all --region-method shrink_minkowski)
"$cc" -q verify "${vrun[@]}" -o verify.json >/dev/null 2>&1
for k in 0 1; do "$cc" -q verify "${vrun[@]}" --shard "$k/2" -o "v$k.json" >/dev/null 2>&1; done
"$cc" merge v1.json v0.json -o verify-merged.json >/dev/null 2>&1
"$same" verify.json verify-merged.json || fail "2 merged verify shards differ from one run"
# The oracle on one thread answers what it answers on every core (--oracle-threads).
"$cc" -q verify "${vrun[@]}" --oracle-threads 1 -o verify-one-thread.json >/dev/null 2>&1
"$same" verify.json verify-one-thread.json || fail "the oracle on one thread differs from every core"

# fuzz: the cases split in three; shards 0 and 1 both fail (cases 3 and 7), and the lowest is the
# run's failure, shrunk the same.
buggy="$subjects/buggy_sphere_subject"
"$cc" -q fuzz --subject "$buggy" --budget 40 --seed 5 -o fuzz.json --out case >/dev/null 2>&1
for k in 0 1 2; do "$cc" -q fuzz --subject "$buggy" --budget 40 --seed 5 --shard "$k/3" -o "fuzz$k.json" --out case >/dev/null 2>&1; done
"$cc" merge fuzz2.json fuzz0.json fuzz1.json -o fuzz-merged.json >merge.out 2>&1
[ $? -eq 1 ] || fail "merged fuzz shards that found a failure did not exit 1"
grep -q '"first_failing_case": 3,' fuzz0.json && grep -q '"first_failing_case": 7,' fuzz1.json ||
  fail "fuzz shards 0 and 1 no longer both fail (cases 3 and 7): the lowest-failure rule is not exercised"
winner=$(sed -n 's/.*"counterexample": "\(case-shard[0-9]\)".*/\1/p' fuzz-merged.json)
[ -n "$winner" ] || fail "the merged fuzz summary names no shard's counterexample folder"
sed "s/\"$winner\"/\"case\"/" fuzz-merged.json >fuzz-merged-renamed.json
"$same" fuzz.json fuzz-merged-renamed.json || fail "3 merged fuzz shards differ from one run"
grep -q '"cases": 4,' fuzz.json || fail "the unsharded fuzz run no longer fails at case 4 (seed 5)"
cmp -s case/scene.json "$winner/scene.json" && cmp -s case/path.json "$winner/path.json" ||
  fail "the winning shard shrank to another case than the unsharded run"
"$cc" -q fuzz --subject "$subjects/builtin_subject frustum" --budget 12 --seed 2 -o pass.json >/dev/null 2>&1
for k in 0 1 2; do "$cc" -q fuzz --subject "$subjects/builtin_subject frustum" --budget 12 --seed 2 --shard "$k/3" -o "pass$k.json" >/dev/null 2>&1; done
"$cc" merge pass0.json pass1.json pass2.json -o pass-merged.json >/dev/null 2>&1 || fail "merged passing fuzz shards did not exit 0"
"$same" pass.json pass-merged.json || fail "3 merged passing fuzz shards differ from one run"

# cell: one view cell's samples split in three; the union is the cell's PVS and PVSn.
crun=(--generator manhattan --seed 3 --params '{"blocks_x":4,"blocks_y":4}' --cell 5 --nodes --method shrink_former)
"$cc" -q cell "${crun[@]}" -o cell.json >/dev/null 2>&1 || fail "cell exited $?"
for k in 0 1 2; do "$cc" -q cell "${crun[@]}" --shard "$k/3" -o "cell$k.json" >/dev/null 2>&1 || fail "cell --shard $k/3 exited $?"; done
"$cc" merge cell2.json cell0.json cell1.json -o cell-merged.json >/dev/null 2>&1 || fail "merging cell shards exited $?"
python3 - cell.json cell-merged.json cell0.json cell1.json cell2.json <<'PY' || fail "3 merged cell shards differ from one run"
import json, sys
one, merged, *shards = [json.load(open(p)) for p in sys.argv[1:]]
keys = ["method", "epsilon", "sampling", "samples", "pvs", "pvs_size", "pvs_n", "pvs_n_size"]
diff = [k for k in keys if one.get(k) != merged.get(k)]
if diff: print("differs:", diff); sys.exit(1)
if set(one) != set(merged): print("keys:", sorted(set(one) ^ set(merged))); sys.exit(1)
# The work was split: every shard computed a third of the samples, none the whole PVS alone.
if sorted(s["samples"] for s in shards) != sorted([one["samples"] // 3 + (k < one["samples"] % 3) for k in range(3)]):
    print("shard samples", [s["samples"] for s in shards], "of", one["samples"]); sys.exit(1)
if one["samples"] < 6 or all(s["pvs_size"] == one["pvs_size"] for s in shards):
    print("the shards did not split the cell's work"); sys.exit(1)
PY

# Bad input: exit 2 and a line that says what is wrong.
expect_refusal() {  # what text command...
  local what=$1 text=$2
  shift 2
  "$@" >out 2>err
  local got=$?
  [ "$got" -eq 2 ] || fail "$what: exit $got, expected 2"
  grep -q -- "$text" err || { fail "$what: stderr lacks '$text'"; head -3 err; }
}
expect_refusal "shard 4 of 4" "K must be below N" "$cc" report --shard 4/4
expect_refusal "shard 1/x" "is not K/N" "$cc" verify --shard 1/x
expect_refusal "verify shard without a file" "needs --output" "$cc" verify "${vrun[@]}" --shard 0/2
expect_refusal "fuzz shard without a file" "needs --output" "$cc" fuzz --subject "$buggy" --shard 0/2
expect_refusal "fuzz and report shards" "cannot be merged together" "$cc" merge fuzz0.json shard1.json fuzz2.json
expect_refusal "cell shard without a file" "needs --output" "$cc" cell "${crun[@]}" --shard 0/3
expect_refusal "cell shard with --from" "cannot be given with --from" "$cc" cell "${crun[@]}" --shard 0/3 -o c.json \
  --from '{"position":[1,1,1.7]}'
expect_refusal "cell and fuzz shards" "cannot be merged together" "$cc" merge cell0.json fuzz1.json cell2.json
expect_refusal "two of three cell shards" "every shard of the run is needed" "$cc" merge cell0.json cell2.json
expect_refusal "three of four shards" "every shard of the run is needed" "$cc" merge shard0.json shard1.json shard3.json
expect_refusal "a shard twice" "is given twice" "$cc" merge shard0.json shard1.json shard1.json shard3.json
"$cc" -q report "${run[@]}" --claim-seed 2 --shard 2/4 -o other2.json >/dev/null 2>&1
expect_refusal "shards run with other flags" "the shards were run with other flags" "$cc" merge shard0.json shard1.json other2.json shard3.json
"$cc" -q report "${city[@]}" --seed 4 "${run[@]:6}" --shard 2/4 -o city2.json >/dev/null 2>&1
expect_refusal "shards of another city" "not a shard of the same run" "$cc" merge shard0.json shard1.json city2.json shard3.json
expect_refusal "a plain report" "not a shard file" "$cc" merge one.json
cp merged.json kept.json
"$cc" merge shard0.json shard1.json -o merged.json >/dev/null 2>&1
cmp -s merged.json kept.json || fail "a refused merge touched the report already written"

if [ "$failures" -gt 0 ]; then echo "$failures failures"; exit 1; fi
echo "shard_cli_test: all passed"
