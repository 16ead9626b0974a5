"""One LMGC90 model of a calibration truth, for bench/lmgc90/truths.py. Not part of the test suite.

Run with the Python that pylmgc90 was built for (/usr/bin/python3 here), PYTHONPATH at the
LMGC90 build folder, in the model's own working folder (one model per process):

    python3 truth_case.py gen MODEL.json           # writes DATBOX/ once per specimen
    python3 truth_case.py run MODEL.json RUN.json OUT.json

MODEL.json (written by truths.py):

    {"dt_s", "theta", "tol", "friction", "alert_m", "gravity_m_s2",
     "bodies": [{"role": 1|2, "centroid": [x, y], "vertices": [[dx, dy], ...] (about the
                 centroid, counter-clockwise), "density_kg_m3", "evolution": "FILE.dat" (driven
                 bodies: x velocity from DATBOX/FILE.dat)}],
     "collapse_drop_m", "collapse_rotation_rad", "every"}

RUN.json: {"n_steps", "lead_steps"}; truths.py writes the evolution files of the run into
DATBOX/ before each run (the same DATBOX serves every amplitude of a specimen).

The model is that of lmgc90_case.py (shared/LMGC90.md): rigid polygons (RBDY2 + POLYG,
'Rxx2D'), IQS_CLB between blocks and between blocks and the driven bodies, Moreau-Jean with
theta, ExSolver('Stored_Delassus_Loops', 'Quad ', tol, 1., 10, 1000). Driven bodies have x
velocity from their evolution file, y and rotation velocity 0. Blocks may have their own
density (a heavier crown): one material per density.

Collapse (voussoir-run's criteria): a free body dropped by more than collapse_drop_m or
turned by more than collapse_rotation_rad from its position at the start, checked every
`every` steps; the run stops at the first collapse. OUT.json: collapsed, collapse_time_s
(from the start of the motion, i.e. after the lead), steps, loop_s, settle_max_drop_m
(largest drop of a free body at the end of the lead at rest).

With "crown_bodies" (1-based, the keystone or the two middle voussoirs) and "table_body"
(1-based, a driven body the table carries) in MODEL.json, OUT.json also holds the crown's
record relative to the table, as a laboratory's crown transducer gives it (the contract's
crown_dx_m, crown_dy_m): every `every` steps from the start of the motion, the mean of the
crown bodies' centroids less the table body's position, less that offset at the start of
the motion: "crown_t_s", "crown_dx_m", "crown_dy_m".
"""
import json
import math
import os
import sys
import time

import numpy as np

from lmgc90_case import step  # the same Moreau-Jean step as the side-by-side bench


def gen(model):
    from pylmgc90 import pre

    os.makedirs("DATBOX", exist_ok=True)
    bodies = pre.avatars()
    mats = pre.materials()
    mods = pre.models()
    svs = pre.see_tables()
    tacts = pre.tact_behavs()
    mod = pre.model(name="rigid", physics="MECAx", element="Rxx2D", dimension=2)
    mods.addModel(mod)
    by_density = {}
    for b in model["bodies"]:
        rho = float(b["density_kg_m3"])
        if rho not in by_density:
            by_density[rho] = pre.material(name=f"MAT{len(by_density):02d}", materialType="RIGID", density=rho)
            mats.addMaterial(by_density[rho])
    for b in model["bodies"]:
        driven = b["role"] != 1
        body = pre.rigidPolygon(model=mod, material=by_density[float(b["density_kg_m3"])],
                                center=np.array(b["centroid"], float), color="FOUND" if driven else "BLOCK",
                                generation_type="full", vertices=np.array(b["vertices"], float))
        if driven:
            path = os.path.join("DATBOX", b["evolution"])
            if not os.path.exists(path):
                np.savetxt(path, np.array([[0.0, 0.0], [1e3, 0.0]]))
            body.imposeDrivenDof(component=[1], dofty="vlocy", description="evolution", evolutionFile=b["evolution"])
            body.imposeDrivenDof(component=[2, 3], dofty="vlocy")
        bodies.addAvatar(body)
    law = pre.tact_behav(name="iqsc0", law="IQS_CLB", fric=model["friction"])
    tacts += law
    for antagonist in ("BLOCK", "FOUND"):
        svs += pre.see_table(CorpsCandidat="RBDY2", candidat="POLYG", colorCandidat="BLOCK",
                             CorpsAntagoniste="RBDY2", antagoniste="POLYG", colorAntagoniste=antagonist,
                             behav=law, alert=model["alert_m"])
    pre.writeDatbox(2, mats, mods, bodies, tacts, svs, gravy=[0.0, -model["gravity_m_s2"], 0.0])


def run(model, spec, out_path):
    from pylmgc90 import chipy

    chipy.Initialize()
    chipy.checkDirectories()
    chipy.utilities_DisableLogMes()
    chipy.SetDimension(2, 1)
    chipy.TimeEvolution_SetTimeStep(model["dt_s"])
    chipy.Integrator_InitTheta(model["theta"])
    chipy.ReadDatbox(deformable=False)
    chipy.ComputeMass()

    roles = [b["role"] for b in model["bodies"]]
    free = [i + 1 for i, r in enumerate(roles) if r == 1]
    ref = {i: np.array(chipy.RBDY2_GetBodyVector("Coor0", i)) for i in free}
    drop, rot = model["collapse_drop_m"], model["collapse_rotation_rad"]
    every = model["every"]
    dt = model["dt_s"]
    lead = spec["lead_steps"]
    solver = ["Stored_Delassus_Loops         ", "Quad ", model["tol"], 1.0, 10, 1000]
    collapsed, collapse_t, settle = False, math.nan, math.nan
    crown, table = model.get("crown_bodies"), model.get("table_body")
    record, start = {"crown_t_s": [], "crown_dx_m": [], "crown_dy_m": []}, None

    def relative():
        c = np.mean([chipy.RBDY2_GetBodyVector("Coor_", i)[:2] for i in crown], axis=0)
        return c - np.array(chipy.RBDY2_GetBodyVector("Coor_", table)[:2])

    t0 = time.perf_counter()
    k = 0
    for k in range(1, spec["n_steps"] + 1):
        step(chipy, solver)
        if k == lead:
            settle = max(ref[i][1] - chipy.RBDY2_GetBodyVector("Coor_", i)[1] for i in free)
            if crown:
                start = relative()
        if crown and start is not None and (k - lead) % every == 0:
            d = relative() - start
            record["crown_t_s"].append((k - lead) * dt)
            record["crown_dx_m"].append(float(d[0]))
            record["crown_dy_m"].append(float(d[1]))
        if k % every == 0:
            for i in free:
                q = chipy.RBDY2_GetBodyVector("Coor_", i)
                if ref[i][1] - q[1] > drop or abs(q[2] - ref[i][2]) > rot:
                    collapsed, collapse_t = True, (k - lead) * dt
                    break
            if collapsed:
                break
    loop_s = time.perf_counter() - t0
    chipy.Finalize()
    with open(out_path, "w") as f:
        json.dump({"collapsed": collapsed, "collapse_time_s": collapse_t, "steps": k, "loop_s": loop_s,
                   "settle_max_drop_m": settle, **(record if crown else {})}, f)


if __name__ == "__main__":
    with open(sys.argv[2]) as f:
        model = json.load(f)
    if sys.argv[1] == "gen":
        gen(model)
    else:
        with open(sys.argv[3]) as f:
            spec = json.load(f)
        run(model, spec, sys.argv[4])
