"""voussoir-run at rest on a semicircle of three rings (&bridge n_rings, issue 37).

    bridge_rings_at_rest.py VOUSSOIR_RUN VOUSSOIR_LIMIT WORK_DIR

A semicircle (R_i 3 m, ring 0.45 m of 10 voussoirs) in three rings, friction 10 between
them: it stands, and the supports (the two abutments) hold up the weight of all three
rings, computed here by hand: chord-faced voussoirs between radii R_i and R_e add up to
(n/2)(R_e^2 - R_i^2) sin(pi/n), times density x g x width (1e-5 at NLGS tol 1e-6, measured 1.5e-6;
1e-8 does not converge within 10000 sweeps);
each abutment is in contact with the springing voussoir of every ring at the last sample
(which ring takes the thrust there is the solver's: near the least thickness the thrust
line runs by the extrados at the springings, and the inner ring's force may vanish). At friction 0.5 between the rings the limit analysis finds that the
weight alone brings it down (no equilibrium without tension within friction: the rings,
0.15 m each, t/R about 0.05, well below a single ring's 0.10 minimum, slide on each other):
voussoir-run must then see it fall at rest too.
"""
import math
import pathlib
import subprocess
import sys

import h5py
import numpy as np

run_exe, limit_exe = (str(pathlib.Path(p).resolve()) for p in sys.argv[1:3])
work = pathlib.Path(sys.argv[3])
work.mkdir(parents=True, exist_ok=True)
R_I, T, N, RINGS, RHO, WIDTH, G = 3.0, 0.45, 10, 3, 2200.0, 1.5, 9.81
failures = []


def rings(name, mu, solver=""):
    """The semicircle in three rings at friction `mu` between them, at rest; `solver`: a
    &solver group or none."""
    (work / (name + ".h5")).unlink(missing_ok=True)
    (work / name).write_text(
        f"&bridge shape = 'semicircular', span_m(1) = {2 * R_I}, ring_thickness_m = {T}, n_voussoirs = {N},\n"
        f"  n_rings = {RINGS}, ring_joint_friction = {mu}, abutment_width_m = 1.0, width_m = {WIDTH},\n"
        f"  ring_density_kg_m3 = {RHO} /\n"
        "&motion waveform = 'afd', amplitude_m = 0.0, frequency_hz = 1.0, n_full = 0, rest_s = 0.0 /\n"
        f"{solver}"
        f"&output file = '{name}.h5' /\n")
    return subprocess.run([run_exe, name], cwd=work, capture_output=True, text=True)


def check(good, what):
    print(("PASS  " if good else "FAIL  ") + what)
    if not good:
        failures.append(what)


out = rings("rings.nml", 10, "&solver tol = 1e-6 /\n")
check(out.returncode == 0 and out.stdout.startswith("stood;"), f"three rings stand at rest: {out.stdout.strip()}")
with h5py.File(work / "rings.nml.h5") as f:
    role = f["bodies/role"][()]
    c = f["contacts"]
    start = c["start"][()]
    rows = slice(int(start[-2]), int(start[-1]))
    body = c["body"][rows] - 1
    normal = c["normal"][rows]
    fn, ft = c["normal_force_n"][rows], c["tangent_force_n"][rows]
    position = f["bodies/position"][()]
    config = f.attrs["config_nml"].decode() if isinstance(f.attrs["config_nml"], bytes) else f.attrs["config_nml"]
tangent = np.column_stack([-normal[:, 1], normal[:, 0]])
on_a = fn[:, None] * normal + ft[:, None] * tangent   # the force on body a of each contact
free = role == 1
weight = RHO * G * WIDTH * 0.5 * N * ((R_I + T) ** 2 - R_I ** 2) * math.sin(math.pi / N)
a, b = body[:, 0], body[:, 1]
support = ~free[a] & free[b] | free[a] & ~free[b]
on_free = np.where((~free[a] & free[b])[:, None], -on_a, on_a)[support]
check(len(role) == N * RINGS + 2 and free.sum() == N * RINGS, "30 voussoirs and two abutments")
check(abs(on_free[:, 1].sum() - weight) <= 1e-5 * weight,
      f"the abutments hold up all three rings: {on_free[:, 1].sum():.6f} N against "
      f"(n/2)(R_e^2 - R_i^2) sin(pi/n) x rho g w = {weight:.6f} N")
left, right = N * RINGS, N * RINGS + 1   # 0-based: the abutments follow the voussoirs
carried = []
for r in range(RINGS):
    first, last = r * N, r * N + N - 1
    for springing, abutment in ((first, left), (last, right)):
        pair = ((a == springing) & (b == abutment)) | ((a == abutment) & (b == springing))
        carried.append(bool(pair.any()) and float(fn[pair].min()) >= 0.0)
check(all(carried), f"each abutment touches the springing voussoir of every ring, in compression or none ({carried})")
moved = np.abs(position[-1, :, :2] - position[0, :, :2]).max()
check(moved < 1e-3, f"the rings stay put ({moved:.2e} m)")
check("n_rings = 3" in config and "ring_joint_friction = 1.0" in config, "the result file records n_rings and "
      "ring_joint_friction")
# At friction 0.5 between the rings: the LP says the weight brings it down; so must the run.
out = rings("slipping.nml", 0.5)
lp = subprocess.run([limit_exe, "slipping.nml"], cwd=work, capture_output=True, text=True)
check(lp.returncode != 0 and "the dead load alone brings the assembly down" in lp.stderr and
      out.returncode == 0 and out.stdout.startswith("collapsed"),
      f"friction 0.5 between the rings: the LP finds no equilibrium and voussoir-run sees it fall: {out.stdout.strip()}")
print(f"{len(failures)} failures" if failures else "all passed")
sys.exit(1 if failures else 0)
