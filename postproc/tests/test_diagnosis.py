"""The diagnosis must find an effect hidden in synthetic data.

Each campaign is written by the project's own simulator (voussoir_post.synthetic) under
one hidden truth, with realistic amplitude steps and sensor noise, in the spec's format
and with no trace of the truth in any file. The diagnosis is told nothing; the truth
lives only in the assertions below.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from voussoir_post.campaign import read_campaign
from voussoir_post.diagnosis import (CandidateResult, DiagnosisSettings, PairData, TableEvidence, afd_command,
                                     decide, diagnose, fit_actuator)
from voussoir_post.synthetic import Truth, write_synthetic_campaign

from conftest import bin_dir, executable

TRUTHS = {
    "none": Truth(),
    "contact_edges": Truth(effect="contact_edges", inset_m=0.004),
    "friction": Truth(effect="friction", friction=0.40),
    "table_motion": Truth(effect="table_motion", accel_gain=1.12, delay_s=0.02),
    "base_restraint": Truth(effect="base_restraint", restrained_springings="both"),
}


@pytest.fixture(scope="module", params=list(TRUTHS))
def diagnosed(request, tmp_path_factory, voussoir_run_exe):
    if executable("voussoir-sweep") is None or executable("voussoir-limit") is None:
        pytest.fail(f"voussoir-sweep and voussoir-limit are needed in {bin_dir()}")
    name = request.param
    truth = TRUTHS[name]
    root = tmp_path_factory.mktemp(f"campaign_{name}")
    folder = root / "campaign"
    write_synthetic_campaign(folder, truth, bin_dir(), seed=7)
    out = root / "diagnosis"
    result = diagnose(folder, out, DiagnosisSettings(bin_dir=bin_dir(), n_ranks=2, log=lambda m: None))
    return name, truth, folder, out, result


def test_campaign_hides_the_truth(diagnosed):
    name, truth, folder, out, result = diagnosed
    campaign = read_campaign(folder)  # a valid campaign of the spec
    assert all(s.friction == 0.5 for s in campaign.specimens.values())  # nominal, whatever the truth
    words = ("inset", "restrain", "bracket", "gain", "truth", "hidden", "effect", "delay")
    for path in folder.rglob("*"):
        if path.is_file():
            text = path.read_text().lower()
            assert not any(w in text for w in words), f"{path} gives the truth away"


#: Causes that thresholds and hinges cannot tell apart on these campaigns, by physics: a
#: ring thinner by a factor (geometry) lowers the thresholds like a contact inset and
#: opens the same four hinges (issue 13). For them the spec's answer is `inconclusive`
#: with both among the rivals, never the other one named.
INDISTINGUISHABLE = {"contact_edges": {"geometry"}}


def _named_or_honest_rivals(name, result) -> bool:
    if result["verdict"] == name:
        return True
    allowed = INDISTINGUISHABLE.get(name)
    return (allowed is not None and result["verdict"] == "inconclusive" and name in result["rivals"]
            and set(result["rivals"]) <= {name} | allowed)


def test_verdict_names_the_hidden_effect(diagnosed):
    name, truth, folder, out, result = diagnosed
    assert _named_or_honest_rivals(name, result), result["notes"]


def test_parameter_is_recovered(diagnosed):
    name, truth, folder, out, result = diagnosed
    params = result["parameters"]
    if result["verdict"] == "inconclusive" and name != "none":  # the rival's own fit must hold the truth
        params = next(c["parameters"] for c in result["candidates"] if c["effect"] == name)
    if name == "none":
        assert params == {}
    elif name == "contact_edges":
        assert abs(params["inset_m"]["value"] - truth.inset_m) <= 1.0e-3
        assert params["inset_m"]["unit"] == "m"
    elif name == "friction":
        assert abs(params["friction"]["value"] - truth.friction) <= 0.05
    elif name == "table_motion":
        assert abs(params["accel_gain"]["value"] - truth.accel_gain) <= 0.05
        assert abs(params["delay_s"]["value"] - truth.delay_s) <= 0.01
    elif name == "base_restraint":
        assert sorted(params["restrained_springings"]["value"]) == ["left", "right"]
    for p in params.values():
        if isinstance(p["value"], float):
            assert p["low"] <= p["value"] <= p["high"]


def test_extended_model_beats_baseline(diagnosed):
    name, truth, folder, out, result = diagnosed
    base = result["baseline"]["threshold_error_pct"]
    ext = result["extended"]["threshold_error_pct"]
    if name == "none":
        assert ext == base and base < 5.0
    else:
        assert ext < 0.6 * base, (base, ext)
        if result["baseline"]["hinge_match"] is not None:
            assert result["extended"]["hinge_match"] >= result["baseline"]["hinge_match"]


def test_outputs_follow_the_spec(diagnosed):
    name, truth, folder, out, result = diagnosed
    on_disk = json.loads((out / "diagnosis.json").read_text())
    assert on_disk == json.loads(json.dumps(result))
    assert set(on_disk) == {"campaign", "verdict", "effects", "rivals", "parameters", "baseline", "extended",
                            "candidates", "notes"}
    assert on_disk["campaign"] == "campaign"
    assert {c["effect"] for c in on_disk["candidates"]} == {"contact_edges", "table_motion", "base_restraint",
                                                             "friction", "geometry"}
    for key in ("baseline", "extended"):
        assert set(on_disk[key]) == {"threshold_error_pct", "hinge_match"}
    # effects and rivals follow the verdict (shared/MEASURED_DATA.md)
    if on_disk["verdict"] in ("none", "inconclusive"):
        assert on_disk["effects"] == []
    else:
        assert on_disk["effects"] == [on_disk["verdict"]] and on_disk["rivals"] == []
    report = (out / "report.md").read_text()
    assert (f"`{name}`" if result["verdict"] == name else name) in report
    assert "## Crown motion" in report and "## Hinges" in report
    for png in ("thresholds.png", "candidates.png"):
        assert png in report and (out / png).stat().st_size > 1000


# ------------------------------------------------------------------ fast unit checks


def test_actuator_fit_recovers_gain_and_delay():
    class T:  # the fields of a campaign test that the fit reads
        frequency_hz, amplitude_m, n_attack, n_full, n_decay = 1.6, 0.03, 1, 1, 1
    t = np.arange(0.0, 3.0, 0.005)
    rng = np.random.default_rng(3)
    x = 1.07 * afd_command(t - 0.031, 1.6, 0.03) + 5e-5 * rng.standard_normal(t.size)
    gain, delay, rms = fit_actuator(t, x, T)
    assert abs(gain - 1.07) < 0.005
    assert abs(delay - 0.031) < 0.002
    assert rms < 0.01


def _pair(threshold_m, resolution=0.02, nominal_m=None):
    from voussoir_post.campaign import MeasuredThreshold, Specimen
    from voussoir_post.diagnosis import Variant
    m = MeasuredThreshold("S", 1.0, threshold_m, threshold_m * (1 - resolution), threshold_m * (1 + resolution),
                          1, 1, False, [])
    p = PairData(m, Specimen("S", 156, 13, 0.508, 0.071, 0.145, 700), resolution, math.hypot(resolution, 0.03))
    p.simulated[Variant()] = nominal_m if nominal_m is not None else threshold_m
    return p


def _cand(effect, preds, cv):
    return CandidateResult(effect, 0.0, 0.0, 0.0, cv, cv, [], per_pair=list(preds))


def test_decide_none_within_resolution():
    pairs = [_pair(0.05, nominal_m=0.0505), _pair(0.03, nominal_m=0.0297)]
    d = decide(pairs, 0.03, {"friction": _cand("friction", [0.05, 0.03], 0.0)}, TableEvidence("none"))
    assert d.verdict == "none"


def test_decide_inconclusive_when_two_effects_explain_equally():
    meas = [0.050, 0.030, 0.040, 0.060]
    pairs = [_pair(m, nominal_m=1.25 * m) for m in meas]
    cands = {"contact_edges": _cand("contact_edges", [1.01 * m for m in meas], 0.01),
             "friction": _cand("friction", [0.995 * m for m in meas], 0.005)}
    d = decide(pairs, 0.03, cands, TableEvidence("none"))
    assert d.verdict == "inconclusive"
    assert "contact_edges" in d.notes and "friction" in d.notes
    # The rivals, best first: friction's predictions are the closer ones here.
    assert d.rivals == ["friction", "contact_edges"] and d.best_rival.effect == "friction"


def test_decide_names_the_clear_winner():
    meas = [0.050, 0.030, 0.040, 0.060]
    pairs = [_pair(m, nominal_m=1.25 * m) for m in meas]
    cands = {"contact_edges": _cand("contact_edges", [1.01 * m for m in meas], 0.01),
             "friction": _cand("friction", [1.15 * m for m in meas], 0.15)}
    assert decide(pairs, 0.03, cands, TableEvidence("none")).verdict == "contact_edges"
