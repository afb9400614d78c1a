#!/usr/bin/env bash
# Runs the tests labelled `solver` (the convex subproblem solvers, the joint flattening, whole maps, the CVXOPT
# differential test) once per OpenBLAS kernel that this CPU can execute, chosen with OPENBLAS_CORETYPE. liftmap's own
# code calls no BLAS (its sparse factorisation uses Eigen's kernels); a kernel changes the rounding of CVXOPT's BLAS
# calls in the differential test, and of anything that would call BLAS again: every result must hold under each.
# Fails if a kernel's run fails, or if OpenBLAS did not take the kernel asked for.
# Usage: scripts/test-blas-kernels.sh BUILD_DIR [JOBS [KERNEL ...]] (default: every kernel the CPU supports)
set -euo pipefail
build="${1:?usage: $0 BUILD_DIR [JOBS [KERNEL ...]]}"
jobs="${2:-2}"
shift $(($# < 2 ? $# : 2))
flags=" $(grep -m1 '^flags' /proc/cpuinfo | cut -d: -f2) "
has() { for f in "$@"; do [[ "$flags" == *" $f "* ]] || return 1; done; }
kernels=()
has pni && kernels+=(Prescott)  # SSE3 is 'pni' in /proc/cpuinfo
has ssse3 sse4_2 && kernels+=(Nehalem)
has avx && kernels+=(Sandybridge)
has avx2 fma && kernels+=(Haswell Zen)
has avx512f avx512bw avx512dq avx512vl && kernels+=(SkylakeX)
if [ $# -gt 0 ]; then
  for k in "$@"; do
    [[ " ${kernels[*]} " == *" $k "* ]] || { echo "test-blas-kernels: this CPU cannot run the kernel $k" >&2; exit 1; }
  done
  kernels=("$@")
fi
if [ ${#kernels[@]} -eq 0 ]; then
  echo "test-blas-kernels: no OpenBLAS x86-64 kernel matches this CPU's flags" >&2
  exit 1
fi
# The library libblas.so.3 resolves to (Debian's alternatives), asked for the kernel it runs.
libblas=$(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3)
corename() {
  OPENBLAS_CORETYPE="$1" /usr/bin/python3 -c "
import ctypes, sys
lib = ctypes.CDLL(sys.argv[1])
if not hasattr(lib, 'openblas_get_corename'):
    sys.exit('libblas.so.3 is not OpenBLAS: ' + sys.argv[1])
lib.openblas_get_corename.restype = ctypes.c_char_p
print(lib.openblas_get_corename().decode())" "$libblas"
}
echo "test-blas-kernels: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'); kernels: ${kernels[*]}"
failed=()
for k in "${kernels[@]}"; do
  got=$(corename "$k")
  if [ "${got,,}" != "${k,,}" ]; then
    echo "test-blas-kernels: OPENBLAS_CORETYPE=$k gave the kernel '$got'" >&2
    failed+=("$k")
    continue
  fi
  echo "== OPENBLAS_CORETYPE=$k (OpenBLAS reports '$got')"
  if ! OPENBLAS_CORETYPE="$k" ctest --test-dir "$build" --output-on-failure -j "$jobs" -L solver -LE slow; then
    failed+=("$k")
  fi
done
if [ ${#failed[@]} -ne 0 ]; then
  echo "test-blas-kernels: failed under ${failed[*]}" >&2
  exit 1
fi
echo "test-blas-kernels: passed under ${kernels[*]}"
