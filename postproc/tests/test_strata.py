"""Posterior model samples stratified by the rival models (voussoir-post samples; issue 36,
item 2): the allocation against counts worked out by hand, the file's rows against the
source file read here with the csv module, its weights against the diagnosis's
probabilities."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from voussoir_post.cli.post import main
from voussoir_post.diagnosis.strata import allocate, read_strata, stratify_file
from voussoir_post.errors import InputError

ROOT = Path(__file__).resolve().parents[2]
SEED = ROOT / "docs" / "seed_2013"


def test_allocation_is_the_hand_computed_one():
    # 0.5, 0.3, 0.15, 0.04 over 0.99 (e below 0.02 left out): n q = 5.05, 3.03, 1.52, 0.40 -> 5, 3, 1, 1
    assert allocate({"a": 0.5, "b": 0.3, "c": 0.15, "d": 0.04, "e": 0.01}, 10, 0.02) == {"a": 5, "b": 3, "c": 1, "d": 1}
    # n q = 3.6, 0.2, 0.2: the floors of one give 3 + 1 + 1 = 5 > 4, taken back from a
    assert allocate({"a": 0.9, "b": 0.05, "c": 0.05}, 4) == {"a": 2, "b": 1, "c": 1}
    # n q = 4.5, 4.5, 1: floors 4, 4, 1; the one left over to the tie's larger probability, then the name
    assert allocate({"x": 0.45, "w": 0.45, "z": 0.10}, 10) == {"w": 5, "x": 4, "z": 1}
    with pytest.raises(InputError, match="at least 3"):
        allocate({"a": 0.5, "b": 0.3, "c": 0.2}, 2)


def test_the_seed_posterior_in_30_samples():
    # diagnosis.json's probabilities >= 0.01 (the seed campaign read as ramps, 2026-11-30):
    # contact_edges .285723, geometry .270533, friction .210446, contact_edges+geometry .073219,
    # friction+geometry .056692, contact_edges+friction .054735, base_restraint+friction .029006
    # (sum .980354); 30 q = 8.74, 8.28, 6.44, 2.24, 1.73, 1.68, 0.89: floors 8, 8, 6, 2, 1, 1 and
    # the floor of one 1 (27), the 3 left to the largest remainders .744 (edges), .735
    # (friction+geometry), .675 (edges+friction)
    p = json.loads((SEED / "diagnosis.json").read_text())["probabilities"]
    assert allocate(p, 30) == {"contact_edges": 9, "geometry": 8, "friction": 6, "contact_edges+geometry": 2,
                               "friction+geometry": 2, "contact_edges+friction": 2, "base_restraint+friction": 1}


def test_the_stratified_file_keeps_each_models_first_rows_and_its_weights(tmp_path):
    out = tmp_path / "strat.csv"
    strata = stratify_file(str(SEED / "posterior_samples_A156.csv"), str(SEED / "diagnosis.json"), 30, str(out))
    with open(SEED / "posterior_samples_A156.csv") as f:
        source = list(csv.DictReader(line for line in f if not line.startswith("#")))
    with open(out) as f:
        lines = f.read().splitlines()
    assert lines[0] == "# format: voussoir posterior samples 1" and lines[1] == "# model version: 1"
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    assert len(rows) == 30 and strata.models == [r["model"] for r in rows]
    for model, k in strata.counts().items():
        assert [r["sample"] for r in rows if r["model"] == model] == \
            [r["sample"] for r in source if r["model"] == model][:k]
    p = json.loads((SEED / "diagnosis.json").read_text())["probabilities"]
    total = sum(p[m] for m in strata.counts())
    for model, w in zip(strata.models, strata.weights):
        assert w == pytest.approx(p[model] / total / strata.counts()[model], rel=1e-7)
    assert strata.weights.sum() == pytest.approx(1.0, abs=1e-12)
    assert read_strata(str(out)).counts() == strata.counts()


def test_the_command_writes_a_file_the_strata_reader_reads(tmp_path, capsys):
    out = tmp_path / "s.csv"
    assert main(["samples", str(SEED / "posterior_samples_A156.csv"), "--n", "7", "--min-probability", "0.05",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    # 0.05 leaves out base_restraint+friction (0.029): 6 models (sum 0.951348); 7 q = contact_edges 2.10 -> 2,
    # the others 1.99, 1.55, 0.54, 0.42, 0.40 -> 1 each (7 in all)
    assert read_strata(str(out)).counts() == {"contact_edges": 2, "geometry": 1, "friction": 1,
                                              "contact_edges+geometry": 1, "friction+geometry": 1,
                                              "contact_edges+friction": 1}
    assert "wrote" in text
    assert main(["samples", str(SEED / "posterior_samples_A156.csv"), "--n", "3", "--out", str(out)]) == 2
