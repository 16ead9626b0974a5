#!/usr/bin/env bash
# Kernel speed on the benchmark case of issue 2 (bench/arch_180_1hz.nml: the 180-degree
# seed arch at 1 Hz, A = 30 mm, dt = 1e-3, tol 1e-4, 5 s): microseconds per time step
# (simulation loop only, from the result file's wall_time_s) and NLGS iterations per
# step, best and median of N repeats. Goal: 6 us/step, 20x the reference code (LMGC90 3.0
# takes 127 us/step on this kind of machine, issue 11).
#   bash bench/kernel_speed.sh [N=7]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
n=${1:-7}
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
for i in $(seq "$n"); do
  "$root/build/drivers/voussoir-run" "$root/bench/arch_180_1hz.nml" >/dev/null
  "$py" - <<'PY' >> times.txt
import h5py
with h5py.File('bench_arch_180.h5') as f:
    r = f['result'].attrs
    print(1e6 * r['wall_time_s'] / r['n_steps'], r['mean_iterations'], r['n_steps'])
PY
done
"$py" - <<'PY'
import numpy as np
d = np.loadtxt('times.txt', ndmin=2)
us, it, steps = d[:, 0], d[:, 1], d[:, 2]
print(f"180-degree arch, 1 Hz, A = 30 mm, dt = 1e-3 s, tol 1e-4, {int(steps[0])} steps, {len(us)} repeats")
print(f"  time per step   best {us.min():6.2f} us   median {np.median(us):6.2f} us   (goal 6 us, issue 11)")
print(f"  NLGS iterations {it.mean():6.2f} per step")
PY
