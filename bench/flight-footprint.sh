#!/usr/bin/env bash
# Flight footprint of the FSW library on the bare-metal Cortex-M4F
# (docs/flight-footprint.md).  Builds the two programs of bench/footprint
# with the cortex-m4f toolchain (GCC, picolibc) for a typical configuration,
# FSW_MAX_RW 4 and FSW_MAX_THR 8 (other capacities at their defaults), for
# fsw_real double and float at -Os and -O2:
#   with link  flight/m4f/kestrel_fsw_m4f.c: fsw_acs behind the FSW link
#              (deframer, codec, node, configuration image), UART, two console lines
#   ACS only   bench/footprint/acs_only.c: fsw_acs alone, configuration and
#              messages in memory
# each with every stage of fsw_acs ("full") and with the typical selection
# (FSW_CFG_<stage>=0 for the stages a wheel-and-thruster mission does not
# fly; the list is $typical below), and prints per program: .text/.data/.bss of the whole ELF
# (arm-none-eabi-size; .text includes .rodata, picolibc's start-up, libm
# and, for double, the soft-float routines), the part of .text that comes
# from the flight library's archive (from the link map), for the ACS-only
# program the "chain": its code linked without start-up files (the library
# with the libm, soft-float and string routines it calls), whether each of
# the two is under the goal of 32 KiB, and the worst-case
# stack: main's frame (-fstack-usage) + the deepest flight-library call it
# makes (tools/fsw_stack_report.py, the method of fsw_proof_stack); for the
# PIL program also its UART interrupt and 104 B of exception stacking.
# Built with warnings as errors, like every flight build.  Prints figures;
# asserts nothing.
#
#   bench/flight-footprint.sh [work-dir]     (default build/footprint)
set -euo pipefail
cd "$(dirname "$0")/.."
src="$PWD"
work="${1:-build/footprint}"
mkdir -p "$work"
launcher=()
if [ -n "${CMAKE_C_COMPILER_LAUNCHER:-}" ]; then launcher=(-DCMAKE_C_COMPILER_LAUNCHER="$CMAKE_C_COMPILER_LAUNCHER"); fi

lib_text() {  # map file [N] -> bytes of .text/.rodata input sections from libkestrel_fsw.a
  # (with N: the N largest archive members instead, one per line)
  python3 - "$1" "${2:-0}" <<'PY'
import re, sys
per, on, pending = {}, False, False
def add(size, where):
    m = re.search(r"libkestrel_fsw\.a\(([^)]+)\)", where)
    if m:
        name = m.group(1).replace(".c.obj", ".c")
        per[name] = per.get(name, 0) + int(size, 16)
for line in open(sys.argv[1], errors="replace"):
    if line.startswith("Linker script and memory map"):
        on = True
        continue
    if not on:
        continue
    m = re.match(r"^ (\.text|\.rodata)\S*(\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+(\S+))?", line)
    if m:
        pending = not m.group(2)
        if m.group(2):
            add(m.group(3), m.group(4))
        continue
    if pending:
        m = re.match(r"^\s+0x[0-9a-f]+\s+0x([0-9a-f]+)\s+(\S+)", line)
        if m:
            add(m.group(1), m.group(2))
        pending = False
n = int(sys.argv[2])
if n:
    for name, size in sorted(per.items(), key=lambda kv: -kv[1])[:n]:
        print(f"  {name:24s} {size:7d}")
else:
    print(sum(per.values()))
PY
}

# The typical selection of docs/flight-footprint.md: wheels (rw_map, rw_null,
# rw_sat), thrusters (thr_map, remainder pulsing), thruster momentum dumps,
# sun-safe and inertial pointing, thr_map in its default minimum-norm mode;
# everything else left out.
typical="MTQ;MTQ_DESAT;ORBIT;RW_BIAS;RW_VOLT;SPEED_FILTER;LPF;PULSE_SCHMITT;THR_NNLS"
goal=32768  # [B] the ACS chain without the link at -Os
fmt="%-7s %-4s %-8s %-9s %8s %6s %7s %10s %12s %6s %-s\n"
printf "$fmt" real opt stages program .text .data .bss "fsw .text" "chain .text" stack "under 32 KiB (fsw/chain)"
for real in double float; do
  for opt in Os O2; do
    for sel in full typical; do
      b="$work/$real-$opt-$sel"
      leave=""
      if [ "$sel" = typical ]; then leave="$typical"; fi
      cmake -S bench/footprint -B "$b" -G Ninja --fresh -DKESTREL_DIR="$src" \
        -DCMAKE_TOOLCHAIN_FILE="$src/toolchains/cortex-m4f.cmake" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_C_FLAGS_RELEASE="-$opt -DNDEBUG" -DKESTREL_REAL="$real" \
        -DKESTREL_FSW_MAX_RW=4 -DKESTREL_FSW_MAX_THR=8 -DKESTREL_FSW_LEAVE_OUT="$leave" \
        -DKESTREL_WERROR=ON "${launcher[@]}" > "$b.configure.log" 2>&1 \
        || { cat "$b.configure.log" >&2; exit 1; }
      cmake --build "$b" -j2 > "$b.build.log" 2>&1 || { tail -30 "$b.build.log" >&2; exit 1; }
      report=$(python3 tools/fsw_stack_report.py --objdir "$b/kestrel/fsw_c/CMakeFiles/fsw.dir" \
               --archive "$b/kestrel/fsw_c/libkestrel_fsw.a" --nm arm-none-eabi-nm --objdump arm-none-eabi-objdump \
               --limit 1000000)
      w() { for f in "$@"; do echo "$report" | awk -v f="$f" '$3 == f { print $1 }'; done | sort -n | tail -1; }
      for prog in acs_only with_link; do
        read -r text data bss _ < <(arm-none-eabi-size "$b/$prog.elf" | tail -1)
        su=$(find "$b/CMakeFiles/$prog.dir" -name '*.su')
        main=$(awk -F'\t' '$1 ~ /:main$/ { print $2 }' "$su")
        fsw=$(lib_text "$b/$prog.map")
        if [ "$prog" = acs_only ]; then
          deep=$(w fsw_acs_init fsw_acs_cycle)
          stack=$((main + deep))
          name="ACS only"
          chain=$(arm-none-eabi-size "$b/acs_chain.elf" | tail -1 | awk '{ print $1 }')
          verdict="$([ "$fsw" -le $goal ] && echo yes || echo no)/$([ "$chain" -le $goal ] && echo yes || echo no)"
        else
          deep=$(w fsw_link_node_receive fsw_link_config_decode fsw_acs_check fsw_link_node_init)
          isr=$(awk -F'\t' '$1 ~ /:uart0_rx_isr$/ { print $2 }' "$su")
          stack=$((main + deep + isr + 104))
          name="with link"
          chain="-"
          verdict=""
        fi
        printf "$fmt" "$real" "-$opt" "$sel" "$name" "$text" "$data" "$bss" "$fsw" "$chain" "$stack" "$verdict"
      done
    done
  done
done
for real in double float; do
  for sel in full typical; do
    echo "largest flight-library objects in the ACS-only program, $real -Os, $sel (.text + .rodata, bytes):"
    lib_text "$work/$real-Os-$sel/acs_only.map" 10
  done
done
