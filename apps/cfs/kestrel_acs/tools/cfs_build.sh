#!/bin/sh
# cfs_build.sh SRC_TARBALL_OR_DIR BUILD_DIR
#
# Builds a native cFS (cFE + OSAL + PSP + lab apps) with the KESTREL_ACS
# application added out of tree, and installs it.  Idempotent: a second call
# reuses the unpacked tree, the mission definitions and the configured build,
# and rebuilds only what changed (the application, normally).
#
#   SRC_TARBALL_OR_DIR  a cFS bundle: a .tar.xz/.tar.gz of it, or an unpacked
#                       directory (the one holding cfe/, osal/, psp/, apps/, tools/)
#   BUILD_DIR           everything goes below it:
#                         BUILD_DIR/cfs           the unpacked tree (tarball input only)
#                         BUILD_DIR/kestrel_defs  mission definitions: a copy of
#                                                 cFE's sample_defs with kestrel_acs in
#                                                 cpu1's app list and startup script, and
#                                                 ci_lab/to_lab polling every 2 ms instead
#                                                 of 500 ms (lockstep: one command and one
#                                                 reply per control cycle)
#                         BUILD_DIR/build         the cmake build
#                         BUILD_DIR/build/exe/cpu1  the installed core-cpu1, cf/ and tables
#
# The last line of standard output is the installed cpu1 directory (the build's
# own output goes to standard error).  Exit status: 0 built, 2 bad arguments
# (no such tarball or directory, not a cFS bundle), 1 the build failed.
# Environment:
# CFS_JOBS (default 2) parallel jobs; KESTREL_ACS_APPS the directory holding
# kestrel_acs/ (default: this script's ../..).  The build runs under nice.
set -eu

if [ $# -ne 2 ]; then
  echo "usage: $0 SRC_TARBALL_OR_DIR BUILD_DIR" >&2
  exit 2
fi
SRC=$1
OUT=$2
JOBS=${CFS_JOBS:-2}
HERE=$(cd "$(dirname "$0")" && pwd)
APPS=${KESTREL_ACS_APPS:-$(cd "$HERE/../.." && pwd)}

mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

# 1. the cFS tree
if [ -d "$SRC" ]; then
  CFS=$(cd "$SRC" && pwd)
elif [ -f "$SRC" ]; then
  CFS=$OUT/cfs
  STAMP=$OUT/cfs/.kestrel_unpacked
  if [ ! -f "$STAMP" ] || [ "$(cat "$STAMP")" != "$(cd "$(dirname "$SRC")" && pwd)/$(basename "$SRC")" ]; then
    rm -rf "$CFS"
    mkdir -p "$CFS"
    tar -xf "$SRC" -C "$CFS"
    # a tarball holding one top-level directory: use it
    if [ ! -d "$CFS/cfe" ] && [ "$(ls "$CFS" | wc -l)" -eq 1 ]; then
      inner=$CFS/$(ls "$CFS")
      mv "$inner"/* "$inner"/.[!.]* "$CFS"/ 2>/dev/null || true
      rmdir "$inner" 2>/dev/null || true
    fi
    echo "$(cd "$(dirname "$SRC")" && pwd)/$(basename "$SRC")" > "$STAMP"
  fi
else
  echo "cfs_build.sh: no cFS tree or tarball at '$SRC'" >&2
  exit 2
fi
for d in cfe osal psp apps/ci_lab apps/to_lab tools; do
  if [ ! -d "$CFS/$d" ]; then
    echo "cfs_build.sh: '$CFS' is not a cFS bundle (no $d/)" >&2
    exit 2
  fi
done
if [ ! -f "$APPS/kestrel_acs/CMakeLists.txt" ]; then
  echo "cfs_build.sh: no kestrel_acs application under '$APPS'" >&2
  exit 2
fi

# 2. mission definitions: cFE's sample_defs, with the application added
DEFS=$OUT/kestrel_defs
DEFS_VERSION=3   # bump when the edits below change: the build is then configured afresh
if [ ! -f "$DEFS/.kestrel_defs_done" ] || [ "$(cat "$DEFS/.kestrel_defs_done")" != "$DEFS_VERSION" ]; then
  rm -rf "$DEFS" "$OUT/build"
  cp -r "$CFS/cfe/cmake/sample_defs" "$DEFS"
  # config files are found by the MISSIONCONFIG prefix
  mv "$DEFS/sample_perfids.h" "$DEFS/kestrel_perfids.h"
  sed -i 's/^SET(cpu1_APPLIST \(.*\))/SET(cpu1_APPLIST \1 kestrel_acs)/' "$DEFS/targets.cmake"
  grep -q '^SET(cpu1_APPLIST .*kestrel_acs)' "$DEFS/targets.cmake" || {
    echo "cfs_build.sh: could not add kestrel_acs to cpu1_APPLIST in $DEFS/targets.cmake" >&2
    exit 1
  }
  # the startup line goes before the '!' terminator
  awk 'BEGIN { done = 0 }
       /^!/ && !done { print "CFE_APP, kestrel_acs, KESTREL_ACS_AppMain, KESTREL_ACS,  90,   32768, 0x0, 0;"; done = 1 }
       { print }' "$DEFS/cpu1_cfe_es_startup.scr" > "$DEFS/cpu1_cfe_es_startup.scr.new"
  mv "$DEFS/cpu1_cfe_es_startup.scr.new" "$DEFS/cpu1_cfe_es_startup.scr"
  # ci_lab reads its UDP socket after each 500 ms software-bus wait and to_lab
  # forwards telemetry every 500 ms: 2 cycles a second at best in lockstep.
  # Overrides in the defs dir (a platform config file found by its own name)
  # make both poll every 2 ms.
  sed 's/^#define CI_LAB_SB_RECEIVE_TIMEOUT .*/#define CI_LAB_SB_RECEIVE_TIMEOUT 2 \/* [ms] KESTREL: was 500 *\//' \
    "$CFS/apps/ci_lab/config/default_ci_lab_internal_cfg.h" > "$DEFS/ci_lab_internal_cfg.h"
  sed 's/^#define TO_LAB_TASK_MSEC .*/#define TO_LAB_TASK_MSEC 2 \/* [ms] KESTREL: was 500 *\//' \
    "$CFS/apps/to_lab/config/default_to_lab_internal_cfg.h" > "$DEFS/to_lab_internal_cfg.h"
  grep -q 'KESTREL: was 500' "$DEFS/ci_lab_internal_cfg.h" && grep -q 'KESTREL: was 500' "$DEFS/to_lab_internal_cfg.h" || {
    echo "cfs_build.sh: could not set the ci_lab/to_lab polling periods" >&2
    exit 1
  }
  echo "$DEFS_VERSION" > "$DEFS/.kestrel_defs_done"
fi

# 3. configure once (MISSION_DEFS and CFS_APP_PATH are cached by cFE's build:
#    a build configured for another tree, definitions or application directory
#    is started afresh)
BLD=$OUT/build
KEY="$CFS|$DEFS|$APPS"
if [ -d "$BLD" ] && [ "$(cat "$BLD/.kestrel_config" 2>/dev/null)" != "$KEY" ]; then
  rm -rf "$BLD"
fi
mkdir -p "$BLD"
if [ ! -f "$BLD/CMakeCache.txt" ]; then
  if ! (cd "$BLD" && SIMULATION=native nice cmake -DCMAKE_BUILD_TYPE=debug -DCMAKE_INSTALL_PREFIX=/exe \
     -DMISSIONCONFIG=kestrel -DMISSION_DEFS="$DEFS" -DCFS_APP_PATH="$APPS" "$CFS/cfe") >&2; then
    rm -f "$BLD/CMakeCache.txt"
    echo "cfs_build.sh: cmake configuration failed in $BLD" >&2
    exit 1
  fi
  echo "$KEY" > "$BLD/.kestrel_config"
fi

# 4. build and install
if ! (cd "$BLD" && nice make -j"$JOBS" mission-all && nice make DESTDIR="$BLD" mission-install) >&2; then
  echo "cfs_build.sh: build failed in $BLD" >&2
  exit 1
fi
test -f "$BLD/exe/cpu1/core-cpu1" && test -f "$BLD/exe/cpu1/cf/kestrel_acs.so" || {
  echo "cfs_build.sh: build finished without exe/cpu1/core-cpu1 and cf/kestrel_acs.so" >&2
  exit 1
}
echo "$BLD/exe/cpu1"
