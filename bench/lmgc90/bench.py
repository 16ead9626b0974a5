"""Side-by-side bench: the same cases in Voussoir and in LMGC90 on this machine.

Called by bench/lmgc90/run.sh (read it for the arguments); not part of the test suite.
For each case:
  1. voussoir-run once with output at every step (not timed): its result file gives the
     polygons, the reference positions, the table velocity at every step and the alert
     distance, written to case.json for LMGC90 (lmgc90_case.py gen writes its DATBOX);
  2. N rounds, each one voussoir-run (output every 10 steps) and one LMGC90 run
     (lmgc90_case.py run), alternating so that both see the same load; each is timed
     as a whole process (start to exit) and for its time loop only.
Prints microseconds per step (best and median of N), NLGS sweeps per step, and the
outcome; writes the table as JSON to --json if given.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

ARCH = """&arch
  embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071,
  width_m = 0.145, density_kg_m3 = 700, friction = 0.5
/
&motion
  waveform = 'afd', frequency_hz = 1.25, amplitude_m = {amp},
  n_attack = 1, n_full = 1, n_decay = 1, rest_s = 1.0
/
&solver
  dt_s = 1.0e-3, theta = 0.5, tol = 1.0e-4, max_iter = 10000
/
&output
  file = '{file}', every = {every}, collapse_drop_m = 0.0355, stop_after_collapse_s = -1
/
"""

ARCH180 = """&arch
  embrace_deg = 180, n_voussoirs = 15, r_ext_m = 0.508, thickness_m = 0.071
/
&motion
  waveform = 'afd', frequency_hz = 1.0, amplitude_m = 0.030, duration_s = 5.0
/
&solver
  dt_s = 1.0e-3, tol = 1.0e-4, max_iter = 10000
/
&output
  file = '{file}', every = {every}, collapse_drop_m = 0.0355, stop_after_collapse_s = -1
/
"""

WALL = """&wall courses = {n}, blocks_per_course = {n}, block_width_m = 0.2, block_height_m = 0.1 /
&arch width_m = 0.1, density_kg_m3 = 2000, friction = 0.6 /
&motion waveform = 'afd', frequency_hz = 2.0, amplitude_m = 0.00621, table_delay_s = 0.2, duration_s = {duration} /
&solver dt_s = 1.0e-3, theta = 0.5, tol = 1.0e-4, max_iter = 10000, allow_nonconvergence = .true. /
&output file = '{file}', every = {every}, collapse_drop_m = 0.05, stop_after_collapse_s = -1 /
"""


def cases(names):
    out = []
    for name in names:
        if name == "arch180_30":
            out.append((name, "180-degree arch, 15 voussoirs, afd 1 Hz, A = 30 mm, 5 s (bench/arch_180_1hz.nml)",
                        lambda file, every: ARCH180.format(file=file, every=every), 0.0355))
        elif name.startswith("arch156_"):
            amp = float(name.split("_")[1]) / 1000.0
            out.append((name, f"156-degree arch, 13 voussoirs, afd 1.25 Hz, A = {amp * 1000:g} mm, 3.4 s",
                        lambda file, every, amp=amp: ARCH.format(amp=amp, file=file, every=every), 0.0355))
        elif name.startswith("wall"):
            n = int(name[4:])
            out.append((name, f"running-bond wall {n} x {n}, afd 2 Hz, A = 6.21 mm after 0.2 s, 1.2 s",
                        lambda file, every, n=n, duration=1.2: WALL.format(n=n, file=file, every=every,
                                                                           duration=duration), 0.05))
        else:
            sys.exit(f"bench.py: unknown case '{name}' (arch180_30, arch156_<amplitude in mm> or wall<N>)")
    return out


def voussoir(exe, work, name, text_of, every):
    nml = os.path.join(work, f"{name}_{every}.nml")
    h5 = os.path.join(work, f"{name}_{every}.h5")
    with open(nml, "w") as f:
        f.write(text_of(h5, every))
    t0 = time.perf_counter()
    p = subprocess.run([exe, nml], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=work)
    whole = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit(f"voussoir-run {nml} failed: {p.stderr.decode()}")
    return h5, whole


def export_case(h5, drop):
    """case.json for lmgc90_case.py from a Voussoir result file written at every step."""
    with h5py.File(h5) as f:
        verts = f["bodies/vertices_local_m"][()]
        nv = f["bodies/n_vertices"][()]
        role = f["bodies/role"][()]
        pos0 = f["bodies/position"][0]
        cfg_s = dict(f["config/solver"].attrs)
        cfg_a = dict(f["config/arch"].attrs)
        t = f["time_s"][()]
        v = f["table/v_m_s"][()]
        n_steps = int(f["result"].attrs["n_steps"])
        is_arch = "arch" in f
    free = [i for i in range(len(role)) if role[i] == 1]
    radius = [float(np.max(np.hypot(verts[i, :nv[i], 0], verts[i, :nv[i], 1]))) for i in free]
    alert = float(cfg_s["alert_m"]) or 0.04 * min(radius)   # as voussoir's automatic_alert_m
    if is_arch:
        n = len(free)
        crown = [free[(n + 1) // 2 - 1]] if n % 2 else [free[n // 2 - 1], free[n // 2]]
    else:
        crown = [free[int(np.argmax(pos0[free, 1]))]]
    return {
        "dt_s": float(cfg_s["dt_s"]), "theta": float(cfg_s["theta"]), "tol": float(cfg_s["tol"]),
        "n_steps": n_steps, "friction": float(cfg_a["friction"]), "density_kg_m3": float(cfg_a["density_kg_m3"]),
        "alert_m": alert, "gravity_m_s2": 9.81,
        "bodies": [{"role": int(role[i]), "centroid": pos0[i, :2].tolist(), "vertices": verts[i, :nv[i]].tolist()}
                   for i in range(len(role))],
        "crown": crown, "collapse_drop_m": drop, "collapse_rotation_rad": 0.5,
        "table_t_s": t.tolist(), "table_v_m_s": v.tolist(), "every": 10,
    }


def lmgc90(py, env, work, case_json, out_json):
    t0 = time.perf_counter()
    p = subprocess.run([py, os.path.join(HERE, "lmgc90_case.py"), "run", case_json, out_json],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=work, env=env)
    whole = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit(f"LMGC90 run in {work} failed: {p.stderr.decode()[-2000:]}")
    with open(out_json) as f:
        return json.load(f), whole


def stats(xs):
    return min(xs), statistics.median(xs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--voussoir", required=True)
    ap.add_argument("--lmgc90-python", required=True)
    ap.add_argument("--lmgc90-build", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--json")
    ap.add_argument("cases", nargs="+")
    a = ap.parse_args()
    env = dict(os.environ, PYTHONPATH=a.lmgc90_build + os.pathsep + os.environ.get("PYTHONPATH", ""))
    table = []
    print(f"load average before: {os.getloadavg()[0]:.2f} (1 min), {os.cpu_count()} cores", flush=True)
    for name, title, text_of, drop in cases(a.cases):
        work = os.path.join(a.work, name)
        os.makedirs(work, exist_ok=True)
        h5, _ = voussoir(a.voussoir, work, name, text_of, 1)
        case = export_case(h5, drop)
        wall = name.startswith("wall")
        if wall:
            case["split_step"] = 200   # the shaking second: steps 201-1200
        case_json = os.path.join(work, "case.json")
        with open(case_json, "w") as f:
            json.dump(case, f)
        lwork = os.path.join(work, "lmgc90")
        os.makedirs(lwork, exist_ok=True)
        p = subprocess.run([a.lmgc90_python, os.path.join(HERE, "lmgc90_case.py"), "gen", case_json],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=lwork, env=env)
        if p.returncode != 0:
            sys.exit(f"LMGC90 DATBOX for {name} failed: {p.stderr.decode()[-2000:]}")
        n = case["n_steps"]
        vw, vl, lw, ll, vs, ls = [], [], [], [], [], []
        loads = []
        for _ in range(a.repeats):
            loads.append(os.getloadavg()[0])
            h5, whole = voussoir(a.voussoir, work, name, text_of, 10)
            with h5py.File(h5) as f:
                r = dict(f["result"].attrs)
                vit = f["solver/iterations"][()]
                vct = f["contacts/count"][()]
            vw.append(1e6 * whole / int(r["n_steps"]))
            vl.append(1e6 * float(r["wall_time_s"]) / int(r["n_steps"]))
            if wall:   # as bench/walls.sh: a 1.2 s run minus a 0.2 s run, over the 1000 steps between
                h5s, _ = voussoir(a.voussoir, work, name + "_settle", lambda file, every: text_of(file, every, duration=0.2), 10)
                with h5py.File(h5s) as f:
                    vs.append(1e6 * (float(r["wall_time_s"]) - float(f["result"].attrs["wall_time_s"])) / 1000)
            res, whole = lmgc90(a.lmgc90_python, env, lwork, case_json, os.path.join(lwork, "out.json"))
            lw.append(1e6 * whole / res["n_steps"])
            ll.append(1e6 * res["loop_s"] / res["n_steps"])
            if wall:
                ls.append(1e6 * (res["loop_s"] - res["loop_to_split_s"]) / 1000)
        lit = np.array(res["iterations"])
        row = {
            "case": name, "title": title, "steps": n, "repeats": a.repeats,
            "load_1min_min": min(loads), "load_1min_max": max(loads),
            "voussoir": {"whole_us": stats(vw), "loop_us": stats(vl), "sweeps_mean": float(np.mean(vit)),
                         "sweeps_after_0.2s": float(np.mean(vit[200:])), "contacts_mean": float(np.mean(vct[1:])),
                         "sweeps_max": int(np.max(vit)), "collapsed": bool(r["collapsed"]),
                         "collapse_time_s": float(r["collapse_time_s"]),
                         "peak_crown_mm": 1e3 * float(r["peak_crown_disp_m"]),
                         "residual_mm": 1e3 * float(r["max_residual_disp_m"]), "n_steps": int(r["n_steps"])},
            "lmgc90": {"whole_us": stats(lw), "loop_us": stats(ll), "sweeps_mean": float(np.mean(lit)),
                       "sweeps_after_0.2s": float(np.mean(lit[200:])),
                       "contacts_mean": float(np.mean(res["contacts"][9::10])),
                       "sweeps_max": int(np.max(lit)), "collapsed": res["collapsed"],
                       "collapse_time_s": res["collapse_time_s"], "peak_crown_mm": 1e3 * res["peak_crown_disp_m"],
                       "residual_mm": 1e3 * res["max_residual_disp_m"], "n_steps": res["n_steps"]},
        }
        if wall:
            row["voussoir"]["shaking_loop_us"] = stats(vs)
            row["lmgc90"]["shaking_loop_us"] = stats(ls)
        table.append(row)
        print(f"\n{title}: {n} steps of 1 ms, {a.repeats} rounds, load {min(loads):.1f}-{max(loads):.1f}")
        print(f"  {'code':9} {'whole process us/step':>24} {'time loop us/step':>20} {'sweeps/step':>12} "
              f"{'max':>6}  outcome")
        for code in ("voussoir", "lmgc90"):
            c = row[code]
            out = (f"collapsed at {c['collapse_time_s']:.2f} s" if c["collapsed"] else "stood")
            print(f"  {code:9} {c['whole_us'][0]:10.1f} (med {c['whole_us'][1]:7.1f}) "
                  f"{c['loop_us'][0]:8.1f} (med {c['loop_us'][1]:7.1f}) {c['sweeps_mean']:12.1f} "
                  f"{c['sweeps_max']:6d}  {out}, peak crown {c['peak_crown_mm']:.3g} mm, "
                  f"largest residual {c['residual_mm']:.3g} mm; sweeps/step after the first 0.2 s "
                  f"{c['sweeps_after_0.2s']:.1f}; contacts {c['contacts_mean']:.1f}", flush=True)
        if wall:
            print(f"  the shaking second only (time loop, as bench/walls.sh): Voussoir "
                  f"{row['voussoir']['shaking_loop_us'][0]:.0f} (med {row['voussoir']['shaking_loop_us'][1]:.0f}), LMGC90 "
                  f"{row['lmgc90']['shaking_loop_us'][0]:.0f} (med {row['lmgc90']['shaking_loop_us'][1]:.0f}) us/step")
        print(f"  total (best whole process): Voussoir {row['voussoir']['whole_us'][0] * n / 1e6:.2f} s, "
              f"LMGC90 {row['lmgc90']['whole_us'][0] * n / 1e6:.2f} s; "
              f"ratio {row['lmgc90']['whole_us'][0] / row['voussoir']['whole_us'][0]:.1f}x (whole), "
              f"{row['lmgc90']['loop_us'][0] / row['voussoir']['loop_us'][0]:.1f}x (loop)", flush=True)
    print(f"\nload average after: {os.getloadavg()[0]:.2f}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(table, f, indent=1)


if __name__ == "__main__":
    main()
