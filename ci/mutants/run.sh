#!/usr/bin/env bash
# Mutation check of the oracle-based properties (README "Tests and replays", mutants).
#
# Each patch in ci/mutants/patches/ weakens one step that a method's conservativeness rests on.
# For each one this script applies it to the source tree (git apply), rebuilds only the targets
# the checks need, runs only the oracle-based checks of the methods it weakens at the CI budget
# (RapidCheck properties that compare a PVS with the oracle, and `cullcheck fuzz` on the method
# wrapped as an outside subject, which is all an outside subject gets), reverts it (git apply
# -R, also on error or Ctrl-C), and prints mutant -> killed (by which check) or survived.
# Checks run in order and stop at the first that fails; a mutant no check kills survives.
#
# Usage: ci/mutants/run.sh [-B BUILD_DIR] [MUTANT ...]    (default: every patch, build/)
# Exit 0 when every mutant is killed; 1 when one survived, a check erred (crash, timeout) or a
# patch no longer applies (after a merge: refresh it against today's code, see README).
# Each patch starts with "checks: GROUPS" (oh, dh, region: the check groups below) and "why:".
set -uo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
build=build
while getopts "B:" opt; do
  case $opt in
    B) build=$OPTARG ;;
    *) echo "usage: $0 [-B BUILD_DIR] [MUTANT ...]" >&2; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
patches=()
if [ $# -eq 0 ]; then
  patches=(ci/mutants/patches/*.patch)
else
  for m in "$@"; do
    p=ci/mutants/patches/${m%.patch}.patch
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
scratch=$(mktemp -d)

# The oracle-based checks, by group: "name|target|command".
checks_of() {
  case $1 in
    oh) cat <<EOF
Conservativeness|conservativeness_test|$build/properties/conservativeness_test --gtest_filter=Conservativeness.ObjectSpace*
fuzz(oh_os_conservative)|cullcheck builtin_subject|$cc fuzz --subject '$subject oh_os_conservative' --budget 100 --seed 1 --out $scratch/cex
EOF
      ;;
    dh) cat <<EOF
fuzz(delta_h_guarded)|cullcheck builtin_subject|$cc fuzz --subject '$subject delta_h_guarded' --budget 100 --seed 1 --out $scratch/cex
EOF
      ;;
    region) cat <<EOF
RegionShrinking.*HoldsOverTheDisc|region_shrinking_test|$build/properties/region_shrinking_test --gtest_filter=RegionShrinking.*HoldsOverTheDisc
ViewCell.PvsHoldsFromEveryEyeInTheCell|view_cell_test|$build/properties/view_cell_test --gtest_filter=ViewCell.PvsHoldsFromEveryEyeInTheCell
NavigationGraph.NodePvsHoldsForEveryEyeInTheCell|vbaoi_test|$build/properties/vbaoi_test --gtest_filter=NavigationGraph.NodePvsHoldsForEveryEyeInTheCell
EOF
      ;;
    *) echo "unknown check group '$1'" >&2; return 1 ;;
  esac
}
groups_of() { sed -n 's/^checks: //p;/^diff /q' "$1"; }

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
all_targets=$(for g in oh dh region; do checks_of $g | cut -d'|' -f2; done | tr ' ' '\n' | sort -u | tr '\n' ' ')

results=()
killed=0 survived=0 stale=0 errors=0
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
  groups=$(groups_of "$p")
  checks=$(for g in $groups; do checks_of "$g"; done)
  targets=$(echo "$checks" | cut -d'|' -f2 | tr ' ' '\n' | sort -u | tr '\n' ' ')
  echo "== $name ($(sed -n 's/^why: //p' "$p")): building $targets"
  if ! cmake --build "$build" --target $targets -j2 >"$scratch/build.log" 2>&1; then
    tail -20 "$scratch/build.log"
    results+=("$name|error|build failed|$((SECONDS - t0))")
    errors=$((errors + 1))
    revert
    continue
  fi
  outcome=survived by="all checks passed"
  while IFS='|' read -r check _ command; do
    [ -n "$check" ] || continue
    rm -rf "$scratch/cex"
    c0=$SECONDS
    timeout "$check_timeout" bash -c "$command" </dev/null >"$scratch/check.log" 2>&1
    rc=$?
    echo "   $check: exit $rc in $((SECONDS - c0)) s"
    if [ $rc -eq 1 ]; then
      outcome=killed by=$check
      grep -m1 -E "replay:|Falsifiable|counterexample" "$scratch/check.log" | cut -c1-300 | sed 's/^/     /'
      break
    elif [ $rc -ne 0 ]; then
      outcome=error by="$check exit $rc"
      tail -5 "$scratch/check.log" | sed 's/^/     /'
      break
    fi
  done <<<"$checks"
  revert
  case $outcome in killed) killed=$((killed + 1)) ;; survived) survived=$((survived + 1)) ;; *) errors=$((errors + 1)) ;; esac
  results+=("$name|$outcome|$by|$((SECONDS - t0))")
done

echo "== restoring the unmutated build"
cmake --build "$build" --target $all_targets -j2 >"$scratch/build.log" 2>&1 || { tail -20 "$scratch/build.log"; errors=$((errors + 1)); }

echo
printf '%-40s %-9s %-52s %s\n' mutant outcome "killed by" seconds
for r in "${results[@]}"; do
  IFS='|' read -r n o b s <<<"$r"
  printf '%-40s %-9s %-52s %s\n' "$n" "$o" "$b" "$s"
done
total=${#results[@]}
echo "kill rate: $killed/$total killed, $survived survived, $errors errors, $stale stale ($((SECONDS - start_all)) s)"
[ $survived -eq 0 ] && [ $errors -eq 0 ] && [ $stale -eq 0 ]
