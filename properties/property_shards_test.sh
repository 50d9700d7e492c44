#!/usr/bin/env bash
# Property budgets on every core (properties/CMakeLists.txt, CULLCHECK_PROPERTY_SHARDS): a
# property binary run in 3 GoogleTest shards gives, test by test, the outcome and failure text of
# the same binary run whole. Each binary given is run whole and as 3 concurrent shards, with
# --gtest_output=xml; the results are compared by compare_shards below. The comparison must fire:
# a shard run under another RapidCheck seed changes the fixture's counterexample and is caught.
# Usage: property_shards_test.sh FIXTURE [PROPERTY_BINARY...]
# The first binary is property_shard_fixture: ShardFixture.SmallSumsOnly must fail in both runs.
set -uo pipefail
fixture=$1
shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
unset GTEST_TOTAL_SHARDS GTEST_SHARD_INDEX RC_PARAMS CULLCHECK_SEED CULLCHECK_RC_BUDGET

fail() { echo "FAIL: $*"; exit 1; }

# run_whole BIN DIR / run_shards BIN DIR [RC_PARAMS for every shard]: exit codes into DIR/*.rc
run_whole() {
  mkdir -p "$2"
  "$1" --gtest_output="xml:$2/whole.xml" > "$2/whole.log" 2>&1
  echo $? > "$2/whole.rc"
}
run_shards() {
  mkdir -p "$2"
  for k in 0 1 2; do
    (
      export GTEST_TOTAL_SHARDS=3 GTEST_SHARD_INDEX=$k
      [ -n "${3:-}" ] && export RC_PARAMS="$3"
      "$1" --gtest_output="xml:$2/shard$k.xml" > "$2/shard$k.log" 2>&1
      echo $? > "$2/shard$k.rc"
    ) &
  done
  wait
}

# compare_shards DIR [MUST_FAIL_TEST]: exit 0 when the shards equal the whole run.
compare_shards() {
  python3 - "$@" <<'PY'
import re, sys, xml.etree.ElementTree as ET
d = sys.argv[1]
must_fail = sys.argv[2] if len(sys.argv) > 2 else ""

def results(path):
    out = {}
    for case in ET.parse(path).getroot().iter("testcase"):
        if case.get("result") == "suppressed" or case.get("status") == "notrun":
            continue
        name = case.get("classname") + "." + case.get("name")
        failures = [f.get("message", "") + (f.text or "") for f in case.findall("failure")]
        skipped = case.find("skipped") is not None
        out[name] = ("failed" if failures else "skipped" if skipped else "passed", "\n".join(failures))
    return out

whole = results(f"{d}/whole.xml")
rc = lambda n: int(open(f"{d}/{n}.rc").read())
union, owner, nonempty = {}, {}, 0
for k in range(3):
    part = results(f"{d}/shard{k}.xml")
    nonempty += bool(part)
    for name, r in part.items():
        if name in union:
            print(f"{name} ran in shards {owner[name]} and {k}"); sys.exit(1)
        union[name], owner[name] = r, k
problems = []
if nonempty < 2:
    problems.append(f"only {nonempty} of 3 shards ran a test: nothing was spread")
for name in sorted(set(whole) | set(union)):
    if name not in union:
        problems.append(f"{name}: in the whole run, in no shard")
    elif name not in whole:
        problems.append(f"{name}: in shard {owner[name]}, not in the whole run")
    elif whole[name] != union[name]:
        problems.append(f"{name}: whole run {whole[name][0]}, shard {owner[name]} {union[name][0]}"
                        + ("" if whole[name][0] != union[name][0] else "; failure text differs"))
if must_fail and whole.get(must_fail, ("missing",))[0] != "failed":
    problems.append(f"{must_fail} should fail in the whole run: {whole.get(must_fail, ('missing',))[0]}")
if (rc("whole") != 0) != any(rc(f"shard{k}") != 0 for k in range(3)):
    problems.append("exit codes: whole " + str(rc("whole")) + ", shards " + str([rc(f"shard{k}") for k in range(3)]))
for p in problems:
    print(p)
print(f"{len(whole)} tests, {len(union)} in shards of sizes {[list(owner.values()).count(k) for k in range(3)]}, "
      f"{sum(r[0] == 'failed' for r in whole.values())} failed")
sys.exit(1 if problems else 0)
PY
}

# The fixture: whole and sharded, with its counterexample.
run_whole "$fixture" "$work/fixture"
run_shards "$fixture" "$work/fixture"
compare_shards "$work/fixture" ShardFixture.SmallSumsOnly || fail "the fixture's shards differ from its whole run"
grep -q "Falsifiable" "$work/fixture/whole.log" || fail "the fixture's failing property printed no counterexample"

# The comparison fires: the shards run under another seed (every shard, so that the changed
# seed reaches the failing property whichever shard holds it), against the whole run above.
mkdir -p "$work/other_seed" && cp "$work/fixture/whole.xml" "$work/fixture/whole.rc" "$work/other_seed/"
run_shards "$fixture" "$work/other_seed" "seed=7 max_success=500 max_size=100"
if compare_shards "$work/other_seed" > "$work/other_seed/compare.log"; then
  cat "$work/other_seed/compare.log"
  fail "shards run under another seed compared equal: the comparison cannot see a changed counterexample"
fi
grep -q "ShardFixture.SmallSumsOnly: .*failure text differs" "$work/other_seed/compare.log" ||
  { cat "$work/other_seed/compare.log"; fail "the other seed's difference was not named"; }

# Real property binaries.
for bin in "$@"; do
  dir="$work/$(basename "$bin")"
  run_whole "$bin" "$dir"
  run_shards "$bin" "$dir"
  compare_shards "$dir" || fail "$(basename "$bin"): its shards differ from its whole run"
done
echo "PASS: sharded property runs equal whole runs"
