#!/usr/bin/env bash
# The main job, as the README runs it: installs any missing Debian packages,
# builds the `kestrel` CLI (with the offline HTML report), runs scenario S1
# (deep-space Sun pointing, 4 fully-coupled reaction wheels, from a tumble)
# and prints where the results and the report are.
#
#   scripts/run-main.sh [output-dir]        (default: results/s1; replaced whole
#                                           if it holds an earlier run's results)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-results/s1}"

scripts/install-deps.sh host
cmake --preset host-release > build-configure.log 2>&1 || { cat build-configure.log; exit 1; }
rm -f build-configure.log
cmake --build build/host-release --target kestrel -j2
build/host-release/harness/kestrel run scenarios/s1_sun_pointing.yaml -o "$out" --force \
  --set wheel_defaults.model=fully_coupled
echo
echo "Results: $(cd "$out" && pwd)"
echo "Report:  $(cd "$out" && pwd)/report.html"
