#!/usr/bin/env bash
# Install the Debian packages Kestrel needs, only those that are missing.
# Usage: scripts/install-deps.sh [host|targets|all]   (default: all)
set -euo pipefail
what="${1:-all}"
host_pkgs=(cmake ninja-build g++ gcc clang libgtest-dev googletest libbenchmark-dev
           universal-ctags  # tools/harness_shape_check.py: function lengths of the harness
           cppcheck  # tools/misra_check.py: MISRA C:2012 of the flight code (docs/misra-deviations.md)
           libeigen3-dev binutils python3 pkgconf libyaml-cpp-dev libhdf5-dev libcli11-dev nlohmann-json3-dev
           nodejs chromium python3-h5py lcov  # report: npm bundle at build time, headless test
           clang-19 llvm-19 libclang-rt-19-dev  # coverage preset: MC/DC of the flight library (-fcoverage-mcdc, llvm-cov, its profile runtime; docs/coverage.md)
           socat  # HWIL: the serial link tested over a pseudo-terminal pair
           valgrind  # kestrel bench --callgrind: instructions per tick (docs/performance.md)
           make xz-utils  # cFS closed loop: cFS builds with make; its bundle is a .tar.xz (docs/hwil.md, "cFS")
           openmpi-bin libopenmpi-dev slurm-wlm munge  # Monte Carlo: mpirun; the Slurm array test's one-node cluster
           libcpp-httplib-dev  # live view: the local HTTP server of `kestrel run --live`
           python3-jsonschema python3-yaml  # the scenario JSON Schema's test (docs/scenario-schema.md), the packet dictionary (tools/icd_gen.py)
           pybind11-dev python3-numpy python3-dev python3-matplotlib python3-pytest  # the kestrel Python module and its example (docs/python.md)
           frama-c-base why3 cvc4  # test fsw_eva (docs/eva.md): Frama-C's Eva and WP; why3 and cvc4 are only recommended by frama-c-base
           python3-pandas python3-setuptools python3-wheel python3-build python3-venv python3-pip  # Results.to_pandas(); pip install . / python3 -m build offline (docs/python.md)
           python3-nbclient python3-nbformat python3-ipykernel)  # the tutorial notebooks, executed by their test (examples/notebooks/, docs/python.md)
# NodeSource's nodejs ships npm and conflicts with Debian's npm package
command -v npm >/dev/null 2>&1 || host_pkgs+=(npm)
target_pkgs=(gcc-arm-none-eabi binutils-arm-none-eabi picolibc-arm-none-eabi
             libstdc++-arm-none-eabi-picolibc qemu-system-arm qemu-user
             g++-aarch64-linux-gnu g++-arm-linux-gnueabihf g++-s390x-linux-gnu)
# (with these, host-release also builds the processor-in-the-loop programs, docs/pil.md)
pkgs=()
case "$what" in
  host) pkgs=("${host_pkgs[@]}") ;;
  targets) pkgs=("${target_pkgs[@]}") ;;
  all) pkgs=("${host_pkgs[@]}" "${target_pkgs[@]}") ;;
  *) echo "install-deps.sh: unknown set '$what' (host|targets|all)" >&2; exit 2 ;;
esac
missing=()
for p in "${pkgs[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#pkgs[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
