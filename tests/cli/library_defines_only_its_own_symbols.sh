#!/usr/bin/env bash
# The libraries users link define no symbol outside namespace liftmap with external linkage (no interposition of
# libgomp's, SuiteSparse's or any other library's entry points, no copy of a header-only library's implementation
# that would clash with the host's). Weak symbols (template instantiations, inline functions) are allowed: the
# linker merges them with the host's.
# Usage: library_defines_only_its_own_symbols.sh LIBRARY.a ...
set -euo pipefail
status=0
for lib in "$@"; do
  foreign=$(nm --defined-only "$lib" | awk '$2 ~ /^[TDBRGS]$/ {print $3}' |
    grep -v -E '^_Z(N|NK|ZN|ZNK|GVZN|GVZNK|TVN|TSN|TIN|THN)?7liftmap' || true)
  if [ -n "$foreign" ]; then
    echo "$lib defines symbols outside namespace liftmap:" >&2
    echo "$foreign" | head -20 >&2
    status=1
  fi
done
[ $status -eq 0 ] && echo "$# libraries define only liftmap's own symbols"
exit $status
