#!/usr/bin/env bash
# Installs the Debian packages liftmap needs to build, test and benchmark. Idempotent: runs apt-get only when a
# package is missing. Needs root (or sudo) on a Debian 12 machine.
# libopenblas0-serial: for `make test-blas-kernels`, which runs the solver tests under each OpenBLAS CPU kernel
# (OPENBLAS_CORETYPE). liftmap itself calls no BLAS (its sparse factorisation uses Eigen's kernels), so its results
# must not change with the kernel; CVXOPT, the differential test's independent solver, does call BLAS. OpenBLAS
# takes over libblas.so.3 through Debian's alternatives (priority 90 against the reference BLAS's 10).
set -euo pipefail
packages=(
  cmake ninja-build g++ make pkg-config
  libeigen3-dev libsuitesparse-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libopenblas0-serial
  libgtest-dev libcli11-dev nlohmann-json3-dev libstb-dev
  python3 python3-dev python3-numpy python3-cvxopt python3-matplotlib
  pybind11-dev python3-pytest python3-distributed
  clang-format clang-tidy
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
