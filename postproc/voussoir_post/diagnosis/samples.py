"""The diagnosis's posterior as model samples of each arch, for the fragility.

`posterior_samples_<specimen>.csv` (one file per specimen with a certain set-up): rows
drawn from the posterior, each a model (by its probability) and its parameters (by
their posterior weights), written as the &arch values of that specimen:

    sample,model,friction,contact_inset_m,thickness_m,r_ext_m

A thickness factor f changes the ring about its mean radius (thickness f t, extrados
R_mean + f t / 2). Only what belongs to the arch itself is carried: a table gain is the
laboratory's actuator and a restraint the laboratory's set-up, so a sample of
`contact_edges+table_motion` keeps its inset and drops its gain, and one of
`base_restraint` is the nominal arch. The file is what `&sweep model_samples_file` of an
IDA reads (docs/earthquakes.md): the fragility of the arch as the table tests revealed it.

Comment lines let the IDA check that the file is meant for its arch and its code
(src/sweep/model_samples.f90 refuses it otherwise):

    # format: voussoir posterior samples 1
    # model version: 1
    # code: voussoir-post 0.1.0
    # nominal arch: embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, ...

the version of this layout; the version of the model the values mean (MODEL_VERSION,
which must equal the sweep's model_version in src/core/version.f90.in: raised, on both
sides, when a sampled parameter changes meaning, e.g. the contact inset, the thickness
factor or the friction law); the code that wrote the file (provenance, which the IDA's
HDF5 file repeats as model_samples_code); and the specimen's nominal &arch values the
samples are relative to (embrace_deg, n_voussoirs, r_ext_m, thickness_m, width_m,
density_kg_m3, each written to round-trip exactly), which must be those of the IDA's
base &arch.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .. import __version__
from ..readers.campaign import Specimen
from .observations import Observations
from .decision import PARAMETER_NAMES, prior_bound
from .posterior import Posterior

__all__ = ["write_samples", "draw_samples", "nominal_arch_line", "SAMPLE_COLUMNS", "FORMAT_LINE", "NOMINAL_KEYS",
           "MODEL_VERSION", "model_lines"]

SAMPLE_COLUMNS = ("sample", "model", "friction", "contact_inset_m", "thickness_m", "r_ext_m")
#: The first line of a file; a new layout gets a new number (and the IDA's reader learns it).
FORMAT_LINE = "# format: voussoir posterior samples 1"
#: The version of what the samples' values mean (the contact inset, the thickness factor
#: about the mean radius, the friction law, ...): raised with model_version of
#: src/core/version.f90.in when one changes meaning; the IDA refuses a file of another.
MODEL_VERSION = 1
#: The &arch variables of the nominal arch line, in its order.
NOMINAL_KEYS = ("embrace_deg", "n_voussoirs", "r_ext_m", "thickness_m", "width_m", "density_kg_m3")


def nominal_arch_line(spec: Specimen) -> str:
    """"# nominal arch: embrace_deg = ..., ..." of a specimen (reals as repr: exact)."""
    values = [f"{key} = {int(spec.n_voussoirs) if key == 'n_voussoirs' else float(getattr(spec, key))!r}"
              for key in NOMINAL_KEYS]
    return "# nominal arch: " + ", ".join(values)


def model_lines() -> list[str]:
    """The model version and code lines of a samples file."""
    return [f"# model version: {MODEL_VERSION}", f"# code: voussoir-post {__version__}"]


def constraint_line(post: Posterior, at_least: float = 0.05) -> str:
    """Which parameters of the models drawn (probability >= at_least) the data bound, and
    which lie against an edge of their prior (there the prior, not the data, bounds them)."""
    bound, edge = [], []
    for m in post.ranked():
        if post.probabilities[m] < at_least or m == "none":
            continue
        at_edge = set(prior_bound(post, m))
        for name, v in zip(post.models[m].grid.names, post.models[m].grid.values):
            if v.dtype == object:
                continue
            label = f"{PARAMETER_NAMES[name]} in {m}"
            (edge if PARAMETER_NAMES[name] in at_edge else bound).append(label)
    return ("# bounded by the data: " + (", ".join(bound) or "none") + "; against an edge of the prior (the prior, "
            "not the data, bounds it): " + (", ".join(edge) or "none"))


def draw_samples(post: Posterior, n: int, seed: int = 2026) -> list[tuple[str, dict]]:
    """`n` draws (model id, {effect: value}) from the posterior, with a fixed seed."""
    rng = np.random.default_rng(seed)
    models = list(post.probabilities)
    p = np.array([post.probabilities[m] for m in models])
    out = []
    for m in rng.choice(len(models), size=n, p=p / p.sum()):
        mp = post.models[models[m]]
        k = rng.choice(mp.grid.n, p=mp.weights)
        out.append((models[m], {name: v[k] for name, v in zip(mp.grid.names, mp.grid.values)}))
    return out


def write_samples(out_dir: Path, post: Posterior, obs: Observations, n: int, campaign_name: str) -> list[Path]:
    """Write the posterior samples of every specimen with a certain set-up; return the files."""
    draws = draw_samples(post, n)
    written = []
    for sid in sorted({p.specimen_id for p in obs.pairs}):
        spec = obs.specimens[sid]
        r_mean = spec.r_ext_m - 0.5 * spec.thickness_m
        lines = [FORMAT_LINE, *model_lines(),
                 f"# Posterior samples of the model of specimen {sid}, from voussoir-diagnose (voussoir_post "
                 f"{__version__}) on campaign "
                 f"{campaign_name} ({n} draws: a model by its probability, its parameters by their posterior "
                 "weights).",
                 "# &arch values of the arch itself: table gains and restraints (the laboratory's) are not "
                 "carried; a thickness factor f gives thickness f t about the mean radius.",
                 nominal_arch_line(spec), constraint_line(post),
                 ",".join(SAMPLE_COLUMNS)]
        for k, (model, values) in enumerate(draws):
            f = float(values.get("geometry", 1.0))
            friction = float(values.get("friction", spec.friction))
            inset = float(values.get("contact_edges", 0.0))
            lines.append(f"{k},{model},{friction:.6g},{inset:.6g},{f * spec.thickness_m:.6g},"
                         f"{r_mean + 0.5 * f * spec.thickness_m:.6g}")
        path = Path(out_dir) / f"posterior_samples_{sid}.csv"
        path.write_text("\n".join(lines) + "\n")
        written.append(path)
    return written
