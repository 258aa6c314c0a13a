#!/usr/bin/env bash
# MC/DC (modified condition/decision coverage) of the flight library
# (fsw_c/src) after the FSW tests.  Configures and builds a small sub-build
# of the flight library and its tests only (no plant, no harness) with
# clang 19's source-based coverage and MC/DC instrumentation, runs the FSW
# tests (label fsw), merges the profiles and reports with llvm-cov:
# per-file table, gaps (every decision with a condition not shown to
# act independently), a JSON summary and a one-line summary.  Fails when
# MC/DC falls below the ratchet (a minimum percent of conditions covered and
# a maximum number of uncovered conditions).
#
#   scripts/mcdc-report.sh BUILD_DIR SOURCE_DIR MIN_PERCENT MAX_UNCOVERED [LAUNCHER]
#
# Tools: clang-19, clang++-19, llvm-profdata-19, llvm-cov-19 (Debian 12:
# apt-get install clang-19 llvm-19); override with KESTREL_MCDC_CLANG,
# KESTREL_MCDC_CLANGXX, KESTREL_MCDC_PROFDATA, KESTREL_MCDC_COV.
set -euo pipefail
build="$(realpath "$1")"; src="$(realpath "$2")"; min_pct="$3"; max_unc="$4"; launcher="${5:-}"
cc="${KESTREL_MCDC_CLANG:-clang-19}"
cxx="${KESTREL_MCDC_CLANGXX:-clang++-19}"
profdata="${KESTREL_MCDC_PROFDATA:-llvm-profdata-19}"
cov="${KESTREL_MCDC_COV:-llvm-cov-19}"
for t in "$cc" "$cxx" "$profdata" "$cov"; do
  command -v "$t" >/dev/null || { echo "mcdc: $t not found (apt-get install clang-19 llvm-19, or scripts/install-deps.sh)" >&2; exit 2; }
done
out="$build/mcdc"
sub="$out/build"
mkdir -p "$out"
rm -rf "$out/profraw" "$out/html" "$out/summary.txt"
start=$(date +%s)

# The library and the C test support instrumented at -O0; the C++ tests are
# not (their coverage is not the question), which keeps the build short.
flags="-O0 -fprofile-instr-generate -fcoverage-mapping -fcoverage-mcdc"
cfg=(-S "$src" -B "$sub" -G Ninja --fresh
     -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=
     -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS=-O0
     -DCMAKE_EXE_LINKER_FLAGS=-fprofile-instr-generate
     -DKESTREL_BUILD_TESTS=ON -DKESTREL_BUILD_SIM=OFF -DKESTREL_BUILD_HARNESS=OFF
     -DKESTREL_BUILD_BENCHMARKS=OFF -DKESTREL_BUILD_FUZZ=OFF -DKESTREL_INSTALL=OFF
     -DKESTREL_SANITIZE=OFF -DKESTREL_COVERAGE=OFF -DKESTREL_WERROR=ON)
if [ -n "$launcher" ]; then
  cfg+=(-DCMAKE_C_COMPILER_LAUNCHER="$launcher" -DCMAKE_CXX_COMPILER_LAUNCHER="$launcher")
fi
cmake "${cfg[@]}" > "$out/configure.log" 2>&1 || { cat "$out/configure.log" >&2; exit 1; }
# the FSW tests only: one executable per CTest test of label fsw
mapfile -t tests < <(ctest --test-dir "$sub" -N -L '^fsw$' | sed -n 's/^ *Test *#[0-9]*: *\([A-Za-z0-9_]*\)$/\1/p')
[ "${#tests[@]}" -gt 0 ] || { echo "mcdc: no FSW tests in $sub" >&2; exit 1; }
cmake --build "$sub" -j2 --target "${tests[@]}" > "$out/build.log" 2>&1 || { tail -50 "$out/build.log" >&2; exit 1; }
built=$(date +%s)
LLVM_PROFILE_FILE="$out/profraw/%m-%p.profraw" \
  ctest --test-dir "$sub" -L '^fsw$' -j2 --output-on-failure > "$out/ctest.log" 2>&1 || { tail -50 "$out/ctest.log" >&2; exit 1; }
"$profdata" merge -sparse -o "$out/fsw.profdata" "$out"/profraw/*.profraw

objs=()
for t in "${tests[@]}"; do
  exe=$(find "$sub/test" -type f -name "$t" -perm -u+x | head -1)
  [ -n "$exe" ] || { echo "mcdc: executable $t not found" >&2; exit 1; }
  if [ "${#objs[@]}" -eq 0 ]; then objs+=("$exe"); else objs+=(-object "$exe"); fi
done
srcs=("$src"/fsw_c/src/*.c)
common=(-instr-profile "$out/fsw.profdata" "${objs[@]}")
"$cov" report --show-mcdc-summary --show-branch-summary=false --show-region-summary=false \
  "${common[@]}" "${srcs[@]}" > "$out/files.txt"
"$cov" show --show-mcdc --show-mcdc-summary --format=text \
  "${common[@]}" "${srcs[@]}" > "$out/show.txt"
"$cov" export --format=text "${common[@]}" "${srcs[@]}" > "$out/export.json"

# Decisions and conditions of fsw_c/src; the gaps, one line per decision.
python3 - "$out" "$src" <<'PY'
import json, os, sys
out, src = sys.argv[1], os.path.realpath(sys.argv[2])
data = json.load(open(os.path.join(out, "export.json")))["data"][0]
dec = dec_full = 0
gaps = []
for f in data["files"]:
    name = os.path.relpath(os.path.realpath(f["filename"]), src)
    for r in f.get("mcdc_records", []):
        # [line, col, end line, end col, ..., conditions covered flags]
        covered = r[-1] if isinstance(r[-1], list) else []
        dec += 1
        if covered and all(covered):
            dec_full += 1
        else:
            miss = [i + 1 for i, c in enumerate(covered) if not c]
            gaps.append(f"{name}:{r[0]}:{r[1]}: {len(miss)} of {len(covered)} conditions not shown "
                        f"(C{', C'.join(map(str, miss))})")
t = data["totals"]["mcdc"]
with open(os.path.join(out, "gaps.txt"), "w") as g:
    g.write("\n".join(sorted(gaps, key=lambda s: (s.split(':')[0], int(s.split(':')[1])))) + ("\n" if gaps else ""))
with open(os.path.join(out, "figures.txt"), "w") as g:
    g.write(f"{dec} {dec_full} {t['count']} {t['covered']} {t['percent']:.2f}\n")
PY
read -r dec dec_full nc ncov pct < "$out/figures.txt"
unc=$((nc - ncov))
end=$(date +%s)
cat "$out/files.txt"
echo "mcdc gaps ($out/gaps.txt):"
cat "$out/gaps.txt"
line="mcdc fsw_c/src: ${pct}% of ${nc} conditions (${unc} uncovered), ${dec_full} of ${dec} decisions"
echo "$line; build $((built - start)) s, tests and report $((end - built)) s; annotated source $out/show.txt"
echo "$line" > "$out/summary.txt"
ok=$(awk -v p="$pct" -v mp="$min_pct" -v u="$unc" -v mu="$max_unc" 'BEGIN { print (p >= mp && u <= mu) ? 1 : 0 }')
if [ "$ok" != 1 ]; then
  echo "MC/DC fell below the ratchet: ${pct}% (min ${min_pct}%), ${unc} uncovered conditions (max ${max_unc})" >&2
  exit 1
fi
