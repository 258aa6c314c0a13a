#!/usr/bin/env bash
# Structural coverage of the flight library (fsw_c/src) after the FSW tests
# of the coverage preset: lcov capture (lines and branches), HTML report,
# per-file table and a one-line summary.  Fails when coverage falls below
# the ratchet (KESTREL_COVERAGE_MIN_LINES / _BRANCHES, percent).
#
#   scripts/coverage-report.sh zero   BUILD_DIR
#   scripts/coverage-report.sh report BUILD_DIR SOURCE_DIR MIN_LINES MIN_BRANCHES
set -euo pipefail
mode="$1"; build="$2"
rc=(--rc lcov_branch_coverage=1 --quiet)
if [ "$mode" = zero ]; then
  lcov --zerocounters --directory "$build/fsw_c" --quiet
  rm -rf "$build/coverage"
  exit 0
fi
src="$3"; min_lines="$4"; min_branches="$5"
out="$build/coverage"
mkdir -p "$out"
lcov --capture --directory "$build/fsw_c" --base-directory "$src" "${rc[@]}" --output-file "$out/all.info"
lcov --extract "$out/all.info" "*/fsw_c/src/*" "${rc[@]}" --output-file "$out/fsw_src.info"
genhtml "$out/fsw_src.info" --branch-coverage --quiet --title "kestrel fsw_c/src" --output-directory "$out/html"
lcov --list "$out/fsw_src.info" --rc lcov_branch_coverage=1 | tee "$out/files.txt"
summary=$(lcov --summary "$out/fsw_src.info" --rc lcov_branch_coverage=1 2>&1)
lines=$(echo "$summary" | sed -n 's/.*lines\.*: \([0-9.]*\)% (\([0-9]*\) of \([0-9]*\).*/\1 \2 \3/p')
branches=$(echo "$summary" | sed -n 's/.*branches\.*: \([0-9.]*\)% (\([0-9]*\) of \([0-9]*\).*/\1 \2 \3/p')
read -r lp lh lt <<<"$lines"
read -r bp bh bt <<<"$branches"
echo "coverage fsw_c/src: lines ${lp}% (${lh} of ${lt}), branches ${bp}% (${bh} of ${bt}); report $out/html/index.html"
echo "coverage fsw_c/src: lines ${lp}% branches ${bp}%" > "$out/summary.txt"
ok=$(awk -v l="$lp" -v b="$bp" -v ml="$min_lines" -v mb="$min_branches" 'BEGIN { print (l >= ml && b >= mb) ? 1 : 0 }')
if [ "$ok" != 1 ]; then
  echo "coverage fell below the ratchet: lines ${lp}% (min ${min_lines}%), branches ${bp}% (min ${min_branches}%)" >&2
  exit 1
fi
