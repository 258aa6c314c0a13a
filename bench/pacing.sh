#!/usr/bin/env bash
# Pacing lateness of `kestrel run --realtime` (real time, 1x) for a run of
# SECONDS (default 60) at 100 Hz (dt = 0.01 s) and 1 kHz (dt = 0.001 s)
# ticks: prints the p50 / p99 / max tick lateness, overruns and the drift at
# the end.  Figures depend on the machine's load and on whether SCHED_FIFO
# and mlockall are granted (docs/harness.md, "Paced runs").
#
#   bench/pacing.sh [build-dir]        (default build/host-release)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/host-release}"
secs="${SECONDS_RUN:-60}"
k="$build/harness/kestrel"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for dt in 0.01 0.001; do
  hz=$(awk -v d="$dt" 'BEGIN { printf "%d", 1 / d }')
  line=$("$k" run scenarios/s1_sun_pointing.yaml -o "$out/r$hz" --realtime --set duration="$secs" \
         --set rates.dt="$dt" --set rates.record_divisor=10 | grep '^paced at')
  echo "$hz Hz, $secs s: ${line#paced at }"
done
