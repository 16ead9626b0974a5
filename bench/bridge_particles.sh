#!/usr/bin/env bash
# Speed of voussoir-run on a bridge whose fill is particles (issue 37, item 2(b);
# docs/bridges.md, "Fill as particles"): the span of input/bridge_fill.nml (segmental,
# 10 m, rise 2.5 m, a 0.45 m ring of 20 voussoirs, fill to 3.45 m at 2000 kg/m3) with the
# fill cut into particles of SIZE m (0.11 m: about 2,000 blocks), friction 0.6, under the
# ground-motion record input/records/sine_pulse_0.3g.csv (one sine cycle of 0.3 g, period
# 0.5 s) scaled by 0.5 (0.15 g), after LEAD s of settling under gravity alone (&motion
# lead_s: the particles are cut touching, and settle by micrometres). dt 1e-3 s, NLGS
# tol 1e-4 (allowed not to converge within max_iter, as the walls bench). Prints the
# blocks (free particles, voussoirs, supports), the contacts at the end, the steps, the
# mean NLGS sweeps per step, the wall time and the wall time per simulated second, and
# the run's verdict (the ring watched for collapse, the particles not).
#   bash bench/bridge_particles.sh [SIZE=0.11] [DURATION_S=1.0] [LEAD_S=0.1]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
py=python3; [[ -x "$root/.venv/bin/python" ]] && py="$root/.venv/bin/python"
[[ -x /work/main/.venv/bin/python && ! -x "$root/.venv/bin/python" ]] && py=/work/main/.venv/bin/python
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
"$py" - "${VOUSSOIR_BIN_DIR:-$root/build/drivers}/voussoir-run" "$work" "$root/input/records/sine_pulse_0.3g.csv" \
  "${1:-0.11}" "${2:-1.0}" "${3:-0.1}" <<'PY'
import os, subprocess, sys, time
import h5py
import numpy as np

exe, work, record, size, duration, lead = sys.argv[1], sys.argv[2], sys.argv[3], *map(float, sys.argv[4:7])
nml = os.path.join(work, "bridge_particles.nml")
with open(nml, "w") as f:
    f.write(f"&bridge shape = 'segmental', span_m(1) = 10.0, rise_m(1) = 2.5, ring_thickness_m = 0.45, "
            f"n_voussoirs = 20,\n  pier_height_m = 3.0, abutment_width_m = 2.0, width_m = 1.0, "
            f"ring_density_kg_m3 = 2200, ring_friction = 0.6,\n  abutment_friction = 0.6, fill_density_kg_m3 = 2000, "
            f"fill_level_m = 3.45, fill_model = 'particles',\n  fill_particle_size_m = {size}, "
            f"fill_particle_friction = 0.6 /\n"
            f"&motion waveform = 'accelerogram', record_file = '{record}', record_scale = 0.5, lead_s = {lead}, "
            f"duration_s = {duration} /\n"
            f"&solver dt_s = 1.0e-3, tol = 1.0e-4, max_iter = 2000, allow_nonconvergence = .true. /\n"
            f"&output file = '{work}/bridge_particles.h5', every = 50 /\n")
t0 = time.perf_counter()
p = subprocess.run([exe, nml], capture_output=True, text=True)
wall = time.perf_counter() - t0
if p.returncode != 0:
    sys.exit(f"{exe} {nml} failed: {p.stderr}")
with h5py.File(os.path.join(work, "bridge_particles.h5")) as h:
    role = h["bodies/role"][()]
    steps = h["solver/time_s"].shape[0]
    sweeps = float(np.mean(h["solver/iterations"][()]))
    contacts = int(h["contacts/count"][-1])
    simulated = float(h["solver/time_s"][-1])
print(f"particles of {size} m, {duration:g} s simulated (of which {lead:g} s of settling), dt 1e-3 s, tol 1e-4")
print(f"blocks {role.size} ({int((role == 4).sum())} particles, {int((role == 1).sum())} voussoirs, "
      f"{int((role == 2).sum())} supports); contacts at the end {contacts}; steps {steps}; "
      f"mean NLGS sweeps per step {sweeps:.1f}")
print(f"wall time {wall:.1f} s; {wall / simulated:.1f} s per simulated second; {1e3 * wall / steps:.1f} ms per step")
print("voussoir-run: " + p.stdout.strip().splitlines()[0])
PY
