#!/usr/bin/env bash
# `kestrel mc --resume` (docs/monte-carlo.md, "Interrupted campaigns"): a
# short campaign (test/harness/data/mc_short.yaml, 24 runs of 20 s) run
# whole, then run again and killed (SIGKILL) once some runs have finished,
# resumed; and again stopped (SIGTERM), resumed.  Each resumed campaign's
# folder must equal the whole one file for file: summary.csv, mc_runs.json,
# mc_report_data.json, mc_report.html and mc_manifest.json byte for byte
# (the wall-clock figures "wall_seconds" blanked), summary.h5 and every
# run's results.h5 dataset for dataset and attribute for attribute
# (mc_compare.py), every run folder's files as results_digest.py digests
# them.  A resume must also have run only the missing runs (the records
# already there are not rewritten), and --resume refuses another campaign.
#   mc_resume_test.sh KESTREL SCENARIO
set -uo pipefail
K="$1"
S="$2"
here=$(cd "$(dirname "$0")" && pwd)
PY=/usr/bin/python3
W=$(mktemp -d /tmp/kestrel-mc-resume.XXXXXX)
trap 'rm -rf "$W"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$PY" -c "import h5py" 2> /dev/null || { echo "SKIP: h5py is missing for $PY"; exit 77; }
N=24
ARGS=(--runs "$N" --seed 11)

"$K" mc "$S" "${ARGS[@]}" -j 2 -o "$W/whole" > /dev/null 2>&1
rc=$?
[ $rc -eq 0 ] || [ $rc -eq 6 ] || fail "whole campaign: exit $rc"

# Starts the campaign at -j1 into $W/$1, sends signal $2 once at least $3
# runs have a record (in the working folder), waits for it to end.
interrupt() {
  local out="$W/$1" sig=$2 want=$3 n=0
  "$K" mc "$S" "${ARGS[@]}" -j 1 -o "$out" > "$W/$1.log" 2>&1 &
  local pid=$!
  for _ in $(seq 1 3000); do
    n=$(ls "$W"/."$1".kestrel-work-*/records 2> /dev/null | grep -c '^[0-9]*\.json$')
    [ "$n" -ge "$want" ] && break
    sleep 0.01
  done
  kill -s "$sig" "$pid"
  wait "$pid"
  echo "$?"
}

# SIGKILL: nothing committed; the working folder keeps the finished runs
rc=$(interrupt killed KILL 5)
[ "$rc" -eq 137 ] || fail "SIGKILL: exit $rc (the campaign ended before the signal?)"
[ -e "$W/killed" ] && fail "SIGKILL: the campaign folder exists"
had=$(ls "$W"/.killed.kestrel-work-*/records | grep -c '^[0-9]*\.json$')
[ "$had" -ge 5 ] && [ "$had" -lt "$N" ] || fail "SIGKILL: $had records kept"
"$K" mc "$S" "${ARGS[@]}" -j 2 --resume "$W/killed" > "$W/killed-resume.log" 2>&1
rc=$?
[ $rc -eq 0 ] || [ $rc -eq 6 ] || { cat "$W/killed-resume.log"; fail "resume after SIGKILL: exit $rc"; }
grep -q "resuming: $had of $N runs done, $((N - had)) to run" "$W/killed-resume.log" ||
  { cat "$W/killed-resume.log"; fail "the resume did not run just the $((N - had)) missing runs"; }
ls -a "$W" | grep -q '^\.killed\.kestrel-work' && fail "resume left the killed campaign's working folder"
"$PY" "$here/mc_compare.py" "$W/whole" "$W/killed" || fail "resumed after SIGKILL differs from the whole campaign"
echo "SIGKILL after $had of $N runs, resumed: identical"

# SIGTERM: the finished runs committed, marked incomplete, with their journal
rc=$(interrupt stopped TERM 5)
[ "$rc" -eq 143 ] || fail "SIGTERM: exit $rc (128 + 15 expected)"
grep -q '"complete": false' "$W/stopped/mc_manifest.json" || fail "SIGTERM: not marked incomplete"
had=$(ls "$W/stopped/records" | grep -c '^[0-9]*\.json$')
grep -q -- "--resume" "$W/stopped.log" || fail "SIGTERM: the message does not say how to resume"
# another campaign (seed) is refused, and leaves the folder as it was
"$K" mc "$S" --runs "$N" --seed 12 --resume "$W/stopped" > "$W/refused.log" 2>&1 && fail "--resume of another seed ran"
grep -q "master_seed" "$W/refused.log" || { cat "$W/refused.log"; fail "the refusal does not name the master seed"; }
"$K" mc "$S" --runs $((N + 1)) --seed 11 --resume "$W/stopped" > "$W/refused.log" 2>&1 && fail "--resume of another run count ran"
grep -q "runs" "$W/refused.log" || fail "the refusal does not name the runs"
"$K" mc "$S" "${ARGS[@]}" --set duration=21 --resume "$W/stopped" > "$W/refused.log" 2>&1 && fail "--resume of another scenario ran"
grep -q "scenario" "$W/refused.log" || fail "the refusal does not name the scenario"
[ "$(ls "$W/stopped/records" | grep -c '^[0-9]*\.json$')" -eq "$had" ] || fail "a refused resume changed the folder"
# a journal record is read as merge reads a shard: a damaged one (its
# metrics emptied), another run's under its name, or a link is refused,
# naming the file, and nothing moves
rec=$(ls "$W/stopped/records" | grep '^[0-9]*\.json$' | head -1)
other=$(ls "$W/stopped/records" | grep '^[0-9]*\.json$' | sed -n 2p)
cp "$W/stopped/records/$rec" "$W/record.bak"
"$PY" - "$W/stopped/records/$rec" <<'PYEOF'
import json, sys
p = sys.argv[1]
j = json.load(open(p))
def empty_metrics(x):
    if isinstance(x, dict):
        if "metrics" in x:
            x["metrics"] = []
            return True
        return any(empty_metrics(v) for v in x.values())
    if isinstance(x, list):
        return any(empty_metrics(v) for v in x)
    return False
assert empty_metrics(j), "no metrics in the record"
json.dump(j, open(p, "w"))
PYEOF
for damage in metrics other link; do
  case $damage in
    other) cp "$W/stopped/records/$other" "$W/stopped/records/$rec" ;;
    link) rm "$W/stopped/records/$rec"; ln -s "$W/record.bak" "$W/stopped/records/$rec" ;;
  esac
  "$K" mc "$S" "${ARGS[@]}" --resume "$W/stopped" > "$W/refused.log" 2>&1 && fail "--resume with a $damage-damaged record ran"
  grep -q "records/$rec" "$W/refused.log" || { cat "$W/refused.log"; fail "the $damage refusal does not name the record"; }
  grep -q "not resuming" "$W/refused.log" || { cat "$W/refused.log"; fail "the $damage refusal does not say it did not resume"; }
done
rm "$W/stopped/records/$rec"
cp "$W/record.bak" "$W/stopped/records/$rec"
[ "$(ls "$W/stopped/records" | grep -c '^[0-9]*\.json$')" -eq "$had" ] || fail "a refused resume changed the folder"
"$K" mc "$S" "${ARGS[@]}" -j 2 --resume "$W/stopped" > "$W/stopped-resume.log" 2>&1
rc=$?
grep -q "resuming: $had of $N runs done, $((N - had)) to run" "$W/stopped-resume.log" ||
  { cat "$W/stopped-resume.log"; fail "the resume did not run just the $((N - had)) missing runs"; }
[ $rc -eq 0 ] || [ $rc -eq 6 ] || { cat "$W/stopped-resume.log"; fail "resume after SIGTERM: exit $rc"; }
"$PY" "$here/mc_compare.py" "$W/whole" "$W/stopped" || fail "resumed after SIGTERM differs from the whole campaign"
echo "SIGTERM after $had of $N runs, resumed: identical"

# a complete campaign has nothing to resume; no folder at all neither
"$K" mc "$S" "${ARGS[@]}" --resume "$W/whole" > "$W/refused.log" 2>&1 && fail "--resume of a complete campaign ran"
grep -q "complete" "$W/refused.log" || fail "no 'complete' in the refusal"
"$K" mc "$S" "${ARGS[@]}" --resume "$W/nothing" > "$W/refused.log" 2>&1 && fail "--resume of nothing ran"
echo "PASS"
