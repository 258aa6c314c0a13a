#!/usr/bin/env bash
# Instructions per fsw_acs_cycle and per module update on the Cortex-M4F
# (docs/performance.md, "Flight cycle on the target").
#
#   bench/target/m4f_timing.sh [WORK_DIR]     (default build/m4f-timing)
#       builds bench/target/m4f_cycles.c with the cortex-m4f toolchain for
#       fsw_real double and float at -O2 and -Os (library and benchmark), runs
#       each under QEMU mps2-an386 with -icount shift=0 (1 ns of virtual time
#       per instruction), prints each build's table (min / median / max per
#       mode and item over the golden replay), the worst case per item across
#       the builds; m4f_fuzz_replay.cpp, every fsw_acs_cycle of the fuzz
#       corpus test/fuzz/fsw/corpus/acs (float builds too); m4f_link_replay.c,
#       each recorded closed loop of bench/target/data (S1, S2's burn, S3's
#       detumble and hold: a run's configuration image and packets) through
#       the PIL program's link node, the link around the cycle and the
#       cycle; and the share of a 10 Hz period the worst cycle (golden
#       replay, fuzz corpus, recordings) and the worst packet take on a CLOCK_MHZ
#       (default 168) part at CPI 1.0 and CPI_HIGH (default 1.5).
#   bench/target/m4f_timing.sh --check ELF
#       the counter's self-check (ctest m4f_instruction_counter): the
#       hand-counted routines' disassembly is what the check assumes, and
#       ELF (m4f-counter-check.elf) counts them exactly under QEMU.
# Prints figures; asserts nothing (except --check).
set -euo pipefail
cd "$(dirname "$0")/../.."
qemu=(qemu-system-arm -M mps2-an386 -cpu cortex-m4 -nographic -monitor none -serial none
      -semihosting-config enable=on,target=native -icount shift=0 -kernel)

if [[ "${1:-}" == "--check" ]]; then
  elf="${2:?usage: m4f_timing.sh --check m4f-counter-check.elf}"
  # m4f_count_loop must be `subs r0, r0, #1; bne <itself>; bx lr` (2 n + 1
  # instructions) and m4f_count_empty `bx lr` (1): the counts the program expects
  dis() { arm-none-eabi-objdump -d --no-show-raw-insn "$elf" |
          awk -v f="<$1>:" '$2 == f { on = 1; next } on && NF == 0 { on = 0 } on { $1 = ""; print }' | sed 's/^ *//; s/[ \t]\+/ /g'; }
  loop=$(dis m4f_count_loop); empty=$(dis m4f_count_empty)
  want_loop=$(printf 'subs r0, #1\nbne.n %s <m4f_count_loop>\nbx lr' "$(arm-none-eabi-nm "$elf" | awk '$3 == "m4f_count_loop" { sub(/^0+/, "", $1); print $1 }')")
  if [[ "$loop" != "$want_loop" || "$empty" != "bx lr" ]]; then
    printf 'm4f counter self-check: unexpected disassembly\nm4f_count_loop:\n%s\nm4f_count_empty:\n%s\n' "$loop" "$empty"
    exit 1
  fi
  echo "m4f counter self-check: disassembly of m4f_count_loop (3 instructions, 2 n + 1 executed) and m4f_count_empty (1) as assumed"
  timeout 60 "${qemu[@]}" "$elf"
  exit $?
fi

work="${1:-build/m4f-timing}"
clock="${CLOCK_MHZ:-168}"
cpi_hi="${CPI_HIGH:-1.5}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
builds=(double:-O2 float:-O2 double:-Os float:-Os)
for b in "${builds[@]}"; do
  real=${b%%:*} opt=${b#*:} dir="$work/$real${opt}"
  cmake -S . -B "$dir" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$PWD/toolchains/cortex-m4f.cmake" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_C_FLAGS_RELEASE="$opt -DNDEBUG" -DKESTREL_REAL="$real" -DKESTREL_WERROR=ON -DKESTREL_BUILD_TESTS=OFF \
    -DKESTREL_BUILD_SIM=OFF -DKESTREL_BUILD_HARNESS=OFF -DKESTREL_BUILD_BENCHMARKS=OFF -DKESTREL_INSTALL=OFF \
    -DKESTREL_BUILD_FSW_M4F=OFF -DKESTREL_BUILD_M4F_TIMING=ON "${launcher[@]}" >"$out/cmake.log" 2>&1 ||
    { cat "$out/cmake.log"; exit 1; }
  targets=(m4f_cycles m4f_counter_check m4f_fuzz_replay m4f_link_replay)
  cmake --build "$dir" --target "${targets[@]}" >"$out/build.log" 2>&1 || { cat "$out/build.log"; exit 1; }
  # semihosting writes to QEMU's stderr
  "${qemu[@]}" "$dir/bench/target/m4f-counter-check.elf" >"$out/check-$real$opt.txt" 2>&1
  "${qemu[@]}" "$dir/bench/target/m4f-cycles.elf" >"$out/$real$opt.txt" 2>&1
  echo "== fsw_real $real, $opt (GCC $(arm-none-eabi-gcc -dumpversion), -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard)"
  cat "$out/check-$real$opt.txt" "$out/$real$opt.txt"
  "${qemu[@]}" "$dir/bench/target/m4f-fuzz-replay.elf" >"$out/fuzz-$real$opt.txt" 2>&1
  "${qemu[@]}" "$dir/bench/target/m4f-link-replay.elf" >"$out/link-$real$opt.txt" 2>&1
  cat "$out/fuzz-$real$opt.txt" "$out/link-$real$opt.txt"
done

echo
echo "== worst case (max over the replay) per mode and item, instructions"
printf '| mode, actuation | item |'; for b in "${builds[@]}"; do printf ' %s %s |' "${b%%:*}" "${b#*:}"; done; echo
printf '| --- | --- |'; for _ in "${builds[@]}"; do printf ' ---: |'; done; echo
files=(); for b in "${builds[@]}"; do files+=("$out/${b%%:*}${b#*:}.txt"); done
awk -F'|' -v nb="${#builds[@]}" '
  FNR == 1 { f++ }
  $4 ~ /^ *[0-9]+ *$/ { key = $2 "|" $3; if (!(key in seen)) { seen[key] = 1; order[++n] = key } v[key, f] = $7 + 0 }
  END { for (i = 1; i <= n; i++) { printf "|%s|", order[i]; for (j = 1; j <= nb; j++) printf " %d |", v[order[i], j]; print "" } }' "${files[@]}"

echo
echo "== fsw_acs_cycle per mode and real type, median / max over each replay, instructions"
printf '| replay | mode, actuation |'; for b in "${builds[@]}"; do printf ' %s %s |' "${b%%:*}" "${b#*:}"; done; echo
printf '| --- | --- |'; for _ in "${builds[@]}"; do printf ' ---: |'; done; echo
files=()
for src in golden fuzz link; do
  for b in "${builds[@]}"; do
    case $src in golden) files+=("$out/${b%%:*}${b#*:}.txt") ;; *) files+=("$out/$src-${b%%:*}${b#*:}.txt") ;; esac
  done
done
awk -F'|' -v nb="${#builds[@]}" '
  function cell(k) { return (k in v) ? v[k] : "-" }
  FNR == 1 { f++; kind = f <= nb ? "golden" : f <= 2 * nb ? "fuzz" : "link"; col = (f - 1) % nb + 1
             src = kind == "golden" ? "golden replay" : kind == "fuzz" ? "fuzz corpus" : "" }
  kind == "link" && /^m4f_link_replay: recording / { split($0, w, " "); sub(/:$/, "", w[3]); src = w[3] " packets" }
  kind == "fuzz" && $3 ~ /^ *[0-9]+ *$/ { r = src "|" $2 }
  kind != "fuzz" && $3 ~ /^ *fsw_acs_cycle *$/ { r = src "|" $2 }
  kind == "link" && $3 ~ /whole packet/ { r = src ", with the link|" $2 }
  r != "" { if (!(r in seen)) { seen[r] = 1; order[++n] = r }
            gsub(/ /, "", $6); gsub(/ /, "", $7); v[r, col] = $6 " / " $7; r = "" }
  END { for (i = 1; i <= n; i++) { split(order[i], p, "|"); printf "| %s |%s|", p[1], p[2]
                                   for (j = 1; j <= nb; j++) printf " %s |", cell(order[i] SUBSEP j); print "" } }' "${files[@]}"

echo
echo "== share of a 10 Hz period (100 ms) for the worst fsw_acs_cycle, at $clock MHz"
for b in "${builds[@]}"; do
  f="$out/${b%%:*}${b#*:}.txt" z="$out/fuzz-${b%%:*}${b#*:}.txt" l="$out/link-${b%%:*}${b#*:}.txt"
  # fsw_acs_cycle over the golden replay, the fuzz corpus and the recordings
  # (the line scripts/evidence.sh quotes: "worst N instructions"); then the
  # recordings' worst whole packet (the link around the cycle, and the cycle)
  awk -F'|' -v b="${b%%:*} ${b#*:}" -v mhz="$clock" -v hi="$cpi_hi" '
    function line(what, w, m) {
      gsub(/^ +| +$/, "", m); gsub(/  +/, " ", m)
      printf "%-11s %s %7d instructions (%s): CPI 1.0 %.3f ms = %.2f %% of the period; CPI %s %.3f ms = %.2f %%\n",
             b, what, w, m, w / mhz / 1e3, w / mhz / 1e3, hi, w * hi / mhz / 1e3, w * hi / mhz / 1e3 }
    FILENAME ~ /\/fuzz-/ { if ($3 ~ /^ *[0-9]+ *$/ && $7 + 0 > w) { w = $7 + 0; m = $2 " fuzz input " $8 }; next }
    FILENAME ~ /\/link-/ && /^m4f_link_replay: recording / { split($0, q, " "); sub(/:$/, "", q[3]); rec = q[3] }
    FILENAME ~ /\/link-/ && $3 ~ /fsw_acs_cycle/ && $7 + 0 > w { w = $7 + 0; m = $2 " " rec " packets" }
    FILENAME ~ /\/link-/ && $3 ~ /whole packet/ && $7 + 0 > p { p = $7 + 0; pm = $2 " " rec }
    FILENAME !~ /\/(fuzz|link)-/ && $3 ~ /fsw_acs_cycle/ && $7 + 0 > w { w = $7 + 0; m = $2 }
    END { line("worst", w, m); if (p > 0) line("packet, link and cycle, max", p, pm) }' "$f" "$z" "$l"
done
