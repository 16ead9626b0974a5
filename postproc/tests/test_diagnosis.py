"""The diagnosis must name what is hidden in a campaign it did not make.

Each campaign is written by independent_campaigns.py, by a path other than the
diagnosis's own models: polygon files with chamfered corners (not the contact inset), a
ring of thinner polygons (not the thickness parameter), brackets standing off by a gap,
a second-order actuator played as an accelerogram (not gain x delay), truth values off
the diagnosis's grids, a finer time step (5e-4 s against 1e-3 s), hinges found from the
blocks' motion, and a noise seed of its own per campaign. One campaign hides two causes
at once and one hides a cause outside every candidate (joints that gape at the
intrados), whose right answer is `inconclusive`. The diagnosis is told nothing; the truth
lives only in CASES below, and each test prints the verdict it found.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from voussoir_post.readers.campaign import read_campaign
from voussoir_post.diagnosis.pipeline import (CandidateResult, DiagnosisSettings, PairData, TableEvidence,
                                              afd_command, decide, diagnose, fit_actuator)
from voussoir_post.diagnosis.decision import hinge_match, hinge_score

from conftest import VERDICTS, bin_dir, executable
from independent_campaigns import ARCHES, Truth, actuator_record, ring_blocks, write_campaign, write_polygon_file

EDGES_OR_GEOMETRY = {"contact_edges", "geometry"}  # same hinges, same threshold drop (issue 13)


def _amplitude_ratio(f_hz: float, truth: Truth) -> float:
    """|H(f)| of the second-order actuator: the gain its records must show at f."""
    r = f_hz / truth.actuator_hz
    return 1.0 / math.hypot(1.0 - r * r, 2.0 * truth.actuator_damping * r)


#: name: (truth, noise seed, what a right answer is). `names` are the verdicts allowed
#: (`inconclusive` only with `rivals`: a subset that must contain the truth, or None
#: when no rival is right); `param` is (effect, parameter, low, high) read from the
#: named effect, or from the truth's own candidate when the verdict is inconclusive.
ACT = Truth(actuator_hz=6.0, actuator_damping=0.2)
_act_gains = [_amplitude_ratio(f, ACT) for a in ARCHES for f in a.frequencies_hz]
CASES = {
    "nothing": (Truth(), 11, {"names": {"none"}}),
    "chamfer 5.5 mm": (Truth(chamfer_m=0.0055), 11,
                       {"names": {"contact_edges"}, "rivals": EDGES_OR_GEOMETRY,
                        "param": ("contact_edges", "inset_m", 0.004, 0.007)}),
    "chamfer 3 mm, other noise": (Truth(chamfer_m=0.003), 29,
                                  {"names": {"contact_edges"}, "rivals": EDGES_OR_GEOMETRY,
                                   "param": ("contact_edges", "inset_m", 0.0015, 0.0045)}),
    "ring x0.85": (Truth(thickness_factor=0.85), 13,
                   {"names": {"geometry"}, "rivals": EDGES_OR_GEOMETRY,
                    "param": ("geometry", "thickness_factor", 0.81, 0.89)}),
    "actuator 6 Hz": (ACT, 17, {"names": {"table_motion"},
                                "param": ("table_motion", "accel_gain", min(_act_gains) - 0.03,
                                          max(_act_gains) + 0.03)}),
    # Brackets with play are weaker than the catalogue's rigid ones: restraint alone, or
    # with a second effect that weakens it, or rivals that all include it.
    "brackets 0.3 mm off": (Truth(bracket_gap_m=0.0003), 19,
                            {"names": {"base_restraint", "combined"}, "effects_must": {"base_restraint"},
                             "rivals": {"base_restraint", "geometry", "contact_edges", "friction"},
                             "rivals_must": {"base_restraint"}, "shared": "base_restraint",
                             "sides": ["left", "right"]}),
    "friction 0.43": (Truth(friction=0.43), 23, {"names": {"friction"}, "param": ("friction", "friction", 0.39, 0.47)}),
    "chamfer 4 mm and friction 0.42": (Truth(chamfer_m=0.004, friction=0.42), 31,
                                       {"names": {"combined"}, "effects": {"contact_edges", "friction"},
                                        "rivals": {"contact_edges", "friction", "geometry"},
                                        "rivals_must": {"friction"}}),
    "intrados gap (outside the catalogue)": (Truth(intrados_cut_m=0.005), 37, {"names": set(), "rivals": None}),
    # One specimen's set-up fault is not a cause of the campaign: no cause is named, and
    # the specimen is found on its own frequencies (setup_screen.py).
    "brackets on W132 only": (Truth(bracket_gap_m=0.0003, bracket_specimens=("W132",)), 41,
                              {"names": set(), "rivals": None, "restrained_alone": "W132"}),
}


@pytest.fixture(scope="module", params=list(CASES))
def diagnosed(request, tmp_path_factory, voussoir_run_exe):
    if executable("voussoir-sweep") is None or executable("voussoir-limit") is None:
        pytest.fail(f"voussoir-sweep and voussoir-limit are needed in {bin_dir()}")
    name = request.param
    truth, seed, expect = CASES[name]
    root = tmp_path_factory.mktemp("campaign")
    folder = root / "campaign"
    write_campaign(folder, truth, bin_dir(), seed=seed)
    out = root / "diagnosis"
    result = diagnose(folder, out, DiagnosisSettings(bin_dir=bin_dir(), n_ranks=2, log=lambda m: None))
    line = (f"[{name}] verdict {result['verdict']} effects {result['effects']} rivals {result['rivals']} "
            f"parameters {json.dumps(result['parameters'])}; error {result['baseline']['threshold_error_pct']:.1f} % "
            f"-> {result['extended']['threshold_error_pct']:.1f} % (nested held out)")
    print("\n" + line)
    VERDICTS.append(line)
    return name, truth, expect, folder, out, result


def test_campaign_hides_the_truth(diagnosed):
    name, truth, expect, folder, out, result = diagnosed
    campaign = read_campaign(folder)  # a valid campaign of the spec
    assert all(s.friction == 0.5 and s.restrained_springings == "none" for s in campaign.specimens.values())
    words = ("inset", "chamfer", "restrain", "bracket", "gain", "truth", "hidden", "effect", "actuator", "gap")
    for path in folder.rglob("*"):
        if path.is_file():
            text = path.read_text().lower()
            assert not any(w in text for w in words), f"{path} gives the truth away"


def test_verdict_names_what_is_hidden(diagnosed):
    name, truth, expect, folder, out, result = diagnosed
    verdict = result["verdict"]
    if verdict in expect["names"]:
        if verdict == "combined" and "effects" in expect:
            assert set(result["effects"]) == expect["effects"], result["notes"]
        assert expect.get("effects_must", set()) <= set(result["effects"]), result["notes"]
        return
    allowed = expect.get("rivals", "no inconclusive")
    if "restrained_alone" in expect:
        assert f"specimen {expect['restrained_alone']} behaves as if its springings were restrained" \
            in result["notes"], result["notes"]
        assert result["notes"].count("behaves as if its springings were restrained") == 1, result["notes"]
    assert verdict == "inconclusive" and allowed != "no inconclusive", (name, verdict, result["notes"])
    if allowed is None:  # outside the catalogue: any honest inconclusive is right
        return
    rivals = set(result["rivals"])
    assert rivals <= allowed, (name, rivals, result["notes"])
    must = expect.get("rivals_must", expect["names"] & rivals or expect["names"])
    assert must <= rivals or (expect["names"] == {"combined"} and expect["effects"] <= rivals), (name, rivals)
    if "shared" in expect:  # each rival (a pair may be one) includes it, and the notes say so
        assert f"Every rival includes {expect['shared']}" in result["notes"], result["notes"]


def test_no_specimen_is_said_restrained_without_brackets(diagnosed):
    name, truth, expect, folder, out, result = diagnosed
    if truth.bracket_gap_m is None:
        assert "behaves as if its springings were restrained" not in result["notes"], result["notes"]


def test_parameter_is_recovered(diagnosed):
    name, truth, expect, folder, out, result = diagnosed
    if "param" in expect:
        effect, key, low, high = expect["param"]
        params = result["parameters"]
        if result["verdict"] != effect:
            params = next(c["parameters"] for c in result["candidates"] if c["effect"] == effect)
        assert low <= params[key]["value"] <= high, (name, params[key])
    if "sides" in expect:
        params = result["parameters"]
        if result["verdict"] == "inconclusive":  # the best rival that restrains
            params = next(c["parameters"] for c in sorted(result["candidates"], key=lambda c: c["cv_error_pct"])
                          if "restrained_springings" in c["parameters"])
        assert sorted(params["restrained_springings"]["value"]) == expect["sides"]
    if result["verdict"] in ("none", "inconclusive"):
        assert result["parameters"] == {}
    for p in result["parameters"].values():
        if isinstance(p["value"], float):
            assert p["low"] <= p["value"] <= p["high"]


def test_extended_model_beats_baseline(diagnosed):
    name, truth, expect, folder, out, result = diagnosed
    base = result["baseline"]["threshold_error_pct"]
    ext = result["extended"]["threshold_error_pct"]
    if result["verdict"] == "none":
        assert ext == base and base < 5.0
    elif expect.get("rivals", "") is not None:  # a cause in the catalogue: the gain holds out of sample
        assert ext < 0.6 * base, (base, ext)


def test_outputs_follow_the_spec(diagnosed):
    name, truth, expect, folder, out, result = diagnosed
    on_disk = json.loads((out / "diagnosis.json").read_text())
    assert on_disk == json.loads(json.dumps(result))
    assert set(on_disk) == {"campaign", "verdict", "effects", "rivals", "parameters", "baseline", "extended",
                            "candidates", "notes"}
    assert on_disk["campaign"] == "campaign"
    singles = [c["effect"] for c in on_disk["candidates"] if c["effect"] != "combined"]
    assert singles == ["contact_edges", "table_motion", "base_restraint", "friction", "geometry"]
    for c in on_disk["candidates"]:
        if c["effect"] == "combined":
            assert len(c["effects"]) == 2 and set(c["effects"]) <= set(singles)
    for key in ("baseline", "extended"):
        assert set(on_disk[key]) == {"threshold_error_pct", "hinge_match"}
    if on_disk["verdict"] in ("none", "inconclusive"):
        assert on_disk["effects"] == []
    elif on_disk["verdict"] == "combined":
        assert len(on_disk["effects"]) == 2 and on_disk["rivals"] == []
    else:
        assert on_disk["effects"] == [on_disk["verdict"]] and on_disk["rivals"] == []
    if on_disk["verdict"] != "inconclusive":
        assert on_disk["rivals"] == []
    report = (out / "report.md").read_text()
    assert f"`{on_disk['verdict']}`" in report
    assert "## Crown motion" in report and "## Hinges" in report
    for png in ("thresholds.png", "candidates.png"):
        assert png in report and (out / png).stat().st_size > 1000


# ------------------------------------------------------------------ the test data's own checks


def test_actuator_record_has_the_gain_of_its_transfer_function():
    """The actuator's steady response to a sine has the closed-form amplitude |H(f)|."""
    truth = Truth(actuator_hz=6.0, actuator_damping=0.2)
    f = 2.0
    t, x, acc = actuator_record(f, 0.01, 1.0, truth, tail_s=0.0)
    full = (t > 1.0 / f + 0.3) & (t < 2.0 / f)  # the full-amplitude cycle, after the transient
    assert abs(np.abs(x[full]).max() / 0.01 - _amplitude_ratio(f, truth)) < 0.02
    # The acceleration is the second derivative of the displacement.
    dt = t[1] - t[0]
    fd = (x[2:] - 2 * x[1:-1] + x[:-2]) / dt ** 2
    assert np.abs(fd - acc[1:-1]).max() < 1e-3 * np.abs(acc).max() + 1e-6


def test_polygon_ring_is_the_nominal_arch(voussoir_run_exe, tmp_path):
    """The independent ring, uncut, has the arch's voussoir areas and, shaken, falls
    where the kernel's own arch falls: the test data's geometry is the spec's."""
    from voussoir_post.runner import Runner
    arch = ARCHES[0]
    blocks, joints = ring_blocks(arch, Truth())
    area = [0.5 * abs(sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(poly, poly[1:] + poly[:1])))
            for role, poly in blocks if role == "free"]
    r_in = arch.r_ext_m - arch.thickness_m
    sector = math.radians(arch.embrace_deg / arch.n_voussoirs)
    chord_area = 0.5 * math.sin(sector) * (arch.r_ext_m ** 2 - r_in ** 2)  # two triangles from the centre
    assert len(area) == arch.n_voussoirs and max(abs(a - chord_area) for a in area) < 1e-9
    write_polygon_file(tmp_path / "ring.txt", blocks)
    runner = Runner(bin_dir(), tmp_path)
    motion = {"waveform": "afd", "frequency_hz": 2.0, "rest_s": 1.0}
    solver = {"dt_s": 5e-4}
    out = {"stop_after_collapse_s": 0.1, "collapse_drop_m": 0.5 * arch.thickness_m}
    for amp, falls in ((0.0235, False), (0.0285, True)):  # about 10 % either side of the kernel's threshold
        poly = runner.run_single({"arch": {"polygon_file": str(tmp_path / "ring.txt"), "width_m": arch.width_m,
                                           "density_kg_m3": arch.density_kg_m3},
                                  "motion": {**motion, "amplitude_m": amp}, "solver": solver, "output": out},
                                 "poly", keep=False)
        built = runner.run_single({"arch": {"embrace_deg": arch.embrace_deg, "n_voussoirs": arch.n_voussoirs,
                                            "r_ext_m": arch.r_ext_m, "thickness_m": arch.thickness_m,
                                            "width_m": arch.width_m, "density_kg_m3": arch.density_kg_m3},
                                   "motion": {**motion, "amplitude_m": amp}, "solver": solver, "output": out},
                                  "built", keep=False)
        assert poly.collapsed == built.collapsed == falls, amp


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


def _pair(threshold_m, resolution=0.02, nominal_m=None, specimen="S"):
    from voussoir_post.readers.campaign import MeasuredThreshold, Specimen
    from voussoir_post.diagnosis.pipeline import Variant
    m = MeasuredThreshold(specimen, 1.0, threshold_m, threshold_m * (1 - resolution),
                          threshold_m * (1 + resolution), 1, 1, False, [])
    p = PairData(m, Specimen(specimen, 156, 13, 0.508, 0.071, 0.145, 700), resolution,
                 math.hypot(resolution, 0.03))
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


def test_a_pair_is_named_only_when_it_beats_each_member_by_strong_evidence():
    meas = [0.050, 0.030, 0.040, 0.060, 0.045, 0.035]
    pairs = [_pair(m, nominal_m=1.3 * m) for m in meas]
    # Each effect alone takes half the way; together they reach the data.
    halves = {"contact_edges": _cand("contact_edges", [1.15 * m for m in meas], 0.15),
              "friction": _cand("friction", [1.14 * m for m in meas], 0.14)}
    both = _cand("contact_edges+friction", [1.005 * m for m in meas], 0.005)
    d = decide(pairs, 0.03, {**halves, "contact_edges+friction": both}, TableEvidence("none"))
    assert d.verdict == "combined" and d.chosen.members == ("contact_edges", "friction")
    # A pair barely better than one of its members is not named: the simpler story wins.
    close = {"contact_edges": _cand("contact_edges", [1.01 * m for m in meas], 0.01),
             "friction": halves["friction"]}
    d = decide(pairs, 0.03, {**close, "contact_edges+friction": both}, TableEvidence("none"))
    assert d.verdict == "contact_edges"


def test_a_cause_named_by_its_hinges_is_not_said_to_win_on_the_thresholds():
    from voussoir_post.diagnosis.pipeline import notes_named
    from voussoir_post.diagnosis.effects import effect
    meas = [0.050, 0.030, 0.040, 0.060]
    pairs = [_pair(m, nominal_m=1.25 * m) for m in meas]
    cands = {"contact_edges": _cand("contact_edges", [1.01 * m for m in meas], 0.01),
             "friction": _cand("friction", [0.995 * m for m in meas], 0.005)}
    cands["friction"].value, cands["friction"].eff = 0.43, effect("friction")
    cands["contact_edges"].hinge_score, cands["friction"].hinge_score = 0.60, 0.80  # a margin of 0.2
    # The thresholds alone do not separate them (the test above); the hinges do.
    d = decide(pairs, 0.03, cands, TableEvidence("none"))
    assert d.verdict == "friction" and d.rivals == []
    assert "the observed hinges do" in d.separation and "contact_edges 0.60" in d.separation
    notes = notes_named(d.chosen, 0.25, 0.03, cands, TableEvidence("none"), pairs, d.separation)
    assert "less well by strong evidence" not in notes and "the observed hinges do" in notes
    # Named on the thresholds, the notes say so.
    cands["contact_edges"].per_pair = [1.15 * m for m in meas]
    d = decide(pairs, 0.03, cands, TableEvidence("none"))
    assert d.verdict == "friction" and d.separation == ""
    assert "less well by strong evidence" in notes_named(d.chosen, 0.25, 0.03, cands, TableEvidence("none"), pairs)


def test_hinge_score_counts_false_hinges_where_the_match_does_not():
    observed = {"t1": {(0, "extrados"), (4, "intrados")}}
    exact = {"t1": {(0, "extrados"), (4, "intrados")}}
    everything = {"t1": {(j, s) for j in range(14) for s in ("intrados", "extrados")}}
    assert hinge_match(observed, exact) == hinge_match(observed, everything) == 1.0
    assert hinge_score(observed, exact) == 1.0
    assert hinge_score(observed, everything) == pytest.approx(2 * 2 / (2 + 28))


def test_a_specimen_restrained_alone_is_found_on_its_own_frequencies():
    from voussoir_post.diagnosis.pipeline import Variant
    from voussoir_post.diagnosis.setup_screen import specimen_restraints

    def specimen(sid, meas, factors):
        ps = []
        for m in meas:
            p = _pair(m, nominal_m=factors[None] * m, specimen=sid)
            for r in ("left", "right", "both"):
                p.simulated[Variant("base_restraint", r)] = factors[r] * m
            ps.append(p)
        return ps

    # A: the nominal model 25 % low at each frequency, brackets on both sides exact; B:
    # the nominal model right, brackets 20 % too strong; C like A but tested once.
    like_a = {None: 0.75, "left": 0.9, "right": 0.9, "both": 1.0}
    pairs = (specimen("A", [0.050, 0.040, 0.030], like_a)
             + specimen("B", [0.045, 0.035], {None: 1.0, "left": 1.1, "right": 1.1, "both": 1.2})
             + specimen("C", [0.040], like_a))
    settings = DiagnosisSettings(bin_dir=".", log=lambda m: None)
    found = specimen_restraints(pairs, None, settings, TableEvidence("none"))
    assert [f["specimen"] for f in found] == ["A"]
    assert found[0]["restraint"] == "both" and found[0]["held_out_error"] < 1e-9
    assert found[0]["other_errors"]["the nominal model"] == pytest.approx(0.25)
    # Against a campaign model whose fit (on every specimen) already gives A's
    # thresholds, nothing is flagged.
    class Exact:
        def predict(self, pair, value):
            return pair.measured.threshold_m
    model = _cand("friction", [], 0.0)
    model.eff = Exact()
    assert specimen_restraints(pairs, model, settings, TableEvidence("none")) == []
    # Nor when another effect fitted to A alone tells the same story: here friction, whose
    # simulated grid (one value below nominal) reaches A's thresholds.
    for p in pairs[:3]:
        p.simulated[Variant("friction", 0.4)] = p.measured.threshold_m
    assert specimen_restraints(pairs, None, settings, TableEvidence("none")) == []
