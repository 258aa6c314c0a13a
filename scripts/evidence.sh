#!/usr/bin/env bash
# Qualification evidence for the flight library, in one folder
# (docs/assurance.md says what each part shows and what it does not).
#
#   scripts/evidence.sh [OUT]          default OUT = evidence
#   EVIDENCE_PRESETS="host-release coverage cortex-m4f" scripts/evidence.sh
#
# Installs what it needs (scripts/install-deps.sh all), builds and tests the
# presets named in EVIDENCE_PRESETS (default: host-release, coverage,
# cortex-m4f; the whole suite is scripts/test-all.sh) from scratch, runs the
# analyses and writes OUT/index.md with one line per gate and a file per part:
#   versions.txt      commit, tree state and tool versions
#   tests.md          tests passed/failed per preset (names of the failed)
#   stack-<P>.txt     worst-case stack per public function, per preset
#   coverage.md       line and branch coverage of fsw_c/src (coverage preset)
#   mcdc.txt          MC/DC of fsw_c/src (clang 19)
#   misra.txt         MISRA C:2012 findings against the recorded deviations
#   eva.txt           Frama-C Eva alarms against the recorded justifications, WP goals
#   fuzz.md           executions per FSW fuzz harness and whether each still
#                     holds on this tree (test/fuzz/fsw/counts.csv)
#   timing.txt        instructions per fsw_acs_cycle and module on the M4F
#   footprint.txt     .text/.data/.bss and stack of the M4F programs
#   trace-matrix.md   requirement -> tests
# Content depends only on the commit and the tool versions: no times or dates
# except the one "written" line of index.md, so two runs compare with diff.
# The folder is written beside OUT and renamed into place at the end.
# Exit status: 0 when every gate passed, 1 otherwise (the folder is written
# either way, with the failures named in index.md).
set -uo pipefail
cd "$(dirname "$0")/.."
out="${1:-evidence}"
presets="${EVIDENCE_PRESETS:-host-release coverage cortex-m4f}"
scripts/install-deps.sh all || { echo "evidence: dependency installation failed" >&2; exit 1; }

tmp="$out.partial"
rm -rf "$tmp"; mkdir -p "$tmp/logs"
declare -a gates=()
gate() {  # gate NAME STATUS DETAIL
  gates+=("| $1 | $2 | $3 |")
}
first_line() { "$@" 2>&1 | head -n 1; }

# ---- versions -------------------------------------------------------------
{
  echo "commit: $(git rev-parse HEAD 2>/dev/null || echo unknown)"
  changed=$(git status --porcelain 2>/dev/null | grep -vc "^?? $out" || true)
  if [ "$changed" = 0 ]; then echo "tree: clean"; else echo "tree: $changed paths differ from the commit"; fi
  for t in cc gcc arm-none-eabi-gcc clang clang-19 llvm-cov-19 cmake cppcheck frama-c qemu-system-arm python3; do
    if command -v "$t" >/dev/null 2>&1; then
      echo "$t: $(first_line "$t" --version)"
    else
      echo "$t: not installed"
    fi
  done
} > "$tmp/versions.txt"

# ---- tests per preset, stack per preset -----------------------------------
{
  echo "# Tests per preset"
  echo
  echo "| preset | result | tests | failed |"
  echo "| --- | --- | ---: | --- |"
} > "$tmp/tests.md"
for p in $presets; do
  log="$tmp/logs/$p.log"
  if cmake --workflow --preset "$p" --fresh > "$log" 2>&1; then res=PASS; else res=FAIL; fi
  total=$(grep -Eo "tests failed out of [0-9]+" "$log" | tail -1 | awk '{print $NF}')
  failed=$(sed -n '/The following tests FAILED/,/^Errors while running/p' "$log" |
           sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\).*/\1/p' | sort | paste -sd, -)
  echo "| $p | $res | ${total:-0} | ${failed:-none} |" >> "$tmp/tests.md"
  gate "tests $p" "$res" "${total:-0} tests${failed:+, failed: $failed}"
  ctest --test-dir "build/$p" -R '^fsw_proof_stack$' -V 2>&1 |
    sed -n 's/^[0-9]*: //p' | grep -E '^(fsw_|largest|[[:space:]]*[0-9]+ )' > "$tmp/stack-$p.txt" || true
  [ -s "$tmp/stack-$p.txt" ] || rm -f "$tmp/stack-$p.txt"   # the coverage preset has no stack test
  largest=$(grep -Eo "largest: .* B over" "$tmp/stack-$p.txt" 2>/dev/null | sed 's/largest: //; s/ over//')
  [ -n "$largest" ] && gate "stack $p" PASS "largest $largest"
  # coverage: the coverage preset's report (scripts/coverage-report.sh)
  if [ -f "build/$p/coverage/summary.txt" ]; then
    { echo "# Line and branch coverage of fsw_c/src"; echo; cat "build/$p/coverage/summary.txt"; echo;
      echo '```'; cat "build/$p/coverage/files.txt"; echo '```'; } > "$tmp/coverage.md"
    gate "line/branch coverage" "$res" "$(sed 's/coverage fsw_c\/src: //' "build/$p/coverage/summary.txt")"
  fi
  if [ -f "build/$p/mcdc/summary.txt" ]; then
    { cat "build/$p/mcdc/summary.txt"; echo; cat "build/$p/mcdc/files.txt";
      echo; echo "Decisions not fully covered (each justified in docs/coverage.md):"; cat "build/$p/mcdc/gaps.txt"; } > "$tmp/mcdc.txt"
    gate "MC/DC" "$res" "$(cat "build/$p/mcdc/summary.txt")"
  fi
done
# The log files carry times: kept for the reader, not part of the comparison.
mv "$tmp/logs" "$tmp/logs-not-compared"

# ---- analyses -------------------------------------------------------------
run_gate() {  # run_gate NAME FILE SUMMARY_REGEX SCRIPT ARGS...  (a .py runs under python3, else bash)
  local name="$1" file="$2" re="$3" script="$4"; shift 4
  if [ ! -e "$script" ]; then gate "$name" MISSING "$script not in this tree"; return; fi
  local run=bash; case "$script" in *.py) run=python3 ;; esac
  if "$run" "$script" "$@" > "$tmp/$file" 2>&1; then st=PASS; else st=FAIL; fi
  gate "$name" "$st" "$(grep -E "$re" "$tmp/$file" | tail -1)"
}
run_gate "requirements traceability" trace-run.txt "requirements" \
  tools/trace_matrix.py --root . -o "$tmp/trace-matrix.md" check

# MISRA C:2012 (cppcheck's addon) against the recorded deviations
run_gate "MISRA C:2012" misra.txt "^misra_check: Cppcheck" \
  tools/misra_check.py --root . --jobs 2

# timing and size on the Cortex-M4F (QEMU -icount; arm-none-eabi-size)
run_gate "instructions per cycle on the M4F" timing.txt "worst +[0-9]+ instructions" \
  bench/target/m4f_timing.sh "build/evidence-timing"
run_gate "flight footprint on the M4F" footprint.txt "^[a-z]+ +-Os +typical +ACS only" \
  bench/flight-footprint.sh "build/evidence-footprint"

# Frama-C Eva and WP: every driver of test/proofs/eva (the union of the suite's
# fsw_eva, fsw_eva_modules and fsw_eva_app tests, docs/eva.md); the analysis
# times are dropped so that two runs compare
if python3 tools/eva_check.py --root . --work build/evidence-eva --jobs 2 --timeout 120 \
     > "$tmp/eva-run.txt" 2>&1; then st=PASS; else st=FAIL; fi
sed -E 's/ +[0-9]+\.[0-9]s( |$)/\1/g; s/, [0-9]+\.[0-9] s wall, [0-9]+\.[0-9] s CPU of the analyses;/;/' "$tmp/eva-run.txt" > "$tmp/eva.txt"; rm -f "$tmp/eva-run.txt"
gate "Frama-C Eva / WP" "$st" "$(grep -E '^eva_check: [0-9]+ drivers' "$tmp/eva.txt" | tail -1)"

# fuzz: the last long run of each FSW harness (test/fuzz/fsw/counts.csv), and
# whether it still holds: none of the files its binary is built from changed
# since the commit it ran on (tools/fuzz_counts.py; docs/design/fuzzing.md)
{ echo "# Executions per FSW fuzz harness"; echo
  echo "The last long run of each harness, from test/fuzz/fsw/counts.csv; \"current\""
  echo "when no file the harness is built from changed since the commit it ran on."
  echo "How each run was made, and every finding: docs/design/fuzzing.md."
  echo "The committed corpora are replayed by the host-clang preset's fuzz tests."; echo; } > "$tmp/fuzz.md"
if python3 tools/fuzz_counts.py report --root . >> "$tmp/fuzz.md" 2>&1; then st=PASS; else st=FAIL; fi
gate "fuzzing" "$st" "$(grep -E '^fuzz_counts: ' "$tmp/fuzz.md" | tail -1 | sed 's/^fuzz_counts: //')"

# Paths inside the clone are written relative to it (the coverage and stack
# reports name files by absolute path), so that runs in two clones compare.
root_dir=$(pwd -P)
find "$tmp" -maxdepth 1 -type f -exec sed -i "s#$root_dir/##g" {} +

# ---- index ----------------------------------------------------------------
{
  echo "# Kestrel flight library: qualification evidence"
  echo
  echo "written: $(date -u +%Y-%m-%d)"
  echo
  sed 's/^/    /' "$tmp/versions.txt"
  echo
  echo "| gate | status | figures |"
  echo "| --- | --- | --- |"
  printf '%s\n' "${gates[@]}"
  echo
  echo "Files: $(cd "$tmp" && ls | grep -v '^index.md$' | paste -sd' ' -)"
  echo
  echo "What each part shows and what it does not: docs/assurance.md in the source tree."
} > "$tmp/index.md"

rm -rf "$out"; mv "$tmp" "$out"
echo "evidence: $out/index.md"
if printf '%s\n' "${gates[@]}" | grep -qE '\| (FAIL|MISSING) \|'; then
  printf '%s\n' "${gates[@]}" | grep -E '\| (FAIL|MISSING) \|' >&2
  exit 1
fi
