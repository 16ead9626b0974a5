#!/usr/bin/env bash
# The LP time of the limit analysis of any assembly (src/limit/limit_lp.f90, GLPK): a
# 20-block ring, a 10 x 10 wall and a 2,000-block wall. Builds bench/limit_lp.f90 against
# the kernel libraries of BUILD (default build/, a Release build).
# Usage: bench/limit_lp.sh [BUILD]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
inc=()
for c in core input assembly limit; do inc+=(-I "$build/modules/$c"); done
gfortran -O2 -J "$out" "${inc[@]}" "$root/bench/limit_lp.f90" \
  "$build/libvoussoir_limit.a" "$build/libvoussoir_assembly.a" "$build/libvoussoir_input.a" \
  "$build/libvoussoir_core.a" -lglpk -o "$out/limit_lp"
"$out/limit_lp"
