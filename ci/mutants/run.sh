#!/usr/bin/env bash
# Mutation check of the oracle-based properties (ci/mutants/README.md).
#
# Each patch in ci/mutants/patches/ weakens one step that a method's conservativeness rests on.
# For each one this script applies it to the source tree (git apply), rebuilds only the targets
# the checks need, runs only the oracle-based checks of the methods it weakens at the CI budget
# (RapidCheck properties that compare a PVS with the oracle, and `cullcheck fuzz` on the method
# wrapped as an outside subject, which is all an outside subject gets), reverts it (git apply
# -R, also on error or Ctrl-C), and prints mutant -> killed (by which check) or survived.
#
# Usage: ci/mutants/run.sh [-B BUILD_DIR] [-s base|all] [-a] [MUTANT ...]
#   -B  build directory (default build/, configured)
#   -s  which checks: base (those that were there before the mutation check) or all (default)
#   -a  run every check of a mutant (default: stop at the first that kills it); the table then
#       says which killed it, and the kill rate of the base checks alone is printed too
# Exit 0 when every mutant is killed; 1 when one survived, a check erred (crash, timeout) or a
# patch no longer applies (after a merge: refresh the patch against today's code).
# Each patch starts with "checks: GROUPS" (the check groups below) and "why: ...".
set -uo pipefail
cd "$(dirname "$0")/../.."
build=build set=all every=0
while getopts "B:s:a" opt; do
  case $opt in
    B) build=$OPTARG ;;
    s) set=$OPTARG ;;
    a) every=1 ;;
    *) echo "usage: $0 [-B BUILD_DIR] [-s base|all] [-a] [MUTANT ...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
case $set in base|all) ;; *) echo "-s takes base or all, not '$set'" >&2; exit 2 ;; esac
patches=()
if [ $# -eq 0 ]; then
  patches=(ci/mutants/patches/*.patch)
else
  for m in "$@"; do
    p=ci/mutants/patches/$(basename "${m%.patch}").patch
    [ -f "$p" ] || { echo "no such mutant: $m (see ci/mutants/patches/)" >&2; exit 2; }
    patches+=("$p")
  done
fi
[ -f "$build/build.ninja" ] || { echo "no build in $build (cmake --preset default first)" >&2; exit 2; }
export CULLCHECK_RC_BUDGET=1   # the CI budget, whatever the caller's environment says
unset RC_PARAMS
check_timeout=${CULLCHECK_MUTANT_TIMEOUT:-900}   # seconds per check: a mutant may loop
cc=$build/apps/cullcheck/cullcheck
subject=$build/examples/subjects/builtin_subject
tests=$build/properties
scratch=$(mktemp -d)

# The oracle-based checks, by group (the method a mutant weakens): "set|name|target|command".
# Set "base": the properties and the fuzzer that were there before the mutation check;
# "grazing": the hard cases written for it (properties/grazing_*_test.cpp), run first (fast).
region_checks() {
  cat <<CHECKS
grazing|DrawnDiscs.*|region_drawn_scenes_test|$tests/region_drawn_scenes_test
grazing|GrazingDiscs.$1Shrinking*|grazing_region_test|$tests/grazing_region_test --gtest_filter=GrazingDiscs.$1Shrinking*
base|RegionShrinking.$1ShrinkingHoldsOverTheDisc|region_shrinking_test|$tests/region_shrinking_test --gtest_filter=RegionShrinking.$1ShrinkingHoldsOverTheDisc
CHECKS
}
checks_of() {
  case $1 in
    oh) cat <<CHECKS
grazing|GrazingEyes.ObjectSpaceHorizon*|grazing_horizon_test|$tests/grazing_horizon_test --gtest_filter=GrazingEyes.ObjectSpaceHorizon*
base|Conservativeness.ObjectSpace*|conservativeness_test|$tests/conservativeness_test --gtest_filter=Conservativeness.ObjectSpace*
base|fuzz(oh_os_conservative)|cullcheck builtin_subject|$cc fuzz --subject '$subject oh_os_conservative' --budget 100 --seed 1 --out $scratch/cex
CHECKS
      ;;
    dh) cat <<CHECKS
grazing|GrazingEyes.GuardedDeltaHorizon*|grazing_delta_horizon_test|$tests/grazing_delta_horizon_test --gtest_filter=GrazingEyes.GuardedDeltaHorizon*
base|fuzz(delta_h_guarded)|cullcheck builtin_subject|$cc fuzz --subject '$subject delta_h_guarded' --budget 100 --seed 1 --out $scratch/cex
CHECKS
      ;;
    certified) region_checks Certified ;;
    former) region_checks Former ;;
    minkowski) region_checks Minkowski ;;
    corrected) region_checks CorrectedAdjustable ;;
    view_cell) cat <<CHECKS
grazing|ViewCell.PvsHoldsFromEyesLookingDownANarrowGap|view_cell_test|$tests/view_cell_test --gtest_filter=ViewCell.PvsHoldsFromEyesLookingDownANarrowGap
base|ViewCell.PvsHoldsFromEveryEyeInTheCell|view_cell_test|$tests/view_cell_test --gtest_filter=ViewCell.PvsHoldsFromEveryEyeInTheCell
CHECKS
      ;;
    *) echo "unknown check group '$1'" >&2; return 1 ;;
  esac
}
all_groups="oh dh certified former minkowski corrected view_cell"
checks_for() {  # the checks of a patch's groups in the chosen set
  local g
  for g in $(sed -n 's/^checks: //p;/^diff /q' "$1"); do checks_of "$g"; done | { [ "$set" = all ] && cat || grep '^base|'; }
}

applied=""
revert() {
  if [ -n "$applied" ]; then
    git apply -R "$applied" || echo "ERROR: could not revert $applied: the tree is dirty, run git apply -R $applied" >&2
    applied=""
  fi
}
cleanup() { revert; rm -rf "$scratch"; }
trap cleanup EXIT
trap 'echo "interrupted" >&2; exit 130' INT TERM

# Every target any check needs, so the unmutated build is restored at the end.
all_targets=$(for g in $all_groups; do checks_of "$g" | cut -d'|' -f3; done | tr ' ' '\n' | sort -u | tr '\n' ' ')

results=()
killed=0 survived=0 stale=0 errors=0 base_killed=0
start_all=$SECONDS
for p in "${patches[@]}"; do
  name=$(basename "$p" .patch)
  if ! git apply --check "$p" 2>"$scratch/apply.err"; then
    echo "== $name: STALE, the patch no longer applies to this tree (refresh it): $(head -1 "$scratch/apply.err")"
    results+=("$name|stale|patch no longer applies|0")
    stale=$((stale + 1))
    continue
  fi
  t0=$SECONDS
  git apply "$p" && applied=$p
  checks=$(checks_for "$p")
  targets=$(echo "$checks" | cut -d'|' -f3 | tr ' ' '\n' | sort -u | tr '\n' ' ')
  echo "== $name ($(sed -n 's/^why: //p' "$p")): building $targets"
  if ! cmake --build "$build" --target $targets -j2 >"$scratch/build.log" 2>&1; then
    tail -20 "$scratch/build.log"
    results+=("$name|error|build failed|$((SECONDS - t0))")
    errors=$((errors + 1))
    revert
    continue
  fi
  outcome=survived by="" base_kill=0
  while IFS='|' read -r which check _ command; do
    [ -n "$check" ] || continue
    rm -rf "$scratch/cex"
    c0=$SECONDS
    timeout "$check_timeout" bash -c "$command" </dev/null >"$scratch/check.log" 2>&1
    rc=$?
    echo "   $check: exit $rc in $((SECONDS - c0)) s"
    if [ $rc -eq 1 ]; then
      [ "$outcome" = error ] || outcome=killed
      by="${by:+$by, }$check"
      [ "$which" = base ] && base_kill=1
      grep -m1 -E "replay:|FAILED after" "$scratch/check.log" | cut -c1-400 | sed 's/^/     /'
    elif [ $rc -ne 0 ]; then
      outcome=error by="${by:+$by, }$check exit $rc"
      tail -5 "$scratch/check.log" | sed 's/^/     /'
    fi
    [ $rc -ne 0 ] && [ $every -eq 0 ] && break
  done <<<"$checks"
  revert
  case $outcome in killed) killed=$((killed + 1)) ;; survived) survived=$((survived + 1)) ;; *) errors=$((errors + 1)) ;; esac
  base_killed=$((base_killed + base_kill))
  results+=("$name|$outcome|${by:-every check passed}|$((SECONDS - t0))")
done

echo "== restoring the unmutated build"
cmake --build "$build" --target $all_targets -j2 >"$scratch/build.log" 2>&1 || { tail -20 "$scratch/build.log"; errors=$((errors + 1)); }

echo
printf '%-38s %-9s %-7s %s\n' mutant outcome seconds "killed by"
for r in "${results[@]}"; do
  IFS='|' read -r n o b s <<<"$r"
  printf '%-38s %-9s %-7s %s\n' "$n" "$o" "$s" "$b"
done
total=${#results[@]}
echo "kill rate ($set checks): $killed/$total killed, $survived survived, $errors errors, $stale stale; $((SECONDS - start_all)) s"
[ $every -eq 1 ] && [ "$set" = all ] && echo "kill rate of the base checks alone: $base_killed/$total"
[ $survived -eq 0 ] && [ $errors -eq 0 ] && [ $stale -eq 0 ]
