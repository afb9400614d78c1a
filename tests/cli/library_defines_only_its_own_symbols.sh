#!/usr/bin/env bash
# Fails if a library or object defines a symbol with external linkage outside the names it owns.
#
# By default the libraries users link may define only symbols of namespace liftmap (no interposition of libgomp's,
# SuiteSparse's or any other library's entry points, no copy of a header-only library's implementation that would
# clash with the host's); weak symbols (template instances, inline functions) are allowed, since the linker merges
# them with the host's.
#
# --weak-too counts every global symbol (nm's upper-case types: common, indirect and absolute ones too) and the weak
# and unique ones (u, v, w), for an object compiled with other flags than the rest (the AVX2 build of the
# factorisation's arithmetic): the linker keeps one copy of a weak symbol, and that object's copy would then run on
# every CPU. The C++ runtime's personality reference (the same pointer in every object) is allowed.
# --own REGEX replaces the owned names: an extended regular expression matched against the mangled name.
# Every input must define at least one such symbol, or it is not the file expected.
#
# Usage: library_defines_only_its_own_symbols.sh [--weak-too] [--own REGEX] FILE.a|FILE.o ...
set -euo pipefail
types='^[TDBRGS]$'
own='^_Z(N|NK|ZN|ZNK|GVZN|GVZNK|TVN|TSN|TIN|THN)?7liftmap'
while [ $# -gt 0 ]; do
  case "$1" in
    --weak-too) types='^[A-Zuvw]$'; shift ;;
    --own) own="$2"; shift 2 ;;
    *) break ;;
  esac
done
[ $# -gt 0 ] || { echo "usage: $0 [--weak-too] [--own REGEX] FILE ..." >&2; exit 2; }
status=0
for file in "$@"; do
  defined=$(nm --defined-only "$file" | awk -v types="$types" '$2 ~ types {print $3}')
  if [ -z "$defined" ]; then
    echo "$file defines no symbol of the kinds checked: not the file expected" >&2
    status=1
    continue
  fi
  foreign=$(echo "$defined" | grep -v -E "$own" | grep -v -x 'DW.ref.__gxx_personality_v0' || true)
  if [ -n "$foreign" ]; then
    echo "$file defines symbols outside the names it owns ($own):" >&2
    echo "$foreign" | head -20 >&2
    status=1
  fi
done
[ $status -eq 0 ] && echo "$# files define only their own symbols ($own)"
exit $status
