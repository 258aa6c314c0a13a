#!/usr/bin/env bash
# The main job, as the README runs it: installs any missing Debian packages,
# builds the `kestrel` CLI (with the offline HTML report), runs scenario S1
# (deep-space Sun pointing, 4 fully-coupled reaction wheels, from a tumble)
# with its wheel jitter resolved to the documented 1 %, and prints where the
# results and the report are.
#
#   scripts/run-main.sh [output-dir [kestrel-run-option...]]
#       output-dir: default results/s1; replaced whole if it holds an earlier
#       run's results.  Options after it go to `kestrel run`, after the
#       main command's own (a later --set wins): e.g. --set duration=60
#   KESTREL=path/to/kestrel scripts/run-main.sh ...
#       runs that program: nothing is installed or built (the test
#       harness_main_command runs the main command this way)
set -euo pipefail
# a KESTREL given as a path is taken from where the script was started
case "${KESTREL:-}" in */*) KESTREL="$(cd "$(dirname "$KESTREL")" && pwd)/$(basename "$KESTREL")" ;; esac
cd "$(dirname "$0")/.."
out="${1:-results/s1}"
[ $# -gt 0 ] && shift

# S1 with fully-coupled wheels, their imbalance jitter on, and the plant at 2
# RK4 sub-steps per 10 ms tick: the wheels reach 2,934 rpm while acquiring
# the Sun, |Omega| h = 1.54 rad per plant step, within the 2 rad that keeps
# the jitter amplitude within 1 % (about 0.2 % here); one step per tick
# would be 3.07 rad, under-resolved (docs/performance.md, "Accuracy per cost")
main=(scenarios/s1_sun_pointing.yaml --set wheel_defaults.model=fully_coupled --set rates.plant_substeps=2)

if [ -z "${KESTREL:-}" ]; then
  scripts/install-deps.sh host
  cmake --preset host-release > build-configure.log 2>&1 || { cat build-configure.log; exit 1; }
  rm -f build-configure.log
  cmake --build build/host-release --target kestrel -j2
  KESTREL=build/host-release/harness/kestrel
fi
"$KESTREL" run "${main[@]}" -o "$out" --force "$@"
echo
echo "Results: $(cd "$out" && pwd)"
echo "Report:  $(cd "$out" && pwd)/report.html"
