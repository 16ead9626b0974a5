"""The diagnosis's posterior as model samples (voussoir_post.diagnosis.samples), and
those samples through an IDA of voussoir-sweep.

A small posterior is built here with known model probabilities and parameter weights;
the draws must reproduce it (model frequencies, parameter means within a model), and
the written CSV must map each draw to &arch values as the module's docstring says
(thickness f t about the mean radius; table gains and restraints dropped) and carry
the format, model version and nominal arch lines that the IDA checks (the model version
that of the sweep's source). Then the
written file is the `model_samples_file` of a tiny IDA, whose file must carry each
sample's values and whose searches start at the static capacity of each sample's arch.
"""

from __future__ import annotations

import csv
import json
import math
import os
import re
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest

from voussoir_post.diagnosis.models import ModelGrid
from voussoir_post.diagnosis.observations import Observations, PairObservation
from voussoir_post.diagnosis.posterior import ModelPosterior, Posterior
from voussoir_post import __version__
from voussoir_post.diagnosis.samples import MODEL_VERSION, SAMPLE_COLUMNS, draw_samples, write_samples
from voussoir_post.readers.campaign import Specimen

#: The posterior built here: model -> (probability, {parameter: grid values}, weights).
#: contact_edges+geometry is a 3 x 2 grid flattened (inset fastest); the restraint and
#: the table gain of base_restraint+table_motion belong to the laboratory.
INSETS, FACTORS = np.array([0.0, 0.004, 0.008]), np.array([0.8, 1.05])
MODELS = {
    "none": (0.1, {}, np.array([1.0])),
    "friction": (0.4, {"friction": np.array([0.30, 0.40, 0.50, 0.60])}, np.array([0.1, 0.2, 0.3, 0.4])),
    "contact_edges+geometry": (0.3, {"contact_edges": np.tile(INSETS, 2), "geometry": np.repeat(FACTORS, 3)},
                               np.array([0.05, 0.10, 0.15, 0.30, 0.25, 0.15])),
    "base_restraint+table_motion": (0.2, {"base_restraint": np.array(["left", "right", "both", "left"], object),
                                          "table_motion": np.array([0.8, 0.9, 1.1, 1.2])},
                                    np.array([0.25, 0.25, 0.25, 0.25])),
}
#: Two specimens of the seed's campaign (specimens.csv of data/seed_2013).
A156 = Specimen("A156", 156.0, 13, 0.508, 0.071, 0.145, 700.0, 0.5)
A132 = Specimen("A132", 132.0, 11, 0.508, 0.071, 0.145, 700.0, 0.5)


def posterior() -> Posterior:
    models = {}
    for name, (p, params, weights) in MODELS.items():
        grid = ModelGrid(name, tuple(params), list(params.values()), np.log(np.full(weights.size, 1 / weights.size)),
                         np.zeros((weights.size, 1)), gain_per_pair=False)
        models[name] = ModelPosterior(name, grid, 0.0, weights, p)
    return Posterior(models, None, [], {name: spec[0] for name, spec in MODELS.items()})


def observations() -> Observations:
    pairs = [PairObservation(s.specimen_id, 2.0, 0.01, 0.012) for s in (A156, A132)]
    return Observations("synthetic", {"A156": A156, "A132": A132}, pairs, {})


def test_draws_reproduce_the_model_probabilities_and_parameter_means():
    """n = 20 000 draws. A model's count is binomial (n, p): within 4 sqrt(n p (1 - p))
    of n p. Within a model drawn n_m times, a parameter's sample mean has the standard
    error sqrt(var / n_m), var = sum w (v - mean)^2 its posterior variance: within 4 of
    them of the posterior mean sum w v. Each value drawn is a grid value, and for a pair
    the two parameters come from one grid point (no mixing of points)."""
    n = 20_000
    draws = draw_samples(posterior(), n, seed=11)
    assert len(draws) == n
    for name, (p, params, weights) in MODELS.items():
        mine = [values for model, values in draws if model == name]
        assert abs(len(mine) - n * p) < 4 * math.sqrt(n * p * (1 - p)), (name, len(mine))
        points = {tuple(zip(params, column)) for column in zip(*params.values())} if params else {()}
        assert all(tuple((k, values[k]) for k in params) in points for values in mine), name
        for k, v in params.items():
            if v.dtype == object:
                continue
            mean = float(weights @ v)
            se = math.sqrt(float(weights @ (v - mean) ** 2) / len(mine))
            drawn = np.array([values[k] for values in mine], float)
            assert abs(drawn.mean() - mean) < 4 * se, (name, k, drawn.mean(), mean, se)
    assert draw_samples(posterior(), n, seed=11) == draws  # a seed gives them again


def read_samples(path):
    """The rows of a samples file, as {column: text} (the test's own reading)."""
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    return [dict(zip(lines[0].split(","), line.split(","))) for line in lines[1:]]


@pytest.mark.parametrize("spec", [A156, A132], ids=lambda s: s.specimen_id)
def test_written_rows_are_the_draws_as_arch_values(tmp_path, spec):
    """Each row is the draw of the same number (write_samples draws with the default
    seed): friction the drawn one or the specimen's, the inset the drawn one or 0, a
    thickness factor f as thickness f t and extrados R_mean + f t / 2, R_mean = r_ext -
    t / 2 of the specimen (the ring thickened about its mean radius); a restraint and a
    table gain leave the nominal arch. Values are written to 6 significant digits."""
    n = 400
    paths = write_samples(tmp_path, posterior(), observations(), n, "synthetic")
    assert sorted(p.name for p in paths) == ["posterior_samples_A132.csv", "posterior_samples_A156.csv"]
    path = tmp_path / f"posterior_samples_{spec.specimen_id}.csv"
    rows = read_samples(path)
    assert list(rows[0]) == list(SAMPLE_COLUMNS) == ["sample", "model", "friction", "contact_inset_m",
                                                       "thickness_m", "r_ext_m"]
    assert f"specimen {spec.specimen_id}" in path.read_text() and "campaign synthetic" in path.read_text()
    # The two lines the IDA checks (src/sweep/model_samples.f90): the layout's version
    # first, and the specimen's nominal &arch values, exactly.
    comments = [line for line in path.read_text().splitlines() if line.startswith("#")]
    assert comments[0] == "# format: voussoir posterior samples 1"
    # then the model version the values mean and the code that wrote them
    assert comments[1:3] == [f"# model version: {MODEL_VERSION}", f"# code: voussoir-post {__version__}"]
    (nominal,) = [line for line in comments if line.startswith("# nominal arch: ")]
    given = dict(item.split(" = ") for item in nominal[len("# nominal arch: "):].split(", "))
    assert {k: float(v) for k, v in given.items()} == {
        "embrace_deg": spec.embrace_deg, "n_voussoirs": spec.n_voussoirs, "r_ext_m": 0.508, "thickness_m": 0.071,
        "width_m": 0.145, "density_kg_m3": 700.0}
    draws = draw_samples(posterior(), n)
    assert len(rows) == n
    r_mean = 0.508 - 0.071 / 2
    seen = set()
    for k, (row, (model, values)) in enumerate(zip(rows, draws)):
        f = values.get("geometry", 1.0)
        expect = {"friction": values.get("friction", 0.5), "contact_inset_m": values.get("contact_edges", 0.0),
                  "thickness_m": f * 0.071, "r_ext_m": r_mean + f * 0.071 / 2}
        assert row["sample"] == str(k) and row["model"] == model
        for column, value in expect.items():
            assert float(row[column]) == pytest.approx(value, rel=5e-6), (k, column)
        assert float(row["r_ext_m"]) - float(row["thickness_m"]) / 2 == pytest.approx(r_mean, rel=1e-5)
        seen.add(model)
    assert seen == set(MODELS)  # 400 draws hold every model (the rarest has p = 0.1)
    lab = [row for row in rows if row["model"] == "base_restraint+table_motion"]
    assert lab and all((float(r["friction"]), float(r["contact_inset_m"]), float(r["thickness_m"]),
                        float(r["r_ext_m"])) == (0.5, 0.0, 0.071, 0.508) for r in lab)


def test_the_model_version_is_the_sweeps():
    """MODEL_VERSION here and model_version of the sweep's reader (src/core/version.f90.in,
    which src/sweep/model_samples.f90 checks a file's '# model version:' line against)
    are one number: a file this package writes is one the sweep reads."""
    source = (Path(__file__).resolve().parents[2] / "src" / "core" / "version.f90.in").read_text()
    found = re.findall(r"^\s*integer, parameter :: model_version = (\d+)\s*$", source, flags=re.MULTILINE)
    assert len(found) == 1, found
    assert int(found[0]) == MODEL_VERSION


# ------------------------------------------------------------------ through an IDA

ARCH = "&arch embrace_deg = 156, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, width_m = 0.145,\n" \
       "  density_kg_m3 = 700, friction = 0.5 /\n"


def pulse_record(path) -> float:
    """Three cycles of 2 Hz at 1 m/s2 peak (every 10 ms), then 0.5 s at rest; its PGA."""
    accel = [round(math.sin(2 * math.pi * 2.0 * 0.01 * k), 6) if k <= 150 else 0.0 for k in range(201)]
    path.write_text("t_s,accel_m_s2\n" + "".join(f"{0.01 * k:.2f},{a:.6f}\n" for k, a in enumerate(accel)))
    return max(abs(a) for a in accel)


def static_capacity(exe, folder, name, row) -> float:
    """lambda g [m/s2] of a sample's arch by voussoir-limit (the smaller direction)."""
    nml = folder / f"{name}.nml"
    nml.write_text(ARCH.replace(" /", f", friction = {row['friction']}, contact_inset_m = {row['contact_inset_m']}, "
                                      f"thickness_m = {row['thickness_m']}, r_ext_m = {row['r_ext_m']} /"))
    out = json.loads(subprocess.run([str(exe), str(nml), "--json"], capture_output=True, text=True,
                                    check=True).stdout)
    return min(out["lambda_pos"], out["lambda_neg"]) * out["g_m_s2"]


def test_written_samples_reach_the_runs_of_an_ida(tmp_path, voussoir_sweep_exe, voussoir_limit_exe):
    """3 samples written by write_samples (one per model with an arch of its own: the
    draws with seed 2026 are searched for one friction, one contact_edges+geometry and one
    none sample) as the model_samples_file of a tiny IDA (one short pulse record):
    /parameters holds each row's values, the CSV rows carry them, and each sample's static
    capacity and its search's first scale, 0.95 lambda g / PGA, are those of the sample's
    own arch (voussoir-limit on the values as read here)."""
    many = tmp_path / "many"
    many.mkdir()
    (path,) = write_samples(many, posterior(), Observations("synthetic", {"A156": A156},
                                                            [PairObservation("A156", 2.0, 0.01, 0.012)], {}),
                            200, "synthetic")
    text = path.read_text().splitlines()
    comments = [line for line in text if line.startswith("#")]
    rows = read_samples(path)
    picked = [next(r for r in rows if r["model"] == m) for m in ("friction", "contact_edges+geometry", "none")]
    (tmp_path / "samples.csv").write_text("\n".join(comments + [",".join(SAMPLE_COLUMNS)]
                                                   + [",".join(r[c] for c in SAMPLE_COLUMNS) for r in picked]) + "\n")
    pga = pulse_record(tmp_path / "pulse.csv")
    (tmp_path / "ida.nml").write_text(
        ARCH + "&motion rest_s = 0.5 /\n&solver dt_s = 2.0e-3 /\n"
        "&sweep mode = 'ida', record_files = 'pulse.csv', scale_tol = 0.1, scale_max = 30,\n"
        "  model_samples_file = 'samples.csv' /\n&output file = 'ida.h5' /\n")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    proc = subprocess.run(["mpirun", "--oversubscribe", "-np", "1", str(voussoir_sweep_exe), "ida.nml"],
                          cwd=tmp_path, capture_output=True, text=True, env=env, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "could not be checked" not in proc.stdout  # its nominal arch line is the base &arch's
    names = ["friction", "contact_inset_m", "thickness_m", "r_ext_m"]
    with h5py.File(tmp_path / "ida.h5") as h5:
        columns = h5.attrs["parameter_names"]
        columns = (columns.decode() if isinstance(columns, bytes) else str(columns)).split(",")
        values = h5["parameters/values"][()]
        job, run, scale = h5["runs/job"][()], h5["runs/run"][()], h5["runs/scale"][()]
        capacity = h5["results/static_capacity_m_s2"][()]
        code = h5.attrs["model_samples_code"]
    # the file's '# code:' line, echoed into the sweep's provenance
    assert (code.decode() if isinstance(code, bytes) else str(code)) == f"voussoir-post {__version__}"
    assert sorted(columns) == sorted(names) and values.shape == (3, 4)
    for s, row in enumerate(picked):
        assert all(values[s, columns.index(k)] == float(row[k]) for k in names), (s, row)
    with open(tmp_path / "ida.csv", newline="") as f:
        ida_rows = list(csv.DictReader(f))
    assert [int(r["param_set"]) for r in ida_rows] == [0, 1, 2]
    assert all(float(r[k]) == float(p[k]) for r, p in zip(ida_rows, picked) for k in names)
    firsts = []
    for s, row in enumerate(picked):
        first = float(scale[(job == s) & (run == 0)][0])
        limit = static_capacity(voussoir_limit_exe, tmp_path, f"limit_{s}", row)
        assert capacity[s] == pytest.approx(limit, rel=1e-9), (s, capacity[s], limit)
        assert first == pytest.approx(0.95 * limit / pga, rel=1e-9), (s, first, 0.95 * limit / pga)
        firsts.append(first)
    # The thinner or inset ring has another capacity (friction, high enough for hinging,
    # leaves it unchanged): the check sees the geometry columns.
    assert abs(firsts[1] - firsts[2]) > 1e-3 * firsts[2], firsts
