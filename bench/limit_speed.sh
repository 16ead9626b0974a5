#!/usr/bin/env bash
# Wall time of one voussoir-limit call (read the input, four-hinge search both ways with
# the static check, minimum-thickness search, print the table) on the four seed arches
# (input/limit_seed_*.nml), averaged over N calls; no assertions. Builds nothing.
#   bash bench/limit_speed.sh [EXE=build/drivers/voussoir-limit] [N=20]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe=${1:-$root/build/drivers/voussoir-limit}
n=${2:-20}
[[ -x "$exe" ]] || { echo "limit_speed.sh: no executable $exe (build the project first)" >&2; exit 1; }
printf '%-22s %12s %12s\n' "input" "ms per call" "ms (--json)"
for arch in 180 156 132 118; do
  input=$root/input/limit_seed_$arch.nml
  row=()
  for mode in "" "--json"; do
    start=$(date +%s%N)
    for _ in $(seq "$n"); do
      "$exe" "$input" $mode >/dev/null
    done
    end=$(date +%s%N)
    row+=("$(awk -v t=$((end - start)) -v n="$n" 'BEGIN { printf "%.2f", t / n / 1e6 }')")
  done
  printf '%-22s %12s %12s\n' "limit_seed_$arch.nml" "${row[0]}" "${row[1]}"
done
echo "($n calls each, process start-up included; $exe)"
