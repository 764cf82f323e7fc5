#!/usr/bin/env bash
# Mutation testing: plants each bug of tools/mutations/*.diff, one at a time, in a copy of
# the working tree (its files that git tracks or would track), builds only the targets the
# mutation names and runs only the tests it names; a mutation is KILLED when a test fails,
# SURVIVED when they all pass, BROKEN when it does not apply, does not build or matches no
# test. Prints a markdown table (and writes it to $WORK/results.md); docs/mutation-testing.md
# says more.
#
#   tools/mutation_test.sh [NAME...]    # the named mutations (file names without .diff), or all
#
# Each mutation file is a unified diff against the repository root with three header lines:
#   # what: the bug, in words
#   # targets: the CMake targets to build (gridrt for tests that run the program)
#   # tests: a ctest -R regular expression
# Environment: WORK (default /tmp/gridrt-mutation): the copy (src/) and its build (build/),
# kept between runs so that each mutation rebuilds only what it touches; JOBS (default 2).
# Runs everything under nice.
set -euo pipefail
repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work=${WORK:-/tmp/gridrt-mutation}
jobs=${JOBS:-2}
mkdir -p "$work/src" "$work/build" "$work/logs"

# The copy: the working tree's files (tracked, or untracked and not ignored), written over
# the last copy with only changed files touched, so that the build stays incremental.
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
(cd "$repo" && git ls-files -z --cached --others --exclude-standard |
  xargs -0 -I{} sh -c '[ -f "$1" ] && mkdir -p "$2/$(dirname "$1")" && cp -p "$1" "$2/$1" || true' _ {} "$stage")
(cd "$stage" && find . -type f) | while read -r f; do
  cmp -s "$stage/$f" "$work/src/$f" || { mkdir -p "$(dirname "$work/src/$f")" && cp "$stage/$f" "$work/src/$f"; }
done
(cd "$work/src" && find . -type f) | while read -r f; do [ -e "$stage/$f" ] || rm -f "$work/src/$f"; done
mutations=()
if [ $# -eq 0 ]; then
  for f in "$repo"/tools/mutations/*.diff; do mutations+=("$(basename "$f" .diff)"); done
else
  mutations=("$@")
fi

header() { sed -n "s/^# $1: //p" "$2" | head -1; }

nice cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DGRIDRT_LTO=OFF \
  >"$work/logs/configure.log"
results="$work/results.md"
printf '| mutation | what | tests run | result |\n|---|---|---|---|\n' >"$results"
killed=0 survived=0 broken=0
for name in "${mutations[@]}"; do
  diff="$repo/tools/mutations/$name.diff"
  what=$(header what "$diff")
  targets=$(header targets "$diff")
  tests=$(header tests "$diff")
  log="$work/logs/$name.log"
  result=BROKEN
  ran=0
  if (cd "$work/src" && patch -p1 --quiet --forward <"$diff") >"$log" 2>&1; then
    # shellcheck disable=SC2086
    if nice cmake --build "$work/build" -j"$jobs" --target $targets >>"$log" 2>&1; then
      if nice ctest --test-dir "$work/build" -j"$jobs" -R "$tests" --timeout 600 >>"$log" 2>&1; then
        result=SURVIVED
      else
        result=KILLED
      fi
      ran=$(sed -n 's/.* tests failed out of \([0-9]*\)/\1/p' "$log" | tail -1)
      failed=$(sed -n 's/.*% tests passed, \([0-9]*\) tests failed out of.*/\1/p' "$log" | tail -1)
      if [ -z "$ran" ] || [ "$ran" = 0 ]; then
        result="BROKEN (no test matches)"
      elif [ "$result" = KILLED ]; then
        result="KILLED ($failed of $ran fail)"
      fi
    fi
  fi
  # Back to the working tree's files, whether the patch applied wholly, partly or not.
  sed -n 's|^+++ b/||p' "$diff" | while read -r f; do
    cp -p "$stage/$f" "$work/src/$f"
    rm -f "$work/src/$f.orig" "$work/src/$f.rej"
  done
  case $result in KILLED*) killed=$((killed + 1)) ;; SURVIVED) survived=$((survived + 1)) ;; *) broken=$((broken + 1)) ;; esac
  printf '| `%s` | %s | `%s` (%s) | %s |\n' "$name" "$what" "${tests//|/\\|}" "${ran:-0}" "$result" |
    tee -a "$results"
done
echo "killed $killed, survived $survived, broken $broken (logs in $work/logs)" | tee -a "$results"
[ "$survived" -eq 0 ] && [ "$broken" -eq 0 ]
