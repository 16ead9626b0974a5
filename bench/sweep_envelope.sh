#!/usr/bin/env bash
# Benchmark of issue 4 (not a test): the collapse envelope of the 156-degree seed arch,
# input/sweep_envelope_156.nml (9 frequencies, 0.5-4 Hz, thresholds to 0.25 mm), on 1
# and 2 MPI ranks. Prints the wall time of each (best of REPEAT runs, each from an empty
# file so that nothing is resumed), the parallel efficiency T1 / (2 T2) and the share
# of the ranks' time spent in simulations, against the goals (>= 90 % on 2 ranks, the
# whole envelope under 30 s).
#   bench/sweep_envelope.sh [BUILD_DIR] [REPEAT]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(readlink -f "${1:-$here/../build}")
repeat=${2:-3}
exe=$build/drivers/voussoir-sweep
input=$(readlink -f "$here/../input/sweep_envelope_156.nml")
[[ -x $exe ]] || { echo "no $exe: build first (cmake --build $build)"; exit 1; }
mpiexec=$(sed -n 's/^MPIEXEC_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
mpiexec=${mpiexec:-mpiexec}
work=$(mktemp -d /tmp/voussoir_bench_sweep.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
# Open MPI refuses root without these; set here only, for this script.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

best() { sort -g | head -n 1; }
declare -A wall busy inner
for n in 1 2; do
  times=(); shares=(); inners=()
  for ((k = 1; k <= repeat; k++)); do
    rm -f sweep_envelope_156.h5 sweep_envelope_156.csv
    t0=$(date +%s.%N)
    "$mpiexec" -n "$n" "$exe" "$input" > "run_${n}_${k}.txt"
    t1=$(date +%s.%N)
    times+=("$(echo "$t1 - $t0" | bc -l)")
    shares+=("$(sed -n 's/.*(busy \([0-9.]*\) %.*/\1/p' "run_${n}_${k}.txt")")
    inners+=("$(sed -n 's/.* runs in \([0-9.]*\) s on.*/\1/p' "run_${n}_${k}.txt")")
    printf '  %d rank(s), run %d: %6.2f s wall (mpirun included), %6.2f s sweep, ranks busy %s %%\n' \
      "$n" "$k" "${times[-1]}" "${inners[-1]}" "${shares[-1]}"
  done
  wall[$n]=$(printf '%s\n' "${times[@]}" | best)
  inner[$n]=$(printf '%s\n' "${inners[@]}" | best)
  busy[$n]=$(printf '%s\n' "${shares[@]}" | sort -g | tail -n 1)
done
cp sweep_envelope_156.csv "$work/envelope.csv"
runs=$(sed -n 's/.*done: [0-9]* jobs, \([0-9]*\) runs.*/\1/p' run_2_1.txt)
eff=$(echo "100 * ${wall[1]} / (2 * ${wall[2]})" | bc -l)
eff_inner=$(echo "100 * ${inner[1]} / (2 * ${inner[2]})" | bc -l)
echo
echo "156-degree envelope: 9 frequencies, amp_tol 0.25 mm, $runs simulations"
printf 'wall time, 1 rank : %6.2f s (best of %d)\n' "${wall[1]}" "$repeat"
printf 'wall time, 2 ranks: %6.2f s (best of %d)   goal < 30 s: %s\n' "${wall[2]}" "$repeat" \
  "$(echo "${wall[2]} < 30" | bc -l | sed 's/1/met/;s/0/MISSED/')"
printf 'parallel efficiency on 2 ranks: %5.1f %%   goal >= 90 %%: %s\n' "$eff" \
  "$(echo "$eff >= 90" | bc -l | sed 's/1/met/;s/0/MISSED/')"
printf 'without MPI start-up (the sweep'"'"'s own clock): %.2f s and %.2f s, efficiency %.1f %%\n' \
  "${inner[1]}" "${inner[2]}" "$eff_inner"
printf 'simulations share of the ranks time: %s %% on 1 rank, %s %% on 2 ranks\n' "${busy[1]}" "${busy[2]}"
echo
echo "thresholds (frequency_hz, threshold_m, peak_accel_m_s2, full_cycle_accel_m_s2, non_monotonic, failed):"
cut -d, -f2- envelope.csv | column -t -s,
