#!/usr/bin/env bash
# Monte Carlo through the real `kestrel` program (docs/monte-carlo.md):
#   mc_cli_test.sh KESTREL SCENARIO cli     -j1 = -j2; --only; shards + merge = whole; exit codes
#   mc_cli_test.sh KESTREL SCENARIO mpi     mpirun -np 2 = -j2 (OpenMPI)
#   mc_cli_test.sh KESTREL SCENARIO slurm   --slurm scripts run on a one-node Slurm started here = -j2
# "Identical" means byte-identical summary.csv and mc_runs.json without the
# wall-clock times.  Exit 77: the test cannot run here (says why).
set -euo pipefail
K="$1"; SC="$2"; what="$3"
N=6
W=$(mktemp -d /tmp/kestrel-mc-test.XXXXXX)
cleanup() {
  set +e
  if [ -n "${SLURM_W:-}" ]; then
    pids=""
    for p in "$SLURM_W"/run/slurmd.pid "$SLURM_W"/run/slurmctld.pid; do
      [ -f "$p" ] && pids="$pids $(cat "$p")"
    done
    [ -n "$pids" ] && kill $pids 2>/dev/null
    for _ in $(seq 1 50); do  # the daemons write their state into $W until they are gone
      alive=0; for p in $pids; do kill -0 "$p" 2>/dev/null && alive=1; done
      [ $alive -eq 0 ] && break
      sleep 0.1
    done
  fi
  rm -rf "$W" 2>/dev/null
  return 0
}
trap cleanup EXIT

# the records without their wall-clock times
records() { /usr/bin/python3 - "$1" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
for r in j["records"]:
    r.pop("wall_seconds")
print(json.dumps(j["records"], sort_keys=True))
EOF
}
same() {  # same DIR_A DIR_B
  cmp "$1/summary.csv" "$2/summary.csv" || { echo "FAIL: summary.csv differs: $1 vs $2"; diff "$1/summary.csv" "$2/summary.csv" | head; exit 1; }
  [ "$(records "$1/mc_runs.json")" = "$(records "$2/mc_runs.json")" ] || { echo "FAIL: mc_runs.json differs: $1 vs $2"; exit 1; }
}
reference() { "$K" mc "$SC" --runs $N -j 2 -o "$W/j2" > "$W/j2.out" 2>&1 || { rc=$?; [ $rc -eq 6 ] || { cat "$W/j2.out"; exit 1; }; }; }

case "$what" in
cli)
  reference
  "$K" mc "$SC" --runs $N -j 1 -o "$W/j1" > /dev/null 2>&1 || [ $? -eq 6 ]
  same "$W/j1" "$W/j2"
  echo "ok: -j1 and -j2 identical ($N runs)"
  # shards (one of them with 2 threads) and the merge
  "$K" mc "$SC" --runs $N --shard 0/3 -o "$W/s0" > /dev/null 2>&1 || [ $? -eq 6 ]
  "$K" mc "$SC" --runs $N --shard 1/3 -j 2 -o "$W/s1" > /dev/null 2>&1 || [ $? -eq 6 ]
  "$K" mc "$SC" --runs $N --shard 2/3 -o "$W/s2" > /dev/null 2>&1 || [ $? -eq 6 ]
  set +e
  "$K" mc merge -o "$W/m01" "$W/s0" "$W/s1" > "$W/m01.out" 2>&1; rc=$?
  set -e
  [ $rc -eq 2 ] && grep -q "runs are in no shard" "$W/m01.out" || { echo "FAIL: a merge missing a shard must be refused (rc $rc)"; cat "$W/m01.out"; exit 1; }
  set +e
  "$K" mc merge -o "$W/m" "$W/s0" "$W/s1" "$W/s2" > "$W/m.out" 2>&1; rc=$?
  set -e
  [ $rc -eq 0 ] || [ $rc -eq 6 ] || { echo "FAIL: merge exit $rc"; cat "$W/m.out"; exit 1; }
  same "$W/m" "$W/j2"
  for k in 000000 000003 000005; do [ -f "$W/m/runs/$k/manifest.json" ] || { echo "FAIL: merged runs/$k missing"; exit 1; }; done
  echo "ok: 3 shards merged = the whole campaign"
  # --only: the chosen runs' rows are those of the whole campaign
  "$K" mc "$SC" --runs $N --only 1,4 -o "$W/only" > /dev/null 2>&1 || [ $? -eq 6 ]
  for k in 1 4; do
    a=$(grep "^$k," "$W/j2/summary.csv"); b=$(grep "^$k," "$W/only/summary.csv")
    [ "$a" = "$b" ] || { echo "FAIL: --only run $k differs"; exit 1; }
  done
  [ "$(($(wc -l < "$W/only/summary.csv") - 1))" -eq 2 ] || { echo "FAIL: --only 1,4 must give 2 rows"; exit 1; }
  echo "ok: --only 1,4 reruns runs 1 and 4 identically"
  # exit code: a criterion every run fails -> 6, failing runs listed
  set +e
  "$K" mc "$SC" --runs 2 -o "$W/fail" --set "fsw.mrp_fb.K=0.01" > "$W/fail.out" 2>&1; rc=$?
  set -e
  [ $rc -eq 6 ] && grep -q "failing runs: 0 1" "$W/fail.out" || { echo "FAIL: expected exit 6 with failing runs listed (rc $rc)"; cat "$W/fail.out"; exit 1; }
  grep -q '^0,[0-9]*,FAIL,"settled: ' "$W/fail/summary.csv" || { echo "FAIL: the failing reason is not in summary.csv"; head -3 "$W/fail/summary.csv"; exit 1; }
  # a second campaign into the same folder is refused, --force replaces it whole
  set +e
  "$K" mc "$SC" --runs 1 -o "$W/fail" > "$W/again.out" 2>&1; rc=$?
  set -e
  [ $rc -eq 5 ] || { echo "FAIL: an existing campaign folder must be refused (rc $rc)"; exit 1; }
  "$K" mc "$SC" --runs 1 -o "$W/fail" --force > /dev/null 2>&1 || [ $? -eq 6 ]
  [ ! -d "$W/fail/runs/000001" ] || { echo "FAIL: --force left the older campaign's run 1"; exit 1; }
  echo "ok: exit code 6 on failing runs; existing folder refused, --force replaces it whole"
  [ "$(stat -c %s "$W/j2/mc_report.html")" -gt 20000 ] && grep -q "s1_monte_carlo" "$W/j2/mc_report.html" ||
    { echo "FAIL: no campaign report page"; exit 1; }
  # Ctrl-C: the finished runs are written, marked incomplete; exit 130
  "$K" mc "$SC" --runs 400 -j 1 -o "$W/int" > "$W/int.out" 2>&1 &
  pid=$!
  for _ in $(seq 1 100); do [ "$(ls "$W"/.int.kestrel-work-*/runs 2>/dev/null | wc -l)" -ge 4 ] && break; sleep 0.1; done
  kill -INT $pid
  set +e
  wait $pid; rc=$?
  set -e
  [ $rc -eq 130 ] || { echo "FAIL: an interrupted campaign must exit 130 (rc $rc)"; cat "$W/int.out"; exit 1; }
  n=$(($(wc -l < "$W/int/summary.csv") - 1))
  [ "$n" -ge 3 ] && [ "$n" -lt 400 ] || { echo "FAIL: the interrupted campaign holds $n runs"; exit 1; }
  grep -q '"complete": false' "$W/int/mc_manifest.json" || { echo "FAIL: not marked incomplete"; exit 1; }
  [ "$(ls "$W/int/runs" | wc -l)" -eq "$n" ] || { echo "FAIL: run folders without records"; exit 1; }
  for k in $(cut -d, -f1 "$W/int/summary.csv" | tail -n +2); do  # each recorded run is the whole campaign's
    a=$(grep "^$k," "$W/int/summary.csv"); b=$("$K" mc "$SC" --runs 400 --only "$k" -o "$W/int-$k" > /dev/null 2>&1 || true; grep "^$k," "$W/int-$k/summary.csv")
    [ "$a" = "$b" ] || { echo "FAIL: interrupted campaign's run $k differs from its rerun"; exit 1; }
    break
  done
  echo "ok: Ctrl-C keeps the $n finished runs, marked incomplete, exit 130"
  ;;
mpi)
  command -v mpirun > /dev/null || { echo "SKIP: mpirun not installed (scripts/install-deps.sh host installs OpenMPI)"; exit 77; }
  reference
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
  set +e
  timeout 300 mpirun -np 2 --oversubscribe "$K" mc "$SC" --runs $N -o "$W/mpi" > "$W/mpi.out" 2>&1; rc=$?
  set -e
  [ $rc -eq 0 ] || [ $rc -eq 6 ] || { echo "FAIL: mpirun exit $rc"; cat "$W/mpi.out"; exit 1; }
  same "$W/mpi" "$W/j2"
  echo "ok: mpirun -np 2 identical to -j2 ($N runs)"
  ;;
slurm)
  for t in slurmctld slurmd sbatch munged; do
    command -v $t > /dev/null || [ -x /usr/sbin/$t ] || { echo "SKIP: $t not installed (scripts/install-deps.sh host installs slurm-wlm and munge)"; exit 77; }
  done
  [ "$(id -u)" -eq 0 ] || { echo "SKIP: the one-node Slurm of this test needs root (SlurmUser=root)"; exit 77; }
  reference
  SLURM_W="$W/slurm"
  bash "$(dirname "$0")/../../scripts/slurm-local.sh" start "$SLURM_W" > "$W/slurm-start.out" 2>&1 || {
    echo "SKIP: a local Slurm could not start on this machine:"; cat "$W/slurm-start.out"; exit 77; }
  export SLURM_CONF="$SLURM_W/slurm.conf"
  "$K" mc "$SC" --runs $N --slurm 3 -o "$W/sl" > "$W/sl.out"
  "$W/sl.slurm/submit.sh" > "$W/submit.out"
  for _ in $(seq 1 240); do
    [ -f "$W/sl/summary.csv" ] && break
    sleep 0.5
  done
  [ -f "$W/sl/summary.csv" ] || { echo "FAIL: the Slurm merge did not produce the campaign in 120 s"; squeue || true;
    cat "$W"/sl.slurm/logs/* 2>/dev/null | tail -20; exit 1; }
  same "$W/sl" "$W/j2"
  echo "ok: a Slurm array of 3 shards + merge identical to -j2 ($N runs)"
  ;;
*) echo "usage: $0 KESTREL SCENARIO cli|mpi|slurm"; exit 2 ;;
esac
