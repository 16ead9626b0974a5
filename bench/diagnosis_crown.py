"""How far the crown records and the hinges separate the two rivals that the thresholds
confuse most: a thinner ring (geometry, thickness x 0.85) and pivots set in from the
edges (contact_edges, the inset that gives the same threshold) (issue 23, item 4).

    python bench/diagnosis_crown.py BIN_DIR OUT_DIR

On each of the three test arches of the replay tests, at each of their two frequencies:
the inset whose threshold equals the thinner ring's is read off the stored simulation
bank (postproc/tests/data/replay/bank, interpolated between its grid nodes); both
models are then run as a laboratory runs a test that stands (afd 1-1-1 cycles at 0.6,
0.8 and 0.9 of that common threshold) and one that falls (1.1 times it), each at three
time steps (dt x 0.97, 1, 1.03: the simulator's own spread near a chaotic response).

Printed per arch, frequency and amplitude:
- the peak horizontal crown displacement of each model [mm] (mean of its replicas);
- `between`: the RMS over time of the difference of the two models' crown records
  (replica means) [mm]; `within`: the RMS of a model's replicas about their mean [mm];
- `z`: between / sqrt(within^2 + noise^2), with the test generator's sensor noise of
  0.2 mm: a crown record separates the rivals where z is well above 1;
- for the falling test, the hinges (joint and side, up to the collapse at a 1 mm
  opening) that each model opens in all of its replicas, and the share of the two sets
  that differs.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "postproc"), str(ROOT / "postproc" / "tests")]

from voussoir_post.diagnosis.effects import Variant  # noqa: E402
from voussoir_post.diagnosis.settings import DiagnosisSettings  # noqa: E402
from voussoir_post.diagnosis.simulator import Simulator  # noqa: E402
from voussoir_post.readers.campaign import Test  # noqa: E402

from independent_campaigns import ARCHES  # noqa: E402

BANK = ROOT / "postproc" / "tests" / "data" / "replay" / "bank"
THICKNESS_FACTOR = 0.85
NOISE_M = 2.0e-4  #: the test generator's crown sensor noise (independent_campaigns.py)
STAND_FRACTIONS = (0.6, 0.8, 0.9)
FALL_FRACTION = 1.1
DT_FACTORS = (0.97, 1.0, 1.03)


def _interp_node(nodes: dict[float, float], value: float) -> float:
    xs = sorted(nodes)
    return float(np.interp(value, xs, [nodes[x] for x in xs]))


def matched_models(bank: dict, k: int) -> tuple[float, float]:
    """The thinner ring's threshold at frequency k and the inset that gives it (linear
    between the bank's grid nodes, on the monotone stretch below the nominal model)."""
    th = bank["thresholds"]
    geometry = {float(key.split("=")[1]): v[k] for key, v in th.items() if key.startswith("geometry=") and "+" not in key}
    geometry[1.0] = th["nominal"][k]
    target = _interp_node(geometry, THICKNESS_FACTOR)
    edges = {float(key.split("=")[1]): v[k] for key, v in th.items() if key.startswith("contact_edges=") and "+" not in key}
    edges[0.0] = th["nominal"][k]
    xs = sorted(edges)
    for a, b in zip(xs, xs[1:]):
        lo, hi = sorted((edges[a], edges[b]))
        if lo <= target <= hi and edges[a] != edges[b]:
            return target, a + (b - a) * (target - edges[a]) / (edges[b] - edges[a])
    raise SystemExit(f"{bank['specimen_id']}: no inset of the bank reaches the threshold {target:.4f} m")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("bin_dir", type=Path)
    ap.add_argument("out_dir", type=Path)
    args = ap.parse_args()
    args.out_dir.mkdir(parents=True, exist_ok=True)
    sims = {f: Simulator(DiagnosisSettings(bin_dir=args.bin_dir, dt_s=1.0e-3 * f, log=lambda *_: None),
                         args.out_dir / f"dt_{f}") for f in DT_FACTORS}
    summary = []
    print(f"{'arch':5} {'f Hz':>5} {'inset mm':>8} {'A/thr':>5} {'peak ring':>9} {'peak edges':>10} "
          f"{'between':>8} {'within':>7} {'z':>5}   (crown dx, mm)")
    for arch in ARCHES:
        bank = json.loads((BANK / f"{arch.specimen_id}.json").read_text())
        spec = arch.specimen()
        for k, freq in enumerate(bank["frequencies_hz"]):
            threshold, inset = matched_models(bank, k)
            models = {"ring": Variant("geometry", THICKNESS_FACTOR), "edges": Variant("contact_edges", round(inset, 6))}
            fractions = STAND_FRACTIONS + (FALL_FRACTION,)
            tests = [Test(f"t{i}", spec.specimen_id, "afd", "stand", frequency_hz=freq, amplitude_m=a * threshold,
                          n_attack=1, n_full=1, n_decay=1) for i, a in enumerate(fractions)]
            runs = {}
            for f, sim in sims.items():
                jobs = [(spec, t, v, {}) for v in models.values() for t in tests]
                out = sim.run_tests(jobs)
                for m, name in enumerate(models):
                    for i in range(len(tests)):
                        runs[(name, i, f)] = out[m * len(tests) + i]
            for i, a in enumerate(fractions):
                if a < 1.0:
                    t = np.arange(0.0, max(runs[(n, i, f)]["t_s"][-1] for n in models for f in DT_FACTORS), 0.005)
                    series = {n: np.array([np.interp(t, runs[(n, i, f)]["t_s"], runs[(n, i, f)]["crown_dx_m"])
                                           for f in DT_FACTORS]) for n in models}
                    fell = [n for n in models for f in DT_FACTORS if runs[(n, i, f)]["collapsed"]]
                    mean = {n: s.mean(axis=0) for n, s in series.items()}
                    between = float(np.sqrt(np.mean((mean["ring"] - mean["edges"]) ** 2)))
                    within = float(np.sqrt(np.mean([np.mean((s - s.mean(axis=0)) ** 2) for s in series.values()])))
                    z = between / np.hypot(within, NOISE_M)
                    peak = {n: 1e3 * float(np.mean(np.abs(s).max(axis=1))) for n, s in series.items()}
                    note = f"  (fell: {sorted(set(fell))})" if fell else ""
                    print(f"{arch.specimen_id:5} {freq:5.2f} {1e3 * inset:8.2f} {a:5.2f} {peak['ring']:9.2f} "
                          f"{peak['edges']:10.2f} {1e3 * between:8.2f} {1e3 * within:7.2f} {z:5.1f}{note}")
                    summary.append({"arch": arch.specimen_id, "frequency_hz": freq, "inset_m": inset,
                                    "fraction": a, "peak_ring_mm": peak["ring"], "peak_edges_mm": peak["edges"],
                                    "between_mm": 1e3 * between, "within_mm": 1e3 * within, "z": z, "fell": fell})
                else:
                    sets = {}
                    for n in models:
                        fallen = [runs[(n, i, f)] for f in DT_FACTORS if runs[(n, i, f)]["collapsed"]]
                        sets[n] = set.intersection(*(r["hinges"] for r in fallen)) if fallen else None
                    if sets["ring"] is None or sets["edges"] is None:
                        print(f"{arch.specimen_id:5} {freq:5.2f} {1e3 * inset:8.2f} {a:5.2f}   hinges: a model stood "
                              f"at {a} x threshold in some replica: {[(n, s is None) for n, s in sets.items()]}")
                        continue
                    union = sets["ring"] | sets["edges"]
                    differ = len(sets["ring"] ^ sets["edges"]) / max(1, len(union))
                    fmt = lambda s: " ".join(f"{j}{side[0]}" for j, side in sorted(s))  # noqa: E731
                    print(f"{arch.specimen_id:5} {freq:5.2f} {1e3 * inset:8.2f} {a:5.2f}   hinges ring [{fmt(sets['ring'])}]"
                          f"  edges [{fmt(sets['edges'])}]  differing {differ:.0%}")
                    summary.append({"arch": arch.specimen_id, "frequency_hz": freq, "inset_m": inset, "fraction": a,
                                    "hinges_ring": sorted(sets["ring"]), "hinges_edges": sorted(sets["edges"]),
                                    "hinges_differing": differ})
    (args.out_dir / "crown_separation.json").write_text(json.dumps(summary, indent=1))
    print(f"[bench] {sum(s.n_runs for s in sims.values())} runs; table in {args.out_dir / 'crown_separation.json'}")


if __name__ == "__main__":
    main()
