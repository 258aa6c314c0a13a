#!/usr/bin/env bash
# Processor-in-the-loop figures (docs/pil.md):
#   1. lockstep FSW cycles per second of wall time through each PIL link:
#      S1 for SECONDS of simulated time (10 FSW cycles per second), the wall
#      time measured around the whole `kestrel run` (emulator start-up and
#      shutdown included, so short runs understate the steady rate);
#   2. the Cortex-M4F program's .text / .data / .bss per real type;
#   3. its worst-case stack: the main loop's own frame (-fstack-usage) plus
#      the deepest FSW call it makes (fsw_link_node_receive, from the flight
#      library's stack report, tools/fsw_stack_report.py), plus the UART
#      interrupt (its frame and the exception stacking of 26 words with the
#      FPU context) that can arrive on top of it.
#
#   bench/pil.sh [build-dir]        (default build/host-release)
#   SECONDS_LINUX (default 600, the whole S1), SECONDS_M4F (default 30) override the run lengths.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/host-release}"
k="$build/harness/kestrel"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cycles_per_s() {  # target seconds
  local t0 t1
  t0=$(date +%s.%N)
  "$k" run scenarios/s1_sun_pointing.yaml -o "$out/$1" --set duration="$2" --fsw "pil:$1" >/dev/null
  t1=$(date +%s.%N)
  awk -v s="$2" -v a="$t0" -v b="$t1" -v n="$1" \
    'BEGIN { c = s * 10 + 1; printf "%-18s %6d cycles in %6.2f s wall: %7.0f cycles/s\n", n, c, b - a, c / (b - a) }'
}
echo "== lockstep cycles/s through the PIL link (S1, FSW at 10 Hz)"
for t in aarch64-linux armhf-linux; do cycles_per_s "$t" "${SECONDS_LINUX:-600}"; done
for t in cortex-m4f cortex-m4f-float; do cycles_per_s "$t" "${SECONDS_M4F:-30}"; done

echo "== Cortex-M4F program (kestrel-fsw-m4f.elf), bytes"
printf "%-8s %8s %8s %8s %12s\n" real .text .data .bss "stack (w.c.)"
for v in cortex-m4f:double cortex-m4f-float:float; do
  dir="$build/pil/${v%%:*}"
  read -r text data bss _ < <(arm-none-eabi-size "$dir/flight/m4f/kestrel-fsw-m4f.elf" | tail -1)
  report=$(/usr/bin/python3 tools/fsw_stack_report.py --objdir "$dir/fsw_c/CMakeFiles/fsw.dir" \
           --archive "$dir/fsw_c/libkestrel_fsw.a" --nm arm-none-eabi-nm --objdump arm-none-eabi-objdump --limit 1000000)
  w() { echo "$report" | awk -v f="$1" '$3 == f { print $1 }'; }
  node=$(w fsw_link_node_receive)
  # the start-up calls (decode, check, init; picolibc's fprintf charged 256 B
  # like any call out of the library) run before the loop, not under it
  start=$(printf "%s\n" "$(w fsw_link_config_decode)" "$(w fsw_acs_check)" "$(w fsw_link_node_init)" 256 | sort -n | tail -1)
  deep=$(( node > start ? node : start ))
  su="$dir/flight/m4f/CMakeFiles/kestrel_fsw_m4f.dir/kestrel_fsw_m4f.c.su"
  main=$(awk -F'\t' '$1 ~ /:main$/ { print $2 }' "$su")
  isr=$(awk -F'\t' '$1 ~ /:uart0_rx_isr$/ { print $2 }' "$su")
  # main (load_config and send_replies inlined) + its deepest call (fsw_link_frame and
  # fsw_link_deframer_push are smaller than fsw_link_node_receive) + the ISR on top
  total=$((main + deep + isr + 26 * 4))
  printf "%-8s %8s %8s %8s %12s   (main %s + deepest call %s [fsw_link_node_receive %s] + UART ISR %s + 104 exception frame)\n" \
    "${v#*:}" "$text" "$data" "$bss" "$total" "$main" "$deep" "$node" "$isr"
done
