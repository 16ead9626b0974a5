"""Posterior model samples stratified by the rival models, for the calibrated fragility
(issue 36, item 2).

The diagnosis writes its posterior as draws (`posterior_samples_<specimen>.csv`: a model
drawn by its probability, its parameters by their posterior weights). A handful of those
draws in file order cannot represent a posterior split between several rivals, and a
rival of probability 0.09 is left out of 4 draws two times in three. Stratified, each
model of posterior probability at least ``min_probability`` gets a share of the n samples
by its probability (renormalised over those models), at least one:

    n_m = max(1, floor(n q_m)), then the samples left over (or taken back) by the largest
    (smallest) remainders n q_m - n_m, ties by the larger probability, then the name;

and the samples of a model are its first n_m rows in the file (the file's draws are in
random order, their parameters already drawn by their posterior weights). Each sample s of
model m then stands for the weight w_s = q_m / n_m of the mixture (the weights sum to 1):
the calibrated fragility is sum_s w_s F_s(IM), a stratified estimate of the posterior
mixture, whatever the rounding of the shares.

The stratified file is a samples file as `&sweep model_samples_file` reads it (the same
comment lines, header and columns; the `sample` column keeps each row's number in the
source file), with one comment line per stratum that :func:`read_strata` reads back:

    # stratum: model = friction, probability = 0.305308, share = 0.309758, samples = 9, weight = 0.0344176
"""

from __future__ import annotations

import json
import math
import os
import re
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..readers.csv_table import read_csv_table

__all__ = ["allocate", "Strata", "stratify_file", "read_strata", "STRATUM_PREFIX", "DEFAULT_MIN_PROBABILITY"]

#: The comment line of each stratum in a stratified samples file.
STRATUM_PREFIX = "# stratum:"
#: Models below this posterior probability get no sample (their share would be < 0.3 of a sample in 30).
DEFAULT_MIN_PROBABILITY = 0.01
_STRATUM = re.compile(r"#\s*stratum:\s*model\s*=\s*(?P<model>[^,]+),\s*probability\s*=\s*(?P<p>[^,]+),"
                      r"\s*share\s*=\s*(?P<q>[^,]+),\s*samples\s*=\s*(?P<n>\d+),\s*weight\s*=\s*(?P<w>\S+)\s*$")


def allocate(probabilities: dict[str, float], n: int, min_probability: float = DEFAULT_MIN_PROBABILITY,
             available: dict[str, int] | None = None) -> dict[str, int]:
    """The samples of each model: the models of probability >= ``min_probability`` (and
    with rows in ``available``, when given: {model: rows of the file}) share ``n`` by
    their renormalised probabilities, at least one each, the rest by largest remainders
    (module docstring). Ordered by probability, largest first. InputError when ``n`` is
    below the number of such models, or a model needs more rows than the file has."""
    if n < 1:
        raise InputError(f"the number of samples must be >= 1 (got {n})")
    if not 0.0 <= min_probability < 1.0:
        raise InputError(f"the smallest probability of a stratum must be in [0, 1) (got {min_probability})")
    for m, p in probabilities.items():
        if not (math.isfinite(p) and p >= 0.0):
            raise InputError(f"model {m}: probability {p!r} is not a number >= 0")
    chosen = sorted((m for m, p in probabilities.items() if p >= min_probability and p > 0.0),
                    key=lambda m: (-probabilities[m], m))
    if available is not None:
        absent = [m for m in chosen if available.get(m, 0) == 0]
        if absent:
            raise InputError(f"model(s) {', '.join(absent)} of posterior probability >= {min_probability:g} have no "
                             f"row in the samples file: draw more posterior samples (voussoir-diagnose)")
    if not chosen:
        raise InputError(f"no model has a posterior probability >= {min_probability:g}")
    if n < len(chosen):
        raise InputError(f"{n} samples cannot give one to each of the {len(chosen)} models of probability >= "
                         f"{min_probability:g} ({', '.join(chosen)}): ask for at least {len(chosen)}")
    total = sum(probabilities[m] for m in chosen)
    target = {m: n * probabilities[m] / total for m in chosen}
    counts = {m: max(1, int(math.floor(target[m]))) for m in chosen}
    order = sorted(chosen, key=lambda m: (-(target[m] - counts[m]), -probabilities[m], m))
    k = 0
    while sum(counts.values()) < n:
        counts[order[k % len(order)]] += 1
        k += 1
    while sum(counts.values()) > n:  # the floor of one raised some: take back from the smallest remainders
        m = min((m for m in chosen if counts[m] > 1), key=lambda m: (target[m] - counts[m], probabilities[m], m))
        counts[m] -= 1
    if available is not None:
        short = [f"{m} ({counts[m]} needed, {available[m]} in the file)" for m in chosen if counts[m] > available[m]]
        if short:
            raise InputError("the samples file has too few rows of " + ", ".join(short) +
                             ": draw more posterior samples (voussoir-diagnose), or ask for fewer")
    return counts


@dataclass
class Strata:
    """The strata of a stratified samples file, row by row."""

    path: str
    models: list[str]  #: the model of each sample row (param_set s is row s)
    weights: np.ndarray  #: each row's weight in the mixture, q_m / n_m (sum 1)
    probabilities: dict[str, float]  #: each stratum's posterior probability (as the diagnosis gave it)
    shares: dict[str, float]  #: renormalised over the strata (q_m)
    values: dict[str, np.ndarray]  #: the rows' parameter columns (friction, ...)

    @property
    def model_names(self) -> list[str]:
        """The strata, largest share first."""
        return sorted(self.shares, key=lambda m: (-self.shares[m], m))

    def counts(self) -> dict[str, int]:
        return {m: self.models.count(m) for m in self.model_names}


def _probabilities(diagnosis_json: str) -> dict[str, float]:
    try:
        with open(diagnosis_json) as f:
            data = json.load(f)
        probabilities = {str(m): float(p) for m, p in data["probabilities"].items()}
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
        raise InputError(f"{diagnosis_json}: not a diagnosis.json with the models' 'probabilities' ({exc})") from None
    return probabilities


def stratify_file(samples_csv: str, diagnosis_json: str, n: int, out_csv: str,
                  min_probability: float = DEFAULT_MIN_PROBABILITY) -> Strata:
    """Write ``out_csv``: ``n`` rows of the posterior samples file ``samples_csv``
    stratified by the models' probabilities in ``diagnosis_json`` (the diagnosis's
    'probabilities'), with its comment lines, a line on how the rows were chosen and one
    ``# stratum:`` line per model; return its :class:`Strata`."""
    probabilities = _probabilities(diagnosis_json)
    table = read_csv_table(samples_csv, expected="a header row with sample, model, ...")
    if "model" not in table.columns:
        raise InputError(f"{samples_csv}: no 'model' column: not a posterior samples file of the diagnosis")
    rows_by_model: dict[str, list] = {}
    for row in table.rows:
        rows_by_model.setdefault(row.cells["model"], []).append(row)
    counts = allocate(probabilities, n, min_probability, {m: len(r) for m, r in rows_by_model.items()})
    total = sum(probabilities[m] for m in counts)
    with open(samples_csv, encoding="utf-8-sig") as f:
        text = f.read().splitlines()
    comments = [line for line in text[:table.header_line - 1] if line.startswith("#")]
    lines = comments + [
        f"# stratified: {n} of the {len(table.rows)} samples of {os.path.basename(samples_csv)} (voussoir-post "
        f"samples), by model: each model of posterior probability >= {min_probability:g} in "
        f"{os.path.basename(diagnosis_json)} gets a share of the {n} by its probability renormalised over those "
        f"models (largest remainders, at least one), its first rows in the file; in the mixture a sample of model m "
        f"weighs share_m / samples_m (docs/earthquakes.md)"]
    for m, k in counts.items():
        lines.append(f"{STRATUM_PREFIX} model = {m}, probability = {probabilities[m]:.6g}, share = "
                     f"{probabilities[m] / total:.9g}, samples = {k}, weight = {probabilities[m] / total / k:.9g}")
    lines.append(",".join(table.columns))
    for m, k in counts.items():
        for row in rows_by_model[m][:k]:
            lines.append(",".join(row.cells[c] for c in table.columns))
    tmp = out_csv + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, out_csv)
    return read_strata(out_csv)


def read_strata(path: str) -> Strata:
    """The strata of a stratified samples file (:func:`stratify_file`); InputError when it
    has no ``# stratum:`` lines or they disagree with its rows."""
    strata = {}
    with open(path, encoding="utf-8-sig") as f:
        for k, line in enumerate(f, 1):
            if line.startswith(STRATUM_PREFIX):
                found = _STRATUM.match(line.strip())
                if not found:
                    raise InputError(f"{path}:{k}: a stratum line that cannot be read: {line.strip()}")
                strata[found["model"].strip()] = (float(found["p"]), float(found["q"]), int(found["n"]),
                                                  float(found["w"]))
    if not strata:
        raise InputError(f"{path}: no '{STRATUM_PREFIX}' lines: not a stratified samples file (voussoir-post samples)")
    table = read_csv_table(path, expected="a header row with sample, model, ...")
    if "model" not in table.columns:
        raise InputError(f"{path}: no 'model' column")
    models = [row.cells["model"] for row in table.rows]
    for m, (_, _, count, _) in strata.items():
        if models.count(m) != count:
            raise InputError(f"{path}: the stratum line of {m} says {count} samples, the rows have {models.count(m)}")
    unknown = sorted(set(models) - set(strata))
    if unknown:
        raise InputError(f"{path}: rows of model(s) {', '.join(unknown)} without a stratum line")
    weights = np.array([strata[m][3] for m in models])
    if abs(weights.sum() - 1.0) > 1e-6:
        raise InputError(f"{path}: the strata's weights sum to {weights.sum():.9g}, not 1")
    numeric = [c for c in table.columns if c not in ("sample", "model")]
    values = {c: np.array([float(row.cells[c]) for row in table.rows]) for c in numeric}
    return Strata(path, models, weights / weights.sum(), {m: v[0] for m, v in strata.items()},
                  {m: v[1] for m, v in strata.items()}, values)
