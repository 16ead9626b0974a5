#!/usr/bin/env bash
# Speed on running-bond walls (issue 11), beside the figures quoted in issue 11 for the
# reference NSCD code (LMGC90 3.0) "on this kind of machine" (constants with no date,
# build or script, never measured beside Voussoir; bench/lmgc90/run.sh measures LMGC90
# beside Voussoir on the 10 x 10 wall, table in docs/lmgc90.md): blocks 0.20 x 0.10 m, half blocks at the ends of odd
# courses, density 2000, friction 0.6, one driven foundation; afd at 2 Hz with 6.21 mm
# amplitude (0.1 g) after 0.2 s of settling (&motion table_delay_s); dt 1e-3, tol 1e-4,
# one thread. The timed part is the shaking second: the wall time of a 1.2 s run minus
# that of a 0.2 s run, over 1000 steps. Also: NLGS sweeps per step in that second, the
# most sweeps one settling step took, and the peak resident memory of the 1.2 s run.
# VOUSSOIR_COARSE=false runs without the coarse correction of the NLGS (&solver
# coarse_correction, default true), for comparison.
#   bash bench/walls.sh [SIZES...]      (default 10 20 40; 80 takes a few minutes)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
sizes=("$@"); ((${#sizes[@]})) || sizes=(10 20 40)
"$py" - "${VOUSSOIR_BIN_DIR:-$root/build/drivers}/voussoir-run" "$work" "${VOUSSOIR_COARSE:-true}" "${sizes[@]}" <<'PY'
import os, subprocess, sys, time
import h5py
import numpy as np

exe, work, coarse, sizes = sys.argv[1], sys.argv[2], sys.argv[3], [int(s) for s in sys.argv[4:]]
# LMGC90 3.0, us per step of the shaking second, as quoted in issue 11: not measured
# beside Voussoir. Measured side by side on this machine: docs/lmgc90.md.
REFERENCE_US = {10: 1968, 20: 9989, 40: 47437, 80: 248732}


def run(n, duration_s):
    name = os.path.join(work, f"wall_{n}_{duration_s:g}")
    with open(name + ".nml", "w") as f:
        f.write(f"&wall courses = {n}, blocks_per_course = {n}, block_width_m = 0.2, block_height_m = 0.1 /\n"
                f"&arch width_m = 0.1, density_kg_m3 = 2000, friction = 0.6 /\n"
                f"&motion waveform = 'afd', frequency_hz = 2.0, amplitude_m = 0.00621, table_delay_s = 0.2, "
                f"duration_s = {duration_s} /\n"
                f"&solver dt_s = 1.0e-3, tol = 1.0e-4, max_iter = 100000, allow_nonconvergence = .true., "
                f"coarse_correction = .{coarse.strip('.').lower()}. /\n"
                f"&output file = '{name}.h5', every = 100 /\n")
    t0 = time.perf_counter()
    p = subprocess.Popen([exe, name + ".nml"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    if status != 0:
        sys.exit(f"{exe} {name}.nml failed: {p.stderr.read().decode()}")
    with h5py.File(name + ".h5") as h:
        t = h["solver/time_s"][()]
        it = h["solver/iterations"][()]
        blocks = int((h["bodies/role"][()] == 1).sum()) if "bodies/role" in h else -1
    return wall, usage.ru_maxrss / 1024.0, t, it, blocks


print(f"coarse_correction = {coarse}")
print("reference: LMGC90 3.0 as quoted in issue 11, not measured here (measured side by side: docs/lmgc90.md)")
print(f"{'wall':>8} {'blocks':>6} {'reference us/step':>18} {'Voussoir us/step':>17} {'ratio':>6} "
      f"{'sweeps/step':>11} {'max settling sweeps':>19} {'peak RSS MB':>11}")
for n in sizes:
    w12, rss, t, it, blocks = run(n, 1.2)
    w02, _, _, _, _ = run(n, 0.2)
    shaking = t > 0.2 + 1e-9
    us = 1e6 * (w12 - w02) / shaking.sum()
    ref = REFERENCE_US.get(n)
    ratio = f"{ref / us:5.1f}x" if ref else "-"
    print(f"{n:>3} x {n:<3} {blocks:>6} {ref if ref else '-':>18} {us:17.0f} {ratio:>6} "
          f"{it[shaking].mean():11.1f} {int(it[~shaking].max()):19d} {rss:11.1f}", flush=True)
PY
