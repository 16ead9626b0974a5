"""One case in LMGC90 (pylmgc90), for bench/lmgc90/run.sh. Not part of the test suite.

Run with the Python that pylmgc90 was built for (/usr/bin/python3 here) and PYTHONPATH at
the LMGC90 build folder, in an empty working folder:

    python3 lmgc90_case.py gen CASE.json     # writes DATBOX/ (not timed)
    python3 lmgc90_case.py run CASE.json OUT.json

CASE.json is written by bench.py from a Voussoir result file of the same case, so that
both codes start from the same polygons (bodies/vertices_local_m and the first sample of
bodies/position), the same table velocity (/table/v_m_s at every step) and the same
alert distance:

    {"dt_s", "theta", "tol", "n_steps", "friction", "density_kg_m3", "alert_m",
     "gravity_m_s2", "bodies": [{"role": 1|2, "centroid": [x, y], "vertices": [[x, y], ...]}],
     "crown": [0-based body indices], "collapse_drop_m", "collapse_rotation_rad",
     "table_t_s": [...], "table_v_m_s": [...], "every": N}

The model (docs/lmgc90.md, "The build notes"): rigid polygons (RBDY2 + POLYG, 'Rxx2D'), the contact law
IQS_CLB (Signorini + Coulomb) between every pair of blocks and between blocks and the
foundations, Moreau-Jean with theta, the NLGS of
ExSolver('Stored_Delassus_Loops', 'Quad ', tol, 1., 10, 1000) (a convergence check every
10 sweeps, at most 10,000 sweeps). Role-2 bodies (foundations) have their three velocities
imposed: x from the evolution file of the table velocity, y and rotation 0.

OUT.json: loop_s (wall time of the time loop), loop_to_split_s (of its first
split_step steps, if CASE.json gives split_step), iterations (NLGS sweeps of each step, from
POSTPRO/SOLVER_INFORMATIONS.DAT), contacts, collapsed, collapse_time_s,
peak_crown_disp_m (largest norm of the crown's displacement relative to the table), and
max_residual_disp_m (largest displacement of a free body relative to the table at the end).
"""
import json
import math
import os
import sys
import time

import numpy as np


def gen(case):
    from pylmgc90 import pre

    os.makedirs("DATBOX", exist_ok=True)
    bodies = pre.avatars()
    mats = pre.materials()
    mods = pre.models()
    svs = pre.see_tables()
    tacts = pre.tact_behavs()
    block_mat = pre.material(name="BLOCK", materialType="RIGID", density=case["density_kg_m3"])
    found_mat = pre.material(name="FOUND", materialType="RIGID", density=case["density_kg_m3"])
    mats.addMaterial(block_mat, found_mat)
    mod = pre.model(name="rigid", physics="MECAx", element="Rxx2D", dimension=2)
    mods.addModel(mod)

    np.savetxt("DATBOX/table_vx.dat", np.column_stack([case["table_t_s"], case["table_v_m_s"]]), fmt="%.17e")
    for b in case["bodies"]:
        driven = b["role"] != 1
        body = pre.rigidPolygon(model=mod, material=found_mat if driven else block_mat,
                                center=np.array(b["centroid"], float), color="FOUND" if driven else "BLOCK",
                                generation_type="full", vertices=np.array(b["vertices"], float))
        if driven:
            body.imposeDrivenDof(component=[1], dofty="vlocy", description="evolution", evolutionFile="table_vx.dat")
            body.imposeDrivenDof(component=[2, 3], dofty="vlocy")
        bodies.addAvatar(body)

    law = pre.tact_behav(name="iqsc0", law="IQS_CLB", fric=case["friction"])
    tacts += law
    for antagonist in ("BLOCK", "FOUND"):
        svs += pre.see_table(CorpsCandidat="RBDY2", candidat="POLYG", colorCandidat="BLOCK",
                             CorpsAntagoniste="RBDY2", antagoniste="POLYG", colorAntagoniste=antagonist,
                             behav=law, alert=case["alert_m"])
    post = pre.postpro_commands()
    post.addCommand(pre.postpro_command(name="SOLVER INFORMATIONS", step=1))
    pre.writeDatbox(2, mats, mods, bodies, tacts, svs, post=post, gravy=[0.0, -case["gravity_m_s2"], 0.0])


def step(chipy, solver):
    """One Moreau-Jean step of LMGC90: free velocity, contact detection, the NLGS, update."""
    chipy.IncrementStep()
    chipy.ComputeFext()
    chipy.ComputeBulk()
    chipy.ComputeFreeVelocity()
    chipy.SelectProxTactors()
    chipy.RecupRloc()
    chipy.ExSolver(*solver)
    chipy.StockRloc()
    chipy.ComputeDof()
    chipy.UpdateStep()


def run(case, out_path):
    from pylmgc90 import chipy

    chipy.Initialize()
    chipy.checkDirectories()
    chipy.utilities_DisableLogMes()
    chipy.SetDimension(2, 1)
    chipy.TimeEvolution_SetTimeStep(case["dt_s"])
    chipy.Integrator_InitTheta(case["theta"])
    chipy.ReadDatbox(deformable=False)
    chipy.OpenPostproFiles()
    chipy.ComputeMass()

    roles = [b["role"] for b in case["bodies"]]
    free = [i for i, r in enumerate(roles) if r == 1]
    ref = {i: np.array(chipy.RBDY2_GetBodyVector("Coor0", i + 1)) for i in range(len(roles))}
    crown = case["crown"]
    crown_ref = [float(np.mean([ref[i][k] for i in crown])) for k in (0, 1)]
    driven = roles.index(2)
    drop, rot = case["collapse_drop_m"], case["collapse_rotation_rad"]
    every = case["every"]
    dt = case["dt_s"]
    peak, collapsed, collapse_t = 0.0, False, math.nan
    solver = ["Stored_Delassus_Loops         ", "Quad ", case["tol"], 1.0, 10, 1000]

    split = case.get("split_step", 0)
    t_split = math.nan
    t0 = time.perf_counter()
    for k in range(1, case["n_steps"] + 1):
        if k == split + 1:
            t_split = time.perf_counter() - t0
        step(chipy, solver)
        chipy.WritePostproFiles()
        # The monitors (as voussoir-run's, in a cheaper form): the crown relative to the
        # table every step, the collapse criterion every `every` steps.
        table_x = chipy.RBDY2_GetBodyVector("Coor_", driven + 1)[0] - ref[driven][0]
        cx = cy = 0.0
        for i in crown:
            q = chipy.RBDY2_GetBodyVector("Coor_", i + 1)
            cx += q[0]
            cy += q[1]
        peak = max(peak, math.hypot(cx / len(crown) - crown_ref[0] - table_x, cy / len(crown) - crown_ref[1]))
        if not collapsed and k % every == 0:
            for i in free:
                q = chipy.RBDY2_GetBodyVector("Coor_", i + 1)
                if ref[i][1] - q[1] > drop or abs(q[2] - ref[i][2]) > rot:
                    collapsed, collapse_t = True, k * dt
                    break
    loop_s = time.perf_counter() - t0

    table_x = chipy.RBDY2_GetBodyVector("Coor_", driven + 1)[0] - ref[driven][0]
    residual = 0.0
    for i in free:
        q = chipy.RBDY2_GetBodyVector("Coor_", i + 1)
        residual = max(residual, math.hypot(q[0] - ref[i][0] - table_x, q[1] - ref[i][1]))
    chipy.ClosePostproFiles()
    chipy.Finalize()
    info = np.loadtxt("POSTPRO/SOLVER_INFORMATIONS.DAT", ndmin=2)
    with open(out_path, "w") as f:
        json.dump({"loop_s": loop_s, "loop_to_split_s": t_split, "n_steps": case["n_steps"], "iterations": info[:, 1].astype(int).tolist(),
                   "contacts": info[:, 5].astype(int).tolist(), "collapsed": collapsed,
                   "collapse_time_s": collapse_t, "peak_crown_disp_m": peak, "table_x_end_m": table_x,
                   "max_residual_disp_m": residual}, f)


if __name__ == "__main__":
    with open(sys.argv[2]) as f:
        case = json.load(f)
    if sys.argv[1] == "gen":
        gen(case)
    else:
        run(case, sys.argv[3])
