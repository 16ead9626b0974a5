#!/usr/bin/env bash
# Kernel speed on the benchmark case of issue 2 (bench/arch_180_1hz.nml: the 180-degree
# seed arch at 1 Hz, A = 30 mm, dt = 1e-3, tol 1e-4, 5 s): microseconds per time step,
# best and median of N repeats, two ways:
#   - whole process: the wall time of `voussoir-run` from start to exit (loading the
#     program and its libraries, reading the input, the time loop, writing the result
#     file), divided by the steps; the measure of the reference figure of issue 11 (goal
#     6 us/step, 20x the 127 us/step quoted there for LMGC90 3.0 "on this kind of
#     machine": a constant with no date, build or script, never measured beside
#     Voussoir). LMGC90 measured beside Voussoir on this case, on this machine:
#     bench/lmgc90/run.sh (case arch180_30) and its table in docs/lmgc90.md;
#   - time loop only: the result file's wall_time_s over the steps.
# And the NLGS iterations per step.
#   bash bench/kernel_speed.sh [N=7]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
n=${1:-7}
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "kernel_speed.sh: N (repeats) must be a positive whole number, not '$n'" >&2; exit 2; }
exe="${VOUSSOIR_BIN_DIR:-$root/build/drivers}/voussoir-run"
[[ -x "$exe" ]] || { echo "kernel_speed.sh: no $exe (build first: README, or set VOUSSOIR_BIN_DIR)" >&2; exit 2; }
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
"$py" - "$exe" "$root/bench/arch_180_1hz.nml" "$n" <<'PY'
import subprocess, sys, time
import h5py
import numpy as np

exe, nml, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
whole, loop, iters = [], [], []
for _ in range(n):
    t0 = time.perf_counter()
    subprocess.run([exe, nml], stdout=subprocess.DEVNULL, check=True)
    elapsed = time.perf_counter() - t0
    with h5py.File("bench_arch_180.h5") as f:
        r = f["result"].attrs
        steps = int(r["n_steps"])
        whole.append(1e6 * elapsed / steps)
        loop.append(1e6 * r["wall_time_s"] / steps)
        iters.append(r["mean_iterations"])
print(f"180-degree arch, 1 Hz, A = 30 mm, dt = 1e-3 s, tol 1e-4, {steps} steps, {n} repeats")
for name, us in (("whole process  ", whole), ("time loop only ", loop)):
    print(f"  {name} best {min(us):6.2f} us/step   median {np.median(us):6.2f} us/step")
print(f"  goal: 6 us/step for the whole process (20x the 127 us/step quoted for LMGC90 3.0 in issue 11,"
      f" not measured beside Voussoir; measured side by side: docs/lmgc90.md)")
print(f"  NLGS iterations {np.mean(iters):6.2f} per step")
PY
