#!/usr/bin/env bash
# Long fuzzing runs, outside CTest.  Builds the host-clang preset's harnesses
# and runs each named one (default: all) for SECONDS, on its own scratch corpus
# seeded from the committed one; findings are left in build/fuzz/<name>/.
#
#   scripts/fuzz.sh                      # every harness, 600 s each
#   SECONDS_EACH=3600 scripts/fuzz.sh fuzz_scenario_reader
#   RUNS=1000000 scripts/fuzz.sh fuzz_set_parser   # a fixed number of executions
# The build and the fuzzers run under nice; JOBS (default 2) build jobs.
set -euo pipefail
cd "$(dirname "$0")/.."
secs="${SECONDS_EACH:-600}"
cmake --preset host-clang >/dev/null
mapfile -t all < <(ctest --test-dir build/host-clang -L fuzz -N | sed -n 's/^ *Test *#[0-9]*: //p')
names=("$@"); [ "${#names[@]}" -gt 0 ] || names=("${all[@]}")
nice cmake --build build/host-clang -j "${JOBS:-2}" --target "${names[@]}"
for n in "${names[@]}"; do
  exe=$(find build/host-clang/test/fuzz -type f -name "$n" -perm -u+x | head -1)
  corpus=$(ctest --test-dir build/host-clang -R "^$n\$" -N -V | grep -o -- '-DCORPUS=[^ ]*' | head -1 | cut -d= -f2 | tr -d '"')
  work="build/fuzz/$n"; mkdir -p "$work/corpus"
  echo "== $n ($exe, seeds $corpus)"
  limit=(-max_total_time="$secs"); [ -n "${RUNS:-}" ] && limit=(-runs="$RUNS")
  nice "$exe" "${limit[@]}" -timeout=2 -rss_limit_mb=1024 -malloc_limit_mb=1024 -print_final_stats=1 \
    -artifact_prefix="$work/" "$work/corpus" "$corpus" 2>&1 | tee "$work/log.txt" | grep -E 'stat::number_of_executed_units|stat::average_exec_per_sec|ERROR|VIOLATION|SUMMARY|DONE' || true
done
