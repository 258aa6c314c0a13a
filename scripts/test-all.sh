#!/usr/bin/env bash
# The whole test suite, as the README and CI run it: installs any missing
# Debian packages, then configures, builds and tests every preset (host and
# target) with CMake workflow presets.  Target tests run under QEMU.
#
#   scripts/test-all.sh                 # all presets
#   KESTREL_PRESETS="host-release cortex-m4f" scripts/test-all.sh
set -uo pipefail
cd "$(dirname "$0")/.."

ALL_PRESETS="host-debug-asan host-release host-clang host-float coverage cortex-m3 cortex-m4f cortex-m7 cortex-m33 aarch64-linux armhf-linux s390x-linux"
PRESETS="${KESTREL_PRESETS:-$ALL_PRESETS}"

scripts/install-deps.sh all || { echo "test-all: dependency installation failed" >&2; exit 1; }

declare -A result tests secs
failed=0
for p in $PRESETS; do
  echo "=================================================================="
  echo "== preset $p"
  echo "=================================================================="
  start=$(date +%s)
  log="build/logs/$p.log"
  mkdir -p build/logs
  if cmake --workflow --preset "$p" --fresh 2>&1 | tee "$log"; then
    result[$p]="PASS"
  else
    result[$p]="FAIL"
    failed=$((failed + 1))
  fi
  secs[$p]=$(( $(date +%s) - start ))
  tests[$p]=$(grep -Eo "tests passed, [0-9]+ tests failed out of [0-9]+" "$log" | tail -1 | awk '{print $NF}')
  # the worst-case stack table (printed by the fsw_proof_stack test)
  ctest --test-dir "build/$p" -R '^fsw_proof_stack$' -V > "build/logs/$p.stack.log" 2>&1 || true
  stack=$(grep -Eo "largest: .* B over" "build/logs/$p.stack.log" | tail -1 | sed 's/.*largest: //; s/ over//')
  result[$p]="${result[$p]} ${stack:+(largest stack: $stack)}"
  # the structural coverage and MC/DC of the flight library (coverage preset)
  if [ -f "build/$p/coverage/summary.txt" ]; then result[$p]="${result[$p]} ($(cat "build/$p/coverage/summary.txt"))"; fi
  if [ -f "build/$p/mcdc/summary.txt" ]; then result[$p]="${result[$p]} ($(cat "build/$p/mcdc/summary.txt"))"; fi
done

echo
echo "================================ summary ================================"
printf "%-18s %-6s %8s  %s\n" preset tests time result
for p in $PRESETS; do
  printf "%-18s %-6s %7ss  %s\n" "$p" "${tests[$p]:-0}" "${secs[$p]}" "${result[$p]}"
done
n=$(echo $PRESETS | wc -w)
echo "$((n - failed)) passed, $failed failed"
[ "$failed" -eq 0 ]
