#!/usr/bin/env bash
# Monte Carlo peak memory against the number of runs (docs/monte-carlo.md,
# "Memory"): the short campaign test/harness/data/mc_short.yaml (S1, 20 s
# simulated per run, about 30 % of the runs failing, so that retention
# reruns 20 with full results) at each run count, -j2, its peak resident set size measured
# by /usr/bin/time (the process's ru_maxrss) and the ratio to the smallest
# count's.  The memory must be flat in the number of runs: a campaign
# streams each finished run's record to disk (records/) and writes its
# summary from there a record at a time.
#   bench/mc/bench_mc_memory.sh [KESTREL] [RUNS...]
#   (defaults: build/host-release/harness/kestrel 100 2000 20000; 20,000 runs
#   take about 11 minutes on 2 cores; figures in docs/monte-carlo.md, "Memory")
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
K="${1:-$here/build/host-release/harness/kestrel}"
shift || true
COUNTS=("$@")
[ ${#COUNTS[@]} -gt 0 ] || COUNTS=(100 2000 20000)
SC="$here/test/harness/data/mc_short.yaml"
[ -x /usr/bin/time ] || { echo "bench_mc_memory: /usr/bin/time is missing (apt-get install time)"; exit 1; }
W=$(mktemp -d /tmp/kestrel-bench-mc-mem.XXXXXX)
trap 'rm -rf "$W"' EXIT
echo "kestrel mc, $(basename "$SC") (20 s simulated per run), -j2; $(nproc) CPUs"
printf "  %8s  %12s  %10s  %8s\n" runs "peak RSS" "wall" ratio
base=""
for r in "${COUNTS[@]}"; do
  rc=0
  /usr/bin/time -f "%M %e" -o "$W/time" "$K" mc "$SC" --runs "$r" -j 2 -o "$W/c" > /dev/null 2> "$W/err" || rc=$?
  if [ $rc -ne 0 ] && [ $rc -ne 6 ]; then
    echo "bench_mc_memory: $r runs: exit $rc"
    cat "$W/err"
    exit 1
  fi
  read -r kb s < <(tail -1 "$W/time")
  [ -n "$base" ] || base=$kb
  awk -v r="$r" -v kb="$kb" -v s="$s" -v b="$base" \
    'BEGIN {printf "  %8d  %9.1f MB  %8.1f s  %8.3f\n", r, kb / 1024, s, kb / b}'
  rm -rf "$W/c"
done
