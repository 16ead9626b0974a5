#!/usr/bin/env bash
# Benchmark of issue 10 (not a test): an incremental dynamic analysis of the 156-degree
# seed arch under six real records (the main-shock pairs of the suite: El Centro 1940,
# Loma Prieta 1989 Corralitos, San Fernando 1971 Pacoima Dam; docs/earthquakes.md)
# x 20 Latin hypercube model samples (friction, contact inset, thickness, voussoir-size
# imperfection) on 2 MPI ranks, whole records, scale_tol 5 %. Prints the wall time, the
# runs, the parallel efficiency (the simulations' share of the 2 ranks' time: what one
# rank would need for the same runs, over twice the wall time) and the cost of a record
# run per time step against a sinusoid run of the same simulated duration (goal: within
# 2x). With ONE_RANK=1 it also times the same IDA on 1 rank (T1 / (2 T2)).
#   bash bench/ida.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$(readlink -f "${1:-$root/build}")
py=$root/.venv/bin/python
exe=$build/drivers/voussoir-sweep
[[ -x $exe ]] || { echo "no $exe: build first (bash scripts/setup.sh)"; exit 1; }
work=$(mktemp -d /tmp/voussoir_bench_ida.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

files=$("$py" -c "from voussoir_post.earthquake.records import record_path
print(', '.join(repr(str(record_path(k))) for k in ('ELC180', 'ELC270', 'CLS000', 'CLS090', 'PUL164', 'PUL254')))")
cat > ida.nml <<NML
&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, width_m = 0.145,
  density_kg_m3 = 700, friction = 0.5 /
&motion lead_s = 0.5, rest_s = 2.0 /
&solver dt_s = 1.0e-3 /
&sweep mode = 'ida', record_files = $files,
  scale_tol = 0.05, scale_max = 10, n_samples = 20, sample_seed = 1,
  friction_range = 0.45, 0.6, contact_inset_range_m = 0.0, 0.002, thickness_range_m = 0.068, 0.074,
  size_imperfection_range = 0.0, 0.05, progress_every_s = 30 /
&output file = 'ida.h5' /
NML

run() {  # run N: the IDA on N ranks from an empty file; prints the wall time
  rm -f ida.h5 ida.csv
  local t0 t1
  t0=$(date +%s.%N)
  mpirun --oversubscribe -np "$1" "$exe" ida.nml > "ida_$1.txt"
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}
t2=$(run 2)
tail -n 1 ida_2.txt
if [[ "${ONE_RANK:-0}" == 1 ]]; then
  t1=$(run 1)
  tail -n 1 ida_1.txt
  rm -f ida.h5 ida.csv
  t2=$(run 2)   # the file of the 2-rank run is the one read below
fi

# The sinusoid of the same simulated duration: the seed arch at 1.25 Hz and 40 mm
# (moving, below its 46 mm collapse), for the mean duration of the IDA's runs.
mean_s=$("$py" -c "
import h5py, numpy as np
with h5py.File('ida.h5') as f:
    print(float(np.mean(f['runs/n_steps'][()])) * 1e-3)")
cat > sine.nml <<NML
&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, width_m = 0.145,
  density_kg_m3 = 700, friction = 0.5 /
&motion waveform = 'afd', frequency_hz = 1.25, amplitude_m = 0.040, n_attack = 1,
  n_full = $(echo "($mean_s * 1.25 + 0.5) / 1" | bc), n_decay = 1, duration_s = $mean_s /
&solver dt_s = 1.0e-3 /
&output file = 'sine.h5', every = 1000, stop_after_collapse_s = 0 /
NML
for k in 1 2 3; do "$build/drivers/voussoir-run" sine.nml > "sine_$k.txt"; cp sine.h5 "sine_$k.h5"; done

"$py" - "$t2" "${t1:-}" <<'PY'
import sys
import h5py
import numpy as np
t2 = float(sys.argv[1])
t1 = float(sys.argv[2]) if len(sys.argv) > 2 and sys.argv[2] else None
with h5py.File("ida.h5") as f:
    runs = {k: f["runs"][k][()] for k in f["runs"]}
    res = {k: f["results"][k][()] for k in f["results"]}
n_runs = runs["job"].size
busy = runs["wall_time_s"].sum()
us_step = 1e6 * runs["wall_time_s"].sum() / runs["n_steps"].sum()
sine = []
for k in (1, 2, 3):
    with h5py.File(f"sine_{k}.h5") as f:
        a = f["result"].attrs
        sine.append((1e6 * a["wall_time_s"] / a["n_steps"], a["n_steps"], a["wall_time_s"], a["collapsed"]))
sine_us = min(s[0] for s in sine)
mean_steps = runs["n_steps"].mean()
print(f"IDA of the 156-degree arch: 6 records x 20 samples = {res['job'].size} searches, {n_runs} runs, "
      f"{int(res['censored'].sum())} censored, {int(res['non_monotonic'].sum())} non-monotonic")
print(f"wall time on 2 ranks: {t2:.1f} s (mpirun included); simulations {busy:.1f} s of rank time")
print(f"parallel efficiency on 2 ranks (simulation time / (2 x wall)): {100 * busy / (2 * t2):.1f} %")
if t1 is not None:
    print(f"wall time on 1 rank: {t1:.1f} s; T1 / (2 T2) = {100 * t1 / (2 * t2):.1f} %")
print(f"record runs: {us_step:.2f} us per step, mean {mean_steps:.0f} steps ({mean_steps * 1e-3:.1f} s simulated) "
      f"and {runs['wall_time_s'].mean():.3f} s per run")
print(f"sinusoid of the same duration (1.25 Hz, 40 mm, {int(sine[0][1])} steps, "
      f"{'collapsed' if sine[0][3] else 'stood'}): {sine_us:.2f} us per step (best of 3), {min(s[2] for s in sine):.3f} s")
ratio = us_step / sine_us
print(f"cost per step, record / sinusoid: {ratio:.2f}   goal <= 2: {'met' if ratio <= 2 else 'MISSED'}")
PY
